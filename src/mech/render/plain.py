"""Plain output without rich: what rich prints for a piped table, written directly.

Piped output (not a terminal) is plain text 120 columns wide (``$COLUMNS``),
and rich costs as much to import and lay out as ``mech velocity`` spends on
everything but numpy.  :class:`PlainConsole` stands where the rich console
stood and writes the same bytes rich writes for the simple cases — a
:class:`Table` of plain strings in a ``box.SIMPLE`` frame that fits the
width, a line of text that fits it — and hands anything else to a real rich
console made on first need (with :class:`Table` and :class:`Text` rebuilt as
rich's).  So it is never wrong, only sometimes not faster:
tests/test_plain.py prints every example's tables both ways and compares
them byte for byte.  Renderers get :class:`Table` and :class:`Text` from
:func:`mech.render.console.kit` so that they build the kind this console
prints without rich.
"""

from __future__ import annotations

import re
import sys
from typing import Any

from mech._text import visible

__all__ = ["SIMPLE", "PlainConsole", "Table", "Text"]

# characters rich counts one cell wide and prints unchanged; anything else goes to rich
_WIDE_OK = frozenset("—–−…·²³°√≈≤≥×÷→←↔‖∠Σπ′″")
SIMPLE = "SIMPLE"  # rich.box.SIMPLE, named without importing rich
_EMOJI = re.compile(r":\S*?:")  # rich may read ":name:" in a str as an emoji code


def _simple(text: str) -> bool:
    """True when rich would print ``text`` as it is, one cell per character."""
    if text.isascii():
        return text.isprintable()
    for c in text:
        o = ord(c)
        if not (0x20 <= o < 0x7F or (0xA1 <= o < 0x300 and o != 0xAD) or 0x370 <= o < 0x400 or c in _WIDE_OK):
            return False
    return True


class Text:
    """A run of text (styles are dropped: plain output shows none)."""

    def __init__(self, text: str = "", style: str | None = None) -> None:
        self.parts: list[tuple[str, str | None]] = [(text, style)]

    @property
    def plain(self) -> str:
        return "".join(t for t, _ in self.parts)

    def __add__(self, other: Text | str) -> Text:
        out = Text()
        out.parts = [*self.parts, *(other.parts if isinstance(other, Text) else [(other, None)])]
        return out

    def to_rich(self) -> Any:
        from rich.text import Text as RichText

        out = RichText()
        for text, style in self.parts:
            out.append(RichText(text, style=style or ""))
        return out


class Table:
    """The part of ``rich.table.Table`` mech's renderers use: title, columns, rows of strings."""

    def __init__(self, title: str | None = None, box: Any = None, title_justify: str = "center") -> None:
        self.title, self.box, self.title_justify = title, box, title_justify
        self.columns: list[tuple[str, dict[str, Any]]] = []
        self.rows: list[tuple[str, ...]] = []

    def add_column(self, header: str = "", **options: Any) -> None:
        self.columns.append((header, options))

    def add_row(self, *cells: str) -> None:
        self.rows.append(cells)

    def to_rich(self) -> Any:
        from rich import box
        from rich.table import Table as RichTable

        frame = box.SIMPLE if self.box == SIMPLE else self.box
        table = RichTable(title=self.title, box=frame, title_justify=self.title_justify)  # type: ignore[arg-type]
        for header, options in self.columns:
            table.add_column(header, **options)
        for row in self.rows:
            table.add_row(*row)
        return table

    def lines(self, width: int) -> list[str] | None:
        """The table as rich prints it in a SIMPLE box, or None where rich would do more."""
        if self.box != SIMPLE or any(len(r) != len(self.columns) for r in self.rows):
            return None
        if any(
            set(o) - {"justify", "overflow"} or o.get("justify", "left") not in ("left", "right")
            for _, o in self.columns
        ):
            return None
        texts = [self.title or "", *(h for h, _ in self.columns), *(c for r in self.rows for c in r)]
        if not all(isinstance(t, str) and _simple(t) and not _EMOJI.search(t) for t in texts):
            return None
        if any(t != t.strip() for t in texts[1:] if t):
            return None
        widths = [max([len(h), *(len(r[i]) for r in self.rows)]) for i, (h, _) in enumerate(self.columns)]
        total = sum(widths) + 3 * len(widths) + 1
        if total > width or len(self.title or "") > total:
            return None
        out = []
        if self.title is not None:
            if self.title_justify == "left":
                out.append(self.title.ljust(total))
            elif self.title_justify == "center":
                left = (total - len(self.title)) // 2
                out.append(" " * left + self.title + " " * (total - left - len(self.title)))
            else:
                return None
        out.append(" " * total)

        def row(cells: tuple[str, ...] | list[str]) -> str:
            padded = (
                c.rjust(w) if o.get("justify") == "right" else c.ljust(w)
                for c, w, (_, o) in zip(cells, widths, self.columns, strict=True)
            )
            return " " + " ".join(f" {c} " for c in padded) + " "

        out.append(row([h for h, _ in self.columns]))
        out.append(" " + "─".join("─" * (w + 2) for w in widths) + " ")
        out += [row(r) for r in self.rows]
        out.append(" " * total)
        return out


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
            from mech.render.console import rich_console_class

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
            or not _simple(text)
            or (not soft_wrap and len(text) > self.width)
            or (isinstance(obj, str) and _EMOJI.search(text))
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
