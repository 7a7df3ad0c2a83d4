"""Revolute (turning pair, pin): ``radius`` is the pin's radius, for rubbing velocity."""

from __future__ import annotations

from types import MappingProxyType
from typing import TYPE_CHECKING

from mech.fields import NUMBER, Fields, Reader
from mech.pairs.base import PairKind
from mech.specs import PinSpec
from mech.units import Dimension

if TYPE_CHECKING:
    from mech.model import Joint
    from mech.pairs.base import InstantView
    from mech.pairs.glyph import GlyphView, Shape
    from mech.pairs.rows import RowBuilder


class Revolute(PairKind):
    """A pin: a point fixed in every link it joins (a ternary joint is one pin through three links)."""

    name = "revolute"
    keys = MappingProxyType({"radius": NUMBER})
    spec = PinSpec()
    motion = "turning"
    max_links = None
    role = "pin"
    dyad = "pin of an rrr or rrp dyad, or a crank's pivot"
    icentre = ("point", "pin {joint}")

    def read(self, r: Reader, fields: Fields, what: str, links: tuple[str, ...]) -> PinSpec:
        radius = r.optional(
            fields, "radius", lambda n: r.number(n, "the pin radius", Dimension.LENGTH, positive=True)
        )
        return PinSpec(radius=radius)

    def glyph(self, view: GlyphView, j: Joint) -> list[Shape]:
        """An open circle; at a ground pivot a triangle on a hatched base under it."""
        from mech.pairs.glyph import pin

        return pin(view, j.name, ground=view.mech.ground in j.links)

    def rows(self, b: RowBuilder, j: Joint) -> None:
        """The pin's point of the first link on the same point of every other link it joins."""
        from mech.pairs.rows import Coincide

        if j.name not in b.pos:
            return
        xy = b.scn(j.name)
        first = j.links[0]
        for other in j.links[1:]:
            b.coincide.append(
                Coincide(b.index[first], b.to_local(first, xy), b.index[other], b.to_local(other, xy), j.name)
            )

    def inspect(self, seen: InstantView, j: Joint) -> None:
        """A pin is the I-centre of the links it joins (a ternary pin: of each pair)."""
        at = seen.at(j)
        if at is not None:
            seen.pin(j.name, tuple(j.links), at)
