"""Screw pair: accepted for classification and counting; the planar solvers refuse it."""

from __future__ import annotations

from mech.pairs.base import PairKind


class Screw(PairKind):
    name = "screw"
    motion = "screw"
    planar = False
    role = "spatial"
    icentre = ("infinity", "screw {joint}: at infinity, perpendicular to its axis")
