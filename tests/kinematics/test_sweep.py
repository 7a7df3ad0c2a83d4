"""Sweeps: extremes, dead centres, toggles and time ratios against closed forms derived here.

The references are the textbook's geometry, worked in tests/oracles (not taken
from mech): the slider's travel from the collinear crank-and-rod triangles,
the rocker's extreme angles from the law of cosines, the limit of a crank
that cannot turn fully from |BD| = b + c, and extremes of speeds by mpmath
root-finding on the derivative of the closed-form velocity (30 digits).
"""

from __future__ import annotations

import math
from pathlib import Path

import mpmath
import numpy as np
import pytest
from builders import four_bar, slider_crank
from hypothesis import given, settings
from hypothesis import strategies as st

import mech
from mech.errors import InputError, UnsupportedError
from mech.kinematics import sweep
from mech.options import SolveOptions
from mechanism_texts import FOLDING_INVERSOR, ROLLER_CAM
from oracles.four_bar import rocker_angle
from oracles.inversor import FOLD, inversor_p
from oracles.slider_crank import slider_dead_centres, slider_x

FAST = settings(max_examples=15, deadline=None)
FULL = np.radians(np.linspace(0.0, 360.0, 361))


# -- closed forms ------------------------------------------------------------------------------
def speed_extreme(f, guess):
    """(θ, f(θ)) where f'(θ) = 0 near ``guess``: mpmath root of the derivative, 30 digits."""
    with mpmath.workdps(30):
        th = mpmath.findroot(lambda t: mpmath.diff(f, t), guess)
        return float(th), float(f(th))


# -- slider crank ---------------------------------------------------------------------------------
@pytest.mark.parametrize("e", [0.0, 0.03, -0.05])
def test_slider_crank_travel_dead_centres_and_time_ratio(e):
    r, rod = 0.1, 0.4
    s = sweep(slider_crank(r=r, rod=rod, e=e, omega=10.0), FULL, level="acceleration")
    outer, inner, x_max, x_min = slider_dead_centres(r, rod, e)
    ext = {x.quantity: x for x in s.extremes}
    # displacement is measured from the path's through point (0, e) along +x
    d = ext["displacement.P"]
    assert d.max_value == pytest.approx(x_max, rel=1e-12)
    assert d.min_value == pytest.approx(x_min, rel=1e-12)
    angles = sorted(x.angle % (2 * math.pi) for x in s.dead_centres if x.subject == "P")
    assert angles == pytest.approx(sorted([outer % (2 * math.pi), inner]), abs=1e-12)
    beta = (inner - outer) % (2 * math.pi)
    ratio = max(beta, 2 * math.pi - beta) / min(beta, 2 * math.pi - beta)
    if e == 0.0:
        assert s.time_ratio.ratio == pytest.approx(1.0, abs=1e-12)
    else:
        assert s.time_ratio.ratio == pytest.approx(ratio, rel=1e-12)


def test_slider_crank_peak_speed_matches_the_closed_form():
    r, rod, e, w = 0.1, 0.4, 0.02, 10.0
    s = sweep(slider_crank(r=r, rod=rod, e=e, omega=w), FULL, level="velocity", quantities=["sliding.P"])
    (x,) = s.extremes
    v = lambda th: w * mpmath.diff(lambda t: slider_x(r, rod, e, t), th)  # noqa: E731
    th_max, v_max = speed_extreme(v, x.max_angle)
    th_min, v_min = speed_extreme(v, x.min_angle)
    assert x.max_value == pytest.approx(v_max, rel=1e-11)
    assert x.min_value == pytest.approx(v_min, rel=1e-11)
    assert x.max_angle == pytest.approx(th_max, abs=1e-6)
    assert x.min_angle == pytest.approx(th_min, abs=1e-6)


def test_coarse_steps_still_give_exact_extremes():
    """Refinement does not depend on the grid: 12 steps give what 3,600 give."""
    m = slider_crank(r=0.1, rod=0.4, e=0.02, omega=10.0)
    coarse = sweep(m, np.radians(np.linspace(0, 360, 13)), level="velocity", quantities=["sliding.P"])
    fine = sweep(m, np.radians(np.linspace(0, 360, 3601)), level="velocity", quantities=["sliding.P"])
    assert coarse.extremes[0].max_value == pytest.approx(fine.extremes[0].max_value, rel=1e-12)


# -- four-bar ------------------------------------------------------------------------------------
def test_four_bar_rocker_extremes_and_dead_centres_match_the_law_of_cosines():
    a, b, c, d = 0.04, 0.15, 0.08, 0.15
    s = sweep(four_bar(a, b, c, d, omega=-4 * math.pi), FULL, level="acceleration")
    ext = {x.quantity: x for x in s.extremes}

    def rocker_at_collinear(span):  # AC = b ± a: the angle ADC, rocker direction π − ADC (C above)
        return math.pi - math.acos((c * c + d * d - span * span) / (2 * c * d))

    hi, lo = rocker_at_collinear(b + a), rocker_at_collinear(b - a)
    rk = ext["angle.rocker"]
    assert rk.max_value % (2 * math.pi) == pytest.approx(max(hi, lo), rel=1e-12)
    assert rk.min_value % (2 * math.pi) == pytest.approx(min(hi, lo), rel=1e-12)
    # dead centres: crank along AC (extended) or against it (folded)
    dac = lambda span: math.acos((span * span + d * d - c * c) / (2 * span * d))  # noqa: E731
    expected = sorted([dac(b + a), (dac(b - a) + math.pi) % (2 * math.pi)])
    got = sorted(x.angle for x in s.dead_centres if x.subject == "rocker")
    assert got == pytest.approx(expected, abs=1e-12)
    beta = expected[1] - expected[0]
    assert s.time_ratio.ratio == pytest.approx(
        max(beta, 2 * math.pi - beta) / min(beta, 2 * math.pi - beta), rel=1e-12
    )
    # the rocker's fastest turn, against mpmath on the closed-form angle
    w = -4 * math.pi
    om = ext["omega.rocker"]
    f = lambda th: w * mpmath.diff(lambda t: rocker_angle(a, b, c, d, t), th)  # noqa: E731
    assert om.max_value == pytest.approx(speed_extreme(f, om.max_angle)[1], rel=1e-11)
    assert om.min_value == pytest.approx(speed_extreme(f, om.min_angle)[1], rel=1e-11)


