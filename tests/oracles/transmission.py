"""The four-bar's transmission angle and which of its links turn, from the law of cosines.

Frame d (A to D), crank a (A to B), coupler b (B to C), rocker c (D to C); arguments in that
order, frame first, as Grashof's condition is written (the closed forms of
:mod:`oracles.four_bar` take a, b, c, d).  Everything turns on the diagonal BD:

- in triangle A, B, D:  BD² = a² + d² − 2ad·cos θ, so BD runs over [|d − a|, d + a];
- in triangle B, C, D:  the loop closes while |b − c| ≤ BD ≤ b + c, and the transmission
  angle μ (between coupler and rocker, at C) has  cos μ = (b² + c² − BD²) / (2bc).

:func:`transmission_angle` is the cosine rule at a crank angle; :func:`transmission_angle_at`
is its half-angle form at a given BD, tan(μ/2) = √((BD² − (b − c)²) / ((b + c)² − BD²)), exact
at the ends where acos loses digits (μ = 0 and π).  ``tests/oracles/test_oracles.py`` checks
the two forms against each other.

:func:`turning_by_sampling` says which moving links turn fully relative to the frame from the
loop itself, not from Grashof's rule: a link turns fully when the loop closes at every angle of
it.  For the crank AB (a) the loop closes at crank angle θ when BD lies in [|b − c|, b + c],
BD running over [|d − a|, d + a] as θ turns; for the rocker DC (c), when AC = |d e_x + c e(ψ)|
lies in [|a − b|, a + b]; for the coupler's direction φ, when |b e(φ) − d e_x| lies in
[|a − c|, a + c] (the loop written a e(θ) − c e(ψ) = d e_x − b e(φ)).  Each is sampled on a grid of 3,600 angles (0.1°), so the answer
is trusted away from s + l = p + q by more than that grid resolves.  Nothing of mech is used.
"""

from __future__ import annotations

import math
from collections.abc import Callable

__all__ = [
    "crank_turns",
    "diagonal_range",
    "transmission_angle",
    "transmission_angle_at",
    "turning_by_sampling",
]

SAMPLES = [2 * math.pi * k / 3600 for k in range(3600)]


def transmission_angle(d: float, a: float, b: float, c: float, theta: float) -> float:
    """μ (rad) at crank angle ``theta`` (rad from AD), by the law of cosines twice."""
    bd2 = a * a + d * d - 2 * a * d * math.cos(theta)
    return math.acos((b * b + c * c - bd2) / (2 * b * c))


def crank_turns(d: float, a: float, b: float, c: float) -> bool:
    """BD runs over [|d − a|, d + a]; the loop closes while BD is within [|b − c|, b + c]."""
    return abs(b - c) < abs(d - a) and d + a < b + c


def diagonal_range(d: float, a: float, b: float, c: float) -> tuple[float, float]:
    """The diagonal BD the loop can take: BD(θ) ∈ [|d − a|, d + a] and the closure [|b − c|, b + c]."""
    return max(abs(d - a), abs(b - c)), min(d + a, b + c)


def transmission_angle_at(b: float, c: float, bd: float) -> float:
    """μ (rad) at diagonal ``bd``: the cosine rule in its half-angle form, exact at the ends.

    μ = 0 at BD = |b − c|, π at b + c:  tan(μ/2) = √((BD² − (b − c)²) / ((b + c)² − BD²)).
    """
    return 2 * math.atan2(
        math.sqrt(max(bd * bd - (b - c) ** 2, 0.0)), math.sqrt(max((b + c) ** 2 - bd * bd, 0.0))
    )


def _closes_for_every(dist: Callable[[float], float], lo: float, hi: float) -> bool:
    return all(lo <= dist(t) <= hi for t in SAMPLES)


def turning_by_sampling(d: float, a: float, b: float, c: float) -> set[str]:
    """Moving links ("crank", "coupler", "rocker") that turn fully relative to the frame, from
    loop closure at every sampled angle of each."""
    out = set()
    if _closes_for_every(lambda t: math.hypot(a * math.cos(t) - d, a * math.sin(t)), abs(b - c), b + c):
        out.add("crank")
    if _closes_for_every(lambda t: math.hypot(d + c * math.cos(t), c * math.sin(t)), abs(a - b), a + b):
        out.add("rocker")
    if _closes_for_every(lambda t: math.hypot(b * math.cos(t) - d, b * math.sin(t)), abs(a - c), a + c):
        out.add("coupler")
    return out
