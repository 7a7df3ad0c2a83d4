"""Instantaneous centres of a planar mechanism: inspection, Aronhold-Kennedy, velocity check.

The public API::

    from mech.icentres import locate
    ic = locate(mech, kin)            # kin: mech.kinematics.solve(mech, level="velocity")
    ic.count                          # N = n(n − 1)/2
    ic.get("crank", "rocker")         # an ICentre, by link names
    ic.by_number(1, 3); ic.named("I13")
    ic.omega_by_icentres              # link → ω by the I-centre method

Modules, in the order a student works: :mod:`.homogeneous` (points and lines,
points at infinity), :mod:`.inspection` (the geometry of the instant and the
primary I-centres), :mod:`.kennedy` (the theorem, round by round),
:mod:`.locate` (cross-check with the velocity field, completion, ω by
I-centres, the frozen results).  Pure Python: no numpy needed.
"""

from mech.icentres.homogeneous import Frame
from mech.icentres.inspection import Contact, Instant, Pin, Slide, instant_of
from mech.icentres.kennedy import kennedy
from mech.icentres.locate import (
    ICentre,
    ICentreDisagreement,
    ICentres,
    OmegaByICentres,
    from_instant,
    locate,
)

__all__ = [
    "Contact",
    "Frame",
    "ICentre",
    "ICentreDisagreement",
    "ICentres",
    "Instant",
    "OmegaByICentres",
    "Pin",
    "Slide",
    "from_instant",
    "instant_of",
    "kennedy",
    "locate",
]
