"""The grid a sweep analyses, and its limits: memory, the float spacing of angles and positions.

A sweep looks for events (dead centres, extremes, gaps) between angles at most
:data:`RESOLVE` apart, whatever steps it is asked to print (:func:`analysis_grid`);
its arrays may take at most :data:`MEMORY_BUDGET` (:func:`check_memory`), and an angle
or a slider's position so large that floats cannot place it is refused
(:func:`check_precision`, :func:`check_position_precision`).  Split from
:mod:`.sweep`, the driver, which imports these.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from mech.errors import InputError
from mech.kinematics.dyads import DyadProgram, numpy_namespace
from mech.kinematics.solve import Compiled

__all__ = [
    "ANGLE_PRECISION",
    "MEMORY_BUDGET",
    "POSITION_PRECISION",
    "RESOLVE",
    "analysis_grid",
    "check_memory",
    "check_position_precision",
    "check_precision",
    "per_angle",
]

MEMORY_BUDGET = 1 << 30
"""Bytes a sweep's arrays may take (1 GiB); more angles are refused before solving."""


def per_angle(comp: Compiled, prog: DyadProgram | None, lvl: int) -> int:
    """Bytes a sweep keeps per angle (an estimate, on the safe side; see :func:`check_memory`)."""
    if prog is not None:
        with np.errstate(all="ignore"):
            outputs = len(prog.raw(np.zeros(1), 1.0, 0.0, level=lvl, xp=numpy_namespace()))
        return 20 * outputs + 128
    sys_ = comp.system
    values = (lvl + 1) * (2 * len(sys_.loc_names) + len(sys_.links)) + 2 * len(comp.layout.paths)
    return 1200 + 32 * values


def check_memory(comp: Compiled, prog: DyadProgram | None, n: int, lvl: int) -> None:
    """Refuse a sweep whose arrays would exceed :data:`MEMORY_BUDGET` (an estimate, kept on the safe side).

    Closed form: the generated program's outputs and what is derived from them,
    about 20 bytes per output per angle (measured: 650 bytes per angle for a
    four-bar at velocity level, 1,360 for a six-bar at acceleration level).
    Newton: one small record per step, about 1,200 bytes plus 32 per value kept.
    """
    per = per_angle(comp, prog, lvl)
    if n * per <= MEMORY_BUDGET:
        return
    fit = MEMORY_BUDGET // per
    raise InputError(
        f"a sweep of {n:,} angles would need about {n * per / 2**30:.1f} GiB for its arrays "
        f"({per:,} bytes per angle for {comp.mech.label}), more than the {MEMORY_BUDGET / 2**30:g} GiB "
        f"a sweep may use",
        hint=f"give at most {fit:,} angles (--steps {fit - 1}), or sweep the range in parts",
    )


#: The analysis grid's largest step (rad): events (dead centres, extremes, gaps) are looked
#: for between angles at most this far apart, whatever steps the series is printed at.
RESOLVE = math.radians(1.0)
#: The float spacing (rad) the largest angle of a sweep may have: beyond it (angles past
#: about 2.6e8°) an angle is not known well enough to locate anything on it.
ANGLE_PRECISION = 1e-9


def check_precision(phi: np.ndarray) -> None:
    """Refuse angles so large that their float spacing exceeds :data:`ANGLE_PRECISION`."""
    big = float(np.max(np.abs(phi)))
    spacing = float(np.spacing(big))
    if spacing > ANGLE_PRECISION:
        raise InputError(
            f"crank angles as large as {math.degrees(big):.4g}° are held only to "
            f"{math.degrees(spacing):.2g}° in floating point: nothing on them can be located",
            hint="sweep the same crank positions nearer 0 (subtract whole turns of 360°)",
        )


#: The float spacing, relative to the mechanism's size, the farthest position of a slider's
#: stroke may have: beyond it the slider's place is not known well enough to locate anything.
POSITION_PRECISION = 1e-9


