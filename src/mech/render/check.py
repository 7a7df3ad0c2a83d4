"""``mech check`` reports: a rich table, JSON, JUnit XML, Gradescope results.json and CSV.

Every format is made from the same :class:`~mech.batch.Report`, so they
cannot disagree.  Nothing here computes a verdict.
"""

from __future__ import annotations

import csv
import io
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any
from xml.etree import ElementTree as ET

from rich.console import Console
from rich.table import Table
from rich.text import Text

from mech.batch import Report
from mech.check import ERROR, FAIL, PASS, FileResult, Verdict
from mech.errors import InputError
from mech.render.console import is_plain, table_box
from mech.render.jsonout import dumps, error_dict
from mech.render.safe import printable, xml_safe

__all__ = [
    "PROGRESS_THRESHOLD",
    "check_table",
    "csv_text",
    "dumps",
    "gradescope_dict",
    "junit_xml",
    "progress",
    "report_dict",
    "summary_line",
]

#: A progress bar appears only for more rows than this (and only on a terminal).
PROGRESS_THRESHOLD = 20

_MARK = {PASS: ("✓ pass", "green"), FAIL: ("✗ fail", "red"), ERROR: ("! error", "yellow")}
_PLAIN = {PASS: "pass", FAIL: "FAIL", ERROR: "ERROR"}


def _plural(n: int, word: str) -> str:
    return f"{n} {word}{'' if n == 1 else 's'}"


def summary_line(report: Report) -> str:
    """``12 passed, 3 failed, 1 error in 5 files`` (pytest's order), with skipped files."""
    text = f"{report.passed} passed, {report.failed} failed, {_plural(report.errors, 'error')}"
    text += f" in {_plural(report.files, 'file')}"
    if report.students:
        text += f", {_plural(len(report.students), 'student')}"
    if report.skipped:
        text += f" ({_plural(len(report.skipped), 'file')} without answers skipped)"
    return text


def _label(r: FileResult) -> str:
    return f"{r.student}: {r.path}" if r.student is not None else r.path


# -- the table ------------------------------------------------------------------------------
def check_table(report: Report, console: Console, *, quiet: bool = False) -> None:
    """Answers one per row (files grouped), or one row per student for a class; then the summary.

    ``quiet`` lists only answers that failed or could not be computed.
    """
    if len(report.students) > 1:
        _class_table(report, console)
    else:
        _answers_table(report, console, quiet=quiet)
    style = "green" if report.exit_status == 0 else "red"
    console.print(Text(summary_line(report), style="bold " + style))


def _status(v: Verdict, console: Console) -> Text:
    if is_plain(console):
        return Text(_PLAIN[v.status])
    text, style = _MARK[v.status]
    return Text(text, style=style)


def _answers_table(report: Report, console: Console, *, quiet: bool) -> None:
    """One row per answer under a row naming its file (a file column would squeeze the reasons)."""
    table = Table(box=table_box(console))
    table.add_column("answer", overflow="fold")
    table.add_column("claimed", overflow="fold")
    table.add_column("verdict", no_wrap=True)
    table.add_column("computed / reason", overflow="fold")
    rows = 0
    for r in report.results:
        shown = [v for v in r.verdicts if not (quiet and v.passed)]
        if not shown:
            continue
        if rows:
            table.add_section()
        table.add_row(Text(printable(_label(r)), style="bold"), "", "", "")
        previous = None
        for v in shown:
            # one reason (a solve that failed) repeated down a file is said once
            message = "〃 (as above)" if v.status == ERROR and v.message == previous else v.message
            previous = v.message
            table.add_row(
                "  " + printable(v.key), printable(v.claimed), _status(v, console), printable(message)
            )
            rows += 1
    if rows:
        console.print(table)


