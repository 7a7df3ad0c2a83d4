"""Diagnosed mistakes: a claim built to match each usual mistake gets that diagnosis, others none.

Every reference value here is worked in this file by the vector-loop (Raven) method, not
by mech: for the four-bar A(0,0) – B – C – D(150 mm, 0) with AB = 40, BC = 150, CD = 80 mm,
the crank at 60° turning 120 rpm clockwise (ω₂ = −4π rad/s, α₂ = 0):

* B = AB(cos θ, sin θ); C is where the circles (B, BC) and (D, CD) meet, on the branch
  nearest the drawn hint (160, 80), or on the other one (the mirror across BD);
* velocities from v_B + ω₃ k × (C − B) = ω₄ k × (C − D), a 2×2 linear solve;
* accelerations from a_B + α₃ k × (C − B) − ω₃²(C − B) = α₄ k × (C − D) − ω₄²(C − D).

The slotted lever (``mechanisms/crank_slotted_lever.yaml``'s geometry) is worked the same way:
the block at A slides along the lever O₁A; v_slide = v_A · u, ω₄ = v_A · u⊥ / |O₁A|, and the
Coriolis component is 2 ω₄ v_slide u⊥.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mech.check import FAIL, PASS, check
from mech.loader import loads
from mechanism_texts import rack_and_pinion, slider_crank

MM = 1e-3
AB, BC, CD, AD = 40 * MM, 150 * MM, 80 * MM, 150 * MM
THETA, W2 = math.radians(60), -120 * 2 * math.pi / 60

FOUR_BAR = """\
name: four-bar
units: {length: mm, angle: deg}
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [160, 80]}
  D: {type: revolute, links: [rocker, frame], at: [150, 0]}
