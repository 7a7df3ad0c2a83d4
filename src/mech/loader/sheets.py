"""Answer sheets (``mech check --answers``): a student's problem → answers mapping, read as nodes.

A sheet is read with the same decoding, YAML limits and ``file:line:col``
messages as a mechanism file (:mod:`mech.loader.nodes`).  Its entries keep
where their answers are written, not the answers themselves: each is composed
again from the sheet's text when its problem is checked
(:func:`entry_node`), then validated against the problem's mechanism by
:func:`parse_answer_entries`, with the same grammar and messages as a file's
own ``answers``.

Why not keep the nodes: a composed value costs about 2.6 KB (a node, two marks,
a tag), so a class of 2,000 sheets held 1.8 GB of nodes while it was checked
(issue 25).  The text of a sheet is a few hundred bytes per answer, and it is
kept anyway, to quote the line of a message.
"""

from __future__ import annotations

from collections.abc import Callable
from collections.abc import Set as AbstractSet

import yaml

from mech._records import dataclass
from mech.answers import names_by_kind
from mech.errors import InputError, Problem, Where
from mech.loader.answers import DEFAULT_TOLERANCE, read_answers, read_claim
from mech.loader.nodes import compose, is_null, node_kind, text_of, where_of
from mech.loader.reader import NodeReader, Skip
from mech.model import Claim, Mechanism, Tolerance
from mech.pairs import higher_pairs

__all__ = [
    "SheetEntry",
    "answer_keys",
    "entry_node",
    "own_tolerances",
    "parse_answer_entries",
    "parse_answers",
    "sheet_entries",
]


@dataclass(frozen=True, slots=True)
class SheetEntry:
    """One top-level entry of a sheet: a problem key, where it is written, and where its answers are.

    ``span`` locates the answers mapping in the sheet's text: ``(start, end)``
    character offsets and the ``line`` and ``column`` (from 0) it starts at;
    None for an empty entry (``four_bar:``), which answers nothing, or one whose
    value is not a mapping (``problem`` then says why it is no answers).
    ``answers`` counts the keys of the mapping.
    """

    key: str
    where: Where
    span: tuple[int, int, int, int] | None = None
    answers: int = 0
    problem: str | None = None

    @property
    def empty(self) -> bool:
        return self.problem is None and self.answers == 0


def sheet_entries(text: str, path: str) -> tuple[list[SheetEntry], list[tuple[str, str, Where]]]:
    """The entries of a sheet's text, and its keys that are not text ``(as written, what, where)``.

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
    entries: list[SheetEntry] = []
    bad_keys: list[tuple[str, str, Where]] = []
    for knode, vnode in root.value:
        where = where_of(knode, path)
        if not isinstance(knode, yaml.ScalarNode):
            written = " ".join(text[knode.start_mark.index : knode.end_mark.index].split())
            bad_keys.append((written if len(written) <= 40 else written[:39] + "…", node_kind(knode), where))
            continue
        key = str(knode.value)
        if isinstance(vnode, yaml.MappingNode):
            start, end = vnode.start_mark, vnode.end_mark
            span = (start.index, end.index, start.line, start.column) if vnode.value else None
            entries.append(SheetEntry(key, where, span, len(vnode.value)))
        elif is_null(vnode):
            entries.append(SheetEntry(key, where))
        else:
            message = f"the answers to {key} must be a mapping (`dof: 1` lines), not {node_kind(vnode)}"
            entries.append(SheetEntry(key, where, problem=message))
    return entries, bad_keys


def entry_node(source: str, entry: SheetEntry, path: str) -> yaml.MappingNode | None:
    """The answers mapping of a sheet entry, composed again from the sheet's text ``source``.

    Only the entry's own text is composed, after as many line breaks and spaces
    as put it at its line and column, so every node keeps the location it has in
    the sheet.  When that text does not stand alone (an alias to an anchor written
    elsewhere, a ``%TAG`` directive), the whole sheet is composed and the entry
    taken from it.
    """
    if entry.span is None:
        return None
    start, end, line, column = entry.span
    try:
        node = compose("\n" * line + " " * column + source[start:end], path, what="this answer sheet")
    except InputError:
        node = None
    if (
        isinstance(node, yaml.MappingNode)
        and len(node.value) == entry.answers
        and (node.start_mark.line, node.start_mark.column) == (line, column)
    ):
        return node
    root = compose(source, path, what="this answer sheet")
    for knode, vnode in root.value if isinstance(root, yaml.MappingNode) else ():
        if (knode.start_mark.line + 1, knode.start_mark.column + 1) == (entry.where.line, entry.where.column):
            return vnode if isinstance(vnode, yaml.MappingNode) else None
    return None  # pragma: no cover - the sheet changed under us: nothing to grade


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
        higher_pairs(mechanism.joints),
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
    node: yaml.MappingNode,
    mechanism: Mechanism,
    *,
    path: str,
    source: str | None = None,
    wanted: Callable[[str], bool] | None = None,
) -> list[tuple[str, Where, Claim | InputError | None]]:
    """Each entry of an answers mapping read on its own: ``(key, where, claim or its error)``.

    For answer sheets, where one bad key must cost only that key: every entry
    is validated as :func:`parse_answers` would (same grammar, names, units),
    but a problem becomes that entry's :class:`InputError` instead of failing
    the mapping.  Keys are returned as written, repeats and ``tolerance``
    included (the caller decides what they mean on a sheet).  A key for which
    ``wanted(key)`` is false is not read at all (its value is None): the keys of
    a sheet beyond what is graded or listed cost nothing.
    """
    reader = NodeReader(source or "", path)
    kinds = _kinds(mechanism)
    out: list[tuple[str, Where, Claim | InputError | None]] = []
    for knode, vnode in node.value:
        reader.problems = []
        key = str(knode.value) if isinstance(knode, yaml.ScalarNode) else text_of(knode)
        if wanted is not None and not wanted(key):
            out.append((key, reader.where(knode), None))
            continue
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
