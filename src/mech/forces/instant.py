"""The forces at one instant, from the constraint Jacobian: Φ_qᵀ λ = Q − M q̈, one linear solve.

Reference-point coordinates (:mod:`mech.kinematics.constraints`): link i has
q_i = (x, y, θ), the position of its frame's origin R_i and its angle.  A force F
at a point P of link i is the generalised force [F, (P − R_i) × F]; a couple T is
[0, 0, T].  d'Alembert's principle puts each massive link's inertia in as loads:
−m a_G at its centre G and the couple −I_G α (the accelerations are the
kinematics' own), and gravity as m g at G.  With Q the sum of them all,

    Φ_qᵀ λ = Q          (Haug, *Computer-Aided Kinematics and Dynamics*, § 6.3)

and the pairs' reactions on the links are −Φ_qᵀ λ, row by row: the rows of a
joint give the force it carries, which its kind interprets
(:meth:`mech.pairs.base.PairKind.forces`: a pin's force, a slider's normal force
and where it acts, a tooth load along the line of action).  The drive's row gives
the input torque (or force).  The Jacobian is the solver's, scaled by the
mechanism's size; its columns are taken back to SI here, so λ and every force
are in newtons whatever the rows' own scaling.

Where the rows are redundant (a double parallelogram: more rows than their
rank) statics cannot split the load between them: the pairs' forces are not
given, and the input effort comes from the power balance instead, which needs
no split: T ω + Q·q̇ = 0, the constraints doing no work.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from mech.forces.result import Effort, ForceAnalysis, Inertia, PairForce
from mech.model import Mechanism
from mech.pairs import kind_of

__all__ = ["at_instant"]

Vec = tuple[float, float]


def at_instant(mech: Mechanism, kin: Any, comp: Any, *, static: bool = False) -> ForceAnalysis:
    """The force analysis of ``mech`` at the instant ``kin`` was solved for (acceleration level,
    or velocity level when ``static``: no inertia, the rates only for the power balance).

    ``comp`` is the compiled mechanism (:func:`mech.kinematics.solve.compiled`).
    """
    sys_ = comp.system
    n = sys_.n
    loads = _loads(mech, kin, sys_, n)
    inertia, weights, links_inertia = _inertia(mech, kin, sys_, n, static)
    total = loads + inertia + weights
    jac = _jacobian_si(mech, kin, sys_)
    moving = jac[:, : 3 * n]
    lam, rank = _multipliers(moving, total[: 3 * n])
    determinate = rank == jac.shape[0]
    pairs: tuple[PairForce, ...] = ()
    note = ""
    if determinate:
        pairs = _pair_forces(mech, kin, sys_, jac, lam)
    else:
        note = (
            f"the pairs' forces are indeterminate: {jac.shape[0]} constraint rows have rank {rank} "
            "(a redundant constraint: statics cannot split the load); the input effort is from the power balance"
        )
    effort = _effort(mech, kin, sys_, n, (loads, inertia, weights))
    about = _drive_pivot(mech, kin)
    shake, moment = _shaking(links_inertia, about)
    angle = kin.drives[0].angle if kin.drives else None
    return ForceAnalysis(
        mechanism=mech.label,
        drive_angle=angle,
        pairs=pairs,
        effort=effort,
        inertia=tuple(links_inertia),
        shaking_force=shake,
        shaking_moment=moment,
        about=about,
        determinate=determinate,
        note=note,
    )


def _q(kin: Any, sys_: Any) -> np.ndarray:
    """The solved configuration in the system's scaled coordinates, read back from the links."""
    q = np.zeros(3 * sys_.n)
    cx, cy = float(sys_.centre[0]), float(sys_.centre[1])
    for name, i in sys_.link_index.items():
        st = kin.links[name]
        q[3 * i : 3 * i + 3] = ((st.origin[0] - cx) / sys_.scale, (st.origin[1] - cy) / sys_.scale, st.angle)
    return q


