"""``mech check`` reports: a table or a streamed plain listing, JSON, JUnit XML, Gradescope, CSV.

Every format is made from the same :class:`~mech.batch.Report` (or, streamed,
from the same rows as they land), so they cannot disagree.  Nothing here
computes a verdict.  rich is imported only by the table for a terminal: a
streamed plain report (piped, or a large batch) starts without it.

Every file and every student is a row in every format: a file with nothing to
check is a skipped row (JUnit ``<skipped/>``), a problem file left out of the
scores is listed once at the top, a sheet key that is not a question is an
ignored row (reported, never scored).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import IO, TYPE_CHECKING, Any

from mech.batch import Report, StudentScore
from mech.check import ERROR, FAIL, IGNORED, PASS, FileResult, Verdict
from mech.errors import InputError
from mech.render.check_formats import csv_text, gradebook_text, gradescope_dict, junit_chunks, junit_xml
from mech.render.check_rows import label, message, plural, summary_line
from mech.render.jsonout import dumps, error_dict
from mech.render.safe import printable
from mech.render.stats import key_statistics

if TYPE_CHECKING:  # pragma: no cover
    from rich.console import Console

    from mech.render.console import ReportConsole
    from mech.render.table import Text

__all__ = [
    "LARGE_BATCH",
    "PROGRESS_THRESHOLD",
    "Stream",
    "check_table",
    "csv_text",
    "dumps",
    "gradebook_text",
    "gradescope_dict",
    "junit_chunks",
    "junit_xml",
    "progress",
    "report_dict",
    "statistics_lines",
    "summary_line",
]

#: A progress bar appears only for more problem files than this (and only on a terminal).
PROGRESS_THRESHOLD = 20
#: More problem files than this are listed as a streamed plain report even on a terminal.
LARGE_BATCH = 200

_MARK = {
    PASS: ("✓ pass", "green"),
    FAIL: ("✗ fail", "red"),
    ERROR: ("! error", "yellow"),
    IGNORED: ("– ignored", "dim"),
}
_PLAIN = {PASS: "pass", FAIL: "FAIL", ERROR: "ERROR", IGNORED: "ignored"}


def _state(r: FileResult) -> str:
    if r.skipped:
        return "SKIP"
    if r.excluded:
        return "EXCLUDED"
    if r.errors:
        return "ERROR"
    if r.failed:
        return "FAIL"
    return "PASS"


def _first_issue(r: FileResult) -> str:
    if r.skipped:
        return "nothing to check (no answers)"
    bad = [v for v in r.verdicts if v.status in (FAIL, ERROR)]
    if not bad:
        return ""
    v = bad[0]
    more = f" (+{len(bad) - 1} more)" if len(bad) > 1 else ""
    return f"{v.key}: {message(v)}{more}"


# -- streamed plain report --------------------------------------------------------------------
class Stream:
    """A plain report written as rows land: one line per file (or student), details on request.

    Without answer sheets each problem file is written as soon as it (and every
    file before it) is done; with sheets the teacher's excluded files come first,
    then one line per student once every problem is graded.
    """

    def __init__(self, out: IO[str], *, verbose: bool = False, quiet: bool = False) -> None:
        self.out, self.verbose, self.quiet = out, verbose, quiet

    def _write(self, text: str) -> None:
        self.out.write(printable(text) + "\n")

    def file(self, rows: tuple[FileResult, ...]) -> None:
        """Write one problem file's rows (without sheets: one row)."""
        for r in rows:
            if r.student is not None or r.excluded:
                return  # sheets: the excluded files, then the per-student lines, come at the end
            if self.quiet and not (r.failed or r.errors):
                continue
            self._file_line(r)
        self.out.flush()

    def _file_line(self, r: FileResult) -> None:
        state = _state(r)
        head = f"{state:<5} {r.path}"
        if r.skipped:
            self._write(f"{head}  nothing to check (no answers)")
            return
        self._write(
            f"{head}  {r.passed}/{r.total}"
            + (f"  {_first_issue(r)}" if not self.verbose and r.total > r.passed else "")
        )
        if self.verbose:
            self._answers(r)

    def _answers(self, r: FileResult, *, failing_only: bool = False) -> None:
        for v in r.verdicts:
            if (self.quiet and v.status == PASS) or (failing_only and v.status not in (FAIL, ERROR)):
                continue
            claimed = f" {v.claimed}" if v.claimed else ""
            self._write(f"    {_PLAIN[v.status]:<7} {v.key}{claimed}: {message(v)}")

    def end(self, report: Report) -> None:
        """The teacher's excluded files, every student (with sheets), the closing line."""
        if report.students or report.outsiders:
            self._teacher(report)
            by_student: dict[str, list[FileResult]] = {}
            if self.verbose or self.quiet:  # -q lists each student's failing answers (issue 22)
                for r in report.results:
                    if r.student is not None and (r.verdicts or r.sheet):
                        by_student.setdefault(r.student, []).append(r)
            for s in report.scores():
                if self.quiet and s.passed == s.asked:
                    continue
                self._write(_student_line(s))
                for r in by_student.get(s.student, ()):
                    if self.verbose:
                        self._write(f"  {r.path}" + ("  (sheet)" if r.sheet else ""))
                        self._answers(r)
                    elif r.failed or r.errors:
                        self._write(f"  {r.path}" + ("  (sheet)" if r.sheet else ""))
                        self._answers(r, failing_only=True)
            for line in statistics_lines(report):
                self._write(line)
        self._write(summary_line(report))
        self.out.flush()

    def _teacher(self, report: Report) -> None:
        if report.teacher:
            self._write("excluded from every score (the problem file cannot be graded):")
            for r in report.teacher:
                self._write(f"  EXCLUDED {r.path}: {r.verdicts[0].message if r.verdicts else ''}")
        if report.outsiders:
            self._write(OUTSIDERS + ":")
            for r in report.outsiders:
                for v in r.verdicts:
                    self._write(f"  {_PLAIN[v.status]:<7} {r.path} {v.key}: {message(v)}")


