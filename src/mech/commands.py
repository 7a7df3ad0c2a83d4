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

import math
import sys
from collections.abc import Callable, Sequence
from enum import IntEnum
from functools import wraps
from typing import TYPE_CHECKING, Any, TypeVar

from mech._records import dataclass
from mech.errors import InputError, MechError
from mech.options import OutputUnits, SolveOptions

if TYPE_CHECKING:  # pragma: no cover
    from mech.analysis import Result

__all__ = [
    "DEFAULT_FILE",
    "ExitStatus",
    "Request",
    "classify_files",
    "count_dof",
    "echo",
    "handles_errors",
    "kinematics",
    "report_error",
    "solve_options",
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
