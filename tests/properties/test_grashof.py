"""Grashof's criterion and slider-crank inversions (mech.topology.grashof, mech dof, mech classify).

The reference for "which link turns fully" is not Grashof's rule but the loop
itself: a moving link turns fully relative to the frame when the loop closes
at every angle of it, sampled on a fine grid of angles independently of s + l
against p + q (oracles.transmission.turning_by_sampling).
"""

from __future__ import annotations

import json

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mech.loader import loads
from mech.topology import classify
from mech.topology.grashof import FourBarLoop, SliderCrankLoop, linkage_loops
from oracles.transmission import turning_by_sampling


def four_bar_text(d: float, a: float, b: float, c: float, *, unit: str = "mm") -> str:
    return f"""
units: {{length: {unit}}}
links: [frame, crank, coupler, rocker]
joints:
  A: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  B: {{type: revolute, links: [crank, coupler]}}
  C: {{type: revolute, links: [coupler, rocker]}}
  D: {{type: revolute, links: [rocker, frame], at: [{d!r}, 0]}}
lengths: {{AB: {a!r}, BC: {b!r}, CD: {c!r}}}
drive: {{link: crank, angle: 0, rpm: 60}}
"""


EXPECTED_CLASS = {
    frozenset({"crank", "coupler", "rocker"}): "double-crank",
    frozenset({"crank"}): "crank-rocker",
    frozenset({"rocker"}): "crank-rocker",
    frozenset({"coupler"}): "double-rocker",
    frozenset(): "non-grashof",
}

lengths = st.floats(min_value=10.0, max_value=200.0, allow_nan=False)


@settings(max_examples=150, deadline=None)
@given(d=lengths, a=lengths, b=lengths, c=lengths)
def test_grashof_class_matches_which_links_can_turn_fully(d, a, b, c):
    ordered = sorted((a, b, c, d))
    # away from s + l = p + q by more than the 0.1° grid can resolve
    assume(abs(ordered[0] + ordered[3] - ordered[1] - ordered[2]) > 1e-2 * ordered[3])
    (loop,) = classify(loads(four_bar_text(d, a, b, c))).loops
    turning = turning_by_sampling(d, a, b, c)
    assert isinstance(loop, FourBarLoop)
    assert loop.kind == EXPECTED_CLASS[frozenset(turning)]
    assert set(loop.turns_fully) == turning


@pytest.mark.parametrize(
    ("d", "a", "b", "c", "kind", "turning"),
    [
        (150, 40, 150, 80, "crank-rocker", {"crank"}),  # Khurmi Ex. 7.1: 40 + 150 < 80 + 150
        (40, 100, 120, 90, "double-crank", {"crank", "coupler", "rocker"}),  # frame shortest: drag link
        (100, 80, 30, 90, "double-rocker", {"coupler"}),  # coupler shortest
        (100, 70, 60, 80, "non-grashof", set()),  # 60 + 100 > 70 + 80
    ],
)
def test_grashof_class_of_textbook_proportions(d, a, b, c, kind, turning):
    (loop,) = classify(loads(four_bar_text(d, a, b, c))).loops
    assert (loop.kind, set(loop.turns_fully)) == (kind, turning)


def test_change_point_when_s_plus_l_equals_p_plus_q():
    # 40 + 150 = 90 + 100: the links can fold into one line
    (loop,) = classify(loads(four_bar_text(150, 40, 100, 90))).loops
    assert loop.condition == loop.kind == "change-point"
    assert loop.sums == pytest.approx((0.19, 0.19), rel=1e-12)


def test_grashof_needs_every_length_of_the_loop():
    text = four_bar_text(150, 40, 150, 80).replace(", CD: 80", "")
    assert classify(loads(text)).loops == ()


def test_each_four_bar_loop_of_a_watt_six_bar_is_classified(run):
    out = json.loads(run("dof", "mechanisms/watt_six_bar.yaml", "--json").output)
    loops = [(tuple(lp["links"]), lp["class"]) for lp in out["loops"]]
    # O2B 30 + BC 110 = 140 < O4C 70 + O2O4 100 = 170; O4E 60 + O4O6 150 = 210 > EF 120 + O6F 80 = 200
    assert loops == [
        (("frame", "crank", "coupler", "rocker"), "crank-rocker"),
        (("frame", "rocker", "link5", "output"), "non-grashof"),
    ]


