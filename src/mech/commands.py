"""What the hot commands do, without click: the bodies :mod:`mech.cli` and :mod:`mech.entry` share.

``mech dof``, ``mech classify`` and ``mech position|velocity|acceleration``
are the commands run most often, one file at a time, and their start-up is
benchmarked: importing click costs about two interpreter start-ups, and
:mod:`mech.entry` runs their plain command lines without it.  So their
bodies, the error report and the option folding live here, importing
nothing heavy (numpy, rich, yaml and the analyses are imported inside the
functions that use them), and :mod:`mech.cli`'s click commands call them.
:func:`echo` writes as ``click.echo`` does, so both paths print the same bytes.
"""

from __future__ import annotations

import contextlib
import math
import sys
from collections.abc import Callable, Iterable, Sequence
from enum import IntEnum
from functools import wraps
from typing import TYPE_CHECKING, Any, TypeVar

from mech._records import dataclass
from mech.errors import InputError, MechError
from mech.options import OutputUnits, SolveOptions, angle_spacing_problem

if TYPE_CHECKING:  # pragma: no cover
    from mech.analysis import Result

__all__ = [
    "CHECK_UNITS",
    "DEFAULT_FILE",
    "ExitStatus",
    "Request",
    "check_paths",
    "check_targets",
    "check_usage",
    "classify_files",
    "count_dof",
    "echo",
    "handles_errors",
    "kinematics",
    "report_error",
    "solve_options",
    "write_report",
]

F = TypeVar("F", bound=Callable[..., Any])

DEFAULT_FILE = "mechanism.yaml"


class ExitStatus(IntEnum):
    """What ``mech`` returns to the shell (cli.md, "Exit statuses"); no other status is returned."""

    OK = 0
    CHECK_FAILED = 1
    BAD_INPUT = 2
    # sysexits.h's EX_SOFTWARE: a bug in mech, never confused with a failed check or bad input
    INTERNAL_ERROR = 70
    # what a shell reports for a process SIGINT or SIGPIPE stopped (128 + the signal's number)
    INTERRUPTED = 130
    PIPE_CLOSED = 141


def _utf8(stream: Any) -> bool:
    encoding = (getattr(stream, "encoding", None) or "").lower().replace("-", "").replace("_", "")
    return encoding == "utf8"


def echo(message: str, *, err: bool = False) -> None:
    """``click.echo(message, err=err)`` without importing click on the usual streams.

    click writes straight to a UTF-8 stream, with ANSI escapes stripped when
    it is not a terminal; any other stream (an ASCII locale) it re-wraps, so
    there click itself is used.
    """
    stream = sys.stderr if err else sys.stdout
    if stream is None:
        return
    if not _utf8(stream):
        import click

        click.echo(message, err=err)
        return
    out = message + "\n"
    if not stream.isatty():
        import re

        out = re.sub(r"\033\[[;?0-9]*[a-zA-Z]", "", out)  # click.termui's strip_ansi
    stream.write(out)
    stream.flush()


def report_error(error: MechError) -> None:
    """Print every problem of ``error`` to stderr, with the offending line when it has one."""
    echo(error_text(error), err=True)


def error_text(error: MechError) -> str:
    """Every problem of ``error`` as ``file:line:col: error: …`` with the line, a caret and the hint.

    Errors found after loading (a length that cannot close a loop) carry a
    location but not the text; the file is read again here to show the line.
    """
    if error.source is None:
        path = next((p.where.path for p in error.problems if p.where and p.where.line), None)
        if path and path != "<stdin>":
            try:
                with open(path, encoding="utf-8") as f:
                    error.source = f.read()
            except (OSError, UnicodeDecodeError):
                pass
    return error.format()


def handles_errors(fn: F | None = None, *, command: str | None = None) -> Any:
    """Turn a :class:`MechError` into its message on stderr and exit status 2.

    Only errors mech raises on purpose are caught: a bug still shows its
    traceback, so that it gets reported rather than disguised as bad input.
    Under ``--json`` (an ``as_json`` keyword, or a :class:`Request` asking for it)
    the error is JSON on stderr instead, its ``text`` the message as people read it
    (cli.md, "The JSON contract"), naming ``command``: by default the function's
    name without ``_command``.  stdout stays for results only.
    """
    if fn is None:
        return lambda f: handles_errors(f, command=command)

    @wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            return fn(*args, **kwargs)
        except MechError as error:
            request = next((a for a in (*args, *kwargs.values()) if isinstance(a, Request)), None)
            if kwargs.get("as_json", request is not None and request.as_json):
                from mech.render.jsonout import dumps, error_record

                name = command or wrapper.__name__.removesuffix("_command")
                file = kwargs.get("file", request.file if request is not None else None)
                echo(dumps({**error_record(name, file, error), "text": error_text(error)}), err=True)
            else:
                report_error(error)
            sys.exit(error.exit_code)

    return wrapper


