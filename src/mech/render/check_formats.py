"""``mech check`` reports for tools: JUnit XML, Gradescope's JSON, the CSV of verdicts and the gradebook.

Made from the same :class:`~mech.batch.Report` as the table and the stream
(:mod:`mech.render.check`), so they cannot disagree.
"""

from __future__ import annotations

import csv
import io
import os
from collections.abc import Iterator
from typing import Any

from mech.batch import Report
from mech.check import ERROR, FAIL, IGNORED, FileResult, Verdict
from mech.render.check_rows import label, message, summary_line
from mech.render.safe import xml_safe
from mech.render.stats import problem_label

__all__ = ["csv_text", "gradebook_text", "gradescope_dict", "junit_chunks", "junit_xml"]


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
            child = f'<failure message={_attr(message(v))} type="WrongAnswer">{_text(_details(v))}</failure>'
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
        f'  <testsuite name={_attr(label(r))} tests="{tests}" failures="{r.failed}" '
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
        return f"{claimed}could not be checked: {message(v)}"
    return f"{claimed}{message(v)}"


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
