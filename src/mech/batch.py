"""Checking many files at once: folders, answer sheets, parallel processes, one report.

``mech check`` is a thin layer over :func:`run`:

1. :func:`find_problem_files` walks files and folders (recursively, ``*.yaml``
   and ``*.yml``, the suffix in any case) into one sorted list.
2. With ``answers``, :func:`read_sheets` reads one sheet (one student) or a
   folder of sheets (a class; the student is the sheet's path without its
   suffix).  A sheet maps a problem — its file stem, file name, path under a
   folder given, or ``name`` — to an answers mapping in the same grammar as a
   file's own ``answers``.  Paths are resolved here (:class:`_Index`), names
   in the worker that loads the file; a key naming several files, or a
   problem named by several keys, is an error row, never graded twice.
3. Each problem file is loaded and solved **once**, however many students
   answered it, and every student's claims are checked against that one
   solution (:class:`mech.check.Analysis`).  With ``jobs > 1`` problems are
   spread over a process pool; results are sorted, so the report is the same
   whatever order they finish in.
4. :class:`Report` holds every row, counts them and owns the exit status.

A file's exception becomes its row: a malformed problem file, an unreadable
sheet, a sheet entry that names no problem, each is one error row, and the
rest of the batch still runs.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Sequence
from dataclasses import field
from pathlib import Path
from typing import Any

from mech._records import dataclass
from mech.check import ERROR, FAIL, Analysis, FileResult, InternalError, Verdict, check, error_result
from mech.errors import InputError, MechError, Problem, Where
from mech.options import SolveOptions

__all__ = [
    "CheckOptions",
    "Report",
    "Sheet",
    "SheetEntry",
    "StudentScore",
    "find_problem_files",
    "read_sheets",
    "run",
]

SUFFIXES = (".yaml", ".yml")


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
        Worker processes; None means one per CPU core, 1 means no pool.
    solve
        Solver options (Newton's tolerance); drives come from the files.
    """

    paths: tuple[str, ...]
    answers: str | None = None
    jobs: int | None = None
    solve: SolveOptions = field(default_factory=SolveOptions)

    def __post_init__(self) -> None:
        if self.jobs is not None and self.jobs < 1:
            raise ValueError(f"jobs must be at least 1, not {self.jobs}")
        if not self.paths:
            raise ValueError("no files or folders to check")

    @property
    def workers(self) -> int:
        return self.jobs if self.jobs is not None else (os.cpu_count() or 1)


@dataclass(frozen=True, slots=True)
class StudentScore:
    """One student's totals over every problem: the row a gradebook wants."""

    student: str
    problems: int
    passed: int
    failed: int
    errors: int

    @property
    def total(self) -> int:
        return self.passed + self.failed + self.errors

    @property
    def score(self) -> float:
        """Fraction of answers that passed (0 with no answers)."""
        return self.passed / self.total if self.total else 0.0


@dataclass(frozen=True, slots=True)
class Report:
    """Every row of a batch check, sorted; the counts and the exit status.

    ``results`` holds one :class:`~mech.check.FileResult` per problem file (per
    student and problem file with answer sheets, plus rows for sheets that
    could not be used); ``skipped`` the files that carried no answers.
    """

    results: tuple[FileResult, ...]
    skipped: tuple[str, ...] = ()
    students: tuple[str, ...] = ()

    @classmethod
    def of(cls, results: Iterable[FileResult], *, students: Sequence[str] = ()) -> Report:
        """A report from results in any order (e.g. gathered from a Dask or Ray cluster)."""
        rows = list(results)
        kept = sorted((r for r in rows if not r.skipped), key=lambda r: (r.student or "", r.path))
        skipped = sorted(r.path for r in rows if r.skipped)
        return cls(tuple(kept), tuple(skipped), tuple(sorted(students)))

    @property
    def verdicts(self) -> tuple[Verdict, ...]:
        return tuple(v for r in self.results for v in r.verdicts)

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
    def total(self) -> int:
        return sum(r.total for r in self.results)

    @property
    def files(self) -> int:
        """Problem files checked or skipped (a sheet's own rows are not problem files)."""
        return len({r.path for r in self.results if not r.sheet}) + len(self.skipped)

    @property
    def exit_status(self) -> int:
        """0 when every answer passed (and there was at least one), 1 otherwise."""
        return 0 if self.total and self.passed == self.total else 1

    def scores(self) -> tuple[StudentScore, ...]:
        """Per-student totals, sorted by student (empty without answer sheets)."""
        out = []
        for student in self.students:
            rows = [r for r in self.results if r.student == student]
            out.append(
                StudentScore(
                    student=student,
                    problems=len({r.path for r in rows if not r.sheet}),
                    passed=sum(r.passed for r in rows),
                    failed=sum(r.failed for r in rows),
                    errors=sum(r.errors for r in rows),
                )
            )
        return tuple(out)


