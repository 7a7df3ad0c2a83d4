"""Whole ``mech sweep`` commands of the cam examples, against a linkage's, in one interleaved run.

    python tests/benchmarks/bench_cam_sweep.py [--repeat 5] [--mech MECH] [--before-src DIR]

Rows: ``mech sweep FILE`` for every shipped cam with a programme, a roller cam of one's own
(issue 21: offset 10 mm, a cycloidal rise and an SHM return, two dwells), the same at
``--steps 3600``, and the reference ``mech sweep khurmi_six_link_slider.yaml`` (a six-link
linkage: the issue's "1.4 s for a six-link shaper").  Each is a fresh process; wall time and
the child's CPU time (getrusage) are both given, medians over the repeats, each repeat running
every row once in turn so that a burst of load falls on all alike.  With ``--before-src`` (the
``src`` folder of an earlier tree, e.g. ``git archive main src | tar -x -C /tmp/before``), the
same commands as ``python -m mech`` from it, in the same run.  The load average is printed with
the table: the machine is shared, so quote the ratios and the load with the times.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests"))
from mechanism_texts import ROLLER_CAM as OWN_CAM  # noqa: E402  (issue 21's roller cam)


def timed(cmd: list[str], env: dict[str, str] | None = None) -> tuple[float, float]:
    """(wall, CPU) seconds of one fresh process; a failure is an error, never a fast row."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed ({p.returncode}): {p.stderr[-400:]}")
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--mech", default=str(Path(sys.executable).with_name("mech")))
    parser.add_argument(
        "--before-src", type=Path, help="src folder of an earlier tree, run as python -m mech"
    )
    args = parser.parse_args()
    own = Path(tempfile.mkdtemp()) / "own_cam.yaml"
    own.write_text(OWN_CAM, encoding="utf-8")
    cams = ["cam_roller_program", "cam_valve_khurmi", "cam_oscillating_roller", "cam_flat_follower"]
    rows = [(name, [str(ROOT / "mechanisms" / f"{name}.yaml"), "--rpm", "100"]) for name in cams]
    rows += [("own roller cam", [str(own)]), ("own roller cam, 3600 steps", [str(own), "--steps", "3600"])]
    rows += [("reference: six-link slider", [str(ROOT / "mechanisms" / "khurmi_six_link_slider.yaml")])]
    trees: list[tuple[str, list[str], dict[str, str] | None]] = [("now", [args.mech, "sweep"], None)]
    if args.before_src:
        env = dict(os.environ, PYTHONPATH=str(args.before_src))
        trees.append(("before", [sys.executable, "-m", "mech", "sweep"], env))
    times: dict[tuple[str, str], list[tuple[float, float]]] = {}
    for _ in range(args.repeat):
        for tree, cmd, env in trees:
            for name, rest in rows:
                times.setdefault((tree, name), []).append(timed(cmd + rest, env))
    load = os.getloadavg()
    print(
        f"load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f} on {os.cpu_count()} cores; {args.repeat} repeats"
    )
    print(f"{'command: mech sweep …':34} {'tree':7} {'wall s':>8} {'CPU s':>8} {'CPU / reference':>16}")
    for tree, _cmd, _env in trees:
        ref = statistics.median(c for _w, c in times[(tree, rows[-1][0])])
        for name, _rest in rows:
            wall = statistics.median(w for w, _c in times[(tree, name)])
            cpu = statistics.median(c for _w, c in times[(tree, name)])
            print(f"{name:34} {tree:7} {wall:8.2f} {cpu:8.2f} {cpu / ref:16.2f}")


if __name__ == "__main__":
    main()
