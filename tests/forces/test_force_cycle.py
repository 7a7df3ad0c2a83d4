"""Forces over the cycle (mech.forces.cycle, mech.forces.series): each value against an independent derivation.

- Khurmi & Gupta, *Theory of Machines*, Example 16.9 (mechanisms/khurmi_gas_engine_flywheel.yaml):
  the table's turning moment integrated on a fine grid that holds its rows (the trapezoid rule
  is exact on each straight piece), and the book's own numbers: T_mean = 8000/4π N·m,
  ΔE = ½·π(T_max − T_mean)²/T_max, I = ΔE/(ω²·0.04) = 255.4 kg·m², the speed least and
  greatest where the expansion triangle crosses T_mean;
- a four-stroke engine with a gas-force table and the inertia of its piston and rod
  (mechanisms/engine_turning_moment.yaml): the torque in closed form from the power balance,
  integrated on a fine grid (tests/oracles/engine_torque.py);
- the greatest pin force of a four-bar over its turn: Newton–Euler at every angle of a fine
  scan, then a finer one round its best (tests/oracles/newton_euler.py);
- a static lift: the mean torque over a range is the change of potential energy over the
  angle turned (work–energy);
- a slider-driven crank holding a constant torque: ∫ F ds = −M Δθ_crank;
- the grid does not matter: 1 step or 3,600 give the same mean, ΔE and peaks.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from tests.mechanism_texts import EXAMPLES, SLIDER_DRIVEN, lift
from tests.oracles.engine_torque import cycle_integrals, engine_torque
from tests.oracles.newton_euler import four_bar_forces
from tests.oracles.slider_crank import slider_driven_crank

from mech.forces import analyse
from mech.forces.cycle import cycle_span, force_cycle, integrate
from mech.forces.series import Evaluator
from mech.loader import load, loads
from mech.options import SolveOptions

KHURMI = EXAMPLES / "khurmi_gas_engine_flywheel.yaml"
ENGINE = EXAMPLES / "engine_turning_moment.yaml"


def test_khurmi_gas_engine_cycle_matches_the_tables_integral_and_the_books_answer():
    cycle = force_cycle(load(str(KHURMI)))
    # the gases' turning moment, read off the file's table; the input torque is minus it
    rows = np.array([[0, 0], [180, 0], [270, -2546.479], [360, 0], [450, 7639.437], [540, 0], [720, 0]])
    deg = np.union1d(np.linspace(0.0, 720.0, 1_440_001), rows[:, 0])
    torque = -np.interp(deg, rows[:, 0], rows[:, 1])
    th = np.radians(deg)
    steps = np.diff(th) * (torque[:-1] + torque[1:]) / 2
    mean = steps.sum() / (4 * math.pi)
    energy = np.concatenate(([0.0], np.cumsum(np.diff(th) * mean - steps)))
    w = 300 * 2 * math.pi / 60
    assert cycle.mean == pytest.approx(mean, rel=1e-12)
    assert cycle.fluctuation == pytest.approx(energy.max() - energy.min(), rel=1e-9)
    assert cycle.flywheel == pytest.approx((energy.max() - energy.min()) / (w * w * 0.04), rel=1e-9)
    # the book: W = 20 kW × 60 s / 150 cycles = 8000 J, T_mean = 8000/4π; the expansion triangle's
    # height 24 000/π crosses T_mean at 360° + 90° T_mean/T_max and 540° − 90° T_mean/T_max
    t_mean, t_max = 8000 / (4 * math.pi), 24000 / math.pi
    assert -cycle.mean == pytest.approx(t_mean, rel=1e-6)
    de = 0.5 * math.pi * (t_max - t_mean) ** 2 / t_max
    assert cycle.fluctuation == pytest.approx(de, rel=1e-6)
    assert cycle.flywheel == pytest.approx(255.4, rel=5e-4)  # published, to its 4 figures
    assert cycle.least is not None and cycle.greatest is not None
    assert math.degrees(cycle.least[0]) == pytest.approx(360 + 90 * t_mean / t_max, abs=1e-6)
    assert math.degrees(cycle.greatest[0]) == pytest.approx(540 - 90 * t_mean / t_max, abs=1e-6)
    assert cycle.whole and math.degrees(cycle.period) == pytest.approx(720.0)


ENGINE_TABLE = [(0, 0), (10, 80), (170, 80), (180, 0), (270, -1500), (330, -5000), (360, -11800),
                (375, -31400), (400, -20000), (450, -8000), (540, -2400), (550, -160), (710, -160), (720, 0)]  # fmt: skip
ENGINE_DATA = {
    "r": 0.05,
    "rod": 0.2,
    "m_p": 1.2,
    "m_r": 1.5,
    "g": 0.06,
    "inertia": 0.006,
    "table": ENGINE_TABLE,
}


def test_engine_turning_moment_with_inertia_matches_the_closed_form_power_balance():
    w = 1500 * 2 * math.pi / 60
    th = np.radians(np.linspace(0.0, 720.0, 2 * 288_000 + 1))
    mean, de, hi, lo, inertia = cycle_integrals(engine_torque(th, w=w, **ENGINE_DATA), th, w, 0.01)
    cycle = force_cycle(load(str(ENGINE)), steps=360)
    assert cycle.mean == pytest.approx(mean, rel=1e-9)
    assert cycle.fluctuation == pytest.approx(de, rel=1e-9)
    assert cycle.flywheel == pytest.approx(inertia, rel=1e-9)
    step = math.radians(720 / 288_000)  # the oracle's grid: its extremes are good to a step
    assert cycle.greatest is not None and cycle.greatest[0] == pytest.approx(hi, abs=step)
    assert cycle.least is not None and cycle.least[0] == pytest.approx(lo, abs=step)
    # the series on the grid is the closed form's torque, step by step
    grid = cycle.series.angles
    assert np.allclose(cycle.series.effort, engine_torque(grid, w=w, **ENGINE_DATA), rtol=0, atol=1e-9 * 724)


def test_the_cycles_numbers_do_not_depend_on_the_grid():
    mech = load(str(ENGINE))
    fine, coarse, one = (force_cycle(mech, steps=n) for n in (3600, 7, 1))
    for c in (coarse, one):
        assert c.mean == pytest.approx(fine.mean, rel=1e-12)
        assert c.fluctuation == pytest.approx(fine.fluctuation, rel=1e-12)
        assert c.effort_max is not None and fine.effort_max is not None
        assert c.effort_max.value == pytest.approx(fine.effort_max.value, rel=1e-12)
        assert [p.value for p in c.peaks] == pytest.approx([p.value for p in fine.peaks], rel=1e-12)


def test_a_one_degree_trapezoid_is_far_from_the_integral_the_cycle_gives():
    # the yardstick: the grid's own 1° trapezoid is some 3e-5 off (kinks at the table's
    # rows, and the torque's high harmonics) where the cycle agrees with the closed form to 1e-12
    w = 1500 * 2 * math.pi / 60
    th = np.radians(np.linspace(0.0, 720.0, 721))
    t = engine_torque(th, w=w, **ENGINE_DATA)
    trapezoid = float(np.sum(np.diff(th) * (t[:-1] + t[1:]) / 2)) / (4 * math.pi)
    exact = force_cycle(load(str(ENGINE))).mean
    assert exact is not None and abs(trapezoid - exact) > 1e-5 * abs(exact)


FOUR_BAR = (EXAMPLES / "four_bar_inertia_forces.yaml").read_text()
MASSES = {
    "crank": (0.4, 0.0002, 0.015),
    "coupler": (1.5, 0.004, 0.070),
    "rocker": (1.8, 1.8 * 0.06**2, 0.090),
}


def _ne(theta: float, joint: str) -> float:
    ne = four_bar_forces((0.040, 0.150, 0.170, 0.150), theta, 10 * math.pi, MASSES, (0.0, -9.81))
    return float(np.linalg.norm(ne[joint]))


@pytest.mark.parametrize("joint", ["A", "B", "C", "D"])
def test_the_greatest_pin_force_and_its_angle_match_a_newton_euler_scan(joint):
    cycle = force_cycle(loads(FOUR_BAR, path="fourbar.yaml"), steps=36)
    peak = next(p for p in cycle.peaks if p.quantity == f"force.{joint}")
    scan = np.radians(np.arange(0.0, 360.0, 0.05))
    values = [_ne(t, joint) for t in scan]
    k = int(np.argmax(values))
    near = np.linspace(scan[k] - math.radians(0.05), scan[k] + math.radians(0.05), 2001)
    finer = [_ne(t, joint) for t in near]
    j = int(np.argmax(finer))
    assert peak.value == pytest.approx(finer[j], rel=1e-9)
    assert math.remainder(peak.angle - near[j], 2 * math.pi) == pytest.approx(0.0, abs=1e-4)


def test_the_batched_series_is_the_instant_analysis_at_every_step():
    mech = loads(FOUR_BAR, path="fourbar.yaml")
    angles = np.radians([0.0, 33.0, 97.0, 181.0, 275.0, 359.0])
    series = Evaluator(mech)(angles)
    for k, theta in enumerate(angles):
        fa = analyse(mech, SolveOptions(angle=float(theta)))
        assert fa.effort is not None
        assert series.effort[k] == pytest.approx(fa.effort.value, rel=1e-12)
        for i, (joint, on, by) in enumerate(series.pairs):
            pair = fa.pair(joint)
            assert (pair.on, pair.by) == (on, by)
            assert series.forces[k, i] == pytest.approx(pair.force, rel=1e-12, abs=1e-12)
        assert series.shaking[k] == pytest.approx(fa.shaking_force, rel=1e-12)
        assert series.moment[k] == pytest.approx(fa.shaking_moment, rel=1e-12)


def test_the_series_names_the_pair_forces_as_the_kinds_hook_names_them(monkeypatch):
    # a revolute kind whose hook gives the force on its FIRST link (from the second): the sweep must
    # follow the hook, not a rule of its own.  Newton–Euler (tests/oracles/newton_euler.py) gives
    # F_A on the crank from the frame, F_B on the coupler from the crank, F_C on the rocker from the
    # coupler, F_D on the rocker from the frame; on the first link named it is their reaction
    from mech.pairs import kind_of
    from mech.pairs.base import PairForce

    mech = loads(FOUR_BAR, path="fourbar.yaml")
    kind = type(kind_of(next(j for j in mech.joints if j.type == "revolute")))

    def on_first(self, j, wrenches, at, direction):
        first, second = j.links[0], j.links[1]
        return [PairForce(j.name, first, second, wrenches[first][:2], at)] if first in wrenches else []

    monkeypatch.setattr(kind, "forces", on_first)
    angles = np.radians([33.0, 181.0])
    series = Evaluator(mech)(angles)
    assert series.pairs == (
        ("A", "frame", "crank"),
        ("B", "crank", "coupler"),
        ("C", "coupler", "rocker"),
        ("D", "rocker", "frame"),
    )
    sign = {"A": -1.0, "B": -1.0, "C": -1.0, "D": 1.0}
    for k, theta in enumerate(angles):
        ne = four_bar_forces((0.040, 0.150, 0.170, 0.150), float(theta), 10 * math.pi, MASSES, (0.0, -9.81))
        for i, (joint, _, _) in enumerate(series.pairs):
            expected = sign[joint] * np.asarray(ne[joint])
            assert series.forces[k, i] == pytest.approx(
                expected, rel=1e-9, abs=1e-9 * np.linalg.norm(expected)
            )


def test_a_static_sweep_gives_the_mean_torque_of_the_change_in_potential_energy():
    # no drive speed: no inertia.  From 20° to 140° the input's work is the weights' potential
    # energy gained: y_B = r sin θ + √(l² − r² cos² θ), the crank's centre at r/2 sin θ.
    cycle = force_cycle(
        loads(lift(30), path="lift.yaml"), start=math.radians(20), stop=math.radians(140), steps=12
    )
    r, rod, g = 0.1, 0.25, 9.81

    def height(th: float) -> float:
        return 20 * (r * math.sin(th) + math.sqrt(rod**2 - (r * math.cos(th)) ** 2)) + 3 * r / 2 * math.sin(
            th
        )

    gained = g * (height(math.radians(140)) - height(math.radians(20)))
    assert cycle.static and cycle.flywheel is None
    assert cycle.work == pytest.approx(gained, rel=1e-10)
    assert cycle.mean == pytest.approx(gained / math.radians(120), rel=1e-10)
    assert any("static" in n for n in cycle.notes) and any("whole number" in n for n in cycle.notes)


def test_a_slider_drives_force_over_its_stroke_does_the_loads_work():
    # a constant torque M on the crank: ∫ F ds = −M (θ(s₁) − θ(s₀)), the crank's angle from the
    # slider's by the law of cosines
    mech = loads(SLIDER_DRIVEN, path="slider.yaml")
    s0, s1 = 0.26, 0.37
    cycle = force_cycle(mech, start=s0, stop=s1, steps=20)
    t0, _ = slider_driven_crank(0.1, 0.3, s0, 1.0)
    t1, _ = slider_driven_crank(0.1, 0.3, s1, 1.0)
    assert cycle.kind == "force" and cycle.flywheel is None
    assert cycle.work == pytest.approx(-15 * (t1 - t0), rel=1e-9)
    with pytest.raises(Exception, match="stroke"):
        force_cycle(mech)


def test_gears_are_swept_step_by_step_and_carry_their_tooth_load_all_round():
    # a gear on fixed centres carries its force by rows of its own: solved angle by angle.
    # 10 N·m on the wheel (pitch radius 100 mm, φ = 20°): T = −5 N·m on the pinion, tooth load
    # 10/(0.1 cos 20°) at every angle (the pinion at 1200 rpm cw, so its torque is ccw +5 then)
    text = (EXAMPLES / "gear_pair.yaml").read_text()
    text = text[: text.index("\nanswers:")] + "\nloads: {wheel: {torque: 10}}\n"
    mech = loads(text, path="gears.yaml")
    assert not Evaluator(mech).batched
    cycle = force_cycle(mech, steps=6)
    tooth = 10 / (0.100 * math.cos(math.radians(20)))
    assert cycle.mean is not None and abs(cycle.mean) == pytest.approx(5.0, rel=1e-9)
    assert cycle.fluctuation == pytest.approx(0.0, abs=1e-9 * 5 * 2 * math.pi)
    mesh = next(p for p in cycle.peaks if p.quantity == "force.mesh")
    assert mesh.value == pytest.approx(tooth, rel=1e-9)


def test_a_redundant_chain_gives_its_torque_over_the_cycle_but_no_pair_forces():
    text = (EXAMPLES / "double_parallelogram.yaml").read_text()
    text = text[: text.index("\nanswers:")] + "\nloads: {coupler: {torque: 5}}\n"
    # (away from 0° and 180°, where its rows are singular and no rate is given)
    cycle = force_cycle(loads(text, path="dp.yaml"), start=math.radians(10), stop=math.radians(170), steps=12)
    assert cycle.mean == pytest.approx(0.0, abs=1e-9)  # a torque on a translating link does no work
    assert np.isnan(cycle.series.forces).all() and cycle.peaks == ()
    assert any("indeterminate" in n for n in cycle.notes)


@pytest.mark.parametrize(("spans", "cycle"), [((), 360), ((720,), 720), ((360, 720), 720), ((500,), 9000)])
def test_the_default_range_is_the_least_whole_number_of_turns_holding_every_table(spans, cycle):
    table = "".join(
        f"  t{i}: {{torque: {{table: [[0, 0], [{s / 2:g}, 1], [{s:g}, 0]]}}}}\n" for i, s in enumerate(spans)
    )
    links = "".join(f", t{i}" for i in range(len(spans)))
    joints = "".join(
        f"  P{i}: {{type: revolute, links: [frame, t{i}], at: [{i + 1}, 0]}}\n" for i in range(len(spans))
    )
    text = f"""\
