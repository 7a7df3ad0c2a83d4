"""Solve time against the number of links: generated chains of 4, 6, 8, … 40 links.

    python tests/benchmarks/bench_growth.py

Each chain is a crank driving (n − 2)/2 coupler–rocker dyads from its pin B
(one joint of many links), each closing on its own frame pivot: every stage
adds two links, the chain keeps one degree of freedom, and it decomposes into
RRR dyads, so both solvers apply.  Timed (medians):
Newton (``method="newton"``, moved 5° from the drawing, tol 1e-12), the
closed form through :func:`solve` (full result), the lean closed form
(``closed_form(m).state``) and a 360-step vectorised sweep of the full turn.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # a shared 2-core machine: threads only add noise here

import math
import statistics
import timeit

import numpy as np

from mech.kinematics import closed_form, solve, sweep
from mech.model import Drive, Joint, Length, Link, Mechanism, Placement
from mech.options import SolveOptions

FRAME, COUPLER, ROCKER, CRANK = 0.15, 0.15, 0.08, 0.04


def chain(n_links: int) -> Mechanism:
    """A one-DOF chain of ``n_links`` links (even, ≥ 4): a crank driving (n − 2)/2 coupler–rocker dyads.

    Every dyad hangs from the crank pin B (a joint of many links) and closes on
    its own frame pivot G(i), placed round A so that each stage is the same
    Grashof crank-rocker turned through 360°·i/stages: the chain assembles
    and turns fully at any size.
    """
    stages = (n_links - 2) // 2
    links = [Link("frame", 0, is_ground=True), Link("crank", 1)]
    joints = [Joint("A", "revolute", ("frame", "crank"), Placement(at=(0.0, 0.0)))]
    lengths = [Length("A", "B", CRANK)]
    on_b = ["crank"]
    for i in range(1, stages + 1):
        beta = 2 * math.pi * (i - 1) / stages
        links += [Link(f"coupler{i}", len(links)), Link(f"rocker{i}", len(links) + 1)]
        on_b.append(f"coupler{i}")
        joints.append(Joint(f"J{i}", "revolute", (f"coupler{i}", f"rocker{i}")))
        at = (FRAME * math.cos(beta), FRAME * math.sin(beta))
        joints.append(Joint(f"G{i}", "revolute", (f"rocker{i}", "frame"), Placement(at=at)))
        lengths += [Length("B", f"J{i}", COUPLER), Length(f"G{i}", f"J{i}", ROCKER)]
    joints.insert(1, Joint("B", "revolute", tuple(on_b)))
    return Mechanism(
        name=f"{n_links}-link chain",
        path="<generated>",
        ground="frame",
        links=tuple(links),
        joints=tuple(joints),
        lengths=tuple(lengths),
        drives=(Drive(link="crank", angle=math.radians(60), omega=10.0),),
    )


def median_time(fn, number: int, repeat: int = 5) -> float:
    return statistics.median(t / number for t in timeit.repeat(fn, number=number, repeat=repeat))


def main() -> None:
    print(
        "| links | Newton solve | closed form, `solve` | closed form, lean | sweep 360 steps | Newton / closed |"
    )
    print("| ---: | ---: | ---: | ---: | ---: | ---: |")
    for n in range(4, 42, 2):
        m = chain(n)
        target = math.radians(65)
        newton = SolveOptions(angle=target, method="newton")
        closed = SolveOptions(angle=target)
        k_n = solve(m, "acceleration", newton)
        k_c = solve(m, "acceleration", closed)
        worst = max(math.dist(k_n.positions[p], k_c.positions[p]) for p in k_n.positions) / k_n.size
        assert worst < 1e-9, (n, worst)
        prog = closed_form(m)
        assert prog is not None
        reps = max(20, 400 // n)
        t_n = median_time(lambda m=m, o=newton: solve(m, "acceleration", o), max(5, reps // 4))
        t_c = median_time(lambda m=m, o=closed: solve(m, "acceleration", o), reps)
        t_l = median_time(lambda p=prog, a=target: p.state(a, 10.0, 0.0), reps * 20)
        phi = np.radians(np.linspace(0, 360, 361))
        t_s = median_time(lambda m=m, p=phi: sweep(m, p, level="acceleration", analyse=False), 5)
        print(
            f"| {n} | {t_n * 1e3:.2f} ms | {t_c * 1e6:.0f} µs | {t_l * 1e6:.1f} µs | {t_s * 1e3:.2f} ms | "
            f"{t_n / t_c:.0f}× |"
        )


if __name__ == "__main__":
    main()