# -- files ----------------------------------------------------------------------------------
def find_problem_files(paths: Iterable[str]) -> tuple[str, ...]:
    """Every ``*.yaml``/``*.yml`` file named or under a named folder, sorted, without repeats.

    The suffix is matched in any case (``hw.YAML`` is found too).

    Raises
    ------
    InputError
        When a path does not exist, or nothing to check is found.
    """
    found: set[str] = set()
    problems = []
    for raw in paths:
        path = Path(raw)
        if path.is_dir():
            found.update(str(p) for p in _yaml_files(path))
        elif path.is_file():
            found.add(str(path))
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


def _yaml_files(root: Path) -> list[Path]:
    """``*.yaml``/``*.yml`` files under ``root`` (suffix in any case), hidden folders skipped."""
    return sorted(
        p for p in root.rglob("*") if p.suffix.lower() in SUFFIXES and p.is_file() and not _hidden(p, root)
    )


def _hidden(path: Path, root: Path) -> bool:
    return any(part.startswith(".") for part in path.relative_to(root).parts)


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
class SheetEntry:
    """One top-level entry of a sheet: a problem key, where it is written, and its answers.

    ``node`` is the answers mapping node (kept, not converted, so that the
    loader validates it with the same code and locations as a file's own
    ``answers``); None for an empty entry (``four_bar: {}`` or ``four_bar:``),
    which answers nothing.  ``problem`` says why the value cannot be answers.
    """

    key: str
    where: Where
    node: Any = None
    problem: str | None = None

    @property
    def empty(self) -> bool:
        return self.problem is None and (self.node is None or not self.node.value)


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
    root = Path(path)
    if root.is_dir():
        files = _yaml_files(root)
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
    import yaml

    name = str(path)

    def failed(error: InputError, text: str = "") -> Sheet:
        return Sheet(student, name, text, error=error_result(name, error, student=student, sheet=True))

    try:
        text = path.read_bytes().decode("utf-8-sig")
    except (OSError, UnicodeDecodeError) as exc:
        return failed(InputError(f"cannot read the answer sheet: {exc}", where=Where(name)))
    loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
    try:
        root = yaml.compose(text, Loader=loader)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = Where(name, mark.line + 1, mark.column + 1) if mark else Where(name)
        what = getattr(exc, "problem", None) or "malformed YAML"
        return failed(
            InputError(f"this answer sheet is not valid YAML: {what}", where=where, source=text), text
        )
    if not isinstance(root, yaml.MappingNode):
        error = InputError(
            "an answer sheet maps problems to answers (`four_bar: {dof: 1, …}`)",
            where=Where(name, 1, 1),
            hint="each top-level key is a problem's file name, stem or name",
        )
        return failed(error, text)
    from mech.loader import is_null, node_kind

    entries = []
    bad_keys = []
    for knode, vnode in root.value:
        where = Where(name, knode.start_mark.line + 1, knode.start_mark.column + 1)
        if not isinstance(knode, yaml.ScalarNode):
            written = " ".join(text[knode.start_mark.index : knode.end_mark.index].split())
            bad_keys.append((written if len(written) <= 40 else written[:39] + "…", node_kind(knode), where))
            continue
        key = str(knode.value)
        if isinstance(vnode, yaml.MappingNode):
            entries.append(SheetEntry(key, where, vnode))
        elif is_null(vnode):
            entries.append(SheetEntry(key, where))
        else:
            message = f"the answers to {key} must be a mapping (`dof: 1` lines), not {node_kind(vnode)}"
            entries.append(SheetEntry(key, where, problem=message))
    return Sheet(student, name, text, tuple(entries), bad_keys=tuple(bad_keys))


@dataclass(frozen=True, slots=True)
class _Submission:
    """What a worker needs of one student's sheet for one problem."""

    student: str
    sheet: str
    source: str
    entries: tuple[SheetEntry, ...]  # entries naming this problem file (and no other) by path
    ambiguous: tuple[tuple[SheetEntry, tuple[str, ...]], ...]  # entries naming it and others: candidates
    unresolved: tuple[SheetEntry, ...]  # entries naming no file by path: maybe a problem's `name`