def _class_table(report: Report, console: Console) -> None:
    table = Table(box=table_box(console))
    for name, justify in (
        ("student", "left"),
        ("problems", "right"),
        ("answers", "right"),
        ("passed", "right"),
        ("failed", "right"),
        ("errors", "right"),
        ("score", "right"),
    ):
        table.add_column(name, justify=justify)  # type: ignore[arg-type]
    for s in report.scores():
        table.add_row(
            printable(s.student),
            str(s.problems),
            str(s.total),
            str(s.passed),
            str(s.failed),
            str(s.errors),
            f"{100 * s.score:.0f}%",
        )
    console.print(table)


# -- progress -------------------------------------------------------------------------------
@contextmanager
def progress(console: Console | None = None) -> Iterator[tuple[Callable[[int], None], Callable[[Any], None]]]:
    """``(start, advance)`` callbacks for :func:`mech.batch.run`'s ``on_start``/``on_result``.

    The bar is drawn on stderr only when stderr is a terminal, NO_COLOR is not
    set and the batch has more than :data:`PROGRESS_THRESHOLD` rows; otherwise
    both are no-ops, so piped, plain and CI output stays clean.
    """
    console = console or Console(stderr=True, markup=False)
    state: dict[str, Any] = {}

    def start(total: int) -> None:
        if not console.is_terminal or console.no_color or total <= PROGRESS_THRESHOLD:
            return  # NO_COLOR promises plain text: no cursor movement either
        from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

        bar = Progress(
            TextColumn("checking"),
            BarColumn(),
            MofNCompleteColumn(),
            TimeRemainingColumn(),
            console=console,
            transient=True,
        )
        bar.start()
        state["bar"] = bar
        state["task"] = bar.add_task("check", total=total)

    def advance(_: Any) -> None:
        if "bar" in state:
            state["bar"].advance(state["task"])

    try:
        yield start, advance
    finally:
        if "bar" in state:
            state["bar"].stop()


# -- JSON -----------------------------------------------------------------------------------
def _computed(value: Any) -> Any:
    return list(value) if isinstance(value, tuple) else value


def verdict_dict(v: Verdict) -> dict[str, Any]:
    """One answer's verdict as JSON (see cli.md § mech check)."""
    return {
        "key": v.key,
        "status": v.status,
        "claimed": v.claimed,
        "computed": _computed(v.computed),
        "unit": v.unit,
        "error": v.error,
        "allowed": v.allowed,
        "tolerance": v.tolerance,
        "message": v.message,
        "line": v.where.line if v.where and v.where.line else None,
        "column": v.where.column if v.where and v.where.line else None,
        "source": v.where.path if v.where else None,
    }


def report_dict(report: Report) -> dict[str, Any]:
    """The whole report as JSON: summary, per-student scores (with sheets), per-file answers."""
    out: dict[str, Any] = {
        "summary": {
            "passed": report.passed,
            "failed": report.failed,
            "errors": report.errors,
            "total": report.total,
            "files": report.files,
            "skipped": list(report.skipped),
            "exit_status": report.exit_status,
            "text": summary_line(report),
        }
    }
    if report.students:
        out["students"] = [
            {
                "student": s.student,
                "problems": s.problems,
                "passed": s.passed,
                "failed": s.failed,
                "errors": s.errors,
                "total": s.total,
                "score": round(s.score, 6),
            }
            for s in report.scores()
        ]
    results = []
    for r in report.results:
        record: dict[str, Any] = {
            "file": r.path,
            "name": r.name,
            "student": r.student,
            "passed": r.passed,
            "failed": r.failed,
            "errors": r.errors,
            "answers": [verdict_dict(v) for v in r.verdicts],
        }
        if r.problems:
            record["error"] = error_dict(InputError(problems=r.problems))
        results.append(record)
    out["results"] = results
    return out


