"""What a sweep finds over its range: gaps and their toggles, dead centres, extremes, time ratio, circuits.

Each is found on the analysis grid and refined between its neighbouring
steps: with the closed form (or a marched Newton series) by :func:`~.roots.zoom`
on grids of angles, otherwise by :func:`~.roots.illinois` (dead centres) and
:func:`~.roots.brent` (extremes) on Newton solves walked along the sweep's own
branch (:class:`~.sweep_backends.Walk`).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np

from mech.kinematics.dyads import ACCURATE_COND, change_points, closing_edge
from mech.kinematics.quantities import pick, quantity_unit
from mech.kinematics.roots import brent, illinois, zoom
from mech.kinematics.runs import runs
from mech.kinematics.solve import Compiled
from mech.kinematics.sweep_backends import Closed, Walk
from mech.kinematics.sweep_result import Event, Extreme, Gap
from mech.pairs import kind_of

__all__ = [
    "circuits_note",
    "find_change_points",
    "find_dead_centres",
    "find_extremes",
    "find_gaps",
    "left_out_notes",
    "outputs_of",
    "refiner",
    "unbounded_notes",
]

_TWO_PI = 2.0 * math.pi


def circuits_note(phi: np.ndarray, ok: np.ndarray, drawn: float | None) -> str | None:
    """Say so when the assembled steps fall into separate ranges: separate circuits.

    A crank that cannot turn fully between two limit positions reaches only the
    range its drawing lies in; another assembled range (same branch sign of the
    dyads) is a different circuit, reachable only by taking the mechanism apart.
    A full turn whose first and last steps are both assembled wraps into one range.
    """
    runs: list[list[int]] = []
    for i, good in enumerate(ok):
        if good and runs and runs[-1][1] == i - 1:
            runs[-1][1] = i
        elif good:
            runs.append([i, i])
    full_turn = phi.size > 1 and abs(abs(phi[-1] - phi[0]) - _TWO_PI) < 1e-9
    if full_turn and len(runs) > 1 and runs[0][0] == 0 and runs[-1][1] == phi.size - 1:
        runs[0][0] = runs.pop()[0]  # wrapped: the last range continues into the first
    if len(runs) < 2:
        return None

    def span(run: list[int]) -> str:
        return f"{math.degrees(phi[run[0]]):.4g}°–{math.degrees(phi[run[1]]):.4g}°"

    def holds(run: list[int]) -> bool:
        if drawn is None:
            return False
        lo, hi = phi[run[0]], phi[run[1]]
        if lo > hi:  # wrapped range
            return bool(wrap(drawn - lo) >= 0 or wrap(drawn - hi) <= 0)
        k = math.floor((lo - drawn) / _TWO_PI + 1.0)
        a = drawn + k * _TWO_PI
        return bool(lo - 1e-12 <= a <= hi + 1e-12 or lo - 1e-12 <= a - _TWO_PI <= hi + 1e-12)

    def wrap(x: float) -> float:
        return (x + math.pi) % _TWO_PI - math.pi

    mine = [r for r in runs if holds(r)]
    ranges = ", ".join(span(r) for r in runs)
    if mine:
        return (
            f"the assembled ranges {ranges} are separate circuits: the drawing lies on {span(mine[0])}; "
            "the others are the same branch on another circuit, reached only by taking the mechanism apart"
        )
    return f"the assembled ranges {ranges} are separate circuits, and none holds the drawn angle"


#: What a Newton sweep says of a limit it meets, and of the stretch beyond it.
LIMIT = "a limit: the motion from the drawing goes no further (links in line)"
UNREACHED = "the continuation from the drawing stops at a limit position (links in line)"


def find_gaps(
    backend: Any, phi: np.ndarray, data: dict[str, np.ndarray], ok: np.ndarray
) -> tuple[tuple[Gap, ...], tuple[Event, ...]]:
    """Unassembled runs, their edges located as toggles.

    Closed form: the loop cannot close there (a dyad's discriminant is negative), and each
    edge is bisected on the discriminant.  Newton: the stretch was not reached — the
    continuation from the drawing (round the parameter's period too, where it has one) stops
    at a limit, located between the steps where the series was marched; the loop may still
    close there on another circuit, so it is never called unable to (:attr:`Gap.cannot_close`).
    """
    gaps: list[Gap] = []
    toggles: list[Event] = []
    prog = getattr(backend, "prog", None)
    marched = getattr(backend, "marcher", None) is not None
    for s, e in runs(~ok):
        miss = data["miss"][s:e]
        worst = int(np.argmax(np.max(miss, axis=0))) if miss.size else 0
        what = prog.dyads[worst][2] if prog is not None and prog.dyads else UNREACHED
        start, end = float(phi[s]), float(phi[e - 1])
        if prog is not None:
            if s > 0:
                start = _edge(backend, phi[s - 1], phi[s])
                toggles.append(Event("toggle", start, what))
            if e < phi.size:
                end = _edge(backend, phi[e], phi[e - 1])
                toggles.append(Event("toggle", end, what))
        elif marched:  # the limits the continuation reaches, located between the steps
            if s > 0:
                start = backend.edge(s - 1, phi[s])
                toggles.append(Event("toggle", start, LIMIT))
            if e < phi.size:
                end = backend.edge(e, phi[e - 1])
                toggles.append(Event("toggle", end, LIMIT))
        gaps.append(Gap(start, end, float(np.max(miss)) if miss.size else math.nan, what, prog is not None))
    return tuple(gaps), tuple(sorted(toggles, key=lambda t: t.angle))


def find_change_points(backend: Any, phi: np.ndarray, ok: np.ndarray) -> tuple[Event, ...]:
    """Change points inside the assembled runs of the sweep (closed form: :func:`~.dyads.change_points`).

    Each is passed on the branch with a continuous tangent (the closed form
    flips that dyad's sign there: :func:`~.dyads.branches`).
    """
    prog = getattr(backend, "prog", None)
    if phi.size < 3:
        return ()
    if prog is None:
        return _newton_change_points(backend, phi, ok) if getattr(backend, "marcher", None) else ()
    changes = change_points(prog)
    if not changes:
        return ()
    lo, hi = float(np.min(phi)), float(np.max(phi))
    order = np.argsort(phi, kind="stable")
    sp, sok = phi[order], ok[order]
    events = []
    for c in changes:
        a = prog.drawn_angle + c.offset
        a += _TWO_PI * math.ceil((lo - a) / _TWO_PI)
        while a <= hi:
            j = int(np.searchsorted(sp, a))  # sp[j - 1] < a <= sp[j]
            if 0 < j < sp.size and sok[j - 1] and sok[j]:
                events.append(Event("change point", float(a), c.what))
            a += _TWO_PI
    return tuple(sorted(events, key=lambda e: e.angle if phi[-1] >= phi[0] else -e.angle))


#: A marched sweep's σ_min/σ_max below this at a refined dip: two branches meet there.  Newton
#: is accurate to about √tol where Φ_q is singular (1e-6 of the size), so the dip of a change
#: point bottoms out near 1e-6; a steep but regular passage stays far above.
NEWTON_TOUCH = 1e-4


def _newton_change_points(backend: Any, phi: np.ndarray, ok: np.ndarray) -> tuple[Event, ...]:
    """Change points a marched Newton sweep passed: Φ_q singular with the loop closed on both sides.

    Continuation's predictor follows the tangent, so it continues on the branch
    with a continuous tangent by itself; here the places are found (dips of
    σ_min/σ_max along the steps, refined by :func:`zoom`) and said.
    """
    marcher = backend.marcher
    rc = marcher.inverse_condition(backend.solved_q())
    rows = []
    for s, e in runs(ok & np.isfinite(rc)):
        for k in range(s + 1, e - 1):
            r = rc[k - 1 : k + 2]
            if r[1] <= r[0] and r[1] <= r[2] and r[1] < min(r[0], r[2]) and r[1] < 0.05:
                rows.append(k)
    if not rows:
        return ()
    lo = np.array([phi[k - 1] for k in rows], float)
    hi = np.array([phi[k + 1] for k in rows], float)

    def fn(grid: np.ndarray) -> np.ndarray:
        q, conv = backend.corrected(grid.ravel())
        val = marcher.inverse_condition(np.where(conv[:, None], q, np.nan))
        return val.reshape(grid.shape)

    at, val = zoom(fn, lo, hi, "min")
    at = _v_apex(fn, at)
    events = []
    for k, a, v in zip(rows, at, val, strict=True):
        if math.isfinite(float(v)) and v < NEWTON_TOUCH:
            events.append(
                Event("change point", float(a), _meeting(backend, float(a), phi[k - 1], phi[k + 1]))
            )
    return tuple(events)


def _v_apex(fn: Callable[[np.ndarray], np.ndarray], at: np.ndarray, step: float = 1e-4) -> np.ndarray:
    """The apex of σ_min/σ_max's V round each dip, from lines through two points on either side.

    Newton is good only to about √tol where Φ_q is singular, so the V has a
    noisy floor there and its minimum wanders within it (1e-5 rad at the double
    parallelogram's collinear position); the sides, ``step`` and 2·``step``
    away, are clear of the floor, and their lines cross at the apex (exactly,
    for a V symmetric about it).  Kept only where they cross within ``step``.
    """
    offsets = np.array([-2.0, -1.0, 1.0, 2.0]) * step
    r = fn(at[:, None] + offsets[None, :])
    r1, r2, r3, r4 = r.T
    sl, sr = (r2 - r1) / step, (r4 - r3) / step
    with np.errstate(all="ignore"):
        u = (r3 - r2 - (sr + sl) * step) / (sl - sr)
    good = np.isfinite(u) & (np.abs(u) < step) & (sl < 0) & (sr > 0)
    return np.where(good, at + u, at)


def _meeting(backend: Any, at: float, before: float, after: float) -> str:
    """Which named points meet at a Newton sweep's change point (close there, apart either side)."""
    near = at + np.array([0.0, 1e-7, -1e-7, 1e-6, -1e-6])  # Newton may not converge on the point itself
    probes = backend.evaluate(np.concatenate(([before, after], near)))["positions"]
    finite = [k for k in range(2, probes.shape[0]) if np.all(np.isfinite(probes[k]))]
    generic = (
        "the constraint Jacobian loses rank with the loop closed on both sides "
        "(branches of the assembly can meet there)"
    )
    if not finite or not np.all(np.isfinite(probes[:2])):
        return generic
    pos = np.stack([probes[0], probes[finite[0]], probes[1]])
    names = backend.points
    here = pos[1]
    size = float(np.max(np.hypot(*(here[:, None, :] - here[None, :, :]).transpose(2, 0, 1)))) or 1.0
    met = []
    for i in range(len(names)):
        for j in range(i):
            d = [float(np.hypot(*(p[i] - p[j]))) for p in pos]
            if d[1] <= 1e-5 * size and d[0] > 1e-4 * size and d[2] > 1e-4 * size:
                met.append(f"{names[i]} meets {names[j]}")
    return f"{', '.join(met)} (the constraint Jacobian loses rank there)" if met else generic


def _edge(backend: Closed, good: float, bad: float) -> float:
    """Bisect on the worst dyad discriminant to the last angle that still closes."""
    return closing_edge(backend.prog, float(good), float(bad))


def outputs_of(comp: Compiled, names: dict[str, tuple[str, ...]]) -> list[tuple[str, str]]:
    """Candidate outputs for dead centres: sliders on the frame, then links pivoted on the frame (not driven).

    Each is (``"slide"``, joint) or (``"link"``, link).
    """
    lay, mech = comp.layout, comp.mech
    driven = {d.link or d.joint or "" for d in lay.drives}
    out: list[tuple[str, str]] = []
    for ps in lay.paths:
        if ps.guide == mech.ground and ps.joint not in driven:
            out.append(("slide", ps.joint))
    pivoted = []
    for j in mech.joints:
        if kind_of(j).role == "pin" and mech.ground in j.links:
            for lk in j.links:
                if lk != mech.ground and lk not in driven and lk in names["links"] and lk not in pivoted:
                    pivoted.append(lk)
    out += [("link", lk) for lk in pivoted]
    return out


def refiner(
    backend: Any,
    names: dict[str, tuple[str, ...]],
    keys: Sequence[str],
    refs: np.ndarray,
    regular: bool = False,
) -> Callable[[np.ndarray], np.ndarray]:
    """fn(grid (K, m)) → values (K, m) of ``keys[k]`` on row k, one backend call for all rows.

    Angles of links are brought to the branch of ``refs[k]`` (the grid value
    the row refines), since the closed form returns them in (−π, π].  With
    ``regular``, values where the configuration is singular (condition above
    :data:`~.dyads.ACCURATE_COND`; a Newton step judged singular) are NaN: an
    extreme refined toward a change point's singular Jacobian would otherwise
    report rounding blown up by cond² (3e9 m/s for a speed of 1) as a value,
    and positions there are good only to about 1e-16·cond.
    """

    groups: dict[str, list[int]] = {}
    for k, key in enumerate(keys):
        groups.setdefault(key, []).append(k)
    index = {key: np.array(rows) for key, rows in groups.items()}

    def fn(grid: np.ndarray) -> np.ndarray:
        data = backend.evaluate(grid)
        out = np.empty(grid.shape)
        if regular:
            with np.errstate(invalid="ignore"):
                singular = ~(data["condition"] <= ACCURATE_COND)
        for key, rows in index.items():
            vals = pick(data, names, key)[rows]
            if key.startswith("angle."):
                ref = refs[rows][:, None]
                vals = np.where(np.isfinite(ref), vals + _TWO_PI * np.round((ref - vals) / _TWO_PI), vals)
            out[rows] = np.where(singular[rows], np.nan, vals) if regular else vals
        return out

    return fn


def _dedupe(events: list[Event], phi: np.ndarray) -> list[Event]:
    """One event per place: over a full cycle 0° and 360° are the same crank position."""
    full = abs(abs(phi[-1] - phi[0]) - _TWO_PI) < 1e-9
    out: list[Event] = []
    for e in sorted(events, key=lambda e: e.angle):
        same = [
            o
            for o in out
            if o.subject == e.subject
            and (abs(o.angle - e.angle) < 1e-9 or (full and abs(abs(o.angle - e.angle) - _TWO_PI) < 1e-9))
        ]
        if not same:
            out.append(e)
    return out


def find_dead_centres(
    backend: Any,
    comp: Compiled,
    phi: np.ndarray,
    data: dict[str, np.ndarray],
    ok: np.ndarray,
    names: dict[str, tuple[str, ...]],
    rest: Mapping[str, np.ndarray] | None = None,
) -> tuple[tuple[Event, ...], list[tuple[str, str]]]:
    """Where each output reverses: the sign change of its speed, root-found to rounding.

    Closed form: a bracket zoom on the speed.  Newton: regula falsi (Illinois)
    with a solve per iterate.  ``rest`` marks each output's steps inside a dwell
    (:func:`~.sweep_rest.find_dwells`): at rest there, it reverses at none of them.
    """
    outputs = outputs_of(comp, names)
    rest = rest or {}
    brackets: list[tuple[str, str, float, float, float, float]] = []  # name, key, lo, hi, v_lo, v_hi
    for kind, name in outputs:
        key = f"sliding.{name}" if kind == "slide" else f"omega.{name}"
        v = pick(data, names, key)
        finite = v[np.isfinite(v)]
        tiny = 1e-12 * (float(np.max(np.abs(finite))) if finite.size else 1.0)
        sgn = np.where(np.abs(v) <= tiny, 0.0, np.sign(v))
        resting = rest.get(name, np.zeros(v.shape, bool))
        for s, e in runs(ok & np.isfinite(v) & ~resting):
            for k in range(s, e):
                if sgn[k] == 0.0:  # on a grid angle: refine only if the neighbours bracket it
                    if s < k < e - 1 and sgn[k - 1] * sgn[k + 1] < 0:
                        brackets.append((name, key, phi[k - 1], phi[k + 1], v[k - 1], v[k + 1]))
                    else:
                        brackets.append((name, key, phi[k], phi[k], v[k], v[k]))
                elif k + 1 < e and sgn[k] * sgn[k + 1] < 0:
                    brackets.append((name, key, phi[k], phi[k + 1], v[k], v[k + 1]))
    if not brackets:
        return (), outputs
    lo = np.array([b[2] for b in brackets], float)
    hi = np.array([b[3] for b in brackets], float)
    keys = [b[1] for b in brackets]
    pos_keys = [f"displacement.{b[0]}" if b[1].startswith("sliding") else f"angle.{b[0]}" for b in brackets]
    if backend.vectorised:
        roots, _ = zoom(refiner(backend, names, keys, np.full(len(keys), np.nan)), lo, hi, "root")
        at = refiner(backend, names, pos_keys, np.full(len(keys), np.nan))(roots[:, None])[:, 0]
    else:  # one bracket at a time along a warm-started walk, on the sweep's branch
        roots, at = np.empty(len(brackets)), np.empty(len(brackets))
        walk = Walk(backend, phi[0])
        for i in sorted(range(len(brackets)), key=lambda i: abs(lo[i] - phi[0])):  # along the sweep
            probe = _probe(walk, names, keys[i], math.nan)
            roots[i] = illinois(
                lambda g, probe=probe: np.array([[probe(float(g[0, 0]))]]),  # type: ignore[misc]
                lo[i : i + 1],
                hi[i : i + 1],
                np.array([brackets[i][4]]),
                np.array([brackets[i][5]]),
            )[0]
            at[i] = _probe(walk, names, pos_keys[i], math.nan)(float(roots[i]))
    at = np.where(
        [k.startswith("angle.") for k in pos_keys], np.mod(at, _TWO_PI), at
    )  # link angles in [0, 2π)
    events = [
        Event("dead centre", float(r), b[0], float(x)) for r, x, b in zip(roots, at, brackets, strict=True)
    ]
    return tuple(_dedupe(events, phi)), outputs


#: Quantities of the position level: defined at a toggle or change point, where the rates are not.
POSITION_KINDS = ("angle", "position", "displacement", "included")
#: Positions where two branches meet or the loop stops closing are good to about √ε (1.5e-8 of the
#: size; the discriminant's rounding under a square root): a value read at a toggle or change point
#: counts as an extreme only when it passes the extreme found elsewhere by more than this (of the
#: size for a length, in rad for an angle).
AT_EVENT = 1e-6
#: An included angle at a toggle or change point of the links in line at its vertex (the event
#: says so) within this of 0 or π is that exactly: its three points are in line there.
IN_LINE = 1e-4
#: A link's unwrapped angle spanning a full turn less this (rad) turns right round: positions next
#: to a change point are good to about √ε, far inside it, and no rocker swings 359.99994°.
FULL_TURN = 1e-6


def turns_fully(v: np.ndarray, valid: np.ndarray, phi: np.ndarray) -> bool:
    """A link whose unwrapped angle ``v`` spans a full turn, or ends a whole turn on from where it
    started over a full turn of the drive, turns right round: it has no swing (a parallelogram's
    rocker).  A 2:1 wheel's half turn per turn of its pinion is a swing of 180°, not a turn."""
    if not np.any(valid):
        return False
    span = float(np.max(v[valid]) - np.min(v[valid]))
    turn = phi.size > 2 and abs(abs(phi[-1] - phi[0]) - _TWO_PI) < 1e-9 and bool(np.all(valid))
    return span >= _TWO_PI - FULL_TURN or (turn and abs(float(v[-1] - v[0])) >= _TWO_PI - FULL_TURN)


def find_extremes(
    backend: Any,
    phi: np.ndarray,
    data: dict[str, np.ndarray],
    ok: np.ndarray,
    names: dict[str, tuple[str, ...]],
    keys: Sequence[str],
    events: Sequence[Event] = (),
    placed: np.ndarray | None = None,
) -> tuple[Extreme, ...]:
    """Grid extremes of every quantity, refined between the neighbouring steps.

    Closed form: all at once by :func:`zoom`.  Newton: Brent's method on the
    Newton solve, along a :class:`Walk` (warm-started, on the sweep's branch).
    Over a full turn a quantity that comes back to its first value (periodic)
    is refined across the seam (0° and 360° are neighbours); one that does not
    (a 2:1 wheel turns half a turn) is refined only inside the range, never
    extrapolated beyond it.  A quantity that does not vary (a piston's angle)
    or a link that turns right round (its unwrapped angle only grows) has no
    extreme worth reporting and is left out.

    ``ok`` marks the regular assembled steps, ``placed`` (default ``ok``) every assembled
    one, those next to a toggle or change point too, where positions are still defined:
    a link turns right round if its angle does over them.  ``events`` are the toggles
    and change points, located to rounding: a position-level quantity may have its
    extreme there, where refinement cannot look (the configuration is singular) and the
    grid does not reach — a transmission angle is 0 or 180° where coupler and output
    fold into line, at a gap's edge or as the branch passes a change point (:func:`_at_events`).
    """
    placed = ok if placed is None else placed
    turn = phi.size > 2 and abs(abs(phi[-1] - phi[0]) - _TWO_PI) < 1e-9 and bool(np.all(ok))
    seam_event = any(min(abs(e.angle - phi[0]), abs(e.angle - phi[-1])) < 1e-9 for e in events)
    rows: list[tuple[str, str, int, float, float, float]] = []  # key, mode, k, lo, hi, grid value
    wraps: dict[str, bool] = {}
    sizes: dict[str, float] = {}  # each quantity's largest |value|: its rounding is relative to it
    for key in keys:
        v = pick(data, names, key)
        valid = ok & np.isfinite(v)
        if not np.any(valid):
            continue
        size = sizes[key] = max(float(np.max(np.abs(v[valid]))), 1e-300)
        span = float(np.max(v[valid]) - np.min(v[valid]))
        if span <= 1e-12 * size:
            continue
        if key.startswith("angle.") and turns_fully(v, placed & np.isfinite(v), phi):
            continue
        # periodic over the range: back to its first value after the turn (to the solver's accuracy),
        # and not because the turn ends on a change point: the branch continued from the drawing
        # either way meets there, but crosses the seam on the other side (no neighbours across it)
        full = wraps[key] = (
            turn and not seam_event and bool(valid[0] and valid[-1] and abs(v[-1] - v[0]) <= 1e-8 * size)
        )
        for mode in ("max", "min"):
            vv = np.where(valid, v, -np.inf if mode == "max" else np.inf)
            k = int(np.argmax(vv) if mode == "max" else np.argmin(vv))
            lo = (
                phi[k - 1]
                if k > 0 and valid[k - 1]
                else (phi[-2] - _TWO_PI * np.sign(phi[-1] - phi[0]) if full and k == 0 else phi[k])
            )
            hi = (
                phi[k + 1]
                if k + 1 < phi.size and valid[k + 1]
                else (phi[1] + _TWO_PI * np.sign(phi[-1] - phi[0]) if full and k == phi.size - 1 else phi[k])
            )
            rows.append((key, mode, k, min(lo, hi), max(lo, hi), float(v[k])))
    sign = np.array([1.0 if r[1] == "max" else -1.0 for r in rows])
    ang, val = np.full(len(rows), np.nan), np.full(len(rows), np.nan)
    if rows and backend.vectorised:
        # minima are maxima of −v: one zoom refines every extreme of every quantity at once
        inner = refiner(backend, names, [r[0] for r in rows], np.array([r[5] for r in rows]), regular=True)
        ang, val = zoom(
            lambda g: sign[:, None] * inner(g),
            np.array([r[3] for r in rows]),
            np.array([r[4] for r in rows]),
            "max",
        )
    elif rows:
        walk = Walk(backend, phi[0])
        for i in sorted(range(len(rows)), key=lambda i: abs(phi[rows[i][2]] - phi[0])):  # along the sweep
            key, _mode, k, lo, hi, grid = rows[i]
            probe, sg = _probe(walk, names, key, grid), float(sign[i])
            x, fx = brent(lambda a, p=probe, sg=sg: -sg * p(a), lo, hi, float(phi[k]), -sg * grid)  # type: ignore[misc]
            ang[i], val[i] = x, -fx
    results: dict[tuple[str, str], tuple[float, float]] = {}
    for i, r in enumerate(rows):
        x = sign[i] * val[i]
        better = (x >= r[5]) if r[1] == "max" else (x <= r[5])
        results[(r[0], r[1])] = (
            (float(ang[i]), float(x)) if better and math.isfinite(x) else (float(phi[r[2]]), r[5])
        )
    _at_events(backend, phi, data, ok, names, results, events)
    _unbounded(backend, names, results, [e for e in events if e.kind == "toggle"])
    return tuple(
        _extreme(key, results, phi, wraps[key], sizes[key]) for key in dict.fromkeys(r[0] for r in rows)
    )


def _extreme(
    key: str, results: dict[tuple[str, str], tuple[float, float]], phi: np.ndarray, wraps: bool, size: float
) -> Extreme:
    """One quantity's :class:`Extreme` from its refined largest and least values (angle, value).

    A zero (a speed at a dead centre) is found as a difference of terms of the quantity's
    ``size``: below 1e-10 of that it is rounding (2.3e-13 m/s among speeds of 1 m/s), shown as 0.
    """
    (amax, vmax), (amin, vmin) = results[(key, "max")], results[(key, "min")]
    if wraps:
        amax, amin = _into(amax, phi), _into(amin, phi)
    vmax, vmin = (0.0 if abs(x) <= 1e-10 * size else x for x in (vmax, vmin))
    return Extreme(key, quantity_unit(key), amax, vmax, amin, vmin)


def left_out_notes(
    data: dict[str, np.ndarray],
    ok: np.ndarray,
    names: dict[str, tuple[str, ...]],
    asked: Sequence[str],
    extremes: Sequence[Extreme],
    phi: np.ndarray,
    show: Callable[[float, str], str],
) -> list[str]:
    """Why a quantity the user asked for has no row of extremes (:func:`find_extremes` leaves it out).

    A quantity that does not vary (a crank's α at constant speed, a piston's angle), a link
    that turns right round, or one never computed (no step assembled): without a note the
    asked row would simply be missing.  ``show`` writes a value with its unit.
    """
    reported = {e.quantity for e in extremes}
    notes = []
    for key in dict.fromkeys(asked):
        if key in reported:
            continue
        v = pick(data, names, key)
        valid = ok & np.isfinite(v)
        if not np.any(valid):
            notes.append(f"{key}: not computed at any step of the sweep (no extremes)")
        elif key.startswith("angle.") and turns_fully(v, valid, phi):
            notes.append(f"{key}: the link turns right round (no largest or least angle)")
        else:
            value = float(np.median(v[valid]))
            notes.append(f"{key} does not vary over the sweep: {show(value, quantity_unit(key))} throughout")
    return notes


def _at_events(
    backend: Any,
    phi: np.ndarray,
    data: dict[str, np.ndarray],
    ok: np.ndarray,
    names: dict[str, tuple[str, ...]],
    results: dict[tuple[str, str], tuple[float, float]],
    events: Sequence[Event],
) -> None:
    """Each position-level extreme compared with the quantity at every toggle and change point.

    There two branches of the assembly meet, or the loop stops closing: refinement sees a
    singular configuration and leaves it out, so a quantity that turns there (a V, as the
    transmission angle of a parallelogram at 0° and 180°) kept the nearest regular step's
    value (1° off, and 0.1° at ten times the steps).  The quantity is read at the event
    itself (its angle located to rounding; positions there good to about √ε), and counts
    when it passes the extreme by more than :data:`AT_EVENT`.  An included angle P–Q–R at
    an event of the links in line at Q, within :data:`IN_LINE` of 0 or π, is that exactly.
    ``results`` ((key, "max"|"min") → (angle, value)) is updated in place.
    """
    keys = [k for k in dict.fromkeys(key for key, _mode in results) if k.split(".")[0] in POSITION_KINDS]
    if not keys or not events:
        return
    rows = [(key, e) for key in keys for e in events]
    refs = np.empty(len(rows))
    for i, (key, e) in enumerate(rows):  # a link's angle on the turn of the step nearest the event
        v = pick(data, names, key)
        valid = np.flatnonzero(ok & np.isfinite(v))
        refs[i] = v[valid[np.argmin(np.abs(phi[valid] - e.angle))]] if valid.size else math.nan
    # Newton does not converge on a limit itself (its Jacobian is singular there): the nearest
    # angles either side that it does, 1e-12 … 1e-8 rad away (a position there is √δ off)
    nudges = np.array([0.0, -1e-12, 1e-12, -1e-10, 1e-10, -1e-8, 1e-8])
    if backend.vectorised:
        at = np.array([e.angle for _key, e in rows])
        grid = at[:, None] + nudges[None, :] * np.maximum(1.0, np.abs(at))[:, None]
        tries = refiner(backend, names, [key for key, _e in rows], refs)(grid)
        vals = tries[np.arange(len(rows)), np.argmax(np.isfinite(tries), axis=1)]
    else:
        walk = Walk(backend, phi[0])
        vals = np.full(len(rows), np.nan)
        for i in sorted(range(len(rows)), key=lambda i: abs(rows[i][1].angle - phi[0])):  # along the sweep
            for nudge in nudges * max(1.0, abs(rows[i][1].angle)):
                vals[i] = _probe(walk, names, rows[i][0], float(refs[i]))(rows[i][1].angle + nudge)
                if math.isfinite(float(vals[i])):
                    break
    size = _extent(data, ok)
    for (key, e), x in zip(rows, vals, strict=True):
        if not math.isfinite(float(x)):
            continue
        x = float(x)
        kind = key.split(".")[0]
        if kind == "included" and re.search(rf"in line at {re.escape(key.split('.')[2])}(?!\w)", e.subject):
            x = 0.0 if x <= IN_LINE else math.pi if x >= math.pi - IN_LINE else x
        margin = AT_EVENT * (1.0 if kind in ("angle", "included") else size)
        if x > results[(key, "max")][1] + margin:
            results[(key, "max")] = (e.angle, x)
        if x < results[(key, "min")][1] - margin:
            results[(key, "min")] = (e.angle, x)


#: Rates: undefined at a toggle, and most grow without bound toward one.
RATE_KINDS = ("omega", "alpha", "velocity", "acceleration", "sliding")
#: How near a toggle (rad, or of the parameter's size) a rate is read to see whether it grows
#: without bound: there the configuration is still regular (condition about 1e3 to 1e4).
TOWARD = (1e-6, 1e-7)


def _unbounded(
    backend: Any,
    names: dict[str, tuple[str, ...]],
    results: dict[tuple[str, str], tuple[float, float]],
    toggles: Sequence[Event],
) -> None:
    """A rate that grows without bound toward a toggle has an infinite extreme there.

    At a toggle the links in line cannot pass the motion on: velocities there grow like
    Δθ^(−1/2), accelerations like Δθ^(−3/2), and the largest value over the sweep is ∞,
    not the last regular step's (the rod of Khurmi's six-link slider: 257 rad/s a degree
    away).  Each rate is read 1e-6 and 1e-7 rad from each toggle, on the side that closes:
    where it is larger than its extreme and grew more than twice as the distance shrank
    tenfold (√10 for a velocity; a rate that stays finite barely moves), the extreme is
    ±∞ at the toggle.  ``results`` is updated in place.
    """
    keys = [k for k in dict.fromkeys(key for key, _mode in results) if k.split(".")[0] in RATE_KINDS]
    if not keys or not toggles or not backend.vectorised:
        return
    rows = [(key, t) for key in keys for t in toggles]
    at = np.array([t.angle for _key, t in rows])
    scale = np.maximum(1.0, np.abs(at))
    steps = np.array([-TOWARD[0], -TOWARD[1], TOWARD[0], TOWARD[1]])
    grid = at[:, None] + steps[None, :] * scale[:, None]
    vals = refiner(backend, names, [key for key, _t in rows], np.full(len(rows), np.nan), regular=True)(grid)
    for (key, t), (far_l, near_l, far_r, near_r) in zip(rows, vals, strict=True):
        for far, near in ((far_l, near_l), (far_r, near_r)):
            if not (math.isfinite(far) and math.isfinite(near)) or abs(near) <= 2.0 * abs(far):
                continue
            mode = "max" if near > 0 else "min"
            if abs(near) > abs(results[(key, mode)][1]):
                results[(key, mode)] = (t.angle, math.copysign(math.inf, near))


def unbounded_notes(extremes: Sequence[Extreme], at: Callable[[float], str]) -> list[str]:
    """A note for each infinite extreme (:func:`_unbounded`), ``at`` writing the parameter."""
    out = []
    for ex in extremes:
        for word, angle, value in (
            ("largest", ex.max_angle, ex.max_value),
            ("least", ex.min_angle, ex.min_value),
        ):
            if math.isinf(value):
                sign = "" if value > 0 else "−"
                out.append(
                    f"{ex.quantity} grows without bound toward the toggle at {at(angle)}: its {word} value is {sign}∞"
                )
    return out


def _extent(data: dict[str, np.ndarray], ok: np.ndarray) -> float:
    """The largest distance of a point from the points' centre at the first assembled step (m)."""
    k = np.flatnonzero(ok)
    if not k.size:
        return 1.0
    pos = data["positions"][k[0]]
    pos = pos[np.all(np.isfinite(pos), axis=-1)]
    if not pos.size:
        return 1.0
    return float(np.max(np.hypot(*(pos - pos.mean(axis=0)).T))) or 1.0


def _into(a: float, phi: np.ndarray) -> float:
    """An angle of a full-cycle sweep brought into the swept range, the seam's own as its start.

    A flat extreme at 0° is refined to about 1e-8 rad, as often just below 360°: within
    :data:`SEAM` of the range's top it is the same crank position as its bottom, and is
    written there (0°, not 359.9999987°: angles in [0°, 360°)).
    """
    lo, hi = min(phi[0], phi[-1]), max(phi[0], phi[-1])
    while a < lo:
        a += _TWO_PI
    while a > hi:
        a -= _TWO_PI
    return lo if hi - a < SEAM else a


#: How near (rad) the top of a full turn a periodic quantity's extreme is the seam's (its start).
SEAM = 1e-6


def _probe(walk: Walk, names: dict[str, tuple[str, ...]], key: str, ref: float) -> Callable[[float], float]:
    """fn(angle) → ``key`` there along the walk (NaN where not reached); a link's angle on ``ref``'s turn."""

    def fn(angle: float) -> float:
        arrays = walk.to(angle)
        if arrays is None:
            return math.nan
        v = float(pick(arrays, names, key))
        if key.startswith("angle.") and math.isfinite(ref) and math.isfinite(v):
            v += _TWO_PI * round((ref - v) / _TWO_PI)
        return v

    return fn