def test_dof_shows_grashof_worked_in_the_files_units(run):
    result = run("dof", "mechanisms/four_bar.yaml")
    assert result.exit_code == 0
    assert "s + l = 40 + 150 = 190 < p + q = 80 + 150 = 230 mm" in result.output
    assert "crank-rocker; turns fully: crank" in result.output


def test_classify_shows_grashof(run):
    assert "crank-rocker" in run("classify", "mechanisms/khurmi_four_bar_acceleration.yaml").output


@pytest.mark.parametrize(
    ("path", "fixed", "crank"),
    [
        ("mechanisms/slider_crank.yaml", "guide", "crank"),
        ("mechanisms/whitworth_quick_return.yaml", "crank", "frame"),  # O1O2 100 < OP 200: shortest fixed
        ("mechanisms/crank_slotted_lever.yaml", "rod", "crank"),  # O1O2 500 > O2A 120
    ],
)
def test_slider_crank_inversion_is_named_by_the_fixed_link(path, fixed, crank, run):
    from mech.loader import load

    loop = next(lp for lp in linkage_loops(load(path)) if isinstance(lp, SliderCrankLoop))
    assert (loop.fixed, loop.crank) == (fixed, crank)


def test_slider_fixed_is_the_fourth_inversion():
    text = """
links: [frame, crank, rod, slider]
ground: slider
joints:
  O: {type: revolute, links: [frame, crank], at: [0, 0]}
  A: {type: revolute, links: [crank, rod], at: [0, 1]}
  B: {type: revolute, links: [rod, slider], at: [3, 0]}
  P: {type: prismatic, links: [slider, frame], path: {through: [0, 0], angle: 0}}
"""
    (loop,) = linkage_loops(loads(text))
    assert loop.fixed == "slider" and "fourth inversion" in loop.inversion


def test_offset_slider_crank_turns_fully_when_r_plus_e_within_l(run):
    # offset_slider_crank.yaml: r = 50, e = 20, l = 200 mm: 70 ≤ 200
    out = json.loads(run("dof", "mechanisms/offset_slider_crank.yaml", "--json").output)
    (loop,) = out["loops"]
    assert loop["crank_turns_fully"] is True
    assert abs(loop["offset"]) == pytest.approx(0.02, rel=1e-12)


#: Watt's six-bar with a Grashof second loop: O4E = 30 mm is its shortest link, beside the frame, so
#: that loop alone is a crank-rocker whose "crank" is the first loop's rocker (issue 21, item 4).
WATT_GRASHOF_SECOND_LOOP = """
units: {length: mm, angle: deg}
ground: frame
links: [frame, crank, coupler, rocker, link5, output]
joints:
  O2: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [117, 68]}
  O4: {type: revolute, links: [rocker, frame], at: [100, 0]}
  E: {type: revolute, links: [rocker, link5], near: [120, -20]}
  F: {type: revolute, links: [link5, output], near: [230, 100]}
  O6: {type: revolute, links: [output, frame], at: [250, 0]}
lengths: {O2B: 30, BC: 110, O4C: 70, O4E: 30, CE: 80, EF: 150, O6F: 100}
drive: {link: crank, angle: 60, rpm: 100, direction: ccw}
"""


def test_a_loop_driven_through_another_says_its_rockers_real_swing_beside_the_loops_class(run):
    # The second loop alone: s + l = 30 + 150 < p + q = 100 + 150, shortest beside the frame: a
    # crank-rocker whose rocker would turn fully.  In the mechanism the first loop moves it: its
    # swing is between the first loop's limit positions (crank and coupler in line, |O2C| = 110 ± 30),
    # the angle at O4 by the law of cosines in triangle O2 O4 C.  It said "turns fully: rocker".
    import math

    def at_o4(o2c: float) -> float:
        return math.degrees(math.acos((100.0**2 + 70.0**2 - o2c**2) / (2 * 100.0 * 70.0)))

    swing = at_o4(140.0) - at_o4(80.0)
    out = run("properties", "-", input=WATT_GRASHOF_SECOND_LOOP).output
    second = out[out.index("loop frame–rocker–link5–output") :]
    assert "crank-rocker as a loop alone; turns fully: rocker" in second
    assert f"in this mechanism: rocker swings {swing:.5g}°" in second
