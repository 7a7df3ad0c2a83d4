"""What a force analysis finds at one instant: the force each pair carries, the input effort and
its parts, the shaking force and moment on the frame.  Plain records, SI; rendering is elsewhere."""

from __future__ import annotations

from dataclasses import field
from typing import Any

from mech._records import dataclass
from mech.pairs.base import PairForce  # a pair kind's forces hook gives these: defined with the kinds

__all__ = ["Effort", "ForceAnalysis", "Inertia", "PairForce"]

Vec = tuple[float, float]


@dataclass(frozen=True, slots=True)
class Inertia:
    """d'Alembert's inertia load of one massive link: ``force`` = −m a_G at ``centre``, ``couple`` = −I_G α."""

    link: str
    mass: float
    centre: Vec
    acceleration: Vec
    alpha: float
    force: Vec
    couple: float
    weight: Vec


@dataclass(frozen=True, slots=True)
class Effort:
    """The input torque (N·m, ccw +) or force (N, along the slider's path) that holds the mechanism
    at the instant, and its parts: the loads, the links' inertia and their weight."""

    kind: str  # "torque" or "force"
    driver: str
    value: float
    loads: float
    inertia: float
    gravity: float


@dataclass(frozen=True, slots=True)
class ForceAnalysis:
    """Everything :func:`mech.forces.analyse` finds at one instant.

    ``determinate`` is False where the constraint rows are redundant (a double
    parallelogram): the pairs' forces are then not fixed by statics (``pairs``
    is empty and ``note`` says why), but the input effort, from the power
    balance, still is.
    """

    mechanism: str
    drive_angle: float | None
    pairs: tuple[PairForce, ...]
    effort: Effort | None
    inertia: tuple[Inertia, ...]
    shaking_force: Vec
    shaking_moment: float
    about: Vec
    determinate: bool
    note: str = ""
    #: True for a static problem (no drive speed: no inertia, the rates only for the power balance).
    static: bool = False
    #: What else the reader must know: a load at a pin of two moving links that names neither
    #: (:func:`mech.forces.core.unsaid_on`), its pin's force shown with the load on the first.
    notes: tuple[str, ...] = ()
    #: The solved instant the forces are of (a :class:`mech.kinematics.Kinematics`), for the free
    #: bodies and the drawings; not part of the result's value.
    kinematics: Any = field(default=None, compare=False, repr=False)

    def pair(self, joint: str) -> PairForce:
        """The force of ``joint`` on its second link (the first row found for a joint of more links)."""
        for p in self.pairs:
            if p.joint == joint:
                return p
        raise KeyError(joint)
