"""The oracles themselves against published answers, so that tests may trust them.

Each oracle is checked on a worked textbook example (source beside the numbers) and, where
two oracles derive the same quantity by different routes, against each other.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from oracles.cam import (
    lift_on_polygon,
    lift_oscillating,
    oscillating_pressure_angle,
    textbook_rise,
    three_point_radius,
)
from oracles.four_bar import (
    crank_rocker_limits,
    crank_rocker_sweep,
    four_bar,
    four_bar_clear_of_toggle,
    rocker_angle,
)
from oracles.inversor import FOLD, inversor_by_circles, inversor_p
from oracles.lines import line_intersection, meet
from oracles.slider_crank import slider_crank, slider_dead_centres, slider_driven_crank, slider_x
from oracles.transmission import (
    crank_turns,
    diagonal_range,
    transmission_angle,
    transmission_angle_at,
    turning_by_sampling,
)
from oracles.velocity_field import icentre, velocity_field

# Khurmi & Gupta, *Theory of Machines*, Example 7.1: AD = 150 mm fixed, crank AB = 40 mm at
# 120 rpm clockwise, CD = 80 mm, BC = AD, angle BAD = 60 deg.  Published (graphical):
# v_B = 0.503 m/s, v_C = 0.385 m/s, omega_CD = 4.8 rad/s clockwise -- to drawing accuracy (2 %).
KHURMI_7_1 = dict(a=0.04, b=0.15, c=0.08, d=0.15, theta=math.radians(60), w2=-120 * 2 * math.pi / 60)


def _khurmi_7_1_pins() -> tuple[list[tuple], np.ndarray, np.ndarray]:
    k = KHURMI_7_1
    B = k["a"] * np.array([math.cos(k["theta"]), math.sin(k["theta"])])
    C, *_ = four_bar(k["a"], k["b"], k["c"], k["d"], k["theta"], k["w2"])
    pins = [
        ("pin", (0.0, 0.0), "frame", "crank"),
        ("pin", B, "crank", "coupler"),
        ("pin", C, "coupler", "rocker"),
        ("pin", (k["d"], 0.0), "rocker", "frame"),
    ]
    return pins, B, C


def test_four_bar_oracle_gives_khurmi_example_7_1():
    k = KHURMI_7_1
    C, _w3, w4, _a3, _a4 = four_bar(k["a"], k["b"], k["c"], k["d"], k["theta"], k["w2"])
    assert C[1] > 0  # C above AD, as in the book's figure
    assert math.dist(C, (0.04 * math.cos(k["theta"]), 0.04 * math.sin(k["theta"]))) == pytest.approx(0.15)
    assert math.dist(C, (0.15, 0)) == pytest.approx(0.08)
    assert abs(k["w2"]) * k["a"] == pytest.approx(0.503, rel=0.02)
    assert w4 < 0 and abs(w4) == pytest.approx(4.8, rel=0.02)  # clockwise
    assert abs(w4) * k["c"] == pytest.approx(0.385, rel=0.02)


def test_four_bar_oracle_sweep_agrees_with_the_single_angle_loop():
    """The vectorised Cramer's-rule sweep and the matrix solve are two routes to one answer."""
    th = np.linspace(5.0, 355.0, 36)
    psi, w4s, w3s, vc = crank_rocker_sweep(1.0, 3.0, 2.5, 3.0, th, 10.0)
    for i, t in enumerate(th):
        C, w3, w4, _, _ = four_bar(1.0, 3.0, 2.5, 3.0, math.radians(t), 10.0)
        assert w4s[i] == pytest.approx(w4, rel=1e-12, abs=1e-12)
        assert w3s[i] == pytest.approx(w3, rel=1e-12, abs=1e-12)
        assert psi[i] == pytest.approx(math.degrees(math.atan2(C[1], C[0] - 3.0)), abs=1e-10)
        assert vc[i] == pytest.approx(abs(w4) * 2.5, rel=1e-12)


