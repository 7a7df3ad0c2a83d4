"""The ``drive:`` section: which link turns (or which slider moves), how fast, from where.

A crank drive names a ``link`` (angle, rpm or omega, direction, alpha, about,
relative_to); a slider drive names a prismatic or slot ``joint`` (speed,
acceleration).  One drive or a list of them, one per input.
"""

from __future__ import annotations

import math

import yaml

from mech.loader.nodes import article, did_you_mean
from mech.loader.reader import NodeReader, Skip
from mech.model import Drive, Joint
from mech.pairs import kind_of
from mech.units import Dimension, parse_quantity

__all__ = ["CRANK_KEYS", "DIRECTIONS", "DRIVE_KEYS", "SLIDER_KEYS", "read_drives"]

#: The keys only a crank drive (``link:``) takes.
CRANK_KEYS = ("angle", "rpm", "omega", "direction", "alpha", "about", "relative_to")
#: The keys only a slider drive (``joint:``) takes.
SLIDER_KEYS = ("speed", "accel", "acceleration")
#: Every key of one drive, in the order cli.md lists them.
DRIVE_KEYS = ("link", "joint", *CRANK_KEYS, *SLIDER_KEYS)
#: The senses a drive may turn in.
DIRECTIONS = ("cw", "ccw")

Fields = dict[str, tuple[yaml.Node, yaml.Node]]


def read_drives(
    r: NodeReader, node: yaml.Node, links: set[str], ground: str | None, joints: list[Joint]
) -> list[Drive]:
    """One drive or a list of them; a link or slider driven twice is a problem."""
    items = node.value if isinstance(node, yaml.SequenceNode) else [node]
    out: list[Drive] = []
    for item in items:
        try:
            drive = _drive(r, item, links, ground, joints)
        except Skip:
            continue
        twin = next((d for d in out if (d.link, d.joint) == (drive.link, drive.joint)), None)
        if twin is not None:
            r.problem(
                item,
                f"{drive.link or drive.joint} is driven twice (first at line {twin.where.line if twin.where else '?'})",
                "one drive per input link or slider; a mechanism of n degrees of freedom needs n different inputs",
            )
            continue
        out.append(drive)
    return out


def _drive(r: NodeReader, node: yaml.Node, links: set[str], ground: str | None, joints: list[Joint]) -> Drive:
    f = r.mapping(node, "the drive", allowed=DRIVE_KEYS)
    link = r.optional(f, "link", lambda n: r.name(n, "the driven link"))
    joint = r.optional(f, "joint", lambda n: r.name(n, "the driven joint"))
    if (link is None) == (joint is None):
        raise r.problem(node, "a drive names either a `link` (a crank) or a `joint` (a slider)")
    if link is not None:
        _check_crank(r, f, link, links, ground)
    if joint is not None:
        _check_slider(r, f, joint, joints)
    if "rpm" in f and "omega" in f:
        r.problem(f["omega"][0], "give rpm or omega, not both")
    direction, omega = _speed(r, f)
    sign = -1.0 if direction == "cw" else 1.0
    alpha = None
    if "alpha" in f:
        alpha = _signed(r, f["alpha"][1], "alpha", Dimension.ANGULAR_ACCELERATION)
    angle = r.optional(f, "angle", lambda n: r.number(n, "the drive angle", Dimension.ANGLE))
    about = r.optional(f, "about", lambda n: r.name(n, "`about`"))
    relative_to = _relative_to(r, f, link, links, ground)
    speed = r.optional(f, "speed", lambda n: r.number(n, "the slider speed", Dimension.VELOCITY))
    acc_key = "accel" if "accel" in f else "acceleration"
    accel = r.optional(f, acc_key, lambda n: r.number(n, "the slider acceleration", Dimension.ACCELERATION))
    if angle is not None and sign < 0 and link is not None and _turns_a_programme(link, joints):
        # a cam's drive angle is its turn from the programme's start in the sense it turns
        # (DESIGN § 1.1); the model keeps every angle counter-clockwise, so a cw turn is negative
        angle = -angle
    return Drive(
        link=link,
        joint=joint,
        angle=angle,
        omega=None if omega is None else sign * omega,
        alpha=alpha,
        about=about,
        speed=speed,
        accel=accel,
        direction=direction,
        where=r.where(node),
        relative_to=relative_to,
    )


def _check_crank(r: NodeReader, f: Fields, link: str, links: set[str], ground: str | None) -> None:
    """A crank turns a known link other than the ground and takes no slider keys."""
    if links and link not in links:
        raise r.problem(
            f["link"][1], f"the drive turns unknown link {link!r}", did_you_mean(link, links, "links")
        )
    if link == ground:
        raise r.problem(f["link"][1], "the drive cannot turn the ground link", "drive the crank")
    for key in SLIDER_KEYS:
        if key in f:
            r.problem(f[key][0], f"`{key}` belongs to a slider drive (`joint:`); a crank takes rpm or omega")


