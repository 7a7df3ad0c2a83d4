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

import csv
import io
import os
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import IO, TYPE_CHECKING, Any

from mech.batch import Report, StudentScore
from mech.check import ERROR, FAIL, IGNORED, PASS, FileResult, Verdict
from mech.errors import InputError
from mech.render.jsonout import dumps, error_dict
from mech.render.safe import printable, xml_safe
from mech.render.stats import key_statistics, problem_label

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


def _plural(n: int, word: str) -> str:
    return f"{n} {word}{'' if n == 1 else 's'}"


def summary_line(report: Report) -> str:
    """``12 passed, 3 failed, 1 error in 5 files`` (pytest's order), then what was not scored."""
    text = f"{report.passed} passed, {report.failed} failed, {_plural(report.errors, 'error')}"
    text += f" in {_plural(report.files, 'file')}"
    if report.students:
        text += f", {_plural(len(report.students), 'student')}"
    notes = []
    if report.skipped:
        notes.append(f"{_plural(len(report.skipped), 'file')} with nothing to check")
    if report.teacher:
        notes.append(f"{_plural(len(report.teacher), 'problem file')} excluded from every score")
    if report.ignored:
        notes.append(f"{_plural(report.ignored, 'sheet key')} ignored")
    if notes:
        text += f" ({'; '.join(notes)})"
    return text


def _label(r: FileResult) -> str:
    return f"{r.student}: {r.path}" if r.student is not None else r.path


def _message(v: Verdict) -> str:
    """The verdict's message, with its diagnosis when it has one."""
    if v.diagnosis:
        return f"{v.message} — matches {v.diagnosis}"
    return v.message


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
    return f"{v.key}: {_message(v)}{more}"


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
            self._write(f"    {_PLAIN[v.status]:<7} {v.key}{claimed}: {_message(v)}")

    def end(self, report: Report) -> None:
        """The teacher's excluded files, every student (with sheets), the closing line."""
        if report.students:
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
        if not report.teacher:
            return
        self._write("excluded from every score (the problem file cannot be graded):")
        for r in report.teacher:
            self._write(f"  EXCLUDED {r.path}: {r.verdicts[0].message if r.verdicts else ''}")


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
        notes.append(f"{_plural(s.errors, 'error')}")
    if s.ignored:
        notes.append(f"{_plural(s.ignored, 'sheet key')} ignored")
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
        table.add_row(Text(printable(_label(r)), style="bold"), "", "", "")
        previous = None
        for v in shown:
            # one reason (a solve that failed) repeated down a file is said once
            message = _message(v)
            text = "〃 (as above)" if v.status == ERROR and message == previous else message
            previous = message
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
def junit_xml(report: Report) -> str:
    """JUnit XML for CI: one ``testsuite`` per file (and student), one ``testcase`` per answer.

    The structure is the common denominator of the Ant/Jenkins JUnit schemas
    that CI servers read: ``testsuites`` (tests, failures, errors, skipped)
    holding ``testsuite`` (name, tests, failures, errors, skipped) holding
    ``testcase`` (classname, name) with a ``failure`` (a wrong answer),
    ``error`` (an answer that could not be computed, or a file that could not
    be read) or ``skipped`` (nothing to check; a problem file excluded from the
    scores; an ignored sheet key) child carrying ``message``.
    """
    return "".join(junit_chunks(report))


def junit_chunks(report: Report) -> Iterator[str]:
    """:func:`junit_xml` in pieces, one ``testsuite`` at a time, to write a large report in flat memory.

    (An element tree, or one string, of a 10,000-file batch would cost tens of MB.)
    """
    tests = skipped_total = 0
    for r in report.results:  # the totals first: the root element carries them
        extra = 1 if r.skipped or (r.excluded and not r.verdicts) else 0
        tests += len(r.verdicts) + extra
        skipped_total += extra + r.ignored
    yield (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<testsuites name="mech check" tests="{tests}" failures="{report.failed}" '
        f'errors="{report.errors}" skipped="{skipped_total}"' + (">\n" if report.results else " />\n")
    )
    for r in report.results:
        yield xml_safe(_suite(r))
    if report.results:
        yield "</testsuites>\n"


