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
    for (key, mode, _a), (lf, ln, rn, rf) in zip(rows, vals, strict=True):
        if not all(math.isfinite(x) for x in (lf, ln, rn, rf)):
            continue
        step_near, step_far = abs(rn - ln), abs(rf - lf)
        if step_near > 1e-6 * size[key] and step_near > 0.5 * step_far:
            out[(key, mode)] = (float(ln), float(rn)) if sense > 0 else (float(rn), float(ln))
    return tuple(
        replace(e, max_jump=out.get((e.quantity, "max")), min_jump=out.get((e.quantity, "min")))
        for e in extremes
    )


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
