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

import numpy as np

from mech._records import dataclass
from mech.errors import GeometryError, InputError, UnsupportedError
from mech.kinematics.compiled import Compiled, compiled, instant_pairs, mobility, refuse_underdriven
from mech.kinematics.drives import angle_text, drives_as_used, omega_ref_of
from mech.kinematics.dyads import (
    ACCURATE_COND,
    SLACK,
    DyadProgram,
    branches,
    change_points,
    closes,
    closure_gaps,
    passed,
    program,
    route,
)
from mech.kinematics.geometry import wrap_angle
from mech.kinematics.layout import layout
from mech.kinematics.linalg import BLOCK_MIN, NEAR_TOGGLE, SINGULAR, pinv, snap_to_error
from mech.kinematics.moving import continue_along, move_from_drawing, move_to
from mech.kinematics.rates import accel_rhs, near_toggle_note, rate_rhs, rates
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
    "refuse_flipped",
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
    _refuse_overrides(mech, options)
    if lvl > 0 or options.angle is not None:
        layout(mech)  # the file's own mistakes first (a drive's frame, a spatial pair): linear, remembered
        refuse_underdriven(mech)  # then the count, before the assembly and the rank (cubic in the chain)
    comp = _compiled(mech, options)
    plan: _Plan = comp.memo.get(("plan", options, lvl), lambda: _plan(comp, options, lvl))
    drives, moved, omega_ref = plan.drives, plan.moved, plan.omega_ref
    flipped = options.flipped
    if plan.closed or flipped:
        fast = _closed_form(comp, drives, lvl, omega_ref, options, moved)
        if fast is not None:
            state, note, near = fast
            told: tuple[str, ...] | Callable[[], tuple[str, ...]] = plan.notes
            if moved or flipped or near is not None:
                told = lambda: (  # noqa: E731
                    *plan.notes,
                    *((note(),) if moved else ()),
                    *((_flipped_note(flipped),) if flipped else ()),
                    *((near(),) if near is not None else ()),
                )
            return lazy_result(comp, level, state, omega_ref, moved or bool(flipped), told, drives)
        if flipped:
            raise GeometryError(
                f"{mech.label} cannot close with {', '.join(flipped)} on the other assembly branch at this angle",
                hint="the other branch does not assemble here (or is next to a toggle)",
            )
    notes = list(plan.notes)
    q = move_from_drawing(comp, drives, options, list(plan.targets), notes) if moved else comp.system.q0
    qd, qdd = rates(comp, q, drives, lvl, omega_ref)
    if qd is None:
        return result(comp, level, q, qd, qdd, omega_ref, moved, tuple(notes), drives)
    told = lambda: (*notes, *near_toggle_note(comp, q))  # noqa: E731  (read when the notes are)
    return lazy_result(comp, level, lambda: (q, qd, qdd), omega_ref, moved, told, drives)


@dataclass(frozen=True, slots=True)
class _Plan:
    """What a solve decides before it computes, for one compiled mechanism, options and level.

    Made once and kept in the compiled mechanism's memo, so a repeated solve (a
    batch of homework files asking the same instant, a caller's loop) repeats
    none of it; an error found on the way is raised afresh each time, never kept.
    """

    drives: tuple[Drive, ...]  # as used: overrides applied, angles from the drawing, ω signed
    targets: tuple[float | None, ...]  # each drive's angle asked for
    moved: bool  # away from the drawing
    omega_ref: float  # the time scale
    notes: tuple[str, ...]  # the drawing's and the mobility's
    closed: bool  # try the closed-form dyads first


def _plan(comp: Compiled, options: SolveOptions, lvl: int) -> _Plan:
    """:class:`_Plan` of a solve: the drives as used, checked against the mobility, and the route."""
    drives = drives_as_used(comp.mech, comp.layout, comp.drawn, options, lvl)
    targets = tuple(d.angle for d in drives)
    moved = any(
        spec.link is not None and abs(wrap_angle(t - a)) > 1e-15  # type: ignore[operator]
        for spec, t, a in zip(comp.layout.drives, targets, comp.drawn.drive_angles, strict=False)
    )
    if lvl > 0 or moved:
        comp.refuse_drives(len(drives))
    return _Plan(
        drives,
        targets,
        moved,
        omega_ref_of(drives, comp.drawn.scale),
        (*comp.drawn.notes, *comp.system.notes, *comp.mobility.notes),
        _closed_route(comp, options, lvl, moved),
    )


