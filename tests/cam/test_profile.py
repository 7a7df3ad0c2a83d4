"""Generated cam profiles against geometry that does not use the generator.

A profile is only a polygon of points here: the follower is put on it (the
cam turned to θ, the follower pushed down its line until it first touches the
polygon) and its lift is compared with the programme's s(θ).  Checks of the
pressure angle and the radii of curvature use closed forms from the textbooks
or a three-point circle through neighbouring pitch points.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mech.cam.analysis import analyse
from mech.cam.profile import CamLayout, evaluate
from mech.cam.program import CamProgram, Segment, follower_motion
from oracles.cam import lift_on_polygon, lift_oscillating, three_point_radius

D = math.radians
R_B = 0.04
R_R = 0.01
SIZE = 0.08  # the cams' size, for tolerances


def programme(follower: str, *, motion: str = "translating", lift: float = 0.03) -> CamProgram:
    return CamProgram(
        base_radius=R_B,
        follower=follower,
        roller_radius=R_R if follower == "roller" else None,
        motion=motion,
        segments=(
            Segment("rise", D(120), lift, "shm"),
            Segment("dwell", D(30)),
            Segment("return", D(150), lift, "cycloidal"),
            Segment("dwell", D(60)),
        ),
    )


def turned(profile: np.ndarray, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return profile @ np.array([[c, s], [-s, c]])


CHECK_ANGLES = np.radians(np.linspace(3.3, 357.1, 41))  # none on the sampling grid


@pytest.mark.parametrize("follower", ["knife", "roller", "flat"])
@pytest.mark.parametrize("sense", [1, -1])
@pytest.mark.parametrize("offset", [0.0, 0.012])
def test_translating_follower_placed_on_profile_reproduces_the_programme(follower, sense, offset):
    prog = programme(follower)
    axis = D(70)
    layout = CamLayout(prog, sense=sense, axis=axis, offset=offset)
    a = analyse(layout, samples=3600)
    e_n = -sense * offset  # the offset's side: where the cam's surface moves as the follower rises
    rp = R_B + (R_R if follower == "roller" else 0.0)
    start = R_B if follower == "flat" else math.sqrt(rp**2 - offset**2)
    s_ref = follower_motion(prog, CHECK_ANGLES).s
    for th, s in zip(CHECK_ANGLES, s_ref, strict=True):
        got = lift_on_polygon(turned(a.state.profile, sense * th), follower, axis, e_n, start, R_R)
        assert got == pytest.approx(s, abs=1e-5 * SIZE), math.degrees(th)


@pytest.mark.parametrize("follower", ["knife", "roller"])
@pytest.mark.parametrize(("sense", "branch"), [(1, 1), (-1, 1), (1, -1)])
def test_oscillating_follower_placed_on_profile_reproduces_the_programme(follower, sense, branch):
    prog = programme(follower, motion="oscillating", lift=D(20))
    pivot = np.array([0.09, 0.03])
    arm = 0.08
    layout = CamLayout(prog, sense=sense, pivot=(0.09, 0.03), arm=arm, branch=branch)
    a = analyse(layout, samples=3600)
    # the arm's angle at the programme's start, from the geometry alone: |P + L·r̂| = r_p
    rp = R_B + (R_R if follower == "roller" else 0.0)
    d = float(np.hypot(*pivot))
    gamma = math.acos((arm**2 + d**2 - rp**2) / (2 * arm * d))  # at the pivot, between P→O and the arm
    to_o = math.atan2(-pivot[1], -pivot[0])
    psi0 = to_o + branch * gamma
    c0 = pivot + arm * np.array([math.cos(psi0), math.sin(psi0)])
    # rising swings the point away from O
    sf = 1.0 if np.dot(c0, [-math.sin(psi0), math.cos(psi0)]) > 0 else -1.0
    s_ref = follower_motion(prog, CHECK_ANGLES[::3]).s
    for th, s in zip(CHECK_ANGLES[::3], s_ref, strict=True):
        psi = lift_oscillating(turned(a.state.profile, sense * th), pivot, arm, psi0 + sf * s, layout.roller)
        assert sf * (psi - psi0) == pytest.approx(s, abs=1e-5), math.degrees(th)


@pytest.mark.parametrize("offset", [0.0, 0.01, -0.015])
@pytest.mark.parametrize("sense", [1, -1])
def test_pressure_angle_matches_closed_form_for_offset_translating_follower(offset, sense):
    """tan φ = (ds/dθ − e) / (√(r_p² − e²) + s)  (Norton, Design of Machinery, eq. 8.31)."""
    prog = programme("roller")
    layout = CamLayout(prog, sense=sense, axis=D(90), offset=offset)
    theta = np.radians(np.arange(0, 360, 7.5))
    st = evaluate(layout, theta)
    m = follower_motion(prog, theta)
    rp = R_B + R_R
    ref = np.arctan((m.ds - offset) / (math.sqrt(rp**2 - offset**2) + m.s))
    np.testing.assert_allclose(st.pressure, ref, rtol=0, atol=1e-12)


def test_pressure_angle_is_the_angle_between_the_profile_normal_and_the_line_of_stroke():
    """Independently of the formula: the normal from a discrete pitch curve's chord."""
    prog = programme("knife")
    layout = CamLayout(prog, sense=1, axis=D(90), offset=0.008)
    theta = np.radians(np.linspace(0, 360, 7201)[:-1])
    st = evaluate(layout, theta)
    for k in range(50, 7200, 311):
        # the pitch curve's chord around k, turned back into the fixed frame at θ_k
        chord = st.pitch[k + 1] - st.pitch[k - 1]
        c, s = math.cos(theta[k]), math.sin(theta[k])
        tx, ty = c * chord[0] - s * chord[1], s * chord[0] + c * chord[1]
        # the normal is (ty, −tx) up to sign; its angle from the line of stroke (+y)
        phi = math.atan2(abs(ty), abs(tx))  # angle between the tangent and x, i.e. normal and y
        assert abs(st.pressure[k]) == pytest.approx(phi, abs=1e-5)