units: {{length: m, angle: deg}}
links: [frame, crank{links}]
joints:
  O: {{type: revolute, links: [frame, crank], at: [0, 0]}}
{joints}lengths: {{}}
drive: {{link: crank, angle: 0, rpm: 60}}
""" + (f"loads:\n{table}" if spans else "")
    assert math.degrees(cycle_span(loads(text, path="spans.yaml"))) == pytest.approx(cycle)


def test_gauss_legendre_pieces_integrate_a_septic_exactly():
    def f(x: np.ndarray) -> np.ndarray:
        return 3 * x**7 - x**4 + 2

    a, b = np.array([0.0, 0.3]), np.array([0.3, 1.7])
    exact = [
        (3 * q**8 / 8 - q**5 / 5 + 2 * q) - (3 * p**8 / 8 - p**5 / 5 + 2 * p)
        for p, q in zip(a, b, strict=True)
    ]
    assert integrate(f, a, b) == pytest.approx(exact, rel=1e-14)


def test_a_programme_cam_is_swept_at_once_and_pushes_along_its_normal_at_every_step():
    # the cam's law row moves the follower; its push row (along the common normal at the contact)
    # carries the force: batched, and equal to the instant's analysis at every step.  At the file's
    # own instant, 60° into a simple-harmonic rise (h = 30 mm over 120°, base 40, roller 10, in
    # line): tan φ = (ds/dθ) / (r_b + r_r + s) = 22.5 / 65, so the guide takes 100 tan φ sideways
    text = (EXAMPLES / "cam_roller_program.yaml").read_text().split("\nanswers:")[0]
    mech = loads(text + '\nloads: {K: {force: [0, -100], "on": follower}}\n', path="cam.yaml")
    evaluator = Evaluator(mech)
    assert evaluator.batched
    angles = np.radians([-60.0, -10.0, -100.0, -200.0, -300.0])  # turning cw from +x
    series = evaluator(angles)
    for k, theta in enumerate(angles):
        fa = analyse(mech, SolveOptions(angle=float(theta)))
        assert fa.effort is not None
        assert series.effort[k] == pytest.approx(fa.effort.value, rel=1e-9, abs=1e-12)
        for i, (joint, _, _) in enumerate(series.pairs):
            assert series.forces[k, i] == pytest.approx(fa.pair(joint).force, rel=1e-9, abs=1e-9)
    guide = series.pairs.index(next(p for p in series.pairs if p[0] == "S"))
    assert series.magnitude(guide)[0] == pytest.approx(100 * 22.5 / 65, rel=1e-9)


def test_a_steady_effort_swings_no_energy_and_names_no_greatest_or_least_speed():
    # a gear pair held by a constant torque: T is the same at every angle, so E(θ) = ∫(T_mean − T) dθ
    # is 0 throughout — what is left is rounding (3e-13 J was said, greatest at 0° and least at 142°)
    text = (EXAMPLES / "gear_pair.yaml").read_text().split("\nanswers:")[
        0
    ] + "\nloads: {wheel: {torque: 10}}\n"
    cycle = force_cycle(loads(text, path="gears.yaml"), steps=36)
    assert cycle.fluctuation == 0.0
    assert cycle.greatest is None and cycle.least is None
