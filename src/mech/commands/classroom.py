"""``mech key`` and ``mech variants``: the teacher's side of a class (DESIGN § 1.3).

Thin: reading the command line's values, calling the library, writing what it
returns.  The library parts are :mod:`mech.grading.key` (a problem's answers) and
:mod:`mech.variants` (a problem for each student).
"""

from __future__ import annotations

import sys
from collections.abc import Mapping
from typing import Any

from mech.commands import echo, handles_errors, write_report
from mech.commands.exits import ExitStatus
from mech.errors import MechError

__all__ = ["key_command"]


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
