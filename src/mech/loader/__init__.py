"""YAML text → :class:`~mech.model.Mechanism`: units, names, validation.

The loader is split by section over one located-node reader:

========================  ===============================================================
:mod:`~.nodes`            YAML text → nodes with ``file:line:col`` (decoding, syntax, limits)
:mod:`~.reader`           :class:`NodeReader`: typed values from nodes, problems collected
:mod:`~.units`            ``units:``
:mod:`~.links`            ``links:`` and ``ground:``
:mod:`~.joints`           ``joints:`` (each type's own keys read by :mod:`mech.pairs`)
:mod:`~.points`           placements, ``points:`` and ``lengths:``
:mod:`~.drives`           ``drive:``
:mod:`~.answers`          ``answers:`` and ``asks:`` (answer sheets too)
:mod:`~.loads`            ``loads:``
:mod:`~.refs`             cross-references: one namespace, names on the right link, cycles
:mod:`~.mechanism`        a whole file: the top-level keys and the order sections are read in
========================  ===============================================================

Each section module names its keys in a table (``DRIVE_KEYS`` …) that the
reader checks against and :mod:`mech.schema` is generated from.  All problems
in a file are gathered and raised together as one :class:`~mech.errors.InputError`.
"""

from __future__ import annotations

import os
import sys

import yaml

from mech.answers import names_by_kind
from mech.errors import InputError, Problem, Where
from mech.loader.answers import DEFAULT_TOLERANCE, read_answers, read_claim
from mech.loader.mechanism import read_mechanism
from mech.loader.nodes import compose, decode, is_null, node_kind, text_of
from mech.loader.reader import NodeReader, Skip
from mech.loader.refs import placement_cycles
from mech.model import Claim, Mechanism, Tolerance

__all__ = [
    "compose",
    "decode",
    "is_null",
    "load",
    "loads",
    "node_kind",
    "parse_answer_entries",
    "parse_answers",
    "placement_cycles",
]


def load(path: str | os.PathLike[str]) -> Mechanism:
    """Read a mechanism file.  ``"-"`` reads standard input.

    Raises
    ------
    InputError
        Naming the file, line and column of every problem, with a hint.
    """
    name = os.fspath(path)
    if name == "-":
        data = sys.stdin.buffer.read()
        return loads(data, path="<stdin>")
    try:
        with open(name, "rb") as f:  # not pathlib: it costs mech dof ~5 ms of start-up (urllib, ipaddress)
            data = f.read()
    except FileNotFoundError:
        raise InputError(
            f"no such file: {name}",
            where=Where(name),
            hint="check the path; with no FILE, mech reads mechanism.yaml in this folder",
        ) from None
    except IsADirectoryError:
        raise InputError(
            f"{name} is a folder, not a mechanism file",
            where=Where(name),
            hint="name a .yaml file (mech check takes folders)",
        ) from None
    except OSError as exc:
        raise InputError(f"cannot read {name}: {exc.strerror}", where=Where(name)) from None
    return loads(data, path=name)


def loads(text: str | bytes, *, path: str = "<string>") -> Mechanism:
    """Read a mechanism from YAML text (``path`` is used only in messages).

    Examples
    --------
    >>> m = loads('''
    ... links: [frame, crank, coupler, rocker]
    ... joints:
    ...   A: {type: revolute, links: [frame, crank]}
    ...   B: {type: revolute, links: [crank, coupler]}
    ...   C: {type: revolute, links: [coupler, rocker]}
    ...   D: {type: revolute, links: [rocker, frame]}
    ... ''')
    >>> m.ground, len(m.joints)
    ('frame', 4)
    """
    if isinstance(text, bytes):
        text = decode(text, path)
    return read_mechanism(text, path)


def _kinds(mechanism: Mechanism) -> dict[str, set[str]]:
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
