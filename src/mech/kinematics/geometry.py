"""Closed-form planar primitives: circle intersections and angles.

Pure functions on plain floats (no numpy), each with an explicit branch
argument and a clear answer when there is no solution (``None`` plus the gap),
never a silent NaN.  The assembler uses them for its first guess of every
dyad.  Lines and points at infinity in homogeneous coordinates live in
:mod:`mech.icentres.homogeneous`, where Kennedy's construction needs them.
"""

from __future__ import annotations

import math

__all__ = ["circle_circle", "circle_line", "cross", "wrap_angle"]

Vec = tuple[float, float]

#: relative slack under which two curves that miss are taken as touching (tangent)
_TANGENT = 1e-12


def cross(a: Vec, b: Vec) -> float:
    """The z component of ``a × b`` (positive when b is counter-clockwise of a)."""
    return a[0] * b[1] - a[1] * b[0]


def wrap_angle(angle: float) -> float:
    """``angle`` (rad) brought into (−π, π]."""
    a = math.remainder(angle, 2.0 * math.pi)
    return math.pi if a == -math.pi else a


def circle_circle(c1: Vec, r1: float, c2: Vec, r2: float, *, left: bool = True) -> tuple[Vec | None, float]:
    """Apex of the dyad: the point at ``r1`` from ``c1`` and ``r2`` from ``c2``.

    Parameters
    ----------
    c1, c2
        Circle centres (any length unit; the answer is in the same unit).
    r1, r2
        Radii, non-negative.
    left
        Which of the two intersections: the one to the left of ``c1 → c2``
        (counter-clockwise side) when True, else the right one.

    Returns
    -------
    (point, gap)
        ``point`` is None when the circles do not meet; ``gap`` is then how far
        apart they are at their closest (positive, same unit), else 0.

    Examples
    --------
    >>> circle_circle((0.0, 0.0), 5.0, (6.0, 0.0), 5.0)
    ((3.0, 4.0), 0.0)
    """
    dx, dy = c2[0] - c1[0], c2[1] - c1[1]
    d = math.hypot(dx, dy)
    slack = _TANGENT * (r1 + r2 + d)  # rounding of a drawn tangency is not a gap
    if d == 0.0:
        return None, abs(r1 - r2)
    if d > r1 + r2 + slack:
        return None, d - (r1 + r2)
    if d < abs(r1 - r2) - slack:
        return None, abs(r1 - r2) - d
    a = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d)
    h = math.sqrt(max(r1 * r1 - a * a, 0.0))
    ex, ey = dx / d, dy / d
    sign = 1.0 if left else -1.0
    return (c1[0] + a * ex - sign * h * ey, c1[1] + a * ey + sign * h * ex), 0.0


def circle_line(c: Vec, r: float, p: Vec, u: Vec, *, forward: bool = True) -> tuple[Vec | None, float]:
    """The point at ``r`` from ``c`` on the line through ``p`` along unit ``u``.

    ``forward`` picks the intersection farther along ``u`` (the slider-crank
    default: the slider ahead of the crank along its path).  Returns
    ``(None, gap)`` when the line passes farther than ``r`` from ``c``.

    Examples
    --------
    >>> circle_line((0.0, 0.0), 5.0, (0.0, 3.0), (1.0, 0.0))
    ((4.0, 3.0), 0.0)
    """
    wx, wy = p[0] - c[0], p[1] - c[1]
    along = wx * u[0] + wy * u[1]
    off = cross(u, (wx, wy))  # signed distance of the line from c
    if abs(off) > r + _TANGENT * (r + abs(off)):
        return None, abs(off) - r
    h = math.sqrt(max(r * r - off * off, 0.0))
    s = -along + (h if forward else -h)
    return (p[0] + s * u[0], p[1] + s * u[1]), 0.0
