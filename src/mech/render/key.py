"""``mech key`` and ``mech variants``' keys: a plain table, JSON records, CSV rows.

Nothing here computes: the rows come from :func:`mech.grading.key.answer_key`.
"""

from __future__ import annotations

import csv
import io
from collections.abc import Iterable, Sequence
from typing import Any

from mech.grading.key import KeyRow
from mech.render.safe import printable

__all__ = ["KEY_COLUMNS", "key_csv", "key_records", "key_table"]

#: The columns of ``mech key --csv`` (``mech variants`` puts ``student`` first).
KEY_COLUMNS = ("problem", "key", "value", "unit")

Problems = Sequence[tuple[str, Sequence[KeyRow]]]


def _cell(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, list):
        return f"[{value[0]!r}, {value[1]!r}]"
    return repr(value) if isinstance(value, float) else str(value)


def key_records(problems: Problems, student: str | None = None) -> list[dict[str, Any]]:
    """One JSON record per question: problem, key, value (SI), unit, text, marks, error."""
    head = {"student": student} if student is not None else {}
    return [
        {
            **head,
            "problem": path,
            "key": r.key,
            "value": r.value,
            "unit": r.unit,
            "text": r.text,
            "marks": r.marks,
            "error": r.error,
        }
        for path, rows in problems
        for r in rows
    ]


def key_csv(problems: Iterable[tuple[str | None, str, Sequence[KeyRow]]]) -> str:
    """CSV of (student?, problem, key, value, unit); ``student`` is a column when any row has one."""
    items = list(problems)
    with_student = any(s is not None for s, _, _ in items)
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow((("student",) if with_student else ()) + KEY_COLUMNS)
    for student, path, rows in items:
        for r in rows:
            cells = [path, r.key, _cell(r.value), r.unit or ""]
            writer.writerow(([student or ""] if with_student else []) + cells)
    return buffer.getvalue()


def key_table(problems: Problems) -> str:
    """A plain table per problem: key, answer (with its unit and sense), marks; why one has none."""
    out: list[str] = []
    for path, rows in problems:
        out.append(printable(path))
        width = max((len(r.key) for r in rows), default=3)
        for r in rows:
            answer = r.text if r.error is None else f"— {r.error}"
            marks = f"  ({r.marks:g} marks)" if r.marks != 1 else ""
            out.append(f"  {r.key:<{width}}  {printable(answer)}{marks}")
        out.append("")
    return "\n".join(out).rstrip("\n")
