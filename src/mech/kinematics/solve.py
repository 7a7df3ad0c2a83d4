"""Solve a mechanism at one instant: position (Newton), velocity and acceleration (linear).

Stages:

1. **Drawn configuration** (:mod:`.assemble`): the file's own data, at the
   file's drive angle.  Compiled once per mechanism into a :class:`System` of
   constraint rows (kept in the mechanism's memo).
2. **Position**: when ``--angle`` asks for another angle, the mechanism is
   *moved* there from the drawn configuration by Newton–Raphson continuation
   (steps of at most 15°, each predicted with the velocity solution, halved on
   failure), so it stays on the drawn assembly branch.  It goes the short way
   round, then the long way if a limit position blocks the short one.
3. **Velocity**: ``Φ_q q̇ = −Φ_t``.  **Acceleration**: ``Φ_q q̈ = γ``; the
   Coriolis terms of a slider on a moving guide come out of γ by themselves.

All in scaled units (lengths / size, time × |ω|), so the tolerances are
relative and a 1 µm linkage behaves like a 1 km one.  One SVD of Φ_q per
configuration solves both linear systems and measures its condition: above
1e6 (see :data:`SINGULAR`) the configuration is singular (a toggle) and the
links the null vector moves are named; velocities there are never printed.  A slider crank at dead
centre is *not* singular for a crank drive (the slider stops, the rod's ω
is finite) and solves normally.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Sequence
from dataclasses import field, replace
from types import MappingProxyType
from typing import Any

import numpy as np

from mech._memo import Memo
from mech._records import dataclass
from mech.errors import GeometryError, InputError, UnsupportedError, Where
from mech.kinematics.assemble import Drawn, assemble, complete
from mech.kinematics.blocks import BlockForm, block_form
from mech.kinematics.constraints import System, build_system
from mech.kinematics.geometry import wrap_angle
from mech.kinematics.layout import Layout, layout
from mech.kinematics.mobility import kutzbach, numeric_mobility
from mech.kinematics.result import Fields, JointGeom, Kinematics, LinkState, Mobility
from mech.model import Drive, Mechanism
from mech.options import SolveOptions
from mech.pairs import kind_of

__all__ = ["Compiled", "closed_form", "compiled", "continuation", "mobility", "refuse_underdriven", "solve"]

LEVELS = ("position", "velocity", "acceleration")
#: Condition number of Φ_q (scaled) above which a configuration is refused as singular.
#: Positions near a toggle are only as accurate as ε·cond and velocities lose
#: another factor cond, so velocity errors grow like ε·cond² (measured: 2e-7 at
#: cond 7e5, 3e-5 at 7e6 on a triple-rocker approaching its limit).  1e6 keeps
#: answers to about 1e-6 relative; beyond it they would be silently wrong.
SINGULAR = 1e6
_MAX_STEP = math.radians(15.0)
_TWO_PI = 2.0 * math.pi
#: q, q̇, q̈ of a solve, scaled (q̇ and q̈ None above the level asked).
_State = tuple[np.ndarray, "np.ndarray | None", "np.ndarray | None"]


@dataclass(frozen=True, slots=True)
class Compiled:
    """Everything about a mechanism that does not depend on the asked angle or speed."""

    mech: Mechanism
    layout: Layout
    drawn: Drawn
    system: System
    mobility: Mobility
    #: Φ_q with the drive rows at the drawn configuration (read-only): the rates of a solve that
    #: is not moved use it again.
    jacobian: np.ndarray
    #: Whether Φ_q is singular as drawn, judged block by block (a large chain); None: by
    #: :func:`_is_singular` when first asked (:attr:`singular`).
    judged: bool | None
    #: What is derived from it in turn (the drives of each options, the closed-form program).
    memo: Memo = field(default_factory=Memo, init=False, repr=False, compare=False, hash=False)

    @property
    def singular(self) -> bool:
        """Φ_q with drive rows is singular at the drawn configuration (a toggle drawn)."""
        if self.judged is not None:
            return self.judged
        return self.memo.get("singular", lambda: _is_singular(self.jacobian))


def compiled(
    mech: Mechanism, angles: tuple[float | None, ...] | None, *, allow_free: bool = False
) -> Compiled:
    """Layout, drawn configuration, constraint system and mobility of ``mech`` (remembered).

    Kept in the mechanism's own memo (:class:`mech._memo.Memo`): the model is
    immutable, so an entry never goes stale, and it goes when the mechanism goes.
    """
    return mech.memo.get(("compiled", angles, allow_free), lambda: _compile(mech, angles, allow_free))


def _compile(mech: Mechanism, angles: tuple[float | None, ...] | None, allow_free: bool) -> Compiled:
    lay = layout(mech)
    drawn = assemble(lay, drive_angles=angles, allow_free=allow_free)
    system = build_system(lay, drawn)
    jac = system.jacobian(system.q0)  # once, for the rank, the drawn toggle and the drawn rates
    jac.setflags(write=False)
    form = _blocks(system)
    if form is None:
        mob = numeric_mobility(mech, system, system.q0, jacobian=jac)
        return Compiled(mech, lay, drawn, system, mob, jac, None)  # the toggle: judged if asked
    # A large chain, square with its drives: judged block by block, as its velocities are solved
    # (two dense SVDs of a 6,000-column Φ_q took 380 s on a 2,000-link chain of dyads).
    cond, _ = form.condition(jac)
    singular = cond > SINGULAR
    mob = numeric_mobility(
        mech, system, system.q0, jacobian=jac, nonsingular=None if singular else (form, cond)
    )
    return Compiled(mech, lay, drawn, system, mob, jac, singular)


def mobility(mech: Mechanism) -> Mobility:
    """Numeric mobility at the drawn configuration; no drive needed.

    A file whose data leave the configuration free (no drive angle, nothing
    drawn on the moving links) is assembled in some consistent configuration,
    which gives the generic rank (:func:`mech.kinematics.mobility.numeric_mobility`).
    It lives here, beside :func:`compiled`, so that :mod:`.mobility` (the rank
    itself) never imports the solver that imports it.

    Raises
    ------
    InputError
        When the file has no geometry (nothing placed by ``at``).
    GeometryError
        When it cannot be assembled.

    Examples
    --------
    >>> from mech.kinematics import mobility                    # doctest: +SKIP
    >>> mobility(mech).numeric                                  # doctest: +SKIP
    1
    """
    if not mech.has_geometry:
        raise InputError(
            "numeric mobility needs geometry: nothing in the file is placed",
            hint="place the ground joints with at and give the links' lengths",
        )
    try:
        return compiled(mech, None, allow_free=True).mobility
    except (GeometryError, InputError) as error:
        # A ground pivot without `at` is put anywhere by a free assembly: a gear mesh or a length
        # that then fails quotes a distance mech made up.  Name the pivot instead.
        unplaced = [
            j
            for j in mech.joints
            if mech.ground in j.links
            and kind_of(j).located != "none"
            and j.place.at is None
            and not j.place.is_relative
            and not kind_of(j).higher
        ]
        if not unplaced:
            raise
        first = unplaced[0]
        raise GeometryError(
            f"{first.name} is on the ground link {mech.ground} but not placed, so the assembly put it "
            f"anywhere and then: {error.problems[0].message}",
            where=first.where,
            hint=f"place it with at: [x, y] (every joint on the {mech.ground} needs one)",
            source=mech.source,
        ) from error


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

    drives = _drives_of(comp, options, lvl)
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
            return _lazy(comp, level, state, omega_ref, moved, told, drives)
    if moved:
        q = _moved(comp, drives, options, targets, notes)

    qd, qdd = _rates(comp, q, drives, lvl, omega_ref)
    return _result(comp, level, q, qd, qdd, omega_ref, moved, tuple(notes), drives)


def _moved(
    comp: Compiled,
    drives: tuple[Drive, ...],
    options: SolveOptions,
    targets: list[float | None],
    notes: list[str],
) -> np.ndarray:
    """q at the drives' targets by Newton continuation from the drawing; what it did goes to ``notes``."""
    sys_, drawn = comp.system, comp.drawn
    if sys_.velocity_only:
        raise UnsupportedError(
            f"cannot move {comp.mech.label} to another angle: {instant_pairs(sys_.velocity_only)} "
            "only the instant drawn (no profile is given)",
            hint="analyse the drawn angle, or draw the mechanism at the angle you need",
        )
    passed: list[float] = []
    q = move_to(comp, drives, options, passed)
    shown = [
        f"{_deg(a)} → {_deg(t)}" for a, t in zip(drawn.drive_angles, targets, strict=False) if a is not None
    ]
    notes.append(f"moved from the drawn angle by continuation ({', '.join(shown)}), keeping its branch")
    notes += [
        f"passed a change point at {math.degrees(at):.6f}° (the constraint Jacobian loses rank with the loop "
        "closed on both sides) and continued on the branch with a continuous tangent"
        for at in passed
    ]
    return q


