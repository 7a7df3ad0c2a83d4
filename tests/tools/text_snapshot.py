"""Every example under every command's report for people, plain and rich, taken once and compared.

``json_snapshot.py`` guards the numbers; this guards the bytes people read.  ``take`` runs the
installed ``mech`` (whole commands, fresh processes) on every file of ``mechanisms/`` under every
command that prints a report, three ways: piped (plain text, what a pipe or a file gets),
piped with ``NO_COLOR=1``, and as a terminal would get it (``FORCE_COLOR=1``: rich, with colour
codes).  The commands that ``mech.entry`` runs without click are also run in a form that only
click reads (``--`` before the file), so the two parsers are compared too.  Each run's stdout,
stderr and exit status are kept verbatim; ``compare`` lists every run whose bytes differ.

Usage::

    python tests/tools/text_snapshot.py take before.json [--mech PATH/TO/mech] [--jobs 2]
    python tests/tools/text_snapshot.py compare before.json after.json
"""

from __future__ import annotations

import argparse
import concurrent.futures
import difflib
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]

#: Command lines run on every example (the file is appended, or put after ``--`` for ``click``).
COMMANDS: tuple[tuple[str, ...], ...] = (
    ("dof",),
    ("dof", "--mobility"),
    ("classify",),
    ("position",),
    ("velocity",),
    ("velocity", "--explain", "--units", "mm"),
    ("acceleration",),
    ("acceleration", "--explain"),
    ("icentres",),
    ("icentres", "--explain"),
    ("properties",),
    ("sweep", "--steps", "72"),
    ("cam",),
    ("check", "-j", "1"),
    ("check", "-j", "1", "-v"),
)
#: The commands mech.entry reads without click: also run as ``mech CMD OPTIONS -- FILE``.
FAST = {"dof", "classify", "position", "velocity", "acceleration"}

MODES: dict[str, dict[str, str]] = {
    "piped": {},
    "no_color": {"NO_COLOR": "1"},
    "terminal": {"FORCE_COLOR": "1"},
}


def _env(mode: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in ("NO_COLOR", "FORCE_COLOR", "TTY_COMPATIBLE")}
    env.update(COLUMNS="120", LC_ALL="C.UTF-8", PYTHONIOENCODING="utf-8", **MODES[mode])
    return env


def _run(mech: str, argv: list[str], mode: str) -> dict[str, Any]:
    proc = subprocess.run(
        [mech, *argv], capture_output=True, text=True, env=_env(mode), cwd=ROOT, timeout=600
    )
    return {"status": proc.returncode, "stdout": proc.stdout, "stderr": proc.stderr}


def cases() -> list[tuple[str, list[str], str]]:
    """(name, argv, mode) of every run."""
    out = []
    for f in sorted((ROOT / "mechanisms").glob("*.yaml")):
        rel = str(f.relative_to(ROOT))
        for command in COMMANDS:
            forms = [("", [*command, rel])]
            if command[0] in FAST:
                forms.append((" [click]", [*command, "--", rel]))
            for tag, argv in forms:
                for mode in MODES:
                    out.append((f"{f.name} :: {' '.join(command)}{tag} :: {mode}", argv, mode))
    every = [str(p.relative_to(ROOT)) for p in sorted((ROOT / "mechanisms").glob("*.yaml"))]
    for mode in MODES:
        out.append((f"* :: dof (every example) :: {mode}", ["dof", *every], mode))
        out.append((f"* :: check mechanisms/ :: {mode}", ["check", "-j", "1", "mechanisms"], mode))
    return out


def take(target: Path, mech: str, jobs: int) -> None:
    todo = cases()
    with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
        results = list(pool.map(lambda c: _run(mech, c[1], c[2]), todo))
    doc = {name: r for (name, _, _), r in zip(todo, results, strict=True)}
    target.write_text(json.dumps(doc, indent=1, sort_keys=True), encoding="utf-8")
    print(f"{len(doc)} runs written to {target}")


def compare(before: Path, after: Path) -> int:
    a = json.loads(before.read_text(encoding="utf-8"))
    b = json.loads(after.read_text(encoding="utf-8"))
    differences = 0
    for case in sorted(set(a) | set(b)):
        if case not in a or case not in b:
            print(f"{case}: only in {'after' if case not in a else 'before'}")
            differences += 1
            continue
        if a[case] == b[case]:
            continue
        differences += 1
        print(f"{case}:")
        for part in ("status", "stdout", "stderr"):
            if a[case][part] != b[case][part]:
                if part == "status":
                    print(f"  exit status {a[case][part]} -> {b[case][part]}")
                    continue
                diff = difflib.unified_diff(
                    a[case][part].splitlines(), b[case][part].splitlines(), part, part, lineterm="", n=1
                )
                print("\n".join(f"  {line}" for line in list(diff)[:30]))
    print(f"{len(set(a) | set(b))} runs compared, {differences} differ")
    return 1 if differences else 0


def main() -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    sub = parser.add_subparsers(dest="verb", required=True)
    t = sub.add_parser("take")
    t.add_argument("target", type=Path)
    t.add_argument("--mech", default=shutil.which("mech") or "mech")
    t.add_argument("--jobs", type=int, default=2)
    c = sub.add_parser("compare")
    c.add_argument("before", type=Path)
    c.add_argument("after", type=Path)
    args = parser.parse_args()
    if args.verb == "take":
        take(args.target, args.mech, args.jobs)
        return 0
    return compare(args.before, args.after)


if __name__ == "__main__":
    sys.exit(main())
