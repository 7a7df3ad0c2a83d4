"""Cold start of mech, measured in fresh subprocesses; prints a table of medians.

    python tests/benchmarks/bench_startup.py [--repeat 21]
    python tests/benchmarks/bench_startup.py --python BEFORE/bin/python AFTER/bin/python

With ``--python``, every case runs under each interpreter in turn, run by run (two trees
installed in two virtual environments, compared in one interleaved run), and each row gives
each interpreter's median and its ratio to the first one's.

Run it with the interpreter of a fresh virtual environment (``.venv/bin/python``):
packages with ``.pth`` start-up hooks in a busy system Python add their own cost.

Compares bare Python, ``import mech.cli`` (click, which the plain forms of the hot
commands skip: see mech.entry), whole ``mech dof`` / ``mech classify`` / ``mech
velocity`` runs on a shipped example (their output piped, as here: written
without rich), and for contrast ``import numpy`` and ``import rich``.  Medians,
because the machine is shared.
"""

from __future__ import annotations

import argparse
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = str(ROOT / "mechanisms" / "four_bar.yaml")

CASES: list[tuple[str, list[str]]] = [
    ("python -c pass", ["-c", "pass"]),
    ("import mech.cli (click: the other commands)", ["-c", "import mech.cli"]),
    ("mech dof --json four_bar.yaml", ["-m", "mech", "dof", "--json", EXAMPLE]),
    ("mech dof four_bar.yaml (table, piped)", ["-m", "mech", "dof", EXAMPLE]),
    ("mech classify four_bar.yaml (piped)", ["-m", "mech", "classify", EXAMPLE]),
    ("import yaml (PyYAML: every command pays it)", ["-c", "import yaml"]),
    ("import dataclasses (pulls inspect, ast, dis)", ["-c", "import dataclasses"]),
    ("import yaml, dataclasses, json, typing, enum", ["-c", "import yaml, dataclasses, json, typing, enum"]),
    ("import numpy (not paid by dof)", ["-c", "import numpy"]),
    ("mech velocity four_bar.yaml --rpm 600 (piped)", ["-m", "mech", "velocity", EXAMPLE, "--rpm", "600"]),
    ("import rich.table (not paid when piped)", ["-c", "import rich.table, rich.console"]),
]


def measure(args: list[str], repeat: int, python: str = sys.executable) -> list[float]:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run([python, *args], check=True, capture_output=True)
        times.append(time.perf_counter() - start)
    return times


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--repeat", type=int, default=21)
    parser.add_argument(
        "--python", nargs="+", help="interpreters to compare, interleaved (the first is the reference)"
    )
    args = parser.parse_args()
    if args.python:
        compare(args.python, args.repeat)
        return
    print(
        f"cold start, median of {args.repeat} runs; Python {platform.python_version()}, {platform.machine()}"
    )
    print(f"interpreter: {sys.executable}")
    print(f"{'case':48} {'median ms':>10} {'min ms':>8} {'× bare python':>14}")
    # Interleave the cases run by run, so that a burst of load on a shared machine
    # hits every case alike instead of the one that happened to be running.
    times: dict[str, list[float]] = {label: [] for label, _ in CASES}
    for _ in range(args.repeat):
        for label, argv in CASES:
            times[label] += measure(argv, 1)
    base = statistics.median(times[CASES[0][0]])
    for label, _ in CASES:
        t = times[label]
        med = statistics.median(t)
        print(f"{label:48} {med * 1e3:10.1f} {min(t) * 1e3:8.1f} {med / base:14.2f}")


def compare(pythons: list[str], repeat: int) -> None:
    """Every case under every interpreter, interleaved run by run; medians and ratios to the first."""
    print(f"cold start, median of {repeat} runs, interleaved; {platform.machine()}")
    for i, python in enumerate(pythons):
        print(f"  [{i}] {python}")
    times = {(label, py): [] for label, _ in CASES for py in pythons}
    for _ in range(repeat):
        for label, argv in CASES:
            for python in pythons:
                times[(label, python)] += measure(argv, 1, python)
    head = "".join(f" {f'[{i}] ms':>9}" for i in range(len(pythons)))
    ratios = "".join(f" {f'[{i}]/[0]':>8}" for i in range(1, len(pythons)))
    print(f"{'case':48}{head}{ratios}")
    for label, _ in CASES:
        medians = [statistics.median(times[(label, py)]) for py in pythons]
        cells = "".join(f" {m * 1e3:9.1f}" for m in medians)
        cells += "".join(f" {m / medians[0]:8.3f}" for m in medians[1:])
        print(f"{label:48}{cells}")


if __name__ == "__main__":
    main()