def refuse_underdriven(mech: Mechanism) -> None:
    """Refuse, from the counts alone, a mechanism with more degrees of freedom than drives.

    Each joint writes at most the rows Kutzbach counts for it (a pin of k links
    2(k − 1), a prismatic or rolling pair 2, a slot, cam, contact or gear 1:
    :func:`mech.kinematics.mobility.kutzbach`), so ``rank Φ_q ≤ 2j + h`` and the
    true mobility ``3(l − 1) − rank Φ_q`` is at least Kutzbach's count.  When
    that count alone exceeds the drives, the mechanism can move with every
    drive held whatever its geometry: refused here, before the assembly and the
    rank (a dense SVD that takes minutes on a 2,000-link chain).  The count may
    be *below* the true mobility (a double parallelogram: 0 against 1), so it
    never refuses the other way; that is the rank's test in :func:`solve`.

    Raises
    ------
    InputError
        Kutzbach's count exceeds the number of drives: the message names both
        and how many inputs are needed.
    """
    count = kutzbach(mech)
    given = len(mech.drives)
    if count <= given or not mech.has_geometry:  # nothing placed: the assembly says so at once
        return
    from mech.topology import dof

    drives = f"{given} drive{'s' if given != 1 else ''}" if given else "no drive"
    raise InputError(
        f"{mech.label} has {count} degree{'s' if count != 1 else ''} of freedom ({dof(mech).formula}; "
        f"special geometry can only add to that) but {drives}: it needs {count} "
        f"input{'s' if count != 1 else ''}, one drive per degree of freedom",
        where=mech.drives[0].where if mech.drives else Where(mech.path),
        hint=f"give one drive per degree of freedom: drive: [{{link: …, angle: …, rpm: …}}, …] ({count} of them)",
        source=mech.source,
    )


def instant_pairs(names: Sequence[str]) -> str:
    """``joint K describes`` / ``joints K, L describe``: the higher pairs known at one instant."""
    if len(names) == 1:
        return f"joint {names[0]} describes"
    return f"joints {', '.join(names)} describe"


