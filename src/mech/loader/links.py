"""The ``links:`` and ``ground:`` sections: the bodies of the mechanism and which one is fixed."""

from __future__ import annotations

import contextlib
from typing import Any

import yaml

from mech.loader.nodes import did_you_mean, is_null, node_kind
from mech.loader.reader import NodeReader, Skip

__all__ = ["LINK_KEYS", "LINK_KINDS", "RawLink", "read_ground", "read_links"]

#: The keys a link may carry when ``links:`` is a mapping (``links: {coupler: {kind: rigid}}``).
LINK_KEYS = ("kind", "description")
#: What ``kind`` of a link may be.
LINK_KINDS = ("rigid", "flexible", "fluid")

#: A link as read: its name, its key node (for messages) and its optional fields.
RawLink = tuple[str, yaml.Node, dict[str, Any]]


def read_links(r: NodeReader, node: yaml.Node) -> list[RawLink]:
    """``links: [frame, crank, …]`` or ``links: {frame: , crank: {kind: rigid}}``."""
    out: list[RawLink] = []
    if isinstance(node, yaml.SequenceNode):
        for item in node.value:
            with contextlib.suppress(Skip):
                out.append((r.name(item, "a link"), item, {}))
    elif isinstance(node, yaml.MappingNode):
        for key, (knode, vnode) in r.mapping(node, "links").items():
            try:
                name = r.name(knode, "a link")
            except Skip:
                continue
            extra = {} if is_null(vnode) else _link_fields(r, vnode, key)
            out.append((name, knode, extra))
    else:
        raise r.problem(
            node,
            f"links must be a list of names or a mapping, not {node_kind(node)}",
            "e.g. `links: [frame, crank, coupler, rocker]`",
        )
    if not out and not r.problems:
        raise r.problem(node, "there are no links", "a mechanism has at least two links")
    return out


def _link_fields(r: NodeReader, vnode: yaml.Node, key: str) -> dict[str, Any]:
    """The optional ``kind`` and ``description`` of one link."""
    extra: dict[str, Any] = {}
    try:
        fields = r.mapping(vnode, f"link {key}", allowed=LINK_KEYS)
    except Skip:
        fields = {}
    if "kind" in fields:
        kind = r.scalar(fields["kind"][1], "kind")
        if kind not in LINK_KINDS:
            r.problem(fields["kind"][1], f"unknown link kind {kind!r}", "kind is rigid, flexible or fluid")
        extra["kind"] = kind
    if "description" in fields:
        extra["description"] = r.scalar(fields["description"][1], "description")
    return extra


def read_ground(
    r: NodeReader, root: yaml.Node, top: dict[str, tuple[Any, Any]], links: list[str]
) -> str | None:
    """The ground link: ``ground:`` if given, else the one link called frame or ground."""
    if "ground" in top:
        vnode = top["ground"][1]
        try:
            g = r.name(vnode, "the ground link")
        except Skip:
            return None
        if links and g not in links:
            r.problem(
                vnode,
                f"ground link {g!r} is not among the links",
                did_you_mean(g, links) or f"links: {', '.join(links)}",
            )
            return None
        return g
    candidates = [n for n in links if n in ("frame", "ground")]
    if len(candidates) == 1:
        return candidates[0]
    if len(candidates) == 2:
        r.problem(
            top["links"][1], "two links could be ground: frame and ground", "say which with `ground: frame`"
        )
        return None
    if links:
        r.problem(
            top["links"][1] if "links" in top else root,
            "no ground link: none is named frame or ground",
            "name the fixed link with `ground: <link>`",
        )
    return None