def _coupler_and_rocker_directions(a, b, c, d, theta, upper) -> tuple[float, float]:
    """Directions (rad) of B→C and D→C from the closed-form C of :func:`four_bar`."""
    C = four_bar(a, b, c, d, theta, 1.0, upper=upper)[0]
    B = (a * math.cos(theta), a * math.sin(theta))
    return math.atan2(C[1] - B[1], C[0] - B[0]), math.atan2(C[1], C[0] - d)


@pytest.mark.parametrize("upper", [True, False])
def test_four_bar_omega_is_the_derivative_of_its_positions_on_either_branch(upper):
    """ω3 and ω4 by the vector loop against central differences of the directions of BC and DC
    taken from the closed-form C (the circle intersection): two routes to one answer."""
    h = 1e-6
    for a, b, c, d in ((0.04, 0.15, 0.08, 0.15), (1.0, 3.0, 2.5, 3.0), (0.3, 0.9, 0.7, 1.0)):
        for th in np.radians(np.arange(5.0, 360.0, 25.0)):
            p3, p4 = _coupler_and_rocker_directions(a, b, c, d, th + h, upper)
            n3, n4 = _coupler_and_rocker_directions(a, b, c, d, th - h, upper)
            _, w3, w4, _, _ = four_bar(a, b, c, d, th, 2.5, upper=upper)
            turn = [math.remainder(p3 - n3, 2 * math.pi), math.remainder(p4 - n4, 2 * math.pi)]
            assert 2.5 * np.array(turn) / (2 * h) == pytest.approx([w3, w4], rel=1e-6, abs=1e-8)


def test_four_bar_clear_of_toggle_refuses_where_the_cosine_rule_says_and_agrees_with_the_field():
    """None exactly where BD leaves the closure (less a margin) or where bc·|sin μ| (μ by the law of
    cosines, :mod:`oracles.transmission`) is too small; elsewhere ω as the velocity field's solve."""
    rng = np.random.default_rng(14)
    refused = {"open": 0, "toggle": 0, "kept": 0}
    for i in range(400):
        # test_icentres_properties' margins, and a determinant large enough to refuse some
        margin, least = (0.05, 1e-3) if i % 2 else (0.0, 0.1)
        a, b, c = rng.uniform(0.1, 2.0, 3)
        th, upper = rng.uniform(-math.pi, math.pi), bool(rng.integers(2))
        got = four_bar_clear_of_toggle(a, b, c, 1.0, th, 1.0, upper=upper, margin=margin, least_det=least)
        bd = math.hypot(a * math.cos(th) - 1.0, a * math.sin(th))
        if not abs(b - c) + margin < bd < b + c - margin:
            refused["open"] += 1
            assert got is None
        elif b * c * math.sin(transmission_angle(1.0, a, b, c, th)) <= least:
            refused["toggle"] += 1
            assert got is None
        else:
            refused["kept"] += 1
            assert got is not None
            (A, B, C, D), (w2, w3, w4) = got
            assert (math.dist(B, C), math.dist(C, D)) == pytest.approx((b, c), rel=1e-12)
            pins = [
                ("pin", A, "frame", "crank"),
                ("pin", B, "crank", "coupler"),
                ("pin", C, "coupler", "rocker"),
                ("pin", D, "rocker", "frame"),
            ]
            field = velocity_field(["frame", "crank", "coupler", "rocker"], "frame", pins, ("crank", w2))
            assert (field["coupler"][1], field["rocker"][1]) == pytest.approx((w3, w4), rel=1e-9, abs=1e-9)
    assert min(refused.values()) > 0, refused


