"""A class of variants (``mech variants``' folder): whose problem each file is, and copied answers.

``mech variants problem.yaml -o class/`` writes ``class/<student>/<problem>`` for every
student and ``class/key.json``.  When ``mech check class/ --answers sheets/`` grades it,
a problem file in a student's folder is that student's alone (:func:`owners`), and a
wrong answer that is another student's right one is diagnosed "the variant of s17"
(:func:`copied`): an answer copied from a classmate fails, and says whose it is.
"""

from __future__ import annotations

import json
import math
import os
from collections import Counter
from collections.abc import Iterable, Sequence
from dataclasses import replace

from mech.check.verdicts import FAIL, FileResult, Verdict
from mech.units import parse_quantity

__all__ = ["ClassKey", "copied", "owners", "read_class_keys"]

#: (problem file name, key) → [(student, value SI)], from each class folder's key.json.
ClassKey = dict[tuple[str, str], list[tuple[str, float]]]


def read_class_keys(paths: Iterable[str]) -> tuple[dict[str, set[str]], ClassKey]:
    """The class folders among ``paths`` (their key.json written by ``mech variants``): each
    folder's students, and every student's numeric answers by (problem file name, key)."""
    folders: dict[str, set[str]] = {}
    table: ClassKey = {}
    for path in paths:
        key_file = os.path.join(path, "key.json")
        if not os.path.isdir(path) or not os.path.isfile(key_file):
            continue
        try:
            with open(key_file, encoding="utf-8") as f:
                doc = json.load(f)
        except (OSError, ValueError):
            continue
        if not isinstance(doc, dict) or doc.get("command") != "variants":
            continue
        students = folders.setdefault(os.path.normpath(path), set())
        for rec in doc.get("answers", ()):
            student, value = rec.get("student"), rec.get("value")
            if not isinstance(student, str):
                continue
            students.add(student)
            if isinstance(value, (int, float)) and not isinstance(value, bool):
                table.setdefault((str(rec.get("problem")), str(rec.get("key"))), []).append(
                    (student, float(value))
                )
    for rows in table.values():
        rows.sort()
    return folders, table


def owners(files: Sequence[str], folders: dict[str, set[str]]) -> dict[str, str]:
    """Problem file → the student whose own variant it is (a file in ``<class>/<student>/``)."""
    out: dict[str, str] = {}
    for f in files:
        parent = os.path.dirname(os.path.normpath(f))
        root, student = os.path.dirname(parent), os.path.basename(parent)
        if student in folders.get(root, ()):
            out[f] = student
    return out


def copied(results: list[FileResult], table: ClassKey) -> list[FileResult]:
    """Each failed answer that is another student's right answer, diagnosed so.

    Where one answer matches several classmates' variants, the classmate whose variant matches
    the most of the sheet's answers to the problem is named (a copied sheet names its source).
    An answer already diagnosed with a usual mistake is named a copy only when a classmate's
    value matches it more closely than the mistake's does: a copy matches to the digits
    written, a mistake that happens to lie near it (a unit slip, 1 % off) does not, and an
    honest slip that a classmate's value lies near by chance keeps its diagnosis.
    """
    if not table:
        return results
    out = []
    for r in results:
        if r.student is None or r.sheet or r.excluded or not any(v.status == FAIL for v in r.verdicts):
            out.append(r)
            continue
        name = os.path.basename(r.path)
        matches = [_whose(v, table.get((name, v.key), ()), r.student) for v in r.verdicts]
        tally = Counter(s for m in matches for s in m)
        verdicts = tuple(
            replace(
                v, diagnosis=f"the variant of {min(m, key=lambda s: (-tally[s], s))}", diagnosis_miss=None
            )
            if m
            else v
            for v, m in zip(r.verdicts, matches, strict=True)
        )
        out.append(replace(r, verdicts=verdicts))
    return out


def _whose(v: Verdict, others: Sequence[tuple[str, float]], student: str) -> list[str]:
    """The classmates whose right answer the failed claim ``v`` is, within its tolerance (and, when
    it has a diagnosis already, more closely than the diagnosed mistake's value)."""
    if v.status != FAIL or not others or not v.claimed:
        return []
    if v.diagnosis is not None and v.diagnosis_miss is None:
        return []  # diagnosed, by a rule that says not how closely (a copy named already)
    claimed = _claimed(v.claimed)
    if claimed is None:
        return []
    value, sense = claimed
    relative = (v.tolerance or "").endswith("%")
    computed = v.computed if isinstance(v.computed, float) and v.computed else None
    rel = (v.allowed or 0.0) / abs(computed) if relative and computed is not None else 0.02
    found = []
    for other, theirs in others:
        if other == student:
            continue
        want = theirs if sense else abs(theirs)
        allowed = rel * abs(want) if relative or v.allowed is None else v.allowed
        miss = abs(value - want)
        closer = v.diagnosis_miss is None or (want != 0.0 and miss / abs(want) < v.diagnosis_miss)
        if math.isfinite(want) and miss <= allowed and closer:
            found.append(other)
    return found


def _claimed(text: str) -> tuple[float, bool] | None:
    """A scalar claim in SI, signed when it says cw/ccw (and whether it did); None if not a number."""
    try:
        q = parse_quantity(text)
    except (KeyError, ValueError):
        return None
    if q.sense == "cw":
        return -abs(q.value), True
    if q.sense == "ccw":
        return abs(q.value), True
    return abs(q.value), False
