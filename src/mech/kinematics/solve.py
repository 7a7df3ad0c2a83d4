"""Solve a mechanism at one instant: the route from a request to a result.

Stages:

1. **Compiled mechanism** (:mod:`.compiled`): layout, drawn configuration (the
   file's own data, at the file's drive angle), constraint rows, mobility and the
   checks that depend on the mechanism alone, made once per mechanism.
2. **Position**: at the drawn angle the drawn configuration; when ``--angle``
   asks for another, the closed-form dyads (:mod:`.dyads`) where the chain
   decomposes, else the mechanism is *moved* there from the drawn configuration
   by Newton–Raphson continuation (:mod:`.moving`), so it stays on the drawn
   assembly branch.
3. **Velocity**: ``Φ_q q̇ = −Φ_t``.  **Acceleration**: ``Φ_q q̈ = γ``
   (:mod:`.rates`); the Coriolis terms of a slider on a moving guide come out of
   γ by themselves.
4. **Result** (:mod:`.result_fields`): unscaled and packaged when first read.

All in scaled units (lengths / size, time × |ω|), so the tolerances are
relative and a 1 µm linkage behaves like a 1 km one.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from mech.errors import GeometryError, InputError, UnsupportedError
from mech.kinematics.compiled import (
    Compiled,
    compiled,
    drives_of,
    instant_pairs,
    mobility,
    refuse_underdriven,
)
from mech.kinematics.drives import angle_text, drives_as_used, omega_ref_of
from mech.kinematics.geometry import wrap_angle
from mech.kinematics.layout import layout
from mech.kinematics.linalg import SINGULAR, pinv, snap_to_error
from mech.kinematics.mobility import kutzbach
from mech.kinematics.moving import continue_along, move_from_drawing, move_to
from mech.kinematics.rates import accel_rhs, rate_rhs, rates
from mech.kinematics.result import Kinematics
from mech.kinematics.result_fields import State, lazy_result, result
from mech.model import Drive, Mechanism
from mech.options import SolveOptions

__all__ = [
    "SINGULAR",
    "Compiled",
    "closed_form",
    "compiled",
    "continuation",
    "instant_pairs",
    "mobility",
    "refuse_underdriven",
    "solve",
]

LEVELS = ("position", "velocity", "acceleration")


def solve(mech: Mechanism, level: str = "velocity", options: SolveOptions | None = None) -> Kinematics:
    """Positions, and velocities and accelerations up to ``level``, at the drive's angle.

    Parameters
    ----------
    mech
        The mechanism (SI).
    level
        ``"position"``, ``"velocity"`` or ``"acceleration"``.
    options
        Overrides of the single drive (angle, omega, direction, alpha) and
        Newton's tolerance (relative to size) and iteration cap.

    Returns
    -------
    Kinematics
        Frozen result: positions (m), link states, point queries.

    Raises
    ------
    InputError
        No drive speed at velocity level ("give rpm or omega (or --rpm)"),
        drives that do not match the mobility, drawn data that disagree with
        given lengths, overrides on a file with several drives.
    GeometryError
        No assembly (with the gap, in the file's unit), a location the file
        leaves free, a singular (toggle) configuration, an angle the
        mechanism cannot reach.
    UnsupportedError
        Screw or spherical pairs; acceleration, or moving the mechanism, with
        a cam, contact, rolling or gear pair known only at the drawn instant.

    Examples
    --------
    >>> kin = solve(mech, level="acceleration")                 # doctest: +SKIP
    >>> kin.links["rocker"].omega                               # doctest: +SKIP
    -4.8
    """
    options = options or SolveOptions()
    if level not in LEVELS:
        raise InputError(f"level must be one of {', '.join(LEVELS)}, not {level!r}")
    lvl = LEVELS.index(level)
    overrides = any(
        v is not None for v in (options.angle, options.omega, options.speed, options.direction, options.alpha)
    )
    if overrides and len(mech.drives) != 1:
        raise InputError(
            f"--angle, --rpm, --speed, --direction and --alpha override a single drive; {mech.label} has "
            f"{len(mech.drives)} drives",
            hint="give the drives in the file"
            if mech.drives
            else "add drive: {link: ..., angle: ..., rpm: ...}",
        )
    if lvl > 0 or options.angle is not None:
        layout(mech)  # the file's own mistakes first (a drive's frame, a spatial pair): linear, remembered
        refuse_underdriven(mech)  # then the count, before the assembly and the rank (cubic in the chain)
    try:
        comp = compiled(mech, None)
    except GeometryError:
        # A file that draws only the ground pivots and gives no drive angle: --angle supplies it.
        if options.angle is None or mech.drives[0].angle is not None or mech.drives[0].link is None:
            raise
        comp = compiled(mech, (options.angle,))
    sys_, lay, drawn = comp.system, comp.layout, comp.drawn
    notes = list(drawn.notes) + list(comp.mobility.notes)

    drives = drives_of(comp, options, lvl)
    n_drives = len(drives)
    numeric = comp.mobility.numeric
    targets = [d.angle for d in drives]
    moved = any(
        spec.link is not None and abs(wrap_angle(t - a)) > 1e-15  # type: ignore[operator]
        for spec, t, a in zip(lay.drives, targets, drawn.drive_angles, strict=False)
    )
    # At a drawn toggle the rank drops and mobility looks one higher: that is the
    # singularity (reported by the velocity solve), not a missing drive.
    toggle = numeric is not None and numeric > n_drives and n_drives == kutzbach(mech) and comp.singular
    if (lvl > 0 or moved) and numeric is not None and n_drives != numeric and not toggle:
        more = n_drives > numeric
        raise InputError(
            f"{mech.label} has mobility {numeric} (from the constraint Jacobian's rank) but "
            f"{n_drives} drive{'s' if n_drives != 1 else ''}: "
            + ("more drives than it can take" if more else f"it needs {numeric} inputs"),
            where=mech.drives[0].where if mech.drives else None,
            hint=(
                "remove a drive"
                if more
                else f"give one drive per degree of freedom: drive: [{{link: …, rpm: …}}, …] ({numeric} of them)"
            ),
            source=mech.source,
        )

    q = sys_.q0
    omega_ref = omega_ref_of(drives, drawn.scale)
    if options.method == "closed" or (moved and options.method == "auto"):
        fast = _closed_form(comp, drives, lvl, omega_ref, options)
        if fast is not None:
            state, note = fast
            told = (lambda: (*notes, note())) if moved else tuple(notes)
            return lazy_result(comp, level, state, omega_ref, moved, told, drives)
    if moved:
        q = move_from_drawing(comp, drives, options, targets, notes)

    qd, qdd = rates(comp, q, drives, lvl, omega_ref)
    return result(comp, level, q, qd, qdd, omega_ref, moved, tuple(notes), drives)


def continuation(
    mech: Mechanism, angles: Sequence[float], level: str, options: SolveOptions
) -> Iterator[Kinematics | None]:
    """Newton continuation along ``angles`` (rad) of the single crank: one result per angle.

    The first angle is reached from the drawn configuration as :func:`solve`
    does; each later one is warm-started from the previous solution with the
    predictor ``q + q̇·Δθ`` (step halving on failure), so the branch is the
    one the previous step was on.  A step that cannot be reached (a limit
    position) yields None, and so do all after it: continuation cannot jump.
    A singular step (a toggle) yields positions only.
    """
    lvl = LEVELS.index(level)
    comp = compiled(mech, None)
    sys_, lay, drawn = comp.system, comp.layout, comp.drawn
    base = options.with_(angle=float(angles[0]) if len(angles) else None, method="newton")
    drives = drives_as_used(mech, lay, drawn, base, lvl)
    omega_ref = omega_ref_of(drives, drawn.scale)
    offset = 2 * sys_.pc_i.size + sys_.ln_s.size
    rows = [sys_.drive_rows[0] - offset]
    ci = 3 * sys_.link_index[drives[0].link] + 2  # type: ignore[index]
    q: np.ndarray | None = None
    prev = 0.0
    for k, phi in enumerate(angles):
        here = tuple(replace(d, angle=float(phi)) for d in drives)
        if k == 0:
            try:
                q = move_to(comp, here, base)
            except GeometryError:
                q = None
        elif q is not None:
            c_ang = sys_.ang_c.copy()
            c_ang[rows] += q[ci] - sys_.q0[ci]  # the drive row's change so far (no 2π ambiguity)
            q, _ = continue_along(sys_, q, c_ang, sys_.ln_c, rows, np.array([float(phi) - prev]), base)
        if q is None:
            yield None
            continue
        prev = float(phi)
        try:
            qd, qdd = rates(comp, q, here, lvl, omega_ref)
            yield result(comp, level, q, qd, qdd, omega_ref, True, (), here)
        except GeometryError:
            yield result(comp, "position", q, None, None, omega_ref, True, ("singular",), here)


# -- closed form ----------------------------------------------------------------------


def _closed_form(
    comp: Compiled, drives: tuple[Drive, ...], lvl: int, omega_ref: float, options: SolveOptions
) -> tuple[Callable[[], State], Callable[[], str]] | None:
    """q, q̇, q̈ (scaled) from the dyad program, or None to let Newton solve (and explain).

    Checked here (closure, reachability, toggles); the arrays and the note are
    made only when the result is read (two callables), so a solve whose caller
    reads one number does not pay for the rest.

    None when the chain does not decompose, when the target angle cannot be
    reached from the drawn one by turning the crank (a gap in between: the
    closed form would land on a configuration the mechanism cannot move to),
    when a dyad cannot close, or near a toggle.  With ``method="closed"`` the
    first of these is an error instead.
    """
    from mech.kinematics.dyads import ACCURATE_COND, SLACK, branches, passed, program, route

    prog = program(comp)
    if prog is None:
        if options.method == "closed":
            raise UnsupportedError(
                f"{comp.mech.label} does not decompose into dyads driven by one crank",
                hint="use method 'auto' or 'newton' (the general solver)",
            )
        return None
    d = drives[0]
    phi = d.angle if d.angle is not None else prog.drawn_angle
    turn = route(prog, phi)
    if turn is None:
        return None
    # past a change point a dyad continues on the branch with a continuous tangent (its sign flips)
    reached = prog.drawn_angle + turn
    branch = branches(prog, prog.drawn_angle, reached)
    met = passed(prog, prog.drawn_angle, reached)
    w = d.omega or 0.0
    al = d.alpha or 0.0
    try:
        out = prog.raw(phi, w, al, level=lvl, branch=branch)
    except ZeroDivisionError:  # no closure, or exactly in line: Newton explains
        return None
    parts = prog.split(out, lvl)
    if min(parts["disc"], default=1.0) < -SLACK:
        return None  # Newton reports the gap, in the file's unit
    sines = [abs(x) for x in parts["sin"]]
    if lvl >= 1 and sines and min(sines) * ACCURATE_COND < 1.0:
        _refuse_singular(comp, prog, d, phi, sines)

    def state() -> State:
        sys_ = comp.system
        n, scale = sys_.n, sys_.scale
        q = np.empty(3 * n)
        q[0::3] = np.asarray(parts["lx"]) / scale
        q[1::3] = np.asarray(parts["ly"]) / scale
        q[2::3] = parts["lt"]
        qd = qdd = None
        if lvl >= 1:
            qd = np.empty(3 * n)
            qd[0::3] = np.asarray(parts["lvx"]) / (scale * omega_ref)
            qd[1::3] = np.asarray(parts["lvy"]) / (scale * omega_ref)
            qd[2::3] = np.asarray(parts["lw"]) / omega_ref
            jac = sys_.jacobian(q)
            inverse = pinv(np.linalg.svd(jac, full_matrices=False))
            qd = snap_to_error(jac, inverse, qd, rate_rhs(comp, drives, omega_ref))
        if lvl >= 2 and qd is not None:
            qdd = np.empty(3 * n)
            qdd[0::3] = np.asarray(parts["lax"]) / (scale * omega_ref**2)
            qdd[1::3] = np.asarray(parts["lay"]) / (scale * omega_ref**2)
            qdd[2::3] = np.asarray(parts["lal"]) / omega_ref**2
            qdd = snap_to_error(jac, inverse, qdd, accel_rhs(comp, q, qd, drives, omega_ref))
        return q, qd, qdd

    def note() -> str:
        kinds = ", ".join(dict.fromkeys(k for k, _, _ in prog.dyads)) or "crank only"
        text = (
            f"moved from the drawn angle ({angle_text(prog.drawn_angle)} → {angle_text(phi)}) keeping its branch, "
            f"in closed form (dyads: {kinds})"
        )
        for at, c in met:
            text += (
                f"; passed a change point at {math.degrees(at):.6f}° ({c.what}) and continued on the "
                "branch with a continuous tangent"
            )
        return text

    return state, note


def _refuse_singular(comp: Compiled, prog: Any, d: Drive, phi: float, sines: list[float]) -> None:
    """Refuse rates at a closed-form configuration next to a toggle or a change point (which, and how bad)."""
    k = sines.index(min(sines))
    cond = 1.0 / min(sines) if min(sines) > 0 else math.inf
    what = _change_point_at(prog, k, phi) or "a toggle or dead-centre position"
    raise GeometryError(
        f"singular configuration of {comp.mech.label} ({d.link} at {angle_text(phi)}): "
        f"{prog.dyads[k][2]} — {what} (condition number {cond:.2g}; "
        f"velocities here would be good only to about {min(2e-16 * cond * cond, 1.0):.0e})",
        hint="analyse a slightly different angle: velocities here are undetermined",
    )


def _change_point_at(prog: Any, k: int, phi: float) -> str | None:
    """ "a change point (P meets C …)" when dyad ``k`` has one within 1e-6 rad of ``phi``, else None."""
    from mech.kinematics.dyads import change_points

    for c in change_points(prog):
        if c.dyad == k and abs(wrap_angle(prog.drawn_angle + c.offset - phi)) < 1e-6:
            return f"a change point, {c.what.split(' (')[0]}: two branches meet and either can follow"
    return None


def closed_form(mech: Mechanism) -> Any:
    """The compiled closed-form (dyad) program of ``mech``, or None when it does not decompose.

    The lean single-solve path: ``closed_form(m).state(phi, omega, alpha)``
    returns a :class:`~mech.kinematics.dyads.FastState` of flat tuples in a
    few microseconds (no notes, no checks beyond closure; use :func:`solve`
    for the full, explained result).

    Examples
    --------
    >>> prog = closed_form(mech)                                 # doctest: +SKIP
    >>> prog.state(math.radians(60), -4 * math.pi).omega         # doctest: +SKIP
    """
    from mech.kinematics.dyads import program

    return program(compiled(mech, None))
