"""``mech check`` memory on a large class and a large folder: peak RSS of the whole process tree.

Issue 25 item 10: students' sheets are untrusted, so memory must stay bounded however many
sheets (or junk keys on them) a class hands in.  Three runs of the installed ``mech check``
(whole commands, fresh processes, the default worker count, a JUnit report written):

* **class**: 2,000 answer sheets for 10 problems; every sheet answers every problem (some
  answers right, some wrong) and carries 20 keys that are not questions (ignored rows);
* **junk**: 40 sheets of 10,000 junk keys each (the issue's 1 GB case);
* **folder**: 20,000 problem files (bench_check's mix: DOF counts, slider cranks, four-bars,
  one malformed file per hundred) without sheets.

The peak is sampled every 20 ms from ``/proc``: the sum of the resident set (VmRSS) of the
command and every process under it (its workers), and the sum of their proportional set
(Pss, shared pages split between the processes that share them: what the tree really costs
the machine).  The target (issue 25): the class and the folder each at most 150 MB (RSS sum).

    python tests/benchmarks/bench_memory.py                      # the mech on PATH
    python tests/benchmarks/bench_memory.py --mech A/bin/mech B/bin/mech   # interleaved, A then B

Linux only (``/proc``).
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_check import generate

PROBLEM = """\
name: slider crank {i}
units: {{length: mm, angle: deg}}
links: [frame, crank, rod, piston]
joints:
  O: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  A: {{type: revolute, links: [crank, rod]}}
  B: {{type: revolute, links: [rod, piston], near: [400, 0]}}
  P: {{type: prismatic, links: [piston, frame], path: {{through: [0, 0], angle: 0}}}}
