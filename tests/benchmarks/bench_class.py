"""A class graded as a teacher grades it: ``mech check problems/ --answers sheets/ --gradebook``.

Generates five problem files (a DOF count, a slider crank's velocities, a four-bar's velocities
and accelerations, a four-bar's properties, a quick-return time ratio) with marks, and N answer
sheets (default 1,000) with right, wrong, unit-slipped and missing answers, then runs the
installed ``mech check problems/ --answers sheets/ --gradebook grades.csv --junit out.xml`` in a
fresh process several times and prints the median wall time, the CPU of every process, sheets
per second and the peak resident memory of the largest process::

    python tests/benchmarks/bench_class.py                   # 1,000 sheets × 5 problems, 3 runs
    python tests/benchmarks/bench_class.py -n 200 -r 5 --mech /path/to/bin/mech

Target (issue 22, 2 cores): a class of 1,000 sheets × 5 problems graded in under 5 s.  It also
checks that the gradebook has one row per student and that the marks add up.
"""

from __future__ import annotations

import argparse
import csv
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

PROBLEMS = {
    "count.yaml": """\
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker]}
  D: {type: revolute, links: [rocker, frame]}
asks: {dof: 1, links.binary: 1}
""",
    "slider.yaml": """\
units: {length: mm, angle: deg}
links: [frame, crank, rod, piston]
joints:
  O: {type: revolute, links: [frame, crank], at: [0, 0]}
  A: {type: revolute, links: [crank, rod]}
  B: {type: revolute, links: [rod, piston], near: [400, 0]}
  P: {type: prismatic, links: [piston, frame], path: {through: [0, 0], angle: 0}}
lengths: {OA: 100, AB: 300}
drive: {link: crank, angle: 90, omega: 10, direction: ccw}
asks: {velocity.B: 2, omega.rod: 1}
""",
    "four_bar.yaml": """\
units: {length: mm, angle: deg}
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [160, 80]}
  D: {type: revolute, links: [rocker, frame], at: [150, 0]}
lengths: {AB: 40, BC: 150, CD: 80}
drive: {link: crank, angle: 60, rpm: 120, direction: cw}
asks: {omega.rocker: 2, velocity.C: 2, acceleration.C: 3}
""",
}
PROBLEMS["properties.yaml"] = PROBLEMS["four_bar.yaml"].replace(
    "asks: {omega.rocker: 2, velocity.C: 2, acceleration.C: 3}",
    "asks: {grashof: 1, transmission_angle.min: 2}",
)
PROBLEMS["time_ratio.yaml"] = PROBLEMS["four_bar.yaml"].replace(
    "asks: {omega.rocker: 2, velocity.C: 2, acceleration.C: 3}", "asks: {time_ratio: 2}"
)
OUT_OF = 1 + 1 + 2 + 1 + 2 + 2 + 3 + 1 + 2 + 2

# right answers (from mech key on these files; the grading's correctness is the tests' business)
RIGHT = {
    "count": {"dof": "1", "links.binary": "4"},
    "slider": {"velocity.B": "1 m/s", "omega.rod": "0"},
    "four_bar": {
        "omega.rocker": "4.7846 rad/s cw",
        "velocity.C": "0.38277 m/s",
        "acceleration.C": "4.9054 m/s^2",
    },
    "properties": {"grashof": "crank-rocker", "transmission_angle.min": "45.573 deg"},
    "time_ratio": {"time_ratio": "1.0883"},
}
WRONG = {
    "omega.rocker": "4.7846 rad/s ccw",
    "velocity.C": "382.77",
    "acceleration.C": "2 m/s^2",
    "velocity.B": "2 m/s",
    "dof": "2",
    "time_ratio": "0.91888",
}


def generate(folder: Path, n: int) -> None:
    (folder / "problems").mkdir()
    (folder / "sheets").mkdir()
    for name, text in PROBLEMS.items():
        (folder / "problems" / name).write_text(text, encoding="utf-8")
    for i in range(n):
        lines = []
        for problem, answers in RIGHT.items():
            if i % 11 == 3 and problem == "properties":
                continue  # a problem left out
            lines.append(f"{problem}:")
            for key, right in answers.items():
                value = WRONG[key] if key in WRONG and (i + len(key)) % 4 == 0 else right
                lines.append(f"  {key}: {value!r}" if " " in value or "^" in value else f"  {key}: {value}")
        (folder / "sheets" / f"s{i:05d}.yaml").write_text("\n".join(lines) + "\n", encoding="utf-8")


def run(folder: Path, mech: str) -> tuple[float, float, float]:
    """One whole command in a fresh process: (seconds, peak RSS MB of its largest process, CPU s)."""
    args = [
        mech, "check", str(folder / "problems"), "--answers", str(folder / "sheets"),
        "--gradebook", str(folder / "grades.csv"), "--junit", str(folder / "out.xml"),
    ]  # fmt: skip
    probe = (
        "import resource, subprocess, sys, time\n"
        "t = time.perf_counter()\n"
        f"subprocess.run({args!r}, stdout=subprocess.DEVNULL)\n"
        "dt = time.perf_counter() - t\n"
        "u = resource.getrusage(resource.RUSAGE_CHILDREN)\n"
        "print(dt, u.ru_maxrss / 1024, u.ru_utime + u.ru_stime)\n"
    )
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True).stdout
    seconds, rss, cpu = out.split()
    return float(seconds), float(rss), float(cpu)


def check_gradebook(path: Path, n: int) -> None:
    rows = list(csv.DictReader(path.open(encoding="utf-8")))
    if len(rows) != n:
        sys.exit(f"the gradebook has {len(rows)} rows for {n} students")
    for r in rows:
        marks = [float(v) for k, v in r.items() if k.endswith(".yaml")]
        if float(r["out_of"]) != OUT_OF or abs(sum(marks) - float(r["total"])) > 1e-9:
            sys.exit(f"marks do not add up: {r}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-n", "--sheets", type=int, default=1000)
    parser.add_argument("-r", "--repeats", type=int, default=3)
    parser.add_argument("--mech", default=shutil.which("mech"), help="the mech command (default: on PATH)")
    args = parser.parse_args()
    if not args.mech:
        sys.exit("the mech command is not installed in this environment (pip install .)")
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        generate(folder, args.sheets)
        runs = [run(folder, args.mech) for _ in range(args.repeats)]
        check_gradebook(folder / "grades.csv", args.sheets)
    load = os.getloadavg() if hasattr(os, "getloadavg") else (float("nan"),) * 3
    median = statistics.median(t for t, _, _ in runs)
    cpu = statistics.median(c for _, _, c in runs)
    peak = max(m for _, m, _ in runs)
    print(
        f"mech check problems/ --answers sheets/ --gradebook grades.csv --junit out.xml, whole command "
        f"({platform.python_implementation()} {platform.python_version()}, {os.cpu_count()} cores, "
        f"load average {load[0]:.1f} {load[1]:.1f} {load[2]:.1f} at the end)"
    )
    print()
    print("| sheets × problems | runs | median (s) | CPU, all processes (s) | sheets/s | peak RSS (MB) |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: |")
    print(
        f"| {args.sheets:,} × 5 | {args.repeats} | {median:.2f} | {cpu:.2f} | {args.sheets / median:,.0f} | {peak:.0f} |"
    )
    print()
    print("gradebook: one row per student, marks add up")


if __name__ == "__main__":
    main()