lengths: {AB: 40, BC: 150, CD: 80}
drive: {link: crank, angle: 60, rpm: 120, direction: cw}
answers:
"""


def _cross(w: float, r: np.ndarray) -> np.ndarray:
    return np.array([-w * r[1], w * r[0]])


def four_bar(branch: str = "drawn") -> dict[str, object]:
    """Positions, ω, α, point velocities and accelerations of the four-bar, by the vector loop."""
    b = AB * np.array([math.cos(THETA), math.sin(THETA)])
    d = np.array([AD, 0.0])
    # circle–circle intersection
    bd = d - b
    dist = float(np.hypot(*bd))
    x = (BC**2 - CD**2 + dist**2) / (2 * dist)
    h = math.sqrt(BC**2 - x**2)
    ex = bd / dist
    ey = np.array([-ex[1], ex[0]])
    c1, c2 = b + x * ex + h * ey, b + x * ex - h * ey
    hint = np.array([160 * MM, 80 * MM])
    near, far = sorted((c1, c2), key=lambda c: float(np.hypot(*(c - hint))))
    c = near if branch == "drawn" else far
    rb, rc = c - b, c - d
    vb = _cross(W2, b)
    # v_B + ω3 k×rb = ω4 k×rc  →  [k×rb, −k×rc] [ω3, ω4]ᵀ = −v_B
    m = np.column_stack([_cross(1.0, rb), -_cross(1.0, rc)])
    w3, w4 = np.linalg.solve(m, -vb)
    ab = -(W2**2) * b
    rhs = -ab + w3**2 * rb - w4**2 * rc
    a3, a4 = np.linalg.solve(m, rhs)
    vc = _cross(w4, rc)
    ac = _cross(a4, rc) - w4**2 * rc
    return {"B": b, "C": c, "w3": w3, "w4": w4, "a3": a3, "a4": a4, "vb": vb, "vc": vc, "ab": ab, "ac": ac}


FB = four_bar()
OTHER = four_bar("other")


def verdict(answers: str, body: str = FOUR_BAR):
    (v,) = check(loads(body + "".join(f"  {ln}\n" for ln in answers.splitlines())))
    return v


def assert_diagnosed(answer: str, words: str, body: str = FOUR_BAR) -> None:
    v = verdict(answer, body)
    assert v.status == FAIL, v
    assert v.diagnosis is not None and words in v.diagnosis, (v.message, v.diagnosis)


def test_the_reference_solution_agrees_with_mech() -> None:
    # guard: the hand-worked four-bar is the one mech solves (so the claims below are built right)
    assert verdict(f"omega.rocker: {FB['w4']:.6f}").status == PASS
    assert verdict(f"acceleration.C: {math.hypot(*FB['ac']):.6f}").status == PASS


def test_opposite_sense() -> None:
    sense = "ccw" if FB["w4"] < 0 else "cw"  # the wrong one
    assert_diagnosed(f"omega.rocker: {abs(FB['w4']):.6f} rad/s {sense}", "the opposite sense")


def test_opposite_sense_of_an_angular_acceleration_names_the_sense_of_alpha_not_of_turning() -> None:
    # α₄ by the vector loop; its sense is not how the rocker turns (ω₄), so the words are α's own
    sense = "ccw" if FB["a4"] < 0 else "cw"  # the wrong one
    right = "ccw" if FB["a4"] > 0 else "cw"
    assert_diagnosed(
        f"alpha.rocker: {abs(FB['a4']):.6f} rad/s^2 {sense}", f"the opposite sense (α of rocker is {right})"
    )


def test_unit_slip_mm_written_as_m() -> None:
    assert_diagnosed(f"velocity.C: {1000 * math.hypot(*FB['vc']):.6f}", "×1000")


def test_unit_slip_rpm_read_as_rad_per_s() -> None:
    assert_diagnosed("omega.crank: 120 rad/s", "rpm")


def test_unit_slip_degrees_as_radians() -> None:
    assert_diagnosed(f"alpha.rocker: {math.degrees(abs(FB['a4'])):.6f} rad/s^2", "degrees given as radians")


def test_other_assembly_branch_for_an_angular_velocity() -> None:
    v = verdict(f"omega.rocker: {abs(OTHER['w4']):.6f}")
    assert v.status == FAIL and v.diagnosis is not None
    assert v.diagnosis.startswith("the other assembly branch (C ") and v.diagnosis.endswith(" BD)")


def test_other_assembly_branch_for_a_position() -> None:
    x, y = OTHER["C"]
    assert_diagnosed(f"position.C: [{x:.6f}, {y:.6f}]", "the other assembly branch")


def test_other_assembly_branch_of_a_slider_crank() -> None:
    # r = 0.1, l = 0.4 m, crank at 45° turning 10 rad/s ccw: with the slider behind the crank,
    # x_B = r cos θ − √(l² − r² sin² θ), so ẋ_B = −rω sin θ + r²ω sin θ cos θ / √(l² − r² sin² θ)
    r, rod, th, w = 0.1, 0.4, math.radians(45), 10.0
    v_other = -r * w * math.sin(th) + r * r * w * math.sin(th) * math.cos(th) / math.sqrt(
        rod**2 - (r * math.sin(th)) ** 2
    )
    body = slider_crank(r, rod, angle=45, omega=w) + "answers:\n"
    v = verdict(f"velocity.B: {abs(v_other):.6f} m/s", body)
    assert v.status == FAIL and v.diagnosis is not None
    assert v.diagnosis.startswith("the other assembly branch (B "), v.diagnosis


def test_omega_of_the_wrong_link() -> None:
    assert_diagnosed(f"omega.rocker: {abs(FB['w3']):.6f}", "ω of the wrong link (coupler's)")


def test_relative_velocity_given_for_an_absolute_one() -> None:
    rel = FB["vc"] - FB["vb"]
    assert_diagnosed(f"velocity.C: {math.hypot(*rel):.6f}", "relative to B")


def test_absolute_velocity_given_for_a_relative_one() -> None:
    assert_diagnosed(f"velocity.C.B: {math.hypot(*FB['vc']):.6f}", "the absolute velocity of C")


def test_only_the_normal_component_of_a_relative_acceleration() -> None:
    assert_diagnosed(f"acceleration.C.B: {FB['w3'] ** 2 * BC:.6f}", "only the normal component of a_CB")


def test_only_the_tangential_component_of_a_point_turning_about_a_pivot() -> None:
    # (on the coupler, α₃·BC is within 2% of |a_CB| itself here: ω₃²·BC is small, so no test there)
    assert_diagnosed(f"acceleration.C: {abs(FB['a4']) * CD:.6f}", "only the tangential component (α·DC")


def test_only_the_normal_component_of_a_point_turning_about_a_pivot() -> None:
    assert_diagnosed(f"acceleration.C: {FB['w4'] ** 2 * CD:.6f}", "only the normal component (ω²·DC")


SLOTTED = """\
name: slotted lever
units: {length: mm, angle: deg}
links: [frame, crank, block, lever]
joints:
  O2: {type: revolute, links: [frame, crank], at: [0, 500]}
  A: {type: revolute, links: [crank, block]}
  slot: {type: prismatic, links: [block, lever], path: {through: O1, toward: B}}
  O1: {type: revolute, links: [lever, frame], at: [0, 0]}
