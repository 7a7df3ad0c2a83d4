"""The built-in pair kinds, registered in :data:`mech.pairs.table.KINDS` by the ``type:`` a file writes.

Adding a kind: write its module in :mod:`mech.pairs` (a subclass of
:class:`mech.pairs.base.PairKind`) and add one instance to the tuple below, or
call :func:`register` from anywhere before the file is loaded (a plug-in);
``tests/test_pair_kinds.py`` walks every kind through every hook.
"""

from __future__ import annotations

from mech.pairs.cam import Cam
from mech.pairs.contact import Contact
from mech.pairs.gear import Gear
from mech.pairs.prismatic import Prismatic
from mech.pairs.revolute import Revolute
from mech.pairs.rolling import Rolling
from mech.pairs.screw import Screw
from mech.pairs.slot import Slot
from mech.pairs.spherical import Spherical
from mech.pairs.table import KINDS, kind_of, register

__all__ = ["KINDS", "kind_of", "register"]

for _kind in (Revolute(), Prismatic(), Slot(), Rolling(), Cam(), Contact(), Gear(), Screw(), Spherical()):
    register(_kind)
