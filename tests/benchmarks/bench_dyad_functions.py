"""Issue 12's question, measured: the closed-form dyads as ordinary functions instead of generated code.

    pip install -e '.[bench]'                      # pylinkage, for the reference row
    python tests/benchmarks/bench_dyad_functions.py [--repeat 7]

The four-bar of mechanisms/four_bar.yaml (AB 40, BC 150, CD 80, AD 150 mm) is written here by
hand as ordinary functions: one closure per step of the program mech generates for it (ground,
crank, its pivot, B on the crank, D on the ground, the RRR apex C, the coupler and the rocker
posed from two points each), the same formulas as mech.kinematics.dyads, over a list of
registers.  It must agree with the generated function to 1e-12 (checked before timing), and
both run on floats (one configuration) and on arrays (3,601 crank angles) in one interleaved
run, with the benchmark table's rows beside them (the lean ``state``, pylinkage's one step with
derivatives, the four-bar's 3,600-step sweep).  The figures quoted in the dyads module's
docstring come from this script.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # a shared 2-core machine: threads only add noise here

import argparse
import math
import statistics
import sys
import timeit
from collections.abc import Callable
from operator import itemgetter
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE))

import mech  # noqa: E402
from mech.kinematics import closed_form, sweep  # noqa: E402
from mech.kinematics.dyads import MATH, numpy_namespace  # noqa: E402

Step = Callable[[list[Any], Any, Any, Any, Any], None]


class Registers:
    """Names → slots of the register list the steps read and write."""

    def __init__(self) -> None:
        self.slot: dict[str, int] = {}

    def __call__(self, name: str) -> int:
        return self.slot.setdefault(name, len(self.slot))

    def link(self, i: int, *what: str) -> list[int]:
        return [self(f"l{i}_{w}") for w in what]

    def point(self, k: int, *what: str) -> list[int]:
        return [self(f"p{k}_{w}") for w in what]


R = Registers()
XYVA = ("x", "y", "vx", "vy", "ax", "ay")


def ground(gi: int) -> Step:
    pairs = list(
        zip(
            R.link(gi, "x", "y", "t", "c", "s", "vx", "vy", "w", "ax", "ay", "al"),
            [0.0] * 3 + [1.0] + [0.0] * 7,
            strict=True,
        )
    )

    def step(r: list[Any], phi: Any, omega: Any, alpha: Any, xp: Any) -> None:
        for k, v in pairs:
            r[k] = v

    return step


def crank(i: int, c0: float) -> Step:
    t, w, al = R.link(i, "t", "w", "al")

    def step(r: list[Any], phi: Any, omega: Any, alpha: Any, xp: Any) -> None:
        r[t] = phi + c0
        r[w] = omega
        r[al] = alpha

    return step


def ground_point(k: int, x: float, y: float) -> Step:
    ix, iy, ivx, ivy, iax, iay = R.point(k, *XYVA)

    def step(r: list[Any], phi: Any, omega: Any, alpha: Any, xp: Any) -> None:
        r[ix], r[iy], r[ivx], r[ivy], r[iax], r[iay] = x, y, 0.0, 0.0, 0.0, 0.0

    return step


def link_point(k: int, i: int, sx: float, sy: float) -> Step:
    ix, iy, ivx, ivy, iax, iay = R.point(k, *XYVA)
    lx, ly, lc, ls, lvx, lvy, lw, lax, lay, lal = R.link(
        i, "x", "y", "c", "s", "vx", "vy", "w", "ax", "ay", "al"
    )

    def step(r: list[Any], phi: Any, omega: Any, alpha: Any, xp: Any) -> None:
        c, s, w, al = r[lc], r[ls], r[lw], r[lal]
        rx = c * sx - s * sy
        ry = s * sx + c * sy
        r[ix] = r[lx] + rx
        r[iy] = r[ly] + ry
        r[ivx] = r[lvx] - w * ry
        r[ivy] = r[lvy] + w * rx
        r[iax] = r[lax] - al * ry - w * w * rx
        r[iay] = r[lay] + al * rx - w * w * ry

    return step


def place_from_point(i: int, k: int, sx: float, sy: float) -> Step:
    px, py, pvx, pvy, pax, pay = R.point(k, *XYVA)
    lt, lx, ly, lc, ls, lvx, lvy, lw, lax, lay, lal = R.link(
        i, "t", "x", "y", "c", "s", "vx", "vy", "w", "ax", "ay", "al"
    )

    def step(r: list[Any], phi: Any, omega: Any, alpha: Any, xp: Any) -> None:
        t, w, al = r[lt], r[lw], r[lal]
        c, s = xp.cos(t), xp.sin(t)
        r[lc], r[ls] = c, s
        rx = c * sx - s * sy
        ry = s * sx + c * sy
        r[lx] = r[px] - rx
        r[ly] = r[py] - ry
        r[lvx] = r[pvx] + w * ry
        r[lvy] = r[pvy] - w * rx
        r[lax] = r[pax] + al * ry + w * w * rx
        r[lay] = r[pay] - al * rx + w * w * ry

    return step


def rrr(kd: int, j: int, p: int, q: int, lp: float, lq: float, sign: float) -> Step:
    pi, qi, ji = R.point(p, *XYVA), R.point(q, *XYVA), R.point(j, *XYVA)
    d, sn, ms = R(f"d{kd}"), R(f"sn{kd}"), R(f"ms{kd}")
    s2, m2 = (lp + lq) ** 2, (lp - lq) ** 2
    inv, low, high = 1.0 / (s2 * s2), abs(lp - lq) - (lp + lq), abs(lp - lq) + lp + lq
    l2, inv_pq = lp * lp - lq * lq, 1.0 / (lp * lq)

    def step(r: list[Any], phi: Any, omega: Any, alpha: Any, xp: Any) -> None:
        pxx, pyy, pvx, pvy, pax, pay = (r[k] for k in pi)
        qxx, qyy, qvx, qvy, qax, qay = (r[k] for k in qi)
        dx = qxx - pxx
        dy = qyy - pyy
        dd = dx * dx + dy * dy
        f1 = s2 - dd
        f2 = dd - m2
        r[d] = f1 * f2 * inv - (dd == 0.0)
        dd = dd + (dd == 0.0)
        r[ms] = (low + abs(2.0 * xp.sqrt(dd) - high)) * 0.5
        a = (l2 + dd) / (2.0 * dd)
        h = sign * xp.sqrt(xp.clip(f1 * f2)) / (2.0 * dd)
        jx = pxx + a * dx - h * dy
        jy = pyy + a * dy + h * dx
        epx, epy, eqx, eqy = jx - pxx, jy - pyy, jx - qxx, jy - qyy
        det = epx * eqy - epy * eqx
        r[sn] = det * inv_pq
        det = det + (det == 0.0)
        r1 = epx * pvx + epy * pvy
        r2 = eqx * qvx + eqy * qvy
        jvx = (r1 * eqy - epy * r2) / det
        jvy = (epx * r2 - r1 * eqx) / det
        ux, uy, wx, wy = jvx - pvx, jvy - pvy, jvx - qvx, jvy - qvy
        r1 = epx * pax + epy * pay - ux * ux - uy * uy
        r2 = eqx * qax + eqy * qay - wx * wx - wy * wy
        r[ji[0]], r[ji[1]], r[ji[2]], r[ji[3]] = jx, jy, jvx, jvy
        r[ji[4]] = (r1 * eqy - epy * r2) / det
        r[ji[5]] = (epx * r2 - r1 * eqx) / det

    return step


def pose2(i: int, a: int, b: int, beta: float) -> Step:
    ai, bi = R.point(a, *XYVA), R.point(b, *XYVA)
    t, w, al = R.link(i, "t", "w", "al")

    def step(r: list[Any], phi: Any, omega: Any, alpha: Any, xp: Any) -> None:
        dx = r[bi[0]] - r[ai[0]]
        dy = r[bi[1]] - r[ai[1]]
        r[t] = xp.atan2(dy, dx) - beta
        dd = dx * dx + dy * dy
        dd = dd + (dd == 0.0)
        r[w] = (dx * (r[bi[3]] - r[ai[3]]) - dy * (r[bi[2]] - r[ai[2]])) / dd
        r[al] = (dx * (r[bi[5]] - r[ai[5]]) - dy * (r[bi[4]] - r[ai[4]])) / dd

    return step


def four_bar_functions(m: Any) -> Callable[..., tuple[Any, ...]]:
    """The four-bar's program (as ``closed_form(m).steps`` lists it) as ordinary functions.

    Links 0 crank, 1 coupler, 2 rocker, 3 ground; points 0 A, 1 B, 2 C, 3 D (the generated
    program's order).  Frames as mech draws them: the crank's origin at A toward B, the
    coupler's at B toward C, the rocker's at C (its x axis from D toward C, so C→D is at π).
    """
    length = {f"{ln.a}{ln.b}": ln.value for ln in m.lengths}
    ad = m.joint("D").place.at[0] - m.joint("A").place.at[0]
    steps = [
        ground(3),
        crank(0, 0.0),
        ground_point(0, 0.0, 0.0),
        place_from_point(0, 0, 0.0, 0.0),
        link_point(1, 0, length["AB"], 0.0),
        ground_point(3, ad, 0.0),
        rrr(0, 2, 1, 3, length["BC"], length["CD"], 1.0),
        pose2(1, 1, 2, 0.0),
        place_from_point(1, 1, 0.0, 0.0),
        pose2(2, 2, 3, math.pi),
        place_from_point(2, 2, length["CD"], 0.0),
    ]
    names = [f"{w}0" for w in ("d", "sn", "ms")]
    names += [f"l{i}_{w}" for w in ("x", "y", "t") for i in range(3)]
    names += [f"p{k}_{w}" for w in ("x", "y") for k in range(4)]
    names += [f"l{i}_{w}" for w in ("vx", "vy", "w") for i in range(3)]
    names += [f"p{k}_{w}" for w in ("vx", "vy") for k in range(4)]
    names += [f"l{i}_{w}" for w in ("ax", "ay", "al") for i in range(3)]
    names += [f"p{k}_{w}" for w in ("ax", "ay") for k in range(4)]
    out = itemgetter(*[R.slot[n] for n in names])
    size = len(R.slot)

    def run(phi: Any, omega: Any, alpha: Any, xp: Any = MATH) -> tuple[Any, ...]:
        r: list[Any] = [0.0] * size
        for s in steps:
            s(r, phi, omega, alpha, xp)
        return out(r)  # type: ignore[no-any-return]

    return run


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args()
    m = mech.load(ROOT / "mechanisms" / "four_bar.yaml")
    prog = closed_form(m)
    generated = prog.function(2)
    functions = four_bar_functions(m)
    nx = numpy_namespace()
    phi = math.radians(97.0)
    phis = np.radians(np.linspace(0.0, 360.0, 3601))
    omega = -4 * math.pi

    def gen_float() -> tuple[Any, ...]:
        return generated(phi, omega, 0.0, MATH.sqrt, MATH.cos, MATH.sin, MATH.atan2, MATH.clip)

    def gen_array() -> tuple[Any, ...]:
        return generated(phis, omega, 0.0, nx.sqrt, nx.cos, nx.sin, nx.atan2, nx.clip)

    a, b = gen_float(), functions(phi, omega, 0.0)
    assert max(abs(x - y) for x, y in zip(a, b, strict=True)) < 1e-12, (
        "the functions disagree with the program"
    )
    for x, y in zip(gen_array(), functions(phis, omega, 0.0, nx), strict=True):
        assert np.allclose(
            np.broadcast_to(x, phis.shape), np.broadcast_to(y, phis.shape), rtol=0.0, atol=1e-12
        )

    cases: dict[str, tuple[Callable[[], object], int]] = {
        "generated, floats": (gen_float, 5000),
        "functions, floats": (lambda: functions(phi, omega, 0.0), 5000),
        "generated, 3,601 angles": (gen_array, 50),
        "functions, 3,601 angles": (lambda: functions(phis, omega, 0.0, nx), 50),
        "lean state (generated)": (lambda: prog.state(phi, omega, 0.0), 5000),
        "sweep series, 3,600 steps": (lambda: sweep(m, phis, level="acceleration", analyse=False), 1),
    }
    try:
        from bench_peers import pylinkage_models

        model = pylinkage_models()[0][0]
        cases["pylinkage one step (+ v, a)"] = (
            lambda: next(iter(model.step_with_derivatives(iterations=1))),
            500,
        )
    except ImportError:
        print("pylinkage is not installed (pip install -e '.[bench]'): its row is left out", file=sys.stderr)
    sweep(m, phis[:10], level="acceleration", analyse=False)  # compile outside the timing
    samples: dict[str, list[float]] = {name: [] for name in cases}
    for _ in range(args.repeat):  # interleaved: a burst of load falls on every case alike
        for name, (fn, number) in cases.items():
            samples[name].append(min(timeit.repeat(fn, number=number, repeat=3)) / number)
    med = {name: statistics.median(v) for name, v in samples.items()}
    print(f"median of {args.repeat} interleaved repeats")
    print("| case | time | ratio |")
    print("| --- | ---: | ---: |")
    for name, ref in (
        ("generated, floats", None),
        ("functions, floats", "generated, floats"),
        ("generated, 3,601 angles", None),
        ("functions, 3,601 angles", "generated, 3,601 angles"),
        ("lean state (generated)", "pylinkage one step (+ v, a)"),
        ("sweep series, 3,600 steps", None),
        ("pylinkage one step (+ v, a)", None),
    ):
        if name not in med:
            continue
        ratio = f"{med[name] / med[ref]:.2f}× {ref}" if ref in med else ""
        print(f"| {name} | {med[name] * 1e6:.2f} µs | {ratio} |")


if __name__ == "__main__":
    main()