@pytest.mark.parametrize("sense", [1, -1])
@pytest.mark.parametrize("motion", ["translating", "oscillating"])
def test_radius_of_curvature_matches_three_point_circles_of_the_pitch_curve(sense, motion):
    prog = programme("roller", motion=motion, lift=0.03 if motion == "translating" else D(20))
    if motion == "translating":
        layout = CamLayout(prog, sense=sense, axis=D(90), offset=0.01)
    else:
        layout = CamLayout(prog, sense=sense, pivot=(0.09, 0.03), arm=0.08)
    st = evaluate(layout, np.radians(np.linspace(0, 360, 14401)[:-1]))
    geo = three_point_radius(st.pitch)
    # the pitch curve runs clockwise round a counter-clockwise cam: + means convex after flipping
    geo = geo * -sense
    for k in range(17, 14400, 613):
        assert st.rho[k] == pytest.approx(geo[k], rel=1e-4), k


def test_flat_face_radius_of_curvature_is_base_plus_lift_plus_its_second_derivative():
    """ρ = r_b + s + s''  (Norton eq. 8.30), and the profile's three-point circles agree."""
    prog = programme("flat")
    layout = CamLayout(prog, sense=-1, axis=D(90))
    theta = np.radians(np.linspace(0, 360, 14401)[:-1])
    st = evaluate(layout, theta)
    m = follower_motion(prog, theta)
    np.testing.assert_allclose(st.rho, R_B + m.s + m.d2s, rtol=1e-12)
    geo = three_point_radius(st.profile) * layout.sense * -1
    for k in range(17, 14400, 613):
        assert st.rho[k] == pytest.approx(geo[k], rel=1e-4)


def test_small_base_circle_undercuts_a_large_roller():
    """A steep rise on a small cam: the pitch curve's least convex radius is below the roller's.

    At the peak of an SHM rise and return (no dwell), s' = 0 and s'' = −π²h/2β², so the
    pitch curve's radius there is r²/(r − s'') with r = r_b + r_r + h: 13.85 mm here, against a
    20 mm roller.
    """
    prog = CamProgram(
        base_radius=0.015,
        follower="roller",
        roller_radius=0.02,
        segments=(
            Segment("rise", D(45), 0.03, "shm"),
            Segment("return", D(45), 0.03, "shm"),
            Segment("dwell", D(270)),
        ),
    )
    a = analyse(CamLayout(prog, sense=1, axis=D(90)), samples=7200)
    assert a.undercut
    r = 0.015 + 0.02 + 0.03
    d2s = -(math.pi**2) * 0.03 / (2 * D(45) ** 2)
    assert a.least_radius is not None
    assert a.least_radius.value == pytest.approx(r**2 / (r - d2s), rel=1e-9)
    assert math.degrees(a.least_radius.theta) == pytest.approx(45.0, abs=1e-6)
    # the same least radius from three-point circles of the sampled pitch curve
    geo = three_point_radius(a.state.pitch) * -1
    assert a.least_radius.value == pytest.approx(float(np.min(geo[geo > 0])), rel=1e-3)
    # a 5 mm roller on the same programme: the peak's radius is 8.6 mm, no undercut
    small = CamProgram(base_radius=0.015, follower="roller", roller_radius=0.005, segments=prog.segments)
    b = analyse(CamLayout(small, sense=1, axis=D(90)), samples=7200)
    r = 0.015 + 0.005 + 0.03
    assert b.least_radius is not None
    assert b.least_radius.value == pytest.approx(r**2 / (r - d2s), rel=1e-9)
    assert not b.undercut


