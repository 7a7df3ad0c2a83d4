"""The forces at one instant: the batched solve of :mod:`mech.forces.core` on a stack of one.

The kinematics' own solution gives the pose, rates and accelerations
(:func:`motion_of`); the solve gives the multipliers, and each joint's kind
reads the force it carries from what its rows put on its links
(:meth:`mech.pairs.base.PairKind.forces`: a pin's force, a slider's normal
force and where it acts, a tooth load along the line of action).  The drive's
row gives the input torque (or force), which the power balance also gives.

Where the rows are redundant (a double parallelogram: more rows than their
rank) statics cannot split the load between them: the pairs' forces are not
given, and the input effort comes from the power balance, which needs no
split: T ω + Q·q̇ = 0, the constraints doing no work.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mech.forces.core import Motion, Solved, push_rows, reactions, solve, unsaid_notes
from mech.forces.result import Effort, ForceAnalysis, Inertia, PairForce
from mech.model import Mechanism
from mech.options import SolveOptions
from mech.pairs import kind_of

__all__ = ["analyse", "at_instant", "drive_options", "drive_pivot", "has_speed", "motion_of"]

Vec = tuple[float, float]


def analyse(
    mech: Mechanism, options: SolveOptions | None = None, *, flanks: dict[str, float] | None = None
) -> ForceAnalysis:
    """The forces of ``mech`` at its drive's angle (``options`` as for :func:`mech.kinematics.solve`).

    With masses and a drive speed the links' inertia counts (d'Alembert: the
    mechanism is solved to accelerations; without masses to velocities); a drive
    without a speed (or at a speed of zero) is a static problem: the rates are taken
    at unit speed for the power balance only, and no inertia acts.

    ``flanks`` (:func:`at_instant`): the gear flanks in contact at a nearby instant, tried first
    and updated.

    Raises
    ------
    InputError
        A load at a pin two moving links share without ``on``; a file that cannot be solved.
    """
    from mech.kinematics.solve import compiled, solve

    options, static = drive_options(mech, options or SolveOptions())
    comp = compiled(mech, None)
    # accelerations only where they act: a massless mechanism (a cam known at its instant) needs rates alone
    kin = solve(mech, "acceleration" if mech.masses and not static else "velocity", options)
    return at_instant(mech, kin, comp, static=static, flanks=flanks)


def has_speed(mech: Mechanism, options: SolveOptions) -> bool:
    """True when the drive turns (or slides) at a speed other than zero: inertia acts."""
    if options.omega is not None or options.speed is not None:
        return bool(options.omega or options.speed)
    return any(d.omega or d.speed for d in mech.drives)


def drive_options(mech: Mechanism, options: SolveOptions) -> tuple[SolveOptions, bool]:
    """The options a force solve runs with, and whether it is static (no drive speed).

    A static problem (loads and gravity on a mechanism at rest, or turning at a
    speed of zero) is solved at unit speed for the power balance only; no inertia acts.
    """
    if has_speed(mech, options):
        return options, False
    driven = mech.drives[0] if mech.drives else None
    if driven is not None and driven.link is not None:
        return options.with_(omega=1.0), True
    return options.with_(speed=1.0), True


def at_instant(
    mech: Mechanism, kin: Any, comp: Any, *, static: bool = False, flanks: dict[str, float] | None = None
) -> ForceAnalysis:
    """The force analysis of ``mech`` at the instant ``kin`` was solved for (acceleration level,
    or velocity level when ``static``: no inertia, the rates only for the power balance).

    ``comp`` is the compiled mechanism (:func:`mech.kinematics.solve.compiled`).  Gear teeth only
    push: a tooth load that would pull is solved again on the other flanks.  ``flanks`` (gear
    joint → ±1, the flanks in contact) are tried first when given, and left as found: a sweep
    passes the last step's, and solves again only where the load turns.
    """
    sys_ = comp.system
    about = drive_pivot(mech, kin)
    motion = motion_of(kin, sys_, static=static)
    chosen = dict(flanks or {})
    pushed: dict[tuple[str, int], list[float]] = {}  # each push row, made once for both solves

    def rows(jac: np.ndarray) -> np.ndarray:
        return _reaction_rows(mech, kin, sys_, motion, jac, chosen, pushed)

    solved = solve(mech, sys_, motion, about=np.array([about]), rows=rows)
    if bool(solved.determinate[0]):
        turned = _other_flanks(mech, kin, sys_, solved)
        if turned:
            chosen.update({name: -chosen.get(name, 1.0) for name in turned})
            solved = solve(mech, sys_, motion, about=np.array([about]), rows=rows)
    if flanks is not None:
        flanks.clear()
        flanks.update(chosen)
    determinate = bool(solved.determinate[0])
    pairs: tuple[PairForce, ...] = ()
    note = ""
    if determinate:
        pairs = _pair_forces(mech, kin, sys_, solved)
    else:
        m = solved.jac.shape[1]
        note = (
            f"the pairs' forces are indeterminate: {m} constraint rows have rank {int(solved.rank[0])} "
            "(a redundant constraint: statics cannot split the load); the input effort is from the power balance"
        )
    angle = kin.drives[0].angle if kin.drives else None
    return ForceAnalysis(
        mechanism=mech.label,
        drive_angle=angle,
        pairs=pairs,
        effort=_effort(mech, kin, solved),
        inertia=_records(mech, solved),
        shaking_force=(float(solved.shaking[0, 0]), float(solved.shaking[0, 1])),
        shaking_moment=float(solved.moment[0]),
        about=about,
        determinate=determinate,
        note=note,
        static=static,
        notes=unsaid_notes(mech) + _force_notes(mech, kin, pairs),
        kinematics=kin,
    )


def motion_of(kin: Any, sys_: Any, *, static: bool = False) -> Motion:
    """The solved instant ``kin`` as a stack of one (:class:`mech.forces.core.Motion`)."""
    n = sys_.n
    pose, rates, accels = np.zeros((1, n, 3)), np.zeros((1, n, 3)), np.zeros((1, n, 3))
    for name, i in sys_.link_index.items():
        st = kin.links[name]
        pose[0, i] = (st.origin[0], st.origin[1], st.angle)
        if st.velocity is not None:
            rates[0, i] = (st.velocity[0], st.velocity[1], st.omega or 0.0)
        if not static and st.acceleration is not None:
            accels[0, i] = (st.acceleration[0], st.acceleration[1], st.alpha or 0.0)
    angle = float(kin.drives[0].angle) if kin.drives and kin.drives[0].angle is not None else 0.0
    named = {name: np.array([p], float) for name, p in kin.positions.items()}
    return Motion(pose, rates, None if static else accels, np.array([angle]), np.array([_rate(kin)]), named)


def _rate(kin: Any) -> float:
    """The drive's rate: ω of the driven link relative to what it turns on, or a slider's speed."""
    if not kin.drives:
        return 0.0
    d = kin.drives[0]
    if d.link is not None:
        return float(
            (kin.links[d.link].omega or 0.0)
            - (kin.links[d.relative_to].omega or 0.0 if d.relative_to else 0.0)
        )
    return float(kin.sliding(d.joint))


def _reaction_rows(
    mech: Mechanism,
    kin: Any,
    sys_: Any,
    motion: Motion,
    jac: np.ndarray,
    flanks: dict[str, float],
    pushed: dict[tuple[str, int], list[float]],
) -> np.ndarray:
    """The Jacobian with the rows of a pair that carries its force otherwise (a gear on fixed
    centres) replaced by its kind's (on the mirror line of action where ``flanks`` says −1)."""
    jac = push_rows(mech, sys_, motion, jac, pushed)
    names = np.array(sys_.row_names)
    view = _View(mech, kin, sys_, flanks)
    for j in mech.joints:
        rows = kind_of(j).reaction_rows(j, view)
        if rows is None:
            continue
        idx = np.flatnonzero(names == j.name)
        jac[0, idx[: len(rows)]] = rows
    return jac


