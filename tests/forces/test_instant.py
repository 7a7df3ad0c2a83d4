"""Forces at an instant (mech.forces): each value against an independent derivation.

- the slider-crank engine: gas force → thrust in the rod, side thrust on the cylinder wall,
  crank effort and torque, by the textbook's triangle of forces (Khurmi & Gupta, *Theory of
  Machines*, ch. 15, "turning moment": F_Q = F_P / cos φ, F_N = F_P tan φ, T = F_Q r sin(θ + φ));
- the inertia force of the reciprocating parts: −m a_B with a_B the slider's exact
  acceleration (tests/oracles/slider_crank.py), and the textbook's series m ω² r (cos θ +
  cos 2θ / n) to its own truncation error;
- a four-bar with masses on every moving link: every pin force and the input torque against a
  Newton–Euler solve link by link (tests/oracles/newton_euler.py), and the power balance
  T ω = Σ (m a_G · v_G + I α ω) − Σ m g · v_G to 1e-9;
- gravity on a slow lever: the torque that holds a weight is m g times its arm;
- the shaking force is −Σ m a_G.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from tests.mechanism_texts import epicyclic, lift, rack_and_pinion
from tests.oracles.newton_euler import four_bar_forces
from tests.oracles.slider_crank import slider_crank

from mech.forces import analyse
from mech.loader import loads
from mech.options import SolveOptions

ENGINE = """\
units: {{length: mm, angle: deg}}
links: [frame, crank, rod, piston]
joints:
  O: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  A: {{type: revolute, links: [crank, rod]}}
  B: {{type: revolute, links: [rod, piston], near: [600, 0]}}
  P: {{type: prismatic, links: [piston, frame], path: {{through: [0, 0], angle: 0}}}}
lengths: {{OA: 150, AB: 600}}
drive: {{link: crank, angle: {angle}{speed}}}
loads: {{B: {{force: [-2000, 0], on: piston}}}}
{extra}"""


@pytest.mark.parametrize("deg", [25.0, 40.0, 110.0, 200.0, 300.0])
def test_gas_force_gives_the_textbook_rod_thrust_side_thrust_and_crank_torque(deg):
    # Khurmi & Gupta ch. 15: the piston effort F_P = 2000 N toward the crank; the rod at φ with
    # sin φ = sin θ / n (n = l/r = 4) carries F_Q = F_P / cos φ; the wall takes F_N = F_P tan φ;
    # the crank effort F_T = F_Q sin(θ + φ) gives T = F_T r, which the input torque balances.
    m = loads(ENGINE.format(angle=deg, speed="", extra=""), path="engine.yaml")
    fa = analyse(m)
    th = math.radians(deg)
    phi = math.asin(0.15 * math.sin(th) / 0.6)  # the rod's angle below the line of stroke
    f_p = 2000.0
    f_q = f_p / math.cos(phi)
    assert fa.pair("B").magnitude == pytest.approx(f_q, rel=1e-9)
    assert abs(fa.pair("P").normal) == pytest.approx(abs(f_p * math.tan(phi)), rel=1e-9, abs=1e-9 * f_p)
    torque = f_q * math.sin(th + phi) * 0.15  # the gas force turns the crank backwards above the line
    assert fa.effort is not None and fa.effort.value == pytest.approx(
        -torque, rel=1e-9, abs=1e-9 * f_p * 0.15
    )
    assert fa.pair("O").magnitude == pytest.approx(f_q, rel=1e-9)  # a two-force rod: the main bearing too


ENGINE_MASSES = """\
points:
  Gp: {link: piston, from: B, toward: A, distance: 0}
masses:
  piston: {mass: 2.5, centre: B}
