"""Large files through ``mech dof``: a chain of N links with ``answers``, timed in fresh processes.

Issue 11: a 10,000-link file with answers took over 60 s and 2.9 GB for ``mech dof``,
building every I-centre's name (49,995,000 of them) to check the answer keys, and
classifying a link at a time over every joint.  Names are now decided from the name
(mech.answers.ICentreNames) and the joints of each link come from one index.  Then 0.96 s at
low load, half of it the cyclic garbage collector walking the 500,000 YAML nodes and marks
of the file again and again while it was read; the loader now reads with it paused, resolves
only the null tag and measures nesting on the composed nodes: 0.43 s (1.05 s before,
interleaved, load 3.5-4; 0.44 s of CPU instead of 1.1 s).

Prints a table: N, median wall time of ``mech dof FILE`` over three runs, peak RSS, and the
ratio against ``python -c pass`` in the same run.  No assertion: a measurement.

    python tests/benchmarks/bench_large_files.py [N ...]
"""

from __future__ import annotations

import itertools
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # a shared 2-core machine: threads only add noise


def chain(n: int) -> str:
    """A closed chain of n links (ground and n − 1 moving), revolute pins, one answer."""
    links = ["frame"] + [f"l{i}" for i in range(1, n)]
    ring = [*links, "frame"]
    joints = "\n".join(
        f"  J{i}: {{type: revolute, links: [{a}, {b}]}}" for i, (a, b) in enumerate(itertools.pairwise(ring))
    )
    return f"links: [{', '.join(links)}]\njoints:\n{joints}\nanswers:\n  dof: {n - 3}\n  icentres.count: {n * (n - 1) // 2}\n"


def timed(argv: list[str]) -> tuple[float, float]:
    """Wall seconds and the child's peak RSS (MiB) of one run."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    t = time.perf_counter()
    subprocess.run(argv, check=True, stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - t
    peak = max(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss, before)
    return wall, peak / 1024


def main(sizes: list[int]) -> None:
    mech = str(Path(sys.executable).with_name("mech"))
    base = statistics.median(timed([sys.executable, "-c", "pass"])[0] for _ in range(3))
    print("| links | mech dof median (s) | peak RSS (MiB) | × python -c pass |")
    print("| ---: | ---: | ---: | ---: |")
    with tempfile.TemporaryDirectory() as tmp:
        for n in sizes:
            path = Path(tmp) / f"chain{n}.yaml"
            path.write_text(chain(n), encoding="utf-8")
            runs = [timed([mech, "dof", str(path)]) for _ in range(3)]
            wall = statistics.median(r[0] for r in runs)
            print(f"| {n:,} | {wall:.2f} | {max(r[1] for r in runs):.0f} | {wall / base:.0f} |")


if __name__ == "__main__":
    main([int(a) for a in sys.argv[1:]] or [100, 1_000, 10_000])
