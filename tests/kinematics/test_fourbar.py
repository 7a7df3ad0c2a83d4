"""Four-bar chain against the vector-loop closed form (tests/oracles/four_bar.py, not the solver's method)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from builders import build, four_bar

from cli_runner import assert_bad_input, close, mech, no_traceback, points, strict_json
from mech.errors import GeometryError, InputError
from mech.kinematics import solve
from mech.options import SolveOptions
from mechanism_texts import FOUR_BAR_PARALLELOGRAM
from oracles.four_bar import four_bar as closed_form

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


# -- through mech velocity/position --json (cli_runner: tracebacks shown) ---------------------
# AB = BC = CD = 1, AD = 2: coupler and rocker fall in line (a toggle) where |BD| = 2, cos θ = 1/4.
EQUAL_LINKS_TOGGLE = """\
links: [frame, crank, coupler, rocker]
joints:
  A: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  B: {{type: revolute, links: [crank, coupler]}}
  C: {{type: revolute, links: [coupler, rocker], near: [1.1, 0.5]}}
  D: {{type: revolute, links: [rocker, frame], at: [2, 0]}}
lengths: {{AB: 1, BC: 1, CD: 1}}
drive: {{link: crank, angle: {angle}, omega: 10}}
"""


def test_parallelogram_coupler_translates_and_rocker_turns_with_the_crank(write):
    """B = 0.5 (cos 60, sin 60), v_B = ω k×B; C = B + (1, 0) moves with B."""
    f = write(FOUR_BAR_PARALLELOGRAM)
    p = mech("velocity", "--json", str(f))
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    assert abs(d["links"]["coupler"]["omega"]) <= 1e-12 * 10
    assert close(d["links"]["rocker"]["omega"], 10.0)
    pts = points(d)
    vb = (-10 * 0.5 * math.sin(math.radians(60)), 10 * 0.5 * math.cos(math.radians(60)))
    for name in ("B", "C"):
        assert close(pts[name]["velocity"][0], vb[0])
        assert close(pts[name]["velocity"][1], vb[1])


def test_velocities_exactly_at_a_toggle_are_refused_as_singular(write):
    """At cos θ = 1/4 exactly: exit 2 naming the singular toggle, nothing on stdout."""
    f = write(EQUAL_LINKS_TOGGLE.format(angle=60))
    p = mech("velocity", "--json", str(f), "--angle", repr(math.degrees(math.acos(0.25))))
    assert_bad_input(p, located=False)
    assert "singular configuration" in p.stderr and "toggle" in p.stderr
    assert p.stdout == ""


def test_a_file_drawn_at_a_toggle_is_refused_at_its_drive_s_line(write):
    """The same toggle, cos θ = 1/4, as the file's own drive angle: the refusal points at it."""
    f = write(EQUAL_LINKS_TOGGLE.format(angle=repr(math.degrees(math.acos(0.25)))))
    p = mech("velocity", str(f))
    assert_bad_input(p, f)
    assert f"{f}:8:" in p.stderr and "singular configuration" in p.stderr


@pytest.mark.parametrize("angle", ["0", "180"])
def test_parallelogram_folded_flat_is_refused(write, angle):
    """All four links on one line: the velocities are undetermined (once a ZeroDivisionError)."""
    f = write(FOUR_BAR_PARALLELOGRAM)
    p = mech("velocity", "--json", str(f), "--angle", angle)
    assert_bad_input(p, located=False)
    assert p.stdout == ""


def test_velocity_near_a_toggle_after_continuation_matches_the_closed_form_branch(write):
    """1.4e-8 deg short of the toggle, ω_coupler to 1e-6 of the loop (once 4.2e-5 off).

    The branch is the file's: at the drawn 60 deg, ``near: [1.1, 0.5]`` is closer to the
    assembly right of B→D (C = (1, 0)) than to the left one, and continuation keeps it.
    """
    th0, th = math.radians(60), math.radians(75.5224878)
    branches = {up: closed_form(1, 1, 1, 2, th0, 10.0, upper=up)[0] for up in (True, False)}
    upper = min(branches, key=lambda up: math.dist(branches[up], (1.1, 0.5)))
    assert upper is False
    C, w3, _w4, _, _ = closed_form(1, 1, 1, 2, th, 10.0, upper=upper)
    f = write(EQUAL_LINKS_TOGGLE.format(angle=60))
    p = mech("velocity", "--json", str(f), "--angle", "75.5224878")
    no_traceback(p)
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    assert abs(d["links"]["coupler"]["omega"] - w3) <= 1e-6 * abs(w3), (d["links"]["coupler"], w3)
    assert math.dist(points(d)["C"]["position"], C) <= 1e-6