lengths: {O2A: 120}
points:
  B: {link: lever, at: [102.170, 591.237]}
drive: {link: crank, angle: 35, rpm: 600, direction: ccw}
answers:
"""


def test_coriolis_left_out() -> None:
    w2, r, t = 600 * 2 * math.pi / 60, 0.12, math.radians(35)
    o2 = np.array([0.0, 0.5])
    a = o2 + r * np.array([math.cos(t), math.sin(t)])
    va = _cross(w2, a - o2)
    u = a / np.hypot(*a)
    n = np.array([-u[1], u[0]])
    slide = float(va @ u)
    w4 = float(va @ n) / float(np.hypot(*a))
    coriolis = 2 * w4 * slide * n
    aa = -(w2**2) * (a - o2)
    assert math.hypot(*coriolis) == pytest.approx(98.48, rel=1e-3)  # the example file's own check
    assert verdict(f"coriolis.slot: {math.hypot(*coriolis):.6f}", SLOTTED).status == PASS
    assert_diagnosed(f"acceleration.A: {math.hypot(*(aa - coriolis)):.6f}", "Coriolis left out", SLOTTED)
    assert_diagnosed(f"coriolis.slot: {math.hypot(*coriolis) / 2:.6f}", "factor 2", SLOTTED)


# -- no diagnosis where there is none ---------------------------------------------------------------
RIGHT = [
    f"omega.rocker: {abs(FB['w4']):.6f} rad/s {'ccw' if FB['w4'] > 0 else 'cw'}",
    f"omega.coupler: {abs(FB['w3']):.6f}",
    f"velocity.C: {math.hypot(*FB['vc']):.6f}",
    f"velocity.C.B: {math.hypot(*(FB['vc'] - FB['vb'])):.6f}",
    f"acceleration.C: {math.hypot(*FB['ac']):.6f}",
    f"alpha.rocker: {abs(FB['a4']):.6f}",
    f"position.C: [{FB['C'][0]:.6f}, {FB['C'][1]:.6f}]",
]


@pytest.mark.parametrize("answer", RIGHT)
def test_a_right_answer_passes_without_a_diagnosis(answer: str) -> None:
    v = verdict(answer)
    assert v.status == PASS and v.diagnosis is None


@pytest.mark.parametrize("answer", RIGHT)
def test_diagnose_never_names_a_mistake_for_the_right_value(answer: str) -> None:
    from mech.answers import parse_key
    from mech.diagnose import diagnose
    from mech.grading import Analysis, value

    mech = loads(FOUR_BAR + f"  {answer}\n")
    (claim,) = mech.answers
    an = Analysis(mech)
    an.need([claim])
    akey = parse_key(claim.key)
    assert diagnose(claim, akey, value(akey, an), an, mech.tolerance) is None


@pytest.mark.parametrize(
    "answer",
    [
        f"velocity.C: {1.37 * math.hypot(*FB['vc']):.6f}",
        f"omega.rocker: {0.61 * abs(FB['w4']):.6f}",
        f"acceleration.C: {1.23 * math.hypot(*FB['ac']):.6f}",
        f"position.C: [{FB['C'][0] + 0.05:.6f}, {FB['C'][1]:.6f}]",
    ],
)
def test_an_unrelated_wrong_answer_fails_without_a_diagnosis(answer: str) -> None:
    v = verdict(answer)
    assert v.status == FAIL and v.diagnosis is None, v.diagnosis


# -- every format carries it ---------------------------------------------------------------------
def test_the_diagnosis_reaches_json_junit_gradescope_and_the_listing(tmp_path, run) -> None:
    import json
    from xml.etree import ElementTree as ET

    f = tmp_path / "a.yaml"
    f.write_text(FOUR_BAR + f"  omega.rocker: {abs(FB['w3']):.6f}\n")
    junit, gs = tmp_path / "j.xml", tmp_path / "g.json"
    result = run("check", str(f), "-v", "--junit", str(junit), "--gradescope", str(gs))
    assert result.exit_code == 1
    words = "matches ω of the wrong link (coupler's)"
    assert words in result.output
    assert words in ET.parse(junit).getroot().find(".//failure").get("message")
    assert words in json.loads(gs.read_text())["tests"][0]["output"]
    data = json.loads(run("check", str(f), "--json").stdout)
    assert data["results"][0]["answers"][0]["diagnosis"] == "ω of the wrong link (coupler's)"


def test_omega_of_the_wrong_link_with_the_wrong_sense() -> None:
    # the coupler's ω (1.309 rad/s ccw by the vector loop) given as the rocker's, turned cw
    sense = "cw" if FB["w3"] > 0 else "ccw"
    assert_diagnosed(
        f"omega.rocker: {abs(FB['w3']):.6f} rad/s {sense}",
        "ω of the wrong link (coupler's), with the wrong sense",
    )


def test_the_other_branch_with_a_wrong_magnitude_names_the_magnitude_before_the_sense() -> None:
    # the other branch turns the rocker the other way and 1.4× as fast: the magnitude is the larger error
    sense = "ccw" if OTHER["w4"] > 0 else "cw"
    v = verdict(f"omega.rocker: {abs(OTHER['w4']):.6f} rad/s {sense}")
    assert v.status == FAIL and not v.message.startswith("wrong sense"), v.message
    off = abs(abs(OTHER["w4"]) - abs(FB["w4"])) / abs(FB["w4"])
    assert f"off by {off:.1%}" in v.message and v.message.endswith("the sense is wrong")
    assert v.diagnosis is not None and v.diagnosis.startswith("the other assembly branch")


def _time_ratio() -> float:
    """Slow stroke over fast for the crank-rocker, from its two dead centres (law of cosines):
    crank and coupler in line (AC = BC + AB, crank along AC) and folded (AC = BC − AB, crank
    opposite AC); the crank turns 180° + (φ_folded − φ_extended) between them one way."""
    ext = math.acos((AD**2 + (BC + AB) ** 2 - CD**2) / (2 * AD * (BC + AB)))
    fold = math.acos((AD**2 + (BC - AB) ** 2 - CD**2) / (2 * AD * (BC - AB)))
    one = math.pi + fold - ext
    return max(one, 2 * math.pi - one) / min(one, 2 * math.pi - one)


def test_the_reciprocal_time_ratio() -> None:
    assert verdict(f"time_ratio: {_time_ratio():.6f}").status == PASS  # guard: the closed form is mech's
    assert_diagnosed(f"time_ratio: {1 / _time_ratio():.6f}", "the reciprocal")


def test_half_the_stroke() -> None:
    # an in-line slider crank's stroke is twice the crank (r = 0.1 m): 0.2 m; half of it is r
    body = slider_crank(0.1, 0.4) + "answers:\n"
    assert verdict("stroke.P: 0.2", body).status == PASS
    assert_diagnosed("stroke.P: 0.1", "half the stroke", body)


RACK_AND_PINION = rack_and_pinion(extra="answers:\n")


@pytest.mark.parametrize(
    ("answer", "words"),
    [
        # 1000 N held along the pitch line: the tooth load is 1000 / cos 20° = 1064.18 N
        ("force.mesh: 1000 N", "the tangential part only"),
        ("force.mesh: 363.97 N", "the radial part only"),  # 1000 tan 20°
    ],
)
def test_a_tooth_load_worked_as_one_of_its_parts(answer, words) -> None:
    assert_diagnosed(answer, words, RACK_AND_PINION)
