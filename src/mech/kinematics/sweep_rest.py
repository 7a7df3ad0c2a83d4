"""Rest and return over a sweep: where an output dwells, and the time ratio of every output.

An output at rest over an interval — a cam follower's dwell, or any output whose rate is
zero there — is one dwell, never a dead centre at every step inside it (DESIGN § 1.2).  It
is found from the motion itself, not from a cam's programme, so it holds for any mechanism:
the output's rate (a slider's speed along its path, a pivoted link's ω) within :data:`REST`
of zero at two or more consecutive steps.  Its ends are bisected between the last step at
rest and the first that moves, to where the rate leaves rounding (:data:`EDGE`).

The time ratio (quick return) of an output is its slow stroke over its fast one: the crank
angles between its two limit positions over a full, gap-free turn (a stroke runs from leaving one
limit to reaching the other, so a dwell held at a limit belongs to neither stroke) (Khurmi & Gupta, *Theory of
Machines*, § 5.11; Norton, *Design of Machinery*, § 3.5).  Every output with exactly two gets
one; the bare ``time_ratio`` is the mechanism's one such output's, refused with the candidates
named when there are several (even alike: a slotted lever and the ram it drives), and each
refusal says why.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from mech.kinematics.quantities import pick
from mech.kinematics.runs import runs
from mech.kinematics.sweep_backends import Walk
from mech.kinematics.sweep_result import Dwell, Event, Extreme, TimeRatio

__all__ = ["EDGE", "REST", "find_dwells", "find_time_ratios", "held_over_dwells"]

_TWO_PI = 2.0 * math.pi
#: An output whose rate is within this of its largest over the sweep is at rest (rounding at
#: rest is about 1e-16 of it; the slowest law leaving a dwell, 4-5-6-7, is 2e-8 of it a tenth of a
#: degree into a 150° rise).
REST = 1e-9
#: A dwell's end is where the rate passes this of its largest (or a hundred times the rounding
#: seen at rest, if more): a harmonic law leaves rest linearly, so its edge is found to 1e-12
#: of the law's span; a cycloidal one quadratically, to about 3e-7 of it.
EDGE = 1e-12
#: Bisections of a dwell's end (a Newton walk): a sweep step shrinks 2⁴⁰ times (1e-14 rad from a
#: degree).  Vectorised, :data:`ROUNDS` sub-grids of :data:`SUB` points shrink it as far.
BISECT = 40
SUB = 33
ROUNDS = 9
#: A dwell's end within this (rad) of 0° or 360° over a full turn is on the seam: a law leaving
#: rest quadratically has its edge found to about 1e-6 rad.
SEAM = 1e-5


def _full_turn(phi: np.ndarray) -> bool:
    return phi.size > 2 and abs(abs(phi[-1] - phi[0]) - _TWO_PI) < 1e-9


def _keys(kind: str, name: str) -> tuple[str, str]:
    """The rate and position quantities of an output (``"slide"`` joint or ``"link"``)."""
    return (
        (f"sliding.{name}", f"displacement.{name}") if kind == "slide" else (f"omega.{name}", f"angle.{name}")
    )


def find_dwells(
    backend: Any,
    phi: np.ndarray,
    data: dict[str, np.ndarray],
    ok: np.ndarray,
    names: dict[str, tuple[str, ...]],
    outputs: Sequence[tuple[str, str]],
) -> tuple[tuple[Dwell, ...], dict[str, np.ndarray]]:
    """Every output's dwells, and the steps at rest inside them (by output), for the dead centres.

    Over a full turn a dwell across the seam (at rest at both the first and the last step) is
    one dwell, from its start before 360° to its end after 0°.
    """
    full = _full_turn(phi)
    found: list[tuple[str, str, int, int, float]] = []  # kind, name, s, e, edge threshold
    rest: dict[str, np.ndarray] = {}
    for kind, name in outputs:
        v = pick(data, names, _keys(kind, name)[0])
        good = ok & np.isfinite(v)
        vmax = float(np.max(np.abs(v[good]))) if np.any(good) else 0.0
        if vmax == 0.0:
            continue
        spans = _spans(good & (np.abs(v) <= REST * vmax), full)
        if not spans:
            continue
        mask = np.zeros(phi.size, bool)
        for s, e in spans:
            mask[s:e] = True
        rest[name] = mask
        threshold = max(EDGE * vmax, 100.0 * float(np.max(np.abs(v[mask]))))
        found += [(kind, name, s, e, threshold) for s, e in spans]
    if not found:
        return (), rest
    edges = _edges(backend, phi, ok, names, found)
    dwells = []
    for i, (kind, name, s, e, _t) in enumerate(found):
        rate, place = (pick(data, names, k) for k in _keys(kind, name))
        start, end = edges[i]
        before, after = s - 1, e
        if full and s == 0 and any(f[1] == name and f[3] == phi.size for f in found[i + 1 :]):
            continue  # the seam's dwell, written once from its start before 360°
        if full and e == phi.size:
            first = next((j for j, f in enumerate(found) if f[1] == name and f[2] == 0), None)
            if first is not None and first != i:
                end, after = edges[first][1], found[first][3]
        if full:  # a dwell that starts or ends on the seam is written from 0° or to 360°
            start = float(phi[0]) if abs(start - phi[-1]) < SEAM else start
            end = float(phi[-1]) if abs(end - phi[0]) < SEAM else end
        value = float(np.median(place[s:e]))
        sides = [rate[k] for k in (before, after) if 0 <= k < phi.size and ok[k] and np.isfinite(rate[k])]
        reverses = len(sides) == 2 and float(np.sign(sides[0]) * np.sign(sides[1])) < 0
        dwells.append(Dwell(name, start, end, value % _TWO_PI if kind == "link" else value, reverses))
    return tuple(sorted(dwells, key=lambda d: (d.start, d.subject))), rest


def _spans(still: np.ndarray, full: bool) -> list[tuple[int, int]]:
    """Runs of two or more steps at rest; over a full turn the first and last step are one place,
    so a run ending on 360° and one starting at 0° are one dwell's two parts (kept together)."""
    spans = runs(still)
    if spans == [(0, still.size)]:
        return []  # at rest at every step: the output does not move
    seam = full and len(spans) > 1 and spans[0][0] == 0 and spans[-1][1] == still.size
    joined = seam and (spans[0][1] + still.size - spans[-1][0] - 1) >= 2
    return [sp for k, sp in enumerate(spans) if sp[1] - sp[0] >= 2 or (joined and k in (0, len(spans) - 1))]


