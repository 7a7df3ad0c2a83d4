"""What a joint's own keys are read with: the loader's reader as a protocol, shared readers, schema pieces.

A pair kind (:mod:`mech.pairs`) and a cam programme (:mod:`mech.cam.read`) read
their keys through the loader's node reader, so every value gets the same
units, ranges and ``file:line:col`` messages as the rest of the file.  This
module says what such a reader may be asked (:class:`Reader`, implemented by
:class:`mech.loader.reader.NodeReader`), reads the shapes several kinds share
(a reference, a path, profiles, radii), and holds the JSON-Schema fragments from
which ``mech schema`` is generated.  It sits below the pairs and the loader.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from functools import partial
from typing import Any, Protocol

import yaml

from mech.specs import Circle, Curve, Knife, Line, Path, Profile, Profiles, Ref, Vec
from mech.units import Dimension

__all__ = [
    "NAME",
    "NUMBER",
    "PATH",
    "PROFILE",
    "PROFILES",
    "RADII",
    "REF",
    "XY",
    "Fields",
    "Reader",
    "is_null",
    "read_path",
    "read_profiles",
    "read_radii",
    "read_ref",
]

#: A mapping as the loader reads it: key → (key node, value node).
Fields = Mapping[str, tuple[Any, Any]]


class Reader(Protocol):
    """What a kind's reader may ask of the loader (see :class:`mech.loader.reader.NodeReader`)."""

    def problem(self, node: yaml.Node | None, message: str, hint: str | None = None) -> Exception: ...
    def guard(self, fn: Callable[[], Any], default: Any) -> Any: ...
    def optional(self, mapping: Fields, key: str, reader: Callable[..., Any]) -> Any: ...
    def mapping(
        self, node: yaml.Node, what: str, *, allowed: Iterable[str] | None = None
    ) -> dict[str, tuple[yaml.Node, yaml.Node]]: ...
    def sequence(self, node: yaml.Node, what: str) -> list[yaml.Node]: ...
    def scalar(self, node: yaml.Node, what: str) -> str: ...
    def name(self, node: yaml.Node, what: str) -> str: ...
    def boolean(self, node: yaml.Node, what: str) -> bool: ...
    def number(
        self, node: yaml.Node, what: str, dimension: Dimension, *, positive: bool = False
    ) -> float: ...
    def vec(self, node: yaml.Node, what: str) -> Vec: ...


# -- JSON-Schema fragments shared by kinds and the rest of the schema ---------------------------
NUMBER: dict[str, Any] = {
    "description": 'A bare number in the file\'s units, or a string with its unit ("40 mm", "60 deg").',
    "oneOf": [
        {"type": "number"},
        {"type": "string", "pattern": r"^\s*[+-]?(\d[\d_]*(\.\d*)?|\.\d+)([eE][+-]?\d+)?\s*[^\s\d]*.*$"},
    ],
}
NAME: dict[str, Any] = {"type": "string", "pattern": r"^[^\s.\-\[\]{},:#]+$"}
XY: dict[str, Any] = {"type": "array", "items": NUMBER, "minItems": 2, "maxItems": 2}
REF: dict[str, Any] = {"oneOf": [NAME, XY], "description": "Coordinates [x, y] or the name of a point."}
PATH: dict[str, Any] = {
    "type": "object",
    "required": ["through"],
    "additionalProperties": False,
    "properties": {"through": REF, "angle": NUMBER, "toward": REF},
}
PROFILE: dict[str, Any] = {
    "description": "A curve fixed in the link: circle, line, point (knife edge) or closed curve.",
    "type": "object",
    "minProperties": 1,
    "maxProperties": 1,
    "additionalProperties": False,
    "properties": {
        "circle": {
            "type": "object",
            "required": ["centre", "radius"],
            "additionalProperties": False,
            "properties": {"centre": REF, "radius": NUMBER},
        },
        "line": PATH,
        "point": REF,
        "curve": {"type": "array", "items": XY, "minItems": 3},
    },
}
PROFILES: dict[str, Any] = {
    "description": "Each link's curve, keyed by link: with profiles the pair moves.",
    "type": "object",
    "additionalProperties": PROFILE,
}
RADII: dict[str, Any] = {
    "type": "array",
    "items": {"oneOf": [NUMBER, {"type": "null"}]},
    "minItems": 2,
    "maxItems": 2,
}


# -- readers shared by kinds ------------------------------------------------------------------
def read_ref(r: Reader, node: yaml.Node, what: str) -> Ref:
    """Coordinates ``[x, y]`` or the name of a joint or point."""
    if isinstance(node, yaml.SequenceNode):
        return Ref(xy=r.vec(node, what))
    return Ref(name=r.name(node, what))


