"""The ``loads:`` section: a force at a point, a torque on a link (DESIGN § 1.1)."""

from __future__ import annotations

import yaml

from mech.loader.nodes import did_you_mean
from mech.loader.reader import NodeReader
from mech.model import Joint, Load, Point
from mech.pairs import located_on
from mech.units import Dimension

__all__ = ["LOAD_KEYS", "read_loads"]

#: The keys of one load: a force at a point or a torque on a link.
LOAD_KEYS = ("force", "torque")


def read_loads(
    r: NodeReader, node: yaml.Node, links: list[str], joints: list[Joint], points: list[Point]
) -> tuple[Load, ...]:
    """``loads: {P: {force: [0, -500]}, rocker: {torque: "20 N m"}}``."""
    located = {j.name for j in joints if located_on(j)} | {p.name for p in points}
    out = []
    for name, (knode, vnode) in r.mapping(node, "loads").items():
        fields = r.mapping(vnode, f"the load on {name}", allowed=LOAD_KEYS)
        if name in links:
            if "torque" not in fields or "force" in fields:
                r.problem(knode, f"{name} is a link: load it with a torque", 'e.g. {torque: "20 N m"}')
                continue
            torque = r.number(fields["torque"][1], f"the torque on {name}", Dimension.TORQUE)
            out.append(Load(name, torque=torque, where=r.where(knode)))
        elif name in located:
            if "force" not in fields or "torque" in fields:
                r.problem(knode, f"{name} is a point: load it with a force", "e.g. {force: [0, -500]}")
                continue
            items = r.sequence(fields["force"][1], f"the force at {name}")
            if len(items) != 2:
                r.problem(fields["force"][1], f"the force at {name} must be a pair [Fx, Fy] (N)")
                continue
            fx, fy = (r.number(n, f"the force at {name}", Dimension.FORCE) for n in items)
            out.append(Load(name, force=(fx, fy), where=r.where(knode)))
        else:
            r.problem(
                knode,
                f"loads names {name!r}, which is neither a link nor a point",
                did_you_mean(name, set(links) | located),
            )
    return tuple(out)
