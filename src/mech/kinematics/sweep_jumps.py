"""Extremes reached at a jump: a quantity that changes at once (a cam law's segment end).

Above the events (it reads the quantities through their refiner), below the sweep that
calls it once its extremes are found.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from mech.kinematics.sweep_events import refiner
from mech.kinematics.sweep_result import Extreme

__all__ = ["jump_notes", "with_jumps"]


#: How far either side of an extreme a jump is looked for (rad, times max(1, |angle|)): the values
#: there differ by a jump's size at both distances, by a slope times the distance where smooth.
_JUMP_PROBE = (1e-6, 1e-8)


def with_jumps(
    backend: Any, names: dict[str, tuple[str, ...]], extremes: tuple[Extreme, ...], phi: np.ndarray
) -> tuple[Extreme, ...]:
    """``extremes`` with those reached at a jump of their quantity marked, with the values either side.

    A cam's acceleration is greatest where its law's segment begins (SHM, uniform
    acceleration): the value jumps there from the dwell's 0 to its largest, and the
    grid's largest value is that jump's side, not the top of a smooth curve (issue 20:
    "the jump is reported as a jump, not as an extreme").  Each extreme is read 1e-6 and
    1e-8 rad either side: where the two sides differ by more than a millionth of the
    quantity's size at both distances, alike (a smooth quantity's difference shrinks a
    hundredfold), it is a jump.  At the ends of a range that is not a whole period there
    is no other side: none is looked for there.
    """
    if not extremes or not backend.vectorised:
        return extremes
    results = {(e.quantity, "max"): (e.max_angle, e.max_value) for e in extremes}
    results |= {(e.quantity, "min"): (e.min_angle, e.min_value) for e in extremes}
    lo, hi = float(min(phi[0], phi[-1])), float(max(phi[0], phi[-1]))
    turn = abs(hi - lo - 2.0 * math.pi) < 1e-9  # a whole turn: the range's ends have another side
    rows = [
        (key, mode, angle)
        for (key, mode), (angle, value) in results.items()
        if math.isfinite(value) and (turn or lo < angle < hi)
    ]
    if not rows:
        return extremes
    at = np.array([a for _k, _m, a in rows])
    scale = np.maximum(1.0, np.abs(at))[:, None]
    far, near = _JUMP_PROBE
    grid = at[:, None] + np.array([-far, -near, near, far])[None, :] * scale
    refs = np.array([results[(k, m)][1] for k, m, _a in rows])  # a link's angle read on its extreme's turn
    vals = refiner(backend, names, [k for k, _m, _a in rows], refs, regular=True)(grid)
    size = {
        key: max(abs(results[(key, "max")][1]), abs(results[(key, "min")][1]), 1e-300) for key, _m, _a in rows
    }
    sense = 1.0 if phi[-1] >= phi[0] else -1.0
    out: dict[tuple[str, str], tuple[float, float]] = {}
    jumps: list[int] = []
    for i, ((key, mode, _a), (lf, ln, rn, rf)) in enumerate(zip(rows, vals, strict=True)):
        if not all(math.isfinite(x) for x in (lf, ln, rn, rf)):
            continue
        step_near, step_far = abs(rn - ln), abs(rf - lf)
        if step_near > 1e-6 * size[key] and step_near > 0.5 * step_far:
            out[(key, mode)] = (float(ln), float(rn)) if sense > 0 else (float(rn), float(ln))
            jumps.append(i)
    for i in _held(backend, names, rows, vals, refs, size, jumps, phi):
        del out[(rows[i][0], rows[i][1])]
    return tuple(
        replace(e, max_jump=out.get((e.quantity, "max")), min_jump=out.get((e.quantity, "min")))
        for e in extremes
    )


def _held(
    backend: Any,
    names: dict[str, tuple[str, ...]],
    rows: list[tuple[str, str, float]],
    vals: np.ndarray,
    refs: np.ndarray,
    size: dict[str, float],
    jumps: list[int],
    phi: np.ndarray,
) -> list[int]:
    """The jumps whose extreme is also held on its side: the value a whole dwell keeps.

    A follower's acceleration is 0 over a dwell and jumps to the next segment's value at
    its end: its least magnitude, 0, is the dwell's, reached at every angle of it, not the
    jump's.  Read one grid step away on the extreme's side: a value held there to 1e-9 of
    the quantity's size is a plateau (an SHM rise's cosine, flat to second order at its
    start, has moved by 3e-4 of its peak one degree in).
    """
    if not jumps:
        return []
    step = float(abs(phi[1] - phi[0])) if phi.size > 1 else 0.0
    if step == 0.0:
        return []
    at = np.array([rows[i][2] for i in jumps])
    # the extreme's side: the one (before or after) whose value is the extreme's
    side = np.array([-1.0 if (vals[i][1] >= vals[i][2]) == (rows[i][1] == "max") else 1.0 for i in jumps])
    probe = refiner(backend, names, [rows[i][0] for i in jumps], refs[jumps], regular=True)(
        (at + side * step)[:, None]
    )
    return [
        i
        for i, v in zip(jumps, probe[:, 0], strict=True)
        if math.isfinite(v)
        and abs(v - (max if rows[i][1] == "max" else min)(vals[i][1], vals[i][2])) <= 1e-9 * size[rows[i][0]]
    ]


def jump_notes(extremes: Sequence[Extreme], at: Callable[[float], str]) -> list[str]:
    """A note for each extreme reached at a jump (:func:`with_jumps`), ``at`` writing the parameter."""
    out = []
    for ex in extremes:
        for word, angle, jump in (
            ("largest", ex.max_angle, ex.max_jump),
            ("least", ex.min_angle, ex.min_jump),
        ):
            if jump is not None:
                out.append(
                    f"{ex.quantity} jumps at {at(angle)} from {jump[0]:.6g} to {jump[1]:.6g} {ex.unit}: "
                    f"its {word} value is that jump's, not an extreme of a smooth curve"
                )
    return out
