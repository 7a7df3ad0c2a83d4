"""Every option and argument of every command, declared once.

Each :class:`Param` says an option's names, where its value goes, its type, default,
help and check.  Two readers use the same declarations:

* :mod:`mech.cli` builds click's options and arguments from them (:func:`mech.cli.params_of`),
  so ``--help``, click's conversions and its usage errors come from here;
* :mod:`mech.entry`'s fast path reads the plainest command lines of the hot commands
  with :func:`read`, without importing click (click costs about two start-ups of the
  interpreter), and hands the same values to the same command bodies.

:func:`read` takes only what click would read to the same values — exact spellings, values
that convert as click converts them — and answers None for anything else, which click
then parses as it always has.  So the fast path can cost speed, never behaviour.

Checks that say more than a type (``--rpm`` is a finite speed ≥ 0) are each option's
``check``; :func:`validate` runs them in the command bodies, on whichever path read the
command line, and a failure is an :class:`~mech.errors.InputError` (exit 2).
"""

from __future__ import annotations

import math
import os
import stat
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from mech.errors import InputError
from mech.options import angle_spacing_problem

__all__ = ["COMMANDS", "DEBUG", "FAST", "Param", "read", "validate"]

DEFAULT_FILE = "mechanism.yaml"

Check = Callable[[Any], None]


class Param:
    """One option (``names`` start with ``-``) or argument (one name, no dash) of a command.

    ``kind``: ``flag``, ``text``, ``float``, ``int``, ``choice`` or ``path``.  ``low``/``high``
    bound a number (``low_open``: the bound itself is refused), as click's ``FloatRange`` and
    ``IntRange``; ``exists``, ``dir_okay``, ``allow_dash`` and ``writable`` are click's ``Path``'s.
    ``nargs=-1``: an argument that takes every positional word.  ``check``: what the value
    must also be, raising :class:`~mech.errors.InputError` (run by :func:`validate`).

    A plain slotted class, not a dataclass: some sixty are made at every start-up of the fast
    path, and a generated ``__init__`` costs more to make than all of them (1.2 ms).
    """

    __slots__ = (
        "allow_dash",
        "check",
        "choices",
        "default",
        "dest",
        "dir_okay",
        "exists",
        "help",
        "high",
        "kind",
        "low",
        "low_open",
        "multiple",
        "names",
        "nargs",
        "required",
        "show_default",
        "writable",
    )

    def __init__(
        self,
        names: tuple[str, ...],
        dest: str,
        kind: str = "text",
        help: str = "",
        *,
        default: Any = None,
        show_default: bool = False,
        required: bool = False,
        multiple: bool = False,
        choices: tuple[str, ...] = (),
        low: float | None = None,
        high: float | None = None,
        low_open: bool = False,
        exists: bool = False,
        dir_okay: bool = True,
        allow_dash: bool = False,
        writable: bool = False,
        nargs: int = 1,
        check: Check | None = None,
    ) -> None:
        self.names, self.dest, self.kind, self.help = names, dest, kind, help
        self.default, self.show_default, self.required, self.multiple = (
            default,
            show_default,
            required,
            multiple,
        )
        self.choices, self.low, self.high, self.low_open = choices, low, high, low_open
        self.exists, self.dir_okay, self.allow_dash, self.writable = exists, dir_okay, allow_dash, writable
        self.nargs, self.check = nargs, check

    def __repr__(self) -> str:
        return f"Param({'/'.join(self.names)} -> {self.dest}: {self.kind})"

    @property
    def is_option(self) -> bool:
        return self.names[0].startswith("-")

    def convert(self, text: str) -> Any:
        """``text`` as click converts it; :data:`NO` where click might refuse it or read it otherwise.

        Conservative on purpose: only the plainest spellings are converted here.
        """
        if self.kind == "choice":
            return text if text in self.choices else NO
        if self.kind in ("text", "path"):
            return text if self.kind == "text" or self._path_ok(text) else NO
        if self.kind == "int":  # only plain digits: click's int() also reads "+3", " 3", "3_0"
            if not (text.isascii() and text.isdigit()):
                return NO
            number: float = int(text)
        else:
            try:
                number = float(text)  # click's FLOAT converts with float() itself
            except ValueError:
                return NO
            if (self.low is not None or self.high is not None) and not math.isfinite(number):
                return NO  # a range's infinities: left to click
        if self.low is not None and (number < self.low or (self.low_open and number == self.low)):
            return NO
        if self.high is not None and number > self.high:
            return NO
        return number

    def _path_ok(self, path: str) -> bool:
        """What click's ``Path(exists=…, dir_okay=…, allow_dash=…)`` accepts without a word."""
        if path == "-":
            return self.allow_dash
        try:
            st = os.stat(path)
        except OSError:
            return not self.exists
        if not self.dir_okay and stat.S_ISDIR(st.st_mode):
            return False
        return os.access(path, os.R_OK)


