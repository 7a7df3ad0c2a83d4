"""Every example under every command's ``--json``, taken once and compared with another tree's.

A refactor must not move a number.  ``take`` runs the installed ``mech`` (whole commands, in
fresh processes, as a user runs them) on every file of ``mechanisms/`` under every command
that reads a mechanism, and writes one JSON document of what each printed (stdout parsed as
JSON, the exit status, the first line of stderr).  ``compare`` reads two such documents and
lists every leaf that differs: numbers beyond ``--rtol`` of the mechanism's size scale (the
largest magnitude of the same key's family in that output, so a velocity is compared with
velocities), strings, keys present on one side only, and exit statuses.

Usage::

    python tests/tools/json_snapshot.py take before.json [--mech PATH/TO/mech] [--jobs 2]
    python tests/tools/json_snapshot.py compare before.json after.json [--rtol 1e-9]

The README ("One truth for each thing") quotes the result of the last comparison.
"""

from __future__ import annotations

import argparse
import concurrent.futures
import json
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]

#: Command lines run on every example (the file is appended).  Each reads a mechanism; those
#: a file cannot answer (a cam command on a four-bar) are kept too: their refusal is compared.
COMMANDS: tuple[tuple[str, ...], ...] = (
    ("dof", "--json"),
    ("dof", "--mobility", "--json"),
    ("classify", "--json"),
    ("position", "--json"),
    ("velocity", "--json"),
    ("acceleration", "--json"),
    ("icentres", "--json"),
    ("properties", "--json"),
    ("sweep", "--json"),
    ("sweep", "--level", "acceleration", "--steps", "72", "--json"),
    ("cam", "--json"),
    ("check", "--json", "-j", "1"),
    ("forces", "--json"),
    ("sweep", "--level", "forces", "--steps", "12", "--json"),
)


def _run(mech: str, command: tuple[str, ...], path: Path) -> dict[str, Any]:
    env = dict(os.environ, NO_COLOR="1", COLUMNS="200")
    proc = subprocess.run(
        [mech, command[0], str(path), *command[1:]],
        capture_output=True,
        text=True,
        env=env,
        cwd=ROOT,
        timeout=600,
    )
    try:
        out: Any = json.loads(proc.stdout) if proc.stdout.strip() else None
    except json.JSONDecodeError:
        out = {"unparsed": proc.stdout[:2000]}
    err = proc.stderr.strip().splitlines()
    return {"status": proc.returncode, "json": out, "stderr": err[0] if err else ""}


def take(target: Path, mech: str, jobs: int) -> None:
    files = sorted((ROOT / "mechanisms").glob("*.yaml"))
    cases = [(c, f) for f in files for c in COMMANDS]
    with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
        results = list(pool.map(lambda cf: _run(mech, cf[0], cf[1]), cases))
    doc = {f"{f.name} :: {' '.join(c)}": r for (c, f), r in zip(cases, results, strict=True)}
    target.write_text(json.dumps(doc, indent=1, sort_keys=True), encoding="utf-8")
    print(f"{len(doc)} runs written to {target}")


def _leaves(node: Any, path: str = "") -> dict[str, Any]:
    if isinstance(node, dict):
        out: dict[str, Any] = {}
        for k, v in node.items():
            out.update(_leaves(v, f"{path}.{k}" if path else str(k)))
        return out
    if isinstance(node, list):
        out = {}
        for k, v in enumerate(node):
            out.update(_leaves(v, f"{path}[{k}]"))
        return out
    return {path: node}


def _family(path: str) -> str:
    """The key with list indices dropped: the numbers compared against one scale."""
    import re

    return re.sub(r"\[\d+\]", "[]", path)


def compare(before: Path, after: Path, rtol: float) -> int:
    a = json.loads(before.read_text(encoding="utf-8"))
    b = json.loads(after.read_text(encoding="utf-8"))
    differences = 0
    for case in sorted(set(a) | set(b)):
        if case not in a or case not in b:
            print(f"{case}: only in {'after' if case not in a else 'before'}")
            differences += 1
            continue
        ra, rb = a[case], b[case]
        lines: list[str] = []
        if ra["status"] != rb["status"]:
            lines.append(f"  exit status {ra['status']} -> {rb['status']}  ({rb['stderr'][:160]})")
        la, lb = _leaves(ra["json"]), _leaves(rb["json"])
        scale: dict[str, float] = {}
        for leaves in (la, lb):
            for k, v in leaves.items():
                if isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v):
                    f = _family(k)
                    scale[f] = max(scale.get(f, 0.0), abs(v))
        for k in sorted(set(la) | set(lb)):
            if k not in la or k not in lb:
                side = "after" if k not in la else "before"
                lines.append(f"  {k}: only {side} ({(la | lb)[k]!r:.80})")
                continue
            va, vb = la[k], lb[k]
            num = (int, float)
            if isinstance(va, num) and isinstance(vb, num) and not isinstance(va, bool):
                if va == vb or (math.isnan(va) and math.isnan(vb)):
                    continue
                tol = rtol * max(scale.get(_family(k), 0.0), 1e-300)
                if not (abs(va - vb) <= tol):
                    lines.append(f"  {k}: {va!r} -> {vb!r}")
            elif va != vb:
                lines.append(f"  {k}: {va!r:.100} -> {vb!r:.100}")
        if lines:
            differences += 1
            print(f"{case}: {len(lines)} difference(s)")
            print("\n".join(lines[:40]))
            if len(lines) > 40:
                print(f"  … and {len(lines) - 40} more")
    print(f"{len(set(a) | set(b))} runs compared, {differences} differ (rtol {rtol:g} of each key's scale)")
    return 1 if differences else 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="verb", required=True)
    t = sub.add_parser("take")
    t.add_argument("target", type=Path)
    t.add_argument("--mech", default=shutil.which("mech") or "mech")
    t.add_argument("--jobs", type=int, default=2)
    c = sub.add_parser("compare")
    c.add_argument("before", type=Path)
    c.add_argument("after", type=Path)
    c.add_argument("--rtol", type=float, default=1e-9)
    args = parser.parse_args()
    if args.verb == "take":
        take(args.target, args.mech, args.jobs)
        return 0
    return compare(args.before, args.after, args.rtol)


if __name__ == "__main__":
    sys.exit(main())
