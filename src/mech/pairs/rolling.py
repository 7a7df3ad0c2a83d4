"""Pure rolling (no slip; counted as a lower pair in j): the contact point has one velocity on both links.

``radii: [r1, r2]`` (``null`` for a straight line) is shorthand for circles about
each link's pivot; ``profiles`` names the curves outright.  With either, the
pair moves; with neither, ``at`` describes the instant.
"""

from __future__ import annotations

from mech.model import JointType
from mech.pairs.base import PROFILES, RADII, Fields, PairKind, Reader, read_profiles, read_radii
from mech.pairs.specs import RollingSpec


def _read(r: Reader, fields: Fields, what: str, links: tuple[str, ...]) -> RollingSpec:
    radii = r.optional(fields, "radii", lambda n: read_radii(r, n, what, nulls=True))
    profiles = r.optional(fields, "profiles", lambda n: read_profiles(r, n, what, links)) or ()
    if "radii" in fields and "profiles" in fields:
        r.problem(
            fields["radii"][0],
            f"{what} gives both `radii` and `profiles`",
            "radii are shorthand for circle profiles: give one",
        )
    return RollingSpec(radii=radii, profiles=profiles)


ROLLING = PairKind(
    type=JointType.ROLLING,
    keys={"radii": RADII, "profiles": PROFILES},
    read=_read,
    spec=RollingSpec(),
    higher=False,
    motion="rolling",
    line_contact=True,
    closure="force",
)
