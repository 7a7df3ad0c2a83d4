"""Slot (pin in a straight slot): the pin runs along the slot and may turn in it (a higher pair, h)."""

from __future__ import annotations

from mech.pairs.path import PathPair


class Slot(PathPair):
    """The pin's centre: a point of the pin link, moving along the slotted link."""

    name = "slot"
    higher = True
    motion = "sliding and turning (pin in slot)"
    line_contact = True
    located = "first"
    icentre = ("line", "pin in slot {joint}: on the normal to the slot through the pin")
    glyph = "slot"
