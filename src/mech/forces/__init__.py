"""Forces: what drives a mechanism and what its pairs carry (DESIGN § 1.4), without friction.

:func:`analyse` solves the kinematics at the level the question needs (the
accelerations when links have mass and the drive a speed; the rates only for a
static problem) and then the forces at that instant
(:func:`mech.forces.instant.at_instant`).  Only what a question needs is
modelled: a file without ``masses`` is massless, and gravity acts only when the
file gives it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from mech.forces.result import ForceAnalysis
    from mech.model import Mechanism
    from mech.options import SolveOptions

__all__ = ["analyse"]


def analyse(mech: Mechanism, options: SolveOptions | None = None) -> ForceAnalysis:
    """The forces of ``mech`` at its drive's angle (``options`` as for :func:`mech.kinematics.solve`).

    With masses and a drive speed the links' inertia counts (d'Alembert: the
    mechanism is solved to accelerations; without masses to velocities); a drive
    without a speed (or at a speed of zero) is a static problem: the rates are taken
    at unit speed for the power balance only, and no inertia acts.  The work is
    :func:`mech.forces.instant.analyse` (imported here on first call: numpy).

    Raises
    ------
    InputError
        A load at a pin two moving links share without ``on``; a file that cannot be solved.
    """
    from mech.forces.instant import analyse as at_drive_angle

    return at_drive_angle(mech, options)
