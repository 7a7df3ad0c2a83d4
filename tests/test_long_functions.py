"""No function in src/mech runs past 80 lines without a reason written beside it (issue 14 part 3).

A function's length is its code: ``end_lineno − lineno + 1`` less its docstring (a docstring
that teaches is welcome at any length).  A function that must stay long says why in a comment
``# long: <reason>`` on the line above its ``def`` (above its decorators, if any) or on one of
its first three lines.

``IN_FLIGHT`` lists the long functions another engineer is cutting up this round, in files they
own; each entry names who and why.  An entry is refused once its function is short (or gone),
so the list cannot outlive the work it waits for.
"""

from __future__ import annotations

import ast

import pytest

from source_trees import SRC, source_trees

LIMIT = 80

#: "path relative to src/mech:function" → who is splitting it and where it stands.
IN_FLIGHT: dict[str, str] = {}


def _code_lines(fn: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    assert fn.end_lineno is not None
    n = fn.end_lineno - fn.lineno + 1
    first = fn.body[0] if fn.body else None
    if (
        isinstance(first, ast.Expr)
        and isinstance(first.value, ast.Constant)
        and isinstance(first.value.value, str)
    ):
        assert first.end_lineno is not None
        n -= first.end_lineno - first.lineno + 1
    return n


def _has_reason(fn: ast.FunctionDef | ast.AsyncFunctionDef, lines: list[str]) -> bool:
    top = min([fn.lineno, *(d.lineno for d in fn.decorator_list)])
    around = [lines[top - 2]] if top >= 2 else []
    around += lines[fn.lineno - 1 : fn.lineno + 2]
    return any("# long:" in line and line.split("# long:", 1)[1].strip() for line in around)


def long_functions() -> dict[str, tuple[int, bool]]:
    """``"path:function"`` → (code lines, has a ``# long:`` reason) for every function over the limit."""
    out: dict[str, tuple[int, bool]] = {}
    for path, text, tree in source_trees():
        lines = text.splitlines()
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                n = _code_lines(node)
                if n > LIMIT:
                    key = f"{path.relative_to(SRC).as_posix()}:{node.name}"
                    out[key] = (n, _has_reason(node, lines))
    return out


def test_every_function_over_80_lines_says_why_it_is_long() -> None:
    unexplained = {
        key: n for key, (n, reason) in long_functions().items() if not reason and key not in IN_FLIGHT
    }
    assert not unexplained, (
        "cut these into named steps, or write `# long: <reason>` above the def: "
        + ", ".join(f"{k} ({n} lines)" for k, n in sorted(unexplained.items()))
    )


@pytest.mark.parametrize("key", sorted(IN_FLIGHT))
def test_an_in_flight_entry_is_dropped_once_its_function_is_short(key: str) -> None:
    assert key in long_functions(), f"{key} is no longer over {LIMIT} lines: remove it from IN_FLIGHT"


def test_the_length_counts_code_not_the_docstring() -> None:
    # a 3-line docstring and 2 lines of code under the def: 1 (def) + 2 = 3 code lines
    fn = ast.parse('def f():\n    """One.\n\n    Two."""\n    x = 1\n    return x\n').body[0]
    assert isinstance(fn, ast.FunctionDef)
    assert _code_lines(fn) == 3


def test_a_reason_above_the_def_or_in_its_first_lines_is_found() -> None:
    above = "# long: one table, row by row\ndef f():\n    pass\n"
    inside = "def f():\n    # long: one table, row by row\n    pass\n"
    empty = "# long:\ndef f():\n    pass\n"
    found = []
    for text in (above, inside, empty):
        fn = ast.parse(text).body[0]
        assert isinstance(fn, ast.FunctionDef)
        found.append(_has_reason(fn, text.splitlines()))
    assert found == [True, True, False]
