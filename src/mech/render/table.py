"""A report's tables and styled text, built once, printed by whichever console stands on stdout.

Renderers build :class:`Table` and :class:`Text` from here and print them on the console
:func:`mech.render.console.stdout` gives.  On a terminal that is rich's console, which
prints them as rich's own (``__rich__``: :meth:`Table.to_rich`, :meth:`Text.to_rich`);
piped or under ``NO_COLOR`` it is :class:`mech.render.plain.PlainConsole`, which lays out
the simple ones itself (:meth:`Table.lines`, rich's bytes without importing rich) and hands
the rest to rich.  Either way the table was built once, by one renderer.

Nothing here imports rich until a table is turned into rich's.
"""

from __future__ import annotations

import re
from typing import Any

__all__ = ["ROUNDED", "SIMPLE", "Table", "Text", "simple"]

# rich.box.SIMPLE and rich.box.ROUNDED, named without importing rich
SIMPLE = "SIMPLE"
ROUNDED = "ROUNDED"
# characters rich counts one cell wide and prints unchanged; anything else goes to rich
_WIDE_OK = frozenset("—–−…·²³°√≈≤≥×÷→←↔‖∠Σπ′″")
EMOJI = re.compile(r":\S*?:")  # rich may read ":name:" in a str as an emoji code


def simple(text: str) -> bool:
    """True when rich would print ``text`` as it is, one cell per character."""
    if text.isascii():
        return text.isprintable()
    for c in text:
        o = ord(c)
        if not (0x20 <= o < 0x7F or (0xA1 <= o < 0x300 and o != 0xAD) or 0x370 <= o < 0x400 or c in _WIDE_OK):
            return False
    return True


def _rich_cell(cell: Any) -> Any:
    return cell.to_rich() if isinstance(cell, Text) else cell


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

        # as rich's own ``Text(a, style) + Text(b)`` builds it: the first part's style is the base
        # style of the whole text (so "name — velocities" is bold throughout), the rest appended
        (first, style), *rest = self.parts
        out = RichText(first, style=style or "")
        for text, part_style in rest:
            out.append(RichText(text, style=part_style or ""))
        return out

    __rich__ = to_rich  # rich's console prints it as its own


class Table:
    """The part of ``rich.table.Table`` mech's renderers use: title, columns, rows, sections.

    ``options`` are rich's (``show_edge``, ``pad_edge`` …), handed to it unchanged; cells are
    strings or :class:`Text`.
    """

    def __init__(
        self, title: str | None = None, box: Any = None, title_justify: str = "center", **options: Any
    ) -> None:
        self.title, self.box, self.title_justify, self.options = title, box, title_justify, options
        self.columns: list[tuple[str, dict[str, Any]]] = []
        self.rows: list[tuple[Any, ...] | None] = []  # None: a section's rule

    def add_column(self, header: str = "", **options: Any) -> None:
        self.columns.append((header, options))

    def add_row(self, *cells: Any) -> None:
        self.rows.append(cells)

    def add_section(self) -> None:
        self.rows.append(None)

    def to_rich(self) -> Any:
        from rich import box
        from rich.table import Table as RichTable

        frame = {SIMPLE: box.SIMPLE, ROUNDED: box.ROUNDED}.get(self.box, self.box)
        table = RichTable(title=self.title, box=frame, title_justify=self.title_justify, **self.options)  # type: ignore[arg-type]
        for header, options in self.columns:
            table.add_column(header, **options)
        for row in self.rows:
            if row is None:
                table.add_section()
            else:
                table.add_row(*(_rich_cell(c) for c in row))
        return table

    __rich__ = to_rich  # rich's console prints it as its own

    def lines(self, width: int) -> list[str] | None:
        """The table as rich prints it in a SIMPLE box, or None where rich would do more."""
        if (
            self.box != SIMPLE
            or self.options
            or any(r is None or len(r) != len(self.columns) for r in self.rows)
        ):
            return None
        if any(
            set(o) - {"justify", "overflow"} or o.get("justify", "left") not in ("left", "right")
            for _, o in self.columns
        ):
            return None
        rows = [r for r in self.rows if r is not None]
        texts = [self.title or "", *(h for h, _ in self.columns), *(c for r in rows for c in r)]
        if not all(isinstance(t, str) and simple(t) and not EMOJI.search(t) for t in texts):
            return None
        if any(t != t.strip() for t in texts[1:] if t):
            return None
        widths = [max([len(h), *(len(r[i]) for r in rows)]) for i, (h, _) in enumerate(self.columns)]
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
        out += [row(r) for r in rows]
        out.append(" " * total)
        return out