#: The heading of the rows of sheets scored for no one (:attr:`~mech.batch.Report.outsiders`).
OUTSIDERS = "sheets scored for no one (no variant of the class was made for their student)"


def statistics_lines(report: Report) -> list[str]:
    """Per question: how many got it right, and the commonest diagnosed mistake (what to re-teach)."""
    stats = key_statistics(report.results)
    if not stats:
        return []
    lines = ["per question (right / asked; the commonest diagnosed mistake):"]
    for k in stats:
        mistake = f"; {k.mistaken} × {k.mistake}" if k.mistake else ""
        lines.append(f"  {k.problem} {k.key}: {k.right}/{k.asked} right{mistake}")
    return lines


def _student_line(s: StudentScore) -> str:
    notes = []
    if s.failed:
        notes.append(f"{s.failed} failed")
    if s.errors:
        notes.append(f"{plural(s.errors, 'error')}")
    if s.ignored:
        notes.append(f"{plural(s.ignored, 'sheet key')} ignored")
    tail = f"  ({', '.join(notes)})" if notes else ""
    return f"{s.student}  {s.passed}/{s.asked}  {100 * s.score:.0f}%{tail}"


# -- the table (a terminal) ------------------------------------------------------------------
def check_table(
    report: Report, console: ReportConsole, *, quiet: bool = False, verbose: bool = False
) -> None:
    """The report as rich tables: files (or students) by default, every answer with ``verbose``.

    ``quiet`` lists only what did not pass.
    """
    from mech.render.table import Text

    if report.teacher:
        _teacher_table(report, console)
    if report.outsiders:
        _outsiders_table(report, console)
    if report.students:
        _class_table(report, console, quiet=quiet)
    elif not verbose:
        _files_table(report, console, quiet=quiet)
    if verbose:
        _answers_table(report, console, quiet=quiet)
    elif quiet and report.students:  # -q: each student's failing answers (issue 22)
        _answers_table(report, console, quiet=True, failing_only=True)
    if report.students:
        for line in statistics_lines(report):
            console.print(Text(printable(line)))
    style = "green" if report.exit_status == 0 else "red"
    console.print(Text(summary_line(report), style="bold " + style))


def _box(console: ReportConsole) -> Any:
    from mech.render.console import table_box

    return table_box(console)


def _status(status: str, console: ReportConsole) -> Text:
    from mech.render.console import is_plain
    from mech.render.table import Text

    if is_plain(console):
        return Text(_PLAIN[status])
    text, style = _MARK[status]
    return Text(text, style=style)


def _teacher_table(report: Report, console: ReportConsole) -> None:
    from mech.render.table import Table

    table = Table(box=_box(console), title="excluded from every score (the problem file cannot be graded)")
    table.add_column("problem file", overflow="fold")
    table.add_column("why", overflow="fold")
    for r in report.teacher:
        table.add_row(printable(r.path), printable(r.verdicts[0].message if r.verdicts else ""))
    console.print(table)


def _outsiders_table(report: Report, console: ReportConsole) -> None:
    from mech.render.table import Table

    table = Table(box=_box(console), title=OUTSIDERS)
    table.add_column("sheet", overflow="fold")
    table.add_column("entry", overflow="fold")
    table.add_column("why", overflow="fold")
    for r in report.outsiders:
        for v in r.verdicts:
            table.add_row(printable(r.path), printable(v.key), printable(message(v)))
    console.print(table)


def _files_table(report: Report, console: ReportConsole, *, quiet: bool) -> None:
    from mech.render.table import Table

    table = Table(box=_box(console))
    table.add_column("file", overflow="fold")
    table.add_column("result", no_wrap=True)
    table.add_column("passed", justify="right", no_wrap=True)
    table.add_column("first problem", overflow="fold")
    rows = 0
    for r in report.results:
        if quiet and not (r.failed or r.errors):
            continue
        state = _state(r)
        status = {"PASS": PASS, "FAIL": FAIL, "ERROR": ERROR}.get(state)
        shown = _status(status, console) if status else state.lower()
        table.add_row(
            printable(r.path), shown, "" if r.skipped else f"{r.passed}/{r.total}", printable(_first_issue(r))
        )
        rows += 1
    if rows:
        console.print(table)