def test_crank_rocker_limits_give_khurmi_7_1_time_ratio_and_a_resting_rocker():
    # mechanisms/four_bar.yaml works the same chain by the cosine rule: crank angles between the
    # limit positions 187.61 / 172.39 deg, time ratio 1.0883.
    t_ext, t_fold, ratio = crank_rocker_limits(0.04, 0.15, 0.08, 0.15)
    assert t_fold - t_ext == pytest.approx(187.61, abs=0.01)
    assert ratio == pytest.approx(1.0883, abs=1e-4)
    # at a limit position the rocker is at rest: the loop's ω4 vanishes there
    _, w4, _, _ = crank_rocker_sweep(0.04, 0.15, 0.08, 0.15, np.array([t_ext, t_fold]), 1.0)
    assert np.abs(w4) == pytest.approx([0, 0], abs=1e-9)


def test_slider_crank_oracle_gives_khurmi_examples_7_2_and_8_1():
    # Khurmi & Gupta, Examples 7.2 and 8.1: crank 150 mm at a constant 300 rpm, rod 600 mm,
    # crank 45 deg from inner dead centre.  Published (graphical): mid-point D of the rod at
    # 4.1 m/s (exact 3.995, the book's drawing is 2.6 % high: 3 %) and 117 m/s^2 (2 %).
    # Mirrored so that the piston is ahead (+x): the crank at 45 deg.
    r, rod, w, th = 0.15, 0.6, 300 * 2 * math.pi / 60, math.radians(45)
    _x, w3, v, _a3, a = slider_crank(r, rod, 0.0, th, w)
    A = r * np.array([math.cos(th), math.sin(th)])
    vA, aA = w * np.array([-A[1], A[0]]), -(w**2) * A
    vD, aD = (vA + np.array([v, 0.0])) / 2, (aA + np.array([a, 0.0])) / 2  # D midway on a rigid rod
    assert np.hypot(*vD) == pytest.approx(4.1, rel=0.03)
    assert np.hypot(*aD) == pytest.approx(117, rel=0.02)
    assert abs(w3) == pytest.approx(5.642, rel=1e-3)  # worked in mechanisms/slider_crank.yaml


def test_slider_dead_centres_are_where_the_slider_stops():
    r, rod, e = 0.1, 0.4, 0.05
    outer, inner, x_out, x_in = slider_dead_centres(r, rod, e)
    for th, x in ((outer, x_out), (inner, x_in)):
        xb, _, v, _, _ = slider_crank(r, rod, e, th, 1.0)
        assert xb == pytest.approx(x, rel=1e-12)
        assert v == pytest.approx(0.0, abs=1e-12)
    assert x_out - x_in > 2 * r  # an offset slider's stroke is longer than twice the crank


def test_slider_driven_crank_runs_the_slider_crank_backwards():
    """θ and ω from the slider's x and speed, put back into the crank-driven closed form (the rod's
    angle differentiated): the slider stands at x and moves at the speed given."""
    for r, rod, x, v in ((0.08, 0.25, 0.28, -2.0), (0.1, 0.4, 0.45, 1.0), (0.1, 0.4, 0.35, 3.0)):
        th, w = slider_driven_crank(r, rod, x, v)
        assert 0.0 < th < math.pi  # the crank pin above the axis
        xb, _, vb, _, _ = slider_crank(r, rod, 0.0, th, w)
        assert xb == pytest.approx(x, rel=1e-12)
        assert vb == pytest.approx(v, rel=1e-9)