"""


@pytest.mark.parametrize("deg", [0.0, 30.0, 90.0, 150.0, 233.0])
def test_inertia_of_the_reciprocating_parts_is_minus_m_a_and_the_textbooks_series(deg):
    text = ENGINE.format(
        angle=deg, speed=", rpm: 1200, direction: ccw", extra="masses: {piston: {mass: 2.5, centre: B}}\n"
    )
    text = text.replace("loads: {B: {force: [-2000, 0], on: piston}}\n", "")
    fa = analyse(loads(text, path="engine.yaml"))
    w = 1200 * 2 * math.pi / 60
    th = math.radians(deg)
    *_, a_b = slider_crank(0.15, 0.6, 0.0, th, w)
    (piston,) = fa.inertia
    assert piston.force[0] == pytest.approx(-2.5 * a_b, rel=1e-9, abs=1e-9 * 2.5 * w * w * 0.15)
    series = 2.5 * w * w * 0.15 * (math.cos(th) + math.cos(2 * th) / 4.0)
    # the series drops (λ³/4)(cos 2θ − cos 4θ) and smaller (λ = r/l = 1/4): 0.6 m ω² r λ³ bounds them
    assert piston.force[0] == pytest.approx(series, abs=0.6 * 2.5 * w * w * 0.15 / 4.0**3)
    # the crank's torque holds the piston's inertia: T ω = m a_B v_B (power), no gravity, no load
    _, _, v_b, _, _ = slider_crank(0.15, 0.6, 0.0, th, w)
    assert fa.effort is not None
    assert fa.effort.value * w == pytest.approx(2.5 * a_b * v_b, abs=1e-9 * 2.5 * (w * w * 0.15) * (w * 0.15))
    assert fa.effort.inertia == pytest.approx(fa.effort.value, rel=1e-12)


FOUR_BAR = """\
units: {{length: mm, angle: deg}}
links: [frame, crank, coupler, rocker]
joints:
  A: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  B: {{type: revolute, links: [crank, coupler]}}
  C: {{type: revolute, links: [coupler, rocker], near: [160, 80]}}
  D: {{type: revolute, links: [rocker, frame], at: [150, 0]}}
lengths: {{AB: 40, BC: 150, CD: 170}}
points:
  G2: {{link: crank, from: A, toward: B, distance: 15}}
  G3: {{link: coupler, from: B, toward: C, distance: 70}}
  G4: {{link: rocker, from: D, toward: C, distance: 90}}
masses:
  crank: {{mass: 0.4, centre: G2, inertia: 0.0002}}
  coupler: {{mass: 1.5, centre: G3, inertia: 0.004}}
  rocker: {{mass: 1.8, centre: G4, radius_of_gyration: 60}}