def _answers_table(
    report: Report, console: ReportConsole, *, quiet: bool, failing_only: bool = False
) -> None:
    """One row per answer under a row naming its file (a file column would squeeze the reasons).

    ``failing_only``: the failed and errored answers alone (``-q`` with a class).
    """
    from mech.render.table import Table, Text

    table = Table(box=_box(console))
    table.add_column("answer", overflow="fold")
    table.add_column("claimed", overflow="fold")
    table.add_column("verdict", no_wrap=True)
    table.add_column("computed / reason", overflow="fold")
    rows = 0
    for r in report.results:
        if failing_only:
            shown = [v for v in r.verdicts if v.status in (FAIL, ERROR)]
        else:
            shown = [v for v in r.verdicts if not (quiet and v.passed)]
        if not shown:
            continue
        if rows:
            table.add_section()
        table.add_row(Text(printable(label(r)), style="bold"), "", "", "")
        previous = None
        for v in shown:
            # one reason (a solve that failed) repeated down a file is said once
            said = message(v)
            text = "〃 (as above)" if v.status == ERROR and said == previous else said
            previous = said
            table.add_row(
                "  " + printable(v.key), printable(v.claimed), _status(v.status, console), printable(text)
            )
            rows += 1
    if rows:
        console.print(table)


def _class_table(report: Report, console: ReportConsole, *, quiet: bool) -> None:
    from mech.render.table import Table

    table = Table(box=_box(console))
    for name, justify in (
        ("student", "left"),
        ("problems", "right"),
        ("asked", "right"),
        ("passed", "right"),
        ("failed", "right"),
        ("errors", "right"),
        ("ignored", "right"),
        ("score", "right"),
    ):
        table.add_column(name, justify=justify)  # type: ignore[arg-type]
    for s in report.scores():
        if quiet and s.passed == s.asked:
            continue
        table.add_row(
            printable(s.student),
            str(s.problems),
            str(s.asked),
            str(s.passed),
            str(s.failed),
            str(s.errors),
            str(s.ignored),
            f"{100 * s.score:.0f}%",
        )
    console.print(table)


# -- progress -------------------------------------------------------------------------------
@contextmanager
def progress(console: Console | None = None) -> Iterator[tuple[Callable[[int], None], Callable[[Any], None]]]:
    """``(start, advance)`` callbacks for :func:`mech.batch.run`'s ``on_start``/``on_file``.

    The bar is drawn on stderr only when stderr is a terminal, NO_COLOR is not
    set and the batch has more than :data:`PROGRESS_THRESHOLD` files; otherwise
    both are no-ops, so piped, plain and CI output stays clean.
    """
    if console is None:
        from rich.console import Console

        console = Console(stderr=True, markup=False)
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
        "diagnosis": v.diagnosis,
        "marks": v.marks,
        "earned": v.earned,
        "line": v.where.line if v.where and v.where.line else None,
        "column": v.where.column if v.where and v.where.line else None,
        "source": v.where.path if v.where else None,
    }


def _file_dict(r: FileResult) -> dict[str, Any]:
    record: dict[str, Any] = {
        "file": r.path,
        "name": r.name,
        "student": r.student,
        "status": _state(r).lower(),
        "passed": r.passed,
        "failed": r.failed,
        "errors": r.errors,
        "ignored": r.ignored,
        "total": r.total,
        "earned": r.earned,
        "out_of": r.out_of,
        "skipped": r.skipped,
        "excluded": r.excluded,
        "sheet": r.sheet,
        "answers": [verdict_dict(v) for v in r.verdicts],
    }
    if r.problems:
        record["error"] = error_dict(InputError(problems=r.problems))
    return record


def report_dict(report: Report) -> dict[str, Any]:
    """The whole report as JSON: summary, excluded problem files, per-student scores, every row."""
    out: dict[str, Any] = {
        "summary": {
            "passed": report.passed,
            "failed": report.failed,
            "errors": report.errors,
            "ignored": report.ignored,
            "total": report.total,
            "files": report.files,
            "skipped": list(report.skipped),
            "excluded": [r.path for r in report.teacher],
            "exit_status": report.exit_status,
            "text": summary_line(report),
        }
    }
    if report.students:
        out["students"] = [
            {
                "student": s.student,
                "problems": s.problems,
                "asked": s.asked,
                "passed": s.passed,
                "failed": s.failed,
                "errors": s.errors,
                "ignored": s.ignored,
                "total": s.asked,
                "earned": s.earned,
                "out_of": s.out_of,
                "score": round(s.score, 6),
            }
            for s in report.scores()
        ]
        out["statistics"] = [
            {
                "problem": k.problem,
                "key": k.key,
                "asked": k.asked,
                "right": k.right,
                "wrong": k.wrong,
                "commonest_mistake": k.mistake,
                "mistaken": k.mistaken,
            }
            for k in key_statistics(report.results)
        ]
    out["results"] = [_file_dict(r) for r in report.results]
    return out


# -- JUnit XML ------------------------------------------------------------------------------