def _suite(r: FileResult) -> str:
    classname = _attr(_classname(r))
    cases: list[str] = []
    skipped = 0
    if r.skipped or (r.excluded and not r.verdicts):
        why = (
            "nothing to check (no answers)" if r.skipped else "the problem file is excluded from every score"
        )
        cases.append(_case(classname, "answers", f"<skipped message={_attr(why)} />"))
        skipped += 1
    for v in r.verdicts:
        child = ""
        if v.status == FAIL:
            child = f'<failure message={_attr(_message(v))} type="WrongAnswer">{_text(_details(v))}</failure>'
        elif v.status == ERROR:
            kind = "FileError" if v.key == "file" else "CannotCompute"
            text = "\n".join(_problem_lines(r)) if v.key == "file" and r.problems else _details(v)
            child = f'<error message={_attr(v.message)} type="{kind}">{_text(text)}</error>'
        elif v.status == IGNORED:
            child = f"<skipped message={_attr(v.message)} />"
            skipped += 1
        cases.append(_case(classname, v.key, child))
    tests = len(cases)
    if r.verdicts and not (r.excluded or r.sheet or r.skipped):
        # the score in marks (DESIGN § 1.3): JUnit has no score, so it rides as suite properties
        cases.insert(
            0,
            f'    <properties>\n      <property name="earned" value="{r.earned:g}" />\n'
            f'      <property name="out_of" value="{r.out_of:g}" />\n    </properties>\n',
        )
    return (
        f'  <testsuite name={_attr(_label(r))} tests="{tests}" failures="{r.failed}" '
        f'errors="{r.errors}" skipped="{skipped}"'
        + (">\n" + "".join(cases) + "  </testsuite>\n" if cases else " />\n")
    )


def _attr(text: str) -> str:
    """An XML attribute value, quoted, with newlines and tabs kept (as character references).

    As ``xml.sax.saxutils.quoteattr`` writes it, without importing it (it imports
    ``urllib.request``, a fifth of ``mech check``'s own start-up).
    """
    text = _text(text).replace("\n", "&#10;").replace("\r", "&#13;").replace("\t", "&#9;")
    if '"' not in text:
        return f'"{text}"'
    if "'" not in text:
        return f"'{text}'"
    return '"' + text.replace('"', "&quot;") + '"'


def _text(text: str) -> str:
    """XML character data: ``&``, ``<`` and ``>`` escaped (as ``xml.sax.saxutils.escape``)."""
    return text.replace("&", "&amp;").replace(">", "&gt;").replace("<", "&lt;")


def _case(classname: str, name: str, child: str) -> str:
    head = f'    <testcase classname={classname} name={_attr(name)} time="0"'
    return f"{head}>\n      {child}\n    </testcase>\n" if child else f"{head} />\n"


def _classname(r: FileResult) -> str:
    """The file's path without its suffix, dotted (``hw.week1.four_bar``), as
    ``PurePath(path).with_suffix("").as_posix()`` would spell it before the dots
    (without importing pathlib: it costs ``mech check`` ~5 ms of start-up)."""
    parts = [p for p in r.path.replace(os.sep, "/").split("/") if p not in ("", ".")]
    if parts:
        dot = parts[-1].rfind(".")
        if 0 < dot < len(parts[-1]) - 1:
            parts[-1] = parts[-1][:dot]
    stem = ".".join(parts).lstrip(".")
    return f"{r.student}.{stem}" if r.student is not None else stem


def _details(v: Verdict) -> str:
    lines = [f"{v.where}: {v.key}: {v.claimed}" if v.where else f"{v.key}: {v.claimed}", v.message]
    if v.diagnosis:
        lines.append(f"matches {v.diagnosis}")
    if v.error is not None and v.allowed is not None:
        lines.append(f"error {v.error:.6g}, allowed {v.allowed:.6g} ({v.tolerance})")
    return "\n".join(lines)


def _problem_lines(r: FileResult) -> list[str]:
    return [p.format() for p in r.problems]