def _refuse_overrides(mech: Mechanism, options: SolveOptions) -> None:
    """The command's overrides of a drive (--angle, --rpm …) apply to a file with one drive only."""
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


def _compiled(mech: Mechanism, options: SolveOptions) -> Compiled:
    """The compiled mechanism; a file that draws only the ground pivots and gives no drive angle gets --angle's."""
    try:
        return compiled(mech, None)
    except GeometryError:
        if options.angle is None or mech.drives[0].angle is not None or mech.drives[0].link is None:
            raise
        return compiled(mech, (options.angle,))


def _closed_route(comp: Compiled, options: SolveOptions, lvl: int, moved: bool) -> bool:
    """Whether the closed-form dyads are tried: asked for, or (``auto``) at any angle the chain reaches.

    The drawn angle takes them as a moved one does, with two exceptions judged once
    per mechanism: a toggle drawn (Φ_q singular as drawn: the general route refuses
    it, naming the links in line), and a chain of :data:`~mech.kinematics.linalg.BLOCK_MIN`
    unknowns or more, where generating and compiling the program costs more than the
    drawn solve it would replace (a 200-link chain: 1.5 s against 25 ms), so the drawn
    configuration and the block solver answer as before.
    """
    if options.method != "auto":
        return options.method == "closed"
    if moved:
        return True
    return 3 * comp.system.n < BLOCK_MIN and (lvl == 0 or not comp.singular)


def refuse_flipped(options: SolveOptions, what: str) -> None:
    """A sweep or a continuation follows the drawing's own branches: ``flipped`` is one instant's."""
    if options.flipped:
        raise UnsupportedError(
            f"{what} follows the drawing's own branches; flipped closes dyads the other way at one instant",
            hint="solve each instant with solve(..., options=SolveOptions(angle=…, flipped=…))",
        )


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
    refuse_flipped(options, "continuation")
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
    comp: Compiled,
    drives: tuple[Drive, ...],
    lvl: int,
    omega_ref: float,
    options: SolveOptions,
    moved: bool = True,
) -> tuple[Callable[[], State], Callable[[], str], Callable[[], str] | None] | None:
    """q, q̇, q̈ (scaled) from the dyad program, or None to let the general route solve (and explain).

    Returned with the note of a move and, next to a toggle, the note that says where it is
    (:func:`_near_toggle_note`), both callables.

    Checked here (closure, reachability, toggles); the arrays and the note are
    made only when the result is read (two callables), so a solve whose caller
    reads one number does not pay for the rest.

    None when the chain does not decompose, when the target angle cannot be
    reached from the drawn one by turning the crank (a gap in between: the
    closed form would land on a configuration the mechanism cannot move to),
    when a dyad cannot close, or (at the drawn angle, not ``moved``) next to a
    toggle, where the general route judges Φ_q as it always has.  With
    ``method="closed"`` the first of these is an error instead, and a moved
    angle next to a toggle is refused.
    """
    prog = program(comp, lvl, whole_turn=moved)
    if prog is None:
        if options.flipped:
            raise UnsupportedError(
                f"{comp.mech.label} does not decompose into dyads driven by one crank: its other assembly "
                "branch is not solved by closing a dyad the other way",
                hint="draw the other branch in the file (its joints' near: or at:) and solve that",
            )
        if options.method == "closed":
            raise UnsupportedError(
                f"{comp.mech.label} does not decompose into dyads driven by one crank",
                hint="use method 'auto' or 'newton' (the general solver)",
            )
        return None
    d = drives[0]
    phi = d.angle if d.angle is not None else prog.drawn_angle
    way = _way(prog, phi) if moved else ((), [])
    if way is None:
        return None
    branch, met = way
    if options.flipped:
        branch = _flip(prog, branch, options.flipped, comp.mech.label)
    try:
        out = prog.raw(phi, d.omega or 0.0, d.alpha or 0.0, level=lvl, branch=branch)
    except ZeroDivisionError:  # no closure, or exactly in line: Newton explains
        return None
    nd = len(prog.dyads)
    if min(out[:nd], default=1.0) < -SLACK:
        return None  # Newton reports the gap, in the file's unit
    if options.flipped and not closes(prog, comp.system, phi, out):
        return None  # the other side breaks a row the dyads did not use (a redundant link)
    sines = [abs(x) for x in out[nd : 2 * nd]]
    if lvl >= 1 and sines and min(sines) * ACCURATE_COND < 1.0:
        if not moved and options.method == "auto" and not options.flipped:
            return None
        _refuse_singular(comp, prog, d, phi, sines)
    near = None
    if lvl >= 1 and sines and min(sines) < NEAR_TOGGLE:
        near = lambda: _near_toggle_note(comp, prog, phi, prog.split(out, lvl))  # noqa: E731
    # away from the drawn configuration: its rates are not solved with Φ_q as drawn
    shifted = moved or bool(options.flipped)
    return (
        (lambda: _state(comp, prog, prog.split(out, lvl), drives, lvl, omega_ref, shifted)),
        (lambda: _moved_note(prog, phi, met)),
        near,
    )


