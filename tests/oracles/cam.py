"""Cam references that do not use mech's generator: textbook laws, a follower put on a profile.

- :func:`textbook_rise`: the four classic rise laws written out from Khurmi & Gupta,
  *Theory of Machines*, ch. 20 (s, v = ω ds/dθ, a = ω² d²s/dθ²).
- :func:`lift_on_polygon`, :func:`lift_oscillating`: a profile taken as a bare polygon of
  points, the follower pushed down its line (or swung about its pivot) until it first touches
  it; the lift read there is what the programme asked for if the profile is right.
- :func:`three_point_radius`: the radius of curvature of a polygon by the circle through each
  point and its two neighbours (R = abc / 4·area).
- :func:`oscillating_pressure_angle`: mechanisms/cam_oscillating_roller.yaml's pressure angle
  from its numbers alone, by a central difference of the roller centre's path on the cam.

``tests/oracles/test_oracles.py`` checks the laws against finite differences of their own s,
the three-point radius on a circle and an ellipse, and the pressure angle over a dwell against
the triangle cam centre, pivot, roller centre.  Nothing of mech is used.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "lift_on_polygon",
    "lift_oscillating",
    "oscillating_pressure_angle",
    "textbook_rise",
    "three_point_radius",
]


def textbook_rise(law: str, th: float, S: float, BETA: float, OMEGA: float) -> tuple[float, float, float]:
    """s (m), v (m/s), a (m/s²) at cam angle ``th`` (rad) into a rise of ``S`` over ``BETA``, cam at ``OMEGA``.

    ``law``: ``uniform``, ``shm``, ``parabolic`` (uniform acceleration and retardation) or
    ``cycloidal``, written out from Khurmi & Gupta ch. 20 (v = ω ds/dθ, a = ω² d²s/dθ²).
    """
    x = th / BETA
    if law == "uniform":
        return S * x, OMEGA * S / BETA, 0.0
    if law == "shm":  # Khurmi: v = π ω S / (2 θ_O) sin(π θ/θ_O), a = π² ω² S / (2 θ_O²) cos(π θ/θ_O)
        return (
            S / 2 * (1 - math.cos(math.pi * x)),
            math.pi * OMEGA * S / (2 * BETA) * math.sin(math.pi * x),
            math.pi**2 * OMEGA**2 * S / (2 * BETA**2) * math.cos(math.pi * x),
        )
    if law == "parabolic":  # uniform acceleration then equal retardation
        if x <= 0.5:
            return 2 * S * x**2, 4 * OMEGA * S * th / BETA**2, 4 * OMEGA**2 * S / BETA**2
        return (
            S - 2 * S * (1 - x) ** 2,
            4 * OMEGA * S * (BETA - th) / BETA**2,
            -4 * OMEGA**2 * S / BETA**2,
        )
    assert law == "cycloidal"  # s = S(θ/θ_O − sin(2πθ/θ_O)/2π)
    return (
        S * (x - math.sin(2 * math.pi * x) / (2 * math.pi)),
        OMEGA * S / BETA * (1 - math.cos(2 * math.pi * x)),
        2 * math.pi * OMEGA**2 * S / BETA**2 * math.sin(2 * math.pi * x),
    )


def lift_on_polygon(
    poly: np.ndarray, follower: str, axis: float, e_n: float, start: float, roller: float = 0.0
) -> float:
    """The translating follower's lift when it rests on the polygon (cam frame already turned).

    ``e_n``: the line's distance from O along k × u; ``start``: the follower
    point's distance along u at zero lift; ``roller``: a roller follower's radius.  A knife
    edge meets the polygon where its line crosses an edge; a roller where the circle about its
    centre first touches a vertex; a flat face on the highest vertex.
    """
    u = np.array([math.cos(axis), math.sin(axis)])
    n = np.array([-u[1], u[0]])
    along = poly @ u
    side = poly @ n - e_n
    if follower == "flat":
        return float(np.max(along)) - start  # the face rests on the highest point
    if follower == "roller":
        ok = np.abs(side) <= roller
        return float(np.max(along[ok] + np.sqrt(roller**2 - side[ok] ** 2))) - start
    nxt = np.roll(np.arange(len(poly)), -1)
    cross = np.where(np.sign(side) != np.sign(side[nxt]))[0]
    j = nxt[cross]
    t = along[cross] + (along[j] - along[cross]) * (-side[cross]) / (side[j] - side[cross])
    return float(np.max(t)) - start


def lift_oscillating(poly: np.ndarray, pivot: np.ndarray, arm: float, psi_ref: float, roller: float) -> float:
    """The arm's angle at which it rests on the polygon: the roller (or edge) just touches it."""

    def gap(psi: float) -> float:
        c = pivot + arm * np.array([math.cos(psi), math.sin(psi)])
        if roller > 0:
            return float(np.min(np.hypot(*(poly - c).T))) - roller
        # a knife edge: is it outside the polygon? (winding number through the edge's position)
        rel = poly - c
        ang = np.arctan2(rel[:, 1], rel[:, 0])
        winding = np.sum(np.angle(np.exp(1j * (np.roll(ang, -1) - ang)))) / (2 * math.pi)
        dist = float(np.min(np.hypot(*rel.T)))
        return -dist if abs(winding) > 0.5 else dist

    lo, hi = psi_ref - 0.05, psi_ref + 0.05
    glo = gap(lo)
    assert glo * gap(hi) < 0
    for _ in range(50):
        mid = (lo + hi) / 2
        if (gap(mid) > 0) == (glo > 0):
            lo = mid
        else:
            hi = mid
    return (lo + hi) / 2