def test_crank_that_cannot_turn_reports_the_gap_and_its_toggles():
    a, b, c, d = 0.1, 0.1, 0.05, 0.15  # |BD| reaches b + c = 0.15 before the crank comes round
    s = sweep(four_bar(a, b, c, d, angle=math.radians(30), omega=1.0), FULL, level="velocity")
    limit = math.acos((a * a + d * d - (b + c) ** 2) / (2 * a * d))
    assert len(s.gaps) == 1
    g = s.gaps[0]
    assert g.start == pytest.approx(limit, abs=1e-12)
    assert g.end == pytest.approx(2 * math.pi - limit, abs=1e-12)
    assert [t.angle for t in s.toggles] == pytest.approx([limit, 2 * math.pi - limit], abs=1e-12)
    assert "coupler and rocker in line" in g.what
    inside = (limit < FULL) & (2 * math.pi - limit > FULL)
    assert not s.assembled[inside].any() and s.assembled[~inside].all()
    assert np.isnan(s.positions[inside]).all()


# -- stability at the extremes ----------------------------------------------------------------------
@FAST
@given(eps=st.sampled_from([1e-9, -1e-9, 3e-10]), e=st.sampled_from([0.0, 0.02]))
def test_sweep_within_a_nanoradian_of_a_dead_centre(eps, e):
    r, rod, w = 0.1, 0.4, 10.0
    outer, inner, *_ = slider_dead_centres(r, rod, e)
    phi = np.array([outer - 0.01, outer + eps, inner + eps, inner + 0.01])
    s = sweep(slider_crank(r=r, rod=rod, e=e, omega=w), phi, level="velocity")
    v = s.series("sliding.P")
    for k in (1, 2):
        exact = float(w * mpmath.diff(lambda t: slider_x(r, rod, e, t), mpmath.mpf(phi[k])))
        assert v[k] == pytest.approx(exact, abs=1e-12 * r * w)
    assert s.max_condition < 10


@FAST
@given(eps=st.sampled_from([1e-9, 1e-7, 1e-5]))
def test_sweep_within_a_nanoradian_of_a_toggle_is_answered_to_its_stated_accuracy(eps):
    """Down to 1e-9 rad short of the limit, ω_rocker is given (not refused) and right to 1e-6."""
    a, b, c, d = 0.1, 0.1, 0.05, 0.15
    limit = math.acos((a * a + d * d - (b + c) ** 2) / (2 * a * d))
    phi = np.array([limit - 0.1, limit - eps])
    s = sweep(four_bar(a, b, c, d, angle=math.radians(30), omega=1.0), phi, level="velocity")
    assert s.assembled.all()
    with mpmath.workdps(40):
        th = mpmath.mpf(phi[1])
        exact_w = float(mpmath.diff(lambda t: rocker_angle(a, b, c, d, t), th))
        exact_ang = float(rocker_angle(a, b, c, d, th))
    cond = s.condition[1]
    assert math.remainder(s.series("angle.rocker")[1] - exact_ang, 2 * math.pi) == pytest.approx(0, abs=1e-7)
    w = s.series("omega.rocker")[1]
    assert not math.isnan(w), s.notes
    # the stated accuracy: about 2e-16·cond² relative (velocity rows lose cond, positions another)
    assert w == pytest.approx(exact_w, rel=max(1e-12, 1e-15 * cond * cond))
    assert w == pytest.approx(exact_w, rel=1e-6)


@FAST
@given(ratio=st.sampled_from([1e-6, 1e6]))
def test_extreme_link_ratios(ratio):
    """A crank 1e-6 of the frame, or a rod 1e6 times the crank: travel still 2r to 1e-9 of the size."""
    if ratio < 1:
        r, rod = 1e-6, 1.0
    else:
        r, rod = 1.0, 1e6
    s = sweep(
        slider_crank(r=r, rod=rod, omega=3.0),
        FULL,
        level="velocity",
        quantities=["displacement.P", "sliding.P"],
    )
    d = s.extremes[0]
    assert d.max_value - d.min_value == pytest.approx(2 * r, abs=1e-9 * (r + rod))
    v = s.extremes[1]
    # the peak speed of a very long rod tends to r·ω at θ = 90° (simple harmonic motion)
    assert v.max_value == pytest.approx(3.0 * r, rel=5 * r / rod + 1e-9)


@FAST
@given(rpm=st.floats(min_value=1e-6, max_value=1e6))
def test_series_scale_with_speed_over_twelve_decades(rpm):
    w = rpm * 2 * math.pi / 60
    ref = sweep(four_bar(omega=1.0), FULL, level="acceleration", analyse=False)
    s = sweep(four_bar(omega=w), FULL, level="acceleration", analyse=False)
    np.testing.assert_allclose(s.omegas, w * ref.omegas, rtol=1e-12, atol=1e-14 * w)
    np.testing.assert_allclose(s.accelerations, w * w * ref.accelerations, rtol=1e-12, atol=1e-13 * w * w)


