"""Stretches of a sweep: the runs of assembled steps, and link angles continuous along them.

At the bottom of the sweep's modules (plain numpy on masks), shared by the events, the rests
and the sweep itself.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["runs", "unwrap_runs"]

_TWO_PI = 2.0 * math.pi


def runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """Index ranges [i, j) where ``mask`` is True."""
    edges = np.flatnonzero(np.diff(np.concatenate(([0], mask.astype(np.int8), [0]))))
    return [(int(i), int(j)) for i, j in zip(edges[0::2], edges[1::2], strict=True)]


def unwrap_runs(a: np.ndarray, ok: np.ndarray, phi: np.ndarray | None = None) -> np.ndarray:
    """Link angles continuous along each assembled run (no 2π jumps), first value in [0, 2π).

    Over a full turn of a crank (``phi``) whose first and last steps are assembled, the first
    and last runs are one stretch of the motion, through 360° ≡ 0° (the two-crank five-bar:
    169.5°–360° then 0°–123.6°): the first run continues the last, so that angles on either
    side of a gap are on one turn.
    """
    out = a.copy()
    spans = runs(ok)
    for start, end in spans:
        run = np.unwrap(out[start:end], axis=0)
        run -= np.floor(run[0] / _TWO_PI) * _TWO_PI
        out[start:end] = run
    full = phi is not None and phi.size > 2 and abs(abs(float(phi[-1] - phi[0])) - _TWO_PI) < 1e-9
    if full and len(spans) > 1 and spans[0][0] == 0 and spans[-1][1] == ok.size:
        (s0, e0), last = spans[0], out[spans[-1][1] - 1]
        out[s0:e0] += _TWO_PI * np.round((last - out[s0]) / _TWO_PI)
    return out
