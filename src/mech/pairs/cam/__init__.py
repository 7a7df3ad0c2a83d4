"""Cam pair (h = 1): a common normal at the instant, profiles that move, or the follower's programme.

Without profiles, ``at`` (the contact point) and ``normal`` (the common
normal's angle) describe the instant drawn.  With ``profiles`` (one curve per
link, :mod:`mech.specs`) the pair moves; a cam may give its follower's
``program`` instead (:mod:`mech.cam`), and then the follower moves by its law.
"""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

from mech.cam.program import program_schema
from mech.fields import NUMBER, PROFILES, Fields, Reader
from mech.pairs.base import PairKind, contact_forces
from mech.pairs.higher import read_contact, see_contact
from mech.specs import ContactSpec

if TYPE_CHECKING:
    from mech.model import Joint, Mechanism
    from mech.pairs.base import InstantView, PairForce, Wrench
    from mech.pairs.glyph import GlyphView, Shape
    from mech.pairs.rows import RowBuilder
    from mech.specs import Profile

Vec = tuple[float, float]

__all__ = ["Cam"]

PROGRAM: dict[str, Any] = {
    "description": "The follower's programme, from which mech generates the cam profile (DESIGN § 1.1).",
    **program_schema(NUMBER),
}


def _programme(j: Joint) -> bool:
    return getattr(j.spec, "program", None) is not None


class Cam(PairKind):
    """A cam and its follower, touching at a point (line contact), kept together by a force."""

    name = "cam"
    keys = MappingProxyType({"normal": NUMBER, "profiles": PROFILES, "program": PROGRAM})
    spec = ContactSpec()
    higher = True
    motion = "cam (sliding and rolling)"
    line_contact = True
    closure = "force"
    icentre = ("line", "cam {joint}: on the common normal at the contact")

    def read(self, r: Reader, fields: Fields, what: str, links: tuple[str, ...]) -> ContactSpec:
        return read_contact(r, fields, what, links, program=True)

    def glyph(self, view: GlyphView, j: Joint) -> list[Shape]:
        """The profiles as they are now (what the contact belongs to where no profile is drawn, a follower's stem on its guide), the common normal and tangent, the contact."""
        from mech.pairs.glyph import contact

        return contact(view, j, self.drawn_profiles(view.mech, j, view.positions.get(j.name)), pitch=False)

    def fixed_in(self, j: Joint) -> tuple[str, ...]:
        """A programme's joint stands for the follower's own point (DESIGN § 1.2); a contact moves."""
        return j.links[1:2] if _programme(j) else ()

    def located_on(self, j: Joint) -> tuple[str, ...]:
        """A programme's joint is a point of the follower (its arm's length may end there)."""
        return j.links[1:2] if _programme(j) else super().located_on(j)

    def drawn_at(self, mech: Mechanism, j: Joint) -> Vec | None:
        """The follower's point where the programme puts it at the drive's angle."""
        if not _programme(j):
            return None
        from mech.cam.profile import evaluate
        from mech.pairs.cam.setup import cam_setup

        setup = cam_setup(mech, j.name)
        x, y = evaluate(setup.layout, [setup.angle]).point[0]
        return (float(x) + setup.centre[0], float(y) + setup.centre[1])

    def rows(self, b: RowBuilder, j: Joint) -> None:
        """The follower moved by its programme's law, profiles that touch, or the common normal of the instant."""
        if _programme(j):
            from mech.pairs.cam.law import programme_rows

            programme_rows(b, j)
            return
        from mech.pairs.profiles import instant_normal, moving_contact

        if not moving_contact(b, j):
            instant_normal(b, j, j.normal)

    def inspect(self, seen: InstantView, j: Joint) -> None:
        """On the common normal at the contact."""
        see_contact(seen, j)

    def drawn_profiles(self, mech: Mechanism, j: Joint, contact: Vec | None) -> list[tuple[str, Profile]]:
        """The profiles, or those a programme generates (none when the programme cannot be placed:
        the analysis reports why)."""
        if getattr(j.spec, "program", None) is None:
            return list(j.profiles)
        from mech.errors import MechError
        from mech.pairs.cam.setup import program_profiles

        try:
            return list(program_profiles(mech, j).items())
        except MechError:
            return []

    def pushes(self, j: Joint) -> str | None:
        return "stacked" if _programme(j) else None

    def push(self, j: Joint, sys_: Any, q: Any) -> tuple[Any, Any] | None:
        """A programme's contact and common normal at ``q``, as its rows locate them."""
        if not _programme(j):
            return None
        return sys_.contact_points[j.name](q), sys_.normals[j.name](q)

    def force_note(
        self, j: Joint, mech: Mechanism, positions: Mapping[str, Vec], force: PairForce
    ) -> str | None:
        """A cam only pushes: a contact force that pulls the follower toward the cam's pivot means
        the follower leaves the cam there, unless a spring or its weight keeps it on (judged on a
        disc cam, whose profile every ray from its pivot crosses once: the outward normal at the
        contact then points away from the pivot)."""
        from mech.pairs.table import kind_of

        cam = j.links[0]
        pins = [k.name for k in mech.joints_of(cam) if kind_of(k).role == "pin" and k.name in positions]
        if force.at is None or len(pins) != 1 or force.on != j.links[1]:
            return None
        o = positions[pins[0]]
        away = (force.at[0] - o[0]) * force.force[0] + (force.at[1] - o[1]) * force.force[1]
        if away >= 0.0:
            return None
        return (
            f"at {j.name}, {cam} would have to pull {force.on} toward it ({force.magnitude:.6g} N): a cam "
            f"only pushes, so {force.on} leaves {cam} here unless a spring or its weight holds it on "
            "(add that force as a load)"
        )

    def forces(
        self, j: Joint, wrenches: Mapping[str, Wrench], at: Vec | None, direction: Vec | None
    ) -> list[PairForce]:
        """The force on the second link at the contact, and its component along the common normal."""
        return contact_forces(j, wrenches, at, direction)
