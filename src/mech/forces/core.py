"""The force solve, written once with a batch axis: K configurations of one mechanism at a time.

Reference-point coordinates (:mod:`mech.kinematics.constraints`): link i has
q_i = (x, y, θ), the position of its frame's origin R_i and its angle.  A force F
at a point P of link i is the generalised force [F, (P − R_i) × F]; a couple T is
[0, 0, T].  d'Alembert's principle puts each massive link's inertia in as loads:
−m a_G at its centre G and the couple −I_G α (the accelerations are the
kinematics' own), and gravity as m g at G.  With Q the sum of them all,

    Φ_qᵀ λ = Q          (Haug, *Computer-Aided Kinematics and Dynamics*, § 6.3)

and the pairs' reactions on the links are −Φ_qᵀ λ, row by row: the rows of a
joint give the force it carries.  The Jacobian is the constraint system's
(:meth:`mech.kinematics.constraints.System.jacobian`, which takes a stack of
configurations), scaled by the mechanism's size; its columns are taken back to
SI here, so λ and every force are in newtons whatever the rows' own scaling.

The input effort comes from the power balance, which needs no split of the
load between redundant rows: T ω_in + Q·q̇ = 0, the constraints doing no work.

One instant (:func:`mech.forces.instant.at_instant`) is a stack of one; a sweep
over the cycle (:mod:`mech.forces.cycle`) stacks every step, so that the whole
cycle is one batched Jacobian and one batched decomposition, not a solve per step.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np

from mech._records import dataclass
from mech.model import Load, Mechanism
from mech.pairs import kind_of, load_link, point_link
from mech.pairs.base import push_row

__all__ = [
    "Motion",
    "Solved",
    "jacobian_si",
    "load_value",
    "locate",
    "multipliers",
    "push_rows",
    "reactions",
    "solve",
    "unsaid_notes",
    "unsaid_on",
    "unsaid_text",
]


@dataclass(frozen=True)
class Motion:
    """K configurations of one mechanism, SI: what the force solve reads.

    ``pose`` (K, n, 3) is each moving link's origin (m) and angle (rad), in the
    constraint system's link order; ``rates`` (K, n, 3) its origin's velocity and
    ω; ``accels`` (K, n, 3) its origin's acceleration and α, or None for a static
    problem (no inertia).  ``angle`` (K,) is the drive's angle (rad), which load
    tables are read at; ``rate`` (K,) the drive's rate (ω of a crank relative to
    what it turns on, or a slider drive's speed), which the power balance divides
    by.  ``named`` holds the positions (K, 2) of located names where they are known
    otherwise (a solve's own); any other name is placed from its link's pose.
    """

    pose: np.ndarray
    rates: np.ndarray
    accels: np.ndarray | None
    angle: np.ndarray
    rate: np.ndarray
    named: Mapping[str, np.ndarray]

    @property
    def size(self) -> int:
        return int(self.pose.shape[0])


@dataclass(frozen=True)
class Solved:
    """The force solve of a stack of K configurations (arrays with K first).

    ``parts`` are the generalised forces (K, 3n + 3; the ground's last) of the
    loads, the inertia and the weights; ``jac`` the Jacobian in SI (K, m, 3n + 3);
    ``lam`` the multipliers (K, m); ``rank`` the rank of the moving columns (K,);
    ``effort`` the input effort's parts, loads, inertia, gravity (K, 3), NaN where
    the drive does not move; ``centres``, ``accel``, ``force``, ``couple`` and
    ``weight`` each massive link's centre (K, M, 2), a_G, its link's α (K, M), −m a_G, −I_G α (K, M) and
    m g (M, 2), in the order of ``mech.masses``; ``shaking`` (K, 2) and ``moment``
    (K,) what the moving links' inertia puts on the frame, about ``about`` (K, 2).
    """

    parts: tuple[np.ndarray, np.ndarray, np.ndarray]
    jac: np.ndarray
    lam: np.ndarray
    rank: np.ndarray
    effort: np.ndarray
    centres: np.ndarray
    accel: np.ndarray
    alpha: np.ndarray
    force: np.ndarray
    couple: np.ndarray
    weight: np.ndarray
    shaking: np.ndarray
    moment: np.ndarray
    about: np.ndarray

    @property
    def determinate(self) -> np.ndarray:
        """(K,) True where the rows are independent: statics splits the load between the pairs."""
        return np.asarray(self.rank == self.jac.shape[1])


class _Stack:
    """Positions and generalised forces over one stack (the solve's working context)."""

    def __init__(self, mech: Mechanism, sys_: Any, motion: Motion) -> None:
        self.mech, self.sys, self.motion = mech, sys_, motion
        self.n = sys_.n
        self.width = 3 * (sys_.n + 1)
        self.k = motion.size

    def zeros(self) -> np.ndarray:
        return np.zeros((self.k, self.width))

    def index(self, link: str) -> int | None:
        return self.sys.link_index.get(link)

    def where(self, name: str) -> np.ndarray:
        """(K, 2) the position of a located name (m)."""
        known = self.motion.named.get(name)
        if known is not None:
            return known
        i, s = self.sys.local[name]
        if i == self.n:  # fixed in the ground: scaled global coordinates
            return np.broadcast_to(self.sys.centre + self.sys.scale * s, (self.k, 2))
        pose = self.motion.pose[:, i]
        c, sn = np.cos(pose[:, 2]), np.sin(pose[:, 2])
        sx, sy = self.sys.scale * s[0], self.sys.scale * s[1]
        return np.stack((pose[:, 0] + c * sx - sn * sy, pose[:, 1] + sn * sx + c * sy), axis=1)

    def apply(self, q: np.ndarray, link: str, force: np.ndarray, at: np.ndarray) -> None:
        """A force (K, 2) at ``at`` (K, 2) on ``link`` as a generalised force on its q block."""
        i = self.index(link)
        if i is None:
            return
        origin = self.motion.pose[:, i, :2]
        q[:, 3 * i] += force[:, 0]
        q[:, 3 * i + 1] += force[:, 1]
        q[:, 3 * i + 2] += (at[:, 0] - origin[:, 0]) * force[:, 1] - (at[:, 1] - origin[:, 1]) * force[:, 0]

    def acceleration(self, link: str, at: np.ndarray) -> np.ndarray:
        """(K, 2) the acceleration of the point of ``link`` at ``at``: a_O + α × r − ω² r."""
        i = self.sys.link_index[link]
        assert self.motion.accels is not None
        pose, rate, acc = self.motion.pose[:, i], self.motion.rates[:, i], self.motion.accels[:, i]
        rx, ry = at[:, 0] - pose[:, 0], at[:, 1] - pose[:, 1]
        w2 = rate[:, 2] * rate[:, 2]
        return np.stack((acc[:, 0] - acc[:, 2] * ry - w2 * rx, acc[:, 1] + acc[:, 2] * rx - w2 * ry), axis=1)


def locate(mech: Mechanism, sys_: Any, motion: Motion, name: str) -> np.ndarray:
    """(K, 2) the position of a located name over the stack (m)."""
    return np.array(_Stack(mech, sys_, motion).where(name))


def load_value(load: Load, angle: np.ndarray) -> np.ndarray:
    """A load's value at the drive's angles (K,): (K, 2) for a force, (K,) for a torque
    (:meth:`mech.model.Load.values`: a table read linearly, repeated with its span)."""
    return load.values(angle)  # type: ignore[no-any-return]


def _loads(st: _Stack) -> np.ndarray:
    """The file's loads as generalised forces (K, 3n + 3)."""
    q = st.zeros()
    for load in st.mech.loads:
        value = load_value(load, st.motion.angle)
        if load.is_force:
            st.apply(q, load_link(st.mech, load), value, st.where(load.target))
        else:
            i = st.index(load.target)
            if i is not None:
                q[:, 3 * i + 2] += value
    return q


def unsaid_on(mech: Mechanism) -> dict[str, tuple[str, ...]]:
    """Forces at a pin of two or more moving links that do not say which they act on: pin → its
    moving links (:func:`mech.pairs.load_link` says which takes the load).

    DESIGN § 1.4: such a load says which link it acts on (``on: piston``).  Where it does not,
    the power balance (the input effort) is the same whichever link takes it, and so is every
    other pair's force, but the force the pin itself carries is not (:func:`unsaid_text`).
    """
    out: dict[str, tuple[str, ...]] = {}
    for load in mech.loads:
        joint = next((j for j in mech.joints if j.name == load.target), None)
        if joint is None or not load.is_force or load.on is not None:
            continue
        kind = kind_of(joint)
        if kind.role == "contact" and not kind.rolls:
            continue  # a cam's or a contact's name is its follower's own point: no choice to make
        # a pin, or a pitch point (gears, rolling): a point of each link it joins, alike
        moving = tuple(lk for lk in joint.links if lk != mech.ground)
        if len(moving) > 1:
            out[load.target] = moving
    return out


def unsaid_text(pin: str, links: tuple[str, ...]) -> str:
    """Why the force of ``pin`` is not given: its load names none of ``links`` (:func:`unsaid_on`)."""
    return (
        f"{pin} joins {' and '.join(links)}, and the load at {pin} does not say which it acts on "
        f"({' or '.join(f'on: {lk}' for lk in links)}): the force {pin} carries depends on it"
    )


def unsaid_notes(mech: Mechanism) -> tuple[str, ...]:
    """The notes of a force solve (one instant or the cycle) for each load :func:`unsaid_on` finds."""
    return tuple(
        f"{unsaid_text(pin, links)}; it is shown with the load on {point_link(mech, pin)}"
        for pin, links in unsaid_on(mech).items()
    )


def _inertia(st: _Stack) -> tuple[np.ndarray, np.ndarray, tuple[np.ndarray, ...]]:
    """d'Alembert's inertia loads and the weights as generalised forces, and each massive link's
    centre, a_G, α, −m a_G, −I_G α and weight (stacked over ``mech.masses``)."""
    k, count = st.k, len(st.mech.masses)
    inertia, weights = st.zeros(), st.zeros()
    centres, accel, force = np.zeros((k, count, 2)), np.zeros((k, count, 2)), np.zeros((k, count, 2))
    couple, alpha, weight = np.zeros((k, count)), np.zeros((k, count)), np.zeros((count, 2))
    g = st.mech.gravity or (0.0, 0.0)
    for c, ms in enumerate(st.mech.masses):
        at = st.where(ms.centre)
        centres[:, c] = at
        if st.motion.accels is not None:
            accel[:, c] = st.acceleration(ms.link, at)
            alpha[:, c] = st.motion.accels[:, st.sys.link_index[ms.link], 2]
            couple[:, c] = -ms.inertia * alpha[:, c]
        force[:, c] = -ms.mass * accel[:, c]
        weight[c] = (ms.mass * g[0], ms.mass * g[1])
        st.apply(inertia, ms.link, force[:, c], at)
        inertia[:, 3 * st.sys.link_index[ms.link] + 2] += couple[:, c]
        st.apply(weights, ms.link, np.broadcast_to(weight[c], (k, 2)), at)
    return inertia, weights, (centres, accel, alpha, force, couple, weight)


def scaled_q(sys_: Any, motion: Motion) -> np.ndarray:
    """The stack's configurations in the constraint system's coordinates (K, 3n): scaled, from its centre."""
    pose = motion.pose
    q = np.empty((motion.size, 3 * sys_.n))
    q[:, 0::3] = (pose[:, :, 0] - float(sys_.centre[0])) / sys_.scale
    q[:, 1::3] = (pose[:, :, 1] - float(sys_.centre[1])) / sys_.scale
    q[:, 2::3] = pose[:, :, 2]
    return q


def jacobian_si(sys_: Any, motion: Motion) -> np.ndarray:
    """Φ_q of every configuration with the ground's columns, x and y columns per metre (K, m, 3n + 3)."""
    q = scaled_q(sys_, motion)
    jac = np.asarray(sys_.jacobian(q, ground=True)).reshape(motion.size, sys_.m, -1)
    cols = np.tile([1.0 / sys_.scale, 1.0 / sys_.scale, 1.0], sys_.n + 1)
    return jac * cols


def push_rows(
    mech: Mechanism,
    sys_: Any,
    motion: Motion,
    jac: np.ndarray,
    made: dict[tuple[str, int], list[float]] | None = None,
) -> np.ndarray:
    """``jac`` with the row of each pair that pushes along its common normal (a programme cam) made
    that push's (:func:`~mech.pairs.base.push_row`), at every configuration of the stack: where the
    kind's :meth:`~mech.pairs.base.PairKind.push` says it touches and along which normal.  ``made``
    keeps the rows by (joint, step) for another solve of the same stack."""
    made = {} if made is None else made
    pushing = [j for j in mech.joints if kind_of(j).pushes(j) == "stacked"]
    if not pushing:
        return jac
    names, qs = np.array(sys_.row_names), scaled_q(sys_, motion)
    centre, scale = np.asarray(sys_.centre, float), float(sys_.scale)
    ground = (float(centre[0]), float(centre[1]))  # the ground's frame: the system's centre, unturned
    for j in pushing:
        row = int(np.flatnonzero(names == j.name)[0])
        for k in range(motion.size):
            if (j.name, k) not in made:
                touch = kind_of(j).push(j, sys_, qs[k])
                if touch is None:
                    continue
                at, normal = touch
                frames = _Frames(sys_, motion.pose[k], ground)
                made[j.name, k] = push_row(frames, j, tuple(np.asarray(at) * scale + centre), tuple(normal))
            jac[k, row] = made[j.name, k]
    return jac


class _Frames:
    """What :func:`~mech.pairs.base.push_row` reads of one configuration: columns, link origins (SI)."""

    def __init__(self, sys_: Any, pose: np.ndarray, ground: tuple[float, float]) -> None:
        self.sys, self.pose, self.ground = sys_, pose, ground

    @property
    def width(self) -> int:
        return 3 * (self.sys.n + 1)

    def column(self, link: str) -> int:
        return 3 * self.sys.link_index.get(link, self.sys.n)

    def origin(self, link: str) -> tuple[float, float]:
        i = self.sys.link_index.get(link)
        return self.ground if i is None else (float(self.pose[i][0]), float(self.pose[i][1]))


def multipliers(moving: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """λ of Φ_qᵀ λ = Q for each configuration and the rows' rank: ``moving`` (K, m, 3n), ``q``
    (K, 3n) → (K, m), (K,).

    As many rows as coordinates (a mechanism with its drives, solved by its
    kinematics: Φ_q is regular there, or the kinematics would have failed): one
    batched LU solve.  Any other shape (redundant rows: a double parallelogram),
    or a matrix the LU finds singular, by the singular values: λ is then the
    least-squares split and the rank says what statics fixes.
    """
    k, m, c = moving.shape
    if m == c and k:
        try:
            lam = np.linalg.solve(np.swapaxes(moving, 1, 2), q[:, :, None])[:, :, 0]
        except np.linalg.LinAlgError:
            pass
        else:
            rank = np.full(k, m)
            bad = ~np.isfinite(lam).all(axis=1)
            if bad.any():
                lam[bad], rank[bad] = _by_singular_values(moving[bad], q[bad])
            return lam, rank
    return _by_singular_values(moving, q)


def _by_singular_values(moving: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """λ by the pseudo-inverse (least squares where the rows are redundant) and the rows' rank."""
    u, s, vt = np.linalg.svd(np.swapaxes(moving, 1, 2), full_matrices=False)
    tol = max(moving.shape[1:]) * np.finfo(float).eps * (s[:, :1] if s.shape[1] else np.zeros((len(s), 1)))
    keep = s > tol
    rank = np.sum(keep, axis=1)
    inv = np.where(keep, 1.0 / np.where(keep, s, 1.0), 0.0)
    proj = np.einsum("kir,ki->kr", u, q)
    lam = np.einsum("krm,kr->km", vt, inv * proj)
    return lam, rank


def _rates(st: _Stack) -> np.ndarray:
    """q̇ in SI (K, 3n + 3; the ground's zero)."""
    qd = st.zeros()
    qd[:, : 3 * st.n] = st.motion.rates.reshape(st.k, 3 * st.n)
    return qd


def solve(
    mech: Mechanism,
    sys_: Any,
    motion: Motion,
    *,
    about: np.ndarray,
    rows: Callable[[np.ndarray], np.ndarray] | None = None,
) -> Solved:
    """The force solve of ``motion``'s K configurations (see the module's docstring).

    ``about`` (K, 2) is the point the shaking moment is taken about (the drive's
    pivot); ``rows``, given the Jacobian in SI, returns it with the rows of pairs
    that carry their force otherwise (:meth:`mech.pairs.base.PairKind.reaction_rows`).
    """
    st = _Stack(mech, sys_, motion)
    loads = _loads(st)
    inertia, weights, (centres, accel, alpha, force, couple, weight) = _inertia(st)
    jac = jacobian_si(sys_, motion)
    if rows is not None:
        jac = rows(jac)
    total = loads + inertia + weights
    lam, rank = multipliers(jac[:, :, : 3 * st.n], total[:, : 3 * st.n])
    qd = _rates(st)
    with np.errstate(divide="ignore", invalid="ignore"):
        effort = np.stack(
            [
                np.where(motion.rate != 0.0, -np.einsum("kw,kw->k", p, qd) / motion.rate, np.nan)
                for p in (loads, inertia, weights)
            ],
            axis=1,
        )
    shaking = force.sum(axis=1)
    r = centres - about[:, None, :]
    moment = np.sum(r[:, :, 0] * force[:, :, 1] - r[:, :, 1] * force[:, :, 0] + couple, axis=1)
    return Solved(
        (loads, inertia, weights),
        jac,
        lam,
        rank,
        effort,
        centres,
        accel,
        alpha,
        force,
        couple,
        weight,
        shaking,
        moment,
        np.asarray(about),
    )


def reactions(solved: Solved, sys_: Any, joint: str, links: Sequence[str]) -> dict[str, np.ndarray]:
    """What the rows of ``joint`` (or a drive's row, named as the system names it) put on each of
    ``links``: (K, 3), the force (N) and its moment about the link's origin (N·m)."""
    idx = [r for r, name in enumerate(sys_.row_names) if name == joint]
    if not idx:
        return {}
    reaction = -np.einsum("krw,kr->kw", solved.jac[:, idx, :], solved.lam[:, idx])
    out = {}
    for link in links:
        col = 3 * sys_.link_index.get(link, sys_.n)
        out[link] = reaction[:, col : col + 3]
    return out
