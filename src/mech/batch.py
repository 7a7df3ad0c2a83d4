"""Checking many files at once: folders, answer sheets, worker processes, one report.

``mech check`` is a thin layer over :func:`run`:

1. :func:`find_problem_files` walks files and folders (recursively, ``*.yaml``
   and ``*.yml``, the suffix in any case) into one sorted list.  Every entry
   with such a name is a row, even when it is not a regular file: a FIFO, a
   device, a dangling or looping symbolic link, an unreadable file each become
   an error row (:func:`probe`), never a silent gap or a hung read.
2. With ``answers``, :func:`read_sheets` reads one sheet (one student) or a
   folder of sheets (a class; the student is the sheet's path without its
   suffix).  A sheet maps a problem — its file stem, file name, path under a
   folder given, or ``name`` — to an answers mapping in the same grammar as a
   file's own ``answers``.
3. Each problem file is one task (:class:`mech.check.problem.Task`), loaded
   and solved **once** however many students answered it, in worker processes
   that can be killed (:mod:`mech.batchpool` runs :func:`mech.check.problem.run_task`):
   a file past ``timeout`` seconds is its own error row and the others finish.
   Results come back in sorted order, as soon as they are ready, so a report
   can be streamed.
4. :class:`Report` holds every row, counts them, scores students and owns the
   exit status.

**Scores mean the same for everyone.**  The questions of a problem are fixed by
the teacher: the keys of its ``answers``, else its ``asks``.  Each student gets,
for each problem, exactly one scored verdict per question — pass, fail (wrong,
or not answered) or error (the sheet's entry for it could not be read) — so a
student's score is passed questions over asked questions, the same denominator
for every student.  A sheet key that is not a question is reported as ignored,
never scored.  A problem file that cannot be read, or asks nothing, is the
teacher's error: one row (``excluded``), reported once, and left out of every
score.

**A sheet error costs only what it touches**: each answer of a sheet entry is
read on its own (:func:`mech.loader.parse_answer_entries`), so a bad key or
value is an error for that question alone, located ``line:column``.

**Memory stays bounded** however many sheets a class hands in, and however much
is written on them: a sheet is kept as its text and where each entry's answers
are (:class:`mech.loader.sheets.SheetEntry`), never as YAML nodes; a worker
composes one entry at a time; at most :data:`mech.check.problem.MAX_LISTED`
keys that are not questions are listed per entry (and per sheet, entries naming
no problem), the rest counted in one row.

The trip runs one way: this module calls the pool, the pool calls
:mod:`mech.check.problem`, and nothing below imports this module back.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Callable, Iterable, Sequence
from dataclasses import field, replace
from typing import TYPE_CHECKING, Any

from mech._records import dataclass
from mech.batchpool import Pool, cpu_count, run_jobs
from mech.check.classes import copied, owners, read_class_keys
from mech.check.problem import (
    MAX_LISTED,
    Done,
    Submission,
    Task,
    ambiguous,
    lost_task,
    probe,
    questions_of,
    run_task,
)
from mech.check.verdicts import ERROR, IGNORED, FileResult, Verdict, error_result
from mech.errors import InputError, Problem, Where
from mech.loader.sheets import SheetEntry
from mech.options import SolveOptions

if TYPE_CHECKING:  # pathlib costs mech check ~5 ms of start-up (urllib, ipaddress): only sheets need it
    from pathlib import Path

__all__ = [
    "DEFAULT_TIMEOUT",
    "CheckOptions",
    "Report",
    "Sheet",
    "SheetEntry",
    "StudentScore",
    "find_problem_files",
    "probe",
    "questions_of",
    "read_sheets",
    "run",
]

SUFFIXES = (".yaml", ".yml")

#: Seconds one problem file may take (load, solve, every student's claims) before it is an error row.
DEFAULT_TIMEOUT = 30.0

#: Students graded in one task: a class's problem is checked in parts of this many sheets.
STUDENTS = 200


@dataclass(frozen=True, slots=True)
class CheckOptions:
    """Everything ``mech check`` was asked, folded into one value.

    Parameters
    ----------
    paths
        Problem files and folders.
    answers
        An answer sheet, or a folder of sheets (one per student); None to
        check the answers the problem files carry.
    jobs
        Worker processes; None means one per CPU core, 1 means none (this process).
    solve
        Solver options (Newton's tolerance); drives come from the files.
    timeout
        Seconds a problem file may take before it is an error row (None: no limit).
    """

    paths: tuple[str, ...]
    answers: str | None = None
    jobs: int | None = None
    solve: SolveOptions = field(default_factory=SolveOptions)
    timeout: float | None = DEFAULT_TIMEOUT

    def __post_init__(self) -> None:
        if self.jobs is not None and self.jobs < 1:
            raise ValueError(f"jobs must be at least 1, not {self.jobs}")
        if self.timeout is not None and not self.timeout > 0:
            raise ValueError(f"timeout must be positive, not {self.timeout}")
        if not self.paths:
            raise ValueError("no files or folders to check")

    @property
    def workers(self) -> int:
        return self.jobs if self.jobs is not None else cpu_count()


@dataclass(frozen=True, slots=True)
class StudentScore:
    """One student's totals over every problem that counts: the row a gradebook wants.

    ``asked`` is the number of questions over every problem that is not
    excluded: the same for every student.  ``ignored`` counts sheet keys that
    are not questions (reported, not scored).
    """

    student: str
    problems: int
    asked: int
    passed: int
    failed: int
    errors: int
    ignored: int = 0
    earned: float = 0.0  # marks earned (DESIGN § 1.3: a question is worth 1 unless the file says)
    out_of: float = 0.0  # marks asked: the same for every student

    @property
    def total(self) -> int:
        return self.asked

    @property
    def score(self) -> float:
        """Marks earned over marks asked (0 when nothing is asked); with no marks given, passed over asked."""
        return self.earned / self.out_of if self.out_of else 0.0


@dataclass(frozen=True, slots=True)
class Report:
    """Every row of a batch check, sorted; the counts, the scores and the exit status.

    ``results`` holds one :class:`~mech.check.FileResult` per problem file
    (per student and problem file with answer sheets), including files with
    nothing to check (``skipped``), problem files left out of scoring
    (``excluded``: once without a student — the teacher's row — and once per
    student), and rows about sheets themselves (``sheet``).
    """

    results: tuple[FileResult, ...]
    students: tuple[str, ...] = ()

    @classmethod
    def of(cls, results: Iterable[FileResult], *, students: Sequence[str] = ()) -> Report:
        """A report from results in any order (e.g. gathered from a Dask or Ray cluster)."""
        rows = sorted(results, key=_row_order)
        return cls(tuple(rows), tuple(sorted(students)))

    @property
    def verdicts(self) -> tuple[Verdict, ...]:
        return tuple(v for r in self.results for v in r.verdicts)

    @property
    def skipped(self) -> tuple[str, ...]:
        """Problem files with nothing to check."""
        return tuple(r.path for r in self.results if r.skipped and r.student is None)

    @property
    def teacher(self) -> tuple[FileResult, ...]:
        """Problem files left out of every score (cannot be read, ask nothing): the teacher's rows."""
        return tuple(r for r in self.results if r.excluded and r.student is None)

    @property
    def outsiders(self) -> tuple[FileResult, ...]:
        """Rows of sheets scored for no one: a student no variant of a class was made for."""
        scored = set(self.students)
        return tuple(r for r in self.results if r.student is not None and r.student not in scored)

    @property
    def passed(self) -> int:
        return sum(r.passed for r in self.results)

    @property
    def failed(self) -> int:
        return sum(r.failed for r in self.results)

    @property
    def errors(self) -> int:
        return sum(r.errors for r in self.results)

    @property
    def ignored(self) -> int:
        return sum(r.ignored for r in self.results)

    @property
    def total(self) -> int:
        """Scored verdicts (pass, fail, error)."""
        return sum(r.total for r in self.results)

    @property
    def files(self) -> int:
        """Problem files checked, skipped or excluded (a sheet's own rows are not problem files)."""
        return len({r.path for r in self.results if not r.sheet})

    @property
    def exit_status(self) -> int:
        """0 when every scored answer passed (and there was one) and no file was in error; else 1."""
        return 0 if self.total and self.passed == self.total else 1

    def scores(self) -> tuple[StudentScore, ...]:
        """Per-student totals, sorted by student (empty without answer sheets)."""
        acc: dict[str, list[Any]] = {
            s: [0, 0, 0, 0, 0, 0, 0.0, 0.0] for s in self.students
        }  # problems, asked, passed, failed, errors, ignored, earned, out_of
        for r in self.results:
            if r.student is None or r.student not in acc:
                continue
            a = acc[r.student]
            a[5] += r.ignored
            if r.sheet or r.excluded:
                continue
            a[0] += 1
            a[1] += r.total
            a[2] += r.passed
            a[3] += r.failed
            a[4] += r.errors
            a[6] += r.earned
            a[7] += r.out_of
        return tuple(StudentScore(s, *acc[s]) for s in self.students)


def _row_order(r: FileResult) -> tuple[str, int, str]:
    # the teacher's rows and files checked on their own first, then each student's rows by path
    return (r.student or "", 1 if r.sheet else 0, r.path)


# -- files ----------------------------------------------------------------------------------
def find_problem_files(paths: Iterable[str]) -> tuple[str, ...]:
    """Every ``*.yaml``/``*.yml`` entry named or under a named folder, sorted, without repeats.

    The suffix is matched in any case (``hw.YAML`` is found too).  Entries that
    are not regular files (a FIFO, a dangling symbolic link …) are listed too:
    each becomes an error row, see :func:`probe`.  Hidden files and folders
    are skipped; symbolic links to folders are not followed (no loops).

    Raises
    ------
    InputError
        When a path does not exist, or nothing to check is found.
    """
    paths = list(paths)
    found: set[str] = set()
    problems = []
    for raw in paths:
        if os.path.isdir(raw):
            found.update(_yaml_files(raw))
        elif os.path.lexists(raw):
            found.add(raw)
        else:
            problems.append(Problem(f"no such file or folder: {raw}", Where(raw), "check the path"))
    if problems:
        raise InputError(problems=problems)
    if not found:
        raise InputError(
            f"no mechanism files (*.yaml, *.yml) in {', '.join(paths)}",
            hint="name problem files or folders that hold them",
        )
    return tuple(sorted(found))


def _yaml_files(root: str) -> list[str]:
    """``*.yaml``/``*.yml`` entries under ``root`` (suffix in any case), hidden ones skipped."""
    out: list[str] = []
    stack = [root]
    while stack:
        folder = stack.pop()
        try:
            entries = list(os.scandir(folder))
        except OSError:
            continue
        for e in entries:
            if e.name.startswith("."):
                continue
            if e.is_dir(follow_symlinks=False):
                stack.append(e.path)
            elif os.path.splitext(e.name)[1].lower() in SUFFIXES and not _linked_folder(e):
                out.append(e.path)
    return sorted(out)


def _linked_folder(e: os.DirEntry[str]) -> bool:
    try:
        return e.is_symlink() and e.is_dir()
    except OSError:
        return False


@dataclass(frozen=True, slots=True)
class _Index:
    """Which problem files each sheet key names: by stem, file name or path under a folder given.

    A problem's ``name`` is learnt only when its file is loaded (in a worker),
    so keys naming no file here may still name a problem by its ``name``.
    """

    files: dict[str, tuple[str, ...]]  # key → the problem files it names
    labels: dict[str, str]  # problem file → the shortest key naming it alone

    @classmethod
    def of(cls, files: Sequence[str], roots: Iterable[str]) -> _Index:
        from pathlib import Path

        dirs = [Path(r) for r in roots if Path(r).is_dir()]
        ids: dict[str, list[str]] = {}
        for f in files:
            p = Path(f)
            keys = [p.stem, p.name]
            for d in dirs:
                try:
                    rel = p.relative_to(d)
                except ValueError:
                    continue
                keys += [rel.with_suffix("").as_posix(), rel.as_posix()]
            ids[f] = list(dict.fromkeys(keys))
        by_key: dict[str, list[str]] = {}
        for f, keys in ids.items():
            for k in keys:
                by_key.setdefault(k, []).append(f)
        labels = {f: next((k for k in ids[f] if len(by_key[k]) == 1), f) for f in files}
        return cls({k: tuple(v) for k, v in by_key.items()}, labels)


# -- answer sheets --------------------------------------------------------------------------
@dataclass(frozen=True, slots=True)
class Sheet:
    """One student's answer sheet: its entries, or the error row that it could not be read.

    ``bad_keys`` are entries whose key is not text (a list, a mapping): the
    key as written and where.
    """

    student: str
    path: str
    source: str
    entries: tuple[SheetEntry, ...] = ()
    error: FileResult | None = None
    bad_keys: tuple[tuple[str, str, Where], ...] = ()  # (key as written, what it is, where)
    missing: bool = False  # none handed in: a class's student without a sheet (answers nothing)


def read_sheets(path: str) -> tuple[Sheet, ...]:
    """One sheet (a file) or every sheet under a folder, sorted by student.

    In a folder the student is the sheet's path without its suffix; two sheets
    for one student (``carol.yaml`` and ``carol.yml``) are one error row for
    that student, so that no sheet is counted twice.  A sheet that cannot be
    read is returned with its ``error`` row set, so that one bad sheet costs
    one student one row, not the class its run.

    Raises
    ------
    InputError
        When ``path`` does not exist or a folder holds no sheets.
    """
    from pathlib import Path

    root = Path(path)
    if root.is_dir():
        files = [Path(p) for p in _yaml_files(path)]
        if not files:
            raise InputError(f"no answer sheets (*.yaml, *.yml) in {path}", where=Where(path))
        by_student: dict[str, list[Path]] = {}
        for p in files:
            by_student.setdefault(p.relative_to(root).with_suffix("").as_posix(), []).append(p)
        return tuple(
            _read_sheet(found[0], student) if len(found) == 1 else _two_sheets(student, found)
            for student, found in sorted(by_student.items())
        )
    if root.is_file():
        return (_read_sheet(root, root.stem),)
    if os.path.lexists(path):  # it is there, but neither a sheet nor a folder of sheets: say what it is
        why = probe(path) or "neither a file nor a folder"
        link = (
            f" (a symbolic link to {os.readlink(path)})"
            if os.path.islink(path) and os.path.exists(path)
            else ""
        )
        raise InputError(
            f"the answer sheet {path}{link} is {why}",
            where=Where(path),
            hint="give one sheet (a YAML file) or a folder of sheets",
        )
    raise InputError(f"no such answer sheet or folder: {path}", where=Where(path), hint="check the path")


def _two_sheets(student: str, paths: Sequence[Path]) -> Sheet:
    """Sheets that are one student's (``carol.yaml``, ``carol.yml``): neither is graded."""
    names = [str(p) for p in paths]
    error = InputError(
        f"student {student!r} has {len(names)} answer sheets: {', '.join(names)}; none of them is graded",
        where=Where(names[0]),
        hint="keep one sheet per student (remove or rename the others)",
    )
    return Sheet(student, names[0], "", error=error_result(names[0], error, student=student, sheet=True))


def _read_sheet(path: Path, student: str) -> Sheet:
    """One sheet read through the loader (same decoding, YAML limits and located messages)."""
    from mech.loader import decode
    from mech.loader.sheets import sheet_entries

    name = str(path)

    def failed(error: InputError, text: str = "") -> Sheet:
        return Sheet(student, name, text, error=error_result(name, error, student=student, sheet=True))

    why = probe(name)
    if why is not None:
        return failed(InputError(f"the answer sheet {name} is {why}", where=Where(name)))
    try:
        data = path.read_bytes()
    except OSError as exc:
        return failed(InputError(f"cannot read the answer sheet: {exc}", where=Where(name)))
    try:
        text = decode(data, name, what="answer sheet")
    except InputError as error:
        return failed(error)
    try:
        entries, bad_keys = sheet_entries(text, name)
    except InputError as error:
        return failed(error, text)
    return Sheet(student, name, text, tuple(entries), bad_keys=tuple(bad_keys))


# -- the batch ------------------------------------------------------------------------------
def run(
    options: CheckOptions,
    *,
    on_start: Callable[[int], None] | None = None,
    on_file: Callable[[tuple[FileResult, ...]], None] | None = None,
) -> Report:
    """Check every problem file under ``options.paths``; see the module docstring.

    ``on_start`` is called once with the number of problem files, and
    ``on_file`` with each problem file's rows (every student's, with sheets)
    as soon as it and every file sorted before it are done: the order of the
    final report, so a caller can stream it.

    Raises
    ------
    InputError
        For a usage error: a path that does not exist, nothing to check, a
        sheet folder with no sheets.
    """
    files = find_problem_files(options.paths)
    sheets_given = _yaml_files(options.answers) if options.answers and os.path.isdir(options.answers) else ()
    parts = max(1, -(-len(sheets_given) // STUDENTS))  # a class's problem is graded in parts
    pool: Pool[Task, Done] | None = None
    if options.workers > 1 and len(files) * parts > 1:
        from mech import topology  # noqa: F401  (what every file needs, imported once, before the fork)

        # the workers start now, from a parent that has read no sheet yet: none of them inherits
        # (and counts again in its resident memory) a class's sheets; each task carries its own
        pool = Pool(run_task, lost_task, workers=options.workers, timeout=options.timeout).start()
    with pool or contextlib.nullcontext():
        sheets = read_sheets(options.answers) if options.answers else None
        index = _Index.of(files, options.paths) if sheets is not None else _Index({}, {})  # keys name files
        # a class of variants (mech variants' folder): each student's own problem files, and their keys
        folders, class_key = read_class_keys(options.paths) if sheets is not None else ({}, {})
        owner = owners(files, folders)
        if sheets is not None and owner and options.answers and os.path.isdir(options.answers):
            sheets = _with_roster(sheets, owner, options.answers)
        tasks, extra = _plan(files, sheets, options.solve, index, owner)
        if sheets is not None:
            extra += _not_theirs(sheets, index, owner, folders)
        if sheets is not None:  # the tasks carry the texts and entries now, each let go once done;
            # what is left to report is the entries naming no problem file by path
            sheets = tuple(
                replace(s, source="", entries=tuple(e for e in s.entries if e.key not in index.files))
                for s in sheets
            )
        if on_start is not None:
            on_start(len(files))
        paths = [t.path for t in tasks]
        if pool is not None and len(tasks) > 1:
            # a class's part is heavy (hundreds of students): one at a time, so a worker holds one
            chunk = 1 if sheets is not None else max(1, min(32, len(tasks) // (options.workers * 8)))
            done_tasks = pool.map(tasks, chunk=chunk)
        else:
            done_tasks = run_jobs(tasks, run_task, lost_task, workers=1, timeout=options.timeout)
        del tasks  # the pool keeps them while it needs them
        results = list(extra)
        used: list[tuple[str, str, str]] = []
        lost: dict[str, str] = {}
        landed: list[FileResult] = []
        for i, done in enumerate(done_tasks):
            results += done.results
            used += done.used
            landed += done.results
            if done.lost is not None:
                lost.setdefault(paths[i], done.lost)
            if i + 1 == len(paths) or paths[i + 1] != paths[i]:  # a problem file's last part
                if on_file is not None:
                    on_file(tuple(landed))
                landed = []
    if sheets is not None:
        results = copied(_exclude_lost(results, lost), class_key)
        results = _shared_names(results, sheets, index, used)
        results += _unmatched(sheets, index, {(student, key) for student, key, _ in used})
    report = Report.of(results, students=_students(sheets, owner) if sheets is not None else ())
    if not report.total and not report.errors:
        raise InputError(
            "no answers to check: "
            + ("the file has no" if len(files) == 1 else f"none of the {len(files)} files has an")
            + " `answers` section",
            hint="add answers to the files, or give students' sheets with --answers",
        )
    return report


def _plan(
    files: Sequence[str],
    sheets: Sequence[Sheet] | None,
    solve: SolveOptions,
    index: _Index,
    owner: dict[str, str] | None = None,
) -> tuple[list[Task], list[FileResult]]:
    """One task per problem file; with sheets, each task carries every student's answers to it.

    A file ``owner`` gives to a student (their own variant) is graded for that student alone,
    and their sheet's keys name it and no other student's.
    """
    owner = owner or {}
    if sheets is None:
        return [Task(f, None, solve) for f in files], []
    extra = [s.error for s in sheets if s.error is not None]
    # per student: the entries naming one file, several files (with their labels), or none
    alone: list[dict[str, list[SheetEntry]]] = []
    shared: list[dict[str, list[tuple[SheetEntry, tuple[str, ...]]]]] = []
    unresolved: list[tuple[SheetEntry, ...]] = []
    for s in sheets:
        one: dict[str, list[SheetEntry]] = {}
        several: dict[str, list[tuple[SheetEntry, tuple[str, ...]]]] = {}
        for e in s.entries:
            named = tuple(f for f in index.files.get(e.key, ()) if owner.get(f, s.student) == s.student)
            if len(named) == 1:
                one.setdefault(named[0], []).append(e)
            for f in named if len(named) > 1 else ():
                several.setdefault(f, []).append((e, tuple(index.labels[c] for c in named)))
        alone.append(one)
        shared.append(several)
        unresolved.append(tuple(e for e in s.entries if e.key not in index.files))
    tasks = []
    for f in files:
        subs = tuple(
            Submission(
                s.student,
                s.path,
                s.source,
                tuple(one.get(f, ())),
                tuple(several.get(f, ())),
                loose,
                unreadable=s.error is not None,
                missing=s.missing,
            )
            for s, one, several, loose in zip(sheets, alone, shared, unresolved, strict=True)
            if owner.get(f, s.student) == s.student
        )
        # a class's problem in parts of STUDENTS students: a worker holds (and sends back) one part
        # at a time, and each part loads and solves the problem again (milliseconds)
        for start in range(0, len(subs), STUDENTS) or (0,):
            tasks.append(Task(f, subs[start : start + STUDENTS], solve, first=start == 0))
    return tasks, extra


def _with_roster(sheets: tuple[Sheet, ...], owner: dict[str, str], answers: str) -> tuple[Sheet, ...]:
    """The sheets, and an empty one for each student a class's variant was made for who handed in none.

    Each student gets one scored row per question (cli.md, "Answer sheets"): a missing sheet
    answers nothing, so every question of the student's own variant is "not answered".
    """
    handed = {s.student for s in sheets}
    missing = sorted(set(owner.values()) - handed)
    empty = tuple(
        Sheet(student, os.path.join(answers, f"{student}.yaml"), "", missing=True) for student in missing
    )
    return tuple(sorted((*sheets, *empty), key=lambda s: s.student))


def _not_theirs(
    sheets: Sequence[Sheet], index: _Index, owner: dict[str, str], folders: dict[str, set[str]]
) -> list[FileResult]:
    """An error row for a sheet entry that names only other students' variants: it is scored for no one."""
    out = []
    for s in sheets:
        for e in s.entries:
            files = index.files.get(e.key, ())
            if not files or any(owner.get(f, s.student) == s.student for f in files):
                continue
            roots = sorted({os.path.dirname(os.path.dirname(os.path.normpath(f))) for f in files})
            made = sorted({student for r in roots for student in folders.get(r, ())})
            listed = ", ".join(made[:5]) + (f" and {len(made) - 5:,} more" if len(made) > 5 else "")
            message = (
                f"not graded: {e.key} is a problem of a class of variants ({', '.join(roots)}), and none of "
                f"them is {s.student}'s (mech variants made them for {listed})"
            )
            verdict = Verdict(e.key, ERROR, message=message, where=e.where)
            out.append(FileResult(s.path, verdicts=(verdict,), student=s.student, sheet=True))
    return out


def _students(sheets: Sequence[Sheet], owner: dict[str, str]) -> list[str]:
    """Who is scored: every sheet's student, but where a class of variants is checked, those it was
    made for (another's sheet is listed apart, not scored: no gradebook line of 0 out of 0), the
    problems the class shares with them included."""
    if not owner:
        return [s.student for s in sheets]
    roster = set(owner.values())
    return [s.student for s in sheets if s.student in roster]


def _exclude_lost(results: list[FileResult], lost: dict[str, str]) -> list[FileResult]:
    """A class's problem of which any part was lost (the time limit, a crash) is left out of
    every score, like a problem that cannot be read: the teacher's row once, and every student's
    rows for it not scored, whichever part they were graded in (scores mean the same for all)."""
    if not lost:
        return results
    out = []
    teachers = {r.path for r in results if r.path in lost and r.student is None and not r.sheet}
    for path, why in lost.items():
        if path not in teachers:
            row = FileResult(path, verdicts=(Verdict("file", ERROR, message=why, where=Where(path)),))
            out.append(replace(row, excluded=True))
    for r in results:
        if r.path in lost and r.student is not None and not (r.excluded or r.sheet):
            message = f"not scored: the problem file is excluded ({lost[r.path]})"
            verdicts = tuple(Verdict(v.key, IGNORED, message=message, where=v.where) for v in r.verdicts)
            r = replace(r, verdicts=verdicts, excluded=True)
        out.append(r)
    return out


def _shared_names(
    results: list[FileResult], sheets: Sequence[Sheet], index: _Index, used: Sequence[tuple[str, str, str]]
) -> list[FileResult]:
    """A sheet key that is the `name` of several problem files: each of them is graded as an error."""
    named: dict[tuple[str, str], list[str]] = {}
    for student, key, path in used:
        named.setdefault((student, key), []).append(path)
    clashes = {sk: sorted(paths) for sk, paths in named.items() if len(paths) > 1}
    if not clashes:
        return results
    by_student = {s.student: s for s in sheets}
    swap: dict[tuple[str, str], InputError] = {}
    for (student, key), paths in clashes.items():
        entry = next(e for e in by_student[student].entries if e.key == key)
        error = ambiguous(entry, [index.labels[p] for p in paths])
        for path in paths:
            swap[(student, path)] = error
    out = []
    for r in results:
        clash = swap.get((r.student or "", r.path)) if not r.sheet and not r.excluded else None
        if clash is None:
            out.append(r)
            continue
        p = clash.problems[0]
        verdicts = tuple(
            Verdict(v.key, ERROR, message=p.message, where=p.where) if v.scored else v for v in r.verdicts
        )
        out.append(replace(r, verdicts=verdicts))
    return out


def _unmatched(sheets: Sequence[Sheet], index: _Index, used: set[tuple[str, str]]) -> list[FileResult]:
    """An ignored row for every sheet entry that names no problem file, or whose key is not text.

    At most :data:`~mech.check.problem.MAX_LISTED` rows a sheet; one more counts the rest.
    """
    out = []
    for s in sheets:
        if s.error is not None:
            continue
        rows = [
            Verdict(
                written,
                IGNORED,
                message=f"ignored: a problem is named by text (its file name, stem, path or `name`), not by {kind}",
                where=where,
            )
            for written, kind, where in s.bad_keys[:MAX_LISTED]
        ]
        unnamed = [e for e in s.entries if e.key not in index.files and (s.student, e.key) not in used]
        rows += [
            Verdict(
                e.key,
                IGNORED,
                message=f"ignored: no problem file is named {e.key!r} (by file name, stem, path or `name`)",
                where=e.where,
            )
            for e in unnamed[: max(0, MAX_LISTED - len(rows))]
        ]
        more = len(s.bad_keys) + len(unnamed) - len(rows)
        if more > 0:
            rows.append(
                Verdict(
                    "…",
                    IGNORED,
                    message=f"ignored: {more:,} more entries of this sheet name no problem file, not listed",
                    where=Where(s.path),
                )
            )
        out += [FileResult(s.path, verdicts=(v,), student=s.student, sheet=True) for v in rows]
    return out
