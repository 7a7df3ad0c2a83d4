"""Speed against accuracy: Newton's tolerance, the closed form, and sweeps coarse and fine.

    python tests/benchmarks/bench_accuracy.py

Mechanisms: the four-bar, the slider crank and the Watt six-bar of
``mechanisms/``.  The reference is the closed-form (dyad) solution evaluated
in 40-digit arithmetic with mpmath — the same generated program, run on
mpmath numbers instead of floats, so it is exact for the file's data to far
below double precision.  (The float closed form and Newton are also checked
against textbook closed forms in the tests.)  Errors are the largest over
all points: positions relative to the mechanism's size, velocities to the
largest speed, accelerations to the largest acceleration.

Tables:

1. one solve at a moved angle: Newton with ``tol`` 1e-3 … 1e-12 against the
   closed form (time per solve, median, and error);
2. a whole turn: per-step Newton continuation against the vectorised closed
   form (time and error over the sweep);
3. extremes: the largest slider speed and rocker ω read off grids of 12 …
   3,600 steps, and refined by the sweep, against the exact extremes.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # a shared 2-core machine: threads only add noise here

import math
import statistics
import timeit
from pathlib import Path

import mpmath
import numpy as np

import mech
from mech.kinematics import closed_form, solve, sweep
from mech.options import SolveOptions

ROOT = Path(__file__).resolve().parents[2]
CASES = {"four-bar": "four_bar", "slider crank": "slider_crank", "Watt six-bar": "watt_six_bar"}


def median_time(fn, number: int, repeat: int = 7) -> float:
    return statistics.median(t / number for t in timeit.repeat(fn, number=number, repeat=repeat))


def reference(prog, phi: float, w: float, al: float) -> dict[str, np.ndarray]:
    """Positions, velocities, accelerations of every point in 40 digits (returned as floats)."""
    with mpmath.workdps(40):
        clip = lambda x: x if x > 0 else mpmath.mpf(0)  # noqa: E731
        out = prog.function(2)(
            mpmath.mpf(phi),
            mpmath.mpf(w),
            mpmath.mpf(al),
            mpmath.sqrt,
            mpmath.cos,
            mpmath.sin,
            mpmath.atan2,
            clip,
        )
        parts = prog.split(out, 2)
        cx, cy = prog.centre
        pick = [k for k, p in enumerate(prog.points) if not p.startswith("#")]
        f = lambda seq: np.array([float(seq[k]) for k in pick])  # noqa: E731
        return {
            "p": np.stack([f(parts["px"]) + cx, f(parts["py"]) + cy], axis=1),
            "v": np.stack([f(parts["pvx"]), f(parts["pvy"])], axis=1),
            "a": np.stack([f(parts["pax"]), f(parts["pay"])], axis=1),
        }


def errors(kin, ref, names) -> tuple[float, float, float]:
    p = np.array([kin.positions[n] for n in names])
    v = np.array([kin.velocity(n) for n in names])
    a = np.array([kin.acceleration(n) for n in names])
    return (
        float(np.max(np.hypot(*(p - ref["p"]).T)) / kin.size),
        float(np.max(np.hypot(*(v - ref["v"]).T)) / np.max(np.hypot(*ref["v"].T))),
        float(np.max(np.hypot(*(a - ref["a"]).T)) / np.max(np.hypot(*ref["a"].T))),
    )


def table_tolerance() -> None:
    print("### 1. One solve (position, velocity, acceleration) at the drawn angle + 37°\n")
    print(
        "| mechanism | method | tol | time per solve | position error | velocity error | acceleration error |"
    )
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: |")
    for label, stem in CASES.items():
        m = mech.load(ROOT / "mechanisms" / f"{stem}.yaml")
        prog = closed_form(m)
        base = solve(m, "acceleration")
        d = base.drives[0]
        phi = d.angle + math.radians(37)
        names = [n for n in prog.points if not n.startswith("#")]
        ref = reference(prog, phi, d.omega, d.alpha or 0.0)
        rows = [("closed form", None)] + [("Newton", 10.0**-k) for k in range(3, 13)]
        for method, tol in rows:
            opts = SolveOptions(angle=phi, method="closed" if tol is None else "newton", tol=tol or 1e-12)
            kin = solve(m, "acceleration", opts)
            t = median_time(lambda m=m, o=opts: solve(m, "acceleration", o), 200 if tol is None else 50)
            ep, ev, ea = errors(kin, ref, names)
            print(
                f"| {label} | {method} | {'—' if tol is None else f'{tol:.0e}'} | {t * 1e6:.0f} µs | {ep:.1e} | {ev:.1e} | {ea:.1e} |"
            )


def table_sweeps() -> None:
    print("\n### 2. A whole turn: per-step Newton continuation against the vectorised closed form\n")
    print(
        "| mechanism | method | steps | time | per step | position error | velocity error | acceleration error |"
    )
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for label, stem in CASES.items():
        m = mech.load(ROOT / "mechanisms" / f"{stem}.yaml")
        prog = closed_form(m)
        d = solve(m, "acceleration").drives[0]
        for method, steps, tol in (
            ("Newton, tol 1e-6", 360, 1e-6),
            ("Newton, tol 1e-12", 360, 1e-12),
            ("closed form", 360, None),
            ("closed form", 3600, None),
        ):
            phi = d.angle + np.radians(np.linspace(0, 360, steps + 1))
            opts = SolveOptions(method="newton" if tol else "auto", tol=tol or 1e-12)
            s = sweep(m, phi, level="acceleration", options=opts, analyse=False)
            t = median_time(
                lambda m=m, p=phi, o=opts: sweep(m, p, level="acceleration", options=o, analyse=False),
                1,
                repeat=3 if tol else 9,
            )
            idx = np.linspace(0, steps, 13).astype(int)  # 13 angles checked in 40 digits
            ep = ev = ea = 0.0
            for k in idx:
                ref = reference(prog, float(phi[k]), d.omega, d.alpha or 0.0)
                pick = [s.points.index(n) for n in s.points]
                size = solve(m, "position").size
                ep = max(ep, float(np.max(np.hypot(*(s.positions[k, pick] - ref["p"]).T))) / size)
                ev = max(
                    ev,
                    float(
                        np.max(np.hypot(*(s.velocities[k, pick] - ref["v"]).T))
                        / np.max(np.hypot(*ref["v"].T))
                    ),
                )
                ea = max(
                    ea,
                    float(
                        np.max(np.hypot(*(s.accelerations[k, pick] - ref["a"]).T))
                        / np.max(np.hypot(*ref["a"].T))
                    ),
                )
            print(
                f"| {label} | {method} | {steps} | {t * 1e3:.2f} ms | {t / (steps + 1) * 1e6:.2f} µs | {ep:.1e} | {ev:.1e} | {ea:.1e} |"
            )


def exact_extreme(prog, key_fn, guess: float, w: float) -> float:
    """The extreme value of a quantity (root of its derivative in 40 digits)."""
    with mpmath.workdps(40):
        clip = lambda x: x if x > 0 else mpmath.mpf(0)  # noqa: E731

        def q(phi):
            out = prog.function(1)(
                phi, mpmath.mpf(w), 0, mpmath.sqrt, mpmath.cos, mpmath.sin, mpmath.atan2, clip
            )
            return key_fn(prog.split(out, 1))

        th = mpmath.findroot(lambda t: mpmath.diff(q, t), mpmath.mpf(guess))
        return float(q(th))


def table_extremes() -> None:
    print(
        "\n### 3. Extremes: read off the grid against refined by the sweep (relative error to the exact extreme)\n"
    )
    print("| mechanism | quantity | steps | grid maximum error | refined error | sweep time |")
    print("| --- | --- | ---: | ---: | ---: | ---: |")
    cases = [("slider crank", "slider_crank", "sliding.P"), ("four-bar", "four_bar", "omega.rocker")]
    for label, stem, key in cases:
        m = mech.load(ROOT / "mechanisms" / f"{stem}.yaml")
        prog = closed_form(m)
        d = solve(m, "velocity").drives[0]
        fine = sweep(m, np.radians(np.linspace(0, 360, 3601)), level="velocity", quantities=[key])
        ext = fine.extremes[0]
        if key.startswith("omega"):
            k = prog.links.index(key.split(".")[1])
            exact = exact_extreme(prog, lambda parts, k=k: parts["lw"][k], ext.max_angle, d.omega)
        else:
            k = prog.points.index("B")
            exact = exact_extreme(prog, lambda parts, k=k: parts["pvx"][k], ext.max_angle, d.omega)
        for steps in (12, 36, 360, 3600):
            phi = np.radians(np.linspace(0, 360, steps + 1))
            s = sweep(m, phi, level="velocity", quantities=[key])
            grid = float(np.nanmax(s.series(key)))
            t = median_time(
                lambda m=m, p=phi, k=key: sweep(m, p, level="velocity", quantities=[k]), 1, repeat=7
            )
            print(
                f"| {label} | max {key} | {steps} | {abs(grid - exact) / abs(exact):.1e} | {abs(s.extremes[0].max_value - exact) / abs(exact):.1e} | {t * 1e3:.2f} ms |"
            )


if __name__ == "__main__":
    table_tolerance()
    table_sweeps()
    table_extremes()
