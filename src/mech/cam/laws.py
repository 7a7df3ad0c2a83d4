"""Follower motion laws for one rise: lift and its derivatives against cam angle.

A rise of height ``h`` over a cam angle ``beta`` is written with the
fraction ``x = phi / beta`` of the segment already turned (``0 <= x <= 1``).
Each law gives the lift ``s`` and its first three derivatives with respect to
the cam angle, ``s' = ds/dθ``, ``s''``, ``s'''`` (per radian).  For a cam turning
at a constant ``ω`` the follower's velocity, acceleration and jerk are
``v = ω s'``, ``a = ω² s''``, ``j = ω³ s'''``; a return is ``h`` minus a rise.

The formulas are the textbook ones (Khurmi & Gupta, *Theory of Machines*, ch. 20
"Cams"; Rattan, *Theory of Machines*, ch. 6 "Cams"; Norton, *Design of
Machinery*, ch. 8 "Cam design"):

* ``uniform`` (uniform velocity): ``s = h x``.  Its acceleration is zero inside
  the segment and infinite (an impulse) at its ends; the table shows the zero
  and says so.
* ``shm`` (simple harmonic motion): ``s = h/2 (1 − cos πx)``;
  ``v_max = π h ω / (2β)``, ``a_max = π² h ω² / (2β²)`` (Khurmi's v_O, a_O);
  its acceleration jumps at the ends, so its jerk is infinite there (Norton).
* ``parabolic`` (uniform acceleration and retardation): ``s = 2h x²`` for
  ``x ≤ ½`` and ``h (1 − 2 (1 − x)²)`` after; ``v_max = 2 h ω / β``,
  ``a = ± 4 h ω² / β²``.
* ``cycloidal``: ``s = h (x − sin 2πx / 2π)``; ``v_max = 2 h ω / β``,
  ``a_max = 2π h ω² / β²``; acceleration is zero at both ends, so jerk is
  finite everywhere.

Everything here is vectorised over numpy arrays of ``x``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["KNOTS", "LAWS", "Motion", "rise"]

FloatArray = NDArray[np.float64]


class Motion(NamedTuple):
    """Lift and its derivatives against cam angle (length or angle per radian^k)."""

    s: FloatArray
    ds: FloatArray
    d2s: FloatArray
    d3s: FloatArray


def _uniform(x: FloatArray, h: float, beta: float) -> Motion:
    one = np.ones_like(x)
    zero = np.zeros_like(x)
    return Motion(h * x, h / beta * one, zero, zero.copy())


def _shm(x: FloatArray, h: float, beta: float) -> Motion:
    k = math.pi / beta
    px = math.pi * x
    return Motion(
        h / 2 * (1 - np.cos(px)),
        h / 2 * k * np.sin(px),
        h / 2 * k**2 * np.cos(px),
        -h / 2 * k**3 * np.sin(px),
    )


def _parabolic(x: FloatArray, h: float, beta: float) -> Motion:
    first = x <= 0.5
    rest = 1.0 - x
    s = np.where(first, 2 * h * x**2, h * (1 - 2 * rest**2))
    ds = np.where(first, 4 * h * x / beta, 4 * h * rest / beta)
    d2s = np.where(first, 4 * h / beta**2, -4 * h / beta**2)
    return Motion(s, ds, d2s, np.zeros_like(x))


def _cycloidal(x: FloatArray, h: float, beta: float) -> Motion:
    tx = 2 * math.pi * x
    return Motion(
        h * (x - np.sin(tx) / (2 * math.pi)),
        h / beta * (1 - np.cos(tx)),
        2 * math.pi * h / beta**2 * np.sin(tx),
        4 * math.pi**2 * h / beta**3 * np.cos(tx),
    )


LAWS: dict[str, Callable[[FloatArray, float, float], Motion]] = {
    "uniform": _uniform,
    "shm": _shm,
    "parabolic": _parabolic,
    "cycloidal": _cycloidal,
}
"""The laws by the name a programme gives them (``law: shm``)."""

#: Where inside a segment (fractions of it) a law's pieces meet, so that a derivative may jump there
#: as at a segment's ends: the parabolic law's acceleration turns from +4h/β² to −4h/β² half-way.
KNOTS: dict[str, tuple[float, ...]] = {"parabolic": (0.5,)}


def rise(law: str, x: ArrayLike, h: float, beta: float) -> Motion:
    """A rise of ``h`` over ``beta`` radians by ``law``, at segment fractions ``x``.

    Parameters
    ----------
    law : one of :data:`LAWS` (``uniform``, ``shm``, ``parabolic``, ``cycloidal``)
    x : fractions of the segment turned, 0 to 1 (values outside are clipped)
    h : the lift (m for a translating follower, rad for an oscillating one)
    beta : the cam angle the segment takes, rad (> 0)

    Examples
    --------
    >>> m = rise("shm", [0.5], 0.05, math.radians(120))
    >>> round(float(m.s[0]), 6), round(float(m.ds[0]), 6)   # half the lift, v_max / ω
    (0.025, 0.0375)
    """
    if law not in LAWS:
        raise KeyError(law)
    if not beta > 0:
        raise ValueError(f"a segment must take a positive cam angle, not {beta}")
    xs = np.clip(np.asarray(x, dtype=float), 0.0, 1.0)
    return LAWS[law](xs, float(h), float(beta))