def _near_toggle_note(comp: Compiled, prog: DyadProgram, phi: float, parts: dict[str, tuple]) -> str:
    """Where the toggle next to ``phi`` is and how fast the output's ω grows toward it.

    A toggle is an edge of a range of drive angles where the loop cannot close (a
    non-Grashof input's limit, :func:`~mech.kinematics.dyads.closure_gaps`): the
    dyad's position goes as √Δθ there, so the ω of the links it carries grows as
    1/√Δθ (a quarter of the distance, twice the ω).  The output named is the link
    turning fastest; its coefficient ω·√Δθ is today's value times the root of the distance.
    """
    two_pi = 2.0 * math.pi
    edges = [prog.drawn_angle + e for gap in closure_gaps(prog) for e in gap]
    if not edges:
        return (
            f"next to a toggle or change point at {angle_text(phi)}: links are within "
            f"{math.degrees(math.asin(NEAR_TOGGLE)):.1f}° of in line, where velocities grow without bound"
        )
    gaps = [abs(math.remainder(phi - e, two_pi)) for e in edges]
    k = gaps.index(min(gaps))
    delta, edge = gaps[k], edges[k]
    links = comp.system.links
    omegas = [abs(float(w)) for w in parts["lw"]]
    drive = comp.mech.drives[0].link
    out = max((i for i, lk in enumerate(links) if lk != drive), key=lambda i: omegas[i], default=None)
    grows = "the links' ω grow as 1/√Δθ toward it"
    if out is not None and delta > 0:
        w, name = omegas[out], links[out]
        grows = (
            f"ω of {name} grows as 1/√Δθ toward it: {w:.4g} rad/s here ≈ {w * math.sqrt(delta):.4g}/√Δθ "
            f"(Δθ in rad), twice that at a quarter of the distance"
        )
    return (
        f"{math.degrees(delta):.3g}° from the toggle at {angle_text(edge)} (the drive cannot pass it: "
        f"links come into line there); {grows}"
    )


def _flipped_note(names: tuple[str, ...]) -> str:
    return f"on the other assembly branch: {', '.join(names)} closed the other way, every other dyad as drawn"


