"""The closed-form (dyad) path against the general Newton solver, on every shipped example that decomposes."""

from __future__ import annotations

import importlib
import math
from pathlib import Path

import numpy as np
import pytest
from builders import four_bar, slider_crank

import mech
from mech.errors import GeometryError, UnsupportedError
from mech.kinematics import closed_form, solve
from mech.options import SolveOptions
from mechanism_texts import FOLDING_INVERSOR, ladder
from oracles.inversor import inversor_p

ROOT = Path(__file__).resolve().parents[2]
DECOMPOSE = [
    "beer_johnston_engine",
    "crank_slotted_lever",
    "crank_slotted_lever_quick_return",
    "four_bar",
    "khurmi_four_bar_acceleration",
    "khurmi_six_link_slider",
    "khurmi_slider_crank_cg",
    "offset_slider_crank",
    "slider_crank",
    "steam_engine_piston",
    "stephenson_six_bar",
    "watt_six_bar",
    "whitworth_quick_return",
]


def _scales(kin):
    v = max((math.hypot(*kin.velocity(p)) for p in kin.positions), default=1.0) or 1.0
    a = max((math.hypot(*kin.acceleration(p)) for p in kin.positions), default=1.0) or 1.0
    return kin.size, v, a


@pytest.mark.parametrize("name", DECOMPOSE)
def test_closed_form_and_newton_agree_on_examples(name):
    m = mech.load(ROOT / "mechanisms" / f"{name}.yaml")
    assert closed_form(m) is not None, "this example decomposes into dyads"
    for deg in (3.0, 47.0, 101.0, 178.0, 222.0, 305.0):
        opts = SolveOptions(angle=math.radians(deg))
        try:
            ref = solve(m, "acceleration", opts.with_(method="newton"))
        except GeometryError:
            with pytest.raises(GeometryError):
                solve(m, "acceleration", opts)  # the closed form must not land where Newton cannot go
            continue
        fast = solve(m, "acceleration", opts.with_(method="closed"))
        size, vs, as_ = _scales(ref)
        for p in ref.positions:
            assert math.dist(fast.positions[p], ref.positions[p]) <= 1e-9 * size, p
            assert math.dist(fast.velocity(p), ref.velocity(p)) <= 1e-9 * vs, p
            assert math.dist(fast.acceleration(p), ref.acceleration(p)) <= 1e-9 * as_, p
        for lk, st in ref.links.items():
            w = max(abs(s.omega) for s in ref.links.values())
            assert fast.links[lk].omega == pytest.approx(st.omega, abs=1e-9 * w)


def test_lean_state_matches_the_full_result():
    m = four_bar(angle=math.radians(60), omega=-4 * math.pi)
    prog = closed_form(m)
    kin = solve(m, "acceleration", SolveOptions(angle=math.radians(130)))
    st = prog.state(math.radians(130), -4 * math.pi, 0.0)
    assert st.position("C") == pytest.approx(kin.positions["C"], abs=1e-12)
    assert st.velocity("C") == pytest.approx(kin.velocity("C"), rel=1e-10)
    assert st.acceleration("C") == pytest.approx(kin.acceleration("C"), rel=1e-10)
    assert st.omega[prog.links.index("rocker")] == pytest.approx(kin.links["rocker"].omega, rel=1e-10)


def test_lean_state_refuses_an_angle_where_the_loop_cannot_close():
    m = four_bar(a=0.1, b=0.1, c=0.05, d=0.15, angle=math.radians(30), omega=1.0)  # crank cannot turn fully
    prog = closed_form(m)
    with pytest.raises(ValueError, match="cannot close"):
        prog.state(math.radians(180), 1.0)


def test_chains_that_do_not_decompose_fall_back_to_newton():
    m = mech.load(ROOT / "mechanisms" / "double_parallelogram.yaml")  # the redundant link flips branch sign
    assert closed_form(m) is None
    kin = solve(m, "velocity", SolveOptions(angle=math.radians(75)))
    assert any("continuation" in n for n in kin.notes)
    with pytest.raises(UnsupportedError, match="does not decompose"):
        solve(m, "velocity", SolveOptions(angle=math.radians(75), method="closed"))


def test_closed_form_keeps_the_branch_of_the_drawing():
    up = solve(slider_crank(), "velocity", SolveOptions(angle=math.radians(200)))
    assert up.positions["B"][0] > 0  # the slider stays ahead of the crank, as drawn
    assert any("closed form" in n for n in up.notes)


# -- the drawn angle: the same closed-form route (issue 20.4) ------------------------------------