# -- counting -------------------------------------------------------------------------
def count_dof(files: Sequence[str], mobility: bool, as_json: bool) -> None:
    """``mech dof``: Kutzbach and Grübler for each file, one table (or JSON) for all.

    A bad file is reported on stderr and the others are still counted (exit
    status 2 at the end).
    """
    from mech.analysis import Request as Asked
    from mech.analysis import analyse
    from mech.render.emit import choose, emit

    asked = Asked(level=None, topology=True, mobility=mobility)
    counted: list[tuple[str, Result | MechError]] = []
    for path in files or (DEFAULT_FILE,):
        try:
            counted.append((path, analyse(path, asked)))
        except MechError as error:
            counted.append((path, error))
            if not as_json:
                report_error(error)
    counted.sort(key=lambda c: isinstance(c[1], MechError))  # the files counted, then the errors
    emit("dof", choose(as_json), counted, echo=echo, mobility=mobility)
    if any(isinstance(r, MechError) for _, r in counted):
        sys.exit(ExitStatus.BAD_INPUT)


@handles_errors(command="classify")
def classify_files(file: str, as_json: bool) -> None:
    """``mech classify``: links, joints and pairs of one file, as tables or JSON."""
    from mech.analysis import Request as Asked
    from mech.analysis import analyse
    from mech.render.emit import choose, emit

    topology = analyse(file, Asked(level=None, topology=True)).topology
    emit("classify", choose(as_json), topology, echo=echo)


# -- kinematics -----------------------------------------------------------------------
@dataclass(frozen=True, slots=True)
class Request:
    """What a solving command was asked, folded from its options once (STYLE: one value)."""

    file: str
    options: SolveOptions
    units: OutputUnits
    as_json: bool

    @property
    def speed_given(self) -> bool:
        """True when --rpm, --omega or --speed set the drive's speed."""
        return self.options.omega is not None or self.options.speed is not None


def solve_options(
    rpm: float | None,
    omega: float | None,
    angle: float | None,
    direction: str | None,
    tol: float,
    alpha: float | None = None,
    speed: float | None = None,
) -> SolveOptions:
    """Command-line speeds and angles (rpm, degrees) → one validated :class:`SolveOptions`."""
    if rpm is not None and omega is not None:
        raise InputError("give --rpm or --omega, not both")
    turning = None
    for name, value, factor in (("--rpm", rpm, 2 * math.pi / 60), ("--omega", omega, 1.0)):
        if value is not None:
            if not math.isfinite(value) or value < 0:
                raise InputError(
                    f"{name} must be a finite speed ≥ 0", hint="give the sense with --direction cw|ccw"
                )
            turning = value * factor
    if angle is not None and not math.isfinite(angle):
        raise InputError("--angle must be a finite number of degrees")
    if angle is not None and (problem := angle_spacing_problem(angle)) is not None:
        raise InputError(problem, hint="give the same crank position nearer 0 (subtract whole turns of 360°)")
    try:
        return SolveOptions(
            # reduce in degrees, where it is exact, before converting (1e300° is 0°)
            angle=None if angle is None else math.radians(math.fmod(angle, 360.0)),
            omega=turning,
            speed=speed,
            direction=direction,
            alpha=alpha,
            tol=tol,
        )
    except ValueError as exc:
        raise InputError(f"{exc}") from None


def kinematics(request: Request, level: str, explain: bool = False) -> None:
    """``mech position|velocity|acceleration``: solve at the instant, emit the tables or JSON."""
    from mech.analysis import Request as Asked
    from mech.analysis import analyse
    from mech.render.emit import choose, emit

    result = analyse(request.file, Asked(level=level, options=request.options))
    construction = None
    if explain:
        from mech.explain import explain as write_out

        assert result.kinematics is not None  # solved at the level asked
        construction = write_out(result.mechanism, result.kinematics, kind=level)
    emit(
        "kinematics",
        choose(request.as_json),
        result,
        echo=echo,
        units=request.units,
        construction=construction,
    )


# -- checking answers -------------------------------------------------------------------
#: The units of every computed value in ``mech check --json`` (claims are compared in SI).
CHECK_UNITS = {
    "length": "m",
    "velocity": "m/s",
    "acceleration": "m/s^2",
    "angle": "rad",
    "angular_velocity": "rad/s",
    "angular_acceleration": "rad/s^2",
    "force": "N",
    "torque": "N m",
}


