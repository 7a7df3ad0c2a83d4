"""Newton sweeps marched in stacks (mech.kinematics.march) against closed forms derived here."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from builders import four_bar, slider_crank

import mech
from mech.kinematics import solve, sweep
from mech.kinematics.solve import compiled
from mech.options import SolveOptions

ROOT = Path(__file__).resolve().parents[2]
NEWTON = SolveOptions(method="newton")


def test_double_parallelogram_sweep_translates_its_coupler_at_the_crank_speed():
    # Khurmi's double parallelogram (mechanisms/double_parallelogram.yaml): cranks AB = EF = DC
    # = 40 mm, 60 rpm ccw, the coupler translates: every coupler point moves on a 40 mm circle
    # with v = ω·40 mm and a = ω²·40 mm (centripetal), C about D = (100, 0) mm.
    m = mech.load(ROOT / "mechanisms" / "double_parallelogram.yaml")
    phi = np.radians(np.linspace(0.0, 360.0, 721))
    s = sweep(m, phi, level="acceleration", analyse=False)
    assert s.method == "newton" and s.assembled.all()
    w, r = 2 * math.pi, 0.04
    k = s.points.index("C")
    assert np.allclose(
        s.positions[:, k, 0], 0.1 + r * np.cos(phi), rtol=0, atol=1e-6 * 0.14
    )  # singular steps too
    away = np.abs(np.sin(phi)) > 0.05  # the flat configurations (0°, 180°) are toggles
    vx, vy = -w * r * np.sin(phi), w * r * np.cos(phi)
    ax, ay = -w * w * r * np.cos(phi), -w * w * r * np.sin(phi)
    assert (
        np.hypot(s.velocities[away, k, 0] - vx[away], s.velocities[away, k, 1] - vy[away]).max()
        < 1e-12 * w * r
    )
    assert (
        np.hypot(s.accelerations[away, k, 0] - ax[away], s.accelerations[away, k, 1] - ay[away]).max()
        < 1e-10 * w * w * r
    )
    assert np.allclose(s.omegas[away][:, s.links.index("coupler")], 0.0, atol=1e-12 * w)
    flat = np.isnan(s.velocities[:, k, 0])
    assert np.all(np.abs(np.sin(phi[flat])) < 0.01)  # only the flat configurations are refused


def test_gear_pair_sweep_turns_the_wheel_at_half_the_pinion_speed_the_other_way():
    # 20/40 teeth, pinion 1200 rpm cw: wheel ω = +62.83 rad/s, wheel angle falls by half the pinion's turn
    m = mech.load(ROOT / "mechanisms" / "gear_pair.yaml")
    phi = np.radians(np.linspace(0.0, 720.0, 2001))  # two turns of the pinion
    s = sweep(m, phi, level="acceleration", analyse=False)
    assert s.assembled.all()
    wheel = s.links.index("wheel")
    assert np.allclose(s.omegas[:, wheel], 1200 * 2 * math.pi / 60 / 2, rtol=1e-13)
    assert np.allclose(s.alphas[:, wheel], 0.0, atol=1e-9)
    turned = s.link_angles[:, wheel] - s.link_angles[0, wheel]
    assert np.allclose(turned, -(phi - phi[0]) / 2, rtol=0, atol=1e-12)


@pytest.mark.parametrize(
    ("build", "name"),
    [
        (lambda: four_bar(angle=math.radians(60), omega=-4 * math.pi, alpha=3.0), "four-bar"),
        (lambda: slider_crank(), "slider crank"),
    ],
)
def test_newton_sweep_matches_the_closed_form_to_rounding(build, name):
    m = build()
    phi = np.radians(np.linspace(-30.0, 330.0, 1441))
    ref = sweep(m, phi, level="acceleration", analyse=False)
    got = sweep(m, phi, level="acceleration", analyse=False, options=NEWTON)
    assert ref.method == "closed form" and got.method == "newton"
    for key in ("positions", "velocities", "accelerations", "link_angles", "omegas", "alphas", "sliding"):
        a, b = getattr(got, key), getattr(ref, key)
        if b.size == 0:  # no slider in a four-bar
            continue
        scale = max(float(np.nanmax(np.abs(b))), 1e-300)
        assert np.nanmax(np.abs(a - b)) < 1e-13 * scale, key


def test_newton_sweep_reaches_the_drawn_circuit_round_the_turn_as_the_closed_form_finds_it():
    # a change-point four-bar (s + l = 0.05 + 0.15 = p + q; crank 0.1 > what the rocker allows): the
    # crank cannot turn fully; its
    # drawn circuit runs from about 289.5° through 0° (which is 360°) to 70.9°, so the sweep from 0° to
    # 360° meets it at both ends: continued from the drawing (30°) both ways and round the turn, the
    # march reaches every step the closed form assembles, and no other (issue 25, item 3)
    m = four_bar(a=0.1, b=0.1, c=0.05, d=0.15, angle=math.radians(30), omega=1.0)
    phi = np.radians(np.linspace(0.0, 360.0, 721))
    ref = sweep(m, phi, level="velocity", analyse=False)
    got = sweep(m, phi, level="velocity", analyse=False, options=NEWTON)
    assert np.array_equal(got.assembled, ref.assembled)
    assert got.assembled[60] and not got.assembled[360]  # the drawn 30°; 180° is beyond both limits
    # on one branch, the one with a continuous tangent through the change point at 0° (d − a = b − c:
    # B, C, D in line), which the closed form now counts as passed on the way round; at the change
    # point itself Newton's Jacobian is singular and its positions are good to about √tol
    regular = got.assembled & (ref.condition < 1e5)
    assert np.nanmax(np.abs(got.positions[regular] - ref.positions[regular])) < 1e-12
    assert np.nanmax(np.abs(got.positions[got.assembled] - ref.positions[got.assembled])) < 1e-6
    assert any("cannot reach" in n for n in got.notes)


@pytest.mark.parametrize(
    "name",
    [
        "double_parallelogram",
        "gear_pair",
        "four_bar",
        "whitworth_quick_return",
        "eccentric_cam_roller",
        "rolling_wheel",
        "cam_oscillating_roller",
        "cam_flat_follower",
    ],
)
def test_constraint_rows_of_a_stack_are_each_configurations_own(name):
    # one truth with a batch axis: Φ, Φ_q and γ of K configurations at once are, row for row, those
    # of each configuration alone (a batch of one), for every row shape the examples use
    sys_ = compiled(mech.load(ROOT / "mechanisms" / f"{name}.yaml"), None).system
    rng = np.random.default_rng(7)
    q = sys_.q0 + rng.uniform(-0.05, 0.05, (5, sys_.q0.size))
    qd = rng.uniform(-1.0, 1.0, (5, sys_.q0.size))
    many = (sys_.phi(q, sys_.ln_c, sys_.ang_c), sys_.jacobian(q), sys_.gamma(q, qd))
    for k in range(5):
        one = (sys_.phi(q[k], sys_.ln_c, sys_.ang_c), sys_.jacobian(q[k]), sys_.gamma(q[k], qd[k]))
        for a, b in zip(many, one, strict=True):
            assert a[k].shape == b.shape
            assert np.allclose(a[k], b, rtol=1e-13, atol=1e-14)


@pytest.mark.parametrize("steps", [12, 360])
def test_newton_sweep_refines_extremes_and_dead_centres_as_the_closed_form_does(steps):
    # refinement evaluates grids between the marched steps: coarse or fine, the refined
    # extremes are the closed form's (which refines its own exact program) to rounding
    m = four_bar(angle=math.radians(60), omega=-4 * math.pi)
    phi = np.radians(np.linspace(0.0, 360.0, steps + 1))
    ref = sweep(m, phi, level="acceleration")
    got = sweep(m, phi, level="acceleration", options=NEWTON)
    assert [e.quantity for e in got.extremes] == [e.quantity for e in ref.extremes]
    for e, r in zip(got.extremes, ref.extremes, strict=True):
        scale = max(abs(r.max_value), abs(r.min_value))
        assert abs(e.max_value - r.max_value) <= 1e-12 * scale, e.quantity
        assert abs(e.min_value - r.min_value) <= 1e-12 * scale, e.quantity
    assert len(got.dead_centres) == len(ref.dead_centres) == 2
    for d, r in zip(got.dead_centres, ref.dead_centres, strict=True):
        assert d.subject == r.subject and abs(d.angle - r.angle) < 1e-10
    assert got.time_ratio is not None and ref.time_ratio is not None
    assert got.time_ratio.ratio == pytest.approx(ref.time_ratio.ratio, rel=1e-10)


@pytest.mark.parametrize(
    "name", ["eccentric_cam_roller", "rolling_wheel", "cam_oscillating_roller", "cam_roller_program"]
)
def test_moving_higher_pairs_march_in_stacks_as_the_step_by_step_sweep_solves_them(name, monkeypatch):
    # distance rows (a roller on an eccentric), rolling rows (the arc rolled) and programme rows
    # (a follower moved by its law): the marched sweep gives the step-by-step continuation's
    # answer to 1e-9 of the size
    import mech.kinematics.march as march

    m = mech.load(ROOT / "mechanisms" / f"{name}.yaml")
    phi = np.radians(np.linspace(0.0, 360.0, 181))
    got = sweep(m, phi, level="acceleration", analyse=False)
    assert got.method == "newton"
    monkeypatch.setattr(march.Marcher, "make", classmethod(lambda cls, backend: None))
    ref = sweep(m, phi, level="acceleration", analyse=False)
    assert got.assembled.all() and ref.assembled.all()
    size = solve(m, "position").size  # the mechanism's own scale (its largest joint distance)
    w = float(np.nanmax(np.abs(ref.omegas)))
    for key, unit in (("positions", size), ("velocities", w * size), ("accelerations", w * w * size)):
        a, b = getattr(got, key), getattr(ref, key)
        assert np.array_equal(np.isnan(a), np.isnan(b)), key
        assert np.nanmax(np.abs(a - b)) <= 1e-9 * unit, key
    turned = got.link_angles - ref.link_angles  # the same angle, whichever turn each counts it in
    assert np.nanmax(np.abs((turned + math.pi) % (2 * math.pi) - math.pi)) <= 1e-9
    for key, unit in (("omegas", w), ("alphas", w * w)):
        a, b = getattr(got, key), getattr(ref, key)
        assert np.nanmax(np.abs(a - b)) <= 1e-9 * unit, key


@pytest.mark.parametrize("r", [1e-12, 1e-13])
def test_marched_sweep_keeps_a_tiny_cranks_rates_to_their_own_digits(r):
    # A 1e-12 m crank on a 1 m rod, 60 rpm, swept by the marched back-end.  Every rate is
    # judged against what it is computed from (solve.snap_to_error, Skeel's bound), not
    # against an absolute 1e-13: near 5° and 85° the rod's ω and the piston's speed are
    # 5.5e-13 and were set to zero.  Truth: the slider-crank closed form (oracles.slider_crank,
    # ω₃ = −r ω cosθ / (l cosφ), v = −r ω sinθ − l ω₃ sinφ …) and the crank pin's speed ω·r.
    from oracles.slider_crank import slider_crank as closed

    rod, w = 1.0, 2 * math.pi
    m = slider_crank(r=r, rod=rod, angle=math.radians(45), omega=w)
    phi = np.radians(np.arange(0.0, 361.0, 5.0))
    s = sweep(m, phi, level="acceleration", analyse=False, options=NEWTON)
    assert s.method == "newton" and s.assembled.all()
    pin = s.velocities[:, s.points.index("A"), :]
    assert np.allclose(np.hypot(pin[:, 0], pin[:, 1]), w * r, rtol=1e-12, atol=0)
    series = {k: s.series(k) for k in ("omega.rod", "sliding.P", "alpha.rod", "acceleration.B.x")}
    for k, th in enumerate(phi):
        _, w3, v, a3, a = closed(r, rod, 0.0, float(th), w)
        for key, want in zip(series, (w3, v, a3, a), strict=True):
            got = series[key][k]
            if abs(want) < 1e-20 * w:  # zero by symmetry (cos 90°): round-off of the formula itself
                assert abs(got) < 1e-20 * w, (key, math.degrees(th))
            else:
                assert got == pytest.approx(want, rel=1e-10), (key, math.degrees(th))
