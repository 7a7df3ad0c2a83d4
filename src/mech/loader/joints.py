"""The ``joints:`` section: the keys every joint shares, the rest read by its pair kind.

What a joint type adds (``path``, ``radii``, ``profiles`` …) is read by that
kind's entry in the pair-kind registry (:mod:`mech.pairs`); this module reads
the common keys, checks that each key belongs to the joint's type, and builds
the :class:`~mech.model.Joint`.
"""

from __future__ import annotations

from typing import Any

import yaml

from mech.loader.nodes import did_you_mean
from mech.loader.points import PLACE_KEYS, read_place
from mech.loader.reader import NodeReader, Skip
from mech.model import Joint
from mech.pairs import KINDS, PairKind

__all__ = ["CLOSURES", "COMMON_JOINT_KEYS", "read_joints"]

#: The keys every joint may carry, whatever its type (a type adds its own: ``PairKind.keys``).
COMMON_JOINT_KEYS = ("type", "links", "closure", "description", *PLACE_KEYS)
#: What ``closure`` may be.
CLOSURES = ("form", "force", "self")

Fields = dict[str, tuple[yaml.Node, yaml.Node]]


def read_joints(r: NodeReader, node: yaml.Node, links: set[str]) -> list[Joint]:
    """Every joint of ``joints:``; a joint with an error is left out and its name tainted."""
    joints: list[Joint] = []
    entries = r.mapping(node, "joints")
    if not entries:
        raise r.problem(node, "there are no joints")
    for key, (knode, vnode) in entries.items():
        try:
            joints.append(_joint(r, knode, vnode, links))
        except Skip:
            r.tainted.add(key)  # reported already: lengths naming it would only echo it
            continue
    return joints


def _joint(r: NodeReader, knode: yaml.Node, vnode: yaml.Node, links: set[str]) -> Joint:
    name = r.name(knode, "a joint")
    what = f"joint {name}"
    fields = r.mapping(vnode, what)
    jtype = _joint_type(r, vnode, fields, what)
    pair = KINDS[jtype]
    _check_keys(r, fields, jtype, pair)
    names = _joint_links(r, vnode, fields, name, what, links, pair, jtype)
    place = read_place(r, fields, what)
    own = {k: v for k, v in fields.items() if k in pair.keys}
    spec = pair.read(r, own, what, tuple(names))
    closure = r.optional(fields, "closure", lambda n: r.scalar(n, "closure"))
    if closure is not None and closure not in CLOSURES:
        r.problem(
            fields["closure"][1], f"unknown closure {closure!r}", "closure is form (self-closed) or force"
        )
    if "description" in fields:
        r.scalar(fields["description"][1], "description")
    return Joint(
        name=name,
        type=jtype,
        links=tuple(names),
        place=place,
        spec=spec,
        closure=closure,
        where=r.where(knode),
    )


def _joint_type(r: NodeReader, vnode: yaml.Node, fields: Fields, what: str) -> str:
    """The joint's ``type``: the name of a registered pair kind."""
    if "type" not in fields:
        raise r.problem(vnode, f"{what} has no `type`", "e.g. `type: revolute` (" + ", ".join(KINDS) + ")")
    type_node = fields["type"][1]
    type_text = r.scalar(type_node, "the joint type")
    if type_text not in KINDS:
        raise r.problem(
            type_node,
            f"unknown joint type {type_text!r}",
            did_you_mean(type_text, list(KINDS)) or "types: " + ", ".join(KINDS),
        )
    return type_text


def _check_keys(r: NodeReader, fields: Fields, jtype: str, pair: PairKind) -> None:
    """Every key is a common one or this type's own; another type's key is named as such."""
    allowed = _allowed_keys(jtype, pair)
    for key, (kn, _) in fields.items():
        if key not in allowed:
            others = [t for t, k in KINDS.items() if key in k.keys]
            hint = f"`{key}` belongs to {', '.join(others)} joints" if others else did_you_mean(key, allowed)
            r.problem(kn, f"unknown key {key!r} for a {jtype} joint", hint)


def _allowed_keys(jtype: str, pair: PairKind) -> frozenset[str]:
    """The keys a joint of this type may have: the common ones and its own (made once per type)."""
    allowed = _ALLOWED.get(pair)
    if allowed is None:
        allowed = _ALLOWED[pair] = frozenset(COMMON_JOINT_KEYS) | frozenset(pair.keys)
    return allowed


_ALLOWED: dict[PairKind, frozenset[str]] = {}  # keyed by the kind itself: a kind registered again is new


def _joint_links(
    r: NodeReader,
    vnode: yaml.Node,
    fields: Fields,
    name: str,
    what: str,
    links: set[str],
    pair: PairKind,
    jtype: str,
) -> list[str]:
    """The links a joint joins: known, not repeated, as many as its type allows."""
    if "links" not in fields:
        raise r.problem(vnode, f"{what} has no `links`", "e.g. `links: [frame, crank]`")
    lnode: Any = fields["links"][1]
    names: list[str] = []
    for item in r.sequence(lnode, f"the links of {what}"):
        try:
            ln = r.name(item, "a link")
        except Skip:
            continue
        if links and ln not in links:
            r.tainted.add(name)  # lengths to this joint would only repeat the error
            r.problem(
                item, f"{what} names unknown link {ln!r}", did_you_mean(ln, links) or "add it to `links:`"
            )
        elif ln in names:
            r.problem(item, f"{what} lists link {ln!r} twice")
        else:
            names.append(ln)
    if len(lnode.value) < 2:
        raise r.problem(
            lnode,
            f"{what} joins {len(lnode.value)} link; a joint joins at least two",
            "list both links it connects",
        )
    if pair.max_links is not None and len(lnode.value) > pair.max_links:
        raise r.problem(
            lnode,
            f"a {jtype} joint joins exactly two links, not {len(lnode.value)}",
            "only a revolute (pin) joint may join more than two",
        )
    return names
