"""One problem file's verdicts: its own answers, or every student's answers to it.

This is what a worker of ``mech check`` does with one problem file
(:func:`run_task`, handed to :func:`mech.batchpool.run_jobs` by
:func:`mech.batch.run`): load it once, solve it once, and grade every claim on
it, whether the file carries them (:func:`check_file`) or students' sheets do.
The batch above it plans the tasks and gathers the rows; nothing here calls
back up into it.

**Scores mean the same for everyone.**  The questions of a problem are fixed by
the teacher: the keys of its ``answers``, else its ``asks``.  Each student gets
exactly one scored verdict per question — pass, fail (wrong, or not answered)
or error (the sheet's entry for it could not be read) — then the sheet's keys
that are not questions, reported as ignored (at most :data:`MAX_LISTED` of them
per entry, then one row counting the rest: a sheet is untrusted, and its junk
must not cost memory or time in proportion to its size).  A problem file that
cannot be read, or asks nothing, is the teacher's error: one row
(``excluded``), and a not-scored row per student.
"""

from __future__ import annotations

import errno
import os
import stat
from collections.abc import Iterator, Sequence
from dataclasses import replace
from typing import Any

from mech import loader
from mech._records import dataclass
from mech.check.verdicts import ERROR, FAIL, IGNORED, FileResult, Verdict, check, error_result
from mech.errors import InputError, MechError, Where
from mech.grading import Analysis, InternalError
from mech.loader.sheets import SheetEntry, answer_keys, entry_node, own_tolerances
from mech.model import Claim, Mechanism
from mech.options import SolveOptions

__all__ = [
    "MAX_LISTED",
    "Done",
    "Submission",
    "Task",
    "ambiguous",
    "check_file",
    "lost_task",
    "marked",
    "probe",
    "questions_of",
    "run_task",
    "special_result",
]

#: Keys of one sheet entry that are not questions, listed one row each; the rest are counted in one row.
MAX_LISTED = 20


# -- a path that is not a problem file ------------------------------------------------------------
def probe(path: str) -> str | None:
    """Why ``path`` cannot be read as a problem file without opening it, or None when it can.

    A FIFO would block the read forever, a device could be endless: neither is
    opened.  Dangling and looping symbolic links are named as such.
    """
    try:
        st = os.stat(path)
    except FileNotFoundError:
        if os.path.islink(path):
            return f"a symbolic link to {os.readlink(path)}, which does not exist"
        return "no such file (it was removed while checking)"
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            return "a symbolic link loop (the link leads back to itself)"
        return f"cannot be read: {exc.strerror}"
    mode = st.st_mode
    if stat.S_ISREG(mode):
        return None
    if stat.S_ISDIR(mode):
        return "a folder, not a file"
    if stat.S_ISFIFO(mode):
        return "a FIFO (named pipe), not a file: not read"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device, not a file: not read"
    if stat.S_ISSOCK(mode):
        return "a socket, not a file: not read"
    return "not a regular file: not read"


def special_result(path: str, reason: str, *, student: str | None = None) -> FileResult:
    """The error row of a path that is not a readable regular file."""
    error = InputError(
        f"this path is {reason}", where=Where(path), hint="problem files are regular YAML files"
    )
    return error_result(path, error, student=student)


def questions_of(mech: Mechanism) -> tuple[str, ...]:
    """A problem's questions: its ``answers`` keys, else its ``asks`` (DESIGN.md § 1.1)."""
    return tuple(c.key for c in mech.answers) or tuple(mech.asks)


# -- a file that carries its own answers -------------------------------------------------------------
def check_file(path: str, *, options: SolveOptions | None = None) -> FileResult:
    """Load one problem file and check the answers it carries.

    The function to map over many machines (Dask ``client.map``, Ray): it
    takes a path and returns a picklable, frozen result; a file that cannot
    be read becomes its error row instead of an exception, and a file with no
    answers a ``skipped`` row (``mech check`` runs the same function).
    """
    why = probe(path)  # a FIFO or a device is never opened; a dangling link is named
    if why is not None:
        return special_result(path, why)
    try:
        mech = loader.load(path)
    except MechError as error:
        return error_result(path, error)
    if not mech.answers:
        return FileResult(path=path, name=mech.name, skipped=True)
    return FileResult(path=path, name=mech.name, verdicts=marked(check(mech, options=options), mech))