def test_velocity_field_agrees_with_the_four_bar_loop_and_kennedy():
    """Field (linear solve of pins) and loop (closed form) are independent routes to ω."""
    pins, B, C = _khurmi_7_1_pins()
    k = KHURMI_7_1
    field = velocity_field(["frame", "crank", "coupler", "rocker"], "frame", pins, ("crank", k["w2"]))
    _, w3, w4, _, _ = four_bar(k["a"], k["b"], k["c"], k["d"], k["theta"], k["w2"])
    assert field["coupler"][1] == pytest.approx(w3, rel=1e-12)
    assert field["rocker"][1] == pytest.approx(w4, rel=1e-12)
    # I13 where lines AB and DC meet (Kennedy); mechanisms/four_bar.yaml: (212.05, 367.29) mm
    P, direction = icentre(field, "frame", "coupler")
    assert direction is None and P is not None
    assert math.dist(P * 1000, (212.05, 367.29)) <= 0.01

    def cross(u, v) -> float:
        return float(u[0] * v[1] - u[1] * v[0])

    assert abs(cross(B, P)) <= 1e-12 and abs(cross(C - (0.15, 0), P - (0.15, 0))) <= 1e-12
    # a pin is its own I-centre
    P12, _ = icentre(field, "crank", "coupler")
    assert P12 is not None and math.dist(P12, B) <= 1e-15


def test_velocity_field_of_a_slider_crank_agrees_with_the_closed_form():
    r, rod, e, th, w = 0.1, 0.4, 0.03, math.radians(70), 12.0
    xb, w3, v, _, _ = slider_crank(r, rod, e, th, w)
    A = (r * math.cos(th), r * math.sin(th))
    cons = [
        ("pin", (0.0, 0.0), "frame", "crank"),
        ("pin", A, "crank", "rod"),
        ("pin", (xb, e), "rod", "piston"),
        ("prismatic", (xb, e), "piston", "frame", (1.0, 0.0)),
    ]
    field = velocity_field(["frame", "crank", "rod", "piston"], "frame", cons, ("crank", w))
    assert field["rod"][1] == pytest.approx(w3, rel=1e-12)
    u, wp = field["piston"]
    assert wp == pytest.approx(0.0, abs=1e-12) and u == pytest.approx([v, 0.0], abs=1e-12 * abs(v))
    # the piston translates: I14 at infinity, across the path
    P, direction = icentre(field, "frame", "piston")
    assert P is None and abs(direction[1]) == pytest.approx(1.0)


def test_mpmath_forms_agree_with_the_float_closed_forms():
    """rocker_angle and slider_x (for mpmath.diff) against four_bar and slider_crank in floats."""
    th = 0.7
    C, _w3, w4, _, _ = four_bar(1.0, 3.0, 2.5, 3.0, th, 1.0)
    assert float(rocker_angle(1.0, 3.0, 2.5, 3.0, th)) == pytest.approx(
        math.atan2(C[1], C[0] - 3.0), abs=1e-14
    )
    assert float(mpmath.diff(lambda t: rocker_angle(1.0, 3.0, 2.5, 3.0, t), th)) == pytest.approx(
        w4, rel=1e-12
    )
    x, _, v, _, _ = slider_crank(0.1, 0.4, 0.03, th, 1.0)
    assert float(slider_x(0.1, 0.4, 0.03, th)) == pytest.approx(x, rel=1e-14)
    assert float(mpmath.diff(lambda t: slider_x(0.1, 0.4, 0.03, t), th)) == pytest.approx(v, rel=1e-12)


def test_the_two_line_intersections_agree_and_find_a_3_4_5_crossing():
    """Cramer's rule and the parametric form share no step; diagonals of a 3 × 4 box cross at its middle."""
    assert line_intersection((0, 0), (3, 4), (3, 0), (0, 4)) == pytest.approx((1.5, 2.0), abs=1e-15)
    assert meet((0, 0), (3, 4), (3, 0), (0, 4)) == pytest.approx((1.5, 2.0), abs=1e-15)
    rng = np.random.default_rng(7)
    for _ in range(50):
        p1, p2, q1, q2 = (tuple(rng.uniform(-5, 5, 2)) for _ in range(4))
        assert line_intersection(p1, p2, q1, q2) == pytest.approx(meet(p1, p2, q1, q2), rel=1e-9, abs=1e-9)


