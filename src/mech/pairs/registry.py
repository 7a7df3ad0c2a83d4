"""The registry of pair kinds, keyed by the ``type:`` a file writes (:data:`KINDS`).

Adding a kind: write its module in :mod:`mech.pairs` (a subclass of
:class:`mech.pairs.base.PairKind`) and add one instance to :data:`KINDS`, or
call :func:`register` from anywhere before the file is loaded (a plug-in);
``tests/test_pair_kinds.py`` walks every kind through every hook.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from mech.pairs.base import PairKind
from mech.pairs.cam import Cam
from mech.pairs.contact import Contact
from mech.pairs.gear import Gear
from mech.pairs.prismatic import Prismatic
from mech.pairs.revolute import Revolute
from mech.pairs.rolling import Rolling
from mech.pairs.screw import Screw
from mech.pairs.slot import Slot
from mech.pairs.spherical import Spherical

if TYPE_CHECKING:
    from mech.model import Joint

__all__ = ["KINDS", "kind_of", "register"]

#: ``type:`` → the kind, in the order the file format lists them.
KINDS: dict[str, PairKind] = {
    k.name: k
    for k in (Revolute(), Prismatic(), Slot(), Rolling(), Cam(), Contact(), Gear(), Screw(), Spherical())
}


def register(kind: PairKind) -> PairKind:
    """Add (or replace) a kind: files may then write ``type: <kind.name>``."""
    KINDS[kind.name] = kind
    return kind


def kind_of(joint: Joint | str) -> PairKind:
    """The kind of a joint, or of a type's name."""
    return KINDS[joint if isinstance(joint, str) else joint.type]
