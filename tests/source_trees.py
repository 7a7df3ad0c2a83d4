"""mech's own source, read and parsed once per test run, for the tests that read its syntax trees.

Parsing every module under src/mech is about a second of CPU; the layer rules, the pair kinds'
rule and the long-function rule each read the whole tree, so they share one parse.
"""

from __future__ import annotations

import ast
import functools
from pathlib import Path

SRC = Path(__file__).resolve().parent.parent / "src" / "mech"


@functools.cache
def source_trees() -> tuple[tuple[Path, str, ast.Module], ...]:
    """Every module under src/mech, in path order: its path, its text and its syntax tree."""
    out = []
    for path in sorted(SRC.rglob("*.py")):
        text = path.read_text(encoding="utf-8")
        out.append((path, text, ast.parse(text)))
    return tuple(out)