gravity: [0, -9.81]
drive: {{link: crank, angle: {angle}, rpm: 300, direction: ccw}}
"""
MASSES = {
    "crank": (0.4, 0.0002, 0.015),
    "coupler": (1.5, 0.004, 0.070),
    "rocker": (1.8, 1.8 * 0.06**2, 0.090),
}


@pytest.mark.parametrize("deg", [10.0, 60.0, 135.0, 250.0, 320.0])
def test_four_bar_with_masses_matches_newton_euler_link_by_link(deg):
    fa = analyse(loads(FOUR_BAR.format(angle=deg), path="fourbar.yaml"))
    w = 300 * 2 * math.pi / 60
    ne = four_bar_forces((0.040, 0.150, 0.170, 0.150), math.radians(deg), w, MASSES, (0.0, -9.81))
    scale = max(float(np.linalg.norm(ne[k])) for k in "ABCD")
    assert fa.determinate
    assert np.allclose(fa.pair("A").force, ne["A"], rtol=0, atol=1e-9 * scale)  # on the crank from the frame
    assert np.allclose(fa.pair("B").force, ne["B"], rtol=0, atol=1e-9 * scale)  # on the coupler
    assert np.allclose(fa.pair("C").force, ne["C"], rtol=0, atol=1e-9 * scale)  # on the rocker
    assert np.allclose(
        fa.pair("D").force, -ne["D"], rtol=0, atol=1e-9 * scale
    )  # on the frame from the rocker
    assert fa.effort is not None
    assert fa.effort.value == pytest.approx(ne["T"], abs=1e-9 * scale * 0.17)


@pytest.mark.parametrize("deg", [10.0, 135.0, 320.0])
def test_four_bar_power_balances(deg):
    # input power = the rate of change of kinetic energy + the rate of work against gravity
    from mech.kinematics import solve

    text = FOUR_BAR.format(angle=deg)
    m = loads(text, path="fourbar.yaml")
    fa = analyse(m)
    kin = solve(m, "acceleration")
    w = kin.links["crank"].omega
    power = 0.0
    for ms in m.masses:
        v, a = kin.velocity(ms.centre, ms.link), kin.acceleration(ms.centre, ms.link)
        lk = kin.links[ms.link]
        power += ms.mass * (a[0] * v[0] + a[1] * v[1]) + ms.inertia * lk.alpha * lk.omega
        power -= ms.mass * (0.0 * v[0] - 9.81 * v[1])
    assert fa.effort is not None
    assert fa.effort.value * w == pytest.approx(power, rel=1e-9)
    assert fa.effort.loads == 0.0
    assert fa.effort.value == pytest.approx(fa.effort.inertia + fa.effort.gravity, rel=1e-12)


def test_the_shaking_force_is_minus_the_sum_of_m_a_g():
    from mech.kinematics import solve

    m = loads(FOUR_BAR.format(angle=60), path="fourbar.yaml")
    fa = analyse(m)
    kin = solve(m, "acceleration")
    fx = -sum(ms.mass * kin.acceleration(ms.centre, ms.link)[0] for ms in m.masses)
    fy = -sum(ms.mass * kin.acceleration(ms.centre, ms.link)[1] for ms in m.masses)
    assert fa.shaking_force == pytest.approx((fx, fy), rel=1e-12)
    # and about the crank's pivot A = (0, 0): −Σ (r_G × m a_G + I_G α)
    mz = 0.0
    for ms in m.masses:
        (gx, gy), (ax, ay) = kin.positions[ms.centre], kin.acceleration(ms.centre, ms.link)
        mz -= gx * ms.mass * ay - gy * ms.mass * ax + ms.inertia * kin.links[ms.link].alpha
    assert fa.shaking_moment == pytest.approx(mz, rel=1e-12)


@pytest.mark.parametrize("deg", [20.0, 75.0, 140.0])
def test_gravity_alone_on_a_slow_lift_needs_the_torque_of_virtual_work(deg):
    # no speed: a static problem.  The platform B rides the vertical through O on a crank OA
    # (r = 100 mm) and a rod AB (l = 250 mm): y_B = r sin θ + √(l² − r² cos² θ); the crank's own
    # 3 kg act at r/2.  Virtual work: T = g (m_p dy_B/dθ + m_c (r/2) cos θ).
    fa = analyse(loads(lift(deg), path="lift.yaml"))
    r, rod, th, g = 0.1, 0.25, math.radians(deg), 9.81
    dy_b = r * math.cos(th) + r * r * math.sin(th) * math.cos(th) / math.sqrt(
        rod**2 - (r * math.cos(th)) ** 2
    )
    want = g * (20 * dy_b + 3 * (r / 2) * math.cos(th))
    assert fa.effort is not None
    assert fa.effort.value == pytest.approx(want, rel=1e-9)
    assert fa.effort.inertia == 0.0 and fa.effort.gravity == pytest.approx(fa.effort.value)
    # the guide carries the rod's side thrust only: the weight is along the path
    assert fa.pair("S").force[1] == pytest.approx(0.0, abs=1e-9 * 20 * g)


def test_a_redundant_chain_gives_its_input_torque_and_says_the_pin_forces_are_indeterminate():
    from tests.mechanism_texts import EXAMPLES

    text = (EXAMPLES / "double_parallelogram.yaml").read_text()
    text = text[: text.index("\nanswers:")] + "\nloads: {coupler: {torque: 5}}\n"
    fa = analyse(loads(text, path="dp.yaml"), SolveOptions(angle=math.radians(50)))
    assert not fa.determinate and fa.pairs == () and "indeterminate" in fa.note
    # a torque on the translating coupler does no work: nothing holds it but the pins
    assert fa.effort is not None and fa.effort.value == pytest.approx(0.0, abs=1e-9)


def test_gears_push_along_their_line_of_action_and_the_bearings_take_the_tooth_load():
    # 20 and 40 teeth, module 5 mm: pitch radii 50 and 100 mm, pressure angle 20°.  A torque of
    # 10 N·m on the wheel is held by a tooth load F = T / (r₂ cos φ) = 106.42 N along the line of
    # action, which each bearing takes back; the pinion's torque is T r₁ / r₂ = 5 N·m.
    from tests.mechanism_texts import EXAMPLES

    text = (EXAMPLES / "gear_pair.yaml").read_text()
    text = text[: text.index("\nanswers:")] if "\nanswers:" in text else text
    fa = analyse(loads(text + "\nloads: {wheel: {torque: 10}}\n", path="gears.yaml"))
    tooth = 10 / (0.100 * math.cos(math.radians(20)))
    mesh = fa.pair("mesh")
    assert mesh.magnitude == pytest.approx(tooth, rel=1e-9)
    assert abs(mesh.normal) == pytest.approx(tooth, rel=1e-9)
    assert fa.pair("O1").magnitude == pytest.approx(tooth, rel=1e-9)
    assert fa.pair("O2").magnitude == pytest.approx(tooth, rel=1e-9)
    assert fa.effort is not None and abs(fa.effort.value) == pytest.approx(5.0, rel=1e-9)


def test_a_programme_cam_pushes_its_follower_along_the_common_normal_and_the_guide_takes_the_thrust():
    # cam_roller_program.yaml at its drive angle, 60° into a simple-harmonic rise of h = 30 mm over
    # β = 120°, base circle 40 mm, roller 10 mm, in line: s = h/2 (1 − cos πθ/β) = 15 mm and
    # ds/dθ = (π h / 2β) sin(πθ/β) = 22.5 mm/rad.  The pressure angle of an in-line roller follower
    # is tan φ = (ds/dθ) / (r_b + r_r + s) = 22.5 / 65.  Holding 100 N down on the follower: the cam
    # pushes along the normal with 100 / cos φ, the guide takes 100 tan φ sideways, the camshaft's
    # bearing takes the push back, and the torque is 100 N × ds/dθ = 2.25 N·m (virtual work).
    from tests.mechanism_texts import EXAMPLES

    text = (EXAMPLES / "cam_roller_program.yaml").read_text().split("\nanswers:")[0]
    fa = analyse(loads(text + '\nloads: {K: {force: [0, -100], "on": follower}}\n', path="cam.yaml"))
    tan_phi = 22.5 / 65
    push = 100 * math.hypot(1, tan_phi)
    contact = fa.pair("K")
    assert contact.magnitude == pytest.approx(push, rel=1e-9)
    assert abs(contact.normal) == pytest.approx(push, rel=1e-9)  # all of it along the normal
    assert fa.pair("S").magnitude == pytest.approx(100 * tan_phi, rel=1e-9)
    assert fa.pair("O").magnitude == pytest.approx(push, rel=1e-9)
    assert fa.effort is not None and abs(fa.effort.value) == pytest.approx(2.25, rel=1e-9)


def test_a_load_at_a_cam_joint_acts_on_its_followers_own_point():
    # DESIGN § 1.2: a cam joint's name is the follower's own point, here the roller's centre C.
    # eccentric_cam_roller.yaml: a circle of 40 mm about E, e = |OE| = 15 mm at 30°, an in-line
    # roller of 10 mm on a vertical slide through O: y_C = e sin θ + √((R + r)² − e² cos² θ), so
    # dy_C/dθ = e cos θ + e² sin θ cos θ / √((R + r)² − e² cos² θ) = 15.0082 mm/rad at 30°, and
    # 100 N held down at C needs T = 100 N × dy_C/dθ (virtual work).
    from tests.mechanism_texts import EXAMPLES

    text = (EXAMPLES / "eccentric_cam_roller.yaml").read_text().split("\nanswers:")[0]
    fa = analyse(loads(text + "\nloads: {K: {force: [0, -100]}}\n", path="cam.yaml"))
    e, reach, th = 0.015, 0.050, math.radians(30)
    root = math.sqrt(reach**2 - (e * math.cos(th)) ** 2)
    dy = e * math.cos(th) + e**2 * math.sin(th) * math.cos(th) / root
    assert fa.effort is not None and fa.effort.value == pytest.approx(100 * dy, rel=1e-9)
    assert not [n for n in fa.notes if "does not say which it acts on" in n]
    # on the follower, the load and the guide hold the cam's push: the contact carries the 100 N
    assert fa.pair("K").normal is not None and abs(fa.pair("K").normal) >= 100 * (1 - 1e-9)


def test_an_epicyclic_train_shares_its_arms_torque_between_its_two_meshes():
    # sun 20, planet 30, fixed ring 80 mm (no pressure angle), the sun and the arm on two pins at
    # one axis, 10 N·m cw held on the arm.  The planet is pushed alike by sun and ring (moments about
    # its centre: F_s r_p = F_r r_p), the arm's pin takes both: 2F (r_s + r_p) = 10 N·m, F = 100 N,
    # the arm's pivot 200 N; the sun needs F r_s = 2 N·m, which is the power balance's
    # T_s ω_s = T_a ω_a with ω_a/ω_s = r_s/(r_s + r_r) = 1/5
    text = epicyclic(extra="loads: {arm: {torque: -10}}\n")
    fa = analyse(loads(text, path="epicyclic.yaml"))
    assert fa.pair("m1").magnitude == pytest.approx(100, rel=1e-9)
    assert fa.pair("m2").magnitude == pytest.approx(100, rel=1e-9)
    assert fa.pair("Q").magnitude == pytest.approx(200, rel=1e-9)
    assert fa.pair("O2").magnitude == pytest.approx(200, rel=1e-9)
    assert fa.pair("O").magnitude == pytest.approx(100, rel=1e-9)
    assert fa.effort is not None and fa.effort.value == pytest.approx(2.0, rel=1e-9)


@pytest.mark.parametrize(
    "pitch",
    [
        "radii: [50, null]",  # the shorthand: a pitch circle on a pitch line
        "profiles: {pinion: {circle: {centre: O, radius: 50}}, rack: {line: {through: R, angle: 0}}}",
    ],
)
def test_a_rack_and_pinion_push_along_the_line_of_action(pitch):
    # 1000 N held on the rack along its pitch line, pinion of pitch radius 50 mm, φ = 20°: the
    # teeth push along the line of action with 1000 / cos φ, the rack's guide takes 1000 tan φ
    # (the radial part), the pinion's bearing the whole tooth load, and T = 1000 N × 0.05 m
    fa = analyse(loads(rack_and_pinion(pitch), path="rack.yaml"))
    phi = math.radians(20)
    assert fa.pair("mesh").magnitude == pytest.approx(1000 / math.cos(phi), rel=1e-9)
    assert fa.pair("mesh").normal == pytest.approx(1000 / math.cos(phi), rel=1e-9)
    assert fa.pair("S").magnitude == pytest.approx(1000 * math.tan(phi), rel=1e-9)
    assert fa.pair("O").magnitude == pytest.approx(1000 / math.cos(phi), rel=1e-9)
    assert fa.effort is not None and fa.effort.value == pytest.approx(50.0, rel=1e-9)


@pytest.mark.parametrize("torque", [10.0, -10.0])
def test_gear_teeth_push_apart_whichever_way_the_load_turns(torque):
    # gear_pair.yaml: wheel of pitch radius 100 mm at +x of the pinion, φ = 20°.  The tooth load on
    # the wheel has a tangential part |T|/r = 100 N, its sign the load's, and a radial part
    # 100 tan φ = 36.40 N that always pushes the wheel away from the pinion (+x): teeth only push,
    # so a reversed load meets the other flanks and the mirror line of action
    from tests.mechanism_texts import EXAMPLES

    text = (EXAMPLES / "gear_pair.yaml").read_text().split("\nanswers:")[0]
    fa = analyse(loads(text + f"\nloads: {{wheel: {{torque: {torque}}}}}\n", path="gears.yaml"))
    fx, fy = fa.pair("mesh").force
    assert fx == pytest.approx(100 * math.tan(math.radians(20)), rel=1e-9)
    assert abs(fy) == pytest.approx(100, rel=1e-9)
    assert fa.pair("O2").force == pytest.approx((-fx, -fy), rel=1e-9)


@pytest.mark.parametrize("load", [-1000, 1000])
def test_a_racks_teeth_push_it_away_from_its_pinion_whichever_way_it_is_loaded(load):
    # the rack under its pinion: the radial part of the tooth load, 1000 tan 20° = 363.97 N, pushes
    # it down (−y) whether the load along the pitch line is +x or −x
    text = rack_and_pinion().replace("force: [-1000, 0]", f"force: [{load}, 0]")
    fa = analyse(loads(text, path="rack.yaml"))
    fx, fy = fa.pair("mesh").force
    assert fy == pytest.approx(-1000 * math.tan(math.radians(20)), rel=1e-9)
    assert fx == pytest.approx(-load, rel=1e-9)


@pytest.mark.parametrize("ring", ["[planet, frame]", "[frame, planet]"])
def test_a_load_at_a_fixed_rings_pitch_point_goes_straight_into_the_ring(ring):
    # 100 N at the ring's pitch point acts on the planet (the moving link of the pair, whichever
    # order the file gives), where the planet touches the fixed ring: the ring takes it all, and
    # nothing else carries anything (the point is the planet's instant centre: no torque)
    text = epicyclic(ring, extra="loads: {m2: {force: [0, 100]}}\n")
    fa = analyse(loads(text, path="epicyclic.yaml"))
    assert fa.pair("m2").magnitude == pytest.approx(100, rel=1e-9)
    for pin in ("O", "O2", "Q", "m1"):
        assert fa.pair(pin).magnitude == pytest.approx(0.0, abs=1e-9)
    assert fa.effort is not None and fa.effort.value == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize(
    ("alpha", "side", "through"),
    [(0.0, -1, 1), (0.0, 1, 1), (30.0, -1, 1), (-50.0, 1, 1), (30.0, -1, 0), (90.0, -1, 0)],
)
def test_a_rack_given_by_radii_lies_along_its_slide_on_its_side_of_the_pinion(alpha, side, through):
    # radii: [50, null] with no contact drawn: the pitch line runs along the rack's slide (at α),
    # tangent to the pinion's pitch circle on the slide's side.  1000 N along the slide on the
    # rack: tooth load 1000/cos 20°, radial part 1000 tan 20° pushing the rack away from the
    # pinion (along side·n, n the slide's normal), torque 1000 N × 0.05 m, rack speed ω r = 0.1π.
    # A slide drawn through the pinion's centre (``through`` 0) puts the rack on its right-hand side
    a = math.radians(alpha)
    u, n = (math.cos(a), math.sin(a)), (-math.sin(a), math.cos(a))
    c = (through * side * 50 * n[0], through * side * 50 * n[1])
    text = f"""\
