"""Sweeps over the crank's cycle: series, gaps, toggles, dead centres, extremes, time ratio.

:func:`sweep` solves a single-crank mechanism at every angle of an array.
Where the chain decomposes into dyads (:mod:`.dyads`) the whole array is one
vectorised evaluation of the closed form — a 3,600-step four-bar sweep takes
about a millisecond — and every refinement (an extreme, a dead centre, the
edge of a gap) evaluates the same closed form at a few angles at once.
Anything else is swept by Newton continuation: each step starts from the
last one's solution moved by the predictor ``q + q̇·Δθ``, so the assembly
branch stays the drawn one.

Rules the results keep:

* **No silent branch jumps.**  The closed form keeps the drawn assembly
  (the sign of each dyad); where a dyad cannot close the steps are *not
  assembled* (NaN, ``assembled`` False) and the range is reported as a
  :class:`Gap` with how far the loop is from closing.  The gap's edges are
  toggles (links in line), located by bisection to rounding.  A Newton
  sweep that meets a limit stops there and says so.
* **Change points are passed on the branch with a continuous tangent.**
  Where a dyad's discriminant touches zero with the loop closed on both
  sides (:func:`~mech.kinematics.dyads.change_points`: the Peaucellier
  inversor folding flat), the closed form flips that dyad's sign past it, as
  continuation's predictor would follow the tangent, and the sweep reports
  the change point (``Sweep.change_points``, a note).
* **Singular steps are not reported as numbers.**  Where the dyad
  condition number exceeds :data:`~mech.kinematics.dyads.ACCURATE_COND`
  (1e5, within about 1e-10 rad of a toggle: rates there are good to less
  than 1e-6), velocities and accelerations are NaN and a note says how
  many; the largest condition met is reported.  Newton sweeps use the
  solver's own :data:`~mech.kinematics.solve.SINGULAR`.  Refining an
  extreme leaves such configurations out too (a change point's rows are
  singular where the two branches meet).
* **Extremes and dead centres are refined**, not read off the grid: the
  closed form is evaluated on a fine sub-grid round each candidate, zooming
  in 16× per round until the bracket is at rounding, so an extreme value is
  exact to about 1e-15 relative and its angle to about 1e-8 rad (the top of
  a smooth maximum is flat: value changes only as Δθ²); a dead centre's
  angle, a root, is found to about 1e-15 rad.  A Newton sweep refines each
  one between its neighbouring steps by Brent's method (extremes) or regula
  falsi (dead centres) on Newton solves warm-started along the sweep's own
  branch (:class:`Walk`), to the solver's tolerance.  Over a full turn only
  a quantity that comes back to its first value is taken as periodic (a
  2:1 wheel is not); nothing is extrapolated beyond the range swept.
* **Bounded memory.**  A sweep whose arrays would exceed
  :data:`~.sweep_grid.MEMORY_BUDGET` (1 GiB, estimated per angle from the chain) is
  refused before solving, with the number of angles that fit.

The quick-return time ratio is the crank angle of the slow stroke over that
of the fast one, between the two dead centres of the output (the last slider
on a fixed guide, else the last link pivoted on the frame), over a full,
gap-free revolution (Khurmi & Gupta, *Theory of Machines*, ch. 5, the crank
and slotted lever: cutting / return = (360° − β)/β, β the crank angle of the
return stroke).

The work is split by job: :mod:`.sweep_result` (what is returned),
:mod:`.quantities` (keys and units), :mod:`.sweep_backends` (closed form,
Newton), :mod:`.sweep_events` (what is found) and :mod:`.roots` (the
refinements' root finders); this module is the driver and the limits of the
grid it analyses, whose limits (``MEMORY_BUDGET``, ``RESOLVE``, ``ANGLE_PRECISION``) are in
:mod:`.sweep_grid`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from mech._records import dataclass
from mech.errors import InputError, UnsupportedError
from mech.kinematics.compiled import instant_why
from mech.kinematics.dyads import ACCURATE_COND, DyadProgram, program
from mech.kinematics.march import MAX_SPAN, Marcher
from mech.kinematics.quantities import (
    LEVELS,
    check_quantity,
    contact_points_asked,
    default_quantities,
    quantity_unit,
)
from mech.kinematics.result import Kinematics
from mech.kinematics.runs import unwrap_runs
from mech.kinematics.solve import (
    SINGULAR,
    Compiled,
    compiled,
    instant_pairs,
    refuse_flipped,
    refuse_underdriven,
    solve,
)
from mech.kinematics.sweep_backends import Closed, Newton, law_series, newton_series, seam_shifts
from mech.kinematics.sweep_events import (
    circuits_note,
    find_change_points,
    find_dead_centres,
    find_extremes,
    find_gaps,
    left_out_notes,
    outputs_of,
    unbounded_notes,
)
from mech.kinematics.sweep_grid import (
    RESOLVE,
    analysis_grid,
    check_memory,
    check_position_precision,
    check_precision,
)
from mech.kinematics.sweep_jumps import jump_notes, with_jumps
from mech.kinematics.sweep_rest import find_dwells, find_time_ratios, held_over_dwells
from mech.kinematics.sweep_result import DriveLaw, Dwell, Event, Extreme, Gap, Sweep, TimeRatio, frozen
from mech.model import Mechanism
from mech.options import SolveOptions
from mech.units import to_unit

__all__ = ["Event", "Extreme", "Gap", "Sweep", "TimeRatio", "default_quantities", "quantity_unit", "sweep"]

_TWO_PI = 2.0 * math.pi


# -- the sweep -------------------------------------------------------------------------------
def sweep(
    mech: Mechanism,
    angles: Sequence[float] | np.ndarray | None = None,
    *,
    level: str = "velocity",
    options: SolveOptions | None = None,
    quantities: Sequence[str] | None = None,
    analyse: bool = True,
    drive: str | None = None,
) -> Sweep:
    """Solve ``mech`` at every drive angle of ``angles`` and find what happens over the range.

    Parameters
    ----------
    mech
        A mechanism with one turning drive about a ground pivot.
    angles
        Drive angles, rad, swept in the order given (default: 0 to 2π in 1°
        steps, 361 angles).
    level
        ``"position"``, ``"velocity"`` or ``"acceleration"``; velocity and
        above need a drive speed (file, or ``options.omega``).
    options
        Speed, sense and α of the drive; ``method`` (``auto``: closed form
        where the chain decomposes; ``newton``: per-step continuation with
        ``tol``); ``angle`` must not be given (the sweep sets it).
    quantities
        Keys whose extremes to report (:func:`quantity_unit`); default: every
        link's angle, ω, α, every point's speed and acceleration, every
        slider's displacement and sliding speed, as the level allows.
    drive
        With a slider drive or several drives (required then): the drive (its
        link or joint) whose coordinate ``angles`` holds — its angle (rad) or
        its slider's position along its path from the path's ``through`` (m).  Every drive follows a linear law in it: each is where the file
        draws it when the lead is, and moves in proportion to its speed
        (:class:`~mech.kinematics.march.LinearLaw`).  Swept by Newton (marched).
    analyse
        False: the series only (no toggles, dead centres, extremes, time
        ratio) — the bare vectorised solve, for timing or when only arrays
        are wanted; gaps are still marked by ``assembled``.

    Returns
    -------
    Sweep
        Frozen, with read-only arrays.

    Raises
    ------
    InputError
        No speed at velocity level, an unknown quantity, ``options.angle`` given.
    UnsupportedError
        A slider drive or several drives without ``drive``; pairs known only
        at the drawn instant (cam, contact): they cannot be moved;
        ``method="closed"`` with a slider drive or several drives.
    GeometryError
        The mechanism cannot be assembled as drawn, or at none of the angles.

    Examples
    --------
    >>> s = sweep(mech, np.radians(np.arange(0, 360.5, 0.5)), level="acceleration")  # doctest: +SKIP
    >>> [(math.degrees(e.angle), e.subject) for e in s.dead_centres]                  # doctest: +SKIP
    [(0.0, 'P'), (180.0, 'P')]
    """
    options = options or SolveOptions()
    if not mech.drives:
        raise InputError(
            f"{mech.label} has no drive: a sweep moves its drive",
            hint="add drive: {link: crank, angle: …, rpm: …}",
        )
    refuse_underdriven(mech)  # a freedom no drive holds would be swept by least squares
    several = len(mech.drives) != 1 or mech.drives[0].link is None
    if several and drive is None:  # what ``angles`` holds must be said: a caller written for cranks refuses
        raise UnsupportedError(
            f"{mech.label} has "
            + (f"{len(mech.drives)} drives" if len(mech.drives) > 1 else "a slider drive")
            + ": a sweep of it names the drive whose angle or position it sweeps",
            hint=f"sweep(..., drive={(mech.drives[0].link or mech.drives[0].joint)!r}) "
            "(mech sweep: the first drive, or --drive)",
        )
    if not several and drive not in (None, mech.drives[0].link):
        raise InputError(f"no drive of {drive!r} to sweep", hint=f"choose {mech.drives[0].link}")
    plan = (_plan_laws if several else _plan)(mech, angles, level, options, drive)
    plan = replace(plan, contacts=contact_points_asked(mech, quantities))
    backend, data, fine, pick = _evaluate(plan, analyse)
    ok, cond, singular = _masked(data, plan.prog is not None, fine if plan.parameter == "angle" else None)
    keys = _quantity_keys(backend, plan, quantities)
    found = _Found()
    if analyse:
        found = _find(backend, plan, fine, data, ok, singular, keys)
        if quantities:  # an asked quantity with no row says why (it does not vary, it turns round)
            names = {"points": backend.points, "links": backend.links, "slides": backend.slides}
            plan.notes.extend(left_out_notes(data, ok & ~singular, names, keys, found.extremes, fine, _shown))
    if pick is not None:  # the series at the steps asked; what was found came from the finer grid
        data = {
            k: v[pick] if isinstance(v, np.ndarray) and v.shape[:1] == fine.shape else v
            for k, v in data.items()
        }
        ok, cond, singular = ok[pick], cond[pick], singular[pick]
    _closing_notes(plan, ok, singular, found)
    return _result(plan, backend, data, ok, cond, found)


@dataclass(frozen=True)
class _Plan:
    """What a sweep was asked and what it knows before solving: the chain, its drive, the angles."""

    mech: Mechanism
    comp: Compiled
    prog: DyadProgram | None  # the closed form, or None: Newton
    level: str
    lvl: int  # the level asked (0, 1, 2)
    lvl_int: int  # the level solved: velocities are needed for dead centres even at position level
    drive: str
    omega: float | None
    alpha: float
    options: SolveOptions
    phi: np.ndarray
    notes: list[str]
    lead: int | None = None  # several drives or a slider drive: the drive whose coordinate phi holds
    parameter: str = "angle"  # or "position" (m): a slider drive leads
    laws: tuple[DriveLaw, ...] = ()
    contacts: tuple[str, ...] = ()  # K@link points asked for (followed by the Newton back-end)


@dataclass(frozen=True)
class _Found:
    """What the analysis of the grid found (nothing, when it was not asked)."""

    gaps: tuple[Gap, ...] = ()
    toggles: tuple[Event, ...] = ()
    dead: tuple[Event, ...] = ()
    extremes: tuple[Extreme, ...] = ()
    ratio: TimeRatio | None = None
    changes: tuple[Event, ...] = ()
    dwells: tuple[Dwell, ...] = ()
    ratios: tuple[TimeRatio, ...] = ()
    refused: tuple[tuple[str, str], ...] = ()


def _checked_level(level: str, options: SolveOptions) -> int:
    if level not in LEVELS:
        raise InputError(f"level must be one of {', '.join(LEVELS)}, not {level!r}")
    if options.angle is not None:
        raise InputError(
            "a sweep sets the crank angle itself", hint="give the range (--from, --to) instead of --angle"
        )
    refuse_flipped(options, "a sweep")
    return LEVELS.index(level)


def _assembled(mech: Mechanism, options: SolveOptions) -> tuple[Kinematics, Compiled]:
    """The drawn configuration solved (validating the file and the options) and compiled.

    Refuses a mechanism whose higher pairs are known only at the drawn instant: a sweep moves it.
    """
    base = solve(mech, "position", options)
    comp = compiled(mech, None)
    if comp.system.velocity_only:
        raise UnsupportedError(
            f"cannot sweep {mech.label}: {instant_pairs(comp.system.velocity_only)} only the instant drawn "
            f"({instant_why(mech, comp.system.velocity_only)})",
        )
    return base, comp


def _plan(
    mech: Mechanism,
    angles: Sequence[float] | np.ndarray | None,
    level: str,
    options: SolveOptions,
    lead: str | None = None,
) -> _Plan:
    """Check the request (level, drive, speed, angles, memory) and compile the mechanism: one crank."""
    lvl = _checked_level(level, options)
    base, comp = _assembled(mech, options.with_(omega=None, direction=None, alpha=None))
    drive = base.drives[0]
    omega = _drive_omega(mech, options)
    if lvl >= 1 and omega is None:
        raise InputError(
            f"drive of {drive.link} has no speed: give rpm or omega (or --rpm)", where=drive.where
        )
    alpha = options.alpha if options.alpha is not None else (mech.drives[0].alpha or 0.0)
    phi = np.radians(np.arange(0.0, 360.5, 1.0)) if angles is None else np.asarray(angles, float).ravel()
    if phi.size == 0 or not np.all(np.isfinite(phi)):
        raise InputError("the sweep needs at least one finite angle")
    prog = program(comp) if options.method != "newton" else None
    if options.method == "closed" and prog is None:
        raise UnsupportedError(
            f"{mech.label} does not decompose into dyads driven by one crank", hint="use method auto"
        )
    check_precision(phi)
    check_memory(comp, prog, phi.size, max(lvl, 1))
    return _Plan(
        mech,
        comp,
        prog,
        level,
        lvl,
        max(lvl, 1),
        drive.link or "",
        omega,
        alpha,
        options,
        phi,
        [*comp.drawn.notes, *comp.system.notes],
    )


def _evaluate(plan: _Plan, analyse: bool) -> tuple[Any, dict[str, np.ndarray], np.ndarray, np.ndarray | None]:
    """The back-end, its arrays on the analysis grid, the grid, and the steps asked in it (or None)."""
    comp, prog, notes = plan.comp, plan.prog, plan.notes
    if plan.lead is not None:
        return _evaluate_laws(plan, analyse)
    fine, pick = analysis_grid(plan.phi, comp, prog, plan.lvl_int, notes) if analyse else (plan.phi, None)
    w_int = plan.omega if plan.omega else 1.0  # velocities are needed for dead centres even at position level
    if prog is not None:
        backend: Any = Closed(comp, prog, w_int, plan.alpha, plan.lvl_int)
        backend.ref = _branch_reference(fine, prog.drawn_angle)
        data = backend.evaluate(fine)
        k0 = int(np.argmin(np.abs(fine - backend.ref)))
        shift = seam_shifts(fine, data["assembled"], k0)
        if np.any(shift):  # the drawing's stretch goes on through 0° ≡ 360°: count its branch that way
            backend.steps, backend.shift = fine, shift
            data = backend.evaluate(fine)
        notes.append("closed form: " + "; ".join(prog.steps))
    else:
        backend = Newton(plan.mech, comp, plan.options, w_int, plan.alpha, plan.lvl_int, extra=plan.contacts)
        data = newton_series(backend, fine, notes, comp.drawn.drive_angles[0])
    return backend, data, fine, pick


def _branch_reference(phi: np.ndarray, drawn: float) -> float:
    """The drawn angle moved by whole turns next to the sweep's step nearest the drawing.

    The sweep is continued from there both ways (as a Newton sweep is), so a
    change point is passed, and a dyad's branch flipped, between it and each step.
    """
    if not phi.size:
        return drawn
    k0 = int(np.argmin(np.abs(np.remainder(phi - drawn + math.pi, _TWO_PI) - math.pi)))
    return drawn + _TWO_PI * round(float(phi[k0] - drawn) / _TWO_PI)


def _masked(
    data: dict[str, np.ndarray], closed: bool, phi: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """NaN where not assembled (and rates where singular), link angles unwrapped; (ok, condition, singular).

    ``phi``: the drive angles, when they are a crank's (a full turn joins its last run to its first).
    """
    ok = data["assembled"]
    cond = np.where(ok, data["condition"], np.nan)
    singular = ok & (cond > (ACCURATE_COND if closed else SINGULAR))
    for key in ("positions", "link_angles", "displacement"):
        data[key] = np.where(_expand(ok, data[key]), data[key], np.nan)
    for key in ("velocities", "omegas", "sliding", "accelerations", "alphas"):
        if key in data:
            data[key] = np.where(_expand(ok & ~singular, data[key]), data[key], np.nan)
    data["link_angles"] = unwrap_runs(data["link_angles"], ok, phi)
    return ok, cond, singular


def _quantity_keys(backend: Any, plan: _Plan, quantities: Sequence[str] | None) -> list[str]:
    """The quantities whose extremes are reported (those asked, checked; else the defaults)."""
    keys = (
        list(quantities)
        if quantities
        else default_quantities(backend.points, backend.links, backend.slides, plan.lvl, plan.drive)
    )
    for key in keys:
        check_quantity(backend.points, backend.links, backend.slides, key, plan.lvl)
    return keys


def _find(
    backend: Any,
    plan: _Plan,
    fine: np.ndarray,
    data: dict[str, np.ndarray],
    ok: np.ndarray,
    singular: np.ndarray,
    keys: Sequence[str],
) -> _Found:
    """Gaps and toggles, dead centres, extremes and the time ratio on the analysis grid."""
    names = {"points": backend.points, "links": backend.links, "slides": backend.slides}
    gaps, toggles = find_gaps(backend, fine, data, ok)
    changes = find_change_points(backend, fine, ok)
    for e in changes:
        plan.notes.append(
            f"change point at {_at_text(plan, e.angle)}: {e.subject}; continued on the branch with a "
            "continuous tangent"
        )
    dwells, rest = find_dwells(backend, fine, data, ok, names, outputs_of(plan.comp, names))
    dead, outputs = find_dead_centres(backend, plan.comp, fine, data, ok, names, rest)
    # an extreme of a position may lie at a toggle or change point, where refinement cannot look
    extremes = find_extremes(backend, fine, data, ok & ~singular, names, keys, toggles + changes, ok)
    extremes = with_jumps(backend, names, extremes, fine)  # a cam law's acceleration at a segment end
    extremes = held_over_dwells(extremes, dwells)  # a value held over a dwell: at the dwell's start
    plan.notes.extend(unbounded_notes(extremes, lambda a: _at_text(plan, a)))  # rates ∞ at a toggle
    plan.notes.extend(jump_notes(extremes, lambda a: _at_text(plan, a)))  # a law's segment ends
    ratio, ratios, refused = find_time_ratios(fine, ok, dead, dwells, outputs, plan.lead is None)
    return _Found(gaps, toggles, dead, extremes, ratio, changes, dwells, ratios, refused)


def _shown(value: float, unit: str) -> str:
    """A constant quantity's value in a note: degrees for an angle, else SI, rounding noise as 0."""
    value = 0.0 if abs(value) < 1e-12 else value
    if unit == "rad":
        return f"{math.degrees(value) + 0.0:.6g}°"
    return f"{value + 0.0:.6g} {unit}"


