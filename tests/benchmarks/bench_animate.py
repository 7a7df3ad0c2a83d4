"""``mech sweep FILE --path C --animate a.gif`` at 100, 1,000 and 10,000 steps (issue 25, item 9).

Whole commands of an installed ``mech``, timed as a user waits for them, with a reference tree
(``--reference PATH/TO/mech``, the tree before a change) interleaved in the same run; the
ratio is this tree's time over the reference's.  A reference run longer than ``--limit``
seconds is stopped and shown as ``>limit``.  Before the change, the label placer measured
every candidate spot of every label against every segment of the traced path in every frame
(132 million distance calls at 10,000 steps); now the path is thinned to a frame's pixel and
only the segments within reach of a label are measured.

``--calls`` counts instead of timing, which no other load on the machine can move: the label
placer's distance calls (``mech.draw.scene._seg_dist``) in the whole command, run in each
tree's own interpreter (``--python`` and ``--reference-python``).  The reference's count is
taken with a stand-in distance that costs nothing: it measures every candidate against every
segment whatever the distances are, so its count is the same and it finishes in minutes.

Usage::

    python tests/benchmarks/bench_animate.py [--mech mech] [--reference OTHER/mech] [--limit 900]
    python tests/benchmarks/bench_animate.py --calls [--python PY] [--reference-python OTHER/PY]
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
FOUR_BAR = str(ROOT / "mechanisms" / "four_bar.yaml")


def timed(mech: str, steps: int, limit: float) -> float:
    with tempfile.TemporaryDirectory() as folder:
        argv = [mech, "sweep", FOUR_BAR, "--path", "C", "--animate", f"{folder}/a.gif", "--steps", str(steps)]
        start = time.perf_counter()
        try:
            subprocess.run(argv, stdout=subprocess.DEVNULL, check=True, timeout=limit)
        except subprocess.TimeoutExpired:
            return float("inf")
        return time.perf_counter() - start


COUNT = """
import sys
import mech.draw.scene as scene
from mech.cli import main

calls = 0
measure = scene._seg_dist if sys.argv[1] == "real" else (lambda p, a, b: 9.0)


def counted(p, a, b):
    global calls
    calls += 1
    return measure(p, a, b)


scene._seg_dist = counted
try:
    main(["sweep", sys.argv[2], "--path", "C", "--animate", sys.argv[3], "--steps", sys.argv[4]])
except SystemExit:
    pass
print(calls, file=sys.__stderr__)
"""


def calls(python: str, steps: int, real: bool) -> int:
    with tempfile.TemporaryDirectory() as folder:
        argv = [python, "-c", COUNT, "real" if real else "free", FOUR_BAR, f"{folder}/a.gif", str(steps)]
        done = subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, check=True)
        return int(done.stderr.split()[-1])


def count_main(args: argparse.Namespace) -> None:
    print(f"{'steps':>7} {'this tree':>14} {'reference':>14} {'ratio':>9}")
    for steps in args.steps:
        mine = calls(args.python, steps, real=True)
        ref = calls(args.reference_python, steps, real=False) if args.reference_python else 0
        ratio = f"{mine / ref:9.4f}" if ref else ""
        print(f"{steps:>7} {mine:>14,} {ref:>14,} {ratio}")


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--mech", default=shutil.which("mech") or "mech")
    parser.add_argument("--reference", default=None)
    parser.add_argument("--limit", type=float, default=900.0)
    parser.add_argument("--steps", type=int, nargs="*", default=[100, 1000, 10_000])
    parser.add_argument("--calls", action="store_true", help="count the label placer's distance calls")
    parser.add_argument("--python", default=sys.executable)
    parser.add_argument("--reference-python", default=None)
    args = parser.parse_args()
    if args.calls:
        count_main(args)
        return
    print(f"{'steps':>7} {'this tree':>11} {'reference':>11} {'ratio':>7}")
    for steps in args.steps:
        mine = timed(args.mech, steps, args.limit)
        ref = timed(args.reference, steps, args.limit) if args.reference else float("nan")
        shown = f">{args.limit:.0f} s" if ref == float("inf") else f"{ref:.1f} s"
        ratio = mine / ref if ref == ref and ref != float("inf") else float("nan")
        print(f"{steps:>7} {mine:>9.1f} s {shown:>11} {ratio:>7.2f}")


if __name__ == "__main__":
    main()