@FAST
@given(offset=st.sampled_from([1e6, -1e6]))
def test_millimetre_links_a_thousand_kilometres_out(offset):
    # The file's D = offset + 15 mm is itself rounded to 1.2e-10 m (the ulp at 1e6 m): the frame
    # the data describe is (offset + d) − offset, exactly, and that is the reference.
    d = (offset + 0.015) - offset
    ref = sweep(four_bar(0.004, 0.015, 0.008, d, omega=2.0), FULL, level="acceleration")
    s = sweep(
        four_bar(0.004, 0.015, 0.008, 0.015, omega=2.0, origin=(offset, offset)), FULL, level="acceleration"
    )
    # Positions are as good as a double at 1e6 m allows (ulp 1.2e-10 m); rates do not see the
    # offset at all: the solver works relative to a ground pivot from assembly on.
    np.testing.assert_allclose(s.positions - offset, ref.positions, atol=3e-10)
    vs, as_ = np.nanmax(np.abs(ref.velocities)), np.nanmax(np.abs(ref.accelerations))
    np.testing.assert_allclose(s.velocities, ref.velocities, rtol=0, atol=1e-12 * vs)
    np.testing.assert_allclose(s.accelerations, ref.accelerations, rtol=0, atol=1e-12 * as_)
    assert [e.angle for e in s.dead_centres] == pytest.approx([e.angle for e in ref.dead_centres], abs=1e-12)


# -- API --------------------------------------------------------------------------------------------
def test_results_are_frozen_and_read_only():
    s = sweep(four_bar(), FULL)
    with pytest.raises(ValueError):
        s.positions[0, 0, 0] = 1.0
    with pytest.raises(AttributeError):
        s.level = "position"  # type: ignore[misc]


def test_newton_sweep_warm_starts_and_agrees_with_the_closed_form():
    phi = np.radians(np.linspace(0, 360, 73))
    m = four_bar(omega=-4 * math.pi)
    fast = sweep(m, phi, level="acceleration")
    slow = sweep(m, phi, level="acceleration", options=SolveOptions(method="newton"))
    assert slow.method == "newton" and fast.method == "closed form"
    np.testing.assert_allclose(slow.positions, fast.positions, atol=1e-12)
    np.testing.assert_allclose(slow.accelerations, fast.accelerations, rtol=1e-9, atol=1e-9)
    assert [e.angle for e in slow.dead_centres] == pytest.approx(
        [e.angle for e in fast.dead_centres], abs=1e-9
    )


def test_sweep_refuses_what_it_cannot_do():
    with pytest.raises(InputError, match="sets the crank angle"):
        sweep(four_bar(), FULL, options=SolveOptions(angle=1.0))
    with pytest.raises(InputError, match="no speed"):
        sweep(four_bar(omega=None), FULL, level="velocity")
    with pytest.raises(InputError, match="unknown quantity"):
        sweep(four_bar(), FULL, quantities=["speed.C"])
    trammel = mech.load(TRAMMEL)  # driven by a slider
    with pytest.raises(UnsupportedError, match="names the drive"):  # angles or positions: it must be said
        sweep(trammel, FULL)
    with pytest.raises(InputError, match="needs its stroke"):  # a slider drive sweeps positions, not angles
        sweep(trammel, drive="PA")
    with pytest.raises(UnsupportedError, match="closed form turns one crank"):
        sweep(trammel, np.linspace(-0.1, 0.1, 5), options=SolveOptions(method="closed"), drive="PA")


PEAUCELLIER = """
name: Peaucellier-Lipkin inversor
units: {length: mm, angle: deg}
links: [frame, crank, arm1, arm2, r1, r2, r3, r4]
joints:
  O: {type: revolute, links: [frame, arm1, arm2], at: [0, 0]}
  Q: {type: revolute, links: [frame, crank], at: [10, 0]}
  C: {type: revolute, links: [crank, r1, r2]}
  A: {type: revolute, links: [arm1, r1, r3], near: [20, 25]}
  B: {type: revolute, links: [arm2, r2, r4], near: [20, -25]}
  D: {type: revolute, links: [r3, r4], near: [40, 0]}
lengths: {QC: 10, OA: 30, OB: 30, AC: 15, BC: 15, AD: 15, BD: 15}
drive: {link: crank, angle: 60, rpm: 60}
"""


@pytest.mark.parametrize("span", [("0", "360"), ("60", "90")])
def test_peaucellier_inversor_sweeps_its_straight_line(span, run, write):
    """C runs on a circle through the fixed pivot O, so D, its inverse (OC·OD = OA² − AC²), runs
    on a straight line: x_D = (30² − 15²) / (2·10) = 33.75 mm.  Past the arms' limit, where both
    rhombus halves fold flat, two dyad apexes coincide exactly: once a ZeroDivisionError."""
    import json

    result = run(
        "sweep",
        str(write(PEAUCELLIER)),
        "--from",
        span[0],
        "--to",
        span[1],
        "--steps",
        "72",
        "--quantity",
        "position.D.x",
        "--json",
    )
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    xs = [x for x in data["series"]["position.D.x"] if x is not None]
    assert len(xs) > 10
    assert xs == pytest.approx([0.03375] * len(xs), rel=1e-12)
    # |OC| = 20 cos(φ/2) must reach OA − AC = 15: the inversor locks at φ = 2 acos(3/4)
    assert data["gaps"][0]["from"] == pytest.approx(math.degrees(2 * math.acos(0.75)), rel=1e-9)


# -- coarse sweeps -----------------------------------------------------------------------------
def four_bar_rocker_dead_centres(a, b, c, d):
    """Crank angles (rad) where the rocker reverses: crank and coupler in line, |AC| = b ± a.

    C lies on the circle of radius c about D = (d, 0), above AD: the angle of AC at A is
    acos((L² + d² − c²) / (2 L d)); extended (L = a + b) the crank points along AC, folded
    (L = b − a) it points the other way.
    """
    ext = math.acos(((a + b) ** 2 + d * d - c * c) / (2 * (a + b) * d))
    fold = math.acos(((b - a) ** 2 + d * d - c * c) / (2 * (b - a) * d)) + math.pi
    return ext, fold


