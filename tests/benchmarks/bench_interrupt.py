"""Ctrl-C in a command's first 50 ms: how often a Python traceback shows, and with what status.

Runs a console script (``mech`` of an installed tree) as a user does and sends SIGINT after
0, 5 … 50 ms, several times each, with a reference tree (``--reference PATH/TO/mech``, the
tree before a change) interleaved in the same run.  Each row counts the runs that printed a
traceback and lists the statuses seen (130 is mech's answer; -2 is a process that died of the
signal, which a shell also shows as 130; anything else is wrong).  Timing on a loaded machine
moves where each delay lands, so the counts are a distribution, not a measurement of one
window.

Usage::

    python tests/benchmarks/bench_interrupt.py [--mech mech] [--reference OTHER/mech] [--runs 10]
"""

from __future__ import annotations

import argparse
import collections
import shutil
import signal
import subprocess
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
FOUR_BAR = str(ROOT / "mechanisms" / "four_bar.yaml")
COMMANDS = (("dof", FOUR_BAR), ("velocity", FOUR_BAR), ("sweep", FOUR_BAR, "--steps", "36"))


def once(mech: str, argv: tuple[str, ...], delay: float) -> tuple[int, bool]:
    proc = subprocess.Popen([mech, *argv], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    time.sleep(delay)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    return proc.returncode, "Traceback" in err


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--mech", default=shutil.which("mech") or "mech")
    parser.add_argument("--reference", default=None)
    parser.add_argument("--runs", type=int, default=10)
    args = parser.parse_args()
    trees = {"this tree": args.mech, **({"reference": args.reference} if args.reference else {})}
    print(f"{'command':<10} {'delay':>6}  " + "  ".join(f"{t:>28}" for t in trees))
    for argv in COMMANDS:
        for ms in range(0, 55, 5):
            cells = []
            results: dict[str, list[tuple[int, bool]]] = {t: [] for t in trees}
            for _ in range(args.runs):
                for name, mech in trees.items():  # interleaved: both see the same machine
                    results[name].append(once(mech, argv, ms / 1000))
            for name in trees:
                tracebacks = sum(tb for _, tb in results[name])
                statuses = collections.Counter(code for code, _ in results[name])
                seen = ",".join(f"{c}×{n}" for c, n in sorted(statuses.items()))
                cells.append(f"{tracebacks:>2} tracebacks [{seen}]".rjust(28))
            print(f"{argv[0]:<10} {ms:>4}ms  " + "  ".join(cells))


if __name__ == "__main__":
    main()
