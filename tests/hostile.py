"""Hostile mechanism files through mech's commands in process (for the never-a-traceback tests).

tests/test_cli.py grows them from the four-bar and tests/forces/test_cli_forces.py from the
engine: hostile edits of a shipped example (a value replaced, deleted or added somewhere in the
tree), each file run through a command by click's CliRunner, where an exception that escapes is
the bug that would have exited 70.
"""

from __future__ import annotations

import traceback
import warnings
from pathlib import Path

__all__ = ["HOSTILE_NUMBERS", "HOSTILE_WORDS", "answers_or_refuses", "edit"]

HOSTILE_WORDS = [
    "frame",
    "crank",
    "coupler",
    "rocker",
    "A",
    "B",
    "C",
    "D",
    "40 mm",
    "60 deg",
    "1e400",
    "-0",
    "nan",
    "cw",
    "rpm",
    "\u202ecrank",
    "a\x01b",
    "revolute",
    "prismatic",
    "gear",
    "rolling",
    "slot",
]
HOSTILE_NUMBERS = [0, -0.0, 1, -1, 1e308, -1e308, 5e-324, 1e-300, float("nan"), float("inf"), 360, 10**30]


def edit(draw, doc, keys, values, times: int) -> None:
    """``times`` hostile edits of ``doc`` (a YAML tree), in place: at a node found by a random walk
    down from the top, an entry replaced by a drawn value, deleted, or a drawn one added."""
    from hypothesis import strategies as st

    for _ in range(times):
        node = doc
        while isinstance(node, (dict, list)) and node and draw(st.booleans()):
            key = draw(st.sampled_from(list(node) if isinstance(node, dict) else range(len(node))))
            if not isinstance(node[key], (dict, list)) or not node[key]:
                break
            node = node[key]
        if not isinstance(node, (dict, list)) or not node:
            continue
        key = draw(st.sampled_from(list(node) if isinstance(node, dict) else range(len(node))))
        action = draw(st.sampled_from(["replace", "delete", "add"]))
        if action == "delete":
            del node[key]
        elif action == "replace":
            node[key] = draw(values)
        elif isinstance(node, dict):
            node[draw(keys)] = draw(values)
        else:
            node.append(draw(values))


def answers_or_refuses(runner, folder: Path, text: str, command: list[str]) -> None:
    """``mech COMMAND FILE ARGS…`` on ``text`` (written to ``folder``/m.yaml, ``{tmp}`` in an
    argument standing for ``folder``): exit 0, 1 (a check only) or 2, no exception, no traceback
    and no RuntimeWarning."""
    from mech.cli import cli

    path = folder / "m.yaml"
    path.write_text(text, encoding="utf-8", errors="surrogatepass")
    args = [a.replace("{tmp}", str(folder)) for a in command]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = runner.invoke(cli, [args[0], str(path), *args[1:]], catch_exceptions=True)
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise AssertionError(
            f"mech {' '.join(args)} raised on:\n{text}\n"
            + "".join(traceback.format_exception(*result.exc_info))
        )
    allowed = (0, 1, 2) if args[0] == "check" else (0, 2)
    assert result.exit_code in allowed, (args, result.exit_code, text, result.output[-800:])
    assert "Traceback" not in result.output
    runtime = [str(w.message) for w in caught if issubclass(w.category, RuntimeWarning)]
    assert not runtime, (args, runtime, text)
