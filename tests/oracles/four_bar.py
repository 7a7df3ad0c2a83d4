"""The four-bar chain in closed form: positions, angular velocities and accelerations, limits.

Crank AB about A = (0, 0), coupler BC, rocker CD about D = (d, 0).  Derived here from the
geometry alone: C by intersecting the circles about B and D, the velocities and
accelerations from the vector loop differentiated once and twice (Raven's method, e.g.
Norton, *Design of Machinery*, § 6.7 and § 7.3), the rocker's limit positions from the law
of cosines (crank and coupler in line).  :func:`four_bar_clear_of_toggle` is the same loop
refused (``None``) where the chain does not close, or closes too near a toggle for its
velocities to be well conditioned.  Nothing of mech is used.
"""

from __future__ import annotations

import math
from typing import Any

import mpmath
import numpy as np

__all__ = [
    "crank_rocker_limits",
    "crank_rocker_sweep",
    "four_bar",
    "four_bar_clear_of_toggle",
    "rocker_angle",
    "rocker_swing",
]

Point = tuple[float, float]


def _k(v: np.ndarray) -> np.ndarray:
    """k × v: v turned a quarter turn anticlockwise."""
    return np.array([-v[1], v[0]])


def four_bar(
    a: float, b: float, c: float, d: float, theta: float, w2: float, al2: float = 0.0, upper: bool = True
) -> tuple[np.ndarray, float, float, float, float]:
    """C, ω3, ω4, α3, α4 of the four-bar at crank angle ``theta`` (rad), crank ω2 and α2.

    ``upper``: C left of the line B→D (the other assembly otherwise).  The vector loop:
    v_B + ω3 k×BC = ω4 k×DC ;  a_B + α3 k×BC − ω3² BC = α4 k×DC − ω4² DC.
    """
    B = np.array([a * math.cos(theta), a * math.sin(theta)])
    D = np.array([d, 0.0])
    f = D - B
    L = float(np.hypot(*f))
    x = (b * b - c * c + L * L) / (2 * L)
    h = math.sqrt(b * b - x * x)
    e = f / L
    perp = np.array([-e[1], e[0]])
    C = B + x * e + (h if upper else -h) * perp
    BC, DC = C - B, C - D
    vB = w2 * _k(B)
    M = np.column_stack([_k(BC), -_k(DC)])
    w3, w4 = np.linalg.solve(M, -vB)
    aB = al2 * _k(B) - w2**2 * B
    rhs = -(aB - w3**2 * BC + w4**2 * DC)
    a3, a4 = np.linalg.solve(M, rhs)
    return C, float(w3), float(w4), float(a3), float(a4)


def four_bar_clear_of_toggle(
    a: float,
    b: float,
    c: float,
    d: float,
    theta: float,
    w2: float,
    *,
    upper: bool = True,
    margin: float = 0.0,
    least_det: float = 0.0,
) -> tuple[tuple[Point, Point, Point, Point], tuple[float, float, float]] | None:
    """Pins A, B, C, D and (ω2, ω3, ω4) of :func:`four_bar`, or ``None`` near a toggle.

    The chain closes at crank angle ``theta`` when the diagonal BD (triangle A, B, D) lies
    within [|b − c|, b + c] (triangle B, C, D); ``None`` unless it lies more than ``margin``
    inside.  The velocity loop's matrix [k×BC, −k×DC] has determinant −BC × DC = −bc sin μ
    (μ the transmission angle), which vanishes at a toggle where ω3 and ω4 grow without
    bound: ``None`` too when its size is ``least_det`` or less.  Otherwise the positions of
    :func:`four_bar` as tuples, and its angular velocities with the crank's ω2 first.
    """
    B = (a * math.cos(theta), a * math.sin(theta))
    bd = math.hypot(d - B[0], -B[1])
    if not abs(b - c) + margin < bd < b + c - margin:
        return None
    C, w3, w4, _, _ = four_bar(a, b, c, d, theta, w2, upper=upper)
    cross = (C[0] - B[0]) * (C[1] - 0.0) - (C[1] - B[1]) * (C[0] - d)
    if abs(cross) <= least_det:
        return None
    return ((0.0, 0.0), B, (float(C[0]), float(C[1])), (d, 0.0)), (w2, w3, w4)


