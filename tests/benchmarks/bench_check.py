"""Throughput of ``mech check``: files per second over a generated homework set, 1 and 2 jobs.

Generates N problem files in a temporary folder — a mix like a real set: a
third DOF counts only (topology, no numpy), a third slider cranks with
velocity answers, a third four-bars with velocity and acceleration answers;
right, wrong and uncomputable answers, and one malformed file per hundred —
then times :func:`mech.batch.run` (the library call behind ``mech check``,
rendering excluded) several times per job count and prints the medians::

    python tests/benchmarks/bench_check.py            # 1,000 files, 5 repeats
    python tests/benchmarks/bench_check.py -n 200 -r 3

It also asserts that every file got exactly the verdicts it was built to get.
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import statistics
import sys
import tempfile
import time
from pathlib import Path

SLIDER = """\
name: slider crank {i}
units: {{length: mm, angle: deg}}
links: [frame, crank, rod, piston]
joints:
  O: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  A: {{type: revolute, links: [crank, rod]}}
  B: {{type: revolute, links: [rod, piston], near: [400, 0]}}
  P: {{type: prismatic, links: [piston, frame], path: {{through: [0, 0], angle: 0}}}}
lengths: {{OA: {r}, AB: {l}}}
drive: {{link: crank, angle: 90, rpm: {rpm}, direction: ccw}}
answers:
  dof: 1
  velocity.A: {va:.6g} m/s
  velocity.B: {wrong:.6g} m/s
  omega.rod: 0 rad/s
"""

FOUR_BAR = """\
name: four-bar {i}
units: {{length: mm, angle: deg}}
links: [frame, crank, coupler, rocker]
joints:
  A: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  B: {{type: revolute, links: [crank, coupler]}}
  C: {{type: revolute, links: [coupler, rocker], near: [160, 80]}}
  D: {{type: revolute, links: [rocker, frame], at: [150, 0]}}
lengths: {{AB: 40, BC: 150, CD: 80}}
drive: {{link: crank, angle: {angle}, rpm: {rpm}, direction: cw}}
answers:
  chain: four-bar
  velocity.B: {vb:.6g} m/s
  acceleration.B: {ab:.6g} m/s^2
  omega.crank: {w:.6g} rad/s ccw
"""

DOF = """\
name: count {i}
links: [frame, a, b, c, d]
joints:
  A: {{type: revolute, links: [frame, a]}}
  B: {{type: revolute, links: [a, b]}}
  C: {{type: revolute, links: [b, c]}}
  D: {{type: revolute, links: [c, d]}}
  E: {{type: revolute, links: [d, frame]}}
answers:
  dof: 2
  links.binary: 5
  icentres.count: {wrong}
"""


def generate(folder: Path, n: int) -> dict[str, dict[str, str]]:
    """Write n problem files; return the verdicts each must get (worked by hand below)."""
    expected: dict[str, dict[str, str]] = {}
    for i in range(n):
        path = folder / f"problem_{i:04d}.yaml"
        rpm = 60 + i % 240
        w = rpm * 2 * math.pi / 60
        if i % 100 == 99:
            path.write_text("links: [frame, crank\njoints: {A: {type: revolute\n")
            expected[str(path)] = {"file": "error"}
        elif i % 3 == 0:
            # five-bar: n = 3·4 − 2·5 = 2, five binary links, N = 5·4/2 = 10 I-centres (claim 11: wrong)
            path.write_text(DOF.format(i=i, wrong=11))
            expected[str(path)] = {"dof": "pass", "links.binary": "pass", "icentres.count": "fail"}
        elif i % 3 == 1:
            # crank at 90°: v_A = ω r; the rod translates, so v_B = v_A (claimed 10% high: wrong)
            r, rod = 100 + i % 50, 400
            va = w * r / 1000
            path.write_text(SLIDER.format(i=i, r=r, l=rod, rpm=rpm, va=va, wrong=1.1 * va))
            expected[str(path)] = {
                "dof": "pass",
                "velocity.A": "pass",
                "velocity.B": "fail",
                "omega.rod": "pass",
            }
        else:
            # crank AB = 40 mm at constant ω clockwise: v_B = ω·0.04, a_B = ω²·0.04 (no α);
            # the claimed sense of ω is wrong (ccw)
            angle = 30 + i % 120
            path.write_text(FOUR_BAR.format(i=i, angle=angle, rpm=rpm, vb=w * 0.04, ab=w * w * 0.04, w=w))
            expected[str(path)] = {
                "chain": "pass",
                "velocity.B": "pass",
                "acceleration.B": "pass",
                "omega.crank": "fail",
            }
    return expected


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-n", "--files", type=int, default=1000)
    parser.add_argument("-r", "--repeats", type=int, default=5)
    parser.add_argument("-j", "--jobs", type=int, nargs="+", default=[1, 2])
    args = parser.parse_args()

    from mech.batch import CheckOptions, run

    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        expected = generate(folder, args.files)
        rows = []
        for jobs in args.jobs:
            times = []
            for _ in range(args.repeats):
                start = time.perf_counter()
                report = run(CheckOptions((str(folder),), jobs=jobs))
                times.append(time.perf_counter() - start)
                got = {r.path: {v.key: v.status for v in r.verdicts} for r in report.results}
                if got != expected:
                    bad = [p for p in expected if got.get(p) != expected[p]][:3]
                    sys.exit(f"wrong verdicts with {jobs} jobs, e.g. {[(p, got.get(p)) for p in bad]}")
            median = statistics.median(times)
            rows.append((jobs, median, min(times), args.files / median))
    print(
        f"mech check: {args.files} generated files, median of {args.repeats} runs "
        f"({platform.python_implementation()} {platform.python_version()}, {os.cpu_count()} cores)"
    )
    print()
    print("| jobs | median (s) | best (s) | files/s (median) |")
    print("| ---: | ---: | ---: | ---: |")
    for jobs, median, best, rate in rows:
        print(f"| {jobs} | {median:.2f} | {best:.2f} | {rate:,.0f} |")
    print()
    print(
        f"verdicts: {report.passed} passed, {report.failed} failed, {report.errors} errors — all as generated"
    )


if __name__ == "__main__":
    main()
