"""Higher pairs that move: profiles in contact, checked over whole sweeps against closed forms.

Each reference is derived independently of the solver:

* eccentric circular cam (eccentricity e, radius R) with a flat-faced translating follower whose
  face is normal to its line of stroke through the cam pivot: the face stays R above the
  eccentric's centre, so s = e·sin θ + R exactly, v = eω cos θ, a = −eω² sin θ;
* the same cam with an in-line roller follower of radius r: the roller centre stays R + r from
  the eccentric's centre — a slider crank of crank e and rod R + r (Norton, *Design of
  Machinery*, § 4.6): s = e sin θ + √((R + r)² − e² cos² θ), v, a by differentiating;
* a wheel of radius r rolling without slip on straight ground, its centre driven along the
  ground by a slider crank: ω_wheel = −v_B / r, α_wheel = −a_B / r, and the wheel's point at the
  contact has zero velocity and acceleration ω² r towards the centre;
* a gear pair on fixed axes at constant speed: ω₂/ω₁ = −r₁/r₂, α = 0, and the pitch point's
  acceleration on each gear is centripetal, ω_i² r_i towards its own centre.
"""

from __future__ import annotations

import math
import textwrap

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mech.errors import InputError
from mech.kinematics import solve
from mech.kinematics.sweep import sweep
from mech.loader import loads

E, R, RR = 0.015, 0.040, 0.010  # eccentricity, cam radius, roller radius (m)
W = 31.41592653589793  # 300 rpm ccw


def _cam(follower: str, point: str, drawn_y: float) -> str:
    return textwrap.dedent(
        f"""
        name: eccentric cam
        units: {{length: mm, angle: deg}}
        links: [frame, cam, follower]
        joints:
          O: {{type: revolute, links: [frame, cam], at: [0, 0]}}
          S: {{type: prismatic, links: [follower, frame], path: {{through: [0, 0], angle: 90}}, point: {point}}}
          K: {{type: cam, links: [cam, follower],
              profiles: {{cam: {{circle: {{centre: E, radius: 40}}}}, follower: {follower}}}}}
        points:
          E: {{link: cam, at: [{15 * math.cos(math.radians(30))!r}, 7.5]}}
          {point}: {{link: follower, at: [0, {drawn_y!r}]}}
        drive: {{link: cam, angle: 30, rpm: 300, direction: ccw}}
        """
    )


def _slider_crank(a: float, rod: float, th: np.ndarray, w: float) -> tuple[np.ndarray, ...]:
    """Vertical in-line slider crank: crank a at angle θ from +x, rod ``rod``; s, ṡ, s̈ (ω constant)."""
    h = np.sqrt(rod**2 - (a * np.cos(th)) ** 2)
    s = a * np.sin(th) + h
    ds = a * np.cos(th) + a**2 * np.cos(th) * np.sin(th) / h
    d2s = -a * np.sin(th) + a**2 * np.cos(2 * th) / h - a**4 * (np.cos(th) * np.sin(th)) ** 2 / h**3
    return s, ds * w, d2s * w**2


ANGLES = np.radians(np.arange(0.0, 360.0, 7.5))


def test_flat_faced_follower_on_an_eccentric_cam_lifts_e_sin_theta_over_the_turn():
    mech = loads(_cam("{line: {through: F, angle: 0}}", "F", 47.5), path="cam.yaml")
    sw = sweep(mech, ANGLES, level="acceleration", analyse=False)
    assert sw.assembled.all()
    k = sw.points.index("F")
    y = sw.positions[:, k, 1]
    assert y - R == pytest.approx(E * np.sin(ANGLES), abs=1e-12)
    assert sw.velocities[:, k, 1] == pytest.approx(E * W * np.cos(ANGLES), abs=1e-10)
    assert sw.accelerations[:, k, 1] == pytest.approx(-E * W**2 * np.sin(ANGLES), abs=1e-8)
    assert np.abs(sw.positions[:, k, 0]).max() < 1e-15


def test_roller_follower_on_an_eccentric_cam_is_a_slider_crank_of_crank_e_and_rod_r_plus_roller():
    y0 = 7.5 + math.sqrt(50.0**2 - (15 * math.cos(math.radians(30))) ** 2)
    mech = loads(_cam("{circle: {centre: C, radius: 10}}", "C", y0), path="cam.yaml")
    sw = sweep(mech, ANGLES, level="acceleration", analyse=False)
    s, v, a = _slider_crank(E, R + RR, ANGLES, W)
    k = sw.points.index("C")
    assert sw.positions[:, k, 1] == pytest.approx(s, abs=1e-12)
    assert sw.velocities[:, k, 1] == pytest.approx(v, abs=1e-10)
    assert sw.accelerations[:, k, 1] == pytest.approx(a, abs=1e-8)


