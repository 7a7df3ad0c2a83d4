"""Closed-form planar primitives: circle intersections, homogeneous lines, angles.

Pure functions on plain floats (no numpy), each with an explicit branch
argument and a clear answer when there is no solution (``None`` plus the gap),
never a silent NaN.  The assembler uses them for its first guess of every
dyad; the I-centre module may use the homogeneous lines.

Homogeneous coordinates: a point is ``(x, y, w)`` (``w = 0`` is a point at
infinity in direction ``(x, y)``); a line is ``(a, b, c)`` meaning
``a x + b y + c w = 0``.  The line through two points and the meeting point of
two lines are both cross products, so no division happens before the caller
tests ``w`` against its own scaled tolerance.
"""

from __future__ import annotations

import math

__all__ = [
    "circle_circle",
    "circle_line",
    "cross",
    "is_at_infinity",
    "left_of",
    "line_through",
    "meet",
    "wrap_angle",
]

Vec = tuple[float, float]
Hom = tuple[float, float, float]

#: relative slack under which two curves that miss are taken as touching (tangent)
_TANGENT = 1e-12


def cross(a: Vec, b: Vec) -> float:
    """The z component of ``a × b`` (positive when b is counter-clockwise of a)."""
    return a[0] * b[1] - a[1] * b[0]


def left_of(p: Vec, a: Vec, b: Vec) -> bool:
    """True when ``p`` lies strictly to the left of the directed line ``a → b``."""
    return cross((b[0] - a[0], b[1] - a[1]), (p[0] - a[0], p[1] - a[1])) > 0.0


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


def line_through(p: Hom, q: Hom) -> Hom:
    """The homogeneous line through two homogeneous points (their cross product)."""
    return (
        p[1] * q[2] - p[2] * q[1],
        p[2] * q[0] - p[0] * q[2],
        p[0] * q[1] - p[1] * q[0],
    )


def meet(l1: Hom, l2: Hom) -> Hom:
    """The homogeneous meeting point of two lines (``w = 0``: parallel lines)."""
    return line_through(l1, l2)


def is_at_infinity(p: Hom, size: float, *, rel: float = 1e-9) -> bool:
    """True when ``p`` is farther than ``size / rel`` away, i.e. ``|w|·size/rel ≤ |(x, y)|``."""
    return abs(p[2]) * size <= rel * math.hypot(p[0], p[1])