def _jacobian_si(mech: Mechanism, kin: Any, sys_: Any) -> np.ndarray:
    """Φ_q at the instant with the ground's columns, its x and y columns per metre (SI), the rows
    of a pair that carries its force otherwise (a gear on fixed centres) replaced by its kind's."""
    jac = sys_.jacobian(_q(kin, sys_), ground=True)
    cols = np.tile([1.0 / sys_.scale, 1.0 / sys_.scale, 1.0], sys_.n + 1)
    jac = jac * cols
    names = np.array(sys_.row_names)
    for j in mech.joints:
        rows = kind_of(j).reaction_rows(j, _View(mech, kin, sys_))
        if rows is None:
            continue
        idx = np.flatnonzero(names == j.name)
        jac[idx[: len(rows)]] = rows
    return jac


class _View:
    """What a kind's :meth:`~mech.pairs.base.PairKind.reaction_rows` reads: the solved instant in SI."""

    def __init__(self, mech: Mechanism, kin: Any, sys_: Any) -> None:
        self.mech, self.kin, self.sys = mech, kin, sys_

    def column(self, link: str) -> int:
        """The first of the link's three columns (ground's are last)."""
        return 3 * self.sys.link_index.get(link, self.sys.n)

    @property
    def width(self) -> int:
        return 3 * (self.sys.n + 1)

    def origin(self, link: str) -> Vec:
        return tuple(self.kin.links[link].origin)  # type: ignore[return-value]


def _wrench(q: np.ndarray, col: int, force: Vec, moment: float) -> None:
    q[col] += force[0]
    q[col + 1] += force[1]
    q[col + 2] += moment


def _apply(q: np.ndarray, sys_: Any, kin: Any, link: str, force: Vec, at: Vec) -> None:
    """A force ``force`` at ``at`` on ``link`` as a generalised force on its q block (ground: none)."""
    i = sys_.link_index.get(link)
    if i is None:
        return
    ox, oy = kin.links[link].origin
    _wrench(q, 3 * i, force, (at[0] - ox) * force[1] - (at[1] - oy) * force[0])


def _drive_value(load: Any, kin: Any) -> Any:
    """A load's value now: constant, or read linearly off its table at the drive's angle (periodic)."""
    if load.table is None:
        return load.force if load.force is not None else load.torque
    table = np.array(load.table)
    theta = float(kin.drives[0].angle)
    start, span = table[0, 0], table[-1, 0] - table[0, 0]
    t = start + math.fmod(theta - start, span) % span if span > 0 else theta
    vals = [float(np.interp(t, table[:, 0], table[:, k])) for k in range(1, table.shape[1])]
    return tuple(vals) if len(vals) == 2 else vals[0]


def _loads(mech: Mechanism, kin: Any, sys_: Any, n: int) -> np.ndarray:
    """The file's loads as generalised forces (3n + 3, SI)."""
    q = np.zeros(3 * (n + 1))
    for load in mech.loads:
        value = _drive_value(load, kin)
        if load.is_force:
            link = load.on or next(lk for lk in kin.carriers.get(load.target, ()) if lk != mech.ground)
            _apply(q, sys_, kin, link, value, kin.positions[load.target])
        else:
            i = sys_.link_index.get(load.target)
            if i is not None:
                q[3 * i + 2] += value
    return q


def _inertia(
    mech: Mechanism, kin: Any, sys_: Any, n: int, static: bool
) -> tuple[np.ndarray, np.ndarray, list[Inertia]]:
    """d'Alembert's inertia loads and the weights, as generalised forces, and each link's record."""
    inertia = np.zeros(3 * (n + 1))
    weights = np.zeros(3 * (n + 1))
    records = []
    g = mech.gravity or (0.0, 0.0)
    for ms in mech.masses:
        at = kin.positions[ms.centre]
        if static:
            a, alpha = (0.0, 0.0), 0.0
        else:
            a = kin.acceleration(ms.centre, ms.link)
            alpha = kin.links[ms.link].alpha or 0.0
        force = (-ms.mass * a[0], -ms.mass * a[1])
        weight = (ms.mass * g[0], ms.mass * g[1])
        _apply(inertia, sys_, kin, ms.link, force, at)
        inertia[3 * sys_.link_index[ms.link] + 2] += -ms.inertia * alpha
        _apply(weights, sys_, kin, ms.link, weight, at)
        records.append(Inertia(ms.link, ms.mass, at, a, alpha, force, -ms.inertia * alpha, weight))
    return inertia, weights, records


