"""Forces over the cycle at constant input speed: the turning-moment diagram and the flywheel.

The input torque T(θ) (or a slider drive's force) is found on the sweep's grid
by one batched force solve (:class:`mech.forces.series.Evaluator`), and from it:

* **the mean torque**, T_mean = ∫ T dθ / Δθ over the range.  A trapezoid over a
  whole period of a smooth periodic integrand converges fast, but a load table
  has kinks at its rows, and a range that is not a whole period has ends: so the
  integral is taken piecewise between the tables' rows (where T is smooth), in
  pieces no wider than :data:`PIECE` whatever the grid, each by 4-node
  Gauss–Legendre (exact for septics) with solves at its nodes, all in one
  batch.  Against a closed-form engine it agrees to 1e-12; a 1° trapezoid is
  3e-5 off;
* **the energy** delivered to the flywheel, E(θ) = ∫ (T_mean − T) dθ from the
  range's start (what the input gives beyond what the mechanism takes, at
  constant speed): the speed is greatest where E is greatest.  E is exact at the
  pieces' ends; its greatest and least are where T crosses T_mean, each crossing
  looked for among the grid's steps, the nodes and the rows (so a coarse grid
  misses none), located by zooming in (16 sub-steps a round, to about 1e-10 rad)
  and E there integrated from the piece's start by Gauss–Legendre;
* **the fluctuation of energy** ΔE = E_max − E_min (DESIGN § 1.4: the greatest
  minus the least of ∫ (T − T_mean) dθ, the same span), and with
  ``flywheel: {fluctuation: C_s}`` the flywheel's moment of inertia
  I = ΔE / (ω² C_s) (Khurmi & Gupta, *Theory of Machines*, § 16.8: the whole
  flywheel, the mechanism's own inertia not subtracted);
* **the greatest values** of the input effort and of every pair's force, with
  the drive angles where they occur (the bearing loads a designer sizes for),
  refined as the kinematic sweep refines its extremes: a sub-grid of 16 round
  the best sample (of the grid, the nodes and the rows: a peak at a table's kink
  is sampled exactly), zoomed 8× a round.  The refinements of every quantity are
  solved together, a batch a round.

The range is by default one cycle of the loads: a turn of the crank, or the
least whole number of turns that holds a whole number of every table's span
(two turns for a four-stroke engine's 720°).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from fractions import Fraction

import numpy as np

from mech._records import dataclass
from mech.errors import InputError
from mech.forces.core import unsaid_notes
from mech.forces.series import Evaluator, ForceSeries, PairKey
from mech.model import Mechanism
from mech.options import SolveOptions

__all__ = [
    "PIECE",
    "ForceCycle",
    "Peak",
    "cycle_span",
    "force_cycle",
    "gauss_nodes",
    "integrate",
    "pair_quantity",
]

#: Widest piece integrated by one Gauss–Legendre rule (rad).
PIECE = math.radians(2.0)
#: Zoom rounds of the refinements (16 sub-steps a round): a 1° step is within 1e-8° after 7.
ROUNDS = 7
#: Most turns the default range may take to close the loads' cycle.
MAX_TURNS = 48

_GL = np.polynomial.legendre.leggauss(4)


@dataclass(frozen=True, slots=True)
class Peak:
    """The greatest value of one quantity over the range and the drive angle (rad) where it occurs."""

    quantity: str
    value: float
    angle: float


@dataclass(frozen=True)
class ForceCycle:
    """What :func:`force_cycle` finds over the range (SI; angles in rad, the drive's own).

    ``series`` is the grid's forces (:class:`~mech.forces.series.ForceSeries`);
    ``energy`` (K,) the flywheel's energy E(θ) = ∫ (T_mean − T) dθ at the grid's
    angles (J), from the range's start; ``mean`` T_mean, ``work`` ∫ T dθ over the
    range (J, the input's work over it); ``fluctuation`` ΔE; ``greatest`` and
    ``least`` (angle, E) where E (and so the speed) is greatest and least;
    ``coefficient`` the file's C_s and ``flywheel`` I = ΔE/(ω² C_s) (kg·m²), None
    without one; ``effort_max``/``effort_min`` the input effort's extremes;
    ``peaks`` each pair force's greatest magnitude; ``shaking`` the greatest
    shaking force.  ``kind`` is ``torque`` (a crank) or ``force`` (a slider drive,
    its energy ∫ F ds).  None where the range holds a step that cannot be solved.
    """

    mechanism: str
    drive: str
    kind: str
    omega: float | None
    static: bool
    start: float
    stop: float
    period: float
    series: ForceSeries
    energy: np.ndarray
    mean: float | None
    work: float | None
    fluctuation: float | None
    greatest: tuple[float, float] | None
    least: tuple[float, float] | None
    coefficient: float | None
    flywheel: float | None
    effort_max: Peak | None
    effort_min: Peak | None
    peaks: tuple[Peak, ...]
    shaking: Peak | None
    notes: tuple[str, ...]

    @property
    def whole(self) -> bool:
        """True when the range is a whole number of the loads' cycles (ΔE and I mean what they say)."""
        turns = abs(self.stop - self.start) / self.period
        return turns >= 1.0 - 1e-9 and abs(turns - round(turns)) < 1e-9


def cycle_span(mech: Mechanism) -> float:
    """The loads' cycle (rad): a turn, or the least number of turns holding every table's span whole."""
    span = Fraction(360)
    for load in mech.loads:
        if load.period:
            s = Fraction(round(math.degrees(load.period) * 1e6), 10**6)
            if s > 0:
                span = _lcm(span, s)
    if span > 360 * MAX_TURNS:
        return 2.0 * math.pi
    return math.radians(float(span))


def _lcm(a: Fraction, b: Fraction) -> Fraction:
    """The least common multiple of two positive rationals."""
    num = a.numerator * b.denominator
    other = b.numerator * a.denominator
    den = a.denominator * b.denominator
    return Fraction(num * other // math.gcd(num, other), den)


def gauss_nodes(
    a: np.ndarray, b: np.ndarray, piece: float = PIECE
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The nodes (ascending), weights and owning interval of 4-node Gauss–Legendre rules on each
    interval (a_i, b_i), cut into pieces no wider than ``piece`` (:data:`PIECE`, in the drive's
    angle; a slider drive's pieces are that times the mechanism's size): ∫ₐᵇ f ≈ Σ w f(x).

    The rule is exact for polynomials of degree 7; on a 2° piece of a torque whose harmonics
    reach the 10th its error is below 1e-14 of the torque.  The intervals must hold no kink of
    the integrand (split them at its kinks first).
    """
    a, b = np.asarray(a, float), np.asarray(b, float)
    width = b - a
    pieces = np.maximum(np.ceil(np.abs(width) / piece - 1e-9), 1).astype(int)
    owner = np.repeat(np.arange(a.size), pieces)
    index = np.arange(owner.size) - np.repeat(np.cumsum(pieces) - pieces, pieces)
    h = (width / pieces)[owner]
    mid, half = a[owner] + (index + 0.5) * h, h / 2
    t, w = _GL
    x = (mid[:, None] + half[:, None] * t).ravel()
    weights = (half[:, None] * w).ravel()
    who = np.repeat(owner, t.size)
    order = np.argsort(x, kind="stable")
    return x[order], weights[order], who[order]


def integrate(
    f: Callable[[np.ndarray], np.ndarray], a: np.ndarray, b: np.ndarray, piece: float = PIECE
) -> np.ndarray:
    """∫ₐᵇ f for each interval (a_i, b_i) by :func:`gauss_nodes`; ``f`` takes every node at once."""
    a = np.asarray(a, float)
    if not a.size:
        return np.zeros(0)
    x, w, owner = gauss_nodes(a, b, piece)
    return np.bincount(owner, weights=w * f(x), minlength=a.size)


def force_cycle(
    mech: Mechanism,
    options: SolveOptions | None = None,
    *,
    start: float | None = None,
    stop: float | None = None,
    steps: int = 360,
) -> ForceCycle:
    """The forces over the range ``start``–``stop`` (the drive's angle, rad; a slider drive's
    position, m) in ``steps`` steps, and what they come to over it (see the module's docstring).

    By default a crank is swept over one cycle of its loads (:func:`cycle_span`)
    from 0; a slider drive needs its stroke.

    Raises
    ------
    InputError
        No drive, a slider drive without its range, an empty range.
    MechError
        Whatever the kinematic sweep raises (no assembly as drawn …).
    """
    if not mech.drives:
        raise InputError(
            f"{mech.label} has no drive: forces over the cycle move its drive",
            hint="add drive: {link: crank, angle: …, rpm: …}",
        )
    d = mech.drives[0]
    kind = "torque" if d.link is not None else "force"
    if kind == "force" and (start is None or stop is None):
        raise InputError(
            f"{mech.label} is driven by the slider {d.joint}: give its stroke", hint="--from and --to"
        )
    first = 0.0 if start is None else float(start)
    period = cycle_span(mech) if kind == "torque" else abs(float(stop) - first)  # type: ignore[arg-type]
    last = first + period if stop is None else float(stop)
    if first == last:
        raise InputError("the range of a force sweep must not be empty")
    ev = Evaluator(mech, options)
    grid = np.linspace(first, last, steps + 1)
    series = ev(grid)
    totals, peaks = _over_range(mech, ev, grid, series)
    omega = _speed(mech, ev)
    totals.energy.flags.writeable = False
    coefficient = mech.flywheel.fluctuation if mech.flywheel is not None else None
    notes = _notes(mech, ev, series, kind, first, last, period)
    flywheel = None
    if coefficient is not None and totals.fluctuation is not None:
        if kind != "torque" or not omega:
            notes.append("no flywheel: the drive does not turn at a speed (give its rpm)")
        else:
            flywheel = totals.fluctuation / (omega * omega * coefficient)
    return ForceCycle(
        mechanism=mech.label,
        drive=str(d.link or d.joint),
        kind=kind,
        omega=omega,
        static=ev.static,
        start=first,
        stop=last,
        period=period,
        series=series,
        energy=totals.energy,
        mean=totals.mean,
        work=totals.work,
        fluctuation=totals.fluctuation,
        greatest=totals.greatest,
        least=totals.least,
        coefficient=coefficient,
        flywheel=flywheel,
        effort_max=peaks.get("effort.max"),
        effort_min=peaks.get("effort.min"),
        peaks=tuple(p for key, p in peaks.items() if key.startswith("force.")),
        shaking=peaks.get("shaking_force"),
        notes=tuple(notes),
    )


def _notes(
    mech: Mechanism, ev: Evaluator, series: ForceSeries, kind: str, first: float, last: float, period: float
) -> list[str]:
    """What a reader of the cycle's numbers must know: gaps, a partial cycle, indeterminacy, statics."""
    notes = []
    if not np.isfinite(series.effort).all():
        notes.append("the mechanism cannot be solved at every step of the range: no mean or energy")
    turns = abs(last - first) / period
    if kind == "torque" and not (turns >= 1.0 - 1e-9 and abs(turns - round(turns)) < 1e-9):
        notes.append(
            f"the range is not a whole number of the loads' cycle ({math.degrees(period):g}°): "
            "the mean torque and the fluctuation of energy are over the range swept"
        )
    if not series.determinate[series.solved].all():
        notes.append(
            "the pairs' forces are indeterminate (redundant constraints): only the input effort is given"
        )
    if ev.static:
        notes.append("no drive speed: a static sweep (loads and gravity, no inertia)")
    notes += unsaid_notes(mech)
    return notes


def _speed(mech: Mechanism, ev: Evaluator) -> float | None:
    """The drive's ω (rad/s, ccw +), or a slider drive's speed (m/s), as the sweep ran; None in a
    static sweep."""
    return None if ev.static else ev.speed


#: An energy swing below this times the largest |effort| × the range is rounding (ΔE = 0).
_STEADY = 1e-10


@dataclass(frozen=True)
class _Totals:
    energy: np.ndarray
    mean: float | None = None
    work: float | None = None
    fluctuation: float | None = None
    greatest: tuple[float, float] | None = None
    least: tuple[float, float] | None = None


Extract = Callable[[ForceSeries], np.ndarray]


@dataclass
class _Job:
    """One refinement: a bracket zoomed round by round, to a maximum of ``extract`` or to its root."""

    lo: float
    hi: float
    extract: Extract
    root: bool
    best: tuple[float, float] = (math.nan, -math.inf)  # (angle, value) of a maximum


def _over_range(
    mech: Mechanism, ev: Evaluator, grid: np.ndarray, series: ForceSeries
) -> tuple[_Totals, dict[str, Peak]]:
    """The mean, the energy and its extremes, and every peak: the refinements solved together.

    The integral's nodes are solved with every quantity, so the crossings of T_mean and the
    peaks are looked for on the grid and the nodes together: a coarse grid (``--steps 4``) misses
    none that steps of at most :data:`PIECE` would find.
    """
    order = np.argsort(grid, kind="stable")
    lo, hi = float(grid[order[0]]), float(grid[order[-1]])
    effort = series.effort[order]
    if not np.isfinite(effort).all():
        peak_jobs = _peak_jobs(_pick(series, order))
        _zoom(ev, list(peak_jobs.values()))
        return _Totals(np.full(grid.size, math.nan)), _peaks(peak_jobs)
    piece = PIECE if mech.drives[0].link is not None else PIECE * ev.sys.scale  # a slider's: in m
    breaks = _breaks(mech, lo, hi, piece)
    nx, weights, owner = gauss_nodes(breaks[:-1], breaks[1:], piece)
    at = np.concatenate((nx, breaks))  # the breaks too: a peak at a table's row (a kink) is sampled exactly
    sort = np.argsort(at, kind="stable")
    solved = ev(at[sort])
    back = np.empty_like(sort)
    back[sort] = np.arange(sort.size)
    pieces = np.bincount(owner, weights=weights * solved.effort[back[: nx.size]], minlength=breaks.size - 1)
    dense = _merge(_pick(series, order), solved)
    peak_jobs = _peak_jobs(dense)
    if not np.isfinite(pieces).all():
        _zoom(ev, list(peak_jobs.values()))
        return _Totals(np.full(grid.size, math.nan)), _peaks(peak_jobs)
    cum = np.concatenate(([0.0], np.cumsum(pieces)))
    total = float(cum[-1])
    mean = total / (hi - lo)  # E below takes this one: E(hi) = E(lo), exactly, over a cycle
    if abs(total) <= 1e-12 * float(np.nanmax(np.abs(dense.effort))) * (hi - lo):
        total = 0.0  # reported as rounding: a cycle of inertia and gravity alone does no work
    at_breaks = mean * (breaks - lo) - cum  # E(θ) = ∫ (T_mean − T) dθ from lo, exact at the breaks
    above = dense.effort > mean
    crossings = np.flatnonzero(above[:-1] != above[1:])
    x = dense.angles
    root_jobs = [_Job(float(x[k]), float(x[k + 1]), _minus(mean), root=True) for k in crossings]
    _zoom(ev, root_jobs + list(peak_jobs.values()))
    roots = np.array([(job.lo + job.hi) / 2 for job in root_jobs])
    base = np.clip(np.searchsorted(breaks, roots, side="right") - 1, 0, breaks.size - 2)
    at_roots = at_breaks[base] + integrate(lambda a: mean - ev(a).effort, breaks[base], roots, piece)
    where = np.concatenate((breaks, roots))
    energy = np.concatenate((at_breaks, at_roots))
    origin = float(np.interp(grid[0], breaks, at_breaks))
    j, k = int(np.argmax(energy)), int(np.argmin(energy))
    sign = 1.0 if grid[-1] >= grid[0] else -1.0
    fluctuation = float(energy[j] - energy[k])
    # a constant effort (a gear train's) swings the energy by rounding only: no greatest, no least
    steady = fluctuation <= _STEADY * float(np.nanmax(np.abs(dense.effort), initial=0.0)) * (hi - lo)
    totals = _Totals(
        _on_grid(grid, dense.angles, dense.effort, mean, breaks, at_breaks) - origin,
        total / (hi - lo),
        sign * total,
        0.0 if steady else fluctuation,
        None if steady else (float(where[j]), float(energy[j] - origin)),
        None if steady else (float(where[k]), float(energy[k] - origin)),
    )
    return totals, _peaks(peak_jobs)


def _merge(a: ForceSeries, b: ForceSeries) -> ForceSeries:
    """Two series as one, by ascending angle, each angle once."""
    joined = ForceSeries(
        np.concatenate((a.angles, b.angles)),
        np.concatenate((a.effort, b.effort)),
        np.concatenate((a.parts, b.parts)),
        a.pairs,
        np.concatenate((a.forces, b.forces)),
        np.concatenate((a.shaking, b.shaking)),
        np.concatenate((a.moment, b.moment)),
        np.concatenate((a.solved, b.solved)),
        np.concatenate((a.determinate, b.determinate)),
    )
    order = np.argsort(joined.angles, kind="stable")
    x = joined.angles[order]
    distinct = np.concatenate(([True], np.diff(x) > 1e-14 * max(1.0, float(np.abs(x).max()))))
    return _pick(joined, order[distinct])  # a break on the grid once: a peak's bracket must not be empty


def _minus(mean: float) -> Extract:
    """T − T_mean from a series (its roots are where the energy turns)."""
    return lambda s: s.effort - mean


def _on_grid(
    grid: np.ndarray, x: np.ndarray, effort: np.ndarray, mean: float, breaks: np.ndarray, exact: np.ndarray
) -> np.ndarray:
    """E at the grid's angles, for the diagram and the CSV: the trapezoid rule along the grid,
    corrected to the exact values at the breaks (the correction spread linearly between them)."""
    pts = np.union1d(x, breaks)
    t = np.interp(pts, x, effort)
    trap = np.concatenate(([0.0], np.cumsum(np.diff(pts) * (mean - (t[:-1] + t[1:]) / 2))))
    drift = exact - np.interp(breaks, pts, trap)
    return np.interp(grid, pts, trap + np.interp(pts, breaks, drift))


def _peak_jobs(series: ForceSeries) -> dict[str, _Job]:
    """A zoom for the greatest input effort, the least, every pair force's and the shaking force's
    greatest, each bracketed by the neighbours of its best sample (``series`` in ascending angle)."""
    wanted: dict[str, Extract] = {
        "effort.max": lambda s: s.effort,
        "effort.min": lambda s: -s.effort,
        "shaking_force": lambda s: np.hypot(s.shaking[:, 0], s.shaking[:, 1]),
    }
    for i, key in enumerate(series.pairs):
        wanted[pair_quantity(key, series.pairs)] = _magnitude(i)
    at = series.angles
    jobs: dict[str, _Job] = {}
    for name, extract in wanted.items():
        vals = extract(series)
        if not np.isfinite(vals).any():
            continue
        k = int(np.nanargmax(vals))
        lo, hi = float(at[max(k - 1, 0)]), float(at[min(k + 1, at.size - 1)])
        jobs[name] = _Job(lo, hi, extract, False, (float(at[k]), float(vals[k])))
    return jobs


def _peaks(jobs: dict[str, _Job]) -> dict[str, Peak]:
    out = {}
    for name, job in jobs.items():
        angle, value = job.best
        out[name] = Peak(name, -value if name == "effort.min" else value, angle)
    return out


def _magnitude(index: int) -> Extract:
    """|F| of pair ``index`` from a series."""
    return lambda s: s.magnitude(index)


def pair_quantity(key: PairKey, pairs: tuple[PairKey, ...]) -> str:
    """``force.B``, or ``force.B.on.rocker`` for a joint of more links (a force on each after the first)."""
    joint, on, _ = key
    shared = sum(1 for k in pairs if k[0] == joint) > 1
    return f"force.{joint}.on.{on}" if shared else f"force.{joint}"


def _zoom(ev: Evaluator, jobs: list[_Job]) -> None:
    """Zoom every job's bracket in, all jobs' sub-steps solved together each round (16 a bracket)."""
    if not jobs:
        return
    t = np.linspace(0.0, 1.0, 17)
    for _ in range(ROUNDS):
        pts = np.array([job.lo + (job.hi - job.lo) * t for job in jobs])
        flat = pts.ravel()
        order = np.argsort(flat, kind="stable")
        rows = np.empty(flat.size, int)
        rows[order] = np.arange(flat.size)
        series = ev(flat[order])
        for i, job in enumerate(jobs):
            _narrow(job, pts[i], job.extract(_pick(series, rows[i * 17 : (i + 1) * 17])))


def _pick(series: ForceSeries, rows: np.ndarray) -> ForceSeries:
    """The steps ``rows`` of a series (one job's sub-steps)."""
    return ForceSeries(
        series.angles[rows],
        series.effort[rows],
        series.parts[rows],
        series.pairs,
        series.forces[rows],
        series.shaking[rows],
        series.moment[rows],
        series.solved[rows],
        series.determinate[rows],
    )


def _narrow(job: _Job, pts: np.ndarray, vals: np.ndarray) -> None:
    """The next bracket of a job from its values at the sub-steps ``pts`` (unsolved ones left out)."""
    ok = np.isfinite(vals)
    if not ok.any():
        return
    if job.root:
        s = vals[ok] > 0
        at = pts[ok]
        cross = np.flatnonzero(s[:-1] != s[1:])
        if cross.size:
            j = int(cross[0])
            job.lo, job.hi = float(at[j]), float(at[j + 1])
        return
    vals = np.where(ok, vals, -np.inf)
    j = int(np.argmax(vals))
    if vals[j] > job.best[1]:
        job.best = (float(pts[j]), float(vals[j]))
    job.lo, job.hi = float(pts[max(j - 1, 0)]), float(pts[min(j + 1, pts.size - 1)])


def _breaks(mech: Mechanism, lo: float, hi: float, piece: float) -> np.ndarray:
    """Where the integral is split: every table row (repeated with its span) inside the range, and
    enough more that no piece is wider than ``piece``; ascending, the range's ends included."""
    points = [np.linspace(lo, hi, math.ceil((hi - lo) / piece) + 1)]
    for load in mech.loads:
        if load.table is None or not load.period:
            continue
        rows = np.array([r[0] for r in load.table])
        span = load.period
        for k in range(math.floor((lo - rows.max()) / span), math.ceil((hi - rows.min()) / span) + 1):
            shifted = rows + k * span
            points.append(shifted[(shifted > lo) & (shifted < hi)])
    merged = np.unique(np.concatenate(points))
    keep = np.concatenate(([True], np.diff(merged) > 1e-12 * max(1.0, abs(lo), abs(hi))))
    merged = merged[keep]
    merged[-1] = hi
    return merged