@pytest.mark.parametrize("name", DECOMPOSE)
def test_the_drawn_angle_is_solved_in_closed_form_with_the_general_route_s_answer(name, monkeypatch):
    # the file's own drive angle takes the dyads as any other angle does: the general route's rate
    # solve is never reached, and every number (and every exact zero) is Newton's to 1e-9
    m = mech.load(ROOT / "mechanisms" / f"{name}.yaml")
    ref = solve(m, "acceleration", SolveOptions(method="newton"))

    def general(*args, **kwargs):
        raise AssertionError("the drawn angle went through the general route")

    monkeypatch.setattr(importlib.import_module("mech.kinematics.solve"), "rates", general)
    kin = solve(m, "acceleration")
    size, vs, as_ = _scales(ref)
    for p in ref.positions:
        assert math.dist(kin.positions[p], ref.positions[p]) <= 1e-9 * size, p
        assert math.dist(kin.velocity(p), ref.velocity(p)) <= 1e-9 * vs, p
        assert math.dist(kin.acceleration(p), ref.acceleration(p)) <= 1e-9 * as_, p
        assert (kin.velocity(p) == (0.0, 0.0)) == (ref.velocity(p) == (0.0, 0.0)), p
        assert (kin.acceleration(p) == (0.0, 0.0)) == (ref.acceleration(p) == (0.0, 0.0)), p
    assert kin.notes == ref.notes  # nothing moved: no note of the route


@pytest.mark.parametrize("deg", [60.0, 97.0, 200.0])
def test_a_ground_pivot_moves_at_exactly_zero_in_closed_form_at_any_angle(deg):
    # the rocker's pivot D, reached round the loop from C, came out at 1e-16 m/s (a direction
    # printed for a point at rest); the rates are refined once against Φ_q, as Newton's are
    kin = solve(
        four_bar(angle=math.radians(60), omega=-4 * math.pi),
        "acceleration",
        SolveOptions(angle=math.radians(deg)),
    )
    assert kin.velocity("D") == (0.0, 0.0) and kin.acceleration("D") == (0.0, 0.0)
    assert kin.links["rocker"].velocity == (0.0, 0.0)


def test_the_drawn_configuration_is_judged_once_per_mechanism(monkeypatch):
    # the toggle test and the SVD the drawn rates are solved and bounded with belong to the
    # mechanism: after the first solve, no solve at the drawn angle takes another SVD (by either route)
    m = mech.load(ROOT / "mechanisms" / "four_bar.yaml")
    for method in ("auto", "newton"):
        assert solve(m, "acceleration", SolveOptions(method=method)).links
    calls = []
    svd = np.linalg.svd
    monkeypatch.setattr(np.linalg, "svd", lambda *a, **k: calls.append(1) or svd(*a, **k))
    for _ in range(3):
        for method in ("auto", "newton"):
            assert solve(m, "acceleration", SolveOptions(method=method)).links
    assert calls == []


def test_a_large_chain_s_drawn_angle_is_solved_without_generating_its_closed_form(monkeypatch):
    # 41 moving links: generating and compiling the program would cost far more than the drawn
    # solve it replaces; a moved angle still takes it
    m = mech.loads(ladder(20), path="ladder.yaml")

    def no_program(*args, **kwargs):
        raise AssertionError("the closed form was generated for the drawn angle")

    monkeypatch.setattr(importlib.import_module("mech.kinematics.solve"), "program", no_program)
    assert solve(m, "velocity").links["crank"].omega == pytest.approx(2 * math.pi)
    with pytest.raises(AssertionError, match="generated"):
        solve(m, "velocity", SolveOptions(angle=1.0))


# -- change points in single solves --------------------------------------------------------------
# The Peaucellier–Lipkin inversor (derivation in tests/oracles/inversor.py): P runs on
# x = 1.28 with OP = 1.28 / cos(θ/2); the rhombus folds flat (P = C) at θ* = 2 acos(0.8) = 73.74°.


def _inversor_p(deg: float) -> tuple[float, float, float]:
    """P.x, P.y and v_P.y (ω = 1) on the inversor line (tests/oracles/inversor.py)."""
    y, dy = inversor_p(math.radians(deg))
    return 1.28, float(y), float(dy)


@pytest.mark.parametrize("method", ["auto", "newton"])
@pytest.mark.parametrize("deg", [40.0, 60.0, 73.0, 75.0, 80.0, 120.0])
def test_an_angle_past_a_change_point_is_reached_on_the_inversor_branch(deg, method):
    kin = solve(
        mech.loads(FOLDING_INVERSOR), "velocity", SolveOptions(angle=math.radians(deg), method=method)
    )
    x, y, vy = _inversor_p(deg)
    assert kin.positions["P"] == pytest.approx((x, y), abs=1e-9)  # not P = C (1.1736, 0.9848 at 80°)
    assert kin.velocity("P") == pytest.approx((0.0, vy), abs=1e-7)


