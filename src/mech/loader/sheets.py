"""Answer sheets (``mech check --answers``): a student's problem → answers mapping, read as nodes.

A sheet is read with the same decoding, YAML limits and ``file:line:col``
messages as a mechanism file (:mod:`mech.loader.nodes`).  Its entries keep
their answers as nodes, not values: each is later validated against its
problem's mechanism by :func:`mech.loader.parse_answer_entries`, with the
same grammar and messages as a file's own ``answers``.
"""

from __future__ import annotations

from collections.abc import Set as AbstractSet
from typing import Any

import yaml

from mech.answers import names_by_kind
from mech.errors import InputError, Problem, Where
from mech.loader.answers import DEFAULT_TOLERANCE, read_answers, read_claim
from mech.loader.nodes import compose, is_null, node_kind, text_of, where_of
from mech.loader.reader import NodeReader, Skip
from mech.model import Claim, Mechanism, Tolerance

__all__ = [
    "RawEntry",
    "answer_keys",
    "own_tolerances",
    "parse_answer_entries",
    "parse_answers",
    "sheet_entries",
]

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


def _kinds(mechanism: Mechanism) -> dict[str, AbstractSet[str]]:
    return names_by_kind(
        (link.name for link in mechanism.links),
        (j.name for j in mechanism.joints),
        (p.name for p in mechanism.points),
        len(mechanism.links),
    )


def parse_answers(
    node: yaml.Node, mechanism: Mechanism, *, path: str, source: str | None = None
) -> tuple[tuple[Claim, ...], Tolerance]:
    """Read an ``answers`` mapping written outside the mechanism's own file.

    ``mech check --answers SHEET`` reads a student's sheet (problem → answers)
    and validates each answers mapping exactly as the loader validates a
    file's own ``answers``: the same key grammar, names checked against
    ``mechanism``, units against the quantity.  ``node`` is the mapping node
    PyYAML composed from the sheet; ``path`` and ``source`` are the sheet's,
    so every problem points into the sheet with a caret.

    Returns the claims and the ``tolerance`` the mapping sets (2% if none).

    Raises
    ------
    InputError
        With every problem in the mapping at once.
    """
    reader = NodeReader(source or "", path)
    claims, tolerance = reader.guard(
        lambda: read_answers(reader, node, _kinds(mechanism)), ([], DEFAULT_TOLERANCE)
    )
    reader.fail()
    return tuple(claims), tolerance


def parse_answer_entries(
    node: yaml.MappingNode, mechanism: Mechanism, *, path: str, source: str | None = None
) -> list[tuple[str, Where, Claim | InputError]]:
    """Each entry of an answers mapping read on its own: ``(key, where, claim or its error)``.

    For answer sheets, where one bad key must cost only that key: every entry
    is validated as :func:`parse_answers` would (same grammar, names, units),
    but a problem becomes that entry's :class:`InputError` instead of failing
    the mapping.  Keys are returned as written, repeats and ``tolerance``
    included (the caller decides what they mean on a sheet).
    """
    reader = NodeReader(source or "", path)
    kinds = _kinds(mechanism)
    out: list[tuple[str, Where, Claim | InputError]] = []
    for knode, vnode in node.value:
        reader.problems = []
        key = str(knode.value) if isinstance(knode, yaml.ScalarNode) else text_of(knode)
        claim: Claim | None = None
        try:
            if not isinstance(knode, yaml.ScalarNode):
                raise reader.problem(
                    knode, f"an answer key is text such as omega.rocker, not {node_kind(knode)}"
                )
            claim = read_claim(reader, key, knode, vnode, kinds)
        except Skip:
            pass
        if reader.problems or claim is None:
            problems = reader.problems or [Problem("unreadable answer", reader.where(knode))]
            error = InputError(problems=problems, source=source)
            out.append((key, reader.where(knode), error))
        else:
            out.append((key, reader.where(knode), claim))
    return out