def crank_rocker_sweep(
    a: float, b: float, c: float, d: float, theta_deg: np.ndarray | float, omega: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Over many crank angles at once (deg), C left of B→D: rocker angle (deg), ω4, ω3, |v_C|.

    The same loop as :func:`four_bar`, vectorised, with ω3 and ω4 by Cramer's rule from
    ``[-BCy DCy; BCx -DCx] [ω3 ω4]ᵀ = -v_B``.
    """
    th = np.radians(np.asarray(theta_deg, float))
    B = np.stack([a * np.cos(th), a * np.sin(th)], -1)
    D = np.array([d, 0.0])
    BD = D - B
    r = np.linalg.norm(BD, axis=-1)
    x = (b * b - c * c + r * r) / (2 * r)
    h = np.sqrt(b * b - x * x)
    u = BD / r[..., None]
    nrm = np.stack([-u[..., 1], u[..., 0]], -1)  # left of B->D
    C = B + x[..., None] * u + h[..., None] * nrm
    vB = omega * np.stack([-B[..., 1], B[..., 0]], -1)
    BC, DC = C - B, C - D
    det = (-BC[..., 1]) * (-DC[..., 0]) - DC[..., 1] * BC[..., 0]
    w3 = ((-vB[..., 0]) * (-DC[..., 0]) - DC[..., 1] * (-vB[..., 1])) / det
    w4 = ((-BC[..., 1]) * (-vB[..., 1]) - (-vB[..., 0]) * BC[..., 0]) / det
    psi = np.degrees(np.arctan2(DC[..., 1], DC[..., 0]))
    return psi, w4, w3, np.abs(w4) * c


def crank_rocker_limits(a: float, b: float, c: float, d: float) -> tuple[float, float, float]:
    """Crank angles (deg) of the rocker's limit positions and the time ratio (180 + α)/(180 − α).

    Crank and coupler in line: extended (AC = a + b, crank along AC) and folded (AC = b − a,
    crank opposite AC); the angle DAC by the law of cosines in triangle A, D, C (C above AD).
    """

    def dac(AC: float) -> float:
        return math.degrees(math.acos((AC * AC + d * d - c * c) / (2 * AC * d)))

    t_ext, t_fold = dac(a + b), dac(b - a) + 180.0
    alpha = t_fold - t_ext - 180.0
    return t_ext, t_fold, (180 + alpha) / (180 - alpha)


def rocker_angle(a: float, b: float, c: float, d: float, th: Any) -> Any:
    """Direction D→C of the rocker in mpmath (C left of B→D, the drawn branch), for exact derivatives.

    The same circle intersection as :func:`four_bar`, written in mpmath so that ``mpmath.diff``
    gives ω4/ω2 to 30 digits.
    """
    bx, by = a * mpmath.cos(th), a * mpmath.sin(th)
    dx, dy = d - bx, -by
    f = mpmath.sqrt(dx**2 + dy**2)
    t = (b**2 - c**2 + f**2) / (2 * f)
    h = mpmath.sqrt(b**2 - t**2)
    cx = bx + t * dx / f - h * dy / f
    cy = by + t * dy / f + h * dx / f
    return mpmath.atan2(cy, cx - d)


def rocker_swing(a: float, b: float, c: float, d: float, theta0: float) -> float | None:
    """The rocker's swing (rad) over one turn of the crank, θ from 0 to 2π, or None when it turns (never turns back).

    For a crank that turns fully.  C is left of B→D at the drawn angle ``theta0`` and keeps the
    branch with a continuous tangent: it changes side at each change point between θ0 and θ,
    where BD touches |b − c| (at θ = 0, when |d − a| = |b − c|) or b + c (at θ = π, when
    d + a = b + c) and the two positions of C meet.  ψ(θ), the direction D→C, is read on 4,096
    angles, unwrapped; it turns when it comes back a whole turn on at θ = 2π.  Otherwise each
    local extreme is refined by golden section on the closed form, and the ends of the turn
    count too (a branch that changed side need not come back to its start).
    """
    flips = [t for t, touch in ((math.pi, d + a == b + c),) if touch]

    def psi(th: np.ndarray) -> np.ndarray:
        th = np.asarray(th, float)
        side = np.ones_like(th)
        for t in flips:  # a change point strictly between the drawn angle and θ
            side = np.where((th - t) * (theta0 - t) < 0, -side, side)
        bx, by = a * np.cos(th), a * np.sin(th)
        fx, fy = d - bx, -by
        f = np.hypot(fx, fy)
        x = (b * b - c * c + f * f) / (2 * f)
        h = np.sqrt(np.maximum(b * b - x * x, 0.0))
        cx = bx + x * fx / f - side * h * fy / f
        cy = by + x * fy / f + side * h * fx / f
        return np.arctan2(cy, cx - d)

    grid = np.linspace(0.0, 2 * math.pi, 4097)
    v = np.unwrap(psi(grid))
    # it turns when it never turns back: over a whole turn of the crank it then comes back a whole
    # turn on, or, past a change point, runs on and comes round after a second turn (a change-point
    # four-bar's rocker running 185° on over one turn); one that turns back swings, between its
    # least and greatest (another runs 211° on between 35° and 325°: a swing of 290°)
    step = np.diff(v)
    if bool(np.all(step >= 0.0)) or bool(np.all(step <= 0.0)):
        return None
    values = [float(v[0]), float(v[-1])]
    for k in range(1, grid.size - 1):
        for sign in (1.0, -1.0):
            if sign * v[k] >= sign * v[k - 1] and sign * v[k] >= sign * v[k + 1]:
                lo, hi = grid[k - 1], grid[k + 1]
                ref = v[k]

                def f(t: float, sign: float = sign, ref: float = float(ref)) -> float:
                    y = float(psi(np.array([t]))[0])
                    return -sign * (y + 2 * math.pi * round((ref - y) / (2 * math.pi)))

                g = (math.sqrt(5.0) - 1.0) / 2.0
                x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
                f1, f2 = f(x1), f(x2)
                for _ in range(80):
                    if f1 < f2:
                        hi, x2, f2 = x2, x1, f1
                        x1 = hi - g * (hi - lo)
                        f1 = f(x1)
                    else:
                        lo, x1, f1 = x1, x2, f2
                        x2 = lo + g * (hi - lo)
                        f2 = f(x2)
                values.append(-sign * min(f1, f2))
    return max(values) - min(values)