def marked(verdicts: tuple[Verdict, ...], mech: Mechanism) -> tuple[Verdict, ...]:
    """The verdicts with each question's marks (DESIGN § 1.3); a question worth 1 is left as it is."""
    if not mech.marks:
        return verdicts
    marks = dict(mech.marks)
    return tuple(
        replace(v, marks=marks[v.key]) if v.status != IGNORED and v.key in marks else v for v in verdicts
    )


# -- one problem file of a batch ------------------------------------------------------------------
@dataclass(frozen=True, slots=True)
class Submission:
    """What a worker needs of one student's sheet for one problem.

    ``entries`` name this problem file (and no other) by path; ``ambiguous``
    name it and others (with the labels of the candidates); ``unresolved`` name
    no file by path, so one may name this problem by its ``name``.
    """

    student: str
    sheet: str
    source: str
    entries: tuple[SheetEntry, ...]
    ambiguous: tuple[tuple[SheetEntry, tuple[str, ...]], ...]
    unresolved: tuple[SheetEntry, ...]
    unreadable: bool = False  # the sheet could not be read: nothing on it is graded
    missing: bool = False  # no sheet at all: a class's variant was made for this student, who handed none in


@dataclass(frozen=True, slots=True)
class Task:
    """One problem file to check: on its own answers (``submissions`` None), or students' sheets.

    A class's problem is checked in parts (:data:`mech.batch.STUDENTS` students each); the
    ``first`` part also carries the teacher's row of a problem left out of every score.
    """

    path: str
    submissions: tuple[Submission, ...] | None
    solve: SolveOptions
    first: bool = True


@dataclass(frozen=True, slots=True)
class Done:
    """A task's rows, and the sheet keys it matched by a problem's ``name`` ``(student, key, path)``.

    ``lost`` says why the task did not finish (the time limit, a crash), None when it did.
    """

    results: tuple[FileResult, ...]
    used: tuple[tuple[str, str, str], ...] = ()
    lost: str | None = None


def run_task(task: Task) -> Done:
    """Every row of one problem file; a bug in mech becomes its rows, never an exception."""
    try:
        return _check_task(task)
    except Exception as exc:  # a bug: this file's rows say so, the batch goes on
        return _lost(task, str(InternalError.of(exc)))


def lost_task(task: Task, why: str) -> Done:
    """The rows of a problem file whose check did not finish: past the time limit, or a crash."""
    if why == "timeout":
        message = "not checked: it took longer than the time limit (--timeout)"
    else:
        message = "mech crashed while checking this file (a bug in mech or its YAML parser: please report it)"
    return _lost(task, message)


def _lost(task: Task, message: str) -> Done:
    row = FileResult(task.path, verdicts=(Verdict("file", ERROR, message=message, where=Where(task.path)),))
    if task.submissions is None:
        return Done((row,), lost=message)
    return Done(_exclude(task, row), lost=message)


def _exclude(task: Task, teacher: FileResult) -> tuple[FileResult, ...]:
    """A problem left out of every score: the teacher's row, and a not-scored row per student."""
    why = teacher.verdicts[0].message if teacher.verdicts else "the problem asks nothing"
    message = f"not scored: the problem file is excluded ({why})"
    rows = [replace(teacher, excluded=True)] if task.first else []
    for sub in task.submissions or ():
        keys = []
        for e in sub.entries:
            node = entry_node(sub.source, e, sub.sheet)
            keys += answer_keys(node, sub.sheet) if node is not None else []
        verdicts = tuple(Verdict(k, IGNORED, message=message, where=w) for k, w in keys[:MAX_LISTED])
        verdicts += _more(len(keys) - MAX_LISTED, message, sub.sheet)
        rows.append(FileResult(task.path, teacher.name, verdicts, student=sub.student, excluded=True))
    return tuple(rows)


def _more(n: int, why: str, sheet: str) -> tuple[Verdict, ...]:
    """One ignored row for the ``n`` keys beyond the ones listed (none when there are none)."""
    if n <= 0:
        return ()
    more = f"{why}: {n:,} more key{'s' if n > 1 else ''} of this entry, not listed"
    return (Verdict("…", IGNORED, message=more, where=Where(sheet)),)


