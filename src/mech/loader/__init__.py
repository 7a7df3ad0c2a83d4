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
:mod:`~.sheets`           answer sheets: entries as nodes, each validated like ``answers``
:mod:`~.mechanism`        a whole file: the top-level keys and the order sections are read in
========================  ===============================================================

Each section module names its keys in a table (``DRIVE_KEYS`` …) that the
reader checks against and :mod:`mech.schema` is generated from.  All problems
in a file are gathered and raised together as one :class:`~mech.errors.InputError`.
"""

from __future__ import annotations

import os
import sys

from mech.errors import InputError, Where
from mech.loader.mechanism import read_mechanism
from mech.loader.nodes import compose, decode, is_null, no_cycle_collection, node_kind
from mech.loader.refs import placement_cycles
from mech.loader.sheets import parse_answer_entries, parse_answers
from mech.model import Mechanism

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
    with no_cycle_collection():
        return read_mechanism(text, path)
