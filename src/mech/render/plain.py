"""Plain output without rich: what rich prints for a piped table, written directly.

Piped output (not a terminal, or ``NO_COLOR`` set) is plain text 120 columns wide
(``$COLUMNS``), and rich costs as much to import and lay out as ``mech velocity``
spends on everything but numpy.  :class:`PlainConsole` stands where the rich console
stood and prints the same bytes rich prints for the simple cases — a
:class:`~mech.render.table.Table` of plain strings in a ``box.SIMPLE`` frame that fits
the width (:meth:`~mech.render.table.Table.lines`), a line of text that fits it — and
hands anything else to a real rich console made on first need.  So it is never wrong,
only sometimes not faster: tests/test_plain.py prints every example's tables both ways
and compares them byte for byte.  The tables themselves are built once, by the
renderers, from :mod:`mech.render.table`.
"""

from __future__ import annotations

import sys
from typing import Any

from mech._text import visible
from mech.render.table import EMOJI, Table, Text, simple

__all__ = ["PlainConsole"]


class PlainConsole:
    """A stand-in for rich's console on a pipe: plain tables and lines, rich for the rest."""

    is_terminal = False
    no_color = False
    color_system = None
    is_plain = True

    def __init__(self, width: int) -> None:
        self.width = width
        self._rich: Any = None

    def rich(self) -> Any:
        """The rich console this one stands for (made once, on first need)."""
        if self._rich is None:
            from mech.render.richconsole import rich_console_class

            console_class = rich_console_class()  # EPIPE is the pipe's status, not rich's exit 1
            self._rich = console_class(highlight=False, markup=False, width=self.width, color_system=None)
        return self._rich

    def __getattr__(self, name: str) -> Any:
        return getattr(self.rich(), name)

    def print(self, *objects: Any, soft_wrap: bool = False, **options: Any) -> None:
        """Print as rich would: directly when the text is plain, through rich otherwise."""
        if set(options) - {"highlight"} or len(objects) > 1:
            self._forward(objects, soft_wrap, options)
            return
        if not objects:
            self._write("")
            return
        obj = objects[0]
        if isinstance(obj, Table):
            lines = obj.lines(self.width)
            if lines is None:
                self._forward(objects, soft_wrap, options)
                return
            self._write("\n".join(lines))
            return
        text = obj.plain if isinstance(obj, Text) else obj if isinstance(obj, str) else None
        if (
            text is None
            or not simple(text)
            or (not soft_wrap and len(text) > self.width)
            or (isinstance(obj, str) and EMOJI.search(text))
        ):
            self._forward(objects, soft_wrap, options)
            return
        self._write(text)

    def _forward(self, objects: tuple[Any, ...], soft_wrap: bool, options: dict[str, Any]) -> None:
        converted = [o.to_rich() if isinstance(o, (Table, Text)) else o for o in objects]
        self.rich().print(*converted, soft_wrap=soft_wrap, **options)

    def _write(self, text: str) -> None:
        # users' text (a title, a path) with its control and direction characters shown as
        # escapes, as the rich console does for what is forwarded to it
        sys.stdout.write(visible(text) + "\n")
