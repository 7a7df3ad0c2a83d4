"""Answer sheets (``mech check --answers``): a student's problem → answers mapping, read as nodes.

A sheet is read with the same decoding, YAML limits and ``file:line:col``
messages as a mechanism file (:mod:`mech.loader.nodes`).  Its entries keep
their answers as nodes, not values: each is later validated against its
problem's mechanism by :func:`mech.loader.parse_answer_entries`, with the
same grammar and messages as a file's own ``answers``.
"""

from __future__ import annotations

from typing import Any

import yaml

from mech.errors import InputError, Where
from mech.loader.nodes import compose, is_null, node_kind, where_of

__all__ = ["RawEntry", "answer_keys", "own_tolerances", "sheet_entries"]

#: One top-level entry: (problem key, where, its answers mapping node or None, why it is no answers).
RawEntry = tuple[str, Where, Any, str | None]


def sheet_entries(text: str, path: str) -> tuple[list[RawEntry], list[tuple[str, str, Where]]]:
    """The entries of a sheet's text, and its keys that are not text ``(as written, what, where)``.

    An empty entry (``four_bar:``) has no node; an entry whose value is not a
    mapping carries the reason instead.

    Raises
    ------
    InputError
        When the text is not YAML, or not a mapping of problems to answers.
    """
    root = compose(text, path, what="this answer sheet")
    if not isinstance(root, yaml.MappingNode):
        raise InputError(
            "an answer sheet maps problems to answers (`four_bar: {dof: 1, …}`)",
            where=Where(path, 1, 1),
            hint="each top-level key is a problem's file name, stem or name",
        )
    entries: list[RawEntry] = []
    bad_keys: list[tuple[str, str, Where]] = []
    for knode, vnode in root.value:
        where = where_of(knode, path)
        if not isinstance(knode, yaml.ScalarNode):
            written = " ".join(text[knode.start_mark.index : knode.end_mark.index].split())
            bad_keys.append((written if len(written) <= 40 else written[:39] + "…", node_kind(knode), where))
            continue
        key = str(knode.value)
        if isinstance(vnode, yaml.MappingNode):
            entries.append((key, where, vnode, None))
        elif is_null(vnode):
            entries.append((key, where, None, None))
        else:
            message = f"the answers to {key} must be a mapping (`dof: 1` lines), not {node_kind(vnode)}"
            entries.append((key, where, None, message))
    return entries, bad_keys


def answer_keys(node: yaml.MappingNode, path: str) -> list[tuple[str, Where]]:
    """The keys of one entry's answers mapping, as written, with where each is."""
    return [(str(knode.value), where_of(knode, path)) for knode, _ in node.value]


def own_tolerances(node: yaml.MappingNode, path: str) -> dict[str, Where]:
    """Keys of a sheet entry written ``{value: …, tolerance: …}``: where their tolerance is."""
    out = {}
    for knode, vnode in node.value:
        if isinstance(vnode, yaml.MappingNode):
            for k, _ in vnode.value:
                if getattr(k, "value", None) == "tolerance":
                    out[str(knode.value)] = where_of(k, path)
    return out
