"""The built-in pair kinds, registered in :data:`mech.pairs.table.KINDS` by the ``type:`` a file writes.

Adding a kind: write its module in :mod:`mech.pairs` (a subclass of
:class:`mech.pairs.base.PairKind`) and add one line to the tuple below, or
call :func:`register` from anywhere before the file is loaded (a plug-in);
``tests/test_pair_kinds.py`` walks every kind through every hook.  Each is
imported when a file first names its type (:mod:`mech.pairs.table`).
"""

from __future__ import annotations

from mech.pairs.table import KINDS, kind_of, register, register_lazy

__all__ = ["KINDS", "kind_of", "register"]

#: ``type:`` and where its kind's class lives, in the order the file format lists them.
BUILT_IN = (
    ("revolute", "mech.pairs.revolute:Revolute"),
    ("prismatic", "mech.pairs.prismatic:Prismatic"),
    ("slot", "mech.pairs.slot:Slot"),
    ("rolling", "mech.pairs.rolling:Rolling"),
    ("cam", "mech.pairs.cam:Cam"),
    ("contact", "mech.pairs.contact:Contact"),
    ("gear", "mech.pairs.gear:Gear"),
    ("screw", "mech.pairs.screw:Screw"),
    ("spherical", "mech.pairs.spherical:Spherical"),
)

for _name, _where in BUILT_IN:
    register_lazy(_name, _where)