@pytest.mark.parametrize("method", ["auto", "newton"])
def test_two_turns_in_three_steps_find_all_four_dead_centres(method):
    # Khurmi's four-bar (a, b, c, d = 40, 150, 80, 150): 23.68° and 211.29° each turn. Three
    # steps of 240° leave no sign change between two of them; the sweep looks between its steps.
    m = four_bar(0.04, 0.15, 0.08, 0.15, angle=math.radians(60), omega=-4 * math.pi)
    ext, fold = four_bar_rocker_dead_centres(0.04, 0.15, 0.08, 0.15)
    s = sweep(m, np.radians([0.0, 240.0, 480.0, 720.0]), options=SolveOptions(method=method))
    found = sorted(e.angle for e in s.dead_centres if e.subject == "rocker")
    expected = sorted([ext, fold, ext + 2 * math.pi, fold + 2 * math.pi])
    assert found == pytest.approx(expected, abs=1e-8)
    assert s.angles.size == 4 and s.omegas.shape[0] == 4  # the series stays at the steps asked


def test_angles_past_float_precision_are_refused():
    # At 1e308 rad the spacing of floats is 2e292 rad: no crank position is known there.
    m = four_bar(0.04, 0.15, 0.08, 0.15, angle=math.radians(60), omega=-4 * math.pi)
    with pytest.raises(InputError, match="floating point"):
        sweep(m, np.linspace(0.0, 1e308, 11))


def test_steps_over_half_a_turn_beyond_the_budget_are_refused():
    # 10 steps of 1e6° (2,778 turns each): resolving them at 1° would take 1e7 angles.
    m = four_bar(0.04, 0.15, 0.08, 0.15, angle=math.radians(60), omega=-4 * math.pi)
    with pytest.raises(InputError, match="more than half a turn"):
        sweep(m, np.radians(np.linspace(0.0, 1e7, 11)))


def test_steps_too_many_to_resolve_say_events_may_be_missed(monkeypatch):
    import importlib

    grid_module = importlib.import_module("mech.kinematics.sweep_grid")

    # A budget that holds the 5 angles asked but not the 721 of a 1° grid over 0..720°.
    monkeypatch.setattr(grid_module, "MEMORY_BUDGET", 5 * 2000)
    m = four_bar(0.04, 0.15, 0.08, 0.15, angle=math.radians(60), omega=-4 * math.pi)
    s = sweep(m, np.radians(np.linspace(0.0, 720.0, 5)))
    assert any("may be missed" in n for n in s.notes), s.notes


# -- a slider drive, several drives: every drive linear in the sweep's parameter ------------------
ROOT = Path(__file__).resolve().parents[2]
TRAMMEL = ROOT / "mechanisms" / "elliptic_trammel.yaml"
FIVE_BAR = ROOT / "mechanisms" / "five_bar_two_cranks.yaml"


def test_elliptic_trammel_swept_by_its_slider_matches_the_closed_form():
    # A = (s, 0) driven at s' = 0.1 m/s, B = (0, y) with y = sqrt(L² − s²), L = 0.2 m; P on AB
    # p = 0.08 m from A: P = (s(1 − p/L), p y / L), on x²/(L−p)² + y²/p² = 1.  Differentiating:
    # y' = −s s'/y, ω_rod = s'/y (cos φ = −s/L), y'' = −s'² L²/y³, α_rod = −s' y'/y².
    m = mech.load(TRAMMEL)
    big_l, p, sd = 0.2, 0.08, 0.1
    s_ = np.linspace(-0.19, 0.19, 77)
    sw = sweep(m, s_, level="acceleration", drive="PA")
    assert sw.parameter == "position" and sw.drive == "PA" and sw.method == "newton"
    assert sw.assembled.all() and sw.drives[0].rate == pytest.approx(sd)
    y = np.sqrt(big_l**2 - s_**2)
    yd = -s_ * sd / y
    assert np.allclose(sw.series("displacement.PA"), s_, rtol=0, atol=1e-15)
    assert np.allclose(sw.series("position.B.y"), y, rtol=1e-13)
    px, py = sw.series("position.P.x"), sw.series("position.P.y")
    assert np.allclose(px, s_ * (1 - p / big_l), rtol=0, atol=1e-15)
    assert np.allclose(px**2 / (big_l - p) ** 2 + py**2 / p**2, 1.0, rtol=0, atol=1e-13)
    assert np.allclose(sw.series("velocity.B.y"), yd, rtol=1e-12, atol=1e-16)
    assert np.allclose(sw.series("omega.rod"), sd / y, rtol=1e-12)
    assert np.allclose(sw.series("velocity.P.x"), sd * (1 - p / big_l), rtol=1e-12)
    assert np.allclose(sw.series("acceleration.B.y"), -(sd**2) * big_l**2 / y**3, rtol=1e-10)
    assert np.allclose(sw.series("alpha.rod"), -sd * yd / y**2, rtol=1e-10, atol=1e-15)
    # B's guide reverses where A passes the crossing (s = 0): a dead centre, refined between steps
    (dead,) = sw.dead_centres
    assert dead.subject == "PB" and abs(dead.angle) < 1e-12 and dead.value == pytest.approx(big_l, rel=1e-13)
    top = next(e for e in sw.extremes if e.quantity == "displacement.PB")
    assert top.max_value == pytest.approx(big_l, rel=1e-14) and abs(top.max_angle) < 1e-6
    assert sw.time_ratio is None


