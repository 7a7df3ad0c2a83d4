"""Points and lines in homogeneous coordinates, points at infinity included.

Why homogeneous: Kennedy's construction joins I-centres by lines and meets
lines in points, and I-centres at infinity (a slider's, a translating link's)
take part like any other.  In homogeneous coordinates a point is ``(x, y, w)``
— ``w = 0`` is the point at infinity in direction ``(x, y)`` — and a line is
``(a, b, c)`` meaning ``a x + b y + c w = 0``.  The line through two points and
the meeting point of two lines are the same operation, the cross product, so
parallel lines meet (at infinity) without a special case and nothing is
divided before we decide whether a point is at infinity.

Every function here works in the mechanism's own units: coordinates are
shifted to the mechanism's centre and divided by its size (see
:class:`Frame`), so a tolerance such as :data:`AT_INFINITY` means the same for
a 1 µm linkage and a 1 km one.  Vectors are normalised to unit Euclidean norm
in R³; the norm of a cross product of two unit vectors is then the sine of the
angle between them, which is how well-defined the join or meet is (near 0:
the two points coincide, or the two lines do).

Reference: Hartley & Zisserman, *Multiple View Geometry*, 2nd ed., §2.2
(points and lines of the projective plane, ideal points, the line at infinity).
"""

from __future__ import annotations

import math

from mech._records import dataclass

__all__ = [
    "AT_INFINITY",
    "Frame",
    "Hom",
    "at_infinity",
    "cross",
    "ideal",
    "join",
    "line_along",
    "meet",
    "norm",
    "point",
    "separation",
    "unit",
]

Vec = tuple[float, float]
Hom = tuple[float, float, float]

#: A point is at infinity when ``|w| ≤ AT_INFINITY · |(x, y)|`` in size units,
#: i.e. farther than 1e10 sizes away.  Directions known to the solver's
#: accuracy (≈ 1e-12) cannot tell lines closer to parallel than this apart.
AT_INFINITY = 1e-10


def cross(a: Hom, b: Hom) -> Hom:
    """The cross product ``a × b`` (the line through two points, or the meet of two lines)."""
    return (
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    )


join = cross
meet = cross


def norm(h: Hom) -> float:
    """Euclidean norm in R³ (overflow-safe)."""
    return math.hypot(h[0], h[1], h[2])


def unit(h: Hom) -> Hom:
    """``h`` scaled to unit norm (the zero vector stays zero: it means "undefined")."""
    n = norm(h)
    if n == 0.0:
        return h
    return (h[0] / n, h[1] / n, h[2] / n)


def point(xy: Vec) -> Hom:
    """The homogeneous point of finite ``(x, y)``."""
    return (float(xy[0]), float(xy[1]), 1.0)


def ideal(direction: Vec) -> Hom:
    """The point at infinity in ``direction`` (and in the opposite one: they are the same point)."""
    return (float(direction[0]), float(direction[1]), 0.0)


def line_along(p: Hom, direction: Vec) -> Hom:
    """The line through point ``p`` with the given direction."""
    return join(p, ideal(direction))


def at_infinity(h: Hom, rel: float = AT_INFINITY) -> bool:
    """True when ``h`` (size units) lies farther than ``1/rel`` sizes away.

    The test compares ``|w|`` with ``rel · |(x, y)|`` and never divides, so a
    point with ``w`` = 1e-300 is a clean "at infinity", not an overflow.
    """
    return abs(h[2]) <= rel * math.hypot(h[0], h[1])


def separation(a: Hom, b: Hom) -> float:
    """Distance between two points of the projective plane (chordal, sign-free).

    ``min(|â − b̂|, |â + b̂|)`` for the unit vectors â, b̂.  For points within
    the mechanism (size units, |p| ≲ 1) it is about ``|Δp| / size``; for far
    points it measures the error relative to their distance, and at infinity
    the difference of directions — the natural yardstick for comparing two
    computations of an I-centre, one of which may be at infinity.
    """
    ua, ub = unit(a), unit(b)
    minus = math.hypot(ua[0] - ub[0], ua[1] - ub[1], ua[2] - ub[2])
    plus = math.hypot(ua[0] + ub[0], ua[1] + ub[1], ua[2] + ub[2])
    return min(minus, plus)


@dataclass(frozen=True, slots=True)
class Frame:
    """Size units: global metres shifted by ``origin`` and divided by ``size``.

    Parameters
    ----------
    origin
        A point near the mechanism's centre, m.
    size
        The mechanism's characteristic length (largest joint distance), m.

    Examples
    --------
    >>> f = Frame((1.0, 2.0), 0.5)
    >>> f.hom((1.5, 2.0))
    (1.0, 0.0, 1.0)
    >>> f.xy((1.0, 0.0, 1.0))
    (1.5, 2.0)
    """

    origin: Vec
    size: float

    def hom(self, xy: Vec) -> Hom:
        """Global ``(x, y)`` (m) as a homogeneous point in size units."""
        return ((xy[0] - self.origin[0]) / self.size, (xy[1] - self.origin[1]) / self.size, 1.0)

    def xy(self, h: Hom) -> Vec:
        """A finite homogeneous point (size units) back to global metres.

        Call only after :func:`at_infinity` said no: then ``w`` is not small
        against ``(x, y)`` and the division is safe.
        """
        return (self.origin[0] + self.size * h[0] / h[2], self.origin[1] + self.size * h[1] / h[2])

    @staticmethod
    def direction(h: Hom) -> Vec:
        """The unit direction of a point at infinity, turned into [0°, 180°).

        A point at infinity is one point for ``u`` and ``−u``; the canonical
        half-turn makes reports and comparisons stable.
        """
        x, y = h[0], h[1]
        n = math.hypot(x, y)
        x, y = x / n, y / n
        if y < 0.0 or (y == 0.0 and x < 0.0):
            x, y = -x, -y
        return (x + 0.0, y + 0.0)
