"""Pure rolling (no slip; counted as a lower pair in j): the contact point has one velocity on both links.

``radii: [r1, r2]`` (``null`` for a straight line) is shorthand for circles about
each link's pivot; ``profiles`` names the curves outright.  With either, the
pair moves; with neither, ``at`` describes the instant.
"""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType
from typing import TYPE_CHECKING

from mech.fields import PROFILES, RADII, Fields, Reader, read_profiles, read_radii
from mech.pairs.base import PairKind, contact_forces
from mech.specs import RollingSpec

Vec = tuple[float, float]

if TYPE_CHECKING:
    from mech.errors import Problem
    from mech.model import Joint, Mechanism
    from mech.pairs.base import InstantView, PairForce, Wrench
    from mech.pairs.glyph import GlyphView, Shape
    from mech.pairs.rows import RowBuilder
    from mech.specs import Profile


class Rolling(PairKind):
    """Two curves rolling without slip: the contact point is the I-centre."""

    name = "rolling"
    keys = MappingProxyType({"radii": RADII, "profiles": PROFILES})
    spec = RollingSpec()
    motion = "rolling"
    line_contact = True
    closure = "force"
    rolls = True
    icentre = ("point", "rolling {joint}: the point of contact")

    def read(self, r: Reader, fields: Fields, what: str, links: tuple[str, ...]) -> RollingSpec:
        radii = r.optional(fields, "radii", lambda n: read_radii(r, n, what, nulls=True))
        profiles = r.optional(fields, "profiles", lambda n: read_profiles(r, n, what, links)) or ()
        if "radii" in fields and "profiles" in fields:
            r.problem(
                fields["radii"][0],
                f"{what} gives both `radii` and `profiles`",
                "radii are shorthand for circle profiles: give one",
            )
        return RollingSpec(radii=radii, profiles=profiles)

    def glyph(self, view: GlyphView, j: Joint) -> list[Shape]:
        """The profiles as they are now (pitch circles about the pivots where no profile is drawn), the common normal and tangent, the contact."""
        from mech.pairs.glyph import contact

        return contact(view, j, self.drawn_profiles(view.mech, j, view.positions.get(j.name)), pitch=True)

    def contact_problem(self, j: Joint) -> Problem | None:
        """Radii put the contact between the circles: no ``at`` needed."""
        return None if j.radii is not None else super().contact_problem(j)

    def drawn_profiles(self, mech: Mechanism, j: Joint, contact: Vec | None) -> list[tuple[str, Profile]]:
        """The profiles, or ``radii``: circles about each link's pin, a straight line through the contact."""
        from mech.pairs.table import kind_of
        from mech.specs import Circle, Line, Ref

        if j.profiles or j.radii is None:
            return list(j.profiles)
        out: list[tuple[str, Profile]] = []
        for link, r in zip(j.links, j.radii, strict=True):
            pins = [k.name for k in mech.joints_of(link) if kind_of(k).role == "pin"]
            if r is not None and len(pins) == 1:
                out.append((link, Circle(Ref(name=pins[0]), r)))
            elif r is None and contact is not None:
                out.append((link, Line(Ref(xy=contact), 0.0)))
        return out

    def rows(self, b: RowBuilder, j: Joint) -> None:
        """Profiles (or radii) that roll without slip, else the contact point of the instant."""
        from mech.pairs.profiles import instant_rolling, moving_contact

        if not moving_contact(b, j, rolls=True, radii=j.radii):
            instant_rolling(b, j)

    def inspect(self, seen: InstantView, j: Joint) -> None:
        """Pure rolling: the point of contact."""
        at = seen.at(j)
        at = j.place.at if at is None else at
        if at is not None:
            seen.contact(j.name, (j.links[0], j.links[1]), at)

    def forces(
        self, j: Joint, wrenches: Mapping[str, Wrench], at: Vec | None, direction: Vec | None
    ) -> list[PairForce]:
        """The force on the second link at the contact, and its component along the common normal."""
        return contact_forces(j, wrenches, at, direction)