def _check_task(task: Task) -> Done:
    if task.submissions is None:
        return Done((check_file(task.path, options=task.solve),))
    why = probe(task.path)
    if why is not None:
        return Done(_exclude(task, special_result(task.path, why)))
    try:
        mech = loader.load(task.path)
    except MechError as error:
        return Done(_exclude(task, error_result(task.path, error)))
    questions = questions_of(mech)
    if not questions:
        asks_nothing = InputError(
            f"{task.path} asks nothing: it has neither `answers` nor `asks`, so no student can be graded on it",
            where=Where(task.path),
            hint="list its questions: `asks: [omega.rocker, velocity.C]` (or give `answers`)",
        )
        return Done(_exclude(task, replace(error_result(task.path, asks_nothing), name=mech.name)))
    return _check_sheets(task, mech, questions)


def _check_sheets(task: Task, mech: Mechanism, questions: tuple[str, ...]) -> Done:
    """Every student's answers to one problem, against one shared solution."""
    analysis = Analysis(mech, options=task.solve)
    analysis.need(questions)
    teacher_tol = {c.key: c.tolerance for c in mech.answers if c.tolerance is not None}
    shared: dict[Any, Any] = {}
    results = []
    used: list[tuple[str, str, str]] = []
    for sub in task.submissions or ():
        entries = list(sub.entries)
        for e in sub.unresolved:
            if mech.name is not None and e.key == mech.name:
                entries.append(e)
                used.append((sub.student, e.key, task.path))
        verdicts = marked(_grade(sub, entries, task.path, mech, questions, teacher_tol, analysis), mech)
        results.append(FileResult(task.path, mech.name, _share(verdicts, shared), student=sub.student))
    return Done(tuple(results), tuple(used))


def _share(verdicts: tuple[Verdict, ...], shared: dict[Any, Any]) -> tuple[Verdict, ...]:
    """The verdicts with their texts shared among the students of one problem.

    Most students' rows read alike ("dof = 1", "1.44 m/s", "2%"); one string each
    (and pickled once per task) instead of one per row keeps a class's report
    small in the process that gathers it.
    """
    return tuple(
        Verdict(
            *(shared.setdefault((type(x), x), x) if isinstance(x, (str, float)) else x for x in _fields(v))
        )
        for v in verdicts
    )


def _fields(v: Verdict) -> Iterator[Any]:
    return (getattr(v, name) for name in _VERDICT_FIELDS)


_VERDICT_FIELDS = Verdict.__match_args__


def _everyone(
    questions: Sequence[str], status: str, message: str, where: Where | None
) -> tuple[Verdict, ...]:
    return tuple(Verdict(q, status, message=message, where=where) for q in questions)


def _grade(
    sub: Submission,
    entries: Sequence[SheetEntry],
    path: str,
    mech: Mechanism,
    questions: tuple[str, ...],
    teacher_tol: dict[str, Any],
    analysis: Analysis,
) -> tuple[Verdict, ...]:
    """Exactly one scored verdict per question, in the problem's order, then the ignored keys."""
    if sub.unreadable:
        return _everyone(questions, ERROR, "not graded: the answer sheet could not be read", Where(sub.sheet))
    if len(entries) > 1:
        e = _twice(path, entries)
        return _everyone(questions, ERROR, e.problems[0].message, e.problems[0].where)
    if not entries:
        if sub.ambiguous:
            e = ambiguous(sub.ambiguous[0][0], sub.ambiguous[0][1])
            return _everyone(questions, ERROR, e.problems[0].message, e.problems[0].where)
        why = "no sheet was handed in" if sub.missing else "the sheet has no answers for this problem"
        return _everyone(questions, FAIL, f"not answered: {why}", Where(sub.sheet))
    entry = entries[0]
    if entry.problem is not None:
        return _everyone(questions, ERROR, f"not graded: {entry.problem}", entry.where)
    node = entry_node(sub.source, entry, sub.sheet)
    if entry.empty or node is None:
        return _everyone(
            questions, FAIL, "not answered: the sheet's entry for this problem is empty", entry.where
        )
    claims, errors, ignored = _read_entry(sub, node, mech, questions, teacher_tol)
    checked = dict(
        zip(
            claims,
            check(mech, tuple(claims.values()), tolerance=mech.tolerance, analysis=analysis),
            strict=True,
        )
    )
    out = []
    for q in questions:
        if q in errors:
            out.append(errors[q])
        elif q in checked:
            out.append(checked[q])
        else:
            out.append(Verdict(q, FAIL, message="not answered", where=entry.where))
    return tuple(out) + tuple(ignored)