# -- JUnit XML ------------------------------------------------------------------------------
def junit_xml(report: Report) -> str:
    """JUnit XML for CI: one ``testsuite`` per file (and student), one ``testcase`` per answer.

    The structure is the common denominator of the Ant/Jenkins JUnit schemas
    that CI servers read: ``testsuites`` (tests, failures, errors) holding
    ``testsuite`` (name, tests, failures, errors, skipped) holding ``testcase``
    (classname, name) with a ``failure`` (a wrong answer) or ``error`` (an
    answer that could not be computed, or a file that could not be read)
    child carrying ``message`` and ``type``.
    """
    root = ET.Element(
        "testsuites",
        name="mech check",
        tests=str(report.total),
        failures=str(report.failed),
        errors=str(report.errors),
    )
    for r in report.results:
        suite = ET.SubElement(
            root,
            "testsuite",
            name=_label(r),
            tests=str(r.total),
            failures=str(r.failed),
            errors=str(r.errors),
            skipped="0",
        )
        classname = _classname(r)
        for v in r.verdicts:
            case = ET.SubElement(suite, "testcase", classname=classname, name=v.key, time="0")
            if v.status == FAIL:
                node = ET.SubElement(case, "failure", message=v.message, type="WrongAnswer")
                node.text = _details(v)
            elif v.status == ERROR:
                kind = "FileError" if v.key == "file" else "CannotCompute"
                node = ET.SubElement(case, "error", message=v.message, type=kind)
                node.text = "\n".join(_problem_lines(r)) if v.key == "file" and r.problems else _details(v)
    ET.indent(root)
    return xml_safe('<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n")


def _classname(r: FileResult) -> str:
    from pathlib import PurePath

    stem = PurePath(r.path).with_suffix("").as_posix().replace("/", ".").lstrip(".")
    return f"{r.student}.{stem}" if r.student is not None else stem


def _details(v: Verdict) -> str:
    lines = [f"{v.where}: {v.key}: {v.claimed}" if v.where else f"{v.key}: {v.claimed}", v.message]
    if v.error is not None and v.allowed is not None:
        lines.append(f"error {v.error:.6g}, allowed {v.allowed:.6g} ({v.tolerance})")
    return "\n".join(lines)


def _problem_lines(r: FileResult) -> list[str]:
    return [p.format() for p in r.problems]


# -- Gradescope -----------------------------------------------------------------------------
def gradescope_dict(report: Report) -> dict[str, Any]:
    """Gradescope autograder ``results.json``: one test per answer, one point each.

    Follows the autograder specification (gradescope-autograders.readthedocs.io,
    "Output format"): a top-level ``score`` and ``output``, and ``tests`` with
    ``name``, ``number``, ``score``, ``max_score``, ``status``
    (``"passed"``/``"failed"``) and ``output``.  An answer that could not be
    computed is a failed test whose output says why.  One submission (one
    student) per file: the caller refuses a class of sheets.
    """
    tests = []
    for i, r in enumerate(report.results, 1):
        for k, v in enumerate(r.verdicts, 1):
            tests.append(
                {
                    "name": f"{r.name or r.path}: {v.key}",
                    "number": f"{i}.{k}",
                    "score": 1.0 if v.passed else 0.0,
                    "max_score": 1.0,
                    "status": "passed" if v.passed else "failed",
                    "output": _gradescope_output(v),
                }
            )
    return {"score": float(report.passed), "output": summary_line(report), "tests": tests}


def _gradescope_output(v: Verdict) -> str:
    claimed = f"claimed {v.claimed}: " if v.claimed else ""
    if v.status == ERROR:
        return f"{claimed}could not be checked: {v.message}"
    return f"{claimed}{v.message}"


# -- CSV ------------------------------------------------------------------------------------
CSV_COLUMNS = ("student", "problem", "passed", "total", "score")


def csv_text(report: Report) -> str:
    """One row per student and problem for a gradebook (Moodle, Canvas): ``score`` is a percentage."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(CSV_COLUMNS)
    for r in report.results:
        score = 100.0 * r.passed / r.total if r.total else 0.0
        writer.writerow([r.student or "", r.path, r.passed, r.total, f"{score:.1f}"])
    return buffer.getvalue()