def test_a_file_drawn_at_the_toggle_assembles_at_other_angles(write):
    """Drive angle exactly the toggle; --angle 70 (|BD|² = 5 - 4 cos 70 < 4) puts C 1 from B and D."""
    toggle = math.degrees(math.acos(0.25))
    f = write(EQUAL_LINKS_TOGGLE.format(angle=repr(toggle)))
    assert mech("position", str(f)).returncode == 0  # the toggle itself has a position
    p = mech("position", "--json", str(f), "--angle", "70")
    assert p.returncode == 0, p.stderr
    pts = points(strict_json(p.stdout))
    b, c = pts["B"]["position"], pts["C"]["position"]
    assert math.degrees(math.atan2(b[1], b[0])) == pytest.approx(70, abs=1e-9)
    assert math.dist(b, c) == pytest.approx(1, rel=1e-9)
    assert math.dist(c, (2, 0)) == pytest.approx(1, rel=1e-9)


NON_GRASHOF = """\
units: {length: mm, angle: deg}
links: [frame, input, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, input], at: [0, 0]}
  B: {type: revolute, links: [input, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [100, 60]}
  D: {type: revolute, links: [rocker, frame], at: [120, 0]}
lengths: {AB: 80, BC: 60, CD: 70}
drive: {link: input, angle: 60, rpm: 60, direction: ccw}
"""


def test_a_solve_next_to_a_toggle_names_it_its_angle_and_how_fast_omega_grows(write):
    # AD = 120, AB = 80, BC = 60, CD = 70 (non-Grashof): the input stops where BC and CD are in
    # line, |BD| = 130: cos θ = (80² + 120² − 130²) / (2·80·120) = 0.203125, θ = 78.2802° (issue 21.6)
    from mech.loader import load

    m = load(write(NON_GRASHOF))
    toggle = math.acos(3900 / 19200)
    delta = math.radians(5e-4)

    def omegas(theta: float) -> tuple[float, float]:
        """ω of coupler and rocker by central differences of the closed-form position (ω_input = 2π)."""

        def angles(t: float) -> tuple[float, float]:
            b = (0.080 * math.cos(t), 0.080 * math.sin(t))
            d = math.dist(b, (0.120, 0.0))
            base = math.atan2(-b[1], 0.120 - b[0])
            at_b = math.acos((0.060**2 + d * d - 0.070**2) / (2 * 0.060 * d))
            c = (b[0] + 0.060 * math.cos(base + at_b), b[1] + 0.060 * math.sin(base + at_b))
            return math.atan2(c[1] - b[1], c[0] - b[0]), math.atan2(c[1], c[0] - 0.120)

        h = 1e-9
        (c1, r1), (c2, r2) = angles(theta + h), angles(theta - h)
        return 2 * math.pi * (c1 - c2) / (2 * h), 2 * math.pi * (r1 - r2) / (2 * h)

    kin = solve(m, "velocity", SolveOptions(angle=toggle - delta))
    (note,) = [n for n in kin.notes if "from the toggle" in n]
    assert "0.0005° from the toggle at 78.2802°" in note
    w_coupler, w_rocker = omegas(toggle - delta)
    assert kin.links["coupler"].omega == pytest.approx(w_coupler, rel=1e-4)
    assert kin.links["rocker"].omega == pytest.approx(w_rocker, rel=1e-4)
    # the fastest link is named with its ω and the coefficient of 1/√Δθ
    assert "ω of coupler grows as 1/√Δθ" in note
    assert f"{abs(w_coupler) * math.sqrt(delta):.3g}" in note
    # far from it, nothing is said
    assert not [n for n in solve(m, "velocity").notes if "toggle" in n]


def test_the_general_route_next_to_a_toggle_says_which_links_are_how_far_from_in_line(write):
    # the same toggle at 78.2802°, solved by Newton: 0.001° of input short of it, |BD| by the cosine
    # rule, and how far BC and CD are from in line at C by the cosine rule on triangle BCD
    from mech.loader import load

    m = load(write(NON_GRASHOF))
    theta = math.acos(3900 / 19200) - math.radians(0.001)
    bd = math.sqrt(80**2 + 120**2 - 2 * 80 * 120 * math.cos(theta))
    off = 180 - math.degrees(math.acos((60**2 + 70**2 - bd**2) / (2 * 60 * 70)))
    kin = solve(m, "velocity", SolveOptions(angle=theta, method="newton"))
    (note,) = [n for n in kin.notes if "toggle" in n]
    assert f"coupler and rocker are {off:.3g}° from in line at C" in note
    # the closed form says it too, its own way: the same solve, the same instant
    (closed,) = [n for n in solve(m, "velocity", SolveOptions(angle=theta)).notes if "toggle" in n]
    assert "0.001° from the toggle at 78.2802°" in closed
    # far from it, neither route says anything
    assert not [n for n in solve(m, "velocity", SolveOptions(method="newton")).notes if "toggle" in n]