def check_position_precision(s: np.ndarray, size: float, fmt: Callable[[float], str]) -> None:
    """Refuse slider positions so far out that their float spacing exceeds :data:`POSITION_PRECISION` of the size."""
    big = float(np.max(np.abs(s)))
    spacing = float(np.spacing(big))
    if spacing > POSITION_PRECISION * size:
        raise InputError(
            f"slider positions as far out as {fmt(big)} are held only to {fmt(spacing)} in floating "
            f"point, on a mechanism {fmt(size)} across: nothing on them can be located",
            hint="sweep a stroke within the slider's reach (--from/--to in the file's length unit)",
        )


def analysis_grid(
    phi: np.ndarray,
    comp: Compiled,
    prog: DyadProgram | None,
    lvl: int,
    notes: list[str],
    resolve: float = RESOLVE,
    position: Callable[[float], str] | None = None,
) -> tuple[np.ndarray, np.ndarray | None]:
    """The angles to analyse: ``phi`` with each step cut into parts of at most :data:`RESOLVE`.

    Returns the grid and the indices of ``phi``'s angles in it (None when no step
    needed cutting).  Two dead centres between two steps leave no sign change to
    refine, so a sweep of 3 steps over two turns saw 2 of its 4; on the finer grid
    it sees them all.  When the finer grid would exceed the memory budget the
    steps given are analysed: a step of more than half a turn is then refused
    (the motion between its ends is unknown), a smaller one gets a note that
    events between steps may be missed.  A slider's stroke (``position`` formats its
    lengths) is never refused for its steps: it gets the note.
    """
    if phi.size < 2:
        return phi, None
    widths = np.abs(np.diff(phi))
    # counted in floats first: a step of 1e30 m (a slider's stroke) has more parts than int64 holds
    parts_f = np.maximum(1.0, np.ceil(widths / resolve * (1.0 - 1e-12)))
    if float(parts_f.max()) == 1.0:
        return phi, None
    total_f = float(parts_f.sum()) + 1.0
    per = per_angle(comp, prog, lvl)
    if total_f * per > MEMORY_BUDGET:
        notes.append(_steps_as_given(phi, widths, total_f, per, position))
        return phi, None
    parts = parts_f.astype(np.int64)
    total = int(total_f)
    starts = np.concatenate(([0], np.cumsum(parts)))
    offset = np.arange(total - 1) - np.repeat(starts[:-1], parts)
    fine = np.repeat(phi[:-1], parts) + np.repeat(np.diff(phi) / parts, parts) * offset
    return np.append(fine, phi[-1]), starts


def _steps_as_given(
    phi: np.ndarray, widths: np.ndarray, total: float, per: int, position: Callable[[float], str] | None
) -> str:
    """The note for a sweep analysed at its own steps, or the refusal when a crank's step is too wide.

    A crank's step of more than half a turn leaves its motion between the ends unknown, so it is
    refused; a narrower one, or any step of a slider's stroke (``position`` formats it), is
    analysed as given with a note.
    """
    widest = float(widths.max())
    if position is not None:
        return (
            f"steps of {position(widest)} analysed as given (a finer grid would exceed the memory "
            "budget): a dead centre or extreme between two steps may be missed; give more --steps"
        )
    span = math.degrees(abs(float(phi[-1] - phi[0])))
    fit = max(int(MEMORY_BUDGET // per) - 1, 1)
    if math.degrees(widest) > 180.0:
        raise InputError(
            f"steps of {math.degrees(widest):.4g}° are more than half a turn: the crank's motion between "
            f"them is unknown, and resolving it ({total:,.0f} angles at 1°) exceeds the memory a sweep may use",
            hint=f"give at least --steps {math.ceil(span / 180.0)} (1° steps: --steps "
            f"{math.ceil(span * (1 - 1e-12))}), at most {fit:,}; or sweep the range in parts",
        )
    return (
        f"steps of {math.degrees(widest):.4g}° analysed as given (a 1° grid would exceed the memory budget): "
        "a dead centre or extreme between two steps may be missed; give more --steps to resolve it"
    )