def _at_text(plan: _Plan, value: float) -> str:
    """A value of the sweep's parameter as the notes write it (degrees, or the file's length unit)."""
    if plan.parameter == "angle":
        return f"{math.degrees(value):.6f}°"
    return f"{to_unit(value, plan.mech.length_unit):.6g} {plan.mech.length_unit}"


def _closing_notes(plan: _Plan, ok: np.ndarray, singular: np.ndarray, found: _Found) -> None:
    """Notes on the steps asked: rates left out where singular, separate circuits, a quick return."""
    notes, ratio = plan.notes, found.ratio
    if np.any(singular):
        _singular_note(plan, ok, singular, found)
    circuits = (
        circuits_note(plan.phi, ok, plan.comp.drawn.drive_angles[plan.lead or 0])
        if plan.parameter == "angle"
        else None
    )
    if circuits:
        notes.append(circuits)
    for r in [ratio] if ratio is not None else found.ratios:  # the bare one, else each output's
        if abs(r.ratio - 1.0) > 1e-9:
            notes.append(
                f"quick return: {r.output} strokes take {math.degrees(r.slow):.4f}° and {math.degrees(r.fast):.4f}° of crank (ratio {r.ratio:.6g})"
            )


def _singular_note(plan: _Plan, ok: np.ndarray, singular: np.ndarray, found: _Found) -> None:
    """Say where rates are left out, and why: next to a toggle or change point, or — ill-conditioned
    at every step with none found — because the equations are that badly scaled (a 1e12:1 gear
    train's condition number is 2e12 at every angle; it is no toggle)."""
    bound = f"{ACCURATE_COND if plan.prog is not None else SINGULAR:.0e}"
    lost = "velocities and accelerations there would be good to less than 1e-6 and are not reported"
    n = int(np.sum(singular))
    if bool(np.all(singular[ok])) and not found.toggles and not found.changes:
        plan.notes.append(
            f"{n} step(s) where the constraint equations' condition number is above {bound} at every "
            f"angle, with no toggle or change point (links or gear ratios of very different scales): {lost}"
        )
        return
    where = "a toggle or change point" if found.changes else "a toggle"
    plan.notes.append(f"{n} step(s) next to {where} (condition number above {bound}): {lost}")