def check_targets(junit: str | None, gradescope: str | None, csv_path: str | None) -> list[tuple[str, str]]:
    """The report files asked for, as (option, path) in the order they are written."""
    return [(o, p) for o, p in (("--junit", junit), ("--gradescope", gradescope), ("--csv", csv_path)) if p]


def check_usage(answers: str | None, targets: Sequence[tuple[str, str]]) -> str | None:
    """What is wrong with a ``mech check`` command line that click alone cannot see (None: nothing)."""
    import os

    if answers and os.path.isdir(answers) and any(o == "--gradescope" for o, _ in targets):
        return "--gradescope writes one submission's results.json; for a folder of sheets use --csv or --json"
    seen: dict[str, str] = {}
    for option, path in targets:
        key = os.path.normcase(os.path.realpath(path))
        if key in seen:
            return f"{seen[key]} and {option} both write {path}: give each report its own file"
        seen[key] = option
    return None


@handles_errors(command="check")
def check_paths(
    options: Any, targets: list[tuple[str, str]], *, quiet: bool, verbose: bool, as_json: bool
) -> None:
    """``mech check`` once its command line is read (``options``: a :class:`mech.batch.CheckOptions`).

    Ctrl-C leaves no report file behind (an old or partial one must not pass
    for this run's) and exits 130.
    """
    import os

    try:
        _check(options, targets, quiet=quiet, verbose=verbose, as_json=as_json)
    except KeyboardInterrupt:
        for _, path in targets:
            with contextlib.suppress(OSError):
                os.unlink(path)
        echo("mech check: interrupted; no report written", err=True)
        sys.exit(ExitStatus.INTERRUPTED)


def _check(
    options: Any, targets: list[tuple[str, str]], *, quiet: bool, verbose: bool, as_json: bool
) -> None:
    """Run the batch, streaming a plain report when piped or large, then write the report files."""
    import os

    from mech.batch import run
    from mech.render.check import LARGE_BATCH, Stream

    stream: list[Stream] = []
    bar: Any = None

    def start(total: int) -> None:
        nonlocal bar
        if as_json:
            return
        if not sys.stdout.isatty() or os.environ.get("NO_COLOR") or total > LARGE_BATCH:
            stream.append(Stream(sys.stdout, verbose=verbose, quiet=quiet))
        if sys.stderr.isatty() and not os.environ.get("NO_COLOR"):
            from mech.render.check import progress

            bar = progress()
            begin, advance = bar.__enter__()
            begin(total)
            bar.advance = advance

    def landed(rows: Any) -> None:
        if bar is not None:
            bar.advance(rows)
        if stream:
            stream[0].file(rows)

    try:
        report = run(options, on_start=start, on_file=landed)
    finally:
        if bar is not None:
            bar.__exit__(None, None, None)
    from mech.render import check as render

    outputs = {
        "--junit": render.junit_chunks,
        "--gradescope": lambda r: render.dumps(render.gradescope_dict(r)) + "\n",
        "--csv": render.csv_text,
    }
    for option, path in targets:
        write_report(path, outputs[option](report))
    if as_json:
        from mech.render.jsonout import stamp

        # the batch's report: each result names its file and mechanism; the top level has no one file
        record = stamp(render.report_dict(report), command="check", file=None, name=None, units=CHECK_UNITS)
        echo(render.dumps(record))
    elif stream:
        stream[0].end(report)
    else:
        from mech.render.console import stdout

        render.check_table(report, stdout(), quiet=quiet, verbose=verbose)
    sys.exit(report.exit_status)


def write_report(path: str, text: str | Iterable[str]) -> None:
    """Write a report file atomically (a temporary file renamed into place); exit 2 if it cannot be.

    ``text`` may come in pieces (a large JUnit report), written as they come.
    """
    import os
    import tempfile

    from mech.errors import Where

    folder = os.path.dirname(os.path.abspath(path))
    tmp = None
    try:
        fd, tmp = tempfile.mkstemp(prefix=".mech-", suffix=".tmp", dir=folder)
        with os.fdopen(fd, "w", encoding="utf-8", newline="") as f:
            if isinstance(text, str):
                f.write(text)
            else:
                f.writelines(text)
        mask = os.umask(0)
        os.umask(mask)
        os.chmod(tmp, 0o666 & ~mask)  # mkstemp makes it private; a report is an ordinary file
        os.replace(tmp, path)
        tmp = None
    except OSError as exc:
        raise InputError(f"cannot write {path}: {exc.strerror}", where=Where(path)) from None
    finally:
        if tmp is not None:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