def test_a_solve_past_a_change_point_says_it_passed_one():
    kin = solve(mech.loads(FOLDING_INVERSOR), "position", SolveOptions(angle=math.radians(80.0)))
    note = next(n for n in kin.notes if "change point" in n)
    assert "passed a change point at 73.739795° (P meets C" in note
    assert "continuous tangent" in note
    before = solve(mech.loads(FOLDING_INVERSOR), "position", SolveOptions(angle=math.radians(70.0)))
    assert not any("change point" in n for n in before.notes)


def test_change_point_of_the_inversor_is_located_where_the_rhombus_folds():
    from mech.kinematics.dyads import change_points

    prog = closed_form(mech.loads(FOLDING_INVERSOR))
    found = [(prog.dyads[c.dyad][1], math.degrees(prog.drawn_angle + c.offset)) for c in change_points(prog)]
    # θ* and its mirror 360° − θ* (C below the axis), where the arms fold the other way
    assert found == [
        ("P", pytest.approx(math.degrees(2 * math.acos(0.8)), abs=1e-6)),
        ("P", pytest.approx(360.0 - math.degrees(2 * math.acos(0.8)), abs=1e-6)),
    ]


@pytest.mark.parametrize("name", DECOMPOSE)
def test_shipped_examples_have_no_change_point(name):
    from mech.kinematics.dyads import change_points

    prog = closed_form(mech.load(ROOT / "mechanisms" / f"{name}.yaml"))
    assert change_points(prog) == ()


def test_velocity_at_the_change_point_itself_is_refused_naming_it():
    # at θ* both branches meet: P's velocity is undetermined by the loop (singular rows), so the
    # solve refuses it, and says it is a change point rather than a limit
    with pytest.raises(GeometryError, match="a change point, P meets C: two branches meet"):
        solve(mech.loads(FOLDING_INVERSOR), "velocity", SolveOptions(angle=2 * math.acos(0.8)))


def test_newton_continuation_past_a_change_point_says_it_passed_one():
    # Newton's predictor follows the tangent (P stays on x = 1.28); the sign of det Φ_q changes
    # where the two branches meet, bisected to about √tol: θ* = 2 acos(0.8) within 1e-5°
    kin = solve(
        mech.loads(FOLDING_INVERSOR), "position", SolveOptions(angle=math.radians(80.0), method="newton")
    )
    assert kin.positions["P"] == pytest.approx(_inversor_p(80.0)[:2], abs=1e-9)
    (note,) = [n for n in kin.notes if "change point" in n]
    at = float(note.split("change point at ")[1].split("°")[0])
    assert at == pytest.approx(math.degrees(2 * math.acos(0.8)), abs=1e-5)
    assert "continuous tangent" in note


@pytest.mark.parametrize("angle", ["180.000000001", "-179.999999999", "0.000000001", "359.999999999"])
def test_a_crank_drawn_next_to_a_dead_centre_is_placed_to_its_angles_own_precision(angle):
    # The crank pin is r (cos θ, sin θ) of the angle as read: its tiny offset from the line of
    # stroke (r sin θ ≈ 2.6e-12 m here) to the last bits, whatever branch of ±π atan2 would
    # give the drawn crank (its frame is the drive's angle, not θ ± 2π rounded).
    text = Path(__file__).resolve().parents[2].joinpath("mechanisms", "slider_crank.yaml").read_text()
    text = text.split("answers:")[0].replace("angle: 135, rpm", f"angle: {angle}, rpm")
    m = mech.loads(text)
    th = m.drives[0].angle
    assert th is not None
    r = 0.15  # OA of mechanisms/slider_crank.yaml
    for kin in (solve(m, "velocity"), solve(m, "velocity", SolveOptions(angle=th))):
        x, y = kin.positions["A"]
        assert y == pytest.approx(r * math.sin(th), rel=1e-12, abs=0)
        assert x == pytest.approx(r * math.cos(th), rel=1e-15)


# -- the other assembly branch: a dyad closed the other way (SolveOptions.flipped) ----------------


