"""A force sweep against the acceleration sweep it stands on: whole commands, fresh processes, medians.

    python tests/benchmarks/bench_forces.py [--repeat 11] [--steps 3600] [--mech PATH]

Runs the installed ``mech`` (the console script beside this interpreter, or ``--mech``: run it
from a virtual environment where the tree was installed with ``pip install .``) on the
single-cylinder engine of ``mechanisms/engine_turning_moment.yaml`` (a gas-force table over
720°, a piston and a rod with mass): ``mech sweep --level acceleration`` and ``mech sweep
--level forces`` over the same 720° in the same number of steps, each printing its report to
a pipe (plain text) and as ``--json``, alternating so that the machine's load falls on both.
Prints the median wall time and CPU time (the child's user + system, by getrusage) of each and
their ratios; the target (issue 24) is a force sweep of 3,600 steps at most 2× the acceleration
sweep.  Medians, and CPU beside wall time, because the machine is shared: the load average at the
start and the end is printed with the table.

The force sweep does the kinematic sweep's solve, then the forces of every step as one batched
solve (the Jacobian of every step at once), the mean torque by Gauss–Legendre between the
table's rows, the crossings of the mean and the peaks refined between steps: about ten batched
solves in all, whatever the number of steps.
"""

from __future__ import annotations

import argparse
import os
import platform
import resource
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
ENGINE = str(ROOT / "mechanisms" / "engine_turning_moment.yaml")


def _mech(path: str | None) -> str:
    if path:
        return path
    here = Path(sys.executable).with_name("mech")
    found = str(here) if here.exists() else shutil.which("mech")
    if not found:
        raise SystemExit("no mech console script found: install the tree (pip install .) or give --mech")
    return found


def _time(cmd: list[str]) -> tuple[float, float]:
    """Wall time and CPU time (user + system of the child) of one run of ``cmd``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--repeat", type=int, default=11)
    parser.add_argument("--steps", type=int, default=3600)
    parser.add_argument(
        "--mech", default=None, help="the mech console script to run (default: this environment's)"
    )
    args = parser.parse_args()
    mech = _mech(args.mech)
    common = [ENGINE, "--from", "0", "--to", "720", "--steps", str(args.steps)]
    cases = {
        ("acceleration", "plain"): [mech, "sweep", *common, "--level", "acceleration"],
        ("forces", "plain"): [mech, "sweep", *common, "--level", "forces"],
        ("acceleration", "json"): [mech, "sweep", *common, "--level", "acceleration", "--json"],
        ("forces", "json"): [mech, "sweep", *common, "--level", "forces", "--json"],
        ("startup", "plain"): [mech, "dof", ENGINE],
    }
    load_before = os.getloadavg()
    for cmd in cases.values():  # warm the file cache and the byte-code
        subprocess.run(cmd, check=True, capture_output=True)
    walls: dict[tuple[str, str], list[float]] = {key: [] for key in cases}
    cpus: dict[tuple[str, str], list[float]] = {key: [] for key in cases}
    for _ in range(args.repeat):
        for key, cmd in cases.items():
            wall, cpu = _time(cmd)
            walls[key].append(wall)
            cpus[key].append(cpu)
    wall_med = {key: statistics.median(v) for key, v in walls.items()}
    cpu_med = {key: statistics.median(v) for key, v in cpus.items()}
    print(f"mech: {mech}")
    print(f"python {platform.python_version()} on {platform.machine()}; {args.repeat} runs each, medians")
    print(f"engine: {Path(ENGINE).name}, 0–720°, {args.steps} steps")
    print(
        f"load average (1, 5, 15 min) on {os.cpu_count()} cores: before "
        + ", ".join(f"{x:.1f}" for x in load_before)
        + "; after "
        + ", ".join(f"{x:.1f}" for x in os.getloadavg())
    )
    print()
    print(f"{'command':<46}{'wall (s)':>10}{'CPU (s)':>10}")
    for key in cases:
        level, mode = key
        name = (
            "mech dof (start-up, for scale)" if level == "startup" else f"mech sweep --level {level} ({mode})"
        )
        print(f"{name:<46}{wall_med[key]:>10.3f}{cpu_med[key]:>10.3f}")
    print()
    for mode in ("plain", "json"):
        wall = wall_med[("forces", mode)] / wall_med[("acceleration", mode)]
        cpu = cpu_med[("forces", mode)] / cpu_med[("acceleration", mode)]
        verdict = "within" if max(wall, cpu) <= 2.0 else "OVER"
        print(f"forces / acceleration ({mode}): wall {wall:.2f}×, CPU {cpu:.2f}×  ({verdict} the 2× target)")


if __name__ == "__main__":
    main()