def _rates(
    comp: Compiled, q: np.ndarray, drives: tuple[Drive, ...], lvl: int, omega_ref: float
) -> tuple[np.ndarray | None, np.ndarray | None]:
    """q̇ and q̈ (scaled) at ``q`` by the linear solves Φ_q q̇ = −Φ_t, Φ_q q̈ = γ (None above ``lvl``).

    Each solve is refined once and each component below its own error bound
    set to zero (:func:`snap_to_error`): a 1e-12 m crank on 1 m links keeps its
    4.4e-12 m/s, a pivot's 1e-17 m/s of round-off does not show.
    """
    sys_ = comp.system
    qd = qdd = None
    if lvl >= 1:
        jac = comp.jacobian if q is sys_.q0 else sys_.jacobian(q)  # not moved: Φ_q as compiled
        lin = _checked(comp, jac, drives)
        rhs = _rate_rhs(comp, drives, omega_ref)
        qd = lin(rhs)
        if lvl >= 2:
            if sys_.velocity_only:
                raise UnsupportedError(
                    f"accelerations need the curvature of the profiles at "
                    f"{', '.join(sys_.velocity_only)}: the file gives only the instant's contact "
                    "point and normal (velocities are available)",
                    hint="ask for velocities (mech velocity; level='velocity' from Python)",
                )
            qdd = lin(_accel_rhs(comp, q, qd, drives, omega_ref))
    return qd, qdd


def _rate_rhs(comp: Compiled, drives: tuple[Drive, ...], omega_ref: float) -> np.ndarray:
    """−Φ_t: the drives' rates (scaled) in their rows, zero elsewhere."""
    sys_, drawn = comp.system, comp.drawn
    rhs = np.zeros(sys_.m)
    rates = [(d.omega if d.link is not None else d.speed / drawn.scale) / omega_ref for d in drives]  # type: ignore[operator]
    rhs[sys_.drive_rows] = rates
    return rhs


def _accel_rhs(
    comp: Compiled, q: np.ndarray, qd: np.ndarray, drives: tuple[Drive, ...], omega_ref: float
) -> np.ndarray:
    """γ with the drives' angular (or linear) accelerations (scaled) in their rows."""
    sys_, drawn = comp.system, comp.drawn
    gamma = sys_.gamma(q, qd)
    acc = [
        (d.alpha if d.link is not None else (d.accel or 0.0) / drawn.scale) / omega_ref**2  # type: ignore[operator]
        for d in drives
    ]
    gamma[sys_.drive_rows] += acc
    return gamma


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
            qd, qdd = _rates(comp, q, here, lvl, omega_ref)
            yield _result(comp, level, q, qd, qdd, omega_ref, True, (), here)
        except GeometryError:
            yield _result(comp, "position", q, None, None, omega_ref, True, ("singular",), here)


# -- closed form ----------------------------------------------------------------------