def _edges(
    backend: Any,
    phi: np.ndarray,
    ok: np.ndarray,
    names: dict[str, tuple[str, ...]],
    found: list[tuple[str, str, int, int, float]],
) -> list[tuple[float, float]]:
    """Each dwell's ends, bisected between its last step at rest and the next step that moves."""
    out = [(float(phi[s]), float(phi[e - 1])) for _k, _n, s, e, _t in found]
    # dwell, end (0 start, 1 end), rate key, moving angle, resting angle, threshold
    rows: list[tuple[int, int, str, float, float, float]] = []
    for i, (kind, name, s, e, threshold) in enumerate(found):
        key = _keys(kind, name)[0]
        if s > 0 and ok[s - 1]:
            rows.append((i, 0, key, float(phi[s - 1]), float(phi[s]), threshold))
        if e < phi.size and ok[e]:
            rows.append((i, 1, key, float(phi[e]), float(phi[e - 1]), threshold))
    if not rows:
        return out
    moving = np.array([r[3] for r in rows])
    resting = np.array([r[4] for r in rows])
    limit = np.array([r[5] for r in rows])
    keys = [r[2] for r in rows]
    if backend.vectorised:  # every end at once, on a sub-grid: 32 times narrower per evaluation
        t = np.linspace(0.0, 1.0, SUB)
        for _ in range(ROUNDS):
            grid = moving[:, None] + t[None, :] * (resting - moving)[:, None]
            data = backend.evaluate(grid)
            rates = np.stack([pick(data, names, key)[k] for k, key in enumerate(keys)])
            moves = ~(np.abs(rates) <= limit[:, None])  # NaN (not reached): not at rest either
            moves[:, 0], moves[:, -1] = True, False  # the bracket's own ends, as found
            j = SUB - 2 - np.argmax(moves[:, -2::-1], axis=1)  # the last sub-step that moves
            at = np.arange(len(rows))
            moving, resting = grid[at, j], grid[at, j + 1]
    else:  # one end after the other along the sweep, each bisected on a warm walk
        walk = Walk(backend, float(phi[0]))
        for k in sorted(range(len(rows)), key=lambda k: abs(moving[k] - phi[0])):
            for _ in range(BISECT):
                mid = 0.5 * (moving[k] + resting[k])
                arrays = walk.to(float(mid))
                rate = math.nan if arrays is None else float(pick(arrays, names, keys[k]))
                if abs(rate) <= limit[k]:
                    resting[k] = mid
                else:
                    moving[k] = mid
    for (i, end, *_rest), a in zip(rows, 0.5 * (moving + resting), strict=True):
        out[i] = (float(a), out[i][1]) if end == 0 else (out[i][0], float(a))
    return out


def held_over_dwells(extremes: Sequence[Extreme], dwells: Sequence[Dwell]) -> tuple[Extreme, ...]:
    """Each extreme an output holds over a dwell, said at the dwell's start.

    Held over an interval, the value has no one angle: refinement stops anywhere on the plateau,
    or just past its edge, where the motion leaves it to within rounding (a roller's lowest
    position held from 0° to 70° was said at 359.9998°).  The dwell's first angle is the one
    the sweep's own line gives (``dwell of S from 0° to 70°``).
    """
    out = []
    for e in extremes:
        kind, _, subject = e.quantity.partition(".")
        mine = [d for d in dwells if d.subject == subject] if kind in ("displacement", "angle") else []
        if not mine:
            out.append(e)
            continue
        angle = kind == "angle"
        out.append(
            replace(
                e,
                max_angle=_dwell_start(mine, e.max_angle, e.max_value, angle),
                min_angle=_dwell_start(mine, e.min_angle, e.min_value, angle),
            )
        )
    return tuple(out)


