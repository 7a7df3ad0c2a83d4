"""Whole commands on large chains, each timed in a fresh process (issue 11: refused only after minutes).

Commands: velocity, acceleration, position, icentres, dof --mobility, check --timeout 60, and
(issue 11, task 2) sweep --steps 4, properties, draw -o drawing.svg.

Files, for N links:

* ``open``: an open chain of revolute pins hanging from one ground pivot (N − 1 freedoms), one drive;
* ``closed``: a ring of N links, two ground pivots placed, lengths given (N − 3 freedoms), one drive;
* ``drawn``: that ring with every pin drawn (``at``) on a regular polygon, one drive;
* ``ladder``: a crank and a chain of dyads, every pin drawn (one freedom, one drive): fully
  driven, so nothing is refused and the rank and the velocities must be computed.

Each command is run once with a wall-clock limit (``--limit``, default 300 s), its exit status and
wall time printed, so that a refusal that takes minutes shows.  No assertion: a measurement.
``mech check`` runs with ``--timeout 60`` on a copy that claims a velocity of 1 m/s (wrong for the
ladder: exit 1 there means it was computed and judged).

    python tests/benchmarks/bench_underdriven.py [--limit S] [--only sweep,properties,draw]
        [--kinds open,closed,drawn,ladder] [N ...]
"""

from __future__ import annotations

import argparse
import itertools
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

FOUR_BAR = Path(__file__).resolve().parents[2] / "mechanisms" / "four_bar.yaml"
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # tests/: the shared mechanism texts
from mechanism_texts import ladder as dyad_ladder  # noqa: E402

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # a shared machine: threads only add noise

COMMANDS = (
    ("velocity",),
    ("acceleration",),
    ("position",),
    ("icentres",),
    ("dof", "--mobility"),
    ("check", "--timeout", "60"),
    ("sweep", "--steps", "4"),
    ("properties",),
    ("draw", "-o", "{tmp}/drawing.svg"),
)


def ring(n: int, kind: str) -> str:
    """``open``, ``closed`` or ``drawn`` chain of n links (frame included), unit lengths, one drive."""
    links = ["frame"] + [f"l{i}" for i in range(1, n)]
    pairs = list(itertools.pairwise([*links, "frame"] if kind != "open" else links))
    radius = 0.5 / math.sin(math.pi / n)  # regular n-gon of unit sides, J0 at (0, 0), the last pin at (1, 0)
    centre_y = radius * math.cos(math.pi / n)

    def vertex(k: int) -> tuple[float, float]:
        a = -math.pi / 2 - math.pi / n - 2 * math.pi * k / n
        return 0.5 + radius * math.cos(a), centre_y + radius * math.sin(a)

    joints = []
    for i, (a, b) in enumerate(pairs):
        at = ""
        if kind == "drawn":
            x, y = (0.0, 0.0) if i == 0 else vertex(i) if i < len(pairs) - 1 else (1.0, 0.0)
            at = f", at: [{x:.12f}, {y:.12f}]"
        elif i == 0 or (kind == "closed" and i == len(pairs) - 1):
            at = ", at: [0, 0]" if i == 0 else ", at: [1, 0]"
        joints.append(f"  J{i}: {{type: revolute, links: [{a}, {b}]{at}}}")
    lengths = ", ".join(f"J{i}J{i + 1}: 1" for i in range(len(pairs) - 1))
    angle = "" if kind == "drawn" else "angle: 60, "
    return (
        f"name: {kind} chain of {n}\nlinks: [{', '.join(links)}]\njoints:\n"
        + "\n".join(joints)
        + f"\nlengths: {{{lengths}}}\ndrive: {{link: l1, {angle}rpm: 60}}\n"
    )


def ladder(n: int) -> str:
    """A crank and (n − 2) / 2 dyads, each hung from the last dyad's pin and a ground pivot: one freedom."""
    dyads = (n - 2) // 2
    return f"name: ladder of {2 + 2 * dyads}\n" + dyad_ladder(dyads)


def timed(argv: list[str], limit: float) -> tuple[str, str]:
    """Wall seconds (or '> limit') and the exit status of one run."""
    t = time.perf_counter()
    try:
        done = subprocess.run(
            argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=limit, check=False
        )
    except subprocess.TimeoutExpired:
        return f"> {limit:.0f}", "killed"
    return f"{time.perf_counter() - t:.2f}", str(done.returncode)


def main(sizes: list[int], limit: float, only: tuple[str, ...] = (), kinds: tuple[str, ...] = ()) -> None:
    mech = str(Path(sys.executable).with_name("mech"))
    print("| file | links | command | wall (s) | exit | × the same command on the 4-link four-bar |")
    print("| --- | ---: | --- | ---: | ---: | ---: |")
    with tempfile.TemporaryDirectory() as tmp:
        # the reference, in the same run: each command on the shipped four-bar (start-up and a solve)
        reference = {
            command: timed([mech, *(a.format(tmp=tmp) for a in command), str(FOUR_BAR)], limit)[0]
            for command in COMMANDS
            if not only or command[0] in only
        }
        for n in sizes:
            for kind in kinds or ("open", "closed", "drawn", "ladder"):
                text = ladder(n) if kind == "ladder" else ring(n, kind)
                path = Path(tmp) / f"{kind}{n}.yaml"
                path.write_text(text, encoding="utf-8")
                asked = Path(tmp) / f"{kind}{n}_asked.yaml"
                first = "P0" if kind == "ladder" else "J1"
                asked.write_text(text + f"answers:\n  velocity.{first}: 1 m/s\n", encoding="utf-8")
                for command in COMMANDS:
                    if only and command[0] not in only:
                        continue
                    target = asked if command[0] == "check" else path
                    argv = [mech, *(a.format(tmp=tmp) for a in command), str(target)]
                    wall, status = timed(argv, limit)
                    shown = " ".join(a.replace("{tmp}/", "") for a in command)
                    ref = reference[command]
                    ratio = f"{float(wall) / float(ref):.1f}×" if not wall.startswith(">") else "—"
                    print(
                        f"| {kind} | {n:,} | mech {shown} | {wall} | {status} | {ratio} (four-bar {ref} s) |",
                        flush=True,
                    )


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--limit", type=float, default=300.0, help="seconds before a command is stopped")
    parser.add_argument("--only", default="", help="commands to run, comma-separated (default: all)")
    parser.add_argument("--kinds", default="", help="files: open,closed,drawn,ladder (default: all)")
    parser.add_argument("sizes", type=int, nargs="*", default=[2_000])
    args = parser.parse_args()
    split = lambda text: tuple(x for x in text.split(",") if x)  # noqa: E731
    main(args.sizes, args.limit, split(args.only), split(args.kinds))
