"""The layer rules hold: text → model → analysis → report, the command line on top.

The contracts are in pyproject.toml ([tool.importlinter]); import-linter reads every import in
src/mech, including those inside functions, so a rule cannot be broken by a lazy import either.
"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip(
    "importlinter", reason="import-linter comes with the test extra: pip install -e '.[test]'"
)

ROOT = Path(__file__).resolve().parent.parent


def test_import_contracts_are_kept():
    result = subprocess.run(
        [sys.executable, "-c", "from importlinter.cli import lint_imports_command; lint_imports_command()"],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert result.returncode == 0, result.stdout[-4000:] + result.stderr[-1000:]
    assert "BROKEN" not in result.stdout and "5 kept, 0 broken" in result.stdout


def test_topology_loads_no_numpy_at_run_time():
    # The contract checks mech.topology's own imports; this checks everything it pulls in.
    code = "import sys, mech.topology; print('numpy' in sys.modules)"
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert result.stdout.strip() == "False"


def test_model_and_analysis_load_no_rich_or_click():
    code = (
        "import sys, mech.loader, mech.kinematics, mech.icentres, mech.topology; "
        "print(sorted(m for m in ('rich', 'click') if m in sys.modules))"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert result.stdout.strip() == "[]"


def _sources() -> list[tuple[str, ast.Module]]:
    src = ROOT / "src" / "mech"
    return [
        (path.relative_to(src).as_posix(), ast.parse(path.read_text(encoding="utf-8")))
        for path in sorted(src.rglob("*.py"))
    ]


def test_no_cache_is_keyed_on_object_ids():
    # id() of an object is reused once it is gone; derived data is kept on the object (mech._memo.Memo)
    calls = [
        f"{name}:{node.lineno}"
        for name, tree in _sources()
        for node in ast.walk(tree)
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "id"
    ]
    assert calls == [], calls


def test_no_module_imports_another_modules_private_names():
    # a name another room needs is public where it belongs (dyads.closing_edge, not dyads._edge)
    private = [
        f"{name}:{node.lineno} imports {alias.name} from {node.module}"
        for name, tree in _sources()
        for node in ast.walk(tree)
        if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("mech")
        for alias in node.names
        if alias.name.startswith("_") and not alias.name.startswith("__")
    ]
    assert private == [], private
