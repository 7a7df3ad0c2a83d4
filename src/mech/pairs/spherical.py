"""Spherical pair (ball joint): accepted for classification and counting; the planar solvers refuse it."""

from __future__ import annotations

from mech.pairs.base import PairKind


class Spherical(PairKind):
    name = "spherical"
    motion = "spherical"
    planar = False
    role = "spatial"
    icentre = ("point", "ball joint {joint} (its centre, in the plane)")
