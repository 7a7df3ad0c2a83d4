"""Contact pair (h = 1): two profiles touching at a point, sliding and rolling on each other."""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType
from typing import TYPE_CHECKING

from mech.fields import NUMBER, PROFILES, Fields, Reader
from mech.pairs.base import PairKind, contact_forces
from mech.pairs.higher import read_contact, see_contact
from mech.specs import ContactSpec

if TYPE_CHECKING:
    from mech.model import Joint
    from mech.pairs.base import InstantView, PairForce, Wrench
    from mech.pairs.glyph import GlyphView, Shape
    from mech.pairs.rows import RowBuilder


Vec = tuple[float, float]


class Contact(PairKind):
    """A point contact between two curves, described at the instant or by profiles that move."""

    name = "contact"
    keys = MappingProxyType({"normal": NUMBER, "profiles": PROFILES})
    spec = ContactSpec()
    higher = True
    motion = "sliding and rolling (point contact)"
    line_contact = True
    closure = "force"
    icentre = ("line", "contact {joint}: on the common normal at the contact")

    def read(self, r: Reader, fields: Fields, what: str, links: tuple[str, ...]) -> ContactSpec:
        return read_contact(r, fields, what, links)

    def glyph(self, view: GlyphView, j: Joint) -> list[Shape]:
        """The profiles as they are now (what the contact belongs to where no profile is drawn, a follower's stem on its guide), the common normal and tangent, the contact."""
        from mech.pairs.glyph import contact

        return contact(view, j, self.drawn_profiles(view.mech, j, view.positions.get(j.name)), pitch=False)

    def rows(self, b: RowBuilder, j: Joint) -> None:
        """Profiles that touch and slide, else the common normal of the instant."""
        from mech.pairs.profiles import instant_normal, moving_contact

        if not moving_contact(b, j):
            instant_normal(b, j, j.normal)

    def inspect(self, seen: InstantView, j: Joint) -> None:
        """On the common normal at the contact."""
        see_contact(seen, j)

    def forces(
        self, j: Joint, wrenches: Mapping[str, Wrench], at: Vec | None, direction: Vec | None
    ) -> list[PairForce]:
        """The force on the second link at the contact, and its component along the common normal."""
        return contact_forces(j, wrenches, at, direction)