def read_path(r: Reader, node: yaml.Node, what: str, *, noun: str = "path") -> Path:
    """``{through: P, angle: a}`` or ``{through: P, toward: Q}``."""
    fields = r.mapping(node, f"the {noun} of {what}", allowed=("through", "angle", "toward"))
    if "through" not in fields:
        raise r.problem(
            node, f"the {noun} of {what} has no `through`", f"e.g. `{noun}: {{through: O, angle: 0}}`"
        )
    if ("angle" in fields) == ("toward" in fields):
        raise r.problem(node, f"the {noun} of {what} needs exactly one of `angle` or `toward`")
    through = read_ref(r, fields["through"][1], f"`through` of {what}")
    angle = r.optional(fields, "angle", lambda n: r.number(n, f"the {noun} angle", Dimension.ANGLE))
    toward = r.optional(fields, "toward", lambda n: read_ref(r, n, f"`toward` of {what}"))
    return Path(through=through, angle=angle, toward=toward)


def _read_profile(r: Reader, node: yaml.Node, what: str) -> Profile:
    fields = r.mapping(node, what, allowed=("circle", "line", "point", "curve"))
    if len(fields) != 1:
        raise r.problem(
            node,
            f"{what} must be exactly one of circle, line, point or curve",
            "e.g. `{circle: {centre: E, radius: 40}}` or `{line: {through: F, angle: 0}}`",
        )
    ((kind, (_, vnode)),) = fields.items()
    if kind == "circle":
        c = r.mapping(vnode, f"the circle of {what}", allowed=("centre", "radius"))
        missing = [k for k in ("centre", "radius") if k not in c]
        if missing:
            raise r.problem(
                vnode, f"the circle of {what} has no `{missing[0]}`", "e.g. `{centre: E, radius: 40}`"
            )
        centre = read_ref(r, c["centre"][1], f"the centre of {what}")
        radius = r.number(c["radius"][1], f"the radius of {what}", Dimension.LENGTH, positive=True)
        return Circle(centre, radius)
    if kind == "line":
        p = read_path(r, vnode, what, noun="line")
        return Line(p.through, p.angle, p.toward)
    if kind == "point":
        return Knife(read_ref(r, vnode, f"the point of {what}"))
    items = r.sequence(vnode, f"the curve of {what}")
    if len(items) < 3:
        raise r.problem(vnode, f"the curve of {what} needs at least 3 points, not {len(items)}")
    points = tuple(r.vec(item, f"a point of the curve of {what}") for item in items)
    if len(set(points)) != len(points):
        raise r.problem(
            vnode,
            f"the curve of {what} passes through the same point twice",
            "a closed curve lists each point once",
        )
    return Curve(points)


def read_profiles(r: Reader, node: yaml.Node, what: str, links: tuple[str, ...]) -> Profiles:
    """``profiles: {link: curve, …}``, keyed by the joint's own links."""
    out: list[tuple[str, Profile]] = []
    for key, (knode, vnode) in r.mapping(node, f"the profiles of {what}").items():
        if links and key not in links:
            r.problem(
                knode,
                f"the profiles of {what} name {key!r}, which it does not join",
                f"key each profile by one of {', '.join(links)}",
            )
            continue
        profile = r.guard(partial(_read_profile, r, vnode, f"the profile of {key} in {what}"), None)
        if profile is not None:
            out.append((key, profile))
    return tuple(out)


def read_radii(r: Reader, node: yaml.Node, what: str, *, nulls: bool) -> tuple[Any, Any]:
    """``radii: [r1, r2]`` (positive lengths; ``null`` for a straight line when ``nulls``)."""
    items = r.sequence(node, f"the radii of {what}")
    if len(items) != 2:
        raise r.problem(node, f"the radii of {what} must be a pair [r1, r2]")
    out: list[float | None] = []
    for k, item in enumerate(items):
        if nulls and is_null(item):
            out.append(None)
        else:
            ordinal = ("first", "second")[k]
            out.append(r.number(item, f"the {ordinal} of radii", Dimension.LENGTH, positive=True))
    if out == [None, None]:
        raise r.problem(
            node, f"the radii of {what} are both null", "at least one of the two must be a circle"
        )
    return (out[0], out[1])


def is_null(node: yaml.Node | None) -> bool:
    """An empty value (``key:``, ``~``, ``null``): YAML's resolver tagged it null."""
    return isinstance(node, yaml.ScalarNode) and node.tag == "tag:yaml.org,2002:null"
