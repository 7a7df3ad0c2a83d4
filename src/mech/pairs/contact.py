"""Cam and contact pairs (h = 1): a common normal at the instant, or profiles that move.

Without profiles, ``at`` (the contact point) and ``normal`` (the common
normal's angle) describe the instant drawn.  With ``profiles`` (one curve per
link, :mod:`mech.pairs.specs`) the pair moves; a cam may give its follower's
``program`` instead, read by :func:`mech.cam.read_program`.
"""

from __future__ import annotations

from typing import Any

from mech.cam.program import program_schema
from mech.model import JointType
from mech.pairs.base import NUMBER, PROFILES, Fields, PairKind, Reader, read_profiles
from mech.pairs.specs import ContactSpec
from mech.units import Dimension

PROGRAM: dict[str, Any] = {
    "description": "The follower's programme, from which mech generates the cam profile (DESIGN § 1.1).",
    **program_schema(NUMBER),
}


def _read_program(r: Reader, node: Any, what: str) -> object:
    try:
        from mech.cam import read_program
    except ImportError:
        raise r.problem(node, f"{what}: cam programmes are not available in this version of mech") from None
    return read_program(r, node, what)


def _read(r: Reader, fields: Fields, what: str, links: tuple[str, ...]) -> ContactSpec:
    normal = r.optional(fields, "normal", lambda n: r.number(n, "the common normal", Dimension.ANGLE))
    profiles = r.optional(fields, "profiles", lambda n: read_profiles(r, n, what, links)) or ()
    program = (
        r.optional(fields, "program", lambda n: _read_program(r, n, what)) if "program" in fields else None
    )
    if "program" in fields and "profiles" in fields:
        r.problem(
            fields["program"][0],
            f"{what} gives both `program` and `profiles`",
            "the programme generates the cam's profile: give one",
        )
    return ContactSpec(normal=normal, profiles=profiles, program=program)


CAM = PairKind(
    type=JointType.CAM,
    keys={"normal": NUMBER, "profiles": PROFILES, "program": PROGRAM},
    read=_read,
    spec=ContactSpec(),
    higher=True,
    motion="cam (sliding and rolling)",
    line_contact=True,
    closure="force",
)

CONTACT = PairKind(
    type=JointType.CONTACT,
    keys={"normal": NUMBER, "profiles": PROFILES},
    read=_read,
    spec=ContactSpec(),
    higher=True,
    motion="sliding and rolling (point contact)",
    line_contact=True,
    closure="force",
)