@dataclass(frozen=True, slots=True)
class _Task:
    path: str
    submissions: tuple[_Submission, ...] | None
    solve: SolveOptions


@dataclass(frozen=True, slots=True)
class _Done:
    results: tuple[FileResult, ...]
    used: tuple[tuple[str, str, str], ...] = ()  # (student, sheet key, problem file) matched by `name`


# -- the worker -----------------------------------------------------------------------------
def _run_tasks(tasks: Sequence[_Task]) -> list[_Done]:
    """Check a chunk of problems (one process-pool job)."""
    return [_run_task(task) for task in tasks]


def _run_task(task: _Task) -> _Done:
    try:
        return _check_task(task)
    except Exception as exc:  # a bug: this file's rows say so, the batch goes on
        error = InternalError.of(exc)
        rows = [Verdict("file", ERROR, message=str(error))]
        students = [s.student for s in task.submissions] if task.submissions is not None else [None]
        return _Done(tuple(FileResult(task.path, verdicts=tuple(rows), student=s) for s in students))


def _check_task(task: _Task) -> _Done:
    from mech.loader import load

    try:
        mech = load(task.path)
    except MechError as error:
        if task.submissions is None:
            return _Done((error_result(task.path, error),))
        return _Done(tuple(error_result(task.path, error, student=s.student) for s in task.submissions))
    if task.submissions is None:
        if not mech.answers:
            return _Done((FileResult(task.path, mech.name, skipped=True),))
        return _Done((FileResult(task.path, mech.name, check(mech, options=task.solve)),))
    return _check_sheets(task, mech)


def _check_sheets(task: _Task, mech: Any) -> _Done:
    """Every student's claims on one problem, against one shared solution."""
    from mech.loader import parse_answers

    analysis = Analysis(mech, options=task.solve)
    teacher = {c.key: c for c in mech.answers}
    parsed: list[tuple[_Submission, SheetEntry | None, Any]] = []
    used: list[tuple[str, str, str]] = []
    for sub in task.submissions or ():
        entries = list(sub.entries)
        for e in sub.unresolved:
            if mech.name is not None and e.key == mech.name:
                entries.append(e)
                used.append((sub.student, e.key, task.path))
        if len(entries) > 1:
            parsed.append((sub, None, _twice(task.path, entries, sub.source)))
            continue
        if not entries:
            error = (
                _ambiguous(sub.ambiguous[0][0], sub.ambiguous[0][1], sub.source) if sub.ambiguous else None
            )
            parsed.append((sub, None, error))
            continue
        entry = entries[0]
        if entry.problem is not None:
            problem = Problem(entry.problem, entry.where, "see cli.md § mech check")
            parsed.append((sub, entry, InputError(problems=[problem], source=sub.source)))
            continue
        if entry.empty:
            parsed.append((sub, entry, None))
            continue
        try:
            _refuse_tolerance(entry.node, sub)
            claims, _ = parse_answers(entry.node, mech, path=sub.sheet, source=sub.source)
        except InputError as error:
            parsed.append((sub, entry, error))
            continue
        parsed.append((sub, entry, claims))
    analysis.need([c for _, _, claims in parsed if isinstance(claims, tuple) for c in claims])
    results = []
    for sub, entry, claims in parsed:
        if isinstance(claims, MechError):
            results.append(error_result(task.path, claims, student=sub.student, name=mech.name))
            continue
        where = entry.where if entry is not None else Where(sub.sheet)
        if claims is None:
            # not answered: nothing on the sheet, or an empty entry; one row per question if the
            # problem file sets them, so that leaving a problem out never scores better than trying it
            why = (
                "the sheet's entry for this problem is empty"
                if entry
                else "the sheet has no answers for this problem"
            )
            verdicts = [Verdict(key, FAIL, message=f"not answered: {why}", where=where) for key in teacher]
            verdicts = verdicts or [Verdict("answers", FAIL, message=f"not answered: {why}", where=where)]
            results.append(FileResult(task.path, mech.name, tuple(verdicts), student=sub.student))
            continue
        # tolerances are the teacher's: per answer from the problem file, else the file's
        with_tol = tuple(
            c
            if c.key not in teacher or teacher[c.key].tolerance is None
            else _with_tolerance(c, teacher[c.key].tolerance)
            for c in claims
        )
        verdicts = list(check(mech, with_tol, tolerance=mech.tolerance, analysis=analysis))
        answered = {c.key for c in claims}
        verdicts += [
            Verdict(key, FAIL, message="not answered", where=where) for key in teacher if key not in answered
        ]
        results.append(FileResult(task.path, mech.name, tuple(verdicts), student=sub.student))
    return _Done(tuple(results), tuple(used))