class _View:
    """What a kind's :meth:`~mech.pairs.base.PairKind.reaction_rows` reads: the solved instant in SI."""

    def __init__(self, mech: Mechanism, kin: Any, sys_: Any, flanks: dict[str, float]) -> None:
        self.mech, self.kin, self.sys, self.flanks = mech, kin, sys_, flanks

    def column(self, link: str) -> int:
        """The first of the link's three columns (ground's are last)."""
        return 3 * self.sys.link_index.get(link, self.sys.n)

    @property
    def width(self) -> int:
        return 3 * (self.sys.n + 1)

    def origin(self, link: str) -> Vec:
        return tuple(self.kin.links[link].origin)  # type: ignore[return-value]


def _other_flanks(mech: Mechanism, kin: Any, sys_: Any, solved: Solved) -> list[str]:
    """The pairs whose solved force pulls where they can only push (gear teeth): each is solved
    again on its mirror line of action (:meth:`~mech.pairs.base.PairKind.other_flank`)."""
    out: list[str] = []
    for j in mech.joints:
        second = j.links[-1]
        on_links = reactions(solved, sys_, j.name, j.links) if kind_of(j).pushes(j) else {}
        if second in on_links:
            fx, fy = (float(v) for v in on_links[second][0][:2])
            if kind_of(j).other_flank(j, mech, kin.positions, (fx, fy)):
                out.append(j.name)
    return out