lengths: {{OA: {r}, AB: 400}}
drive: {{link: crank, angle: 90, rpm: {rpm}, direction: ccw}}
asks: [dof, velocity.A, velocity.B, omega.rod]
"""


def make_class(folder: Path, sheets: int, problems: int, junk: int) -> tuple[Path, Path]:
    """``problems`` slider cranks and ``sheets`` sheets; each sheet answers every problem, plus junk keys.

    At 90° the rod translates: v_A = v_B = ω r, ω_rod = 0 (worked by hand, as in bench_check).
    """
    pdir, sdir = folder / "problems", folder / "sheets"
    pdir.mkdir(parents=True)
    sdir.mkdir()
    truth = []
    for i in range(problems):
        r, rpm = 100 + 5 * i, 60 + 10 * i
        (pdir / f"p{i:02d}.yaml").write_text(PROBLEM.format(i=i, r=r, rpm=rpm))
        truth.append(rpm * 2 * math.pi / 60 * r / 1000)
    for s in range(sheets):
        lines = []
        for i, va in enumerate(truth):
            lines.append(f"p{i:02d}:")
            lines.append("  dof: 1")
            lines.append(f"  velocity.A: {va:.6g} m/s")
            lines.append(f"  velocity.B: {va * (1.0 if s % 2 else 1.1):.6g} m/s")
            lines.append("  omega.rod: 0")
            lines.extend(f"  note_{k}: {s * junk + k}" for k in range(junk // problems if problems else 0))
        (sdir / f"student{s:05d}.yaml").write_text("\n".join(lines) + "\n")
    return pdir, sdir


def make_junk(folder: Path, sheets: int, keys: int) -> tuple[Path, Path]:
    """One problem and ``sheets`` sheets of ``keys`` keys that are not questions (and one that is)."""
    pdir, sdir = folder / "problems", folder / "sheets"
    pdir.mkdir(parents=True)
    sdir.mkdir()
    (pdir / "p00.yaml").write_text(PROBLEM.format(i=0, r=100, rpm=60))
    for s in range(sheets):
        body = "\n".join(f"  junk_key_number_{k}: {k}" for k in range(keys))
        (sdir / f"student{s:03d}.yaml").write_text(f"p00:\n  dof: 1\n{body}\n")
    return pdir, sdir


def _tree(root: int) -> list[int]:
    """``root`` and every process under it (``/proc/PID/task/TID/children``: no walk of all of /proc)."""
    out, todo = [], [root]
    while todo:
        pid = todo.pop()
        out.append(pid)
        try:
            for tid in os.listdir(f"/proc/{pid}/task"):
                with open(f"/proc/{pid}/task/{tid}/children", encoding="ascii") as f:
                    todo += [int(c) for c in f.read().split()]
        except OSError:  # it ended meanwhile
            continue
    return out


def _kb(path: str, field: str) -> int:
    try:
        with open(path, encoding="ascii", errors="replace") as f:
            for line in f:
                if line.startswith(field):
                    return int(line.split()[1])
    except OSError:
        pass
    return 0


def measure(argv: list[str]) -> tuple[float, float, float, int]:
    """Run ``argv``; (seconds, peak RSS sum MB, peak PSS sum MB, exit status), sampled every 20 ms."""
    start = time.perf_counter()
    proc = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    peak_rss = peak_pss = 0
    while proc.poll() is None:
        pids = _tree(proc.pid)
        peak_rss = max(peak_rss, sum(_kb(f"/proc/{p}/status", "VmRSS:") for p in pids))
        peak_pss = max(peak_pss, sum(_kb(f"/proc/{p}/smaps_rollup", "Pss:") for p in pids))
        time.sleep(0.02)
    err = proc.stderr.read().decode(errors="replace") if proc.stderr else ""
    if proc.returncode not in (0, 1):
        sys.exit(f"{' '.join(argv)} exited {proc.returncode}:\n{err[-2000:]}")
    return time.perf_counter() - start, peak_rss / 1024, peak_pss / 1024, proc.returncode


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mech", nargs="+", default=[shutil.which("mech") or "mech"])
    parser.add_argument("--sheets", type=int, default=2000)
    parser.add_argument("--files", type=int, default=20000)
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--only", choices=("class", "junk", "folder"), nargs="+")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        cases: list[tuple[str, list[str]]] = []
        if not args.only or "class" in args.only:
            p, s = make_class(root / "class", args.sheets, 10, 20)
            cases.append(
                (
                    f"class: {args.sheets:,} sheets × 10 problems, 20 junk keys each",
                    [str(p), "--answers", str(s)],
                )
            )
        if not args.only or "junk" in args.only:
            p, s = make_junk(root / "junk", 40, 10_000)
            cases.append(
                ("junk: 40 sheets × 10,000 keys that are not questions", [str(p), "--answers", str(s)])
            )
        if not args.only or "folder" in args.only:
            folder = root / "folder"
            folder.mkdir()
            generate(folder, args.files)
            cases.append((f"folder: {args.files:,} problem files, no sheets", [str(folder)]))
        results: dict[tuple[str, str], list[tuple[float, float, float, int]]] = {}
        for _ in range(args.repeats):
            for label, case in cases:
                for mech in args.mech:  # interleaved: a burst of load hits every build alike
                    junit = root / "out.xml"
                    results.setdefault((label, mech), []).append(
                        measure([mech, "check", *case, "--junit", str(junit)])
                    )
        for label, _ in cases:
            for mech in args.mech:
                runs = results[(label, mech)]
                rows.append(
                    (
                        label,
                        mech,
                        min(r[0] for r in runs),
                        max(r[1] for r in runs),
                        max(r[2] for r in runs),
                        runs[-1][3],
                    )
                )
    print(
        f"mech check memory, whole process tree sampled every 20 ms ({platform.python_implementation()} "
        f"{platform.python_version()}, {os.cpu_count()} cores, default --jobs)"
    )
    print()
    print("| case | mech | seconds | peak RSS sum (MB) | peak PSS sum (MB) | exit |")
    print("| --- | --- | ---: | ---: | ---: | ---: |")
    for label, mech, seconds, rss, pss, status in rows:
        print(f"| {label} | {mech} | {seconds:.1f} | {rss:.0f} | {pss:.0f} | {status} |")


if __name__ == "__main__":
    main()
