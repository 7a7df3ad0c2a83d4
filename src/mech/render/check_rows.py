"""What every ``mech check`` report says of a row: its label, a verdict's message, the summary line.

Below the table and stream (:mod:`mech.render.check`) and the files made for tools
(:mod:`mech.render.check_formats`), which all word a row the same way.
"""

from __future__ import annotations

from mech.batch import Report
from mech.check import FileResult, Verdict

__all__ = ["label", "message", "plural", "summary_line"]


def plural(n: int, word: str) -> str:
    return f"{n} {word}{'' if n == 1 else 's'}"


def summary_line(report: Report) -> str:
    """``12 passed, 3 failed, 1 error in 5 files`` (pytest's order), then what was not scored."""
    text = f"{report.passed} passed, {report.failed} failed, {plural(report.errors, 'error')}"
    text += f" in {plural(report.files, 'file')}"
    if report.students:
        text += f", {plural(len(report.students), 'student')}"
    notes = []
    if report.skipped:
        notes.append(f"{plural(len(report.skipped), 'file')} with nothing to check")
    if report.teacher:
        notes.append(f"{plural(len(report.teacher), 'problem file')} excluded from every score")
    if report.ignored:
        notes.append(f"{plural(report.ignored, 'sheet key')} ignored")
    if notes:
        text += f" ({'; '.join(notes)})"
    return text


def label(r: FileResult) -> str:
    return f"{r.student}: {r.path}" if r.student is not None else r.path


def message(v: Verdict) -> str:
    """The verdict's message, with its diagnosis when it has one."""
    if v.diagnosis:
        return f"{v.message} — matches {v.diagnosis}"
    return v.message
