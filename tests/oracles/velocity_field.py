"""The velocity field of a planar chain from its constraints alone, and its I-centres.

Derived from rigid-body kinematics only: every moving link has an unknown (u, w), the
velocity u of its point at the origin and its angular velocity w, so that v(P) = u + w k×P.
Each joint is written out as linear equations in those unknowns, the drive adds one more,
and a least-squares solve (which must be exact: full rank, zero residual) gives the field.
Nothing of mech is used: not its loader, its solver nor its I-centre construction.
An I-centre of links a and b is then the one point where v_a(P) = v_b(P).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

__all__ = ["Field", "icentre", "velocity_field"]

Field = dict[str, tuple[np.ndarray, float]]


def velocity_field(
    links: Sequence[str], ground: str, constraints: Sequence[tuple[Any, ...]], drive: tuple[Any, ...]
) -> Field:
    """Velocity field of every link from the constraints alone: link -> (u, w).

    u is the velocity of the link's point at the origin, w its angular velocity, so
    v(P) = u + w k x P.  Constraints: ("pin", P, a, b): v_a(P) = v_b(P); ("normal", P, a, b, n):
    n . (v_a(P) - v_b(P)) = 0 (cam, gear, slot); ("prismatic", P, a, b, t): the same across
    the path t, and w_a = w_b.  drive: (link, w) or ("slide", P, slider, t, speed).
    """
    moving = [lk for lk in links if lk != ground]
    idx = {lk: 3 * i for i, lk in enumerate(moving)}
    n = 3 * len(moving)

    def vrow(lk: str, P: Any) -> np.ndarray:
        M = np.zeros((2, n))
        if lk != ground:
            i = idx[lk]
            M[0, i], M[1, i + 1], M[0, i + 2], M[1, i + 2] = 1, 1, -P[1], P[0]
        return M

    def wrow(lk: str) -> np.ndarray:
        r = np.zeros(n)
        if lk != ground:
            r[idx[lk] + 2] = 1
        return r

    rows: list[np.ndarray] = []
    rhs: list[float] = []
    for c in constraints:
        if c[0] == "pin":
            _, P, a, b = c
            rows += list(vrow(a, P) - vrow(b, P))
            rhs += [0.0, 0.0]
        elif c[0] == "normal":
            _, P, a, b, nn = c
            rows.append(np.asarray(nn, float) @ (vrow(a, P) - vrow(b, P)))
            rhs.append(0.0)
        elif c[0] == "prismatic":
            _, P, a, b, t = c
            rows.append(np.array([-t[1], t[0]], float) @ (vrow(a, P) - vrow(b, P)))
            rows.append(wrow(a) - wrow(b))
            rhs += [0.0, 0.0]
        else:
            raise ValueError(f"unknown constraint {c[0]!r}")
    if drive[0] == "slide":
        _, P, slider, t, speed = drive
        rows.append(np.asarray(t, float) @ vrow(slider, P))
        rhs.append(speed)
    else:
        rows.append(wrow(drive[0]))
        rhs.append(drive[1])
    A, b = np.array(rows), np.array(rhs)
    x = np.linalg.lstsq(A, b, rcond=None)[0]
    if np.linalg.matrix_rank(A) != n or not np.allclose(A @ x, b, atol=1e-10 * np.abs(b).max()):
        raise ValueError("the constraints do not fix one velocity field (rank or residual)")
    out: Field = {ground: (np.zeros(2), 0.0)}
    for lk in moving:
        out[lk] = (x[idx[lk] : idx[lk] + 2], float(x[idx[lk] + 2]))
    return out


def icentre(field: Field, a: str, b: str) -> tuple[np.ndarray | None, np.ndarray | None]:
    """The point where v_a = v_b: P = k x (u_a - u_b) / (w_a - w_b); (None, direction) at infinity.

    (None, None) when a and b do not move relative to each other (any point will do).
    """
    (ua, wa), (ub, wb) = field[a], field[b]
    vrel, dw = ua - ub, wa - wb
    wmax = max(abs(w) for _, w in field.values())
    k = np.array([-vrel[1], vrel[0]])
    if abs(dw) <= 1e-12 * wmax:
        norm = np.linalg.norm(k)
        return None, (k / norm if norm > 1e-12 else None)
    return k / dw, None
