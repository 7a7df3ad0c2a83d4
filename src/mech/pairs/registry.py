"""The model layer's registry of pair kinds: :data:`KINDS`, keyed by joint type.

Adding a kind: write its module here (keys, reader, classification — see
:class:`mech.pairs.base.PairKind`), add it to :data:`KINDS`, then give it an
entry in each registry ``tests/test_pair_kinds.py`` walks.
"""

from __future__ import annotations

from mech.model import JointType
from mech.pairs.base import PairKind
from mech.pairs.contact import CAM, CONTACT
from mech.pairs.gear import GEAR
from mech.pairs.revolute import REVOLUTE
from mech.pairs.rolling import ROLLING
from mech.pairs.sliding import PRISMATIC, SLOT
from mech.pairs.spatial import SCREW, SPHERICAL

__all__ = ["KINDS", "kind"]

KINDS: dict[JointType, PairKind] = {
    k.type: k for k in (REVOLUTE, PRISMATIC, SLOT, ROLLING, CAM, CONTACT, GEAR, SCREW, SPHERICAL)
}


def kind(t: JointType) -> PairKind:
    """The registry entry of joint type ``t``."""
    return KINDS[t]
