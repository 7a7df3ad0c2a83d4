"""A class's statistics: per question how many got it right and the commonest diagnosed mistake,
and the distribution of scores (``mech check --answers``; issue 22 item 5).

What a teacher re-teaches: the questions few got right, and the mistake most of the others made.
Computed from a :class:`~mech.batch.Report`'s rows; nothing is solved again.
"""

from __future__ import annotations

import os
from collections import Counter
from collections.abc import Sequence

from mech._records import dataclass
from mech.check import FAIL, PASS, FileResult

__all__ = ["KeyStat", "histogram", "key_statistics", "problem_label"]


@dataclass(frozen=True, slots=True)
class KeyStat:
    """One question over the class: asked of ``asked`` students, ``right`` passed; the commonest
    diagnosed mistake of the others and how many made it (None, 0 when none was diagnosed)."""

    problem: str
    key: str
    asked: int
    right: int
    wrong: int
    mistake: str | None
    mistaken: int


def problem_label(r: FileResult) -> str:
    """A problem's name over the class: its file name when it lies in a folder named after the
    student (``class/s17/four_bar.yaml``: every student's own variant of one problem), else its path."""
    parts = r.path.replace(os.sep, "/").split("/")
    if r.student is not None and len(parts) >= 2 and parts[-2] == r.student:
        return parts[-1]
    return r.path


def _kind(diagnosis: str) -> str:
    """Diagnoses grouped as a teacher reads them: every "the variant of s17" is one kind."""
    return "another student's variant (copied)" if diagnosis.startswith("the variant of ") else diagnosis


def key_statistics(results: Sequence[FileResult]) -> tuple[KeyStat, ...]:
    """Per problem and question, in the order of problems then questions as asked."""
    seen: dict[tuple[str, str], list[int]] = {}
    mistakes: dict[tuple[str, str], Counter[str]] = {}
    for r in results:
        if r.student is None or r.sheet or r.excluded or r.skipped:
            continue
        label = problem_label(r)
        for v in r.verdicts:
            if not v.scored:
                continue
            tally = seen.setdefault((label, v.key), [0, 0, 0])
            tally[0] += 1
            tally[1] += v.status == PASS
            tally[2] += v.status == FAIL
            if v.status == FAIL and v.diagnosis:
                mistakes.setdefault((label, v.key), Counter())[_kind(v.diagnosis)] += 1
    out = []
    for (label, key), (asked, right, wrong) in sorted(seen.items(), key=lambda kv: kv[0][0]):
        common = mistakes.get((label, key))
        mistake, count = min(common.items(), key=lambda kv: (-kv[1], kv[0])) if common else (None, 0)
        out.append(KeyStat(label, key, asked, right, wrong, mistake, count))
    return tuple(out)


def histogram(scores: Sequence[float], *, title: str = "scores") -> str:
    """An SVG bar chart of scores (0–1) in ten bins of 10 % (the last one holds 100 %)."""
    bins = [0] * 10
    for s in scores:
        bins[min(9, max(0, int(s * 10 + 1e-9)))] += 1
    top = max(bins) or 1
    w, h, left, bottom, bar = 440, 260, 40, 40, 36
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" '
        'font-family="sans-serif" font-size="11">',
        f'<text x="{w / 2:g}" y="16" text-anchor="middle" font-size="13">{_escape(title)}: {len(scores)} students</text>',
        f'<line x1="{left}" y1="{h - bottom}" x2="{left + 10 * bar}" y2="{h - bottom}" stroke="black"/>',
    ]
    span = h - bottom - 40
    for i, n in enumerate(bins):
        x = left + i * bar
        height = span * n / top
        y = h - bottom - height
        out.append(f'<rect x="{x + 3}" y="{y:.1f}" width="{bar - 6}" height="{height:.1f}" fill="#4878a8"/>')
        if n:
            out.append(f'<text x="{x + bar / 2:g}" y="{y - 4:.1f}" text-anchor="middle">{n}</text>')
        out.append(f'<text x="{x + bar / 2:g}" y="{h - bottom + 14}" text-anchor="middle">{i * 10}</text>')
    out.append(f'<text x="{left + 10 * bar:g}" y="{h - bottom + 14}" text-anchor="middle">100</text>')
    out.append(f'<text x="{left + 5 * bar:g}" y="{h - 8}" text-anchor="middle">score (%)</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def _escape(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