def _result(
    plan: _Plan, backend: Any, data: dict[str, np.ndarray], ok: np.ndarray, cond: np.ndarray, found: _Found
) -> Sweep:
    """The frozen :class:`Sweep`: arrays read-only, rates only up to the level asked."""
    lvl = plan.lvl
    return Sweep(
        mechanism=plan.mech.label,
        level=plan.level,
        method=backend.method,
        drive=plan.drive,
        omega=plan.omega,
        alpha=plan.alpha,
        angles=frozen(plan.phi.copy()),  # type: ignore[arg-type]
        points=backend.points,
        positions=frozen(data["positions"]),  # type: ignore[arg-type]
        velocities=frozen(data.get("velocities")) if lvl >= 1 else None,
        accelerations=frozen(data.get("accelerations")) if lvl >= 2 else None,
        links=backend.links,
        link_angles=frozen(data["link_angles"]),  # type: ignore[arg-type]
        omegas=frozen(data.get("omegas")) if lvl >= 1 else None,
        alphas=frozen(data.get("alphas")) if lvl >= 2 else None,
        slides=backend.slides,
        displacement=frozen(data["displacement"]),  # type: ignore[arg-type]
        sliding=frozen(data.get("sliding")) if lvl >= 1 else None,
        assembled=frozen(ok.copy()),  # type: ignore[arg-type]
        condition=frozen(cond),  # type: ignore[arg-type]
        gaps=found.gaps,
        toggles=found.toggles,
        dead_centres=found.dead,
        extremes=found.extremes,
        time_ratio=found.ratio,
        change_points=found.changes,
        notes=tuple(plan.notes),
        parameter=plan.parameter,
        drives=plan.laws,
        dwells=found.dwells,
        time_ratios=found.ratios,
        time_ratio_refused=found.refused,
    )