units: {{length: mm, angle: deg}}
links: [frame, pinion, rack]
joints:
  O: {{type: revolute, links: [frame, pinion], at: [0, 0]}}
  S: {{type: prismatic, links: [rack, frame], path: {{through: [{c[0]!r}, {c[1]!r}], angle: {alpha!r}}}, point: R}}
  mesh: {{type: gear, links: [pinion, rack], radii: [50, null], pressure_angle: 20}}
points:
  R: {{link: rack, at: [{c[0]!r}, {c[1]!r}]}}
loads:
  R: {{force: [{-1000 * u[0]!r}, {-1000 * u[1]!r}]}}
drive: {{link: pinion, rpm: 60, direction: ccw}}
"""
    fa = analyse(loads(text, path="rack.yaml"))
    phi = math.radians(20)
    fx, fy = fa.pair("mesh").force
    assert math.hypot(fx, fy) == pytest.approx(1000 / math.cos(phi), rel=1e-9)
    assert side * (fx * n[0] + fy * n[1]) == pytest.approx(1000 * math.tan(phi), rel=1e-9)
    assert fa.pair("S").magnitude == pytest.approx(1000 * math.tan(phi), rel=1e-9)
    assert fa.effort is not None and abs(fa.effort.value) == pytest.approx(50.0, rel=1e-9)
    assert abs(fa.kinematics.sliding("S")) == pytest.approx(0.05 * 2 * math.pi, rel=1e-9)


def test_a_rack_with_a_pin_on_it_is_still_a_rack():
    # the rack drives a rod by a pin T: T is no gear centre, the teeth still push along the line of
    # action (radial part 1000 tan 20° = 363.97 N, down, away from the pinion above it); the rod
    # (T (100, −50) → U (200, −80) mm) pulls the rack with (−1000, 300) N, the guide takes the rest
    text = rack_and_pinion().replace(
        "links: [frame, pinion, rack]", "links: [frame, pinion, rack, rod, block]"
    )
    text = text.replace(
        "points:",
        "  T: {type: revolute, links: [rack, rod], at: [100, -50]}\n"
        "  U: {type: revolute, links: [rod, block], at: [200, -80]}\n"
        "  P2: {type: prismatic, links: [block, frame], path: {through: [0, -80], angle: 0}}\npoints:",
    ).replace("  R: {force: [-1000, 0]}", "  U: {force: [-1000, 0], on: block}")
    fa = analyse(loads(text, path="rack.yaml"))
    fx, fy = fa.pair("mesh").force
    assert fx == pytest.approx(1000, rel=1e-9)
    assert fy == pytest.approx(-1000 * math.tan(math.radians(20)), rel=1e-9)
    # the rack: mesh (1000, −363.97) + rod (−1000, 300) + guide = 0; on the frame, the guide's opposite
    assert fa.pair("S").force[1] == pytest.approx(300 - 1000 * math.tan(math.radians(20)), rel=1e-9)


def test_a_flat_faced_follower_s_guide_takes_a_couple_and_no_normal_force():
    # a flat face square to its stroke touches the cam ds/dθ from its axis (here 60° into a 20 mm
    # simple-harmonic rise over 120°: ds/dθ = π h / 2β = 15 mm/rad): 100 N held down on the axis
    # meets the cam's 100 N up, 15 mm off it, so the guide takes the couple 100 × 0.015 = 1.5 N·m
    # and no side force, and the cam needs 100 N × 15 mm/rad = 1.5 N·m
    text = """\
