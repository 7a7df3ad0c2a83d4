"""The layer rules hold: text → model → analysis → report, the command line on top.

The contracts are in pyproject.toml ([tool.importlinter]); import-linter reads every import in
src/mech, including those inside functions, so a rule cannot be broken by a lazy import either.
No two modules may import each other, however indirectly (issue 20 item 5): the import graph is
read with grimp, counting imports inside functions and under ``TYPE_CHECKING``, and its strongly
connected components are the import circles.
"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

from source_trees import SRC, source_trees

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
    assert "BROKEN" not in result.stdout and "4 kept, 0 broken" in result.stdout


def _import_circles() -> list[list[str]]:
    """Every import circle among mech's modules: the strongly connected components of more than one.

    grimp counts every ``import`` statement, inside functions and under ``TYPE_CHECKING`` too: a
    lazy import hides nothing from it.
    """
    grimp = pytest.importorskip("grimp", reason="grimp comes with import-linter (the test extra)")
    graph = grimp.build_graph("mech", cache_dir=None)
    edges = {m: sorted(graph.find_modules_directly_imported_by(m)) for m in sorted(graph.modules)}
    # Tarjan's algorithm, iteratively (a recursion per module could pass Python's limit)
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    circles: list[list[str]] = []
    for root in edges:
        if root in index:
            continue
        work = [(root, 0)]
        while work:
            node, i = work.pop()
            if i == 0:
                index[node] = low[node] = len(index)
                stack.append(node)
                on_stack.add(node)
            children = edges.get(node, [])
            if i < len(children):
                work.append((node, i + 1))
                child = children[i]
                if child not in index:
                    work.append((child, 0))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                if len(component) > 1:
                    circles.append(sorted(component))
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
    return sorted(circles)


#: The checking rooms (issue 20 item 5, "the checking knot", untied): answer-key forms, grading,
#: one file's verdicts, diagnoses, the batch and its pool, and the answer sheets' reader.
CHECKING = (
    "mech.answers",
    "mech.grading",
    "mech.check",
    "mech.diagnose",
    "mech.batch",
    "mech.batchpool",
    "mech.analysis",
    "mech.loader.answers",
    "mech.loader.sheets",
)


def _in_checking(module: str) -> bool:
    return any(module == room or module.startswith(room + ".") for room in CHECKING)


def test_no_two_modules_import_each_other():
    circles = _import_circles()
    assert circles == [], "import circles:\n" + "\n".join(" ↔ ".join(c) for c in circles)


def test_no_import_circle_runs_through_the_checking_rooms():
    # the checking knot was 16 modules (analysis, answers, batch, check, diagnose, icentres, loader,
    # properties, cam.answers …): forms below the loader, grading above the analysis, one way down
    knotted = [c for c in _import_circles() if any(_in_checking(m) for m in c)]
    assert knotted == [], "import circles through the checking rooms:\n" + "\n".join(
        " ↔ ".join(c) for c in knotted
    )


def test_the_answer_forms_import_nothing_above_the_pair_kinds():
    # mech.answers sits between mech.pairs and the loader (ROOMS.md): the loader reads its forms,
    # so it may import only the rooms below it, even lazily
    grimp = pytest.importorskip("grimp", reason="grimp comes with import-linter (the test extra)")
    graph = grimp.build_graph("mech", cache_dir=None)
    below = ("mech.pairs", "mech.fields", "mech.model", "mech.options", "mech.errors", "mech.units")
    below += ("mech._records", "mech._memo", "mech._text")
    above = sorted(
        m
        for m in graph.find_modules_directly_imported_by("mech.answers")
        if not any(m == b or m.startswith(b + ".") for b in below)
    )
    assert above == []


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
    return [(path.relative_to(SRC).as_posix(), tree) for path, _, tree in source_trees()]


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