def _expand(mask: np.ndarray, arr: np.ndarray) -> np.ndarray:
    return mask.reshape(mask.shape + (1,) * (arr.ndim - mask.ndim))


def _drive_omega(mech: Mechanism, options: SolveOptions) -> float | None:
    d = mech.drives[0]
    omega = d.omega
    if options.omega is not None:
        sign = (
            -1.0 if (options.direction == "cw" or (options.direction is None and (d.omega or 0) < 0)) else 1.0
        )
        omega = sign * options.omega
    elif options.direction is not None and omega is not None:
        omega = abs(omega) * (-1.0 if options.direction == "cw" else 1.0)
    return omega


# -- a slider drive, several drives: every drive linear in the sweep's parameter ----------------
def _plan_laws(
    mech: Mechanism,
    angles: Sequence[float] | np.ndarray | None,
    level: str,
    options: SolveOptions,
    lead: str | None = None,
) -> _Plan:
    """:func:`_plan` for a slider drive or several drives: the lead, each drive's law, the parameter."""
    lvl = _checked_level(level, options)
    names = [d.link or d.joint or "" for d in mech.drives]
    overrides = [
        o
        for o, v in (
            ("--rpm/--omega", options.omega),
            ("--speed", options.speed),
            ("--direction", options.direction),
            ("--alpha", options.alpha),
        )
        if v is not None
    ]
    if len(mech.drives) > 1 and overrides:
        raise InputError(
            f"{', '.join(overrides)} set a single drive; {mech.label} has {len(mech.drives)} drives, each "
            "swept at the speed the file gives it",
            hint="give the speeds in the file",
        )
    if lead is not None and lead not in names:
        raise InputError(f"no drive of {lead!r} to sweep", hint=f"choose from {', '.join(names) or 'none'}")
    k = names.index(lead) if lead is not None else 0
    if options.method == "closed":
        raise UnsupportedError(
            f"the closed form turns one crank; {mech.label} has "
            + (f"{len(names)} drives" if len(names) > 1 else "a slider drive"),
            hint="use method auto or newton",
        )
    _, comp = _assembled(mech, options.with_(omega=None, direction=None, alpha=None, speed=None))
    options, laws = _laws(mech, comp, options, lvl, k)
    d = mech.drives[k]
    parameter = "angle" if d.link is not None else "position"
    if angles is None and parameter == "position":
        raise InputError(
            f"a sweep of the slider drive of {d.joint} needs its stroke: the positions along its path "
            "to sweep between",
            hint="give --from and --to (positions from the path's through point, in the file's length unit)",
        )
    phi = np.radians(np.arange(0.0, 360.5, 1.0)) if angles is None else np.asarray(angles, float).ravel()
    if phi.size == 0 or not np.all(np.isfinite(phi)):
        raise InputError("the sweep needs at least one finite value of its parameter")
    if parameter == "angle":
        check_precision(phi)
    else:
        unit = mech.length_unit
        check_position_precision(phi, comp.drawn.scale, lambda x: f"{to_unit(x, unit):.4g} {unit}")
    check_memory(comp, None, phi.size, max(lvl, 1))
    omega = laws[0].rate if parameter == "angle" else None
    alpha = (d.alpha or 0.0) if d.link is not None else (d.accel or 0.0)
    return _Plan(
        mech,
        comp,
        None,
        level,
        lvl,
        max(lvl, 1),
        names[k],
        omega,
        alpha,
        options,
        phi,
        list(comp.drawn.notes),
        lead=k,
        parameter=parameter,
        laws=laws,
    )


