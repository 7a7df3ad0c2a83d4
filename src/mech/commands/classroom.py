"""``mech key`` and ``mech variants``: the teacher's side of a class (DESIGN § 1.3).

Thin: reading the command line's values, calling the library, writing what it
returns.  The library parts are :mod:`mech.grading.key` (a problem's answers) and
:mod:`mech.check.variants` (a problem for each student).
"""

from __future__ import annotations

import sys
from collections.abc import Mapping
from typing import Any

from mech.commands import echo, handles_errors, write_report
from mech.commands.exits import ExitStatus
from mech.errors import MechError

__all__ = ["key_command", "read_roster", "variants_command"]


@handles_errors(command="key")
def key_command(values: Mapping[str, Any]) -> None:
    """Every problem's answers to its questions: a table, ``--json`` or ``--csv FILE``.

    A problem file that cannot be read is reported (located) on stderr and the
    others are still given; exit 2 then, 1 when a question cannot be computed.
    """
    from mech import loader
    from mech.batch import find_problem_files
    from mech.commands import report_error
    from mech.grading.key import answer_key
    from mech.render.key import key_csv, key_records, key_table

    problems = []
    bad = False
    for path in find_problem_files(values["paths"]):
        try:
            mech = loader.load(path)
        except MechError as error:
            report_error(error)
            bad = True
            continue
        problems.append((path, answer_key(mech)))
    if values.get("csv_path"):
        write_report(values["csv_path"], key_csv((None, p, rows) for p, rows in problems))
    if values["as_json"]:
        from mech.render.jsonout import dumps

        echo(dumps({"command": "key", "file": None, "name": None, "answers": key_records(problems)}))
    else:
        echo(key_table(problems))
    if bad:
        sys.exit(ExitStatus.BAD_INPUT)
    if any(r.error for _, rows in problems for r in rows):
        sys.exit(ExitStatus.CHECK_FAILED)


# -- mech variants ------------------------------------------------------------------------------
def read_roster(path: str) -> tuple[str, ...]:
    """The ``student`` column of a roster CSV, in its order: ids that can name a folder, each once.

    A roster without the column, or an id that is empty, repeated or not a plain folder name,
    is a located InputError (exit 2).
    """
    import csv

    from mech.errors import InputError, Problem, Where

    try:
        with open(path, encoding="utf-8-sig", newline="") as f:
            rows = list(csv.reader(f))
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"cannot read the roster {path}: {exc}", where=Where(path)) from None
    if not rows or "student" not in [c.strip() for c in rows[0]]:
        raise InputError(
            f"{path} has no `student` column", where=Where(path, 1, 1), hint="a header row naming `student`"
        )
    col = [c.strip() for c in rows[0]].index("student")
    seen: dict[str, int] = {}
    problems = []
    for line, row in enumerate(rows[1:], 2):
        if not any(c.strip() for c in row):
            continue
        sid = row[col].strip() if col < len(row) else ""
        bad = not sid or sid in (".", "..") or any(c in sid for c in '/\\:*?"<>|') or sid.startswith(".")
        if bad:
            problems.append(Problem(f"student id {sid!r} cannot name a folder", Where(path, line, 1)))
        elif sid in seen:
            problems.append(
                Problem(f"student {sid} is listed twice (first on line {seen[sid]})", Where(path, line, 1))
            )
        else:
            seen[sid] = line
    if problems:
        raise InputError(problems=problems)
    if not seen:
        raise InputError(f"{path} lists no students", where=Where(path))
    return tuple(seen)


@handles_errors(command="variants")
def variants_command(values: Mapping[str, Any]) -> None:
    """Write each student's problem, its drawing, and the class's key (DESIGN § 1.3)."""
    import os

    from mech.check.variants import plan, variant_for
    from mech.draw import draw, save
    from mech.render.jsonout import dumps
    from mech.render.key import key_csv, key_records

    p = plan(values["file"])
    students = read_roster(values["roster"])
    out = values["output"]
    name = os.path.basename(values["file"])
    stem = os.path.splitext(name)[0]
    keys = []
    distinct = set()
    for student in students:
        v = variant_for(p, values["seed"], student)
        distinct.add(v.values)
        folder = os.path.join(out, student)
        os.makedirs(folder, exist_ok=True)
        write_report(os.path.join(folder, name), v.text)
        save(draw(v.mech, _solved(v.mech)), os.path.join(folder, stem + ".svg"))
        if values["explain"]:
            write_report(os.path.join(folder, stem + ".explain.txt"), _worked(v.mech))
        keys.append((student, name, v.key))
    write_report(os.path.join(out, "key.csv"), key_csv(keys))
    records = [rec for s, n, rows in keys for rec in key_records([(n, rows)], student=s)]
    vary = [{"path": d, "choices": len(c)} for d, c in p.vary]
    doc = {"command": "variants", "file": values["file"], "seed": values["seed"], "vary": vary}
    write_report(os.path.join(out, "key.json"), dumps({**doc, "answers": records}) + "\n")
    echo(
        f"{len(students)} students, {len(distinct)} distinct variants of {name} (seed {values['seed']}) in {out}"
    )
    if len(distinct) < len(students):
        echo(
            f"mech variants: only {len(distinct)} distinct variants for {len(students)} students: "
            "some share their numbers (widen `vary` for one each)",
            err=True,
        )


def _solved(mech: Any) -> Any:
    from mech.analysis import solve_at
    from mech.options import SolveOptions

    return solve_at(mech, "position", SolveOptions())


def _worked(mech: Any) -> str:
    """The worked velocity (and acceleration) construction of one student's variant, as text."""
    from mech.analysis import solve_at
    from mech.explain import explain
    from mech.options import SolveOptions

    parts = []
    for level in ("velocity", "acceleration"):
        try:
            kin = solve_at(mech, level, SolveOptions())
            parts.append(explain(mech, kin, kind=level).text())
        except MechError as error:
            parts.append(
                f"{level}: not written out ({error.problems[0].message if error.problems else error})"
            )
    return "\n\n".join(parts) + "\n"