class _No:
    """What :meth:`Param.convert` answers for a value it leaves to click."""

    def __repr__(self) -> str:
        return "NO"


NO: Any = _No()


# -- checks -------------------------------------------------------------------------------------
def _speed(name: str) -> Check:
    def check(value: float) -> None:
        if not math.isfinite(value) or value < 0:
            raise InputError(
                f"{name} must be a finite speed ≥ 0", hint="give the sense with --direction cw|ccw"
            )

    return check


def _finite_angle(value: float) -> None:
    if not math.isfinite(value):
        raise InputError("--angle must be a finite number of degrees")
    problem = angle_spacing_problem(value)  # an angle past float precision names no position
    if problem is not None:
        raise InputError(problem, hint="give the same crank position nearer 0 (subtract whole turns of 360°)")


def _cam_rpm(value: float) -> None:
    if not (value > 0 and math.isfinite(value)):
        raise InputError(f"--rpm must be a positive number, not {value:g}")


def validate(params: Sequence[Param], values: Mapping[str, Any]) -> None:
    """Run every given option's ``check`` in declaration order (the first failure is raised)."""
    for p in params:
        value = values.get(p.dest)
        if p.check is not None and value is not None:
            p.check(value)


# -- the declarations ---------------------------------------------------------------------------
def _flag(names: tuple[str, ...], dest: str, help: str) -> Param:
    return Param(names, dest, "flag", help, default=False)


DEBUG = _flag(("--debug",), "debug", "Show the traceback of a bug in mech (as MECH_DEBUG=1 does).")
JSON = _flag(("--json",), "as_json", "Print JSON (structure in cli.md) instead of tables.")
FILE = Param(("file",), "file", "path", default=DEFAULT_FILE, dir_okay=False, allow_dash=True)
EXPLAIN = _flag(
    ("--explain",), "explain", "Write the construction out step by step, as the lecture notes draw it."
)
DIRECTION = Param(
    ("--direction",), "direction", "choice", "Sense of the crank's rotation.", choices=("cw", "ccw")
)

#: The options of every command that solves the mechanism at an instant (and of sweeps).
KINEMATIC = (
    FILE,
    Param(("--rpm",), "rpm", "float", "Crank speed in rev/min (overrides the file).", check=_speed("--rpm")),
    Param(
        ("--omega",), "omega", "float", "Crank speed in rad/s (overrides the file).", check=_speed("--omega")
    ),
    Param(
        ("--angle",),
        "angle",
        "float",
        "Crank angle in degrees, counter-clockwise from +x.",
        check=_finite_angle,
    ),
    Param(("--speed",), "speed", "float", "A slider drive's speed in m/s, signed along its path."),
    DIRECTION,
    Param(
        ("--tol",),
        "tol",
        "float",
        "Newton tolerance on the loop closure, relative to the mechanism's size.",
        default=1e-12,
        show_default=True,
    ),
    Param(
        ("--units",),
        "unit_system",
        "choice",
        "Print lengths and speeds in m, mm or cm (angles always in deg, rad/s).",
        default="si",
        show_default=True,
        choices=("si", "mm", "cm"),
    ),
    JSON,
)
ALPHA = Param(
    ("--alpha",), "alpha", "float", "Crank angular acceleration in rad/s², counter-clockwise positive."
)


def _out(names: tuple[str, ...], dest: str, help: str, **more: Any) -> Param:
    """A file mech writes (a drawing, a report): never a folder."""
    return Param(names, dest, "path", help, dir_okay=False, **more)


def _many(names: tuple[str, ...], dest: str, help: str) -> Param:
    return Param(names, dest, "text", help, multiple=True)