def test_flat_face_on_a_small_cam_has_a_cusp():
    """ρ = r_b + s + s'' < 0 where the acceleration is large and negative: a cusp."""
    prog = CamProgram(
        base_radius=0.01,
        follower="flat",
        segments=(
            Segment("rise", D(45), 0.03, "shm"),
            Segment("return", D(45), 0.03, "shm"),
            Segment("dwell", D(270)),
        ),
    )
    a = analyse(CamLayout(prog, sense=1, axis=D(90)), samples=3600)
    m = follower_motion(prog, np.radians(np.linspace(0, 360, 36001)))
    assert a.cusp
    assert a.least_radius_any.value == pytest.approx(float(np.min(R_B * 0 + 0.01 + m.s + m.d2s)), rel=1e-4)
    ok = analyse(CamLayout(programme("flat"), sense=1, axis=D(90)))
    assert not ok.cusp and ok.least_radius_any.value > 0


def test_largest_velocity_and_acceleration_are_the_laws_peaks():
    """SHM rise: v = πhω/2β, a = π²hω²/2β²; cycloidal return: v = 2hω/β, a = 2πhω²/β² (Khurmi ch. 20)."""
    w = 30.0
    a = analyse(CamLayout(programme("knife"), axis=D(90)), omega=w)
    h, b_rise, b_ret = 0.03, D(120), D(150)
    v_peak = max(math.pi * h * w / (2 * b_rise), 2 * h * w / b_ret)
    a_peak = max(math.pi**2 * h * w**2 / (2 * b_rise**2), 2 * math.pi * h * w**2 / b_ret**2)
    assert a.velocity is not None and abs(a.velocity.value) == pytest.approx(v_peak, rel=1e-9)
    assert a.acceleration is not None and abs(a.acceleration.value) == pytest.approx(a_peak, rel=1e-9)
    # the cycloidal return's peak velocity sits at its middle: 150° + 75°
    assert math.degrees(a.velocity.theta) == pytest.approx(225.0, abs=1e-3)
    assert a.acceleration_jumps == pytest.approx((0.0, D(120)))
    assert a.velocity_jumps == ()


def test_a_parabolic_segment_s_jerk_is_infinite_half_way_through_as_at_its_ends():
    """Uniform acceleration and retardation (Khurmi ch. 20): s″ = +4h/β² for the first half of the
    segment and −4h/β² for the second, so the acceleration jumps (the jerk is infinite) at its
    middle as well as at its ends: a return over 140° from 150° jumps at 150°, 220° and 290°."""
    prog = CamProgram(
        0.04,
        "roller",
        (
            Segment("rise", D(100), 0.03, "cycloidal"),
            Segment("dwell", D(50)),
            Segment("return", D(140), 0.03, "parabolic"),
            Segment("dwell", D(70)),
        ),
        roller_radius=0.012,
    )
    a = analyse(CamLayout(prog, axis=D(90)), omega=20.0)
    assert a.acceleration_jumps == pytest.approx((D(150), D(220), D(290)))
    s2 = follower_motion(prog, [D(220) - 1e-6, D(220) + 1e-6]).d2s
    assert s2 == pytest.approx([-4 * 0.03 / D(140) ** 2, 4 * 0.03 / D(140) ** 2])  # a return: signs turned
    # the s–v–a diagram draws that jump as a jump: its acceleration curve breaks at 220° too
    from mech.draw.cam import _broken

    theta = np.degrees(a.state.theta)
    runs = _broken(theta, a.state.d2s, lambda t: t, lambda v: v, prog.breaks)
    ends = sorted(round(run[0][0], 6) for run in runs)
    assert any(abs(x - 220.0) < 1.0 for x in ends), ends