units: {length: mm, angle: deg}
links: [frame, cam, follower]
joints:
  O: {type: revolute, links: [frame, cam], at: [0, 0]}
  S: {type: prismatic, links: [follower, frame], path: {through: [0, 0], angle: 90}}
  K: {type: cam, links: [cam, follower],
      program: {base_radius: 25, follower: flat,
                segments: [{rise: 20, over: 120, law: shm}, {dwell: 30},
                           {return: 20, over: 120, law: shm}, {dwell: 90}]}}
drive: {link: cam, angle: 60, rpm: 100, direction: cw}
loads: {K: {force: [0, -100], "on": follower}}
"""
    fa = analyse(loads(text, path="flat.yaml"))
    guide = fa.pair("S")
    assert guide.force == (0.0, 0.0) and guide.offset is None
    assert abs(guide.couple) == pytest.approx(1.5, rel=1e-9)
    assert fa.pair("K").force[1] == pytest.approx(100, rel=1e-9)
    assert fa.effort is not None and abs(fa.effort.value) == pytest.approx(1.5, rel=1e-9)


OSCILLATING_CAM = """\
units: {{length: mm, angle: deg}}
links: [frame, cam, arm]
joints:
  O: {{type: revolute, links: [frame, cam], at: [0, 0]}}
  P: {{type: revolute, links: [arm, frame], at: [100, 0]}}
  K: {{type: cam, links: [cam, arm], near: [30, 30],
      program: {{base_radius: 30, follower: roller, roller_radius: 10,
                segments: [{{rise: 20, over: 90, law: cycloidal}}, {{dwell: 60}},
                           {{return: 20, over: 120, law: shm}}, {{dwell: 90}}]}}}}