def _closed_form(
    comp: Compiled, drives: tuple[Drive, ...], lvl: int, omega_ref: float, options: SolveOptions
) -> tuple[Callable[[], _State], Callable[[], str]] | None:
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

    def state() -> _State:
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
            inverse = _pinv(np.linalg.svd(jac, full_matrices=False))
            qd = snap_to_error(jac, inverse, qd, _rate_rhs(comp, drives, omega_ref))
        if lvl >= 2 and qd is not None:
            qdd = np.empty(3 * n)
            qdd[0::3] = np.asarray(parts["lax"]) / (scale * omega_ref**2)
            qdd[1::3] = np.asarray(parts["lay"]) / (scale * omega_ref**2)
            qdd[2::3] = np.asarray(parts["lal"]) / omega_ref**2
            qdd = snap_to_error(jac, inverse, qdd, _accel_rhs(comp, q, qd, drives, omega_ref))
        return q, qd, qdd

    def note() -> str:
        kinds = ", ".join(dict.fromkeys(k for k, _, _ in prog.dyads)) or "crank only"
        text = (
            f"moved from the drawn angle ({_deg(prog.drawn_angle)} → {_deg(phi)}) keeping its branch, "
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
        f"singular configuration of {comp.mech.label} ({d.link} at {_deg(phi)}): "
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


# -- drives ---------------------------------------------------------------------------
def _drives_of(comp: Compiled, options: SolveOptions, lvl: int) -> tuple[Drive, ...]:
    """:func:`drives_as_used` for a compiled mechanism, remembered in its memo: a repeated solve skips them.

    Errors are raised afresh, never kept.
    """
    return comp.memo.get(
        ("drives", options, lvl), lambda: drives_as_used(comp.mech, comp.layout, comp.drawn, options, lvl)
    )


def drives_as_used(
    mech: Mechanism, lay: Layout, drawn: Drawn, options: SolveOptions, lvl: int
) -> tuple[Drive, ...]:
    """The drives as used: overrides applied, angle from the drawing, omega signed."""
    out = []
    for k, (d, spec) in enumerate(zip(mech.drives, lay.drives, strict=False)):
        if spec.link is not None:
            if options.speed is not None:
                raise InputError(
                    f"--speed sets a slider drive; the drive of {d.link} turns",
                    where=d.where,
                    hint="use --rpm or --omega",
                )
            omega = d.omega
            if options.omega is not None:
                sign = (
                    -1.0
                    if (options.direction == "cw" or (options.direction is None and (d.omega or 0) < 0))
                    else 1.0
                )
                omega = sign * options.omega
            elif options.direction is not None and omega is not None:
                omega = abs(omega) * (-1.0 if options.direction == "cw" else 1.0)
            angle = options.angle if options.angle is not None else drawn.drive_angles[k]
            if angle is None:
                raise InputError(
                    f"drive of {d.link}: no angle given and none can be read from the drawing",
                    where=d.where,
                    hint="give drive.angle (or --angle)",
                )
            alpha = options.alpha if options.alpha is not None else (d.alpha or 0.0)
            if lvl >= 1 and omega is None:
                raise InputError(
                    f"drive of {d.link} has no speed: give rpm or omega (or --rpm)", where=d.where
                )
            out.append(replace(d, angle=float(angle), omega=omega, alpha=alpha))
        else:
            if options.angle is not None:
                raise InputError(
                    f"--angle applies to a turning drive; the drive of {d.joint} is a slider", where=d.where
                )
            turning = [
                flag
                for flag, given in (
                    ("--rpm/--omega", options.omega is not None),
                    ("--direction", options.direction is not None),
                    ("--alpha", options.alpha is not None),
                )
                if given
            ]
            if turning:
                raise InputError(
                    f"{', '.join(turning)} set a turning drive; the drive of {d.joint} is a slider",
                    where=d.where,
                    hint="give its speed with --speed (m/s, signed along its path) or speed: in the file",
                )
            speed = options.speed if options.speed is not None else d.speed
            if lvl >= 1 and speed is None:
                raise InputError(f"slider drive of {d.joint} has no speed: give speed (m/s)", where=d.where)
            out.append(replace(d, speed=speed, accel=d.accel or 0.0))
    if lvl >= 1 and not out:
        raise InputError(
            f"{mech.label} has no drive: give rpm or omega (or --rpm)",
            hint="add drive: {link: crank, angle: 60, rpm: 120}",
        )
    return tuple(out)


def omega_ref_of(drives: tuple[Drive, ...], scale: float) -> float:
    """Time scale 1/ω: the fastest drive (a slider's v/size), 1 when nothing moves."""
    rates: list[float] = []
    for d in drives:
        rate = d.omega if d.link is not None else (None if d.speed is None else d.speed / scale)
        if rate is not None:
            rates.append(abs(rate))
    best = max(rates, default=0.0)
    return best if best > 0 and math.isfinite(best) else 1.0


def _deg(a: float | None) -> str:
    """An angle for a message; a drive angle the file does not give is said so."""
    return f"{math.degrees(a):.6g}°" if a is not None else "(no angle given)"


# -- linear algebra ---------------------------------------------------------------------
#: Unknowns (3 per moving link) from which square systems are solved block by block
#: (:mod:`.blocks`) rather than densely: below it one dense LU or SVD is cheaper than
#: a Python loop over the blocks.
BLOCK_MIN = 90


def _blocks(sys_: System) -> BlockForm | None:
    """The block-triangular form of ``sys_``'s Φ_q (kept in its memo), or None: small, redundant or irreducible.

    The sparsity is read from Φ_q at the drawn configuration and at a perturbed
    one, so that an entry that happens to vanish as drawn (a link at 0°) is
    still counted.
    """
    n3 = 3 * sys_.n
    if n3 < BLOCK_MIN or sys_.m != n3:
        return None
    return sys_.memo.get("blocks", lambda: _block_form(sys_))


def _block_form(sys_: System) -> BlockForm | None:
    n3 = 3 * sys_.n
    wiggle = np.random.default_rng(0).uniform(-0.1, 0.1, n3)
    pattern = (sys_.jacobian(sys_.q0) != 0) | (sys_.jacobian(sys_.q0 + wiggle) != 0)
    form = block_form(pattern)
    if form is not None and form.largest * 2 > n3:
        form = None  # one block holds most of it: nothing to gain over the dense path
    return form


def _square_solve(sys_: System, jac: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """x with Φ_q x = rhs: one LU (block by block for a large chain), least squares when not square."""
    if jac.shape[0] != jac.shape[1]:
        return np.linalg.lstsq(jac, rhs, rcond=None)[0]
    form = _blocks(sys_)
    return form.solve(jac, rhs) if form is not None else np.linalg.solve(jac, rhs)


def _checked(
    comp: Compiled, jac: np.ndarray, drives: tuple[Drive, ...]
) -> Callable[[np.ndarray], np.ndarray]:
    """A solver of Φ_q x = b at a converged configuration, after refusing a singular one.

    Rank and conditioning are judged here, once per configuration: by one SVD
    (small systems), or block by block for a large chain (:mod:`.blocks`).  The
    solver refines its answer once and zeroes what is below its error bound
    (:func:`snap_to_error`).
    """
    form = _blocks(comp.system)
    if form is None:
        svd = _svd_checked(comp, jac, drives)
        inverse = _pinv(svd) if jac.shape[1] else None
        return lambda rhs: snap_to_error(jac, inverse, _refined(jac, lambda b: _lin_solve(svd, b), rhs), rhs)
    cond, null = form.condition(jac)
    if cond > SINGULAR:
        raise GeometryError(
            _singular_message(comp, null, cond, drives),  # type: ignore[arg-type]
            hint="analyse a slightly different angle: velocities here are undetermined",
        )
    return lambda rhs: snap_to_error(jac, None, _refined(jac, lambda b: form.solve(jac, b), rhs), rhs)


#: Safety factor on the first-order error bound below which a rate is shown as zero.
NOISE_FACTOR = 64.0
_EPS = float(np.finfo(float).eps)


def _refined(jac: np.ndarray, solve: Callable[[np.ndarray], np.ndarray], rhs: np.ndarray) -> np.ndarray:
    """x with Φ_q x = b, improved by one step of iterative refinement.

    The SVD (or LU) leaves every component with an error of about ε times the
    largest one: on a 1e-12 m crank in a 1 m linkage, where the crank's ω is 1
    and the rod's is 4.4e-12 (scaled), that was 1e-4 of the rod's ω.  One
    refinement step x += solve(b − Φ_q x) makes the solve componentwise
    backward stable (Skeel 1980; Higham, *Accuracy and Stability of Numerical
    Algorithms*, § 12.2): each component is then good to its own size.
    """
    x = solve(rhs)
    return x + solve(rhs - jac @ x)


def _pinv(svd: tuple) -> np.ndarray:
    """Φ_q⁺ = V Σ⁻¹ Uᵀ from its SVD (for the componentwise error bound)."""
    u, s, vt = svd
    return vt.T @ (u.T / s[:, None])


def snap_to_error(jac: np.ndarray, inverse: np.ndarray | None, x: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """Components of ``x`` within their own error bound of zero set to exactly zero.

    The bound is Skeel's first-order componentwise one for a refined solve,
    |δx| ≤ ε |Φ_q⁺| (|Φ_q| |x| + |b|), times :data:`NOISE_FACTOR`: each rate is
    judged against the rates and lengths it is computed from, never against the
    mechanism's fastest part, so a real 4.4e-12 rad/s beside 6.3 rad/s is kept.
    Without the inverse (a large chain solved block by block) the bound is the
    normwise one, ε·NOISE_FACTOR·max|x|·1e3 (about 1e-13 of the largest rate).
    """
    if x.size == 0:
        return x
    if inverse is None:
        floor = np.full(x.shape, 1e3 * NOISE_FACTOR * _EPS * float(np.max(np.abs(x))))
    elif x.ndim == 2:  # a stack of K solves (march): jac (K, m, n), inverse (K, n, m), x (K, n), rhs (K, m)
        bound = np.abs(jac) @ np.abs(x)[..., None] + np.abs(rhs)[..., None]
        floor = NOISE_FACTOR * _EPS * (np.abs(inverse) @ bound)[..., 0]
    else:
        floor = NOISE_FACTOR * _EPS * (np.abs(inverse) @ (np.abs(jac) @ np.abs(x) + np.abs(rhs)))
    x[np.abs(x) <= floor] = 0.0
    return x


def _svd_checked(comp: Compiled, jac: np.ndarray, drives: tuple[Drive, ...]) -> tuple:
    """SVD of Φ_q, refusing a singular configuration with the links that lose their guidance."""
    n = jac.shape[1]
    if jac.shape[0] < n:  # fewer equations than unknowns: pad so that the null vector shows
        jac = np.vstack([jac, np.zeros((n - jac.shape[0], n))])
    u, s, vt = np.linalg.svd(jac, full_matrices=False)
    if n == 0:
        return u, s, vt
    cond = float(s[0] / s[n - 1]) if s[n - 1] > 0 else math.inf
    if cond > SINGULAR:
        raise GeometryError(
            _singular_message(comp, vt[n - 1], cond, drives),
            hint="analyse a slightly different angle: velocities here are undetermined",
        )
    return u, s, vt


def _is_singular(jac: np.ndarray) -> bool:
    """True when Φ_q (with drive rows) does not determine q̇: fewer rows or condition above SINGULAR."""
    m, n = jac.shape
    if n == 0:
        return False
    if m < n:
        return True
    s = np.linalg.svd(jac, compute_uv=False)
    return bool(s[n - 1] <= s[0] / SINGULAR)


def _snap(x: np.ndarray) -> np.ndarray:
    """Round-off (below 1e-13 in scaled units, far under the solve's accuracy) to exact zero.

    A pivot's velocity of 1e-16 m/s would otherwise print with a random
    direction; the true values there are zero by the constraints.
    """
    x[np.abs(x) < 1e-13] = 0.0
    return x


def _lin_solve(svd: tuple, rhs: np.ndarray) -> np.ndarray:
    """x = V Σ⁻¹ Uᵀ b: exact for square systems, least squares for consistent redundant rows."""
    u, s, vt = svd
    return vt.T @ ((u.T @ rhs) / s)


def _singular_message(comp: Compiled, v: np.ndarray, cond: float, drives: tuple[Drive, ...]) -> str:
    sys_ = comp.system
    weight = np.abs(v).reshape(-1, 3).max(axis=1)
    moving = [sys_.links[i] for i in np.argsort(-weight) if weight[i] > 0.2 * weight.max()]
    where = ", ".join(
        f"{d.link} at {_deg(d.angle)}" for d in drives if d.link is not None and d.angle is not None
    )
    at = f" ({where})" if where else ""
    if len(moving) == 2:
        what = f"{moving[0]} and {moving[1]} are in line"
    elif len(moving) == 1:
        what = f"{moving[0]} is not held by its joints"
    else:
        what = f"{', '.join(moving)} can move with the drive held (links in line)"
    return (
        f"singular configuration of {comp.mech.label}{at}: {what} — a toggle or dead-centre "
        f"position (condition number {cond:.2g})"
    )


# -- position: continuation ----------------------------------------------------------------
def move_to(
    comp: Compiled, drives: tuple[Drive, ...], options: SolveOptions, passed: list[float] | None = None
) -> np.ndarray:
    """Carry the drawn configuration to the drives' target angles, keeping its branch.

    With ``passed`` (a list), the angles (rad) of the first moving drive where
    the continuation passed a change point are appended (see :func:`continue_along`).
    """
    sys_, drawn = comp.system, comp.drawn
    c_line = sys_.ln_c.copy()
    base_ang = sys_.ang_c.copy()
    offset = 2 * sys_.pc_i.size + sys_.ln_s.size
    deltas = np.zeros(len(drives))
    rows = []
    for k, (d, a) in enumerate(zip(drives, drawn.drive_angles, strict=False)):
        rows.append(sys_.drive_rows[k] - offset)
        if d.link is not None and a is not None:
            deltas[k] = wrap_angle(d.angle - a)  # type: ignore[operator]
    tries = [deltas]
    if np.count_nonzero(deltas) == 1:
        k = int(np.flatnonzero(deltas)[0])
        other = deltas.copy()
        other[k] -= math.copysign(_TWO_PI, deltas[k])
        tries.append(other)
    reached = []
    for total in tries:
        found: list[float] | None = [] if passed is not None and np.count_nonzero(total) == 1 else None
        q, fraction = continue_along(sys_, sys_.q0, base_ang, c_line, rows, total, options, found)
        if q is not None:
            if found:
                k = int(np.flatnonzero(total)[0])
                a = drawn.drive_angles[k]
                passed.extend(float(a) + f * float(total[k]) for f in found if a is not None)  # type: ignore[union-attr]
            return q
        reached.append(fraction)
    c_ang = base_ang.copy()
    c_ang[rows] += deltas
    gap, miss = _closest_gap(comp, c_line, c_ang)
    d = next(d for d in drives if d.link is not None)
    hint = "a rocker or a slider has limits: choose an angle between them (mech sweep shows them)"
    if miss <= 1e-9:
        hint = "that configuration is on another circuit: draw the mechanism there (at/near) to analyse it"
    raise GeometryError(_unreachable_message(comp, drives, reached[0], gap, miss), where=d.where, hint=hint)


def _closest_gap(comp: Compiled, c_line: np.ndarray, c_ang: np.ndarray) -> tuple[str, float]:
    """The joint left most open by the least-squares closest configuration (file's unit).

    Also returns that miss relative to the mechanism's size: about zero when the
    angle can be assembled, but only on another circuit than the drawing's.
    """
    sys_ = comp.system
    q = sys_.q0.copy()
    for _ in range(100):
        r = sys_.phi(q, c_line, c_ang)
        jac = sys_.jacobian(q)
        dq = np.linalg.lstsq(jac, -r, rcond=None)[0]
        t, norm = 1.0, float(np.linalg.norm(r))
        while t > 1e-6 and float(np.linalg.norm(sys_.phi(q + t * dq, c_line, c_ang))) >= norm:
            t /= 2
        if t <= 1e-6:
            break
        q = q + t * dq
    r = sys_.phi(q, c_line, c_ang)
    k = sys_.pc_i.size
    miss = np.concatenate([np.hypot(r[0 : 2 * k : 2], r[1 : 2 * k : 2]), np.abs(r[2 * k :])])
    names = [sys_.row_names[2 * i] for i in range(k)] + list(sys_.row_names[2 * k :])
    worst = int(np.argmax(miss))
    from mech.units import to_unit

    unit = comp.mech.length_unit
    text = f"the closest configuration leaves {names[worst]} open by {to_unit(miss[worst] * sys_.scale, unit):.4g} {unit}"
    return text, float(miss[worst])


def continue_along(
    sys_: System,
    q: np.ndarray,
    base_ang: np.ndarray,
    c_line: np.ndarray,
    rows: list[int],
    total: np.ndarray,
    options: SolveOptions,
    crossings: list[float] | None = None,
) -> tuple[np.ndarray | None, float]:
    """Step the drive angles from 0 to ``total`` (rad); returns (q, 1.0) or (None, fraction reached).

    With ``crossings`` (a list), the fractions of ``total`` where the path
    passes a singular configuration with the loop closed on both sides (a
    change point: det Φ_q changes sign between two steps) are appended,
    located by bisection; watched only on square systems of at most
    :data:`WATCH_MAX` unknowns (a determinant per step).
    """
    done, step = 0.0, min(1.0, _MAX_STEP / max(float(np.max(np.abs(total))), 1e-300))
    rhs_rows = sys_.drive_rows
    watch = crossings is not None and sys_.m == 3 * sys_.n <= WATCH_MAX
    sign = _det_sign(sys_, q) if watch else 0.0
    while done < 1.0:
        h = min(step, 1.0 - done)
        # predictor: q̇ for a unit rate along the total change
        jac = sys_.jacobian(q)
        rhs = np.zeros(sys_.m)
        rhs[rhs_rows] = total
        try:
            pred = q + h * _square_solve(sys_, jac, rhs)
        except np.linalg.LinAlgError:  # a singular start (a toggle drawn): the least-squares rate
            pred = q + h * np.linalg.lstsq(jac, rhs, rcond=None)[0]
        c_ang = base_ang.copy()
        c_ang[rows] += (done + h) * total
        q_new = _newton(sys_, pred, c_line, c_ang, options)
        if q_new is None:
            step = h / 2.0
            if step * float(np.max(np.abs(total))) < 1e-7:
                return None, done
            continue
        if watch and crossings is not None:
            now = _det_sign(sys_, q_new)
            if now * sign < 0.0:  # passed a zero of det Φ_q: locate it between the two steps
                crossings.append(
                    _crossing(sys_, q, base_ang, c_line, rows, total, done, done + h, sign, options)
                )
            sign = now or sign
        q, done = q_new, done + h
        step = min(step * 2.0, 1.0)
        step = min(step, _MAX_STEP / max(float(np.max(np.abs(total))), 1e-300))
    return q, 1.0


#: Largest square system (unknowns) whose det Φ_q a single solve's continuation watches for change points.
WATCH_MAX = 120


def _det_sign(sys_: System, q: np.ndarray) -> float:
    """The sign of det Φ_q (0 where it is singular to rounding)."""
    return float(np.linalg.slogdet(sys_.jacobian(q))[0])


def _crossing(
    sys_: System,
    q: np.ndarray,
    base_ang: np.ndarray,
    c_line: np.ndarray,
    rows: list[int],
    total: np.ndarray,
    lo: float,
    hi: float,
    sign: float,
    options: SolveOptions,
) -> float:
    """The fraction of ``total`` in (lo, hi) where det Φ_q changes sign, bisected from ``q`` (at lo).

    Each probe is one predicted Newton solve from ``q``; Newton is good to about
    √tol next to the singular configuration, so the fraction is good to about that.
    """
    rhs = np.zeros(sys_.m)
    rhs[sys_.drive_rows] = total
    try:
        rate = _square_solve(sys_, sys_.jacobian(q), rhs)
    except np.linalg.LinAlgError:
        return 0.5 * (lo + hi)
    start = lo
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        c_ang = base_ang.copy()
        c_ang[rows] += mid * total
        q_mid = _newton(sys_, q + (mid - start) * rate, c_line, c_ang, options)
        if q_mid is None:
            break
        if _det_sign(sys_, q_mid) * sign > 0.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def _newton(
    sys_: System, q: np.ndarray, c_line: np.ndarray, c_ang: np.ndarray, options: SolveOptions
) -> np.ndarray | None:
    """Newton–Raphson on Φ(q) = 0 (scaled); None when it does not converge quadratically."""
    prev = math.inf
    for _ in range(options.max_iter):
        r = sys_.phi(q, c_line, c_ang)
        norm = float(np.max(np.abs(r))) if r.size else 0.0
        if norm <= options.tol:
            return q
        if not math.isfinite(norm) or (norm > 0.5 * prev and prev < 1e-3):
            return None
        prev = norm
        jac = sys_.jacobian(q)
        try:
            dq = _square_solve(sys_, jac, -r)
        except np.linalg.LinAlgError:
            return None
        if float(np.max(np.abs(dq))) > 1.0:  # more than a mechanism size: lost
            return None
        q = q + dq
    r = sys_.phi(q, c_line, c_ang)
    return q if float(np.max(np.abs(r))) <= options.tol else None


def _unreachable_message(
    comp: Compiled, drives: tuple[Drive, ...], reached: float | None, gap: str, miss: float
) -> str:
    d = next(d for d in drives if d.link is not None)
    a = comp.drawn.drive_angles[0]
    limit = ""
    if reached is not None and a is not None and d.angle is not None:
        stop = a + reached * wrap_angle(d.angle - a)
        limit = f"moving {d.link} from the drawn {_deg(a)} it locks near {_deg(stop)} (a limit position)"
    if miss <= 1e-9:  # it closes there, but not on the drawing's circuit
        return (
            f"{comp.mech.label} cannot reach {d.link} at {_deg(d.angle)} from its drawing: "
            f"{limit or 'a limit position lies between'}; that angle belongs to another circuit "
            "(it can be assembled there only by taking the mechanism apart)"
        )
    return f"{comp.mech.label} cannot be assembled with {d.link} at {_deg(d.angle)}: {gap}" + (
        f"; {limit}" if limit else ""
    )


# -- results -----------------------------------------------------------------------------
def _result(
    comp: Compiled,
    level: str,
    q: np.ndarray,
    qd: np.ndarray | None,
    qdd: np.ndarray | None,
    omega_ref: float,
    moved: bool,
    notes: tuple[str, ...],
    drives: tuple[Drive, ...],
) -> Kinematics:
    """The result of a solve in scaled coordinates ``q, q̇, q̈``, packaged when first read."""
    return _lazy(comp, level, lambda: (q, qd, qdd), omega_ref, moved, notes, drives)


def _lazy(
    comp: Compiled,
    level: str,
    state: Callable[[], _State],
    omega_ref: float,
    moved: bool,
    notes: tuple[str, ...] | Callable[[], tuple[str, ...]],
    drives: tuple[Drive, ...],
) -> Kinematics:
    mech = comp.mech
    return Kinematics.lazy(
        mech.label,
        level,
        comp.mobility,
        drives,
        mech.ground,
        notes,
        lambda: _fields(comp, *state(), omega_ref, moved),
    )


def _fields(
    comp: Compiled,
    q: np.ndarray,
    qd: np.ndarray | None,
    qdd: np.ndarray | None,
    omega_ref: float,
    moved: bool,
) -> Fields:
    """Unscale and package; vectorised, since it runs on every solve of a sweep.

    The steps: every location's position (:func:`_positions`), each link's state
    (:func:`_link_states`), each joint's geometry (:func:`_joint_geoms`).
    """
    sys_, lay = comp.system, comp.layout
    positions, all_pos = _positions(comp, q, moved)
    links = _link_states(comp, q, qd, qdd, omega_ref, positions)
    joints = _joint_geoms(comp, q, positions, all_pos)
    carriers = {n_: c_ for n_, c_ in lay.carriers.items() if not n_.startswith("#")}
    for alias, target in lay.alias.items():
        carriers[alias] = carriers.get(target, ())
    return Fields(
        MappingProxyType(positions),
        MappingProxyType(links),
        MappingProxyType(carriers),
        MappingProxyType(joints),
        joint_names=sys_.joint_names,
    )


def _positions(
    comp: Compiled, q: np.ndarray, moved: bool
) -> tuple[dict[str, tuple[float, float]], dict[str, tuple[float, float]]]:
    """Every location's global position (m): the named ones, and all (``#`` synthetic ones too)."""
    sys_, lay = comp.system, comp.layout
    scale, centre = sys_.scale, sys_.centre
    cx, cy = float(centre[0]), float(centre[1])
    # every located point at once: r = R + A(θ) s, for its carrier (ground appended)
    qf = np.append(q, (0.0, 0.0, 0.0))
    idx, loc = sys_.loc_i, sys_.loc_s
    th = qf[3 * idx + 2]
    c, sn = np.cos(th), np.sin(th)
    xs = ((qf[3 * idx] + c * loc[:, 0] - sn * loc[:, 1]) * scale + cx).tolist()
    ys = ((qf[3 * idx + 1] + sn * loc[:, 0] + c * loc[:, 1]) * scale + cy).tolist()
    all_pos = dict(zip(sys_.loc_names, zip(xs, ys, strict=True), strict=True))
    positions = {n: p for n, p in all_pos.items() if not n.startswith("#")}
    if not moved:
        for n, p in sys_.contact_xy.items():
            positions[n] = (float(p[0] * scale + cx), float(p[1] * scale + cy))
    for n, locate in sys_.locators.items():  # profiles in contact: where they touch now
        p = locate(q)
        positions[n] = (float(p[0] * scale + cx), float(p[1] * scale + cy))
    if lay.contacts:
        complete(lay, positions)  # a moved gear pair: pitch point from its centres
    for alias, target in lay.alias.items():
        if target in positions:
            positions[alias] = positions[target]
    return positions, all_pos


def _link_states(
    comp: Compiled,
    q: np.ndarray,
    qd: np.ndarray | None,
    qdd: np.ndarray | None,
    omega_ref: float,
    positions: dict[str, tuple[float, float]],
) -> dict[str, LinkState]:
    """Each link's origin, angle and (up to the level solved) velocities and accelerations, SI."""
    sys_, lay, mech = comp.system, comp.layout, comp.mech
    scale, centre = sys_.scale, sys_.centre
    v_unit, a_unit = scale * omega_ref, scale * omega_ref**2
    cx, cy = float(centre[0]), float(centre[1])
    n_links = sys_.n
    qs = q.tolist()
    vs = (
        (qd * np.repeat([[v_unit, v_unit, omega_ref]], n_links, axis=0).ravel()).tolist()
        if qd is not None
        else None
    )
    acc_units = np.repeat([[a_unit, a_unit, omega_ref**2]], n_links, axis=0).ravel()
    as_ = (qdd * acc_units).tolist() if qdd is not None else None
    links: dict[str, LinkState] = {}
    zero = (0.0, 0.0)
    for lk in mech.links:
        if lk.is_ground:
            gpts = [positions[p] for p in lay.on_link.get(lk.name, ()) if p in positions]
            links[lk.name] = LinkState(
                lk.name,
                gpts[0] if gpts else (cx, cy),
                0.0,
                zero if vs is not None else None,
                0.0 if vs is not None else None,
                zero if as_ is not None else None,
                0.0 if as_ is not None else None,
            )
            continue
        i = 3 * sys_.link_index[lk.name]
        links[lk.name] = LinkState(
            lk.name,
            (qs[i] * scale + cx, qs[i + 1] * scale + cy),
            qs[i + 2] % _TWO_PI,
            (vs[i], vs[i + 1]) if vs is not None else None,
            vs[i + 2] if vs is not None else None,
            (as_[i], as_[i + 1]) if as_ is not None else None,
            as_[i + 2] if as_ is not None else None,
        )
    return links


def _joint_geoms(
    comp: Compiled,
    q: np.ndarray,
    positions: dict[str, tuple[float, float]],
    all_pos: dict[str, tuple[float, float]],
) -> dict[str, JointGeom]:
    """Each joint's point and direction now: a path's line, a contact's common tangent."""
    sys_, lay, mech = comp.system, comp.layout, comp.mech
    n_links = sys_.n
    joints: dict[str, JointGeom] = {}
    for j in mech.joints:
        direction = None
        point: str | None = lay.resolve(j.name)
        if j.name in sys_.path_dirs:
            g, u = sys_.path_dirs[j.name]
            th_g = 0.0 if g == n_links else float(q[3 * g + 2])
            c_g, s_g = math.cos(th_g), math.sin(th_g)
            direction = (c_g * u[0] - s_g * u[1], s_g * u[0] + c_g * u[1])
            point = sys_.path_points[j.name][1]
        elif j.name in sys_.normals:  # profiles in contact: the common tangent now
            nx, ny = sys_.normals[j.name](q)
            direction = (-float(ny), float(nx))
        elif kind_of(j).role == "contact" and j.normal is not None:
            direction = (-math.sin(j.normal), math.cos(j.normal))
        at = positions.get(point) or all_pos.get(point)  # type: ignore[arg-type]
        if j.name in sys_.contact_points:  # the pair touches away from its location (a follower's point)
            p = sys_.contact_points[j.name](q) * sys_.scale + sys_.centre
            at = (float(p[0]), float(p[1]))
        if point is not None and (point.startswith("#") or point not in positions):
            point = None
        joints[j.name] = JointGeom(j.name, j.type, tuple(j.links), point, direction, j.radius, at)
    return joints