def test_transmission_angle_cosine_rule_agrees_with_its_half_angle_form():
    """μ at a crank angle (BD from triangle ABD) and μ at that BD (half-angle form), and BD's range."""
    for d, a, b, c in ((0.15, 0.04, 0.15, 0.08), (1.0, 0.3, 0.9, 0.7), (0.2, 0.5, 0.6, 0.55)):
        lo, hi = diagonal_range(d, a, b, c)
        bds = []
        for th in np.linspace(0.0, 2 * math.pi, 721):
            bd = math.hypot(a * math.cos(th) - d, a * math.sin(th))
            bds.append(bd)
            if lo < bd < hi:
                assert transmission_angle_at(b, c, bd) == pytest.approx(
                    transmission_angle(d, a, b, c, th), abs=1e-9
                )
        # the crank turns fully exactly when BD never leaves the closure's range
        closes = abs(b - c) <= min(bds) and max(bds) <= b + c
        assert crank_turns(d, a, b, c) == closes
        if closes:
            assert (lo, hi) == pytest.approx((min(bds), max(bds)), abs=1e-12)


def test_textbook_rise_laws_are_their_own_derivatives():
    """v = ω ds/dθ and a = ω dv/dθ, by central differences of the laws' own s and v."""
    S, beta, w, h = 0.04, math.radians(120), 25.0, 1e-6
    for law in ("uniform", "shm", "parabolic", "cycloidal"):
        for th in np.radians([7.0, 33.0, 59.0, 61.0, 97.0, 118.0]):
            _, v, a = textbook_rise(law, th, S, beta, w)
            (s_m, v_m, _), (s_p, v_p, _) = (textbook_rise(law, th + k * h, S, beta, w) for k in (-1, 1))
            assert w * (s_p - s_m) / (2 * h) == pytest.approx(v, rel=1e-7)
            assert w * (v_p - v_m) / (2 * h) == pytest.approx(a, rel=1e-6, abs=1e-9)
        assert textbook_rise(law, beta, S, beta, w)[0] == pytest.approx(S, rel=1e-15)


def test_three_point_radius_is_exact_on_a_circle_and_close_on_an_ellipse():
    """A circle through three points of a circle is that circle; an ellipse's ρ = (a²sin²t + b²cos²t)^1.5 / ab."""
    t = np.linspace(0.0, 2 * math.pi, 4000, endpoint=False)
    circle = 0.03 * np.stack([np.cos(t), np.sin(t)], axis=-1)
    assert three_point_radius(circle) == pytest.approx(np.full(len(t), 0.03), rel=1e-9)
    assert three_point_radius(circle[::-1]) == pytest.approx(np.full(len(t), -0.03), rel=1e-9)
    a, b = 0.05, 0.03
    ellipse = np.stack([a * np.cos(t), b * np.sin(t)], axis=-1)
    rho = (a**2 * np.sin(t) ** 2 + b**2 * np.cos(t) ** 2) ** 1.5 / (a * b)
    assert three_point_radius(ellipse) == pytest.approx(rho, rel=1e-5)


def test_a_follower_put_on_an_eccentric_circle_rests_where_the_circle_puts_it():
    """A disc of radius R about (e, 0), follower on the y axis: knife √(R² − e²), roller √((R + r)² − e²), flat R."""
    R, e, r = 0.04, 0.01, 0.008
    t = np.linspace(0.0, 2 * math.pi, 20000, endpoint=False)
    disc = np.stack([e + R * np.cos(t), R * np.sin(t)], axis=-1)
    up = math.pi / 2
    assert lift_on_polygon(disc, "knife", up, 0.0, 0.0) == pytest.approx(math.sqrt(R**2 - e**2), rel=1e-7)
    assert lift_on_polygon(disc, "roller", up, 0.0, 0.0, r) == pytest.approx(
        math.sqrt((R + r) ** 2 - e**2), rel=1e-7
    )
    assert lift_on_polygon(disc, "flat", up, 0.0, 0.0) == pytest.approx(R, rel=1e-7)
    # an arm of length L about P = (d, 0) resting its roller on the disc: |C − (e, 0)| = R + r, so
    # the arm is γ off P→(e, 0), by the cosine rule in P, (e, 0), C (searched from 0.02 rad away)
    d, L = 0.09, 0.07
    gamma = math.acos((L**2 + (d - e) ** 2 - (R + r) ** 2) / (2 * L * (d - e)))
    psi = lift_oscillating(disc, np.array([d, 0.0]), L, math.pi - gamma + 0.02, r)
    assert psi == pytest.approx(math.pi - gamma, abs=1e-6)


