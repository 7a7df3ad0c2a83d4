"""The table of pair kinds, keyed by the ``type:`` a file writes (:data:`KINDS`).

It sits below every kind's module, so a kind may ask another joint's kind
(:func:`kind_of`) without importing the registry that imports the kinds
(issue 20: that back-edge tied the higher pairs into an import circle).
:mod:`mech.pairs.registry` fills it with the built-in kinds; a plug-in calls
:func:`register`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from mech.pairs.base import PairKind

if TYPE_CHECKING:
    from mech.model import Joint

__all__ = ["KINDS", "kind_of", "register"]

#: ``type:`` → the kind, in the order the file format lists them (filled by :mod:`mech.pairs.registry`).
KINDS: dict[str, PairKind] = {}


def register(kind: PairKind) -> PairKind:
    """Add (or replace) a kind: files may then write ``type: <kind.name>``."""
    KINDS[kind.name] = kind
    return kind


def kind_of(joint: Joint | str) -> PairKind:
    """The kind of a joint, or of a type's name."""
    return KINDS[joint if isinstance(joint, str) else joint.type]
