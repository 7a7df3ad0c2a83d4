"""The suite's own bookkeeping: the slow list in conftest names tests that exist."""

from __future__ import annotations

import ast
import functools
from pathlib import Path

from conftest import SLOW

ROOT = Path(__file__).resolve().parent.parent


@functools.cache
def _functions(file: Path) -> frozenset[str]:
    """The names of the functions defined in a test file (each file parsed once)."""
    return frozenset(
        n.name
        for n in ast.walk(ast.parse(file.read_text(encoding="utf-8")))
        if isinstance(n, ast.FunctionDef)
    )


def test_every_slow_entry_names_a_test_that_exists():
    # a renamed test would silently leave the slow list and come back into the default run
    stale = []
    for entry in SLOW:
        path, _, name = entry.partition("::")
        file = ROOT / path
        if not file.exists():
            stale.append(entry)
            continue
        if name and name not in _functions(file):
            stale.append(entry)
    assert stale == []
