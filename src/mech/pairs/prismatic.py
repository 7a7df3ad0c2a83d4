"""Prismatic (sliding pair): the slider keeps its angle to the guide (a lower pair, j)."""

from __future__ import annotations

from mech.pairs.path import PathPair


class Prismatic(PathPair):
    """A block on a straight guide: a pair, not a point (its ``point`` is the slider's)."""

    name = "prismatic"
    motion = "sliding"
    located = "none"
    keeps_angle = True
    dyad = "path of an rrp or rpr dyad; the slider's angle by pose_angle"
    icentre = ("infinity", "slider {joint}: at infinity, perpendicular to the path")
    glyph = "slider"
