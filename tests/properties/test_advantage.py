"""Mechanical advantage and input torque (mech.properties.advantage) three ways and in closed form.

The I-centre route uses the I-centres' positions only, the virtual-work route central
differences of position solves, the velocity route the solver's velocity analysis; a law
(hypothesis) says all three agree.  Input torques are checked against closed forms derived
here from the loop's geometry (no mech code):

* in-line slider crank, piston on the left: x_B = r cos θ − √(l² − r² sin² θ), so
  dx_B/dθ = −r sin θ + r² sin θ cos θ / √(l² − r² sin² θ), and a force F along x at B is
  balanced by T = −F·dx_B/dθ (virtual work);
* four-bar (Norton, *Design of Machinery*, eq. 6.18): ω₄/ω₂ = a sin(θ₂ − θ₃) / (c sin(θ₄ − θ₃)),
  so a torque T₄ on the rocker is balanced by T₂ = −T₄·ω₄/ω₂.
"""

from __future__ import annotations

import json
import math

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mech.check import check
from mech.errors import InputError
from mech.kinematics import solve
from mech.loader import load, loads
from mech.properties.advantage import input_effort, mechanical_advantage


def four_bar_text(d: float, a: float, b: float, c: float, angle: float, extra: str = "") -> str:
    return f"""
units: {{length: mm, angle: deg}}
links: [frame, crank, coupler, rocker]
joints:
  A: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  B: {{type: revolute, links: [crank, coupler]}}
  C: {{type: revolute, links: [coupler, rocker], near: [{d!r}, {c!r}]}}
  D: {{type: revolute, links: [rocker, frame], at: [{d!r}, 0]}}
lengths: {{AB: {a!r}, BC: {b!r}, CD: {c!r}}}
points:
  E: {{link: coupler, from: B, toward: C, offset: [{0.4 * b!r}, {0.3 * b!r}]}}
drive: {{link: crank, angle: {angle!r}, rpm: 100, direction: ccw}}
{extra}"""


def closes(d: float, a: float, b: float, c: float, theta: float) -> bool:
    bd = math.hypot(a * math.cos(theta) - d, a * math.sin(theta))
    return abs(b - c) + 0.05 * max(a, b, c, d) < bd < b + c - 0.05 * max(a, b, c, d)


lengths = st.floats(min_value=20.0, max_value=200.0)


@settings(max_examples=40, deadline=None)
@given(d=lengths, a=lengths, b=lengths, c=lengths, angle=st.integers(min_value=0, max_value=359))
def test_mechanical_advantage_by_icentres_equals_virtual_work_and_velocity_solution(d, a, b, c, angle):
    assume(closes(d, a, b, c, math.radians(angle)))
    ordered = sorted((a, b, c, d))  # not a change-point linkage (a rhombus folds at the instant)
    assume(abs(ordered[0] + ordered[3] - ordered[1] - ordered[2]) > 1e-2 * ordered[3])
    mech = loads(four_bar_text(d, a, b, c, angle))
    kin = solve(mech, "velocity")
    for output in ("rocker", "coupler", "C", "E"):
        ma = mechanical_advantage(mech, kin, output)
        assume(ma.value < 1e6)  # an output at rest (a dead centre) has no finite advantage
        assert ma.by_icentres == pytest.approx(ma.value, rel=1e-9)
        # virtual displacements are differences of positions, good to ~1e-12 absolute: compare the
        # rates they give (1/MA: dφ/dθ, or |dr/dθ| in m scaled by the size), not MA, which grows
        # without bound near a dead centre of the output
        scale = 1.0 if ma.kind == "link" else kin.size
        assert 1 / ma.by_virtual_work == pytest.approx(1 / ma.value, rel=1e-9, abs=1e-9 * scale)


def test_slider_crank_input_torque_balances_a_piston_force():
    mech = load("mechanisms/slider_crank.yaml")  # r = 150, l = 600 mm, crank at 135°
    assert [(ld.target, ld.force) for ld in mech.loads] == [("B", (-2000.0, 0.0))]
    r, rod, th = 0.15, 0.6, math.radians(135.0)
    root = math.sqrt(rod**2 - (r * math.sin(th)) ** 2)
    dx = -r * math.sin(th) + r * r * math.sin(th) * math.cos(th) / root
    expected = 2000.0 * dx  # T = −F·dx_B/dθ with F = −2000 N
    effort = input_effort(mech, solve(mech, "velocity"))
    assert effort.kind == "torque"
    assert effort.value == pytest.approx(expected, rel=1e-9)
    assert effort.by_virtual_work == pytest.approx(expected, rel=1e-9)


