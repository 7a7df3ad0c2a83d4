"""The answer-key registry (``mech.answers``): every key form, ``position.<point>``, ``asks``.

Reference values are worked by hand on the slider crank of ``tests/test_check.py``:
crank OA = r = 0.1 m at 90°, rod AB = l = 0.3 m, so A = (0, r) and B = (√(l² − r²), 0).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from mech.answers import (
    KINDS,
    PLACEHOLDERS,
    AnswerKind,
    Compare,
    key_forms,
    parse_key,
    register,
    unregister,
)
from mech.check import FAIL, PASS, check
from mech.errors import InputError
from mech.loader import loads
from mech.units import Dimension

ROOT = Path(__file__).resolve().parent.parent
R, L = 0.1, 0.3
XB = math.sqrt(L * L - R * R)

SLIDER = """\
name: slider
links: [frame, crank, rod, piston]
joints:
  O: {type: revolute, links: [frame, crank], at: [0, 0]}
  A: {type: revolute, links: [crank, rod]}
  B: {type: revolute, links: [rod, piston], near: [0.3, 0]}
  P: {type: prismatic, links: [piston, frame], path: {through: [0, 0], angle: 0}}
lengths: {OA: 0.1, AB: 0.3}
drive: {link: crank, angle: 90}
"""


def _sample(pattern: str) -> str:
    """A key of the pattern with names filled in (two different names where two are needed)."""
    fill = iter(("crank", "rod", "frame"))
    return ".".join(next(fill) if p.startswith("<") else p for p in pattern.split("."))


@pytest.mark.parametrize("kind", KINDS, ids=lambda k: k.pattern)
def test_every_registered_pattern_parses_back_to_its_row(kind: AnswerKind) -> None:
    akey = parse_key(_sample(kind.pattern))
    assert akey.kind is kind
    assert len(akey.names) == len(akey.kinds) == sum(p.startswith("<") for p in kind.parts)
    assert all(k in set(PLACEHOLDERS.values()) for k in akey.kinds)


def test_every_registered_key_is_documented_in_cli_md() -> None:
    text = (ROOT / "cli.md").read_text(encoding="utf-8")
    answers = text[text.index("### answers") :]
    missing = [k for k in key_forms() if f"`{k}`" not in answers]
    assert not missing, f"cli.md § answers does not list {missing}"


def test_every_form_has_its_compute_function_and_every_function_its_form() -> None:
    # forms (mech.answers, below the loader) and values (mech.grading, above the analysis) are two
    # tables keyed by the pattern: neither may hold a key the other lacks
    from mech.grading import COMPUTE

    forms = set(key_forms())
    assert sorted(forms - set(COMPUTE)) == [] and sorted(set(COMPUTE) - forms) == []


def test_a_key_added_as_a_form_and_a_compute_function_is_read_and_checked() -> None:
    # ARCHITECTURE.md "Where to add an answer key": a form in mech.answers, a function in
    # mech.grading under the same pattern; the loader and mech check need nothing else.
    # The crank's length |OA| is r = 0.1 m by the file's lengths.
    from mech.grading import COMPUTE
    from mech.grading import register as register_compute

    pattern = "crank_length_for_test.<link>"
    register(AnswerKind(pattern, Compare.MAGNITUDE, "position", Dimension.LENGTH, "a link's OA"))
    register_compute(pattern, lambda an, names: math.dist(an.kin.positions["O"], an.kin.positions["A"]))
    try:
        got = _verdicts("  crank_length_for_test.crank: 100 mm\n  crank_length_for_test.rod: 90 mm\n")
        assert got["crank_length_for_test.crank"][0] == PASS
        assert got["crank_length_for_test.rod"][0] == FAIL
    finally:
        unregister(pattern)
        del COMPUTE[pattern]


def test_a_form_without_a_compute_function_is_an_error_row_that_says_it_is_a_bug() -> None:
    register(AnswerKind("no_value_for_test", Compare.COUNT, "topology", Dimension.NUMBER, "nothing"))
    try:
        (v,) = check(loads(SLIDER + "answers:\n  no_value_for_test: 1\n"))
        assert v.status == "error" and "no compute function" in v.message and "a bug" in v.message
    finally:
        unregister("no_value_for_test")


def test_a_pattern_registered_twice_is_refused() -> None:
    with pytest.raises(ValueError, match="registered twice"):
        register(KINDS[0])


def test_an_unknown_placeholder_is_refused_when_registering() -> None:
    with pytest.raises(ValueError, match="unknown placeholder"):
        AnswerKind("speed.<thing>", Compare.MAGNITUDE, "velocity", Dimension.VELOCITY)


@pytest.mark.parametrize(
    ("key", "reason"),
    [
        ("omega", "does not have the form omega.<link>"),
        ("omega.a.b", "does not have the form"),
        ("velocity..A", "does not have the form"),
        ("speed.A", "unknown answer key"),
        ("links.octagonal", "does not have the form"),
    ],
)
def test_malformed_keys_say_which_forms_exist(key: str, reason: str) -> None:
    with pytest.raises(ValueError, match=re.escape(reason)):
        parse_key(key)


def test_a_literal_pattern_wins_over_a_placeholder() -> None:
    # links.count is a count, not "links.<something>"
    assert parse_key("links.count").kind.pattern == "links.count"
    assert parse_key("velocity.A.B").kind.pattern == "velocity.<point>.<other>"


# -- position.<point> --------------------------------------------------------------------------
def _verdicts(answers: str) -> dict[str, tuple[str, str]]:
    return {v.key: (v.status, v.message) for v in check(loads(SLIDER + "answers:\n" + answers))}


def test_position_of_a_point_passes_at_the_closed_form() -> None:
    got = _verdicts(f"  position.A: [0, {R}]\n  position.B: ['{XB * 1000:.3f} mm', 0]\n")
    assert got == {"position.A": (PASS, got["position.A"][1]), "position.B": (PASS, got["position.B"][1])}


def test_position_needs_no_drive_speed() -> None:
    # positions are a position-level solve: the drive above has no rpm or omega
    assert _verdicts(f"  position.B: [{XB}, 0]\n")["position.B"][0] == PASS


def test_position_tolerance_is_a_fraction_of_the_size() -> None:
    # size = |OB| = √(l² − r²) = 0.2828 m; 2% of it is 5.66 mm
    size = XB
    near = _verdicts(f"  position.A: [{0.9 * 0.02 * size}, {R}]\n")["position.A"]
    far = _verdicts(f"  position.A: [{1.1 * 0.02 * size}, {R}]\n")["position.A"]
    assert near[0] == PASS and far[0] == FAIL
    assert "A is at (0, 0.1) m" in far[1]


def test_position_cannot_be_claimed_at_infinity() -> None:
    with pytest.raises(InputError, match=r"\(a point \[x, y\]\) must be a list"):
        loads(SLIDER + "answers:\n  position.A: infinity\n")


# -- asks ---------------------------------------------------------------------------------------
def test_asks_lists_the_questions_of_a_problem() -> None:
    m = loads(SLIDER + "asks: [omega.rod, velocity.B, position.A]\n")
    assert m.asks == ("omega.rod", "velocity.B", "position.A")
    assert m.answers == ()


def test_asks_reports_every_bad_key_located() -> None:
    text = SLIDER + "asks:\n  - omega.rodd\n  - speed.B\n  - velocity.B\n  - velocity.B\n"
    with pytest.raises(InputError) as info:
        loads(text, path="p.yaml")
    problems = info.value.problems
    first = SLIDER.count("\n") + 2
    assert [(p.where.line, p.where.column) for p in problems] == [(first, 5), (first + 1, 5), (first + 3, 5)]
    assert "unknown link 'rodd'" in problems[0].message and problems[0].hint == "did you mean 'rod'?"
    assert "unknown answer key" in problems[1].message
    assert "twice" in problems[2].message


def test_asks_must_be_a_list() -> None:
    with pytest.raises(InputError, match="asks"):
        loads(SLIDER + "asks: omega.rod\n")


# -- I-centre names, accepted without being built ------------------------------------------------
def _all_icentres(n: int) -> set[str]:
    """Textbook names by hand: I13 while both numbers are single digits, I1,12 beyond (cli.md)."""
    return {f"I{a}{b}" if b < 10 else f"I{a},{b}" for a in range(1, n + 1) for b in range(a + 1, n + 1)}


@pytest.mark.parametrize("n", [2, 4, 9, 10, 12])
def test_icentre_names_accept_exactly_the_textbook_names(n: int) -> None:
    from mech.answers import names_by_kind

    icpoint = names_by_kind(["frame"], ["A", "B"], ["E"], n)["icpoint"]
    assert set(icpoint) == {"A", "B", "E"} | _all_icentres(n)
    assert len(icpoint) == len({"A", "B", "E"} | _all_icentres(n))
    for name in ("I31", "I11", "I0,3", f"I1,{n + 1}", "I1,2", "I", "E2"):
        assert name not in icpoint, name


def test_icentre_names_of_ten_thousand_links_are_not_built() -> None:
    # 49,995,000 names: membership is decided from the name (it took 2.9 GB and a minute).
    from mech.answers import ICentreNames, names_by_kind

    icpoint = names_by_kind([], [], ["P"], 10_000)["icpoint"]
    assert isinstance(icpoint, ICentreNames)
    assert "I9999,10000" in icpoint and "I1,10000" in icpoint and "I12" in icpoint
    assert "I1,10001" not in icpoint and "I10000,9999" not in icpoint
    assert len(icpoint) == 1 + 10_000 * 9_999 // 2


def test_a_misspelt_icentre_answer_on_a_large_file_is_refused_with_a_hint() -> None:
    links = [f"l{i}" for i in range(1, 200)]
    joints = "\n".join(
        f"  J{i}: {{type: revolute, links: [{a}, {b}]}}"
        for i, (a, b) in enumerate(zip(["frame", *links], [*links, "frame"], strict=True))
    )
    text = f"links: [frame, {', '.join(links)}]\njoints:\n{joints}\nanswers:\n  distance.J1.I1,300: 1\n"
    with pytest.raises(InputError, match="names unknown point or I-centre 'I1,300'"):
        loads(text)