def _flip(prog: DyadProgram, branch: tuple, names: tuple[str, ...], label: str) -> tuple:
    """Each dyad's branch multiplier with the dyads placing ``names`` turned to the other side."""
    placed = {name: k for k, (_, name, _) in enumerate(prog.dyads)}
    missing = [n for n in names if n not in placed]
    if missing:
        raise UnsupportedError(
            f"no dyad of {label} places {', '.join(missing)}: its other side is not had by closing a dyad "
            "the other way",
            hint=f"the dyads place {', '.join(placed) or 'nothing (the crank alone)'}",
        )
    turned = {placed[n] for n in names}
    return tuple(-b if k in turned else b for k, b in enumerate(branch or (1.0,) * len(prog.dyads)))


def _way(prog: DyadProgram, phi: float) -> tuple[tuple, list] | None:
    """How the crank reaches ``phi`` from the drawing: each dyad's branch there and the change points passed.

    None when both ways round have a gap.  Past a change point a dyad continues on
    the branch with a continuous tangent (its sign flips).
    """
    turn = route(prog, phi)
    if turn is None:
        return None
    reached = prog.drawn_angle + turn
    return branches(prog, prog.drawn_angle, reached), passed(prog, prog.drawn_angle, reached)


def _state(
    comp: Compiled,
    prog: DyadProgram,
    parts: dict[str, tuple],
    drives: tuple[Drive, ...],
    lvl: int,
    omega_ref: float,
    moved: bool,
) -> State:
    """q, q̇, q̈ (scaled) from the program's outputs, each rate refined and snapped as a linear solve's are.

    The closed form's rates are good to ε times the velocities they are built from
    (a ground pivot's, reached round the loop from the coupler's, comes out at 1e-16
    m/s, not 0), a normwise error that the componentwise bound would not snap.  One
    step of iterative refinement on Φ_q (:func:`~mech.kinematics.linalg.refined`'s
    second half) makes each component good to its own size, as the general route's
    are; then :func:`~mech.kinematics.linalg.snap_to_error`.  Φ_q⁺ at the drawn angle is
    the compiled mechanism's, made once.
    """
    sys_ = comp.system
    n, scale = sys_.n, sys_.scale
    q = prog.configuration(parts, scale)
    if lvl < 1:
        return q, None, None
    if moved:
        jac = sys_.jacobian(q)
        inverse = pinv(np.linalg.svd(jac, full_matrices=False))
    else:
        jac, inverse = comp.jacobian, comp.drawn_inverse()
    qd = np.empty(3 * n)
    qd[0::3] = np.asarray(parts["lvx"]) / (scale * omega_ref)
    qd[1::3] = np.asarray(parts["lvy"]) / (scale * omega_ref)
    qd[2::3] = np.asarray(parts["lw"]) / omega_ref
    rhs = rate_rhs(comp, drives, omega_ref)
    qd = snap_to_error(jac, inverse, qd + inverse @ (rhs - jac @ qd), rhs)
    if lvl < 2:
        return q, qd, None
    qdd = np.empty(3 * n)
    qdd[0::3] = np.asarray(parts["lax"]) / (scale * omega_ref**2)
    qdd[1::3] = np.asarray(parts["lay"]) / (scale * omega_ref**2)
    qdd[2::3] = np.asarray(parts["lal"]) / omega_ref**2
    gamma = accel_rhs(comp, q, qd, drives, omega_ref)
    return q, qd, snap_to_error(jac, inverse, qdd + inverse @ (gamma - jac @ qdd), gamma)


def _moved_note(prog: DyadProgram, phi: float, met: list) -> str:
    """The note of a closed-form solve moved from the drawing: from where to where, the change points passed."""
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


def _refuse_singular(comp: Compiled, prog: DyadProgram, d: Drive, phi: float, sines: list[float]) -> None:
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


def _change_point_at(prog: DyadProgram, k: int, phi: float) -> str | None:
    """ "a change point (P meets C …)" when dyad ``k`` has one within 1e-6 rad of ``phi``, else None."""
    for c in change_points(prog):
        if c.dyad == k and abs(wrap_angle(prog.drawn_angle + c.offset - phi)) < 1e-6:
            return f"a change point, {c.what.split(' (')[0]}: two branches meet and either can follow"
    return None


def closed_form(mech: Mechanism) -> DyadProgram | None:
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
    return program(compiled(mech, None))