def test_elliptic_trammel_beyond_the_rods_length_is_a_gap():
    # |s| > L cannot be assembled: the continuation stops at the limit (s = ±L, rod along the guide)
    sw = sweep(mech.load(TRAMMEL), np.linspace(-0.25, 0.25, 51), level="velocity", drive="PA")
    assert np.array_equal(sw.assembled, np.abs(np.linspace(-0.25, 0.25, 51)) <= 0.2 + 1e-12)
    assert any("cannot reach" in n for n in sw.notes)
    # the limits are located between the steps (bisection on reachability): the toggles at s = ±L
    assert [t.angle for t in sw.toggles] == pytest.approx([-0.2, 0.2], rel=0, abs=1e-9)
    edges = [x for g in sw.gaps for x in (g.start, g.end)]
    assert edges == pytest.approx([-0.25, -0.2, 0.2, 0.25], rel=0, abs=1e-9)


def _five_bar_closed_form(t2, t5, w2, w5):
    """C and v_C of the five-bar A=(0,0), E=(0.1,0), AB=ED=0.04, BC=CD=0.08 (m), C left of B→D."""
    a, b, c, e = 0.04, 0.08, 0.08, 0.04
    bx, by = a * np.cos(t2), a * np.sin(t2)
    dx, dy = 0.1 + e * np.cos(t5), e * np.sin(t5)
    ux, uy = dx - bx, dy - by
    d = np.hypot(ux, uy)
    x = (b * b - c * c + d * d) / (2 * d)
    with np.errstate(invalid="ignore"):  # beyond reach (|BD| > BC + CD): NaN
        h = np.sqrt(b * b - x * x)
    cx, cy = bx + (x * ux - h * uy) / d, by + (x * uy + h * ux) / d
    # v_B + ω3 k×(C−B) = v_D + ω4 k×(C−D): two equations for ω3, ω4 (Cramer)
    vbx, vby = -a * w2 * np.sin(t2), a * w2 * np.cos(t2)
    vdx, vdy = -e * w5 * np.sin(t5), e * w5 * np.cos(t5)
    r3x, r3y, r4x, r4y = cx - bx, cy - by, cx - dx, cy - dy
    det = (-r3y) * (-r4x) - r4y * r3x
    w3 = ((vdx - vbx) * (-r4x) - r4y * (vdy - vby)) / det
    return cx, cy, vbx - w3 * r3y, vby + w3 * r3x, d


def test_two_crank_five_bar_sweep_is_one_dyad_at_each_step():
    # drives: link_2 at 90° + p, 10 rad/s ccw (the lead); link_5 at 90° − 2 p, 20 rad/s cw (absolute,
    # DESIGN § 1.1): each step is one RRR dyad on B and D, closed by a circle intersection
    m = mech.load(FIVE_BAR)
    phi = np.radians(np.arange(0.0, 360.5, 2.0))
    sw = sweep(m, phi, level="velocity", quantities=["velocity.C"], drive="link_2")
    assert sw.parameter == "angle" and [law.drive for law in sw.drives] == ["link_2", "link_5"]
    assert sw.drives[1].per_parameter == pytest.approx(-2.0)
    t2, t5 = phi, math.radians(90) - 2 * (phi - math.radians(90))
    cx, cy, vx, vy, d = _five_bar_closed_form(t2, t5, 10.0, -20.0)
    ok = sw.assembled
    k = sw.points.index("C")
    assert np.allclose(sw.positions[ok, k, 0], cx[ok], rtol=0, atol=1e-15)
    assert np.allclose(sw.positions[ok, k, 1], cy[ok], rtol=0, atol=1e-15)
    regular = ok & np.isfinite(sw.velocities[:, k, 0])
    assert np.allclose(sw.velocities[regular, k, 0], vx[regular], rtol=1e-11, atol=1e-14)
    assert np.allclose(sw.velocities[regular, k, 1], vy[regular], rtol=1e-11, atol=1e-14)
    # the loop closes while |BD| ≤ BC + CD = 160 mm: for φ in [0, 123.6°] and [169.5°, 360°] (issue 25,
    # item 3).  Continued from the drawing (90°) both ways and round the turn (0° is 360°: link_5 turns
    # −2 turns as link_2 turns one), the sweep reaches every such step, and no other
    assert np.array_equal(ok, d <= 0.16)
    # the limits, located between the steps: where |BD| = BC + CD, found here by bisection on the closed form
    edges = []
    for k in np.flatnonzero(np.diff(d <= 0.16)):
        lo, hi = float(phi[k]), float(phi[k + 1])
        inside_lo = bool(d[k] <= 0.16)
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            if (_five_bar_closed_form(mid, math.radians(270) - 2 * mid, 10.0, -20.0)[4] <= 0.16) == inside_lo:
                lo = mid
            else:
                hi = mid
        edges.append(lo)
    assert [math.degrees(e) for e in edges] == pytest.approx([123.5957396, 169.5131634], abs=1e-6)
    assert [t.angle for t in sw.toggles] == pytest.approx(edges, abs=1e-8)
    (gap,) = sw.gaps  # not reached, never "cannot close": Newton cannot tell another circuit's absence
    assert (gap.start, gap.end, gap.kind) == (sw.toggles[0].angle, sw.toggles[1].angle, "not reached")


