"""A single-cylinder engine's input torque over the cycle in closed form, and its integrals on a
fine grid: nothing of mech's.

The in-line slider crank (crank r about O, rod l, the piston B on +x) turns at a constant ω:
from the loop r sin θ + l sin φ = 0, x = r cos θ + l cos φ, differentiated twice (as
:func:`tests.oracles.slider_crank.slider_crank`, here on arrays).  The piston (mass m_p at B)
takes the gas force F(θ), read linearly off a table repeated every 720°; the rod has mass
m_r at G, ``g`` from the crank pin A along A→B, and I_G; the crank is balanced (its centre
at O).  The torque that holds the crank is then, by the power balance (the constraints do
no work; Khurmi & Gupta, *Theory of Machines*, § 15.11),

    T ω = m_p a_B v_B + m_r a_G·v_G + I_G α₃ ω₃ − F v_B − m_r g·v_G.

:func:`cycle_integrals` takes the trapezoid rule on a grid that holds every row of the table
(no kink inside a step), extrapolated from h and 2h (Richardson: the h² terms cancel), so
that its error is far below 1e-6: the mean torque, E(θ) = ∫ (T_mean − T) dθ, its greatest
and least (at the angles where the speed is greatest and least), ΔE and I = ΔE/(ω² C_s).
"""

from __future__ import annotations

import numpy as np

__all__ = ["cycle_integrals", "engine_torque"]


def engine_torque(
    th: np.ndarray,
    *,
    r: float,
    rod: float,
    w: float,
    m_p: float,
    m_r: float,
    g: float,
    inertia: float,
    table: list[tuple[float, float]],
    gravity: float = 9.81,
) -> np.ndarray:
    """The input torque (N·m, ccw +) at crank angles ``th`` (rad); ``table`` rows (deg, F_x on the piston)."""
    s, c = np.sin(th), np.cos(th)
    sp = -r * s / rod
    cp = np.sqrt(1.0 - sp * sp)
    x = r * c + rod * cp
    w3 = -r * w * c / (rod * cp)
    v_b = -r * w * s - rod * w3 * sp
    a3 = (r * w * w * s + rod * w3 * w3 * sp) / (rod * cp)
    a_b = -r * w * w * c - rod * a3 * sp - rod * w3 * w3 * cp
    ux, uy = (x - r * c) / rod, -r * s / rod
    gx, gy = g * ux, g * uy  # G − A
    vgx, vgy = -w * r * s - w3 * gy, w * r * c + w3 * gx
    agx = -w * w * r * c - a3 * gy - w3 * w3 * gx
    agy = -w * w * r * s + a3 * gx - w3 * w3 * gy
    rows = np.array(table, float)
    force = np.interp(np.degrees(th) % 720.0, rows[:, 0], rows[:, 1])
    power = m_p * a_b * v_b + m_r * (agx * vgx + agy * vgy) + inertia * a3 * w3 - force * v_b
    power += gravity * m_r * vgy  # − m g·v_G with g = (0, −9.81); the piston moves level
    return power / w


def _trapezoid(torque: np.ndarray, angles: np.ndarray) -> tuple[float, np.ndarray]:
    h = np.diff(angles)
    steps = h * (torque[:-1] + torque[1:]) / 2
    return float(steps.sum()), np.concatenate(([0.0], np.cumsum(steps)))


def cycle_integrals(
    torque: np.ndarray, angles: np.ndarray, w: float, coefficient: float
) -> tuple[float, float, float, float, float]:
    """T_mean, ΔE, the angles (rad) of the greatest and least E, and I = ΔE/(ω² C_s).

    ``angles`` must hold an odd number of evenly spaced steps' ends, every table row among
    them at an even index: the rule is taken on them and on every other one, and extrapolated.
    """
    fine, cum_fine = _trapezoid(torque, angles)
    coarse, cum_coarse = _trapezoid(torque[::2], angles[::2])
    work = (4 * fine - coarse) / 3
    cum = (4 * cum_fine[::2] - cum_coarse) / 3
    span = angles[-1] - angles[0]
    mean = work / span
    e = mean * (angles[::2] - angles[0]) - cum
    de = float(e.max() - e.min())
    hi, lo = float(angles[::2][int(np.argmax(e))]), float(angles[::2][int(np.argmin(e))])
    return mean, de, hi, lo, de / (w * w * coefficient)