def test_four_bar_input_torque_balances_a_rocker_torque():
    d, a, b, c, th2 = 0.15, 0.04, 0.15, 0.08, math.radians(60.0)  # Khurmi Ex. 7.1
    # circle intersection for C (above AD), then the link angles
    bx, by = a * math.cos(th2), a * math.sin(th2)
    dx, dy = d - bx, -by
    s = math.hypot(dx, dy)
    along = (b * b - c * c + s * s) / (2 * s)
    h = math.sqrt(b * b - along * along)
    cx = bx + along * dx / s - h * dy / s
    cy = by + along * dy / s + h * dx / s
    th3, th4 = math.atan2(cy - by, cx - bx), math.atan2(cy, cx - d)
    ratio = a * math.sin(th2 - th3) / (c * math.sin(th4 - th3))
    mech = loads(
        load("mechanisms/four_bar.yaml").source + 'loads: {rocker: {torque: "20 N m"}}\n', path="fb.yaml"
    )
    effort = input_effort(mech, solve(mech, "velocity"))
    assert effort.value == pytest.approx(-20.0 * ratio, rel=1e-9)
    assert effort.by_virtual_work == pytest.approx(-20.0 * ratio, rel=1e-9)
    assert mechanical_advantage(mech, solve(mech, "velocity"), "rocker").value == pytest.approx(
        1 / abs(ratio), rel=1e-9
    )


def test_check_reads_mechanical_advantage_and_input_torque():
    # ω_rocker/ω_crank = 0.380744 (the I-centre ratio I12·I24 / I14·I24): MA 2.6264; 20 N·m on the rocker
    text = load("mechanisms/four_bar.yaml").source.split("answers:")[0]
    text += 'loads: {rocker: {torque: "20 N m"}}\nanswers:\n  mechanical_advantage.rocker: 2.626\n  input_torque: "-7.615 N m"\n'
    verdicts = check(loads(text))
    assert [v.status for v in verdicts] == ["pass", "pass"], [v.message for v in verdicts]


def test_input_torque_without_loads_says_what_to_add():
    mech = load("mechanisms/four_bar.yaml")
    with pytest.raises(InputError, match="has no loads"):
        input_effort(mech, solve(mech, "velocity"))


def test_a_torque_on_a_point_is_refused_with_its_line(write, run):
    text = load("mechanisms/four_bar.yaml").source.split("answers:")[0] + "loads: {C: {torque: 5}}\n"
    result = run("velocity", str(write(text)))
    assert result.exit_code == 2
    assert "C is a point: load it with a force" in result.stderr


def test_properties_command_shows_advantage_three_ways_and_the_input_torque(write, run):
    text = (
        load("mechanisms/four_bar.yaml").source.split("answers:")[0] + 'loads: {rocker: {torque: "20 N m"}}\n'
    )
    result = run("properties", str(write(text)), "--json", "--output", "rocker", "--output", "C")
    assert result.exit_code == 0, result.output
    out = json.loads(result.output)
    rocker = out["mechanical_advantage"]["rocker"]
    assert rocker["by_icentres"] == pytest.approx(rocker["value"], rel=1e-9)
    assert rocker["by_virtual_work"] == pytest.approx(rocker["value"], rel=1e-9)
    assert "I12·I24 / I14·I24" in rocker["construction"]
    assert out["mechanical_advantage"]["C"]["unit"] == "1/m"
    assert out["input_torque"] == pytest.approx(out["input_effort"]["by_virtual_work"], rel=1e-9)


def test_properties_refuses_an_unknown_output(run):
    result = run("properties", "mechanisms/four_bar.yaml", "--output", "nothing")
    assert result.exit_code == 2 and "neither a link nor a point" in result.stderr


def test_slider_drive_input_force_balances_a_torque_on_the_slotted_link():
    # Hibbeler 16-48: B = (0.6, y) rises with the cylinder; the link's angle θ = atan2(y, 0.6), so
    # dθ/dy = 0.6 / (0.36 + y²) = 0.8333 per m at y = 0.6 m. A torque T on the link is balanced by
    # a force F along the cylinder's path with F·dy + T·dθ = 0: F = −T·dθ/dy.
    text = load("mechanisms/hibbeler_slotted_link_cylinder.yaml").source.split("answers:")[0]
    mech = loads(text + 'loads: {link: {torque: "12 N m"}}\n')
    kin = solve(mech, "velocity")
    dtheta_dy = 0.6 / (0.36 + 0.6**2)
    effort = input_effort(mech, kin)
    assert effort.kind == "force" and effort.by_virtual_work is None  # a slider drive is not turned by θ ± h
    assert effort.value == pytest.approx(-12.0 * dtheta_dy, rel=1e-9)
    ma = mechanical_advantage(mech, kin, "link")
    assert (ma.unit, ma.value) == ("m", pytest.approx(1 / dtheta_dy, rel=1e-9))
    (verdict,) = check(loads(text + 'loads: {link: {torque: "12 N m"}}\nanswers:\n  input_force: "-10 N"\n'))
    assert verdict.status == "pass", verdict.message