def _dwell_start(dwells: Sequence[Dwell], at: float, value: float, angle: bool) -> float:
    """The start of the dwell that holds ``value`` around ``at`` (within 1e-3 rad), else ``at``."""
    for d in dwells:
        held = d.value
        gap = abs(math.remainder(value - held, _TWO_PI)) if angle else abs(value - held)
        if gap > 1e-9 * max(abs(held), abs(value), 1e-12):
            continue
        a, s, t = (x % _TWO_PI for x in (at, d.start, d.end))
        inside = (s - 1e-3 <= a <= t + 1e-3) if s <= t else (a >= s - 1e-3 or a <= t + 1e-3)
        if (
            inside
            or abs(math.remainder(a - s, _TWO_PI)) <= 1e-3
            or abs(math.remainder(a - t, _TWO_PI)) <= 1e-3
        ):
            return d.start
    return at


def find_time_ratios(
    phi: np.ndarray,
    ok: np.ndarray,
    dead: Sequence[Event],
    dwells: Sequence[Dwell],
    outputs: Sequence[tuple[str, str]],
    one_crank: bool = True,
) -> tuple[TimeRatio | None, tuple[TimeRatio, ...], tuple[tuple[str, str], ...]]:
    """The bare time ratio, every output's, and (output, why) for each refused ("" for the bare one)."""
    names = [name for _kind, name in outputs]
    why = _whole_turn_why(phi, ok, one_crank)
    if why is not None:
        return None, (), tuple((n, why) for n in ["", *names])
    start = min(phi[0], phi[-1])
    ratios: list[TimeRatio] = []
    refused: list[tuple[str, str]] = []
    for name in names:
        # each limit position as the crank angles it is held over: a dead centre an instant, a dwell
        # the output comes back from an interval (a pause on the way is its stroke's)
        limits = {(a, a) for a in {round((e.angle - start) % _TWO_PI, 12) for e in dead if e.subject == name}}
        rests = [d for d in dwells if d.subject == name and d.reverses]
        limits |= {((d.start - start) % _TWO_PI, (d.end - start) % _TWO_PI) for d in rests}
        if len(limits) == 2:
            (a0, a1), (b0, b1) = sorted(limits)
            # a stroke runs from leaving one limit to reaching the other: a dwell belongs to neither
            there, back = (b0 - a1) % _TWO_PI, (a0 - b1) % _TWO_PI
            ratios.append(TimeRatio(name, max(there, back), min(there, back)))
        elif not rests:
            said = "never reverses" if not limits else f"reverses {_count(len(limits), 'time')}"
            refused.append((name, f"{name} {said} over the turn (a time ratio needs two dead centres)"))
        else:
            said = f"has {_count(len(limits), 'limit position')} over the turn ({_count(len(rests), 'dwell')} among them)"
            refused.append((name, f"{name} {said}: a time ratio needs two"))
    bare, bare_why = _bare(ratios, refused)
    return bare, tuple(ratios), tuple(refused) + ((("", bare_why),) if bare_why else ())


def _whole_turn_why(phi: np.ndarray, ok: np.ndarray, one_crank: bool) -> str | None:
    """Why no output of this sweep has a time ratio at all, or None."""
    if not one_crank:
        return "the sweep's parameter is not one crank's angle (a slider drive, or several drives)"
    if phi.size < 3 or abs(phi[-1] - phi[0]) < _TWO_PI - 1e-9:
        return "the sweep does not cover a full turn of the crank"
    if not np.all(ok):
        return "the crank does not turn fully: the mechanism cannot be assembled at every step of the turn"
    return None


def _bare(ratios: list[TimeRatio], refused: list[tuple[str, str]]) -> tuple[TimeRatio | None, str | None]:
    """The mechanism's one output's ratio; with several, none, and the candidates named (DESIGN § 1.2).

    Several are refused even when their ratios agree (a slotted lever and the ram it drives):
    which stroke a claim means is the file's to say, not a tie for mech to break.
    """
    if not ratios:
        said = "; ".join(w for _n, w in refused) or "the mechanism has no slider or link pivoted on the frame"
        return None, f"no output has two dead centres over the turn: {said}"
    if len(ratios) == 1:
        return ratios[0], None
    listed = ", ".join(f"{r.output} {r.ratio:.6g}" for r in ratios)
    return None, f"{len(ratios)} outputs have a time ratio ({listed}): name one, time_ratio.<output>"


def _count(n: int, word: str) -> str:
    return f"{n} {word}" + ("" if n == 1 else "s")
