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
from collections.abc import Callable, Iterable, Mapping, Sequence
from functools import wraps
from typing import TYPE_CHECKING, Any, TypeVar

from mech._records import dataclass
from mech.commands.exits import ExitStatus, is_utf8
from mech.commands.params import COMMANDS, DEFAULT_FILE, KINEMATIC, Param, validate
from mech.errors import InputError, MechError
from mech.options import OutputUnits, SolveOptions

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
    "request_of",
    "run_command",
    "write_report",
]

F = TypeVar("F", bound=Callable[..., Any])


def echo(message: str, *, err: bool = False) -> None:
    """``click.echo(message, err=err)`` without importing click on the usual streams.

    click writes straight to a UTF-8 stream, with ANSI escapes stripped when
    it is not a terminal; any other stream (an ASCII locale) it re-wraps, so
    there click itself is used.
    """
    stream = sys.stderr if err else sys.stdout
    if stream is None:
        return
    if not is_utf8(stream):
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
    if as_json and len(counted) == 1 and isinstance(counted[0][1], MechError):
        # one file, and it failed: the error object on stderr, as every command's (cli.md, "The JSON contract")
        from mech.render.jsonout import dumps, error_record

        path, failed = counted[0]
        assert isinstance(failed, MechError)
        echo(dumps({**error_record("dof", path, failed), "text": error_text(failed)}), err=True)
        sys.exit(failed.exit_code)
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


def request_of(values: Mapping[str, Any], params: Sequence[Param] = KINEMATIC) -> Request:
    """A solving command's values (as :mod:`mech.commands.params` declares them) folded into one
    validated :class:`Request`: speeds and angles (rpm, degrees) become one :class:`SolveOptions`.

    Each option's own check runs here (:func:`mech.commands.params.validate`), after the
    rules that tie two options together, on whichever path read the command line.
    """
    rpm, omega, angle = values.get("rpm"), values.get("omega"), values.get("angle")
    if rpm is not None and omega is not None:
        raise InputError("give --rpm or --omega, not both")
    validate(params, values)
    turning = None if rpm is None else rpm * 2 * math.pi / 60
    turning = omega if omega is not None else turning
    try:
        options = SolveOptions(
            # reduce in degrees, where it is exact, before converting (1e300° is 0°)
            angle=None if angle is None else math.radians(math.fmod(angle, 360.0)),
            omega=turning,
            speed=values.get("speed"),
            direction=values.get("direction"),
            alpha=values.get("alpha"),
            tol=values.get("tol", 1e-12),
        )
    except ValueError as exc:
        raise InputError(f"{exc}") from None
    units = OutputUnits.named(values.get("unit_system", "si"))
    return Request(values.get("file", DEFAULT_FILE), options, units, bool(values.get("as_json")))


def solve_command(command: str, values: Mapping[str, Any]) -> None:
    """``mech position|velocity|acceleration`` from its values: fold, solve, report (exit 2 on bad input)."""

    @handles_errors(command=command)
    def run(*, file: str, as_json: bool) -> None:
        kinematics(request_of(values, COMMANDS[command]), command, bool(values.get("explain")))

    run(file=values["file"], as_json=values["as_json"])


def run_command(command: str, values: Mapping[str, Any]) -> None:
    """Run one of :data:`mech.commands.params.FAST` with the values its declarations read."""
    if command == "dof":
        count_dof(values["files"], values["mobility"], values["as_json"])
    elif command == "classify":
        classify_files(file=values["file"], as_json=values["as_json"])
    elif command == "check":
        check_command(values)
    else:
        solve_command(command, values)


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


def check_targets(values: Mapping[str, Any]) -> list[tuple[str, str]]:
    """The report files asked for, as (option, path) in the order they are written."""
    pairs = (
        ("--junit", "junit"),
        ("--gradescope", "gradescope"),
        ("--csv", "csv_path"),
        ("--gradebook", "gradebook"),
    )
    return [(option, values[dest]) for option, dest in pairs if values.get(dest)]


def check_usage(values: Mapping[str, Any]) -> str | None:
    """What is wrong with a ``mech check`` command line that click alone cannot see (None: nothing).

    Two reports may share a device (``/dev/null``): it is written through, one after the other.
    """
    import os
    import stat

    answers, targets = values.get("answers"), check_targets(values)
    if answers and os.path.isdir(answers) and any(o == "--gradescope" for o, _ in targets):
        return "--gradescope writes one submission's results.json; for a folder of sheets use --csv or --json"
    if not answers and any(o == "--gradebook" for o, _ in targets):
        return "--gradebook writes one row per student: give the students' answer sheets with --answers"
    seen: dict[str, str] = {}
    for option, path in targets:
        with contextlib.suppress(OSError):
            if not stat.S_ISREG(os.stat(path).st_mode):
                continue
        key = os.path.normcase(os.path.realpath(path))
        if key in seen:
            return f"{seen[key]} and {option} both write {path}: give each report its own file"
        seen[key] = option
    return None


def check_command(values: Mapping[str, Any]) -> None:
    """``mech check`` from its values (:data:`mech.commands.params.CHECK`), usage already checked."""
    from mech.batch import CheckOptions

    options = CheckOptions(
        paths=tuple(values["paths"]),
        answers=values["answers"],
        jobs=values["jobs"],
        timeout=values["timeout"],
    )
    check_paths(
        options,
        check_targets(values),
        quiet=values["quiet"],
        verbose=values["verbose"],
        as_json=values["as_json"],
    )


@handles_errors(command="check")
def check_paths(
    options: Any, targets: list[tuple[str, str]], *, quiet: bool, verbose: bool, as_json: bool
) -> None:
    """``mech check`` once its command line is read (``options``: a :class:`mech.batch.CheckOptions`).

    Every report path is tried before the first file is checked (a folder that does not
    exist is said at once, not after the batch).  Ctrl-C leaves no report file behind
    (an old one must not pass for this run's; a device or a link stays) and exits 130.
    """
    from mech._files import check_writable, discard

    for _, path in targets:
        check_writable(path)
    try:
        _check(options, targets, quiet=quiet, verbose=verbose, as_json=as_json)
    except KeyboardInterrupt:
        for _, path in targets:
            discard(path)
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
        "--gradebook": render.gradebook_text,
    }
    for option, path in targets:
        write_report(path, outputs[option](report))
        if option == "--gradebook":  # the scores' histogram beside it (issue 22 item 5)
            from mech.render.stats import histogram

            svg = os.path.splitext(path)[0] + ".svg"
            if svg != path and os.path.isfile(path):  # a device (/dev/stdout) has no "beside"
                write_report(svg, histogram([s.score for s in report.scores()], title="scores"))
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
    """Write a report file (:func:`mech._files.write_file`: atomic, links followed, devices written
    through); exit 2 naming the path if it cannot be.

    ``text`` may come in pieces (a large JUnit report), written as they come.
    """
    from mech._files import write_file

    write_file(path, text)
