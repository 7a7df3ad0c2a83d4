"""What the pairs that touch by profiles share (cam, contact, gear): their fields and their contact.

Below those kinds' modules, so none of them imports another kind's (issue 20:
contact and gear imported the cam kind's module for these).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from mech.cam.read import read_program
from mech.fields import Fields, Reader, read_profiles
from mech.specs import ContactSpec
from mech.units import Dimension

if TYPE_CHECKING:
    from mech.model import Joint
    from mech.pairs.base import InstantView

__all__ = ["read_contact", "see_contact"]

Vec = tuple[float, float]


def read_contact(
    r: Reader, fields: Fields, what: str, links: tuple[str, ...], *, program: bool = False
) -> ContactSpec:
    """``normal`` and ``profiles`` (and a cam's ``program``): what a cam or a contact pair reads."""
    normal = r.optional(fields, "normal", lambda n: r.number(n, "the common normal", Dimension.ANGLE))
    profiles = r.optional(fields, "profiles", lambda n: read_profiles(r, n, what, links)) or ()
    prog = r.optional(fields, "program", lambda n: read_program(r, n, what)) if program else None
    if program and "program" in fields and "profiles" in fields:
        r.problem(
            fields["program"][0],
            f"{what} gives both `program` and `profiles`",
            "the programme generates the cam's profile: give one",
        )
    return ContactSpec(normal=normal, profiles=profiles, program=prog)


def see_contact(seen: InstantView, j: Joint, line_of_action: Vec | None = None) -> None:
    """A cam, gear or point contact: its I-centre is somewhere on the common normal (Kennedy finishes it).

    The normal is the solved common tangent turned a quarter, else the file's ``normal``,
    else ``line_of_action`` (a gear's); with none, the contact is taken as rolling (a gear
    whose pitch point is where its pitch circles roll).
    """
    at = seen.at(j)
    at = j.place.at if at is None else at
    if at is None:
        return
    a, b = j.links[0], j.links[1]
    tangent = seen.direction(j)
    normal: Vec | None = line_of_action
    if tangent is not None:
        normal = (tangent[1], -tangent[0])  # the common tangent turned −90°
    elif j.normal is not None:
        normal = (math.cos(j.normal), math.sin(j.normal))
    seen.contact(j.name, (a, b), at, normal)
