"""Errors that users see: typed, located, and with a hint on what to do.

Every error a user can cause by writing a file derives from :class:`MechError`
and carries where it happened (file, line, column) and a hint.  Each subclass
also inherits the builtin it refines (``ValueError`` …) so library callers can
catch what they already know.  Only the command line maps errors to exit codes:
2 for bad input, 1 for a failed check.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Sequence

from mech._records import dataclass
from mech._text import visible

_YAML_BREAK = re.compile("\r\n|[\r\n\x85\u2028\u2029]")


@dataclass(frozen=True, slots=True)
class Where:
    """A place in a source file; ``line`` and ``column`` count from 1."""

    path: str
    line: int = 0
    column: int = 0

    def __str__(self) -> str:
        if self.line:
            return f"{self.path}:{self.line}:{self.column}"
        return self.path


def source_lines(source: str) -> list[str]:
    """The lines of a YAML text as YAML counts them (CR LF, CR, LF, NEL, LS, PS).

    Not ``str.splitlines``: it also breaks at form feeds and the file separators,
    so the line a message quotes would not be the line its number names.
    """
    return _YAML_BREAK.split(source)


@dataclass(frozen=True, slots=True)
class Problem:
    """One thing wrong with an input, with where it is and what to do about it."""

    message: str
    where: Where | None = None
    hint: str | None = None

    def format(self, source: str | None = None) -> str:
        """``file:line:col: error: message``, then the line, a caret and the hint."""
        # a file name, a quoted value or the echoed line may hold control or direction
        # characters from the user's file: shown as escapes, never sent to the terminal
        head = f"{self.where}: error: {self.message}" if self.where else f"error: {self.message}"
        lines = [visible(head)]
        if source is not None and self.where is not None and self.where.line:
            text_lines = source_lines(source)
            if 0 < self.where.line <= len(text_lines):
                text = text_lines[self.where.line - 1].rstrip("\n")
                lines.append(f"    {visible(text)}")
                lead = len(visible(text[: max(self.where.column - 1, 0)]))
                lines.append("    " + " " * lead + "^")
        if self.hint:
            lines.append(visible(f"  hint: {self.hint}"))
        return "\n".join(lines)


class MechError(Exception):
    """Base of every error mech reports to a user.

    It holds one or more :class:`Problem` s, so that a file with three typos
    is reported once with all three, not in three fix-and-run cycles.
    """

    exit_code = 2

    def __init__(
        self,
        message: str | None = None,
        *,
        where: Where | None = None,
        hint: str | None = None,
        problems: Sequence[Problem] | None = None,
        source: str | None = None,
    ) -> None:
        if problems is None:
            problems = [Problem(message or "", where, hint)]
        self.problems: tuple[Problem, ...] = tuple(problems)
        self.source = source
        super().__init__(self.problems[0].message if self.problems else "")

    @property
    def where(self) -> Where | None:
        return self.problems[0].where if self.problems else None

    @property
    def hint(self) -> str | None:
        return self.problems[0].hint if self.problems else None

    def format(self) -> str:
        """All problems, each as ``file:line:col: error: …`` with a caret and a hint."""
        return "\n".join(p.format(self.source) for p in self.problems)

    def __str__(self) -> str:
        if len(self.problems) == 1:
            p = self.problems[0]
            return f"{p.where}: {p.message}" if p.where else p.message
        return "; ".join(f"{p.where}: {p.message}" if p.where else p.message for p in self.problems)


class InputError(MechError, ValueError):
    """The file (or the command line) says something mech cannot accept."""


class UnitError(InputError):
    """A number carries a unit that is unknown or of the wrong kind."""


class GeometryError(MechError, ArithmeticError):
    """The mechanism cannot be assembled, or a configuration is singular.

    Raised by the solvers with the numbers that disagree (the gap, the
    aligned links, the condition number), never as a silent NaN.
    """


class UnsupportedError(MechError, NotImplementedError):
    """The file is valid, but the asked analysis cannot be done for it.

    For example a sweep of a cam whose profile is not given, or velocities
    of a spherical pair in a planar solver.
    """


def collect(problems: Iterable[Problem], *, source: str | None, cls: type[MechError] = InputError) -> None:
    """Raise ``cls`` with every problem at once, or return when there are none."""
    problems = list(problems)
    if problems:
        raise cls(problems=problems, source=source)