def three_point_radius(p: np.ndarray) -> np.ndarray:
    """The circle through each point and its neighbours: its radius (signed: + turning left)."""
    a, b, c = np.roll(p, 1, axis=0), p, np.roll(p, -1, axis=0)
    ab, bc, ca = np.hypot(*(b - a).T), np.hypot(*(c - b).T), np.hypot(*(a - c).T)
    cross = (b - a)[:, 0] * (c - b)[:, 1] - (b - a)[:, 1] * (c - b)[:, 0]
    return ab * bc * ca / (2 * cross)


def oscillating_pressure_angle(theta: float, h: float = 1e-6) -> float:
    """The oscillating example's pressure angle (deg) from its numbers alone (see the file).

    The roller centre C = P + L(cos ψ, sin ψ), ψ = ψ0 ∓ s(θ) (the sign that swings C away from O);
    its path relative to the cam is C turned back by θ (ccw cam); the tangent of that path, turned
    forward again, against C's direction of motion k × (C − P).
    """
    px, length, rp = 100.0, 80.0, 40.0
    x0 = (rp**2 - length**2 + px**2) / (2 * px)
    psi0 = math.atan2(math.sqrt(rp**2 - x0**2), x0 - px)

    def lift(th: float) -> float:
        d, rise = math.degrees(th) % 360, math.radians(20)
        if d < 90:
            x = d / 90
            return rise * (x - math.sin(2 * math.pi * x) / (2 * math.pi))
        if d < 150:
            return rise
        if d < 270:
            return rise - rise / 2 * (1 - math.cos(math.pi * (d - 150) / 120))
        return 0.0

    def centre(psi: float) -> tuple[float, float]:
        return px + length * math.cos(psi), length * math.sin(psi)

    away = 1.0 if math.hypot(*centre(psi0 + 1e-6)) > math.hypot(*centre(psi0)) else -1.0

    def relative(th: float) -> tuple[float, float]:
        cx, cy = centre(psi0 + away * lift(th))
        return math.cos(th) * cx + math.sin(th) * cy, -math.sin(th) * cx + math.cos(th) * cy

    a, b = relative(theta - h), relative(theta + h)
    c, s = math.cos(theta), math.sin(theta)
    tx, ty = c * (b[0] - a[0]) - s * (b[1] - a[1]), s * (b[0] - a[0]) + c * (b[1] - a[1])
    cx, cy = centre(psi0 + away * lift(theta))
    wx, wy = -away * cy, away * (cx - px)
    return math.degrees(math.atan2(tx * wx + ty * wy, abs(-tx * wy + ty * wx)))