def test_contact_point_lies_on_both_profiles_where_the_cam_is_drawn():
    mech = loads(_cam("{line: {through: F, angle: 0}}", "F", 47.5), path="cam.yaml")
    kin = solve(mech, "acceleration")
    ex, ey = kin.positions["E"]
    kx, ky = kin.position("K@cam")  # DESIGN § 1.2: K is the face's point on the axis, K@cam the contact
    assert (kx, ky) == pytest.approx((ex, ey + R), abs=1e-15)  # under the face, above the centre
    assert kin.position("K") == pytest.approx((0.0, ey + R), abs=1e-15)
    # the follower's point at K moves with the follower; the cam's with the cam (ω × r)
    vx, vy = kin.velocity("K@cam")
    assert (vx, vy) == pytest.approx((-W * ky, W * kx), rel=1e-12)


def test_profiles_drawn_apart_are_a_located_error_with_the_gap():
    with pytest.raises(InputError) as err:
        solve(loads(_cam("{line: {through: F, angle: 0}}", "F", 48.5), path="cam.yaml"), "velocity")
    text = str(err.value)
    assert "cam.yaml:8:" in text and "1 mm apart" in text


WHEEL = textwrap.dedent(
    """
    name: rolling wheel
    units: {length: mm, angle: deg}
    links: [frame, crank, rod, wheel]
    joints:
      O: {type: revolute, links: [frame, crank], at: [0, 30]}
      A: {type: revolute, links: [crank, rod]}
      B: {type: revolute, links: [rod, wheel], at: [88.10249675906654, 30]}
      W: {type: rolling, links: [wheel, frame], radii: [30, null]}
    lengths: {OA: 20, AB: 80}
    drive: {link: crank, angle: 60, rpm: 120, direction: ccw}
    """
)


def test_wheel_rolling_on_the_ground_turns_by_its_centre_travel_over_radius():
    sw = sweep(loads(WHEEL, path="wheel.yaml"), ANGLES, level="acceleration", analyse=False)
    w = 4 * math.pi
    # horizontal slider crank: x_B = a cos θ + √(L² − a² sin² θ), with a = 20 mm, L = 80 mm
    a, rod = 0.020, 0.080
    h = np.sqrt(rod**2 - (a * np.sin(ANGLES)) ** 2)
    x = a * np.cos(ANGLES) + h
    dx = (-a * np.sin(ANGLES) - a**2 * np.sin(ANGLES) * np.cos(ANGLES) / h) * w
    d2x = (
        -a * np.cos(ANGLES)
        - a**2 * np.cos(2 * ANGLES) / h
        - a**4 * (np.sin(ANGLES) * np.cos(ANGLES)) ** 2 / h**3
    ) * w**2
    kb, lw = sw.points.index("B"), sw.links.index("wheel")
    assert sw.positions[:, kb, 0] == pytest.approx(x, abs=1e-12)
    assert sw.omegas[:, lw] == pytest.approx(-dx / 0.030, abs=1e-9)
    assert sw.alphas[:, lw] == pytest.approx(-d2x / 0.030, abs=1e-6)
    # the arc rolled is the distance travelled
    turned = sw.link_angles[:, lw] - sw.link_angles[0, lw]
    assert turned == pytest.approx(-(x - x[0]) / 0.030, abs=1e-10)


def test_rolling_wheel_contact_point_has_zero_velocity_and_centripetal_acceleration():
    kin = solve(loads(WHEEL, path="wheel.yaml"), "acceleration")
    omega = kin.links["wheel"].omega
    assert kin.velocity("W") == pytest.approx((0.0, 0.0), abs=1e-14)
    ax, ay = kin.acceleration("W", link="wheel")
    assert (ax, ay) == pytest.approx((0.0, omega**2 * 0.030), rel=1e-12)
    assert kin.acceleration("W", link="frame") == (0.0, 0.0)


GEARS = textwrap.dedent(
    """
    units: {length: mm, angle: deg}
    links: [frame, pinion, wheel]
    joints:
      O1: {type: revolute, links: [frame, pinion], at: [0, 0]}
      O2: {type: revolute, links: [frame, wheel], at: [150, 0]}
      mesh: {type: gear, links: [pinion, wheel], teeth: [20, 40], module: 5}
    drive: {link: pinion, angle: 0, rpm: 1200, direction: cw}
    """
)


def test_gear_pair_at_constant_speed_keeps_its_ratio_and_centripetal_pitch_accelerations():
    mech = loads(GEARS, path="gears.yaml")
    w1 = -1200 * 2 * math.pi / 60
    sw = sweep(mech, ANGLES, level="acceleration", analyse=False)
    lw = sw.links.index("wheel")
    assert sw.omegas[:, lw] == pytest.approx(np.full(ANGLES.size, -w1 * 50 / 100), rel=1e-12)
    assert np.abs(sw.alphas).max() < 1e-9 * w1**2
    for deg in (0.0, 77.0, 200.0):
        kin = solve(mech, "acceleration", _at(deg))
        assert kin.acceleration("mesh", link="pinion") == pytest.approx((-(w1**2) * 0.050, 0.0), rel=1e-12)
        assert kin.acceleration("mesh", link="wheel") == pytest.approx(
            ((w1 / 2) ** 2 * 0.100, 0.0), rel=1e-12
        )


