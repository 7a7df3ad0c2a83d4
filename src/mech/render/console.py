"""The one place that decides colour and width (rich honours NO_COLOR and non-tty).

Piped output is written by :class:`~mech.render.plain.PlainConsole`, which
prints rich's bytes without importing rich where it can; renderers take
their ``Table`` and ``Text`` from :func:`kit` so that it can.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Iterable
from functools import lru_cache
from typing import TYPE_CHECKING, Any, Protocol

from mech._text import visible

if TYPE_CHECKING:  # pragma: no cover
    from rich.box import Box
    from rich.console import Console
    from rich.segment import Segment


class ReportConsole(Protocol):
    """What mech's renderers use of a console: rich's ``Console`` is one, and so is
    :class:`~mech.render.plain.PlainConsole`.

    A renderer prints tables, ``Text`` and strings with :meth:`print` and asks
    :func:`kit` or :func:`table_box` (which read the three attributes) what
    kind of table to build.  Typed against this protocol, a renderer that
    reaches for more of rich's console (which the plain one hands on to rich,
    the slow way) must say so here first.
    """

    @property
    def is_terminal(self) -> bool: ...

    @property
    def no_color(self) -> bool: ...

    @property
    def color_system(self) -> str | None: ...

    def print(self, *objects: Any, soft_wrap: bool = ..., highlight: bool = ...) -> None: ...


@lru_cache(maxsize=1)
def stdout() -> ReportConsole:
    """The console for reports.  Piped output is plain text, $COLUMNS (default 120) wide."""
    if not _isatty() and not _forced_terminal():
        from mech.render.plain import PlainConsole

        return PlainConsole(int(os.environ.get("COLUMNS", 120)))
    console_class = rich_console_class()

    # markup=False: names, claims and messages come from users' files, and "[/b]" in a
    # mechanism's name must print as written, not be read (or fail) as rich markup.
    # Styles are given as Text styles instead.
    console = console_class(highlight=False, markup=False)
    if not console.is_terminal:
        width = int(os.environ.get("COLUMNS", 120))
        return console_class(highlight=False, markup=False, width=width, color_system=None)
    if os.environ.get("NO_COLOR"):
        # rich drops colour for NO_COLOR but keeps bold; we promise plain text
        return console_class(highlight=False, markup=False, color_system=None)
    return console


@lru_cache(maxsize=1)
def rich_console_class() -> type[Console]:
    """rich's Console, except that a reader who closed the pipe is not a failed run,
    and that text from users' files cannot drive the terminal.

    rich answers EPIPE by exiting with status 1, which in mech means "a check
    failed"; this one stops writing and lets :func:`mech.entry.guarded` give the
    pipe's own status (141).  Every rich console mech prints reports with is one.
    """
    from rich.console import Console as RichConsole
    from rich.segment import Segment

    class Console(RichConsole):
        def on_broken_pipe(self) -> None:
            self.quiet = True
            raise BrokenPipeError

        def _render_buffer(self, buffer: Iterable[Segment]) -> str:
            # the one gate every report's text passes on its way out: a title, a path or a
            # claim from a user's file may hold a terminal escape or a direction override,
            # shown here as \x1b / \u202e (the rule of mech._text.visible); rich's own
            # colour codes are added after this, from the segments' styles
            return super()._render_buffer(
                s if s.control else Segment(visible(s.text), s.style) for s in buffer
            )

    return Console


def is_plain(console: ReportConsole) -> bool:
    """True when the console writes plain text (not a terminal, or NO_COLOR set)."""
    return not console.is_terminal or console.no_color or console.color_system is None


def table_box(console: ReportConsole) -> Box:
    """Rounded boxes on a terminal, simple ruled text otherwise."""
    from rich import box

    return box.SIMPLE if is_plain(console) else box.ROUNDED


def kit(console: ReportConsole) -> tuple[Any, Any, Any]:
    """``(Table, Text, box)`` for ``console``: mech's plain ones for a plain console, rich's otherwise.

    ``box`` is :func:`table_box`'s choice, for tables made with this ``Table``.
    """
    if getattr(console, "is_plain", False):
        from mech.render.plain import SIMPLE, Table, Text

        return Table, Text, SIMPLE
    from rich.table import Table as RichTable
    from rich.text import Text as RichText

    return RichTable, RichText, table_box(console)


def _isatty() -> bool:
    try:
        return sys.stdout.isatty()
    except (AttributeError, ValueError):
        return False


def _forced_terminal() -> bool:
    """rich treats the output as a terminal when FORCE_COLOR or TTY_COMPATIBLE says so."""
    return bool(
        os.environ.get("FORCE_COLOR") or os.environ.get("TTY_COMPATIBLE") or os.environ.get("TTY_INTERACTIVE")
    )
