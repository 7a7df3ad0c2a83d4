"""The Peaucellier–Lipkin inversor: P runs on a straight line (derived by hand, no mech).

The crank QC = 1 turns about Q = (1, 0), so C = Q + (cos θ, sin θ) and |OC| = 2 cos(θ/2).
With OA = OB = 2 and the rhombus CA = CB = AP = BP = 1.2, O, C and P lie on the bisector of AB
and OC·OP = OA² − CA² = 4 − 1.44 = 2.56, so P is C inverted in the circle of radius 1.6 about
O: P = 1.28 along +x, on the line x = 1.28, with OP = 1.28 / cos(θ/2) and
P.y = √(OP² − 1.28²); its velocity is vertical, d(P.y)/dθ·ω.  The rhombus folds flat where
OC = OP (C = P, A–C–B in line): cos²(θ*/2) = 0.64, θ* = 2 acos(0.8) = 73.7397952917°, a change
point of the dyad that places P (past it a fixed-sign closed form would follow P = C).
"""

from __future__ import annotations

import math

import numpy as np

#: The change point θ* (rad) where the rhombus folds flat and P meets C.
FOLD = 2.0 * math.acos(0.8)


def inversor_p(theta):
    """(P.y, dP.y/dθ) on the line x = 1.28 at crank angle ``theta`` (rad; a float or an array)."""
    c, s = np.cos(theta / 2), np.sin(theta / 2)
    op = 1.28 / c
    dop = 1.28 * s / (2 * c * c)
    y = np.sqrt(op * op - 1.28**2)
    return y, op * dop / y


def inversor_by_circles(theta: float) -> tuple[float, float]:
    """P = A + B − C (the rhombus), A and B where the circles about O (r 2) and C (r 1.2) meet.

    A second derivation of P, from the links alone: it checks :func:`inversor_p`.
    """
    cx, cy = 1.0 + math.cos(theta), math.sin(theta)
    d = math.hypot(cx, cy)
    a = (4.0 - 1.44 + d * d) / (2.0 * d)  # from O along OC to the chord AB
    h = math.sqrt(4.0 - a * a)
    ux, uy = cx / d, cy / d
    ax, ay = a * ux - h * uy, a * uy + h * ux
    bx, by = a * ux + h * uy, a * uy - h * ux
    return ax + bx - cx, ay + by - cy