def test_five_bar_sweep_led_by_either_crank_or_with_a_relative_drive_is_the_same_motion():
    m = mech.load(FIVE_BAR)
    lead2 = sweep(m, np.radians([90.0, 80.0, 70.0]), level="velocity", drive="link_2")
    # link_5 leading: at θ5 = 90° + 20°, 90° + 40° the lead link_2 is at 80°, 70° (−1/2 of link_5's turn)
    lead5 = sweep(m, np.radians([90.0, 110.0, 130.0]), level="velocity", drive="link_5")
    assert lead5.drive == "link_5" and lead5.drives[1].per_parameter == pytest.approx(-0.5)
    assert np.allclose(lead5.positions, lead2.positions, rtol=0, atol=1e-15)
    assert np.allclose(lead5.velocities, lead2.velocities, rtol=0, atol=1e-14)
    # the second drive relative to link_2: θ5 − θ2 = 0, ω5 − ω2 = −30 rad/s is the same motion
    from dataclasses import replace

    second = replace(m.drives[1], relative_to="link_2", angle=0.0, omega=-30.0, about="E")
    rel = sweep(
        replace(m, drives=(m.drives[0], second)),
        np.radians([90.0, 80.0, 70.0]),
        level="velocity",
        drive="link_2",
    )
    assert rel.drives[1].relative_to == "link_2" and rel.drives[1].per_parameter == pytest.approx(-3.0)
    assert np.allclose(rel.positions, lead2.positions, rtol=0, atol=1e-15)
    assert np.allclose(rel.velocities, lead2.velocities, rtol=0, atol=1e-14)


def test_several_drives_need_every_speed_and_take_no_single_drive_override():
    m = mech.load(FIVE_BAR)
    from dataclasses import replace

    with pytest.raises(InputError, match="in proportion to their speeds"):
        sweep(
            replace(m, drives=(m.drives[0], replace(m.drives[1], omega=None))),
            level="position",
            drive="link_2",
        )
    with pytest.raises(InputError, match="set a single drive"):
        sweep(m, options=SolveOptions(omega=3.0), drive="link_2")
    with pytest.raises(InputError, match="no drive of 'link_3'"):
        sweep(m, drive="link_3")


# -- change points: the Peaucellier–Lipkin inversor folding flat ----------------------------------
# The inversor's P by hand: tests/oracles/inversor.py (x = 1.28, P.y and its rate, the fold θ*).


@pytest.mark.parametrize("method", ["auto", "newton"])
def test_sweep_through_a_change_point_stays_on_the_inversor_line(method):
    mech_ = mech.loads(FOLDING_INVERSOR)
    phi = np.radians(np.linspace(60.0, 90.0, 361))
    s = sweep(mech_, phi, level="velocity", options=SolveOptions(method=method))
    assert bool(np.all(s.assembled))
    p = s.points.index("P")
    y, dy = inversor_p(phi)
    # both sides of θ*: P on x = 1.28 (the folded branch P = C has x = 1 + cos θ, 1.17 at 80°)
    assert phi[0] < FOLD < phi[-1]
    np.testing.assert_allclose(s.positions[:, p, 0], 1.28, rtol=0, atol=1e-9)
    np.testing.assert_allclose(s.positions[:, p, 1], y, rtol=0, atol=1e-9)
    speed = s.series("velocity.P")
    shown = np.isfinite(speed)
    assert int(np.sum(~shown)) <= 2  # at most the steps within ~1e-5 rad of θ* (left out, not wrong)
    np.testing.assert_allclose(speed[shown], np.abs(dy[shown]), rtol=1e-7)
    # extremes: what the hand formula gives, never a blown-up value at θ*
    ext = {e.quantity: e for e in s.extremes}
    assert ext["velocity.P"].max_value == pytest.approx(
        float(np.abs(inversor_p(np.radians(90.0))[1])), rel=1e-9
    )
    assert ext["velocity.P"].min_value == pytest.approx(
        float(np.abs(inversor_p(np.radians(60.0))[1])), rel=1e-9
    )
    for e in s.extremes:
        if e.unit in ("m/s", "rad/s"):
            assert abs(e.max_value) < 10.0 and abs(e.min_value) < 10.0, e


@pytest.mark.parametrize(("method", "within"), [("auto", 1e-6), ("newton", 1e-5)])
def test_sweep_reports_the_change_point_where_the_rhombus_folds(method, within):
    # the closed form: the root of the dyad's signed √disc; Newton: where σ_min of Φ_q dips to zero
    # (Newton is good to about √tol there: 1e-6 of the size, some 1e-8 rad of crank)
    s = sweep(
        mech.loads(FOLDING_INVERSOR),
        np.radians(np.linspace(60.0, 90.0, 361)),
        level="velocity",
        options=SolveOptions(method=method),
    )
    (c,) = s.change_points
    assert c.kind == "change point"
    assert math.degrees(c.angle) == pytest.approx(math.degrees(FOLD), abs=within)
    assert c.subject.startswith("P meets C")
    note = next(n for n in s.notes if n.startswith("change point at"))
    assert f"change point at {math.degrees(c.angle):.6f}°" in note and "continuous tangent" in note
    assert s.toggles == () and s.gaps == ()


def test_sweep_descending_through_the_change_point_comes_back_on_the_same_line():
    phi = np.radians(np.linspace(100.0, 50.0, 101))
    s = sweep(mech.loads(FOLDING_INVERSOR), phi, level="position")
    np.testing.assert_allclose(s.positions[:, s.points.index("P"), 0], 1.28, rtol=0, atol=1e-9)
    assert [round(math.degrees(c.angle), 6) for c in s.change_points] == [round(math.degrees(FOLD), 6)]


def test_sweep_without_a_change_point_reports_none():
    s = sweep(four_bar(omega=10.0), FULL, level="velocity")
    assert s.change_points == ()
    assert not any("change point" in n for n in s.notes)


