"""mech against pylinkage, side by side, in one run: one solve, and a 3,600-step sweep.

    pip install -e '.[bench]'        # pylinkage (MIT), the benchmark extra
    python tests/benchmarks/bench_peers.py

The same four-bar (mechanisms/four_bar.yaml: AB 40, BC 150, CD 80, AD 150 mm,
120 rpm cw) and slider crank (mechanisms/slider_crank.yaml: crank 150, rod
600 mm, 300 rpm cw) are built in both.  Timings are medians of repeated runs
(``timeit``, 7 repeats); ratios are pylinkage time / mech time (above 1: mech
is faster).  Agreement: the largest difference of positions, velocities and
accelerations over the 3,600 steps, relative to the largest value of each.

pylinkage 1.3 gives velocities and accelerations (``step_with_derivatives``,
after ``set_input_velocity``), so all three are compared.  Without numba
(not installed here) its ``step_fast`` runs the same solver in plain Python.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # a shared 2-core machine: threads only add noise here

import math
import platform
import statistics
import sys
import timeit
from pathlib import Path

import numpy as np

import mech
from mech.kinematics import closed_form, solve, sweep
from mech.options import SolveOptions

ROOT = Path(__file__).resolve().parents[2]
N = 3600


def median_time(fn, number: int, repeat: int = 7) -> float:
    """Median seconds per call over ``repeat`` runs of ``number`` calls."""
    return statistics.median(t / number for t in timeit.repeat(fn, number=number, repeat=repeat))


def fmt(t: float) -> str:
    return f"{t * 1e6:9.1f} µs" if t < 1e-3 else f"{t * 1e3:9.2f} ms"


def pylinkage_models():
    """The two mechanisms in pylinkage, started at the same angles, branches as drawn in mech."""
    from pylinkage.actuators import Crank
    from pylinkage.components import Ground
    from pylinkage.dyads import RRPDyad, RRRDyad
    from pylinkage.simulation import Linkage

    step = 2 * math.pi / N
    # four-bar: crank turns clockwise, so a negative step
    a = Ground(0.0, 0.0, name="A")
    d = Ground(0.15, 0.0, name="D")
    crank = Crank(a, 0.04, angular_velocity=-step, initial_angle=math.radians(60), name="B")
    c = RRRDyad(crank.output, d, 0.15, 0.08, x=0.16333, y=0.07888, name="C")
    four = Linkage([a, d, crank, c], name="four-bar")
    four.set_input_velocity(crank, omega=-4 * math.pi)
    # slider crank: piston to the left on the x axis
    o = Ground(0.0, 0.0, name="O")
    far = Ground(-1.0, 0.0, name="far")
    crank2 = Crank(o, 0.15, angular_velocity=-step, initial_angle=math.radians(135), name="A")
    b = RRPDyad(crank2.output, o, far, 0.6, x=-0.6966, y=0.0, name="B")
    slider = Linkage([o, far, crank2, b], name="slider crank")
    slider.set_input_velocity(crank2, omega=-10 * math.pi)
    return (four, 3, "C"), (slider, 3, "B")


def main() -> None:
    try:
        import pylinkage
    except ImportError:
        sys.exit("pylinkage is not installed: pip install -e '.[bench]'")
    cases = [
        ("four-bar", mech.load(ROOT / "mechanisms" / "four_bar.yaml"), "C", math.radians(60), -4 * math.pi),
        (
            "slider crank",
            mech.load(ROOT / "mechanisms" / "slider_crank.yaml"),
            "B",
            math.radians(135),
            -10 * math.pi,
        ),
    ]
    models = pylinkage_models()
    print(
        f"mech vs pylinkage {pylinkage.__version__} (numba: no) — Python {platform.python_version()}, "
        f"numpy {np.__version__}, {platform.machine()}, medians of 7"
    )
    print()
    rows = []
    for (label, m, point, phi0, w), (model, index, _) in zip(cases, models, strict=True):
        target = phi0 + math.radians(37.0)  # a moved angle
        opts = SolveOptions(angle=target)
        solve(m, "acceleration", opts)
        solve(m, "acceleration", SolveOptions())
        prog = closed_form(m)
        t_rich = median_time(lambda m=m, o=opts: solve(m, "acceleration", o), 2000)
        # the file's own drive angle: what `mech velocity FILE` and a homework file ask
        t_drawn = median_time(lambda m=m: solve(m, "acceleration", SolveOptions()), 2000)
        t_lean = median_time(lambda p=prog, a=target, w=w: p.state(a, w, 0.0), 20000)

        def pl_one(model=model):
            return next(iter(model.step_with_derivatives(iterations=1)))

        t_pl_one = median_time(pl_one, 2000)
        phi = phi0 - np.arange(1, N + 1) * (2 * math.pi / N)  # the angles pylinkage visits
        sweep(m, phi, level="acceleration", analyse=False)
        t_sweep = median_time(lambda m=m, p=phi: sweep(m, p, level="acceleration", analyse=False), 20)
        t_sweep_full = median_time(lambda m=m, p=phi: sweep(m, p, level="acceleration"), 5)

        def pl_sweep(model=model):
            return list(model.step_with_derivatives(iterations=N))

        t_pl_sweep = median_time(pl_sweep, 1, repeat=5)
        t_pl_pos = median_time(lambda model=model: list(model.step(iterations=N)), 1, repeat=5)
        # agreement over one revolution from the same start
        fresh = pylinkage_models()[0 if label == "four-bar" else 1][0]
        got = list(fresh.step_with_derivatives(iterations=N))
        pl_p = np.array([g[0][index] for g in got])
        pl_v = np.array([g[1][index] for g in got])
        pl_a = np.array([g[2][index] for g in got])
        s = sweep(m, phi, level="acceleration", analyse=False)
        k = s.points.index(point)
        err = [
            float(np.max(np.abs(ours - theirs)) / np.max(np.abs(ours)))
            for ours, theirs in (
                (s.positions[:, k], pl_p),
                (s.velocities[:, k], pl_v),
                (s.accelerations[:, k], pl_a),
            )
        ]
        rows.append(
            (label, t_rich, t_drawn, t_lean, t_pl_one, t_sweep, t_sweep_full, t_pl_sweep, t_pl_pos, err)
        )

    print("| mechanism | task | mech | pylinkage | ratio |")
    print("| --- | --- | ---: | ---: | ---: |")
    for label, t_rich, t_drawn, t_lean, t_pl_one, t_sweep, t_full, t_pl_sweep, t_pl_pos, _ in rows:
        print(
            f"| {label} | one position + v + a, lean (`closed_form(m).state`) | {fmt(t_lean)} | {fmt(t_pl_one)} | {t_pl_one / t_lean:.1f}× |"
        )
        print(
            f"| {label} | one position + v + a at the drawn angle (`solve`) | {fmt(t_drawn)} | {fmt(t_pl_one)} | {t_pl_one / t_drawn:.2f}× |"
        )
        print(
            f"| {label} | one position + v + a at the drawn angle + 37° (`solve`) | {fmt(t_rich)} | {fmt(t_pl_one)} | {t_pl_one / t_rich:.2f}× |"
        )
        print(
            f"| {label} | 3,600 steps, positions + v + a (`sweep(analyse=False)`) | {fmt(t_sweep)} | {fmt(t_pl_sweep)} | {t_pl_sweep / t_sweep:.0f}× |"
        )
        print(
            f"| {label} | 3,600 steps + extremes, dead centres, time ratio (`sweep`) | {fmt(t_full)} | {fmt(t_pl_sweep)} | {t_pl_sweep / t_full:.1f}× |"
        )
        print(
            f"| {label} | 3,600 steps, positions only (pylinkage `step`) | {fmt(t_sweep)} | {fmt(t_pl_pos)} | {t_pl_pos / t_sweep:.0f}× |"
        )
    print()
    print(
        "| mechanism | largest difference over 3,600 steps (relative) | position | velocity | acceleration |"
    )
    print("| --- | --- | ---: | ---: | ---: |")
    for label, *_, err in rows:
        print(f"| {label} | mech − pylinkage | {err[0]:.1e} | {err[1]:.1e} | {err[2]:.1e} |")


if __name__ == "__main__":
    main()
