"""Revolute (turning pair, pin): ``radius`` is the pin's radius, for rubbing velocity."""

from __future__ import annotations

from mech.model import JointType
from mech.pairs.base import NUMBER, Fields, PairKind, Reader
from mech.pairs.specs import PinSpec
from mech.units import Dimension


def _read(r: Reader, fields: Fields, what: str, links: tuple[str, ...]) -> PinSpec:
    radius = r.optional(
        fields, "radius", lambda n: r.number(n, "the pin radius", Dimension.LENGTH, positive=True)
    )
    return PinSpec(radius=radius)


REVOLUTE = PairKind(
    type=JointType.REVOLUTE,
    keys={"radius": NUMBER},
    read=_read,
    spec=PinSpec(),
    higher=False,
    motion="turning",
    line_contact=False,
    max_links=None,
    role="pin",  # a ternary joint is one pin through three links
)