def test_a_crank_limited_by_a_real_toggle_reports_the_toggle_not_a_change_point():
    # the inversor's crank cannot bring C nearer O than OA − CA = 0.8: 2 cos(θ/2) = 0.8 at
    # θ = 2 acos(0.4) = 132.84°, a toggle (O, C, A in line) at the edge of a gap
    s = sweep(mech.loads(FOLDING_INVERSOR), np.radians(np.linspace(60.0, 180.0, 121)), level="position")
    assert [math.degrees(t.angle) for t in s.toggles] == pytest.approx(
        [math.degrees(2 * math.acos(0.4))], abs=1e-7
    )
    assert len(s.gaps) == 1
    assert [math.degrees(c.angle) for c in s.change_points] == pytest.approx([math.degrees(FOLD)], abs=1e-6)


def test_newton_sweep_of_the_double_parallelogram_says_where_its_jacobian_loses_rank():
    # three equal cranks on collinear pivots: at 180° every link lies on the frame's line and Φ_q
    # loses rank (each parallelogram at its change point; the third crank keeps the translation).
    # The sweep passes it (assembled on both sides) and locates it by symmetry to 1e-6°.
    s = sweep(mech.load(Path(__file__).resolve().parents[2] / "mechanisms" / "double_parallelogram.yaml"))
    assert bool(np.all(s.assembled))
    (c,) = s.change_points
    assert math.degrees(c.angle) == pytest.approx(180.0, abs=1e-6)
    assert "loses rank" in c.subject


def test_a_rate_that_grows_without_bound_toward_a_toggle_has_an_infinite_extreme(run):
    # Khurmi's six-link slider: the loop stops closing where the rod stands at right angles to the
    # slider's path (27.59° and 250.05°).  There the rod cannot drive the slider: with the crank at a
    # steady speed, ω_rod = (v_B · u)/(l cos β) (u along the path, β the rod's angle from the path's
    # normal) grows like Δθ^(−1/2) toward β = 0, and its extremes are ±∞ at the toggles, not the last
    # regular step's 257 rad/s a degree away (issue 25, item 5).  The lever, behind the rod in the
    # chain, keeps finite extremes.
    m = mech.load(ROOT / "mechanisms" / "khurmi_six_link_slider.yaml")
    sw = sweep(m, quantities=["omega.rod", "omega.lever", "angle.rod"])
    toggles = sorted(t.angle for t in sw.toggles)
    ext = {e.quantity: e for e in sw.extremes}
    rod = ext["omega.rod"]
    assert (rod.max_value, rod.min_value) == (math.inf, -math.inf)
    assert sorted((rod.max_angle, rod.min_angle)) == pytest.approx(toggles, abs=1e-12)
    assert all(math.isfinite(v) for v in (ext["omega.lever"].max_value, ext["omega.lever"].min_value))
    # where the rod is at right angles to the path (the toggle), its angle is 270° exactly to √ε
    assert math.degrees(ext["angle.rod"].min_value) == pytest.approx(270.0, abs=1e-5)
    assert any("omega.rod grows without bound toward the toggle" in n for n in sw.notes)
    table = run("sweep", str(ROOT / "mechanisms" / "khurmi_six_link_slider.yaml"), "--quantity", "omega.rod")
    assert "∞ (toggle)" in table.output and "−∞ (toggle)" in table.output


# -- dwells and every output's time ratio (issue 21, items 2 and 3) ------------------------------


def test_a_follower_at_rest_over_a_dwell_is_one_dwell_with_no_dead_centre_inside_it():
    # DESIGN § 1.1: the drive angle is the cam's turn from the programme's start, counted in the
    # sense it turns; a sweep's angle is the absolute (counter-clockwise) one, so a clockwise cam is
    # at programme angle 360° − θ.  The top dwell, programme 120°–180°, is θ = 180°–240°; the bottom
    # one, programme 270°–360°, is θ = 0°–90°.  At rest the roller's centre is on the prime circle
    # (30 + 10 = 40 mm from the cam's centre), offset 10 mm: √(40² − 10²) up the path, 40 mm higher
    # at the top.  The SHM return leaves rest linearly (its ends to rounding), the cycloidal rise
    # quadratically (its end found to about 1e-5°).
    sw = sweep(mech.loads(ROLLER_CAM), level="velocity")
    assert sw.dead_centres == ()  # it listed one at every step of both dwells (122)
    low = math.sqrt(40.0**2 - 10.0**2) / 1000
    got = sorted((math.degrees(d.start), math.degrees(d.end), d.value, d.reverses) for d in sw.dwells)
    assert got == [
        (pytest.approx(0.0, abs=1e-9), pytest.approx(90.0, abs=1e-9), pytest.approx(low, rel=1e-9), True),
        (
            pytest.approx(180.0, abs=1e-9),
            pytest.approx(240.0, abs=1e-3),
            pytest.approx(low + 0.04, rel=1e-9),
            True,
        ),
    ]
    # its two limits are the dwells (DESIGN § 1.2: two limit positions, so a time ratio): the strokes
    # run from leaving one to reaching the other, 90° → 180° and 240° → 360°, so 120° / 90°
    (ratio,) = sw.time_ratios
    assert sw.time_ratio == ratio and ratio.output == "S"
    assert math.degrees(ratio.slow) == pytest.approx(120.0, abs=1e-3)
    assert math.degrees(ratio.fast) == pytest.approx(90.0, abs=1e-3)


def test_a_lift_held_over_a_dwell_is_said_at_the_dwell_s_start():
    # the roller rests at its lowest over 0°–90° of the sweep and at its highest over 180°–240°
    # (the dwells worked in the test above): the least and largest lift are said where each dwell
    # starts, not where refinement stopped on the plateau (the least was said at 359.9997°)
    sw = sweep(mech.loads(ROLLER_CAM), level="velocity")
    (lift,) = [e for e in sw.extremes if e.quantity == "displacement.S"]
    starts = sorted(d.start for d in sw.dwells)
    assert (lift.min_angle, lift.max_angle) == (starts[0], starts[1])
    assert math.degrees(starts[0]) == pytest.approx(0.0, abs=1e-9)
    assert math.degrees(starts[1]) == pytest.approx(180.0, abs=1e-6)


