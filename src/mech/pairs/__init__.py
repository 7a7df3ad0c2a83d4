"""Pair kinds: everything a type of joint means, one module per kind, one registry.

Every layer that treats joints differently by type asks the joint's kind
(:func:`kind_of`), an instance of a :class:`~mech.pairs.base.PairKind`
subclass: what it reads, how it is classified and counted, its constraint
rows, its closed-form dyad, its I-centre by inspection, its glyph.  Nothing
outside this package branches on a type's name.  A new kind is one module and
one line in :data:`~mech.pairs.registry.KINDS` (or a :func:`register` call).

The functions below answer, for a joint, the questions the model leaves to its
kind (the model holds only what the file says).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

from mech.pairs.base import PairKind
from mech.pairs.registry import KINDS, kind_of, register

if TYPE_CHECKING:
    from mech.model import Joint, Load, Mechanism
    from mech.specs import JointSpec

__all__ = [
    "KINDS",
    "PairKind",
    "closure_of",
    "higher_pairs",
    "kind_of",
    "load_link",
    "located_on",
    "point_link",
    "points_of",
    "register",
    "spec_of",
]


def located_on(joint: Joint) -> tuple[str, ...]:
    """The links ``joint`` is a *point* of (where a length may end).

    A prismatic joint is a pair, not a point (its ``point`` is the slider's).
    A slot joint is the pin's centre, a point of the pin link only: it moves
    along the slotted link.  Every other joint is a point of each link it joins
    (a contact point at the drawn instant).
    """
    return KINDS[joint.type].located_on(joint)


def points_of(mech: Mechanism, link: str) -> tuple[str, ...]:
    """Names of every located thing on a link: its joints (those with a point) and points."""
    names = [j.name for j in mech.joints if link in located_on(j)]
    names += [p.name for p in mech.points if p.link == link]
    return tuple(names)


def closure_of(joint: Joint) -> str:
    """``self`` or ``force``: the file's ``closure`` (form → self) or the kind's default."""
    if joint.closure is None:
        return KINDS[joint.type].closure
    return "self" if joint.closure in ("form", "self") else "force"


def spec_of(joint: Joint) -> JointSpec:
    """The joint's spec, or its kind's empty spec when it was built without one."""
    return joint.spec if joint.spec is not None else KINDS[joint.type].spec


def higher_pairs(joints: Iterable[Joint]) -> tuple[tuple[str, tuple[str, ...]], ...]:
    """(name, links) of every cam, contact, rolling or gear pair (DESIGN § 1.2): each link's point at its
    contact is ``K@link``.  Rolling counts as a lower pair in Kutzbach's j, but touches as these do."""
    return tuple(
        (j.name, tuple(j.links)) for j in joints if j.type in KINDS and KINDS[j.type].role == "contact"
    )


def load_link(mech: Mechanism, load: Load) -> str:
    """The link a force acts on: its ``on``, else the one its point is fixed in (:func:`point_link`).

    One answer for the force solve, its free bodies and the power balance of ``mech properties``.
    """
    if load.on is not None:
        return load.on
    link = point_link(mech, load.target)
    if link is None:
        raise KeyError(load.target)
    return link


def point_link(mech: Mechanism, name: str) -> str | None:
    """The moving link the point ``name`` is taken on: a point's link, a joint's moving link.

    A higher pair's name (a cam's, a contact's, a rolling or gear pair's: :func:`higher_pairs`) is
    its follower's own point (DESIGN § 1.2): the pair's second link, or its moving one where the
    second is the frame (a planet on its fixed ring).  A pin of several moving links gives the
    first (a load there without ``on`` leaves the pin's own force undetermined).  None: a joint on
    the frame alone.
    """
    for pt in mech.points:
        if pt.name == name:
            return pt.link
    for j in mech.joints:
        if j.name == name:
            moving = [lk for lk in j.links if lk != mech.ground]
            if not moving:
                return None
            return moving[-1] if KINDS[j.type].role == "contact" else moving[0]
    raise KeyError(name)
