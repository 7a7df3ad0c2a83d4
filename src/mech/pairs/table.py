"""The table of pair kinds, keyed by the ``type:`` a file writes (:data:`KINDS`).

It sits below every kind's module, so a kind may ask another joint's kind
(:func:`kind_of`) without importing the registry that imports the kinds
(issue 20: that back-edge tied the higher pairs into an import circle).
:mod:`mech.pairs.registry` fills it with the built-in kinds; a plug-in calls
:func:`register`.

A built-in kind is registered by where it lives (``"mech.pairs.gear:Gear"``) and
imported when a file first names it: ``mech dof`` on a four-bar of pins never
loads the cam's laws or the gears' involutes (a tenth of its start-up).  Listing
the kinds (iterating, ``values()``) loads them all, in the registry's order.
"""

from __future__ import annotations

from collections.abc import Iterator, MutableMapping
from importlib import import_module
from typing import TYPE_CHECKING

from mech.pairs.base import PairKind

if TYPE_CHECKING:
    from mech.model import Joint

__all__ = ["KINDS", "kind_of", "register", "register_lazy"]


class _Kinds(MutableMapping[str, PairKind]):
    """``type:`` → kind; an entry registered by its module path is imported when first looked up."""

    def __init__(self) -> None:
        self._entries: dict[str, PairKind | str] = {}

    def __getitem__(self, name: str) -> PairKind:
        entry = self._entries[name]
        if isinstance(entry, str):
            module, _, cls = entry.partition(":")
            entry = getattr(import_module(module), cls)()
            if entry.name != name:
                raise RuntimeError(
                    f"{module}.{cls} is registered as {name!r} but names itself {entry.name!r}"
                )
            self._entries[name] = entry
        return entry

    def __setitem__(self, name: str, kind: PairKind) -> None:
        self._entries[name] = kind

    def __delitem__(self, name: str) -> None:
        del self._entries[name]

    def __contains__(self, name: object) -> bool:
        return name in self._entries  # no import: a type's name is known without its module

    def __iter__(self) -> Iterator[str]:
        return iter(list(self._entries))

    def __len__(self) -> int:
        return len(self._entries)

    def __repr__(self) -> str:
        return f"KINDS({list(self._entries)})"


#: ``type:`` → the kind, in the order the file format lists them (filled by :mod:`mech.pairs.registry`).
KINDS = _Kinds()


def register(kind: PairKind) -> PairKind:
    """Add (or replace) a kind: files may then write ``type: <kind.name>``."""
    KINDS[kind.name] = kind
    return kind


def register_lazy(name: str, where: str) -> None:
    """Add a kind by where its class lives (``"package.module:Class"``), imported when first asked for."""
    KINDS._entries[name] = where


_ENTRIES = KINDS._entries


def kind_of(joint: Joint | str) -> PairKind:
    """The kind of a joint, or of a type's name (asked dozens of times per solve: one dict lookup)."""
    name = joint if isinstance(joint, str) else joint.type
    entry = _ENTRIES[name]
    return KINDS[name] if isinstance(entry, str) else entry
