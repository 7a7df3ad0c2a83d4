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
from mechanism_texts import epicyclic, slider_crank


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
        if ma.by_virtual_work is None:  # so near a dead centre that differences of positions lose it
            assert 1 / ma.value < 1e-4 * scale and "not resolved" in ma.notes[0]
            continue
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


def test_input_torque_reads_a_load_table_at_the_drive_angle():
    # DESIGN § 1.4: a load's table is read at the drive's angle, linearly between rows, repeated
    # with its span.  Slider crank r = 50, l = 200 mm, piston on the right, crank at 30°:
    # x_B = r cos θ + √(l² − r² sin² θ), dx_B/dθ = −r sin θ − r² sin θ cos θ / √(l² − r² sin² θ);
    # the piston's force is the row [10°, 80 N] … [170°, 80 N], so T = −80 N·dx_B/dθ.  The crank's
    # own torque table [[0, 0], [90, 9]] (span 90°) reads 3 N·m at 30° and again at 390° (= 30°
    # + 4 × 90°), balanced by −3 N·m.
    base = slider_crank(50, 200, mm=True, drive="{link: crank, angle: ANGLE, rpm: 1500, direction: ccw}")
    force = "loads: {B: {force: {table: [[0, 0, 0], [10, 80, 0], [170, 80, 0], [360, 0, 0]]}, on: piston}}\n"
    r, rod, th = 0.05, 0.2, math.radians(30.0)
    dx = -r * math.sin(th) - r * r * math.sin(th) * math.cos(th) / math.sqrt(rod**2 - (r * math.sin(th)) ** 2)
    mech = loads(base.replace("ANGLE", "30") + force)
    effort = input_effort(mech, solve(mech, "velocity"))
    assert effort.value == pytest.approx(-80.0 * dx, rel=1e-9)
    assert effort.by_virtual_work == pytest.approx(-80.0 * dx, rel=1e-9)
    for angle in ("30", "390"):
        mech = loads(base.replace("ANGLE", angle) + "loads: {crank: {torque: {table: [[0, 0], [90, 9]]}}}\n")
        effort = input_effort(mech, solve(mech, "velocity"))
        assert effort.value == pytest.approx(-3.0, rel=1e-12)
        assert effort.by_virtual_work == pytest.approx(-3.0, rel=1e-9)


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


# -- a dead centre: the advantage is infinite, and said so (issue 25, items 1 and 5) ---------------
# In-line slider crank r = 150, l = 600 mm (slider_crank.yaml), piston on the left:
#   dx_B/dθ = −r sin θ (1 + r cos θ / √(l² − r² sin² θ)), zero at θ = 180°: v_B = 0, MA = ∞.
#   At θ = 180° + δ (δ small), dx_B/dθ = r δ (1 + r/l) + O(δ³): MA = 1 / (r δ (1 + r/l)).
SLIDER_CRANK = load("mechanisms/slider_crank.yaml").source.split("answers:")[0]


def slider_crank_at(angle: str, answers: str = "") -> str:
    text = SLIDER_CRANK.replace("angle: 135, rpm", f"angle: {angle}, rpm")
    assert text != SLIDER_CRANK or angle == "135"
    return text + (f"answers:\n{answers}" if answers else "")


def test_mechanical_advantage_at_the_slider_cranks_dead_centre_is_infinite_every_way():
    mech = loads(slider_crank_at("180"))
    kin = solve(mech, "velocity")
    for output in ("piston", "B"):
        ma = mechanical_advantage(mech, kin, output)
        assert ma.dead_centre and ma.kind == "point"
        assert (ma.value, ma.by_icentres, ma.by_virtual_work) == (math.inf, math.inf, math.inf)
        assert ma.velocity_ratio == 0.0
    # no load does work at a dead centre of the loaded point: the balancing torque is zero
    effort = input_effort(mech, kin)
    assert (effort.value, effort.by_virtual_work) == (0.0, 0.0)