def _twice(path: str, entries: Sequence[SheetEntry], source: str) -> InputError:
    """One problem answered by two entries of a sheet: neither is graded (which one was meant?)."""
    entries = sorted(entries, key=lambda e: (e.where.line, e.where.column))
    keys = " and ".join(f"`{e.key}` (line {e.where.line})" for e in entries)
    return InputError(
        f"{Path(path).name} is answered twice on this sheet: by {keys}; neither is graded",
        where=entries[-1].where,
        hint="keep one entry per problem (a problem's stem, file name, path and `name` all name it)",
        source=source,
    )


def _ambiguous(entry: SheetEntry, candidates: Sequence[str], source: str) -> InputError:
    """A sheet key that names several problem files: it is graded against none of them."""
    return InputError(
        f"`{entry.key}` names {len(candidates)} problem files ({', '.join(candidates)}); it is graded "
        "against none of them",
        where=entry.where,
        hint=f"name one by its path under the problems folder (`{candidates[0]}:`) or by its `name`",
        source=source,
    )


def _with_tolerance(claim: Any, tolerance: Any) -> Any:
    from dataclasses import replace

    return replace(claim, tolerance=tolerance)


def _refuse_tolerance(node: Any, sub: _Submission) -> None:
    """A sheet may not set its own tolerance: the problem file (the teacher) does."""
    import yaml

    problems = []
    for knode, vnode in node.value:
        spots = [knode] if knode.value == "tolerance" else []
        if isinstance(vnode, yaml.MappingNode):
            spots += [k for k, _ in vnode.value if k.value == "tolerance"]
        problems += [
            Problem(
                "an answer sheet cannot set a tolerance",
                Where(sub.sheet, k.start_mark.line + 1, k.start_mark.column + 1),
                "tolerances are set in the problem file; write `key: value` only",
            )
            for k in spots
        ]
    if problems:
        raise InputError(problems=problems, source=sub.source)


# -- the batch ------------------------------------------------------------------------------
def run(
    options: CheckOptions,
    *,
    on_start: Callable[[int], None] | None = None,
    on_result: Callable[[FileResult], None] | None = None,
) -> Report:
    """Check every problem file under ``options.paths``; see the module docstring.

    ``on_start`` is called once with the number of rows to come (files, times
    students with sheets) and ``on_result`` with each row as it lands (in
    completion order), for a progress bar; the returned :class:`Report` is sorted.

    Raises
    ------
    InputError
        For a usage error: a path that does not exist, nothing to check, a
        sheet folder with no sheets.
    """
    files = find_problem_files(options.paths)
    sheets = read_sheets(options.answers) if options.answers else None
    index = _Index.of(files, options.paths)
    tasks, extra = _plan(files, sheets, options.solve, index)
    if on_start is not None:
        on_start(sum(len(t.submissions) if t.submissions is not None else 1 for t in tasks))
    done = _execute(tasks, options.workers, on_result)
    results = list(extra)
    used: list[tuple[str, str, str]] = []
    for d in done:
        results += d.results
        used += d.used
    if sheets is not None:
        results = _shared_names(results, sheets, index, used)
        results += _unmatched(sheets, index, {(student, key) for student, key, _ in used})
    report = Report.of(results, students=[s.student for s in sheets] if sheets is not None else ())
    if not report.results:
        raise InputError(
            f"no answers to check: none of the {len(files)} file{'s' if len(files) != 1 else ''} has an `answers` section",
            hint="add answers to the files, or give students' sheets with --answers",
        )
    return report


def _plan(
    files: Sequence[str], sheets: Sequence[Sheet] | None, solve: SolveOptions, index: _Index
) -> tuple[list[_Task], list[FileResult]]:
    """One task per problem file; with sheets, each task carries every student's answers to it."""
    if sheets is None:
        return [_Task(f, None, solve) for f in files], []
    extra = [s.error for s in sheets if s.error is not None]
    usable = [s for s in sheets if s.error is None]
    # per student: the entries naming one file, several files (with their labels), or none
    alone: list[dict[str, list[SheetEntry]]] = []
    shared: list[dict[str, list[tuple[SheetEntry, tuple[str, ...]]]]] = []
    unresolved: list[tuple[SheetEntry, ...]] = []
    for s in usable:
        one: dict[str, list[SheetEntry]] = {}
        several: dict[str, list[tuple[SheetEntry, tuple[str, ...]]]] = {}
        for e in s.entries:
            named = index.files.get(e.key, ())
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
            _Submission(s.student, s.path, s.source, tuple(one.get(f, ())), tuple(several.get(f, ())), loose)
            for s, one, several, loose in zip(usable, alone, shared, unresolved, strict=True)
        )
        tasks.append(_Task(f, subs, solve))
    return tasks, extra


