"""Root finders and minimisers that refine what a sweep finds between its steps.

:func:`zoom` refines many brackets at once on a vectorised function (the
closed form, or a marched Newton series); :func:`illinois` (regula falsi)
and :func:`brent` (Brent's minimisation) work one solve at a time, for a
Newton sweep that can only be walked.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

__all__ = ["brent", "illinois", "zoom"]


def zoom(
    fn: Callable[[np.ndarray], np.ndarray],
    lo: np.ndarray,
    hi: np.ndarray,
    mode: str,
    rounds: int = 14,
    m: int = 33,
) -> tuple[np.ndarray, np.ndarray]:
    """Refine K brackets at once: maxima, minima (``mode``) or sign changes (``"root"``).

    Each round evaluates ``fn`` on an (K, m) sub-grid of every bracket and
    keeps the two sub-steps round the best point (or the sign change), so a
    bracket shrinks 16× per round: 14 rounds take it from a sweep step to
    rounding.  Returns (angles, values) at the refined points.
    """
    lo, hi = lo.astype(float).copy(), hi.astype(float).copy()
    k = np.arange(lo.size)
    t = np.linspace(0.0, 1.0, m)
    for _ in range(rounds):
        grid = lo[:, None] + (hi - lo)[:, None] * t[None, :]
        vals = fn(grid)
        if mode == "root":
            s = np.sign(vals)
            change = (s[:, :-1] * s[:, 1:]) <= 0
            j = np.where(change.any(axis=1), np.argmax(change, axis=1), m // 2 - 1)
            lo, hi = grid[k, j], grid[k, j + 1]
        else:
            v = np.where(np.isnan(vals), -np.inf if mode == "max" else np.inf, vals)
            j = np.argmax(v, axis=1) if mode == "max" else np.argmin(v, axis=1)
            jl, jh = np.maximum(j - 1, 0), np.minimum(j + 1, m - 1)
            lo, hi = grid[k, jl], grid[k, jh]
        # a root to rounding; a maximum only to 1e-11 rad: its value is then exact (it moves as Δθ²)
        # (a bracket may run downwards, lo > hi, as a descending sweep gives it: measure its width)
        if np.all(np.abs(hi - lo) <= (4e-16 if mode == "root" else 1e-11) * np.maximum(np.abs(lo), 1.0)):
            break
    mid = 0.5 * (lo + hi)
    if mode == "root":
        return mid, fn(mid[:, None])[:, 0]
    grid = lo[:, None] + (hi - lo)[:, None] * t[None, :]
    vals = fn(grid)
    v = np.where(np.isnan(vals), -np.inf if mode == "max" else np.inf, vals)
    j = np.argmax(v, axis=1) if mode == "max" else np.argmin(v, axis=1)
    return grid[k, j], vals[k, j]


def illinois(
    fn: Callable[[np.ndarray], np.ndarray],
    a: np.ndarray,
    b: np.ndarray,
    fa: np.ndarray,
    fb: np.ndarray,
    iters: int = 12,
) -> np.ndarray:
    """Regula falsi (Illinois) on K brackets at once: superlinear, a dozen solves each (Newton sweeps)."""
    a, b, fa, fb = a.copy(), b.copy(), fa.copy(), fb.copy()
    side = np.zeros(a.size)
    for _ in range(iters):
        with np.errstate(invalid="ignore", divide="ignore"):
            c = np.where(fb != fa, b - fb * (b - a) / (fb - fa), a)
        done = (np.abs(b - a) <= 1e-15 * np.maximum(np.abs(a), 1.0)) | (fa == 0) | (fb == 0)
        if np.all(done):
            break
        fc = fn(c[:, None])[:, 0]
        left = np.sign(fc) == np.sign(fa)
        a, fa = np.where(left, c, a), np.where(left, fc, fa)
        b, fb = np.where(left, b, c), np.where(left, fb, fc)
        fb = np.where(left & (side == 1), fb / 2, fb)
        fa = np.where(~left & (side == -1), fa / 2, fa)
        side = np.where(left, 1, -1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(fb != fa, b - fb * (b - a) / (fb - fa), a)


_GOLD = 0.5 * (3.0 - math.sqrt(5.0))


def brent(
    f: Callable[[float], float], a: float, b: float, x: float, fx: float, xtol: float = 1e-10
) -> tuple[float, float]:
    """Brent's minimisation of ``f`` on [a, b] from the best known point ``x`` (value ``fx``).

    Parabolic steps where the function is smooth, golden-section ones where it
    is not (the V of a speed's magnitude through zero); NaN counts as +∞.  The
    bracket shrinks to about ``xtol`` rad, some 10–40 solves.  Returns the best
    point seen, never worse than the start (Brent, *Algorithms for Minimization
    without Derivatives*, 1973, ch. 5).
    """

    def g(u: float) -> float:
        val = f(u)
        return val if math.isfinite(val) else math.inf

    w = v = x
    fw = fv = fx
    d = e = 0.0
    for _ in range(100):
        m = 0.5 * (a + b)
        tol1 = xtol + 4e-16 * abs(x)
        tol2 = 2.0 * tol1
        if abs(x - m) <= tol2 - 0.5 * (b - a):
            break
        golden = True
        if abs(e) > tol1 and math.isfinite(fw) and math.isfinite(fv):  # a parabola through x, w, v
            r = (x - w) * (fx - fv)
            q = (x - v) * (fx - fw)
            p = (x - v) * q - (x - w) * r
            q = 2.0 * (q - r)
            if q > 0.0:
                p = -p
            q = abs(q)
            e_old, e = e, d
            if abs(p) < abs(0.5 * q * e_old) and q * (a - x) < p < q * (b - x):
                d = p / q
                if (x + d) - a < tol2 or b - (x + d) < tol2:
                    d = math.copysign(tol1, m - x)
                golden = False
        if golden:
            e = (a - x) if x >= m else (b - x)
            d = _GOLD * e
        u = x + d if abs(d) >= tol1 else x + math.copysign(tol1, d)
        fu = g(u)
        if fu <= fx:
            if u >= x:
                a = x
            else:
                b = x
            v, fv, w, fw, x, fx = w, fw, x, fx, u, fu
        else:
            if u < x:
                a = u
            else:
                b = u
            if fu <= fw or w == x:
                v, fv, w, fw = w, fw, u, fu
            elif fu <= fv or v in (x, w):
                v, fv = u, fu
    return x, fx