def _multipliers(moving: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, int]:
    """λ of Φ_qᵀ λ = Q (least squares where the rows are redundant) and the rows' rank."""
    u, s, vt = np.linalg.svd(moving.T, full_matrices=False)
    tol = max(moving.shape) * np.finfo(float).eps * (s[0] if s.size else 0.0)
    rank = int(np.sum(s > tol))
    inv = np.where(s > tol, 1.0 / np.where(s > tol, s, 1.0), 0.0)
    lam = vt.T @ (inv * (u.T @ q))
    return lam, rank


def _pair_forces(
    mech: Mechanism, kin: Any, sys_: Any, jac: np.ndarray, lam: np.ndarray
) -> tuple[PairForce, ...]:
    """Each joint's force, as its kind reads it from what its rows put on its links."""
    names = list(sys_.row_names)
    out: list[PairForce] = []
    for j in mech.joints:
        rows = [r for r, name in enumerate(names) if name == j.name]
        if not rows:
            continue
        reaction = -(jac[rows].T @ lam[rows])  # on every link, about each link's origin
        geom = kin.joints.get(j.name)
        at = geom.at if geom is not None else None
        direction = geom.direction if geom is not None else None
        wrenches = {}
        for link in j.links:
            col = 3 * sys_.link_index.get(link, sys_.n)
            fx, fy, m = (float(v) for v in reaction[col : col + 3])
            if at is not None:  # the moment about the pair's point
                ox, oy = kin.links[link].origin
                m -= (at[0] - ox) * fy - (at[1] - oy) * fx
            wrenches[link] = (fx, fy, m)
        out.extend(kind_of(j).forces(j, wrenches, at, direction))
    return tuple(out)


def _rates(kin: Any, sys_: Any, n: int) -> np.ndarray:
    """q̇ in SI (3n + 3; the ground's zero)."""
    qd = np.zeros(3 * (n + 1))
    for name, i in sys_.link_index.items():
        st = kin.links[name]
        qd[3 * i : 3 * i + 3] = (st.velocity[0], st.velocity[1], st.omega)
    return qd


def _effort(mech: Mechanism, kin: Any, sys_: Any, n: int, parts: tuple[np.ndarray, ...]) -> Effort | None:
    """The input torque (or force) and its parts from the power balance, T ω_in + Q·q̇ = 0."""
    if not kin.drives:
        return None
    d = kin.drives[0]
    qd = _rates(kin, sys_, n)
    if d.link is not None:
        rate = (kin.links[d.link].omega or 0.0) - (
            kin.links[d.relative_to].omega or 0.0 if d.relative_to else 0.0
        )
        kind, driver = "torque", d.link
    else:
        rate, kind, driver = float(kin.sliding(d.joint)), "force", str(d.joint)
    if rate == 0.0:
        return None
    loads, inertia, gravity = (-float(p @ qd) / rate for p in parts)
    return Effort(kind, driver, loads + inertia + gravity, loads, inertia, gravity)


def _drive_pivot(mech: Mechanism, kin: Any) -> Vec:
    """The drive's pivot (the shaking moment is taken about it), else the ground's first located point."""
    for d in kin.drives:
        if d.about is not None and d.about in kin.positions:
            return tuple(kin.positions[d.about])  # type: ignore[return-value]
        if d.link is not None:
            for j in mech.joints_of(d.link):
                if mech.ground in j.links and j.name in kin.positions:
                    return tuple(kin.positions[j.name])  # type: ignore[return-value]
    return tuple(kin.links[mech.ground].origin)  # type: ignore[return-value]


def _shaking(records: list[Inertia], about: Vec) -> tuple[Vec, float]:
    """The shaking force −Σ m a_G and moment −Σ (r_G × m a_G + I_G α) about ``about`` (DESIGN § 1.4)."""
    fx = sum(r.force[0] for r in records)
    fy = sum(r.force[1] for r in records)
    m = 0.0
    for r in records:
        rx, ry = r.centre[0] - about[0], r.centre[1] - about[1]
        m += rx * r.force[1] - ry * r.force[0] + r.couple
    return (fx, fy), m