def _check_slider(r: NodeReader, f: Fields, joint: str, joints: list[Joint]) -> None:
    """A slider drive moves a known prismatic or slot joint and takes no crank keys."""
    known = {j.name: j for j in joints}
    if joint not in known:
        raise r.problem(
            f["joint"][1], f"the drive moves unknown joint {joint!r}", did_you_mean(joint, known, "joints")
        )
    if kind_of(known[joint]).role != "path":
        raise r.problem(
            f["joint"][1],
            f"a joint drive moves a slider; {joint} is {known[joint].type}",
            "drive a prismatic joint, or use `link:` for a crank",
        )
    for key in CRANK_KEYS:
        if key in f:
            r.problem(f[key][0], f"`{key}` belongs to a crank drive (`link:`); a slider takes speed")


def _speed(r: NodeReader, f: Fields) -> tuple[str | None, float | None]:
    """``direction`` and the unsigned angular speed from ``rpm`` or ``omega`` (whose sense must agree)."""
    direction = r.optional(f, "direction", lambda n: r.scalar(n, "direction"))
    if direction is not None and direction not in DIRECTIONS:
        r.problem(
            f["direction"][1],
            f"direction must be cw or ccw, not {direction!r}",
            "write `direction: cw` (clockwise) or `direction: ccw` (counter-clockwise)",
        )
        direction = None
    omega = None
    for key, unit_factor_ in (("rpm", 2 * math.pi / 60), ("omega", 1.0)):
        if key in f:
            omega, sense = _angular(r, f[key][1], key, unit_factor_)
            if sense and direction and sense != direction:
                r.problem(f[key][1], f"{key} says {sense} but direction says {direction}")
            direction = direction or sense
    return direction, omega


def _relative_to(
    r: NodeReader, f: Fields, link: str | None, links: set[str], ground: str | None
) -> str | None:
    """The link a crank is driven relative to (None: the ground)."""
    relative_to = r.optional(f, "relative_to", lambda n: r.name(n, "`relative_to`"))
    if relative_to is not None and link is not None:
        if links and relative_to not in links:
            raise r.problem(
                f["relative_to"][1],
                f"relative_to names unknown link {relative_to!r}",
                did_you_mean(relative_to, links, "links"),
            )
        if relative_to == link:
            raise r.problem(
                f["relative_to"][1], f"{link} cannot be driven relative to itself", "name another link"
            )
        if relative_to == ground:
            return None  # relative to the ground is what a drive means anyway
    return relative_to


def _angular(r: NodeReader, node: yaml.Node, key: str, bare_factor: float) -> tuple[float, str | None]:
    raw = r.scalar(node, key)
    try:
        q = parse_quantity(raw)
    except (KeyError, ValueError):
        raise r.problem(node, f'{key} must be a speed such as 600 or "62.8 rad/s", not {raw!r}') from None
    if q.dimension is None:
        value = q.value * bare_factor
    elif q.dimension is Dimension.ANGULAR_VELOCITY and key == "rpm" and q.unit != "rpm":
        # `rpm` names its unit: another one would be read silently as something the key does not say
        raise r.problem(
            node,
            f"rpm is in revolutions per minute, but {raw!r} is in {q.unit}",
            f"write `omega: {raw}` for a speed in {q.unit}, or give rpm in rev/min",
        )
    elif q.dimension is Dimension.ANGULAR_VELOCITY:
        value = q.value
    else:
        raise r.problem(
            node,
            f"{key} must be an angular velocity, but {q.unit!r} is a unit of {q.dimension.label}",
            "give it in rev/min (`rpm: 120`) or as `omega: 12.6 rad/s`; a slider's drive takes `speed:`",
        )
    if value < 0:
        raise r.problem(node, f"{key} must not be negative", "give the sense with `direction: cw` or `ccw`")
    return r.in_range(node, key, value, Dimension.ANGULAR_VELOCITY), q.sense


def _signed(r: NodeReader, node: yaml.Node, key: str, dimension: Dimension) -> float:
    """A signed value, counter-clockwise positive; ``"5 rad/s^2 cw"`` is −5."""
    raw = r.scalar(node, key)
    try:
        q = parse_quantity(raw)
    except (KeyError, ValueError):
        raise r.problem(
            node, f'{key} must be a number such as 5 or "5 {dimension.value} cw", not {raw!r}'
        ) from None
    if q.dimension is not None and q.dimension is not dimension:
        raise r.problem(
            node, f"{key} must be {article(dimension.label)}, but {q.unit!r} is a unit of {q.dimension.label}"
        )
    value = r.in_range(node, key, q.value, dimension)
    if q.sense == "cw":
        return -abs(value)
    if q.sense == "ccw":
        return abs(value)
    return value


def _turns_a_programme(link: str, joints: list[Joint]) -> bool:
    """True when ``link`` is the cam of a cam joint that gives its follower's programme."""
    return any(j.links[:1] == (link,) and getattr(j.spec, "program", None) is not None for j in joints)