def _shared_names(
    results: list[FileResult], sheets: Sequence[Sheet], index: _Index, used: Sequence[tuple[str, str, str]]
) -> list[FileResult]:
    """A sheet key that is the `name` of several problem files: an error row for each of them."""
    named: dict[tuple[str, str], list[str]] = {}
    for student, key, path in used:
        named.setdefault((student, key), []).append(path)
    clashes = {sk: sorted(paths) for sk, paths in named.items() if len(paths) > 1}
    if not clashes:
        return results
    by_student = {s.student: s for s in sheets}
    replace: dict[tuple[str, str], FileResult] = {}
    for (student, key), paths in clashes.items():
        sheet = by_student[student]
        entry = next(e for e in sheet.entries if e.key == key)
        error = _ambiguous(entry, [index.labels[p] for p in paths], sheet.source)
        for path in paths:
            replace[(student, path)] = error_result(path, error, student=student)
    return [replace.get((r.student or "", r.path), r) if not r.sheet else r for r in results]


def _unmatched(sheets: Sequence[Sheet], index: _Index, used: set[tuple[str, str]]) -> list[FileResult]:
    """An error row for every sheet entry that names no problem file, or whose key is not text."""
    out = []
    for s in sheets:
        if s.error is not None:
            continue
        rows = [
            Verdict(
                written,
                ERROR,
                message=f"a problem is named by text (its file name, stem, path or `name`), not by {kind}",
                where=where,
            )
            for written, kind, where in s.bad_keys
        ]
        rows += [
            Verdict(
                e.key,
                ERROR,
                message=f"no problem file is named {e.key!r} (by file name, stem, path or `name`)",
                where=e.where,
            )
            for e in s.entries
            if e.key not in index.files and (s.student, e.key) not in used
        ]
        out += [FileResult(s.path, verdicts=(v,), student=s.student, sheet=True) for v in rows]
    return out


def _execute(
    tasks: Sequence[_Task], workers: int, on_result: Callable[[FileResult], None] | None
) -> list[_Done]:
    """Run tasks serially (one worker, or too few tasks to pay for a pool) or in a process pool."""

    def landed(done: _Done) -> None:
        if on_result is not None:
            for r in done.results:
                on_result(r)

    if workers <= 1 or len(tasks) < 2:
        out = []
        for task in tasks:
            d = _run_task(task)
            landed(d)
            out.append(d)
        return out
    from concurrent.futures import ProcessPoolExecutor, as_completed
    from concurrent.futures.process import BrokenProcessPool

    workers = min(workers, len(tasks))
    # chunks amortise pickling and process hand-off; several per worker keep the load balanced
    size = max(1, min(32, len(tasks) // (workers * 8)))
    chunks = [tasks[i : i + size] for i in range(0, len(tasks), size)]
    out = []
    lost: list[_Task] = []
    with ProcessPoolExecutor(max_workers=workers) as pool:
        futures = {pool.submit(_run_tasks, chunk): chunk for chunk in chunks}
        for future in as_completed(futures):
            try:
                done = future.result()
            except BrokenProcessPool:
                lost.extend(futures[future])  # a worker died: these files get a second chance below
                continue
            for d in done:
                landed(d)
                out.append(d)
    for task in lost:
        d = _run_isolated(task)
        landed(d)
        out.append(d)
    return out


def _run_isolated(task: _Task) -> _Done:
    """Check one file in a process of its own, so that a crash there is that file's error row.

    Used only after a worker died (the interpreter itself crashed on some file): every
    file of the lost chunks is checked again alone, and the one that crashes again is
    reported, while the others get their verdicts.
    """
    from concurrent.futures import ProcessPoolExecutor
    from concurrent.futures.process import BrokenProcessPool

    try:
        with ProcessPoolExecutor(max_workers=1) as pool:
            return pool.submit(_run_task, task).result()
    except BrokenProcessPool:
        message = "mech crashed while checking this file (a bug in mech or its YAML parser: please report it)"
        rows = (Verdict("file", ERROR, message=message),)
        students = [s.student for s in task.submissions] if task.submissions is not None else [None]
        return _Done(tuple(FileResult(task.path, verdicts=rows, student=st) for st in students))