def test_mechanical_advantage_of_a_rocker_at_its_limit_is_an_infinite_torque_ratio():
    # Khurmi's four-bar (d 150, a 40, b 150, c 80 mm): the rocker stops where crank and coupler lie
    # in line, AC = b + a = 190 mm; the crank's angle there from triangle ACD (cosine rule).
    d, a, b, c = 150.0, 40.0, 150.0, 80.0
    theta = math.degrees(math.acos(((b + a) ** 2 + d * d - c * c) / (2 * (b + a) * d)))
    text = load("mechanisms/four_bar.yaml").source.split("answers:")[0]
    mech = loads(text.replace("angle: 60, rpm", f"angle: {theta!r}, rpm"))
    ma = mechanical_advantage(mech, solve(mech, "velocity"), "rocker")
    # a rocker at rest turns about its pivot: a link at a dead centre, not a translating link
    assert (ma.kind, ma.unit, ma.dead_centre) == ("link", "1", True)
    assert (ma.value, ma.by_icentres, ma.by_virtual_work) == (math.inf, math.inf, math.inf)


def test_mechanical_advantage_next_to_a_dead_centre_is_the_closed_form_or_not_given():
    r, rod = 0.15, 0.6
    mech = loads(slider_crank_at("180.000000001"))  # 1e-9° past the dead centre
    th = mech.drives[0].angle  # the angle as read (a double 2.5e-5 of δ from 1e-9° exactly)
    assert th is not None
    dx = -r * math.sin(th) + r * r * math.sin(th) * math.cos(th) / math.sqrt(rod**2 - (r * math.sin(th)) ** 2)
    expected = 1.0 / abs(dx)  # ≈ 1 / (r δ (1 + r/l)) = 3.0558e11 per m
    ma = mechanical_advantage(mech, solve(mech, "velocity"), "piston")
    assert not ma.dead_centre
    assert ma.value == pytest.approx(expected, rel=1e-6)
    # I12·I24 = r δ (1 + r/l) = 3.3e-12 m, measured between points held to an ulp of 0.75 m (1.1e-16 m):
    # five figures at best (it came out 2e-5 off), so no number, and why; the velocity solution's is exact
    assert ma.by_icentres is None and "not resolved to six figures" in ma.construction
    # differences of positions 1.7e-11 rad apart cannot give six figures: no number, and why
    assert ma.by_virtual_work is None and "not resolved" in ma.notes[0]
    # a millionth of a degree out, I12·I24 = 3.3e-9 m is resolved: the closed form to six figures
    near = loads(slider_crank_at("180.000001"))
    th = near.drives[0].angle
    assert th is not None
    dx = -r * math.sin(th) + r * r * math.sin(th) * math.cos(th) / math.sqrt(rod**2 - (r * math.sin(th)) ** 2)
    ma = mechanical_advantage(near, solve(near, "velocity"), "piston")
    assert ma.by_icentres == pytest.approx(1.0 / abs(dx), rel=1e-6)


def test_a_slow_wheel_of_a_high_ratio_gear_train_is_not_at_a_dead_centre():
    # pinion 1 mm, wheel 1e6 mm: ω_wheel/ω_pinion = −r1/r2 = −1e-6 (the rows say so exactly)
    text = """
units: {length: mm, angle: deg}
links: [frame, pinion, wheel]
joints:
  O1: {type: revolute, links: [frame, pinion], at: [0, 0]}
  O2: {type: revolute, links: [frame, wheel], at: [1000001, 0]}
  mesh: {type: gear, links: [pinion, wheel], radii: [1, 1000000]}
drive: {link: pinion, rpm: 1200, direction: cw}
"""
    mech = loads(text)
    ma = mechanical_advantage(mech, solve(mech, "velocity"), "wheel")
    assert not ma.dead_centre
    assert ma.value == pytest.approx(1e6, rel=1e-9)
    assert ma.by_icentres == pytest.approx(1e6, rel=1e-9)