def _at(deg: float):
    from mech.options import SolveOptions

    return SolveOptions(angle=math.radians(deg))


def _circle_as_curve(n: int) -> str:
    """The eccentric's circle (centre E as drawn, radius 40 mm) given as n points of a closed curve."""
    ex, ey = 15 * math.cos(math.radians(30)), 7.5
    return ", ".join(
        f"[{ex + 40 * math.cos(2 * math.pi * k / n)!r}, {ey + 40 * math.sin(2 * math.pi * k / n)!r}]"
        for k in range(n)
    )


@pytest.mark.parametrize("n", [90, 360])
def test_curve_profile_through_a_circles_points_moves_a_flat_follower_like_the_circle(n):
    # The periodic cubic spline through n points of a circle is within O(h⁴) of it in position
    # and O(h²) in curvature (h = 2π/n; de Boor, ch. IV): s = e sin θ + R within those orders.
    doc = _cam("{line: {through: F, angle: 0}}", "F", 47.5).replace(
        "cam: {circle: {centre: E, radius: 40}}", "cam: {curve: [" + _circle_as_curve(n) + "]}"
    )
    sw = sweep(loads(doc, path="cam.yaml"), ANGLES, level="acceleration", analyse=False)
    h = 2 * math.pi / n
    k = sw.points.index("F")
    assert sw.positions[:, k, 1] - R == pytest.approx(E * np.sin(ANGLES), abs=E * h**4)
    assert sw.velocities[:, k, 1] == pytest.approx(E * W * np.cos(ANGLES), abs=E * W * h**3)
    assert sw.accelerations[:, k, 1] == pytest.approx(-E * W**2 * np.sin(ANGLES), abs=E * W**2 * h**2)


def test_curve_profile_against_a_roller_is_the_slider_crank_within_the_splines_accuracy():
    n = 360
    y0 = 7.5 + math.sqrt(50.0**2 - (15 * math.cos(math.radians(30))) ** 2)
    doc = _cam("{circle: {centre: C, radius: 10}}", "C", y0).replace(
        "cam: {circle: {centre: E, radius: 40}}", "cam: {curve: [" + _circle_as_curve(n) + "]}"
    )
    sw = sweep(loads(doc, path="cam.yaml"), ANGLES, level="acceleration", analyse=False)
    s, v, a = _slider_crank(E, R + RR, ANGLES, W)
    h = 2 * math.pi / n
    k = sw.points.index("C")
    assert sw.positions[:, k, 1] == pytest.approx(s, abs=E * h**4)
    assert sw.velocities[:, k, 1] == pytest.approx(v, abs=E * W * h**3)
    assert sw.accelerations[:, k, 1] == pytest.approx(a, abs=E * W**2 * h**2)


RACK = textwrap.dedent(
    """
    units: {length: mm, angle: deg}
    links: [frame, pinion, rack]
    joints:
      O: {type: revolute, links: [frame, pinion], at: [0, 0]}
      S: {type: prismatic, links: [rack, frame], path: {through: [0, -50], angle: 0}, point: P}
      G: {type: gear, links: [pinion, rack],
          profiles: {pinion: {circle: {centre: O, radius: 50}}, rack: {line: {through: P, angle: 0}}}}
    points:
      P: {link: rack, at: [0, -50]}
    drive: {link: pinion, angle: 0, rpm: 600, direction: ccw}
    """
)


def test_rack_and_pinion_rack_travels_the_pitch_arc_at_constant_speed():
    # The pitch line rolls on the pitch circle: x_rack = r θ, v = r ω, a = 0 at constant ω.
    sw = sweep(loads(RACK, path="rack.yaml"), ANGLES, level="acceleration", analyse=False)
    k = sw.points.index("P")
    w = 600 * 2 * math.pi / 60
    assert sw.positions[:, k, 0] == pytest.approx(0.050 * ANGLES, abs=1e-12)
    assert sw.velocities[:, k, 0] == pytest.approx(np.full(ANGLES.size, 0.050 * w), rel=1e-12)
    assert np.abs(sw.accelerations[:, k, :]).max() < 1e-9 * 0.050 * w**2