# -- Gradescope -----------------------------------------------------------------------------
def gradescope_dict(report: Report) -> dict[str, Any]:
    """Gradescope autograder ``results.json``: one test per answer, worth its marks (1 by default).

    Follows the autograder specification (gradescope-autograders.readthedocs.io,
    "Output format"): a top-level ``score`` and ``output``, and ``tests`` with
    ``name``, ``number``, ``score``, ``max_score``, ``status``
    (``"passed"``/``"failed"``) and ``output``.  Tests are named by the file
    (and the problem's ``name``).  An answer that could not be computed is a
    failed test whose output says why; a file with nothing to check, an
    excluded problem file and an ignored sheet key are tests worth 0 points
    that say so.  One submission (one student) per file: the caller refuses a
    class of sheets.
    """
    tests = []
    for i, r in enumerate(report.results, 1):
        title = r.path + (f" ({r.name})" if r.name else "")
        if r.skipped or (r.excluded and not r.verdicts):
            why = (
                "nothing to check (no answers)"
                if r.skipped
                else "excluded from the score (the problem file cannot be graded)"
            )
            tests.append(_gs(f"{title}", f"{i}", 0.0, 0.0, "passed", why))
        for k, v in enumerate(r.verdicts, 1):
            points = v.marks if v.scored and not r.excluded and not r.sheet else 0.0
            tests.append(
                _gs(
                    f"{title}: {v.key}",
                    f"{i}.{k}",
                    points if v.passed else 0.0,
                    points,
                    "passed" if v.passed or v.status == IGNORED else "failed",
                    _gradescope_output(v),
                )
            )
    score = float(sum(t["score"] for t in tests))
    return {"score": score, "output": summary_line(report), "tests": tests}


def _gs(name: str, number: str, score: float, max_score: float, status: str, output: str) -> dict[str, Any]:
    return {
        "name": name,
        "number": number,
        "score": score,
        "max_score": max_score,
        "status": status,
        "output": output,
    }


def _gradescope_output(v: Verdict) -> str:
    claimed = f"claimed {v.claimed}: " if v.claimed else ""
    if v.status == ERROR:
        return f"{claimed}could not be checked: {_message(v)}"
    return f"{claimed}{_message(v)}"


# -- CSV ------------------------------------------------------------------------------------
CSV_COLUMNS = ("student", "problem", "passed", "total", "score", "status", "earned", "out_of")


def csv_text(report: Report) -> str:
    """One row per student and problem: ``score`` is a percentage of the marks (earned over out_of).

    (``--gradebook`` writes the one row per student that gradebooks import.)

        ``status`` says what the row is: ``graded``, ``nothing to check``,
        ``excluded`` (the problem file is the teacher's error: no score, not a 0)
        or ``sheet`` (a row about the sheet itself: ignored keys, unreadable sheet).
    """
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(CSV_COLUMNS)
    for r in report.results:
        if r.excluded:
            why = (
                r.verdicts[0].message
                if r.student is None and r.verdicts
                else "the problem file cannot be graded"
            )
            writer.writerow([r.student or "", r.path, "", "", "", f"excluded: {why}"])
        elif r.skipped:
            writer.writerow([r.student or "", r.path, "", "", "", "nothing to check"])
        elif r.sheet:
            notes = "; ".join(f"{v.key}: {v.message}" for v in r.verdicts)
            writer.writerow([r.student or "", r.path, "", "", "", f"sheet: {notes}"])
        else:
            score = 100.0 * r.earned / r.out_of if r.out_of else 0.0
            row = [r.student or "", r.path, r.passed, r.total, f"{score:.1f}", "graded"]
            writer.writerow([*row, f"{r.earned:g}", f"{r.out_of:g}"])
    return buffer.getvalue()


# -- the gradebook: one row per student --------------------------------------------------------
def _marks(x: float) -> str:
    """Marks as a gradebook cell: a plain decimal number (no exponent, no thousands separator)."""
    return f"{x:.4f}".rstrip("0").rstrip(".") if x != int(x) else str(int(x))


def gradebook_text(report: Report) -> str:
    """``--gradebook``: one row per student, ``student``, a column per problem (marks earned),
    ``total``, ``out_of`` and ``percent`` (DESIGN § 1.3): the shape Moodle's and Canvas's CSV grade
    imports read (a header row, one identifying column, numeric cells, one row per student).

    A problem left out of every score (the teacher's error) has no column: it counts for no one.
    """
    columns: dict[str, None] = {}
    earned: dict[tuple[str, str], float] = {}
    for r in report.results:
        if r.student is None or r.sheet or r.excluded or r.skipped:
            continue
        label = problem_label(r)
        columns.setdefault(label)
        earned[(r.student, label)] = earned.get((r.student, label), 0.0) + r.earned
    problems = sorted(columns)
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(["student", *problems, "total", "out_of", "percent"])
    for s in report.scores():
        cells = [_marks(earned.get((s.student, p), 0.0)) for p in problems]
        writer.writerow([s.student, *cells, _marks(s.earned), _marks(s.out_of), f"{100 * s.score:.1f}"])
    return buffer.getvalue()