lengths: {{PK: 80}}
drive: {{link: cam, angle: 45, rpm: 200, direction: ccw}}
loads: {{arm: {{torque: {torque}}}}}
"""


def test_a_cam_that_would_have_to_pull_its_follower_says_so():
    # a couple on the arm one way presses the roller on the cam, the other way lifts it off: the
    # cam cannot pull, so the second is said, with the force the cam would need
    pressed = analyse(loads(OSCILLATING_CAM.format(torque=5), path="cam.yaml"))
    lifted = analyse(loads(OSCILLATING_CAM.format(torque=-5), path="cam.yaml"))
    assert not [n for n in pressed.notes if "only pushes" in n]
    (note,) = [n for n in lifted.notes if "only pushes" in n]
    assert f"{lifted.pair('K').magnitude:.6g} N" in note and "arm leaves cam" in note


def test_a_load_at_a_pitch_point_between_two_moving_gears_asks_which_it_acts_on():
    # the pitch point is a point of the pinion and of the rack alike: the input torque is the same
    # either way, but the force the mesh carries is not (1064 N with the load on the rack, 0 on the
    # pinion), so without `on` it is said, as at a pin of two moving links
    text = rack_and_pinion().replace("  R: {force: [-1000, 0]}", "  mesh: {force: [-1000, 0]}")
    fa = analyse(loads(text, path="rack.yaml"))
    (note,) = [n for n in fa.notes if "does not say which it acts on" in n]
    assert "on: pinion or on: rack" in note
    assert fa.effort is not None and abs(fa.effort.value) == pytest.approx(50.0, rel=1e-9)
