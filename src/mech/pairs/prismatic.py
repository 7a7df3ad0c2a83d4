"""Prismatic (sliding pair): the slider keeps its angle to the guide (a lower pair, j)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from mech.pairs.path import PathPair

if TYPE_CHECKING:
    from mech.model import Joint
    from mech.pairs.glyph import GlyphView, Shape


class Prismatic(PathPair):
    """A block on a straight guide: a pair, not a point (its ``point`` is the slider's)."""

    name = "prismatic"
    motion = "sliding"
    located = "none"
    keeps_angle = True
    dyad = "path of an rrp or rpr dyad; the slider's angle by pose_angle"
    icentre = ("infinity", "slider {joint}: at infinity, perpendicular to the path")

    def glyph(self, view: GlyphView, j: Joint) -> list[Shape]:
        """A block on its path; on the frame, the line of stroke and the hatched guide."""
        from mech.pairs.glyph import slider

        return slider(view, j)
