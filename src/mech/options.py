"""Options folded into values, validated once (command line and library alike).

A command builds one :class:`SolveOptions` from its flags and hands it down;
no layer below the CLI sees a flag.
"""

from __future__ import annotations

import math
from dataclasses import replace

from mech._records import dataclass
from mech.units import MAGNITUDE_RANGE

__all__ = ["ANGLE_PRECISION", "OutputUnits", "SolveOptions", "angle_spacing_problem"]

#: The float spacing (rad) the largest angle asked for may have: beyond it (angles past about
#: 2.6e8°) an angle is not known well enough to locate anything on it (a sweep's or one solve's).
ANGLE_PRECISION = 1e-9


def angle_spacing_problem(degrees: float) -> str | None:
    """Why an angle (in degrees, as given) is too large to be held in floating point, or None."""
    spacing = math.radians(math.ulp(abs(degrees)))
    if spacing <= ANGLE_PRECISION:
        return None
    return (
        f"a crank angle of {degrees:.4g}° is held only to {math.degrees(spacing):.2g}° in floating "
        "point: nothing on it can be located"
    )


@dataclass(frozen=True, slots=True)
class SolveOptions:
    """What the solver needs beyond the file.

    Parameters
    ----------
    angle
        Overrides the (single) drive's angle, rad, counter-clockwise from +x.
    omega
        Overrides a turning drive's angular speed magnitude, rad/s (``--rpm`` is
        converted before it gets here).  Refused for a slider drive.
    speed
        Overrides a slider drive's speed, m/s, signed along its path.  Refused
        for a turning drive.
    direction
        ``"cw"`` or ``"ccw"``: overrides the drive's sense of rotation.
    alpha
        Overrides the drive's angular acceleration, rad/s² (signed, ccw +).
    tol
        Newton's stopping tolerance on the constraint residual, relative to
        the mechanism's size (its largest joint distance).  1e-12 leaves
        about 1e-9 relative accuracy in velocities at ordinary conditioning.
    max_iter
        Cap on Newton iterations per solve.
    method
        ``"auto"`` (closed-form dyads where the chain decomposes, Newton
        otherwise), ``"closed"`` (dyads or an error) or ``"newton"`` (always
        the general solver, with ``tol``).  The closed form is exact to
        rounding, so ``tol`` matters only where Newton runs.
    flipped
        Points whose dyads close on the other assembly branch than the drawing's
        (a four-bar's rocker pin mirrored in the line of its neighbours), every
        other dyad keeping its own side.  Solved by the closed-form dyads only: a
        chain that does not decompose into them, or a point no dyad places, is
        refused, and so is a sweep (it follows the drawing's own branches).  What a
        diagnosis of "the other assembly branch" solves
        (:mod:`mech.diagnose`), at the price of one evaluation, not a second
        assembly.
    """

    angle: float | None = None
    omega: float | None = None
    speed: float | None = None
    direction: str | None = None
    alpha: float | None = None
    tol: float = 1e-12
    max_iter: int = 50
    method: str = "auto"
    flipped: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.direction not in (None, "cw", "ccw"):
            raise ValueError(f"direction must be 'cw' or 'ccw', not {self.direction!r}")
        if not (0.0 < self.tol < 1.0) or not math.isfinite(self.tol):
            raise ValueError(f"tol must be between 0 and 1, not {self.tol!r}")
        if self.method not in ("auto", "closed", "newton"):
            raise ValueError(f"method must be 'auto', 'closed' or 'newton', not {self.method!r}")
        if not isinstance(self.flipped, tuple) or not all(isinstance(n, str) for n in self.flipped):
            raise ValueError("flipped must be a tuple of point names")
        if self.max_iter < 1:
            raise ValueError("max_iter must be at least 1")
        for name in ("angle", "omega", "speed", "alpha"):
            v = getattr(self, name)
            if v is not None and not math.isfinite(v):
                raise ValueError(f"{name} must be finite")
        if self.omega is not None and self.omega < 0:
            raise ValueError("omega is a magnitude; give the sense with direction")
        low, high = MAGNITUDE_RANGE
        for name in ("omega", "speed", "alpha"):
            v = getattr(self, name)
            if v is not None and v != 0.0 and not low <= abs(v) <= high:
                raise ValueError(
                    f"{name} = {v:g} (SI) is outside the range mech works in ({low:g} to {high:g})"
                )

    def with_(self, **changes: object) -> SolveOptions:
        """A copy with some fields changed (options are immutable)."""
        return replace(self, **changes)  # type: ignore[arg-type]


@dataclass(frozen=True, slots=True)
class OutputUnits:
    """Units in which reports print numbers (analysis is always SI)."""

    length: str = "m"
    velocity: str = "m/s"
    acceleration: str = "m/s^2"
    angular_velocity: str = "rad/s"
    angular_acceleration: str = "rad/s^2"
    angle: str = "deg"

    @classmethod
    def named(cls, name: str) -> OutputUnits:
        """``si`` (m, m/s …) or ``mm`` (mm, mm/s, mm/s²): the ``--units`` choices."""
        if name in ("si", "m"):
            return cls()
        if name == "mm":
            return cls(length="mm", velocity="mm/s", acceleration="mm/s^2")
        if name == "cm":
            return cls(length="cm", velocity="cm/s", acceleration="cm/s^2")
        raise ValueError(f"unknown unit system {name!r} (choose si, mm or cm)")
