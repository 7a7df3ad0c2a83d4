"""Where two lines meet, worked two ways that share no step.

An I-centre found by Kennedy's theorem is the meeting point of two lines through known
centres (I13 of a four-bar on AB and DC, I24 on AD and BC); these give it from the
four points alone, for the tests to compare against.

- :func:`line_intersection`: each line as ``a x + b y = c`` (normal (a, b) = the direction
  turned a quarter turn), the 2×2 system solved by Cramer's rule.
- :func:`meet`: the parametric form ``p1 + t (p2 − p1)``, t from the cross product with the
  other line's direction (:func:`meet_along`, for lines given by a point and a direction).

Parallel lines divide by zero in both (a ``ZeroDivisionError``): a test asks only where the
lines meet at a finite point.  ``tests/oracles/test_oracles.py`` checks the two against each
other and against a 3-4-5 triangle.  Nothing of mech is used.
"""

from __future__ import annotations

from typing import Any

__all__ = ["line_intersection", "meet", "meet_along"]


def line_intersection(p1: Any, p2: Any, q1: Any, q2: Any) -> tuple[float, float]:
    """Where line p1p2 meets line q1q2 (Cramer's rule on the two line equations)."""
    a1, b1 = p2[1] - p1[1], p1[0] - p2[0]
    c1 = a1 * p1[0] + b1 * p1[1]
    a2, b2 = q2[1] - q1[1], q1[0] - q2[0]
    c2 = a2 * q1[0] + b2 * q1[1]
    det = a1 * b2 - a2 * b1
    return ((c1 * b2 - c2 * b1) / det, (a1 * c2 - a2 * c1) / det)


def meet(p1: Any, p2: Any, q1: Any, q2: Any) -> tuple[float, float]:
    """Where line p1p2 meets line q1q2 (p1 + t·(p2 − p1), t by the cross product)."""
    return meet_along(p1, (p2[0] - p1[0], p2[1] - p1[1]), q1, (q2[0] - q1[0], q2[1] - q1[1]))


def meet_along(p: Any, d1: Any, q: Any, d2: Any) -> tuple[float, float]:
    """Where the line through ``p`` along ``d1`` meets the line through ``q`` along ``d2``.

    p + t·d1 = q + s·d2; crossing both sides with d2 leaves t = ((q − p) × d2) / (d1 × d2).
    """
    den = d1[0] * d2[1] - d1[1] * d2[0]
    t = ((q[0] - p[0]) * d2[1] - (q[1] - p[1]) * d2[0]) / den
    return (p[0] + t * d1[0], p[1] + t * d1[1])