def test_every_output_with_two_dead_centres_has_a_time_ratio_the_watt_rocker_by_the_cosine_rule():
    # The Watt six-bar's first loop: crank 30, coupler 110, rocker O4C 70, frame 100 mm.  Its rocker
    # reverses where crank and coupler are in line (the law of cosines: oracles.four_bar), so its
    # time ratio is (180 + α)/(180 − α); the output link O6F, driven through the second loop,
    # reverses four times and has none: bare time_ratio is the rocker's, the one output with two.
    # (It was refused: "no output with two dead centres", while the rocker has exactly two.)
    from oracles.four_bar import crank_rocker_limits

    sw = sweep(mech.load(ROOT / "mechanisms" / "watt_six_bar.yaml"), level="velocity")
    t_ext, t_fold, ratio = crank_rocker_limits(30.0, 110.0, 70.0, 100.0)
    (rocker,) = sw.time_ratios
    assert rocker.output == "rocker" and rocker.ratio == pytest.approx(ratio, rel=1e-10)
    assert math.degrees(rocker.fast) == pytest.approx(360.0 - (t_fold - t_ext), rel=1e-10)
    assert sw.time_ratio == rocker
    # the refusal's reason is true: the output reverses four times, counted here on a fine grid of
    # its angle alone (no dead-centre finding)
    bare = sweep(
        mech.load(ROOT / "mechanisms" / "watt_six_bar.yaml"),
        np.radians(np.linspace(0, 360, 7201)),
        analyse=False,
    )
    step = np.diff(bare.series("angle.output"))
    turns = int(np.sum(np.sign(step[1:]) * np.sign(step[:-1]) < 0))
    assert turns == 4 and dict(sw.time_ratio_refused)["output"].startswith("output reverses 4 times")


def test_a_full_turn_extreme_at_the_seam_is_written_at_0_not_360():
    # The crank-rocker's least transmission angle is at crank 0° (crank toward D: cos μ =
    # (b² + c² − (d − a)²)/(2bc)); refined on the seam it came out 359.9999987°.  0° and 360° are
    # one crank position, written as 0 (angles in [0°, 360°)).
    sw = sweep(mech.load(ROOT / "mechanisms" / "watt_six_bar.yaml"), quantities=["included.B.C.O4"])
    (mu,) = sw.extremes
    assert math.degrees(mu.min_value) == pytest.approx(math.degrees(math.acos(110 / 140)), rel=1e-9)
    assert mu.min_angle == 0.0


def test_dwell_ends_found_on_a_newton_walk_are_the_programmes_as_on_the_marched_grid(monkeypatch):
    # Without a marcher the sweep refines on a Newton walk (sweep_backends.Walk), one end after the
    # other: the same dwells as the marched grid's, from the programme (see the test above).
    import mech.kinematics.sweep_backends as backends

    monkeypatch.setattr(backends.Marcher, "make", classmethod(lambda cls, backend: None))
    sw = sweep(mech.loads(ROLLER_CAM), np.radians(np.linspace(0.0, 360.0, 121)), level="velocity")
    assert sw.method == "newton" and sw.dead_centres == ()
    got = sorted((math.degrees(d.start), math.degrees(d.end)) for d in sw.dwells)
    assert got == [
        (0.0, pytest.approx(90.0, abs=1e-9)),
        (pytest.approx(180.0, abs=1e-9), pytest.approx(240.0, abs=1e-3)),
    ]


def test_an_asked_quantity_with_no_extremes_says_why_instead_of_vanishing():
    # a crank at constant speed: ω = 10 rad/s and α = 0 at every step (the file's data, not mech's
    # result); the slider keeps its angle (0 rad) and the crank turns right round
    s = sweep(
        slider_crank(r=0.1, rod=0.4, e=0.02, omega=10.0),
        FULL,
        level="acceleration",
        quantities=["sliding.P", "omega.crank", "alpha.crank", "angle.crank"],
    )
    assert [x.quantity for x in s.extremes] == ["sliding.P"]
    assert "omega.crank does not vary over the sweep: 10 rad/s throughout" in s.notes
    assert "alpha.crank does not vary over the sweep: 0 rad/s^2 throughout" in s.notes
    assert "angle.crank: the link turns right round (no largest or least angle)" in s.notes


def test_a_speed_s_least_value_at_a_dead_centre_is_zero_not_its_rounding():
    # A triple rocker (AB 100, BC 120, CD 80, AD 150 mm): the rocker stops where crank and coupler
    # are in line, AC = 220 mm, at cos θ = (150² + 220² − 80²)/(2·150·220), θ = 12.2388°; there
    # |v_C| is 0, found between steps as a difference of terms of 1 m/s (it read 2.3313e-13 m/s)
    m = mech.loads(
        "units: {length: mm, angle: deg}\nlinks: [frame, crank, coupler, rocker]\njoints:\n"
        "  A: {type: revolute, links: [frame, crank], at: [0, 0]}\n"
        "  B: {type: revolute, links: [crank, coupler]}\n"
        "  C: {type: revolute, links: [coupler, rocker], near: [100, 150]}\n"
        "  D: {type: revolute, links: [rocker, frame], at: [150, 0]}\n"
        "lengths: {AB: 100, BC: 120, CD: 80}\ndrive: {link: crank, angle: 90, rpm: 60}\n"
    )
    sw = sweep(m, level="velocity")
    (vc,) = [e for e in sw.extremes if e.quantity == "velocity.C"]
    dead = math.acos((150**2 + 220**2 - 80**2) / (2 * 150 * 220))
    assert vc.min_value == 0.0
    assert vc.min_angle == pytest.approx(dead, abs=1e-7)