def test_the_other_branch_of_a_slider_crank_puts_the_slider_behind_the_crank():
    # x_B = r cos θ + s·√(l² − r² sin² θ), s = −1 on the other side of the crank pin; differentiated
    # in time (θ̇ = ω): ẋ_B = −rω sin θ − s·r²ω sin θ cos θ / √(…); ẍ_B by a central difference of ẋ_B.
    r, rod, w = 0.1, 0.4, 20 * math.pi

    def x_b(th: float) -> float:
        return r * math.cos(th) - math.sqrt(rod**2 - (r * math.sin(th)) ** 2)

    def v_b(th: float) -> float:
        root = math.sqrt(rod**2 - (r * math.sin(th)) ** 2)
        return -r * w * math.sin(th) + r * r * w * math.sin(th) * math.cos(th) / root

    m = slider_crank(r=r, rod=rod, omega=w)
    for deg in (45.0, 160.0):
        th, h = math.radians(deg), 1e-5
        kin = solve(m, "acceleration", SolveOptions(angle=th, flipped=("B",)))
        assert kin.positions["B"][0] == pytest.approx(x_b(th), rel=1e-12)
        assert kin.velocity("B")[0] == pytest.approx(v_b(th), rel=1e-10)
        assert kin.acceleration("B")[0] == pytest.approx((v_b(th + h) - v_b(th - h)) / (2 * h) * w, rel=1e-6)
        assert any("other assembly branch" in n for n in kin.notes)
    assert solve(m, "position").positions["B"][0] > 0  # the drawn side is untouched


def test_the_other_branch_of_a_four_bar_is_the_rocker_pin_mirrored_in_bd():
    # AB = 0.04 at 60°, BC = 0.15, CD = 0.08, AD = 0.15 m: C is where the circles (B, BC) and
    # (D, CD) meet, the two points mirror images in BD; the drawing takes one, flipped the other.
    # Then ω₃, ω₄ by the vector loop v_B + ω₃ k×(C − B) = ω₄ k×(C − D), v_B = ω₂ k×B, ω₂ = −4π.
    m = four_bar()
    drawn = solve(m, "velocity")
    other = solve(m, "velocity", SolveOptions(flipped=("C",)))
    b = 0.04 * np.array([math.cos(math.radians(60)), math.sin(math.radians(60))])
    d = np.array([0.15, 0.0])
    dist = float(np.linalg.norm(d - b))
    along = (0.15**2 - 0.08**2 + dist**2) / (2 * dist)
    u = (d - b) / dist
    foot, off = b + along * u, math.sqrt(0.15**2 - along**2) * np.array([-u[1], u[0]])
    both = [foot + off, foot - off]
    drawn_c = np.array(drawn.positions["C"])
    mirror = max(both, key=lambda p: float(np.linalg.norm(p - drawn_c)))  # the one not drawn
    assert min(float(np.linalg.norm(p - drawn_c)) for p in both) <= 1e-12
    assert np.allclose(other.positions["C"], mirror, rtol=0, atol=1e-12)
    assert np.allclose(other.positions["B"], b, rtol=0, atol=1e-15)

    def kx(w: float, r: np.ndarray) -> np.ndarray:
        return np.array([-w * r[1], w * r[0]])

    w2 = -4 * math.pi
    _w3, w4 = np.linalg.solve(np.column_stack([kx(1.0, mirror - b), -kx(1.0, mirror - d)]), -kx(w2, b))
    assert other.links["rocker"].omega == pytest.approx(w4, rel=1e-9)
    assert math.dist(other.velocity("C"), kx(w4, mirror - d)) <= 1e-9 * abs(w4) * 0.08


def test_another_side_that_breaks_the_redundant_link_is_refused():
    # the double parallelogram's third coupler holds only on the drawn branch: with C flipped the
    # dyads close but its length row does not
    m = mech.load(ROOT / "mechanisms" / "double_parallelogram.yaml")
    with pytest.raises(GeometryError, match="other assembly branch"):
        solve(m, "velocity", SolveOptions(flipped=("C",)))


def test_a_point_no_dyad_places_has_no_flipped_side():
    with pytest.raises(UnsupportedError, match=r"no dyad .* places A"):
        solve(slider_crank(), "velocity", SolveOptions(flipped=("A",)))


def test_a_sweep_and_a_continuation_refuse_a_flipped_side_rather_than_sweep_the_drawn_one():
    from mech.kinematics import sweep
    from mech.kinematics.solve import continuation

    options = SolveOptions(flipped=("B",))
    with pytest.raises(UnsupportedError, match="one instant"):
        sweep(slider_crank(), np.radians([0.0, 90.0]), options=options)
    with pytest.raises(UnsupportedError, match="one instant"):
        list(continuation(slider_crank(), [0.0, 0.5], "velocity", options))
