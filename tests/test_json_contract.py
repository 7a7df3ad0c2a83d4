"""The JSON contract: every command's ``--json`` is strict JSON (no NaN/Infinity) with stable keys.

A command either answers (exit 0, strict JSON on stdout) or refuses its input (exit 2, a
message, nothing on stdout); which one is worked out from the file itself by
:func:`expected_refusal`, never by asking mech first.
"""

from __future__ import annotations

import pytest

from cli_runner import mech, no_traceback, strict_json
from mechanism_texts import EXAMPLES, expected_refusal
from oracles.field_cases import IC_CASES


def _assert_answers_or_refuses(p, text: str, command: str, where: object) -> dict | None:
    no_traceback(p)
    refusal = expected_refusal(text, command)
    if refusal is None:
        assert p.returncode == 0, (where, command, p.stderr[-500:])
        return strict_json(p.stdout)
    assert p.returncode == 2 and refusal in p.stderr, (where, command, p.returncode, p.stderr[-500:])
    assert p.stdout == ""
    return None


@pytest.mark.parametrize(
    "cmd",
    [
        ["dof"],
        ["dof", "--mobility"],
        ["classify"],
        ["position"],
        ["velocity"],
        ["acceleration"],
        ["icentres"],
    ],
)
def test_every_example_answers_in_strict_json_or_refuses_as_its_file_says(cmd):
    for f in sorted(EXAMPLES.glob("*.yaml")):
        p = mech(*cmd, "--json", str(f))
        _assert_answers_or_refuses(p, f.read_text(encoding="utf-8"), cmd[0], f.name)


def test_check_json_of_every_example_is_strict_and_all_pass():
    """Every example passes its own answers (exit 0) with a process pool, in strict JSON."""
    p = mech("check", str(EXAMPLES), "--json", "-j", "2", subprocess_=True)
    assert p.returncode == 0, p.stdout[-800:]
    strict_json(p.stdout)


POSITION_KEYS = {
    "mechanism",
    "level",
    "units",
    "size",
    "drives",
    "links",
    "points",
    "relative",
    "sliders",
    "rubbing",
    "mobility",
    "notes",
}
ICENTRES_KEYS = {
    "file",
    "name",
    "units",
    "links",
    "count",
    "formula",
    "kennedy_rounds",
    "icentres",
    "max_check",
    "omega",
    "notes",
}


@pytest.mark.parametrize(
    "case", ["parallelogram_translating_coupler", "gears_internal", "cam_offset_follower"]
)
def test_every_command_keeps_its_top_level_keys_with_centres_at_infinity_and_links_at_rest(tmp_path, case):
    """The same keys for different mechanisms; a cam given by point and normal refuses accelerations."""
    text = IC_CASES[case][0]
    m = tmp_path / "m.yaml"
    m.write_text(text, encoding="utf-8")
    keys = {"position": POSITION_KEYS, "icentres": ICENTRES_KEYS}
    for cmd in ("dof", "classify", "position", "velocity", "acceleration", "icentres"):
        d = _assert_answers_or_refuses(mech(cmd, "--json", str(m)), text, cmd, case)
        if d is not None and cmd in keys:
            assert keys[cmd] <= set(d), (cmd, set(d))
    assert (expected_refusal(text, "acceleration") is not None) == (case == "cam_offset_follower")
    out = tmp_path / "m.svg"
    p = mech("draw", "--json", str(m), "-o", str(out), "--velocity", "--icentres")
    assert p.returncode == 0
    assert set(strict_json(p.stdout)) == {
        *("command", "file", "name", "units"),  # the contract every --json keeps (cli.md)
        *("output", "size_mm", "scales", "icentres", "notes"),
    }


def test_expected_refusal_reads_the_file_not_mech():
    """The rule itself on files whose fate is plain from their text."""
    placed = "joints:\n  A: {type: revolute, links: [frame, a], at: [0, 0]}\ndrive: {link: a, rpm: 60}\n"
    assert expected_refusal(placed, "velocity") is None
    assert expected_refusal(placed.replace(", at: [0, 0]", ""), "position") == "positions need geometry"
    assert expected_refusal(placed.replace(", rpm: 60", ""), "velocity") == "has no speed"
    assert expected_refusal(placed.replace(", rpm: 60", ""), "position") is None
    assert expected_refusal(placed, "dof") is None
