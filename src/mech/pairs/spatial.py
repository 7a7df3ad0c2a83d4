"""Screw and spherical pairs: accepted for classification and counting; the planar solvers refuse them."""

from __future__ import annotations

from mech.model import JointType
from mech.pairs.base import Fields, PairKind, Reader
from mech.pairs.specs import BareSpec


def _read(r: Reader, fields: Fields, what: str, links: tuple[str, ...]) -> BareSpec:
    return BareSpec()


SCREW = PairKind(
    type=JointType.SCREW,
    keys={},
    read=_read,
    spec=BareSpec(),
    higher=False,
    motion="screw",
    line_contact=False,
    planar=False,
    role="spatial",
)

SPHERICAL = PairKind(
    type=JointType.SPHERICAL,
    keys={},
    read=_read,
    spec=BareSpec(),
    higher=False,
    motion="spherical",
    line_contact=False,
    planar=False,
    role="spatial",
)