@pytest.mark.parametrize(("sense", "branch"), [(1, 1), (-1, 1), (1, -1), (-1, -1)])
def test_oscillating_flat_face_rests_on_the_profile_at_the_programmes_angle(sense, branch):
    """The face, a line fixed to the arm at distance c from the pivot, is turned until it
    rests on the profile polygon (the cam on its far side, just touching); its turn from
    the start must be the programme's lift.  Cases with a cusp (ρ < 0) cannot be followed
    and are left out by checking the analysis says so."""
    face = 0.01
    prog = CamProgram(
        base_radius=R_B,
        follower="flat",
        motion="oscillating",
        segments=(
            Segment("rise", D(120), D(15), "cycloidal"),
            Segment("dwell", D(30)),
            Segment("return", D(150), D(15), "shm"),
            Segment("dwell", D(60)),
        ),
    )
    pivot = np.array([0.1, 0.04])
    layout = CamLayout(prog, sense=sense, pivot=(0.1, 0.04), arm=face, branch=branch)
    a = analyse(layout, samples=3600)
    assert not a.cusp  # a mild programme: the profile is convex everywhere
    d = float(np.hypot(*pivot))
    delta = math.atan2(pivot[1], pivot[0])
    g0 = delta + branch * math.acos((R_B + face) / d)  # the face's normal at the start
    rise_sign = 1.0 if -math.sin(g0 - delta) > 0 else -1.0  # turning this way lifts the face off O

    def gap(poly: np.ndarray, g: float) -> float:
        m = np.array([math.cos(g), math.sin(g)])
        return float(np.max(poly @ m)) - (float(m @ pivot) - face)

    for th, s in zip(CHECK_ANGLES[::2], follower_motion(prog, CHECK_ANGLES[::2]).s, strict=True):
        poly = turned(a.state.profile, sense * th)
        lo, hi = g0 + rise_sign * (s - 0.05), g0 + rise_sign * (s + 0.05)
        glo = gap(poly, lo)
        assert glo * gap(poly, hi) < 0
        for _ in range(50):
            mid = (lo + hi) / 2
            if (gap(poly, mid) > 0) == (glo > 0):
                lo = mid
            else:
                hi = mid
        assert rise_sign * ((lo + hi) / 2 - g0) == pytest.approx(s, abs=1e-5), math.degrees(th)


@settings(max_examples=25, deadline=None)
@given(
    rise_law=st.sampled_from(["shm", "parabolic", "cycloidal"]),
    return_law=st.sampled_from(["shm", "parabolic", "cycloidal"]),
    lift=st.floats(0.005, 0.03),
    rise_deg=st.floats(90.0, 180.0),
    offset=st.floats(-0.01, 0.01),
    sense=st.sampled_from([1, -1]),
)
def test_any_roller_programme_without_undercut_is_followed_exactly(
    rise_law, return_law, lift, rise_deg, offset, sense
):
    """Law: whatever the programme, a roller that the analysis says is not undercut rests on the
    generated profile at the programme's lift."""
    prog = CamProgram(
        base_radius=R_B,
        follower="roller",
        roller_radius=R_R,
        segments=(
            Segment("rise", D(rise_deg), lift, rise_law),
            Segment("dwell", D(20)),
            Segment("return", D(340 - rise_deg), lift, return_law),
        ),
    )
    layout = CamLayout(prog, sense=sense, axis=D(90), offset=offset)
    a = analyse(layout, samples=3600)
    assume(not a.undercut)
    rp = R_B + R_R
    start = math.sqrt(rp**2 - offset**2)
    for th, s in zip(CHECK_ANGLES[::4], follower_motion(prog, CHECK_ANGLES[::4]).s, strict=True):
        got = lift_on_polygon(
            turned(a.state.profile, sense * th), "roller", D(90), -sense * offset, start, R_R
        )
        assert got == pytest.approx(s, abs=1e-5 * SIZE)


def uniform_programme(follower: str) -> CamProgram:
    return CamProgram(
        base_radius=R_B,
        follower=follower,
        roller_radius=R_R if follower == "roller" else None,
        segments=(
            Segment("rise", D(120), 0.03, "uniform"),
            Segment("dwell", D(30)),
            Segment("return", D(150), 0.03, "uniform"),
            Segment("dwell", D(60)),
        ),
    )


def test_roller_cannot_follow_the_corner_where_uniform_velocity_stops():
    """At the end of a uniform rise the pitch curve has a corner pointing out: radius zero.

    Placed on the generated profile, the roller rounds the corner instead of following the
    programme (checked on the polygon alone), and the analysis calls that an undercut.
    """
    layout = CamLayout(uniform_programme("roller"), sense=1, axis=D(90))
    a = analyse(layout, samples=3600)
    assert a.undercut
    assert a.least_radius is not None and a.least_radius.value == 0.0
    assert math.degrees(a.least_radius.theta) == pytest.approx(120.0)
    start = R_B + R_R
    th = D(121.0)  # just past the corner, on the dwell
    got = lift_on_polygon(turned(a.state.profile, th), "roller", D(90), 0.0, start, R_R)
    assert got > 0.03 + 1e-5  # held up by the corner: the programme says 30 mm exactly
    # a knife edge follows the same corner exactly
    k = analyse(CamLayout(uniform_programme("knife"), sense=1, axis=D(90)), samples=3600)
    assert not k.undercut
    assert lift_on_polygon(turned(k.state.profile, th), "knife", D(90), 0.0, R_B) == pytest.approx(
        0.03, abs=1e-5 * SIZE
    )


def test_flat_face_cannot_follow_uniform_velocity_stopping():
    a = analyse(CamLayout(uniform_programme("flat"), sense=1, axis=D(90)), samples=3600)
    assert a.cusp
    assert a.least_radius_any.value == -math.inf
