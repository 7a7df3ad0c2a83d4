"""Four-bar chain against the vector-loop closed form written here (not the solver's method)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from builders import build, four_bar

from mech.errors import GeometryError, InputError
from mech.kinematics import solve
from mech.options import SolveOptions


def closed_form(a, b, c, d, theta, w2, al2=0.0, upper=True):
    """Crank AB, coupler BC, rocker CD, A=(0,0), D=(d,0): C, ω3, ω4, α3, α4 by the vector loop.

    v_B + ω3 k×BC = ω4 k×DC ;  a_B + α3 k×BC − ω3² BC = α4 k×DC − ω4² DC.
    """
    B = np.array([a * math.cos(theta), a * math.sin(theta)])
    D = np.array([d, 0.0])
    f = D - B
    L = np.hypot(*f)
    x = (b * b - c * c + L * L) / (2 * L)
    h = math.sqrt(b * b - x * x)
    e = f / L
    perp = np.array([-e[1], e[0]])
    C = B + x * e + (h if upper else -h) * perp
    BC, DC = C - B, C - D
    k = lambda v: np.array([-v[1], v[0]])  # noqa: E731
    vB = w2 * k(B)
    M = np.column_stack([k(BC), -k(DC)])
    w3, w4 = np.linalg.solve(M, -vB)
    aB = al2 * k(B) - w2**2 * B
    rhs = -(aB - w3**2 * BC + w4**2 * DC)
    a3, a4 = np.linalg.solve(M, rhs)
    return C, w3, w4, a3, a4


ANGLES = [0.0, 30.0, 60.0, 90.0, 145.0, 180.0, 200.0, 270.0, 333.0]


@pytest.mark.parametrize("deg", ANGLES)
def test_fourbar_matches_closed_form(deg):
    th = math.radians(deg)
    m = four_bar(angle=th, omega=-4 * math.pi, alpha=3.0)
    kin = solve(m, "acceleration")
    C, w3, w4, a3, a4 = closed_form(0.04, 0.15, 0.08, 0.15, th, -4 * math.pi, 3.0)
    assert kin.positions["C"] == pytest.approx(tuple(C), abs=1e-13)
    assert kin.links["coupler"].omega == pytest.approx(w3, rel=1e-10, abs=1e-12)
    assert kin.links["rocker"].omega == pytest.approx(w4, rel=1e-10, abs=1e-12)
    assert kin.links["coupler"].alpha == pytest.approx(a3, rel=1e-9, abs=1e-10)
    assert kin.links["rocker"].alpha == pytest.approx(a4, rel=1e-9, abs=1e-10)
    assert kin.links["crank"].angle == pytest.approx(th % (2 * math.pi))


def test_fourbar_moved_by_angle_option_keeps_branch():
    m = four_bar(angle=math.radians(60))
    for deg in (120, 240, 300, 61):
        th = math.radians(deg)
        kin = solve(m, "acceleration", SolveOptions(angle=th))
        C, _w3, w4, _a3, a4 = closed_form(0.04, 0.15, 0.08, 0.15, th, -4 * math.pi)
        assert kin.positions["C"] == pytest.approx(tuple(C), abs=1e-12)
        assert kin.links["rocker"].omega == pytest.approx(w4, rel=1e-9)
        assert kin.links["rocker"].alpha == pytest.approx(a4, rel=1e-8)
        assert any("keeping its branch" in n for n in kin.notes)


def test_default_branch_is_reported_and_near_picks_the_other():
    kin = solve(four_bar(), "position")
    assert any(n.startswith("C: left of B→D") for n in kin.notes)
    assert kin.positions["C"][1] > 0
    low = solve(four_bar(near=(0.16, -0.08)), "velocity")
    C, _, w4, _, _ = closed_form(0.04, 0.15, 0.08, 0.15, math.radians(60), -4 * math.pi, upper=False)
    assert low.positions["C"] == pytest.approx(tuple(C), abs=1e-13)
    assert low.links["rocker"].omega == pytest.approx(w4, rel=1e-10)
    assert not any("default rule" in n for n in low.notes)


def test_velocities_match_finite_differences_of_positions():
    m = four_bar(omega=1.0)
    th, h = math.radians(75), 1e-4  # central differences: O(h²) ≈ 1e-8 relative
    kin = solve(m, "acceleration", SolveOptions(angle=th))
    plus = solve(m, "velocity", SolveOptions(angle=th + h))
    minus = solve(m, "velocity", SolveOptions(angle=th - h))
    # ω = 1 rad/s ccw: d/dt = d/dθ
    fd = (np.array(plus.positions["C"]) - np.array(minus.positions["C"])) / (2 * h)
    assert kin.velocity("C") == pytest.approx(tuple(fd), rel=1e-6, abs=1e-9)
    fd_a = (np.array(plus.velocity("C")) - np.array(minus.velocity("C"))) / (2 * h)
    assert kin.acceleration("C") == pytest.approx(tuple(fd_a), rel=1e-6, abs=1e-9)
    dw = (plus.links["rocker"].omega - minus.links["rocker"].omega) / (2 * h)
    assert kin.links["rocker"].alpha == pytest.approx(dw, rel=1e-6)


def test_three_points_of_one_link_obey_the_rigid_body_relation():
    m = build(
        ["frame", "crank", "coupler", "rocker"],
        {
            "A": {"links": ["frame", "crank"], "at": (0, 0)},
            "B": {"links": ["crank", "coupler"]},
            "C": {"links": ["coupler", "rocker"]},
            "D": {"links": ["rocker", "frame"], "at": (0.15, 0)},
        },
        lengths={"A-B": 0.04, "B-C": 0.15, "C-D": 0.08},
        drive={"link": "crank", "angle": 1.0, "omega": 7.0, "alpha": -2.0},
        points={"E": {"link": "coupler", "from": "B", "toward": "C", "offset": (0.05, 0.03)}},
    )
    kin = solve(m, "acceleration")
    B, C, E = (np.array(kin.positions[n]) for n in "BCE")
    e = (C - B) / np.hypot(*(C - B))
    assert pytest.approx(B + 0.05 * e + 0.03 * np.array([-e[1], e[0]]), abs=1e-14) == E
    w, al = kin.links["coupler"].omega, kin.links["coupler"].alpha
    for p, q in (("B", "C"), ("C", "E"), ("B", "E")):
        r = np.array(kin.positions[p]) - np.array(kin.positions[q])
        vpq = np.array(kin.relative_velocity(p, q))
        assert vpq == pytest.approx(w * np.array([-r[1], r[0]]), abs=1e-12)
        apq = np.array(kin.relative_acceleration(p, q))
        assert apq == pytest.approx(al * np.array([-r[1], r[0]]) - w * w * r, abs=1e-10)
        assert float(vpq @ r) == pytest.approx(0.0, abs=1e-13)  # ab ⟂ AB


def test_one_degree_from_toggle_is_accurate_and_exact_toggle_refused():
    # Triple rocker a = b = c = 0.1, d = 0.25: the crank's limit is where coupler and rocker line up.
    lim = math.acos(0.65)
    th = lim - math.radians(1)
    kin = solve(four_bar(a=0.1, b=0.1, c=0.1, d=0.25, angle=th, omega=1.0), "acceleration")
    _, _w3, w4, a3, _a4 = closed_form(0.1, 0.1, 0.1, 0.25, th, 1.0)
    assert kin.links["rocker"].omega == pytest.approx(w4, rel=1e-9)
    assert kin.links["coupler"].alpha == pytest.approx(a3, rel=1e-8)
    with pytest.raises(GeometryError, match=r"coupler and rocker are in line.*condition number"):
        solve(four_bar(a=0.1, b=0.1, c=0.1, d=0.25, angle=lim, omega=1.0), "velocity")
    # Positions at the toggle are fine.
    assert solve(four_bar(a=0.1, b=0.1, c=0.1, d=0.25, angle=lim, omega=1.0), "position")


def test_unassemblable_angle_reports_the_gap_in_file_units():
    m = four_bar(a=0.1, b=0.1, c=0.1, d=0.25, angle=math.radians(90), unit="mm")
    with pytest.raises(GeometryError, match=r"B–C–D cannot close.*269\.258 mm.*gap 69\.2582 mm"):
        solve(m, "position")


def test_moving_past_a_limit_is_refused_with_where_it_locks():
    m = four_bar(a=0.1, b=0.1, c=0.1, d=0.25, angle=0.3, omega=1.0, unit="mm")
    with pytest.raises(GeometryError, match=r"locks near 49\.4584°.*|open by .* mm"):
        solve(m, "velocity", SolveOptions(angle=1.0))


def test_drawn_joint_disagreeing_with_a_length_says_by_how_much():
    m = build(
        ["frame", "crank", "coupler", "rocker"],
        {
            "A": {"links": ["frame", "crank"], "at": (0, 0)},
            "B": {"links": ["crank", "coupler"], "at": (0.02, 0.034641016)},
            "C": {"links": ["coupler", "rocker"], "at": (0.16, 0.08)},
            "D": {"links": ["rocker", "frame"], "at": (0.15, 0)},
        },
        lengths={"A-B": 0.04, "B-C": 0.15},
        drive={"link": "crank", "angle": math.radians(61), "omega": 1.0},
        length_unit="mm",
    )
    with pytest.raises(InputError) as err:
        solve(m)
    text = str(err.value)
    assert (
        "length BC = 150 mm but the drawing gives 147.165 mm (off by 2.83534 mm)" in text
    )  # hypot(140, 45.359)
    assert "drive angle 61° but the drawing gives 60" in text


def test_fully_drawn_fourbar_needs_no_lengths():
    C, _, w4, _, _ = closed_form(0.04, 0.15, 0.08, 0.15, math.radians(60), 2.0)
    m = build(
        ["frame", "crank", "coupler", "rocker"],
        {
            "A": {"links": ["frame", "crank"], "at": (0, 0)},
            "B": {"links": ["crank", "coupler"], "at": (0.02, 0.04 * math.sin(math.radians(60)))},
            "C": {"links": ["coupler", "rocker"], "at": tuple(C)},
            "D": {"links": ["rocker", "frame"], "at": (0.15, 0)},
        },
        drive={"link": "crank", "omega": 2.0},
    )
    kin = solve(m)
    assert kin.links["rocker"].omega == pytest.approx(w4, rel=1e-10)
    assert kin.drives[0].angle == pytest.approx(math.radians(60))


def test_point_left_free_is_named():
    m = build(
        ["frame", "crank", "coupler", "rocker"],
        {
            "A": {"links": ["frame", "crank"], "at": (0, 0)},
            "B": {"links": ["crank", "coupler"]},
            "C": {"links": ["coupler", "rocker"]},
            "D": {"links": ["rocker", "frame"], "at": (0.15, 0)},
        },
        lengths={"A-B": 0.04, "B-C": 0.15, "C-D": 0.08},
        drive={"link": "crank", "omega": 2.0},
    )
    with pytest.raises(GeometryError, match=r"does not fix where .*B") as err:
        solve(m)
    assert "angle" in (err.value.hint or "")
    # --angle supplies what the file lacks.
    assert solve(m, options=SolveOptions(angle=1.0)).positions["B"][0] == pytest.approx(0.04 * math.cos(1.0))


def test_size_is_largest_joint_distance():
    kin = solve(four_bar(), "position")
    pts = np.array(list(kin.positions.values()))
    assert kin.size == pytest.approx(max(np.hypot(*(p - q)) for p in pts for q in pts))
