"""A cam and its follower over one turn: motion, pressure angle, curvature, undercut.

:func:`analyse` samples the turn (every quarter degree by default), then
refines each extreme between its neighbouring samples by zooming in on the
exact formulas, so that the maxima quoted are the laws' own (a sampled
maximum of SHM's velocity would be short by ~1e-5 of it).

Where a law makes the velocity jump (uniform velocity at its ends) the
acceleration there is infinite, an impulse; where the acceleration jumps
(SHM and uniform acceleration at their ends, and between the halves of the
latter) the jerk is infinite.  Those angles are listed rather than hidden in
a finite maximum (Norton, *Design of Machinery*, ch. 8, the "fundamental law of
cam design").
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from mech._records import dataclass
from mech.cam.profile import CamLayout, CamState, evaluate
from mech.cam.program import FULL_TURN, follower_motion

__all__ = ["CamAnalysis", "Extreme", "analyse"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class Extreme:
    """A value and the cam angle (rad, from the programme's start) where it occurs."""

    value: float
    theta: float


@dataclass(frozen=True, slots=True)
class CamAnalysis:
    """The result of :func:`analyse` (SI: m or rad, s⁻¹ …; ``omega`` in rad/s).

    ``velocity``, ``acceleration``, ``jerk``: the largest magnitude, signed as it
    occurs (``None`` without a speed).  ``pressure``: the largest pressure angle
    (signed: positive when the cam pushes the follower up).  ``least_radius``: the
    least radius of curvature of the convex pitch curve (of the profile, for a
    flat face); ``undercut`` when it is below the roller's radius; ``cusp`` when a
    flat face's profile has a negative radius somewhere (a corner where the lift's rate falls at
    once, as at the end of a uniform-velocity rise, counts as radius 0 for a roller and −∞ for
    a flat face: neither can follow it).  ``velocity_jumps`` and
    ``acceleration_jumps`` are the cam angles where the acceleration or the jerk is
    infinite.  ``face`` is the flat face's contact span either side of its axis
    (least, greatest), the face width it needs.
    """

    layout: CamLayout
    omega: float | None
    state: CamState
    stroke: float
    pressure: Extreme
    least_radius: Extreme | None
    least_radius_any: Extreme
    undercut: bool
    cusp: bool
    velocity: Extreme | None
    acceleration: Extreme | None
    jerk: Extreme | None
    velocity_jumps: tuple[float, ...]
    acceleration_jumps: tuple[float, ...]
    face: tuple[float, float] | None

    @property
    def follower_angular(self) -> bool:
        """True when the follower's lift is an angle (an oscillating follower)."""
        return self.layout.oscillating


def _refine(f: Callable[[FloatArray], FloatArray], theta: FloatArray, k: int, *, maximise: bool) -> Extreme:
    """Zoom in around sample ``k`` on the largest (or least) of ``f``."""
    step = float(theta[1] - theta[0]) if len(theta) > 1 else FULL_TURN
    centre = float(theta[k])
    for _ in range(4):
        grid = np.linspace(centre - step, centre + step, 41)
        values = f(grid)
        j = int(np.nanargmax(values) if maximise else np.nanargmin(values))
        centre, step = float(grid[j]), step / 20
    best = float(f(np.array([centre]))[0])
    return Extreme(best, float(np.mod(centre, FULL_TURN)))


def _largest(f: Callable[[FloatArray], FloatArray], theta: FloatArray, values: FloatArray) -> Extreme:
    """The value of largest magnitude, signed, refined."""
    k = int(np.nanargmax(np.abs(values)))
    e = _refine(lambda t: np.abs(f(t)), theta, k, maximise=True)
    sign = float(np.sign(f(np.array([e.theta]))[0])) or 1.0
    return Extreme(sign * e.value, e.theta)


def _jumps(layout: CamLayout, which: int, *, drops: bool = False) -> tuple[float, ...]:
    """Cam angles where derivative ``which`` (1 velocity, 2 acceleration) of the lift jumps
    (only where it falls, with ``drops``)."""
    prog = layout.program
    starts = np.array(prog.breaks)  # segments' starts, and a law's own knots inside a segment
    eps = 1e-9
    before = follower_motion(prog, starts - eps)[which]
    after = follower_motion(prog, starts + eps)[which]
    sample = follower_motion(prog, np.linspace(0, FULL_TURN, 721))[which]
    scale = max(float(np.max(np.abs(sample))), float(np.max(np.abs(after))), 1e-300)
    # a derivative of order 'which' changes by about f^(which+1)·eps across eps: far below 1e-6 of its scale
    return tuple(
        float(t)
        for t, b, a in zip(starts, before, after, strict=True)
        if abs(a - b) > 1e-6 * scale and not (drops and a > b)
    )


def analyse(layout: CamLayout, *, omega: float | None = None, samples: int = 1440) -> CamAnalysis:
    """Analyse a cam over one turn.

    Parameters
    ----------
    layout : the programme and the follower's place (:class:`mech.cam.profile.CamLayout`)
    omega : the cam's speed, rad/s (its magnitude); ``None`` gives no velocities
    samples : cam angles sampled over the turn (the profile has this many points)
    """
    theta = np.linspace(0.0, FULL_TURN, samples, endpoint=False)
    # the segments' ends are sampled too: an extreme or a jump sits there
    state = evaluate(layout, theta)
    prog = layout.program
    flat = prog.follower == "flat"

    def pressure(t: FloatArray) -> FloatArray:
        return evaluate(layout, t).pressure

    def rho(t: FloatArray) -> FloatArray:
        r = evaluate(layout, t).rho
        return np.where(r > 0, r, np.inf)

    def rho_any(t: FloatArray) -> FloatArray:
        return evaluate(layout, t).rho

    pressure_max = _largest(pressure, theta, state.pressure)
    positive = np.where(state.rho > 0, state.rho, np.inf)
    least = None
    if np.isfinite(positive).any():
        least = _refine(rho, theta, int(np.argmin(positive)), maximise=False)
    least_any = _refine(rho_any, theta, int(np.argmin(state.rho)), maximise=False)
    # Where the lift's rate falls at once (the end of a uniform-velocity rise, the start of its
    # return), the pitch curve has a corner pointing away from the cam: radius zero.  A roller
    # cannot follow it (it rolls round the corner instead) and a flat face's profile would need
    # a negative radius there; a knife edge follows a corner.
    drops = _jumps(layout, 1, drops=True)
    if drops and prog.follower != "knife":
        corner = Extreme(0.0 if not flat else -math.inf, drops[0])
        least = corner
        least_any = corner if flat else least_any
    undercut = bool(prog.follower == "roller" and least is not None and least.value < layout.roller)
    cusp = bool(flat and least_any.value <= 0)

    velocity = acceleration = jerk = None
    if omega is not None:
        w = abs(omega)

        def deriv(order: int) -> Callable[[FloatArray], FloatArray]:
            return lambda t: follower_motion(prog, t)[order] * w**order

        velocity = _largest(deriv(1), theta, state.ds * w)
        acceleration = _largest(deriv(2), theta, state.d2s * w**2)
        jerk = _largest(deriv(3), theta, state.d3s * w**3)
    face = None
    if flat:
        if layout.oscillating:
            p = np.array(layout.pivot, dtype=float)
            along = np.hypot(*(state.contact - p).T)
        else:
            u = np.array([math.cos(layout.axis), math.sin(layout.axis)])
            n = np.array([-u[1], u[0]])
            along = (state.contact - state.point) @ n
        face = (float(np.min(along)), float(np.max(along)))
    return CamAnalysis(
        layout=layout,
        omega=None if omega is None else abs(omega),
        state=state,
        stroke=prog.stroke,
        pressure=pressure_max,
        least_radius=least,
        least_radius_any=least_any,
        undercut=undercut,
        cusp=cusp,
        velocity=velocity,
        acceleration=acceleration,
        jerk=jerk,
        velocity_jumps=_jumps(layout, 1),
        acceleration_jumps=_jumps(layout, 2),
        face=face,
    )