SWEEP = (
    Param(
        ("--from",),
        "start",
        "float",
        "First crank angle, degrees (default 0); a slider drive's first position, file's length unit.",
    ),
    Param(
        ("--to",),
        "stop",
        "float",
        "Last crank angle, degrees (default 360); a slider drive's last position, file's length unit.",
    ),
    Param(
        ("--drive",),
        "lead",
        "text",
        "With several drives: the drive (link or slider joint) whose angle or position is swept "
        "(default the first); the others move in proportion to their speeds.",
    ),
    Param(
        ("--steps",),
        "steps",
        "int",
        "Steps (angles − 1).",
        default=360,
        show_default=True,
        low=1,
        high=10_000_000,
    ),
    Param(
        ("--level",),
        "level",
        "choice",
        "How far to solve (default: velocity with a drive speed, else position).",
        choices=("position", "velocity", "acceleration"),
    ),
    _many(
        ("--quantity",),
        "quantities",
        "A quantity to report (repeatable): omega.rocker, velocity.B, displacement.P … (default: all).",
    ),
    _out(
        ("--csv",),
        "csv_path",
        "Write the series as CSV (- for standard output, instead of the report).",
        allow_dash=True,
    ),
    Param(
        ("--method",),
        "method",
        "choice",
        "Closed-form dyads where the chain decomposes (auto), only them, or Newton with --tol.",
        default="auto",
        show_default=True,
        choices=("auto", "closed", "newton"),
    ),
    _out(("--plot",), "plot_path", "Plot the quantities to a PNG (needs matplotlib)."),
    _out(("--animate",), "gif_path", "Animate the cycle to a GIF (needs matplotlib)."),
    _many(
        ("--path",),
        "paths",
        "A point whose path to trace (repeatable): its x and y become quantities (CSV columns, extent).",
    ),
    _out(("--svg",), "svg_path", "Draw the --path curves alone to an SVG file."),
)

CHECK = (
    Param(("paths",), "paths", "path", nargs=-1, required=True, exists=True),
    Param(
        ("--answers",),
        "answers",
        "path",
        "A student's answer sheet, or a folder of sheets (one per student) to check a class.",
        exists=True,
    ),
    Param(
        ("-j", "--jobs"),
        "jobs",
        "int",
        "Worker processes (default: one per CPU core; 1: no pool).",
        low=1,
    ),
    _out(("--junit",), "junit", "Also write JUnit XML (one testcase per answer)."),
    _out(("--gradescope",), "gradescope", "Also write a Gradescope autograder results.json."),
    _out(("--csv",), "csv_path", "Also write a CSV gradebook (student, problem …)."),
    _flag(("-q", "--quiet"), "quiet", "List only files, students and answers that did not pass."),
    _flag(("-v", "--verbose"), "verbose", "List every answer (default: one line per file, or per student)."),
    Param(
        ("--timeout",),
        "timeout",
        "float",
        "Seconds one problem file may take before it is an error row (the others finish).",
        default=30.0,
        show_default=True,
        low=0,
        low_open=True,
    ),
    JSON,
)

DRAW = (
    _out(("-o", "--output"), "output", "The drawing to write: .svg or .png.", required=True),
    _flag(("--velocity",), "velocity", "Add the velocity polygon (o, a, b …) beside the configuration."),
    _flag(("--acceleration",), "acceleration", "Add the acceleration polygon with its components."),
    _flag(("--icentres",), "with_icentres", "Mark the I-centres on the configuration."),
    _many(("--path",), "paths", "Trace a point's path over the cycle (repeatable)."),
    _many(
        ("--centrodes",), "centrodes", "Draw a link's fixed and moving centrodes over the cycle (repeatable)."
    ),
)

#: ``mech view``: the live page (DESIGN § 1.5).
VIEW = (
    _out(("-o", "--output"), "output", "The page to write (.html).", required=True),
    Param(
        ("--steps",),
        "steps",
        "int",
        "Instants over a crank's turn (360: 1° apart); a slider's stroke: steps from --from to --to.",
        default=360,
        show_default=True,
        low=2,
        high=100_000,
    ),
    Param(("--from",), "start", "float", "A slider drive's first position (file's length unit)."),
    Param(("--to",), "stop", "float", "A slider drive's last position (file's length unit)."),
)