def _read_entry(
    sub: Submission, node: Any, mech: Mechanism, questions: tuple[str, ...], teacher_tol: dict[str, Any]
) -> tuple[dict[str, Claim], dict[str, Verdict], list[Verdict]]:
    """A sheet entry's answers read against the problem: the claims to check (with the teacher's
    tolerance), the questions that cannot be graded (why), and the keys ignored (why).

    Only the questions and the first :data:`MAX_LISTED` other keys are read; the
    rest are counted.
    """
    asked = set(questions)
    listed = [0]

    def wanted(key: str) -> bool:
        if key in asked:
            return True
        listed[0] += 1
        return listed[0] <= MAX_LISTED

    own_tolerance = own_tolerances(node, sub.sheet)
    claims: dict[str, Claim] = {}
    errors: dict[str, Verdict] = {}
    first: dict[str, Where] = {}
    ignored: list[Verdict] = []
    for key, where, got in loader.parse_answer_entries(
        node, mech, path=sub.sheet, source=sub.source, wanted=wanted
    ):
        if key not in asked:
            if got is not None:
                ignored.append(_ignored(key, where, got, questions))
            continue
        if key in first:
            errors[key] = Verdict(
                key,
                ERROR,
                message=f"answered twice on this sheet (lines {first[key].line} and {where.line}): neither is graded",
                where=where,
            )
            claims.pop(key, None)
            continue
        first[key] = where
        if isinstance(got, InputError):
            p = got.problems[0]
            more = len(got.problems) - 1
            text = (
                p.message + (f" ({p.hint})" if p.hint else "") + (f" (and {more} more)" if more > 0 else "")
            )
            errors[key] = Verdict(
                key, ERROR, claimed="", message=f"not graded: {text}", where=p.where or where
            )
        elif key in own_tolerance:
            assert got is not None
            errors[key] = Verdict(
                key,
                ERROR,
                claimed=got.text,
                message="not graded: an answer sheet cannot set a tolerance or marks (the problem file sets them)",
                where=own_tolerance[key],
            )
        elif got is not None:
            claims[key] = replace(got, tolerance=teacher_tol.get(key))
    ignored += _more(listed[0] - MAX_LISTED, "ignored, not scored: not questions of this problem", sub.sheet)
    return claims, errors, ignored


def _ignored(key: str, where: Where, got: Claim | InputError, questions: tuple[str, ...]) -> Verdict:
    """A sheet key that is not a question of the problem: reported, not scored."""
    if key == "tolerance":
        reason = "an answer sheet cannot set a tolerance (the problem file sets it)"
    elif isinstance(got, InputError):
        reason = got.problems[0].message + (f" ({got.problems[0].hint})" if got.problems[0].hint else "")
    else:
        reason = f"not a question of this problem (it asks {', '.join(questions)})"
    written = "" if isinstance(got, InputError) else got.text
    return Verdict(key, IGNORED, claimed=written, message=f"ignored, not scored: {reason}", where=where)


def _twice(path: str, entries: Sequence[SheetEntry]) -> InputError:
    """One problem answered by two entries of a sheet: neither is graded (which one was meant?)."""
    entries = sorted(entries, key=lambda e: (e.where.line, e.where.column))
    keys = " and ".join(f"`{e.key}` (line {e.where.line})" for e in entries)
    return InputError(
        f"{os.path.basename(path)} is answered twice on this sheet: by {keys}; neither is graded",
        where=entries[-1].where,
        hint="keep one entry per problem (a problem's stem, file name, path and `name` all name it)",
    )


def ambiguous(entry: SheetEntry, candidates: Sequence[str]) -> InputError:
    """A sheet key that names several problem files: it is graded against none of them."""
    return InputError(
        f"`{entry.key}` names {len(candidates)} problem files ({', '.join(candidates)}); it is graded "
        "against none of them",
        where=entry.where,
        hint=f"name one by its path under the problems folder (`{candidates[0]}:`) or by its `name`",
    )