def _laws(
    mech: Mechanism, comp: Compiled, options: SolveOptions, lvl: int, k: int
) -> tuple[SolveOptions, tuple[DriveLaw, ...]]:
    """Each drive's law (the lead first) and the options the marched solve runs with.

    Several drives advance in proportion to their speeds, so each needs one; a
    lone slider drive without a speed is swept at 1 m/s for positions (and the
    dead centres, found from the speeds), as a crank without one is at 1 rad/s.
    """
    drives = mech.drives
    rates = [
        d.omega if d.link is not None else (options.speed if options.speed is not None else d.speed)
        for d in drives
    ]
    missing = [d.link or d.joint for d, r in zip(drives, rates, strict=True) if r is None]
    if missing and (len(drives) > 1 or lvl >= 1):
        raise InputError(
            f"no speed for the drive of {', '.join(str(m) for m in missing)}: "
            + (
                "several drives are swept in proportion to their speeds"
                if len(drives) > 1
                else "give speed (m/s along its path) or --speed"
            ),
            where=drives[0].where,
            hint="give each drive its rpm or omega (a slider its speed)",
        )
    if missing:  # one slider drive, positions only
        rates, options = [1.0], options.with_(speed=1.0)
    if rates[k] == 0:
        raise InputError(
            f"the drive of {drives[k].link or drives[k].joint} does not move (speed 0): it cannot lead a sweep",
            hint="lead with a moving drive (--drive)",
        )
    laws = [
        DriveLaw(
            d.link or d.joint or "",
            "angle" if d.link is not None else "position",
            None if missing else rates[i],
            float(rates[i]) / float(rates[k]),  # type: ignore[arg-type]
            d.relative_to,
        )
        for i, d in enumerate(drives)
    ]
    return options, (laws[k], *laws[:k], *laws[k + 1 :])


