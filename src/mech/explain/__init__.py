"""The analysis written out as the notes write it (``--explain``).

* :mod:`.polygon` — velocity and acceleration polygons step by step, for a mechanism
  that decomposes into a crank and dyads;
* :mod:`.cam` — a cam's follower from its law at the instant: segment, s, v, a, pressure angle;
* :mod:`.train` — a gear train stage by stage, and its value;
* :mod:`.icentres` — Kennedy's circle diagram.

:func:`explain` picks what the mechanism is: a cam with a programme is worked out from its
law, a train of gears mesh by mesh, anything else as polygons.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from mech.explain.icentres import explain_icentres
from mech.explain.polygon import Construction, Known, Measured, Step, UnknownLine, polygon
from mech.explain.worked import Line, Worked

if TYPE_CHECKING:
    from mech.model import Mechanism

__all__ = [
    "Construction",
    "Known",
    "Line",
    "Measured",
    "Step",
    "UnknownLine",
    "Worked",
    "construction_dict",
    "explain",
    "explain_icentres",
]


def explain(mech: Mechanism, kin: Any, *, kind: str = "velocity") -> Construction | Worked:
    """The working of ``mech`` at the instant solved in ``kin`` (``kind``: velocity or acceleration).

    Raises
    ------
    UnsupportedError
        Polygons: the mechanism does not decompose into a crank and dyads.
    """
    from mech.pairs import kind_of
    from mech.pairs.cam.setup import cam_joints

    if cam_joints(mech):
        from mech.explain.cam import working

        return working(mech, kin)
    if any(kind_of(j).meshes for j in mech.joints):
        from mech.explain.train import working as train

        return train(mech, kin)
    return polygon(mech, kin, kind=kind)


def construction_dict(c: Construction | Worked) -> dict[str, Any]:
    """A working for ``--json`` (SI; directions in degrees)."""
    from mech.explain.polygon import construction_dict as polygon_dict

    return c.as_dict() if isinstance(c, Worked) else polygon_dict(c)
