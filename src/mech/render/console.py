"""The one place that decides colour and width (rich honours NO_COLOR and non-tty).

Piped output is written by :class:`~mech.render.plain.PlainConsole`, which
prints rich's bytes without importing rich where it can; on a terminal rich's own
console prints.  Renderers build every table once, with :mod:`mech.render.table`'s
``Table`` and ``Text``, and print it on whichever :func:`stdout` gives.
"""

from __future__ import annotations

import os
import sys
from functools import lru_cache
from typing import Any, Protocol


class ReportConsole(Protocol):
    """What mech's renderers use of a console: rich's ``Console`` is one, and so is
    :class:`~mech.render.plain.PlainConsole`.

    A renderer prints tables, ``Text`` and strings with :meth:`print` and asks
    :func:`table_box` (which reads the three attributes) what
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
    from mech.render.richconsole import rich_console_class

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


def is_plain(console: ReportConsole) -> bool:
    """True when the console writes plain text (not a terminal, or NO_COLOR set)."""
    return not console.is_terminal or console.no_color or console.color_system is None


def table_box(console: ReportConsole) -> str:
    """Rounded boxes on a terminal, simple ruled text otherwise (:mod:`mech.render.table`'s names)."""
    from mech.render.table import ROUNDED, SIMPLE

    return SIMPLE if is_plain(console) else ROUNDED


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
