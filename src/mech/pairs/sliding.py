"""Prismatic (sliding pair) and slot (pin in a straight slot): a point of the first link on a line of the second.

``path`` is the line, fixed in the guide (the second link); ``point`` names the
slider's point that runs on it.  A prismatic pair also keeps the two links'
relative angle (a lower pair, j); a slot lets the pin turn (a higher pair, h).
"""

from __future__ import annotations

from mech.model import JointType
from mech.pairs.base import NAME, PATH, Fields, PairKind, Reader, read_path
from mech.pairs.specs import SlideSpec


def _read(r: Reader, fields: Fields, what: str, links: tuple[str, ...]) -> SlideSpec:
    path = r.optional(fields, "path", lambda n: read_path(r, n, what))
    point = r.optional(fields, "point", lambda n: r.name(n, f"`point` of {what}"))
    return SlideSpec(path=path, point=point)


_KEYS = {"path": PATH, "point": NAME}

PRISMATIC = PairKind(
    type=JointType.PRISMATIC,
    keys=_KEYS,
    read=_read,
    spec=SlideSpec(),
    higher=False,
    motion="sliding",
    line_contact=False,
    located="none",
    role="path",  # a pair, not a point: its `point` is the slider's
)

SLOT = PairKind(
    type=JointType.SLOT,
    keys=_KEYS,
    read=_read,
    spec=SlideSpec(),
    higher=True,
    motion="sliding and turning (pin in slot)",
    line_contact=True,
    located="first",
    role="path",  # the pin's centre: a point of the pin link, moving along the slot
)
