"""The ``loads:`` section: a force at a point, a torque on a link (DESIGN § 1.1), constant or
varying over the cycle as a table of the drive's angle (DESIGN § 1.4)."""

from __future__ import annotations

from functools import partial

import yaml

from mech.loader.nodes import did_you_mean
from mech.loader.reader import NodeReader
from mech.model import Joint, Load, Point
from mech.pairs import located_on
from mech.units import Dimension

__all__ = ["LOAD_KEYS", "read_loads"]

#: The keys of one load: a force at a point or a torque on a link, and the link a force acts on.
LOAD_KEYS = ("force", "torque", "on")


def read_loads(
    r: NodeReader, node: yaml.Node, links: list[str], joints: list[Joint], points: list[Point]
) -> tuple[Load, ...]:
    """``loads: {P: {force: [0, -500]}, rocker: {torque: "20 N m"}, B: {force: {table: …}, on: piston}}``."""
    carriers: dict[str, tuple[str, ...]] = {j.name: located_on(j) for j in joints if located_on(j)}
    carriers |= {p.name: (p.link,) for p in points}
    out = []
    for name, (knode, vnode) in r.mapping(node, "loads").items():
        fields = r.mapping(vnode, f"the load on {name}", allowed=LOAD_KEYS)
        if name in links:
            if "torque" not in fields or "force" in fields or "on" in fields:
                r.problem(knode, f"{name} is a link: load it with a torque", 'e.g. {torque: "20 N m"}')
                continue
            load = r.guard(partial(_torque, r, fields["torque"][1], name, knode), None)
        elif name in carriers:
            if "force" not in fields or "torque" in fields:
                r.problem(knode, f"{name} is a point: load it with a force", "e.g. {force: [0, -500]}")
                continue
            load = r.guard(partial(_force, r, fields, name, knode, carriers[name]), None)
        elif "@" in name and name.split("@")[0] in {j.name for j in joints}:
            joint, link = name.split("@", 1)
            r.problem(
                knode,
                f"loads names {name!r}, the point of {link} at {joint}'s contact: a load is put on a named "
                "point or a link",
                f"load {joint}, the follower's own point (DESIGN § 1.2), or a point of {link} placed there",
            )
            continue
        else:
            r.problem(
                knode,
                f"loads names {name!r}, which is neither a link nor a point",
                did_you_mean(name, set(links) | set(carriers), "links and points"),
            )
            continue
        if load is not None:
            out.append(load)
    return tuple(out)


def _torque(r: NodeReader, node: yaml.Node, name: str, knode: yaml.Node) -> Load:
    if isinstance(node, yaml.MappingNode):
        table = _table(r, node, f"the torque on {name}", (Dimension.TORQUE,))
        return Load(name, table=table, where=r.where(knode))
    return Load(name, torque=r.number(node, f"the torque on {name}", Dimension.TORQUE), where=r.where(knode))


def _force(
    r: NodeReader,
    fields: dict[str, tuple[yaml.Node, yaml.Node]],
    name: str,
    knode: yaml.Node,
    on: tuple[str, ...],
) -> Load:
    what = f"the force at {name}"
    link = None
    if "on" in fields:
        link = r.name(fields["on"][1], f"the link {what} acts on")
        if link not in on:
            raise r.problem(
                fields["on"][1],
                f"{what} acts on {link!r}, which {name} is not a point of",
                f"{name} joins {', '.join(on)}",
            )
    node = fields["force"][1]
    if isinstance(node, yaml.MappingNode):
        table = _table(r, node, what, (Dimension.FORCE, Dimension.FORCE))
        return Load(name, table=table, on=link, where=r.where(knode))
    items = r.sequence(node, what)
    if len(items) != 2:
        raise r.problem(node, f"{what} must be a pair [Fx, Fy] (N)", "or {table: [[angle, Fx, Fy], …]}")
    fx, fy = (r.number(n, what, Dimension.FORCE) for n in items)
    return Load(name, force=(fx, fy), on=link, where=r.where(knode))


def _table(
    r: NodeReader, node: yaml.Node, what: str, dims: tuple[Dimension, ...]
) -> tuple[tuple[float, ...], ...]:
    """``{table: [[θ, v…], …]}``: the drive's angle (the file's unit), rising, and the values."""
    fields = r.mapping(node, what, allowed=("table",))
    if "table" not in fields:
        raise r.problem(node, f"{what} gives no `table`", "e.g. {table: [[0, 0, 0], [180, 0, -500]]}")
    rows = r.sequence(fields["table"][1], f"the table of {what}")
    if len(rows) < 2:
        raise r.problem(fields["table"][1], f"the table of {what} needs at least two rows")
    out: list[tuple[float, ...]] = []
    for row in rows:
        items = r.sequence(row, f"a row of the table of {what}")
        if len(items) != 1 + len(dims):
            shape = "[angle, Fx, Fy]" if len(dims) == 2 else "[angle, torque]"
            raise r.problem(row, f"each row of the table of {what} is {shape}, not {len(items)} numbers")
        theta = r.number(items[0], "an angle of the table", Dimension.ANGLE)
        if out and not theta > out[-1][0]:
            raise r.problem(items[0], f"the table's angles must rise from row to row ({what})")
        out.append((theta, *(r.number(n, what, d) for n, d in zip(items[1:], dims, strict=True))))
    return tuple(out)
