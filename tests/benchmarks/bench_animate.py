"""``mech sweep FILE --path C --animate a.gif`` at 100, 1,000 and 10,000 steps (issue 25, item 9).

Whole commands of an installed ``mech``, timed as a user waits for them, with a reference tree
(``--reference PATH/TO/mech``, the tree before a change) interleaved in the same run; the
ratio is this tree's time over the reference's.  A reference run longer than ``--limit``
seconds is stopped and shown as ``>limit``.  Before the change, the label placer measured
every candidate spot of every label against every segment of the traced path in every frame
(132 million distance calls at 10,000 steps); now the path is thinned to a frame's pixel and
only the segments within reach of a label are measured.

Usage::

    python tests/benchmarks/bench_animate.py [--mech mech] [--reference OTHER/mech] [--limit 900]
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
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


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--mech", default=shutil.which("mech") or "mech")
    parser.add_argument("--reference", default=None)
    parser.add_argument("--limit", type=float, default=900.0)
    parser.add_argument("--steps", type=int, nargs="*", default=[100, 1000, 10_000])
    args = parser.parse_args()
    print(f"{'steps':>7} {'this tree':>11} {'reference':>11} {'ratio':>7}")
    for steps in args.steps:
        mine = timed(args.mech, steps, args.limit)
        ref = timed(args.reference, steps, args.limit) if args.reference else float("nan")
        shown = f">{args.limit:.0f} s" if ref == float("inf") else f"{ref:.1f} s"
        ratio = mine / ref if ref == ref and ref != float("inf") else float("nan")
        print(f"{steps:>7} {mine:>9.1f} s {shown:>11} {ratio:>7.2f}")


if __name__ == "__main__":
    main()