CAM = (
    FILE,
    Param(("--rpm",), "rpm", "float", "Cam speed in rpm (overrides the file's drive).", check=_cam_rpm),
    Param(
        ("--direction",),
        "direction",
        "choice",
        "The sense the cam turns (overrides the drive).",
        choices=("cw", "ccw"),
    ),
    Param(
        ("--joint",), "joint", "text", "The cam joint to analyse, when the file has several with a programme."
    ),
    Param(
        ("--step",),
        "step",
        "float",
        "Cam angle between rows of the motion table, degrees.",
        default=30.0,
        show_default=True,
        low=0.1,
        high=360.0,
    ),
    Param(
        ("--samples",),
        "samples",
        "int",
        "Cam angles sampled over the turn (points on the profile).",
        default=1440,
        show_default=True,
        low=36,
        high=100_000,
    ),
    _out(("-o", "--output"), "output", "Draw the cam profile to scale (.svg or .png)."),
    _out(("--diagram",), "diagram", "Plot the s–v–a–j diagrams (.svg or .png)."),
    JSON,
)

#: Every command's parameters, in the order ``--help`` lists them (arguments anywhere).
COMMANDS: dict[str, tuple[Param, ...]] = {
    "dof": (
        Param(("files",), "files", "path", nargs=-1, dir_okay=False, allow_dash=True),
        _flag(
            ("--mobility",),
            "mobility",
            "Also compute the true mobility from the constraint Jacobian's rank (needs geometry).",
        ),
        JSON,
    ),
    "classify": (FILE, JSON),
    "schema": (_out(("-o", "--output"), "output", "Write to a file.", writable=True),),
    "position": KINEMATIC,
    "velocity": (EXPLAIN, *KINEMATIC),
    "acceleration": (EXPLAIN, *KINEMATIC, ALPHA),
    "icentres": (
        EXPLAIN,
        _out(("--circle",), "circle_path", "Draw Kennedy's circle diagram to an .svg or .png file."),
        *KINEMATIC,
    ),
    "properties": (
        _many(
            ("--output",),
            "outputs",
            "A link or point whose mechanical advantage to give (repeatable; default: every moving link).",
        ),
        *KINEMATIC,
    ),
    "sweep": (*SWEEP, *KINEMATIC),
    "check": CHECK,
    "draw": (*DRAW, *KINEMATIC, ALPHA),
    "cam": CAM,
    "view": (*VIEW, *KINEMATIC),
}

#: The commands :mod:`mech.entry` reads without click (their bodies are in :mod:`mech.commands`).
FAST = ("dof", "classify", "check", "position", "velocity", "acceleration")


# -- the fast path's reader ---------------------------------------------------------------------
def read(command: str, args: Sequence[str]) -> dict[str, Any] | None:
    """``args`` (after the command's name) as the values click would pass, or None.

    None for anything not plainly one of the command's forms: ``--help``, ``--``, a misspelt
    or abbreviated option, joined short options (``-qv``, ``-j2``), a value click would
    refuse or might read otherwise, a positional word too many.  Values are keyed by each
    parameter's ``dest``, with the declared defaults (``()`` for a repeatable option).
    """
    params = COMMANDS[command]
    options = {name: p for p in params if p.is_option for name in p.names}
    values: dict[str, Any] = {}
    positional: list[str] = []
    i = 0
    while i < len(args):
        token = args[i]
        i += 1
        if token == "-" or not token.startswith("-"):
            positional.append(token)
            continue
        name, eq, given = token.partition("=")
        if eq and not name.startswith("--"):
            return None  # -j=2: click reads "=2" as the value
        p = options.get(name)
        if p is None:
            return None
        if p.kind == "flag":
            if eq:
                return None
            values[p.dest] = True
            continue
        if not eq:
            if i == len(args):
                return None
            given = args[i]
            i += 1
        value = p.convert(given)
        if value is NO:
            return None
        values[p.dest] = (*values.get(p.dest, ()), value) if p.multiple else value
    if not _place(params, positional, values):
        return None
    for p in params:
        if p.dest not in values:
            values[p.dest] = () if p.multiple or p.nargs == -1 else p.default
    return values


def _place(params: Sequence[Param], positional: list[str], values: dict[str, Any]) -> bool:
    """Give the positional words to the command's arguments as click would; False to leave it to click."""
    arguments = [p for p in params if not p.is_option]
    for p in arguments:
        if p.nargs == -1:
            taken, positional = positional, []
            if p.required and not taken:
                return False
        elif positional:
            taken, positional = positional[:1], positional[1:]
        elif p.required or p.default is None:
            return False
        else:
            taken = [p.default]
        converted = [p.convert(t) for t in taken]
        if any(c is NO for c in converted):
            return False
        values[p.dest] = tuple(converted) if p.nargs == -1 else converted[0]
    return not positional
