"""Forces by Newton–Euler, link by link, for a four-bar with masses: nothing of mech's.

Crank 2 about A = (0, 0), coupler 3, rocker 4 about D = (d, 0).  Each link's centre G is
given by a distance along its line (A→B, B→C, D→C); the kinematics comes from the vector
loop (:func:`tests.oracles.four_bar.four_bar`).  The unknowns are the pin forces
F_A (on the crank from the frame), F_B (on the coupler from the crank), F_C (on the rocker
from the coupler), F_D (on the rocker from the frame) and the input torque T on the crank;
each moving link gives ΣF = m a_G and ΣM_G = I_G α: nine equations, nine unknowns, one
dense solve (e.g. Norton, *Design of Machinery*, § 11.4, "force analysis of a fourbar").
"""

from __future__ import annotations

import math

import numpy as np
from tests.oracles.four_bar import four_bar

__all__ = ["four_bar_forces"]


def four_bar_forces(
    lengths: tuple[float, float, float, float],
    theta: float,
    w2: float,
    masses: dict[str, tuple[float, float, float]],
    gravity: tuple[float, float] = (0.0, 0.0),
) -> dict[str, object]:
    """F_A, F_B, F_C, F_D (N, arrays) and T (N·m) of the four-bar at crank angle ``theta``, ω2 constant.

    ``masses``: link → (mass, inertia about G, distance of G along the link's line).
    """
    a, b, c, d = lengths
    C, w3, w4, a3, a4 = four_bar(a, b, c, d, theta, w2, 0.0)
    A, D = np.zeros(2), np.array([d, 0.0])
    B = np.array([a * math.cos(theta), a * math.sin(theta)])

    def k(v: np.ndarray) -> np.ndarray:
        return np.array([-v[1], v[0]])

    aB = -(w2**2) * B
    lines = {
        "crank": (A, B, w2, 0.0, A, np.zeros(2)),
        "coupler": (B, C, w3, a3, B, aB),
        "rocker": (D, C, w4, a4, D, np.zeros(2)),
    }
    g = np.array(gravity)
    G, aG, alpha = {}, {}, {}
    for link, (p, q, w, al, base, a_base) in lines.items():
        _, _, dist = masses[link]
        u = (q - p) / np.linalg.norm(q - p)
        G[link] = p + dist * u
        r = G[link] - base
        aG[link] = a_base + al * k(r) - w * w * r
        alpha[link] = al
    # unknowns x = [FAx, FAy, FBx, FBy, FCx, FCy, FDx, FDy, T]
    M = np.zeros((9, 9))
    rhs = np.zeros(9)
    plan = {
        "crank": [(0, A, +1), (2, B, -1)],
        "coupler": [(2, B, +1), (4, C, -1)],
        "rocker": [(4, C, +1), (6, D, +1)],
    }
    for row, link in enumerate(("crank", "coupler", "rocker")):
        m, inertia, _ = masses[link]
        for col, at, sign in plan[link]:
            M[3 * row, col] += sign
            M[3 * row + 1, col + 1] += sign
            r = at - G[link]
            M[3 * row + 2, col] += sign * -r[1]
            M[3 * row + 2, col + 1] += sign * r[0]
        if link == "crank":
            M[2, 8] = 1.0
        rhs[3 * row : 3 * row + 2] = m * aG[link] - m * g
        rhs[3 * row + 2] = inertia * alpha[link]
    x = np.linalg.solve(M, rhs)
    return {
        "A": x[0:2],
        "B": x[2:4],
        "C": x[4:6],
        "D": x[6:8],
        "T": float(x[8]),
        "G": G,
        "aG": aG,
        "omega": {"crank": w2, "coupler": w3, "rocker": w4},
        "alpha": alpha,
    }
