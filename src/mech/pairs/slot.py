"""Slot (pin in a straight slot): the pin runs along the slot and may turn in it (a higher pair, h)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from mech.pairs.path import PathPair

if TYPE_CHECKING:
    from mech.model import Joint
    from mech.pairs.glyph import GlyphView, Shape


class Slot(PathPair):
    """The pin's centre: a point of the pin link, moving along the slotted link."""

    name = "slot"
    higher = True
    motion = "sliding and turning (pin in slot)"
    line_contact = True
    located = "first"
    icentre = ("line", "pin in slot {joint}: on the normal to the slot through the pin")

    def glyph(self, view: GlyphView, j: Joint) -> list[Shape]:
        """Two lines along the slot round the pin, and the pin."""
        from mech.pairs.glyph import slot

        return slot(view, j)
