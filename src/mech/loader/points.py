"""Where things are: placements (``at``, ``from``/``toward`` …), the ``points:`` and ``lengths:`` sections."""

from __future__ import annotations

from typing import Any

import yaml

from mech.loader.nodes import did_you_mean
from mech.loader.reader import NodeReader, Skip
from mech.model import Length, Placement, Point
from mech.units import Dimension

__all__ = ["PLACE_KEYS", "POINT_KEYS", "read_lengths", "read_place", "read_points"]

#: The keys that place a joint or a point (DESIGN: "Placing a point").
PLACE_KEYS = ("at", "near", "from", "toward", "distance", "offset")
#: The keys of one entry of ``points:``.
POINT_KEYS = ("link", "description", *PLACE_KEYS)


def read_place(r: NodeReader, fields: dict[str, tuple[Any, Any]], what: str) -> Placement:
    """The placement keys of a joint's or a point's mapping, checked for a consistent way to place it."""
    if not any(k in fields for k in PLACE_KEYS):
        return Placement()  # placed by the lengths (most joints of a file)
    at = r.optional(fields, "at", lambda n: r.vec(n, f"`at` of {what}"))
    near = r.optional(fields, "near", lambda n: r.vec(n, f"`near` of {what}"))
    origin = r.optional(fields, "from", lambda n: _anchor(r, n, "from", what))
    toward = r.optional(fields, "toward", lambda n: _anchor(r, n, "toward", what))
    distance = r.optional(
        fields, "distance", lambda n: r.number(n, f"`distance` of {what}", Dimension.LENGTH)
    )
    offset = r.optional(fields, "offset", lambda n: r.vec(n, f"`offset` of {what}"))
    relative = [k for k in ("from", "toward", "distance", "offset") if k in fields]
    if relative:
        anchor = fields[relative[0]][0]
        if "from" not in fields or "toward" not in fields:
            r.problem(anchor, f"{what} is placed relative to two points: give both `from` and `toward`")
        if ("distance" in fields) == ("offset" in fields):
            r.problem(anchor, f"{what} needs exactly one of `distance` or `offset` with from/toward")
        if "at" in fields:
            r.problem(fields["at"][0], f"{what} has both `at` and from/toward", "place it one way")
    return Placement(at=at, near=near, origin=origin, toward=toward, distance=distance, offset=offset)


def _anchor(r: NodeReader, node: yaml.Node, key: str, what: str) -> str:
    """``from``/``toward`` of a placement: the name of a point of the same link."""
    if isinstance(node, yaml.SequenceNode):
        raise r.problem(
            node,
            f"`{key}` of {what} must name a joint or point of the same link, not coordinates",
            "coordinates place it with `at: [x, y]`; from/toward keep it rigid on its link as it moves",
        )
    return r.name(node, f"`{key}` of {what}")


def read_points(r: NodeReader, node: yaml.Node, links: set[str]) -> list[Point]:
    """``points: {P: {link: coupler, at: [x, y]}}``: named points fixed on a link."""
    out: list[Point] = []
    for _key, (knode, vnode) in r.mapping(node, "points").items():
        try:
            name = r.name(knode, "a point")
            what = f"point {name}"
            fields = r.mapping(vnode, what, allowed=POINT_KEYS)
            if "link" not in fields:
                raise r.problem(vnode, f"{what} has no `link`", "say which link it is fixed on")
            link = r.name(fields["link"][1], f"the link of {what}")
            if links and link not in links:
                raise r.problem(
                    fields["link"][1],
                    f"{what} is on unknown link {link!r}",
                    did_you_mean(link, links, "links"),
                )
            place = read_place(r, fields, what)
            if place.at is None and not place.is_relative:
                raise r.problem(
                    vnode,
                    f"{what} is not placed",
                    "give `at: [x, y]` or `from`/`toward` with `distance` or `offset`",
                )
            out.append(Point(name=name, link=link, place=place, where=r.where(knode)))
        except Skip:
            continue
    return out


def read_lengths(r: NodeReader, node: yaml.Node, located: dict[str, set[str]]) -> list[Length]:
    """``lengths: {AB: 40, B-C: "120 mm"}``: distances between two points of one link."""
    out: list[Length] = []
    seen: dict[frozenset[str], str] = {}
    for key, (knode, vnode) in r.mapping(node, "lengths").items():
        try:
            a, b = _length_key(r, knode, key, located)
            if a == b:
                raise r.problem(knode, f"length {key} joins {a!r} to itself")
            value = r.number(vnode, f"length {key}", Dimension.LENGTH, positive=True)
            if {a, b} & r.tainted:  # its joint's error is reported; more would be echoes
                continue
            common = located[a] & located[b]
            if not common:
                raise r.problem(
                    knode,
                    f"{a} and {b} are not on one link ({a}: {', '.join(sorted(located[a]))}; {b}: {', '.join(sorted(located[b]))})",
                    "a length is the distance between two points of the same link",
                )
            pair = frozenset((a, b))
            if pair in seen:
                raise r.problem(
                    knode,
                    f"length {key} is given twice (also as {seen[pair]})",
                    "give each distance once (AB and BA name the same one)",
                )
            seen[pair] = key
            out.append(Length(a, b, value, r.where(knode)))
        except Skip:
            continue
    return out


def _length_key(r: NodeReader, knode: yaml.Node, key: str, located: dict[str, set[str]]) -> tuple[str, str]:
    """The two names of a length key: ``A-B``, or ``AB`` when only one split names two points."""
    if r.tainted:  # a joint whose own error is reported counts as known here, silently
        located = {**{n: set() for n in r.tainted}, **located}
    if "-" in key:
        parts = key.split("-")
        if len(parts) != 2 or not all(parts):
            raise r.problem(knode, f"length {key!r} must name two points as A-B")
        for part in parts:
            if part not in located:
                raise r.problem(
                    knode,
                    f"length {key} names unknown point {part!r}",
                    did_you_mean(part, located) or "name joints or points",
                )
        return parts[0], parts[1]
    splits = [(key[:i], key[i:]) for i in range(1, len(key)) if key[:i] in located and key[i:] in located]
    if len(splits) == 1:
        return splits[0]
    if len(splits) > 1:
        options = " or ".join(f"{a}-{b}" for a, b in splits)
        raise r.problem(knode, f"length {key!r} is ambiguous", f"write {options}")
    raise r.problem(
        knode,
        f"length {key!r} does not name two known points",
        "write it as A-B with the names of two joints or points",
    )