def test_oscillating_pressure_angle_over_a_dwell_is_the_triangle_cam_centre_pivot_roller():
    """Over a dwell the roller centre C circles the cam centre O: the path's normal lies along OC and C
    moves across PC, so the pressure angle is 90° − ∠OCP (cosine rule in O, P, C; the example's
    OP = 100, PC = 80, OC = 40 mm at zero lift, the rise swinging C 20° away from O)."""
    op, pc, oc0 = 100.0, 80.0, 40.0
    at_p0 = math.acos((op**2 + pc**2 - oc0**2) / (2 * op * pc))
    for swing, degrees in ((0.0, (300, 330)), (math.radians(20), (100, 120, 140))):
        oc = math.sqrt(op**2 + pc**2 - 2 * op * pc * math.cos(at_p0 + swing))
        at_c = math.degrees(math.acos((oc**2 + pc**2 - op**2) / (2 * oc * pc)))
        for deg in degrees:
            assert oscillating_pressure_angle(math.radians(deg)) == pytest.approx(90 - at_c, abs=1e-6)


def test_turning_by_sampling_agrees_with_grashofs_inequality():
    """Loop closure sampled at every angle against s + l < p + q: in a Grashof chain the shortest
    link turns fully relative to the frame (all three moving links when the frame is shortest);
    otherwise none does.  The crank's part also against :func:`crank_turns` (BD's range)."""
    rng = np.random.default_rng(5)
    seen = set()
    names = ("frame", "crank", "coupler", "rocker")
    for _ in range(60):
        d, a, b, c = rng.uniform(10.0, 200.0, 4)
        s, p, q, ll = sorted((d, a, b, c))
        if abs(s + ll - p - q) <= 1e-2 * ll:  # as tests/properties/test_grashof.py: clear of the grid
            continue
        shortest = names[int(np.argmin((d, a, b, c)))]
        if s + ll > p + q:
            expected = set()
        elif shortest == "frame":
            expected = {"crank", "coupler", "rocker"}
        else:
            expected = {shortest}
        turning = turning_by_sampling(d, a, b, c)
        assert turning == expected, (d, a, b, c)
        assert ("crank" in turning) == crank_turns(d, a, b, c)
        seen.add(frozenset(turning))
    assert len(seen) == 5  # every class met: none, each link alone, all three


@pytest.mark.parametrize("deg", [30.0, 60.0, 73.0, 75.0, 90.0, 120.0])
def test_the_inversors_p_by_its_line_agrees_with_the_rhombus_built_from_its_links(deg):
    """P on x = 1.28 (inversion) against P = A + B − C from the circles, and its rate by differences."""
    theta = math.radians(deg)
    px, py = inversor_by_circles(theta)
    y, dy = inversor_p(theta)
    assert px == pytest.approx(1.28, abs=1e-12) and py == pytest.approx(float(y), rel=1e-12)
    h = 1e-6
    fd = (inversor_by_circles(theta + h)[1] - inversor_by_circles(theta - h)[1]) / (2 * h)
    assert fd == pytest.approx(float(dy), rel=1e-7)
    # the fold: OC = OP where C = P
    assert 2 * math.cos(FOLD / 2) == pytest.approx(1.28 / math.cos(FOLD / 2), rel=1e-12)