def test_check_passes_a_claim_of_infinity_at_a_dead_centre_and_fails_a_number():
    claims = "  mechanical_advantage.piston: {}\n  mechanical_advantage.B: {}\n"
    passed = check(loads(slider_crank_at("180", claims.format("infinity", "∞"))))
    assert [v.status for v in passed] == ["pass", "pass"], [v.message for v in passed]
    assert passed[0].computed == "infinity" and "∞ (dead centre)" in passed[0].message
    # the finite numbers rounding gave before (4.355e16 by the velocity solution, 1.4e12 by virtual work)
    failed = check(loads(slider_crank_at("180", claims.format("4.4e16", "1.40047e12"))))
    assert [v.status for v in failed] == ["fail", "fail"]
    assert "∞ (dead centre)" in failed[0].message


def test_check_fails_a_claim_of_infinity_where_the_advantage_is_finite():
    (verdict,) = check(loads(slider_crank_at("135", "  mechanical_advantage.piston: infinity\n")))
    assert verdict.status == "fail"
    assert verdict.computed == pytest.approx(7.99258, rel=1e-5) and "not infinity" in verdict.message


def test_properties_prints_infinity_at_a_dead_centre_never_a_number(write, run):
    path = write(slider_crank_at("180"))
    table = run("properties", str(path))
    assert table.exit_code == 0, table.output
    assert "∞ (dead centre)" in table.output
    assert not any(big in table.output for big in ("e+16", "e+12", "e+13", "inf "))
    out = json.loads(run("properties", str(path), "--json").output)
    piston = out["mechanical_advantage"]["piston"]
    assert piston["dead_centre"] is True and piston["value"] is None and piston["velocity_ratio"] == 0.0


def test_properties_of_a_coaxial_internal_gear_pair_gives_the_ratio_without_an_icentre_ratio(write, run):
    # a ring of the pinion's own pitch radius on the same axis: ω_ring/ω_pinion = r1/r2 = 1; I12,
    # I13 and I23 coincide, so the I-centre ratio I12·I23 / I13·I23 is 0/0 (not a number)
    text = """
units: {length: mm, angle: deg}
links: [frame, pinion, ring]
joints:
  O1: {type: revolute, links: [frame, pinion], at: [0, 0]}
  O2: {type: revolute, links: [frame, ring], at: [0, 0]}
  mesh: {type: gear, links: [pinion, ring], teeth: [40, 40], module: 5, internal: true}
drive: {link: pinion, rpm: 1200, direction: cw}
"""
    result = run("properties", str(write(text)), "--json")
    assert result.exit_code == 0, result.output
    ring = json.loads(result.output)["mechanical_advantage"]["ring"]
    assert ring["value"] == pytest.approx(1.0, rel=1e-12)
    assert ring["by_icentres"] is None and "0/0" in ring["construction"]


@pytest.mark.parametrize("ring", ["[planet, frame]", "[frame, planet]"])
def test_a_load_at_a_fixed_rings_pitch_point_does_no_work_by_either_route(ring):
    # the planet's point at the ring's pitch point is its instant centre (it rolls on the fixed
    # ring): a force there does no work, so no input torque holds it — by the velocity solution and
    # by virtual work alike, which differentiates the planet's own point there, not the pitch point
    # (that runs round the ring with the arm: 0.08 m × ω_arm/ω_sun = 0.016 m/rad, 1.6 N·m at 100 N)
    text = epicyclic(ring, extra="loads: {m2: {force: [0, 100]}}\n")
    m = loads(text, path="epicyclic.yaml")
    effort = input_effort(m, solve(m, "velocity"))
    assert effort.value == pytest.approx(0.0, abs=1e-9)
    assert effort.by_virtual_work == pytest.approx(0.0, abs=1e-9)