def test_a_contact_point_drawn_away_from_where_the_profiles_touch_is_refused():
    x_k = 15 * math.cos(math.radians(30))  # mm: the face touches the disc above its centre
    doc = _cam("{line: {through: F, angle: 0}}", "F", 47.5).replace(
        "K: {type: cam, links: [cam, follower],",
        f"K: {{type: cam, links: [cam, follower], at: [{x_k + 1!r}, 47.5],",
    )
    with pytest.raises(InputError, match="1 mm from where its profiles touch"):
        solve(loads(doc, path="cam.yaml"), "velocity")
    good = doc.replace(f"at: [{x_k + 1!r}, 47.5]", f"at: [{x_k!r}, 47.5]")
    assert solve(loads(good, path="cam.yaml"), "velocity").position("K@cam")[0] == pytest.approx(
        0.015 * math.cos(math.radians(30))
    )


@settings(max_examples=30, deadline=None)
@given(
    e=st.floats(2.0, 30.0),
    extra=st.floats(5.0, 60.0),
    r=st.floats(2.0, 25.0),
    deg=st.integers(0, 3590).map(lambda k: k / 10),  # tenths of a degree (mech refuses 1e-38 rad)
    rpm=st.floats(10.0, 3000.0),
)
def test_roller_on_any_eccentric_cam_follows_its_equivalent_slider_crank(e, extra, r, deg, rpm):
    # Law: circle on circle keeps the centres R + r apart, so the roller centre is the piston of
    # the in-line slider crank (crank e, rod R + r) for every geometry, angle and speed.
    big = e + extra  # the disc's radius, larger than its eccentricity
    th, w = math.radians(deg), rpm * math.pi / 30
    y0 = e * math.sin(th) + math.sqrt((big + r) ** 2 - (e * math.cos(th)) ** 2)
    doc = textwrap.dedent(
        f"""
        units: {{length: mm, angle: deg}}
        links: [frame, cam, follower]
        joints:
          O: {{type: revolute, links: [frame, cam], at: [0, 0]}}
          S: {{type: prismatic, links: [follower, frame], path: {{through: [0, 0], angle: 90}}, point: C}}
          K: {{type: cam, links: [cam, follower],
              profiles: {{cam: {{circle: {{centre: E, radius: {big!r}}}}}, follower: {{circle: {{centre: C, radius: {r!r}}}}}}}}}
        points:
          E: {{link: cam, at: [{e * math.cos(th)!r}, {e * math.sin(th)!r}]}}
          C: {{link: follower, at: [0, {y0!r}]}}
        drive: {{link: cam, angle: {deg!r}, rpm: {rpm!r}, direction: ccw}}
        """
    )
    kin = solve(loads(doc, path="cam.yaml"), "acceleration")
    s, v, a = (float(x[0]) for x in _slider_crank(e / 1000, (big + r) / 1000, np.array([th]), w))
    size = (big + r + e) / 1000
    assert kin.positions["C"][1] == pytest.approx(s, abs=1e-12 * size)
    assert kin.velocity("C")[1] == pytest.approx(v, abs=1e-10 * size * w)
    assert kin.acceleration("C")[1] == pytest.approx(a, abs=1e-9 * size * w**2)


@pytest.mark.parametrize("n", [12, 36, 144])
def test_a_curve_profiles_stated_departure_bounds_the_splines_distance_from_the_circle(n):
    # The spline through n points of a circle of radius r strays from it by about r (2π/n)⁴ / 400
    # (measured on a fine grid below, against the circle itself); de Boor's bound that
    # departure() states, (5/384) h⁴ max|f⁗| with f⁗ = r (2π/n)⁴ for the circle's coordinates
    # in the index parameter, is about five times that: above it, and of its order.
    from mech.pairs.curves import Spline

    r = 40.0
    th = 2 * math.pi * np.arange(n) / n
    spline = Spline(np.c_[r * np.cos(th), r * np.sin(th)])
    c, _, _ = spline.eval(np.linspace(0.0, n, 40 * n, endpoint=False))
    true = float(np.abs(np.hypot(c[:, 0], c[:, 1]) - r).max())
    bound = 5 / 384 * r * (2 * math.pi / n) ** 4
    assert true < spline.departure() < 10 * true
    assert spline.departure() == pytest.approx(bound, rel=0.05)


def test_a_solve_on_a_curve_profile_says_how_close_its_spline_is():
    doc = _cam("{line: {through: F, angle: 0}}", "F", 47.5).replace(
        "cam: {circle: {centre: E, radius: 40}}", "cam: {curve: [" + _circle_as_curve(36) + "]}"
    )
    mech = loads(doc, path="cam.yaml")
    bound = 5 / 384 * 40 * (2 * math.pi / 36) ** 4  # mm, as the test above derives it
    for notes in (solve(mech, "velocity").notes, sweep(mech, ANGLES, analyse=False).notes):
        (note,) = [n for n in notes if "spline" in n]
        assert "36 points" in note
        stated = float(note.split("within about ")[1].split(" mm")[0])
        assert stated == pytest.approx(bound, rel=0.05)