def _evaluate_laws(
    plan: _Plan, analyse: bool
) -> tuple[Any, dict[str, np.ndarray], np.ndarray, np.ndarray | None]:
    """:func:`_evaluate` for a slider drive or several drives: the marched Newton series."""
    w_int = plan.omega if plan.omega else 1.0
    args = (plan.mech, plan.comp, plan.options, w_int, plan.alpha, plan.lvl_int)
    backend = Newton(*args, lead=plan.lead, extra=plan.contacts)
    marcher = Marcher.make(backend)
    if marcher is None:
        raise UnsupportedError(
            f"cannot sweep {plan.mech.label} with these drives: its constraint rows do not stack "
            "(a slider drive or several drives are swept by the marched solver only)",
            hint="sweep one crank, the other drives held in the file",
        )
    resolve = RESOLVE * marcher.law.span / MAX_SPAN  # 1° of the fastest drive (or 1.7% of the size)
    length = plan.mech.length_unit
    fine, pick = (
        analysis_grid(
            plan.phi,
            plan.comp,
            None,
            plan.lvl_int,
            plan.notes,
            resolve,
            None if plan.parameter == "angle" else lambda x: f"{to_unit(x, length):.4g} {length}",
        )
        if analyse
        else (plan.phi, None)
    )

    def fmt(p: float) -> str:
        return (
            f"{math.degrees(p):.6g}°" if plan.parameter == "angle" else f"{to_unit(p, length):.6g} {length}"
        )

    data = law_series(backend, marcher, fine, plan.notes, fmt)
    plan.notes.append(
        "drives linear in the parameter ("
        + ", ".join(
            f"{law.drive}: {law.per_parameter:.6g} {_PER[(law.kind, plan.parameter)]}" for law in plan.laws
        )
        + "), Newton continuation (marched)"
    )
    return backend, data, fine, pick


_PER = {
    ("angle", "angle"): "rad/rad",
    ("position", "angle"): "m/rad",
    ("angle", "position"): "rad/m",
    ("position", "position"): "m/m",
}