#: A pair's force component below this times the largest pair force of the instant is rounding:
#: zero (a guide that takes only a couple has a normal force of 6e-15 N, not an offset of 2e14 m).
ROUNDING = 1e-12


def _force_notes(mech: Mechanism, kin: Any, pairs: tuple[PairForce, ...]) -> tuple[str, ...]:
    """What each pair's kind says of its solved force (:meth:`~mech.pairs.base.PairKind.force_note`)."""
    joints = {j.name: j for j in mech.joints}
    said = (kind_of(joints[p.joint]).force_note(joints[p.joint], mech, kin.positions, p) for p in pairs)
    return tuple(n for n in said if n)


def _pair_forces(mech: Mechanism, kin: Any, sys_: Any, solved: Solved) -> tuple[PairForce, ...]:
    """Each joint's force, as its kind reads it from what its rows put on its links."""
    out: list[PairForce] = []
    reacted = {j.name: reactions(solved, sys_, j.name, j.links) for j in mech.joints}
    largest = max(
        (float(np.hypot(*w[0][:2])) for on_links in reacted.values() for w in on_links.values()), default=0.0
    )
    for j in mech.joints:
        on_links = reacted[j.name]
        if not on_links:
            continue
        geom = kin.joints.get(j.name)
        at = geom.at if geom is not None else None
        direction = geom.direction if geom is not None else None
        wrenches = {}
        for link, w in on_links.items():
            fx, fy, m = (float(v) for v in w[0])
            fx, fy = (0.0 if abs(f) <= ROUNDING * largest else f for f in (fx, fy))
            if at is not None:  # the moment about the pair's point
                ox, oy = kin.links[link].origin
                m -= (at[0] - ox) * fy - (at[1] - oy) * fx
                m = 0.0 if abs(m) <= ROUNDING * largest * (kin.size or 1.0) else m + 0.0  # never −0
            wrenches[link] = (fx, fy, m)
        out.extend(kind_of(j).forces(j, wrenches, at, direction))
    return tuple(out)


def _effort(mech: Mechanism, kin: Any, solved: Solved) -> Effort | None:
    """The input torque (or force) and its parts from the power balance, T ω_in + Q·q̇ = 0."""
    if not kin.drives:
        return None
    d = kin.drives[0]
    loads, inertia, gravity = (float(v) for v in solved.effort[0])
    if not np.isfinite(loads):  # the drive does not move: no rate to divide the power by
        return None
    kind, driver = ("torque", d.link) if d.link is not None else ("force", str(d.joint))
    return Effort(kind, driver, loads + inertia + gravity, loads, inertia, gravity)


def _records(mech: Mechanism, solved: Solved) -> tuple[Inertia, ...]:
    """Each massive link's inertia load, weight and the accelerations they come from."""
    out = []
    for c, ms in enumerate(mech.masses):
        out.append(
            Inertia(
                ms.link,
                ms.mass,
                _vec(solved.centres[0, c]),
                _vec(solved.accel[0, c]),
                float(solved.alpha[0, c]),
                _vec(solved.force[0, c]),
                float(solved.couple[0, c]),
                _vec(solved.weight[c]),
            )
        )
    return tuple(out)


def _vec(a: np.ndarray) -> Vec:
    return (float(a[0]), float(a[1]))


def drive_pivot(mech: Mechanism, kin: Any) -> Vec:
    """The drive's pivot (the shaking moment is taken about it), else the ground's first located point."""
    for d in kin.drives:
        if d.about is not None and d.about in kin.positions:
            return tuple(kin.positions[d.about])  # type: ignore[return-value]
        if d.link is not None:
            for j in mech.joints_of(d.link):
                if mech.ground in j.links and j.name in kin.positions:
                    return tuple(kin.positions[j.name])  # type: ignore[return-value]
    return tuple(kin.links[mech.ground].origin)  # type: ignore[return-value]
