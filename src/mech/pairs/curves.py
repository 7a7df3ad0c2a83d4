"""Closed smooth profiles: a periodic cubic spline, and the contact rows it gives with Φ_q and γ.

A ``curve`` profile (a cam's generated surface, or a file's points) is the
periodic cubic spline through its points, parametrised by the point index
``u ∈ [0, N)``.  Why this curve: it passes through every point given; it is
C² (position, tangent and curvature continuous), and the curvature is what
an acceleration analysis reads from a profile — a polyline's curvature is
zero or infinite, a C¹ curve's jumps, and accelerations would jump with it;
it is closed without a seam; and it is cheap and exact to build, since its
second derivatives solve one circulant system (Σ M_{i±1} + 4 M_i =
6 Δ²P_i), diagonalised by the FFT.  (De Boor, *A Practical Guide to
Splines*, ch. IV; periodic end conditions.)

Two contact rows use it (the curve on link C, the other profile on link O;
all in scaled reference-point coordinates):

*point* (a knife edge, or a roller's centre with ``c = ±r``):
    ``Φ = f(s) − c``, ``f`` the signed distance (outward positive) of the
    point ``s = A_Cᵀ(r_O(P) − R_C)`` from the curve.  ``∇f = n`` (the outward
    normal at the closest point), and the Hessian is ``−k/(1 − f k) t tᵀ`` with
    ``k = n·c''/|c'|²`` (the signed curvature), which gives γ its curvature term.
*line* (a flat face through T with normal n, fixed in O):
    ``Φ = n·(r_C(c(u*)) − r_O(T))`` at the support point ``u*`` (least ``n·c``).
    By the envelope theorem Φ_q is that of a point on a line; γ adds
    ``(F_uq q̇)²/F_uu`` for the support point sliding round the curve, i.e.
    ``ρ ω_rel²`` with ρ the radius of curvature there.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mech._records import dataclass

__all__ = ["CurveRow", "Spline", "curve_rows"]


def _piece(p0: Any, p1: Any, m0: Any, m1: Any, t: Any) -> tuple[Any, Any, Any]:
    """c, c', c'' of the cubic piece from ``p0`` to ``p1`` (second derivatives ``m0``, ``m1``) at ``t``.

    Elementwise, so one configuration (floats, points (2,)) and K at once (``t`` (K, 1),
    points (K, 2)) share it.
    """
    s = 1.0 - t
    c = s * p0 + t * p1 + ((s**3 - s) * m0 + (t**3 - t) * m1) / 6.0
    c1 = p1 - p0 + ((1.0 - 3.0 * s * s) * m0 + (3.0 * t * t - 1.0) * m1) / 6.0
    c2 = s * m0 + t * m1
    return c, c1, c2


class Spline:
    """The periodic cubic spline through closed ``points`` (N, 2), in the link's local frame."""

    def __init__(self, points: np.ndarray) -> None:
        p = np.asarray(points, float)
        self.p = p
        self.n = len(p)
        rhs = 6.0 * (np.roll(p, -1, axis=0) - 2.0 * p + np.roll(p, 1, axis=0))
        lam = 4.0 + 2.0 * np.cos(2.0 * np.pi * np.arange(self.n) / self.n)
        self.m = np.real(np.fft.ifft(np.fft.fft(rhs, axis=0) / lam[:, None], axis=0))
        x, y = p[:, 0], p[:, 1]
        area = 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
        self.ccw = area > 0.0

    def departure(self) -> float:
        """About how far (local units) the spline may stray from the smooth curve through its points.

        De Boor's bound for cubic spline interpolation, (5/384) h⁴ max|f⁗|, with h = 1
        (the parameter is the point's index) and f⁗ estimated by the second differences
        of the spline's own second derivatives.  For points on a circle it is about five
        times the true departure (tests/kinematics/test_profiles.py); it shrinks as h⁴:
        twice the points, a sixteenth of the departure.
        """
        d4 = np.roll(self.m, -1, axis=0) - 2.0 * self.m + np.roll(self.m, 1, axis=0)
        return float(5.0 / 384.0 * np.hypot(d4[:, 0], d4[:, 1]).max())

    # -- for K configurations at once (one is a batch of one): arrays (K,) and (K, 2) ------------
    def eval(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """c(u), c'(u), c''(u) (K, 2) for the parameters ``u`` (K,), local."""
        u = u % self.n
        i = np.floor(u).astype(int)
        t = (u - i)[:, None]
        j = (i + 1) % self.n
        p0, p1, m0, m1 = self.p[i], self.p[j], self.m[i], self.m[j]
        return _piece(p0, p1, m0, m1, t)

    def outward(self, c1: np.ndarray) -> np.ndarray:
        """Unit outward normals (K, 2) for tangents ``c1`` (K, 2)."""
        t = c1 / np.hypot(c1[:, 0], c1[:, 1])[:, None]
        return np.stack([t[:, 1], -t[:, 0]], axis=1) if self.ccw else np.stack([-t[:, 1], t[:, 0]], axis=1)

    def _newton(self, u: np.ndarray, g) -> np.ndarray:  # type: ignore[no-untyped-def]
        """Newton on ``g(u) = 0`` for each element (steps of at most half a piece), each stopping on its own."""
        u = u.astype(float)
        active = np.ones(u.shape, bool)
        for _ in range(30):
            if not active.any():
                break
            val, slope = g(u)
            active &= slope != 0.0
            with np.errstate(divide="ignore", invalid="ignore"):
                du = np.where(active, np.clip(-val / slope, -0.5, 0.5), 0.0)
            u = u + du
            active &= ~(np.abs(du) < 1e-13)
        return u % self.n

    def nearest(self, x: np.ndarray) -> np.ndarray:
        """The parameters (K,) of the curve's points closest to the points ``x`` (K, 2)."""
        d = self.p[None, :, :] - x[:, None, :]
        u0 = np.argmin(d[..., 0] ** 2 + d[..., 1] ** 2, axis=1)

        def g(u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            c, c1, c2 = self.eval(u)
            r = c - x
            return _dot(r, c1), _dot(c1, c1) + _dot(r, c2)

        return self._newton(u0, g)

    def support(self, m: np.ndarray) -> np.ndarray:
        """The parameters (K,) of the curve's points with the least ``m · c``, for directions ``m`` (K, 2)."""
        u0 = np.argmin(m @ self.p.T, axis=1)

        def g(u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            _, c1, c2 = self.eval(u)
            return _dot(m, c1), _dot(m, c2)

        return self._newton(u0, g)


@dataclass(frozen=True, eq=False)
class CurveRow:
    """One contact row of a curve on link ``ic`` with a point (``mode="point"``) or a line of link ``io``.

    ``s`` is the point (or the line's through-point) and ``n`` the line's normal,
    local to ``io``; ``c`` the signed distance kept (a roller's radius).
    """

    ic: int
    spline: Spline
    io: int
    mode: str
    s: np.ndarray
    n: np.ndarray | None
    c: float
    joint: str
    holonomic: bool = True


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise dot products of (K, 2) arrays."""
    return a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1]


def _rot(th: np.ndarray, v: np.ndarray) -> np.ndarray:
    """A(θ) v for each angle of ``th`` (K,) and vector of ``v`` ((2,) or (K, 2))."""
    c, s = np.cos(th), np.sin(th)
    vx, vy = (v[0], v[1]) if v.ndim == 1 else (v[:, 0], v[:, 1])
    return np.stack([c * vx - s * vy, s * vx + c * vy], axis=1)


def _perp(v: np.ndarray) -> np.ndarray:
    return np.stack([-v[:, 1], v[:, 0]], axis=1)


def curve_rows(
    row: CurveRow, qf: np.ndarray, vf: np.ndarray | None = None
) -> tuple[np.ndarray, dict[int, np.ndarray], np.ndarray, np.ndarray, np.ndarray]:
    """Φ (K,), the non-zero Φ_q entries (column → (K,)), γ (K,; 0 without ``vf``), the contact
    point and the common normal (K, 2; global, scaled) of K configurations at once.

    ``qf``, ``vf``: coordinates and rates (K, 3n + 3) with ground's three zeros appended.
    One configuration is a batch of one.
    """
    ic, io = 3 * row.ic, 3 * row.io
    th_c, th_o = qf[:, ic + 2], qf[:, io + 2]
    rc, ro = qf[:, ic : ic + 2], qf[:, io : io + 2]
    sp = row.spline
    gamma = np.zeros(qf.shape[0])
    if row.mode == "point":
        a_o = _rot(th_o, row.s)
        w = ro + a_o - rc
        s_loc = _rot(-th_c, w)
        c, c1, c2 = sp.eval(sp.nearest(s_loc))
        n_loc = sp.outward(c1)
        f = _dot(n_loc, s_loc - c)
        k = _dot(n_loc, c2) / _dot(c1, c1)
        n_g = _rot(th_c, n_loc)
        cols = {
            io: n_g[:, 0],
            io + 1: n_g[:, 1],
            io + 2: _dot(n_g, _perp(a_o)),
            ic: -n_g[:, 0],
            ic + 1: -n_g[:, 1],
            ic + 2: -_dot(n_g, _perp(w)),
        }
        if vf is not None:
            w_o, w_c = vf[:, io + 2, None], vf[:, ic + 2, None]
            wd = vf[:, io : io + 2] + w_o * _perp(a_o) - vf[:, ic : ic + 2]
            v_rel = wd - w_c * _perp(w)
            t_g = _rot(th_c, c1 / np.hypot(c1[:, 0], c1[:, 1])[:, None])
            hess = -k / (1.0 - f * k) * _dot(t_g, v_rel) ** 2
            rest = _dot(n_g, -(w_o**2) * a_o - 2.0 * w_c * _perp(wd) - w_c**2 * w)
            gamma = -(hess + rest)
        return f - row.c, cols, gamma, rc + _rot(th_c, c), n_g
    assert row.n is not None
    n_g = _rot(th_o, row.n)
    t_g = _rot(th_o, row.s)
    p, c1, c2 = sp.eval(sp.support(_rot(-th_c, n_g)))
    a_c = _rot(th_c, p)
    d = rc + a_c - ro - t_g
    jn = _perp(n_g)
    cols = {
        ic: n_g[:, 0],
        ic + 1: n_g[:, 1],
        ic + 2: _dot(n_g, _perp(a_c)),
        io: -n_g[:, 0],
        io + 1: -n_g[:, 1],
        io + 2: _dot(jn, d + t_g),
    }
    if vf is not None:
        w_c, w_o = vf[:, ic + 2], vf[:, io + 2]
        dd = vf[:, ic : ic + 2] + w_c[:, None] * _perp(a_c) - vf[:, io : io + 2] - w_o[:, None] * _perp(t_g)
        gamma = (
            w_o**2 * _dot(n_g, d)
            - 2.0 * w_o * _dot(jn, dd)
            + w_c**2 * _dot(n_g, a_c)
            - w_o**2 * _dot(n_g, t_g)
        )
        f_uq = (w_o - w_c) * _dot(jn, _rot(th_c, c1))
        f_uu = _dot(n_g, _rot(th_c, c2))
        with np.errstate(divide="ignore", invalid="ignore"):
            gamma = gamma + np.where(f_uu != 0.0, f_uq**2 / f_uu, 0.0)
    return _dot(n_g, d) - row.c, cols, gamma, rc + a_c, n_g
