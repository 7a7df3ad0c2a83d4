"""Grashof's criterion and slider-crank inversions: now :mod:`mech.topology.grashof`.

The loops are pure geometry of the file's lengths, reported by ``mech dof``, so
they live in the topology's room, below this one.  This name stays for the
callers that still import it from here (the answer keys' compute functions,
which are moving to their own room); new code imports :mod:`mech.topology.grashof`.
"""

from __future__ import annotations

from mech.topology.grashof import (
    EQUAL,
    GRASHOF_CLASSES,
    FourBarLoop,
    SliderCrankLoop,
    four_bar_loops,
    linkage_loops,
)

__all__ = ["EQUAL", "GRASHOF_CLASSES", "FourBarLoop", "SliderCrankLoop", "four_bar_loops", "linkage_loops"]
