"""Forces at many drive angles at once: one kinematic sweep, one batched force solve.

:class:`Evaluator` is the function θ ↦ (input effort, its parts, every pair's
force, the shaking force and moment) over an array of drive angles.  The
kinematics come from :func:`mech.kinematics.sweep` (closed-form dyads where the
chain decomposes, else Newton continuation along the angles in the order
given); their poses, rates and accelerations are stacked into one
:class:`~mech.forces.core.Motion` and solved by :func:`mech.forces.core.solve`:
the Jacobian of every angle in one call, one batched decomposition.  The cycle
analysis (:mod:`mech.forces.cycle`) calls it on its grid, on the
Gauss–Legendre nodes between the grid's angles and on the refinements' few
angles.

A pair that carries its force by rows of its own at an instant (a gear on fixed
centres, :meth:`mech.pairs.base.PairKind.reaction_rows`), or a mechanism whose
links the sweep does not place from located points, is solved angle by angle
instead, through :func:`mech.forces.analyse` (the same solve on a stack of one).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import partial
from typing import Any

import numpy as np

from mech._records import dataclass
from mech.errors import MechError
from mech.forces.core import Motion, push_rows, reactions, solve
from mech.forces.instant import drive_options
from mech.model import Mechanism
from mech.options import SolveOptions
from mech.pairs import kind_of

__all__ = ["Evaluator", "ForceSeries", "PairKey", "pair_keys"]

#: Most Jacobian entries one batched solve holds (16 MB of them): a longer sweep is solved in chunks.
CHUNK = 2_000_000

#: A pair force over a sweep: (joint, the link it acts on, the link it comes from).
PairKey = tuple[str, str, str]


@dataclass(frozen=True)
class ForceSeries:
    """Forces at K drive angles (arrays with K first; NaN where the mechanism was not solved).

    ``effort`` (K,) is the input torque (N·m, ccw +) or force (N), ``parts`` (K, 3)
    its loads, inertia and gravity parts; ``pairs`` names the pair forces whose
    components ``forces`` (K, P, 2) holds, each on its second link from its first
    (DESIGN § 1.4: ``force.<joint>``); ``shaking`` (K, 2) and ``moment`` (K,) are
    what the moving links' inertia puts on the frame.  ``solved`` is False where
    the kinematics failed (a gap, a toggle); ``determinate`` False where the
    rows are redundant (the pairs' forces are then NaN, the effort is not).
    """

    angles: np.ndarray
    effort: np.ndarray
    parts: np.ndarray
    pairs: tuple[PairKey, ...]
    forces: np.ndarray
    shaking: np.ndarray
    moment: np.ndarray
    solved: np.ndarray
    determinate: np.ndarray

    def magnitude(self, index: int) -> np.ndarray:
        """(K,) |F| of pair ``index``."""
        return np.hypot(self.forces[:, index, 0], self.forces[:, index, 1])


class Evaluator:
    """θ ↦ the forces at every angle of an array (see the module's docstring).

    Built once per mechanism and options: the compiled system, the pairs whose
    forces are reported, and whether the batched path applies.
    """

    def __init__(self, mech: Mechanism, options: SolveOptions | None = None) -> None:
        from mech.kinematics.solve import compiled

        self.mech = mech
        self.options, self.static = drive_options(mech, (options or SolveOptions()).with_(angle=None))
        self.level = "acceleration" if mech.masses and not self.static else "velocity"
        self.sys = compiled(mech, None).system
        self.pairs = pair_keys(mech, set(self.sys.row_names))
        d = mech.drives[0]
        self.lead = d.link or d.joint
        self.several = len(mech.drives) != 1 or d.link is None
        self.batched = self._batched()
        #: True once the kinematics are swept by Newton continuation (analysed, to pass change points).
        self.newton = False
        #: The drive's speed (rad/s, ccw +, or a slider's m/s) as the last call solved it.
        self.speed: float | None = None

    def _batched(self) -> bool:
        """True when every link's pose can be read off the sweep and no pair has rows of its own."""
        if any(kind_of(j).pushes(j) == "instant" for j in self.mech.joints):
            return False
        return all(self.sys.frames.get(link) for link in self.sys.links)

    def __call__(self, angles: Sequence[float] | np.ndarray) -> ForceSeries:
        """The forces at ``angles`` (rad, the drive's angle; swept in the order given)."""
        angles = np.asarray(angles, float)
        if not angles.size:
            out = _empty(angles, self.pairs)
        else:
            out = self._batch(angles) if self.batched else self._one_by_one(angles)
        for a in (out.effort, out.parts, out.forces, out.shaking, out.moment, out.solved, out.determinate):
            a.flags.writeable = False
        return out

    # -- the batched path ---------------------------------------------------------------------
    def _batch(self, angles: np.ndarray) -> ForceSeries:
        sw = self._sweep(angles, analyse=self.newton)
        if not self.newton and sw.method == "newton":
            # continuation passes a change point only when the sweep analyses its steps
            self.newton = True
            sw = self._sweep(angles, analyse=True)
        self.speed = _lead_speed(self.mech, sw)
        motion, ok = _motion(self.mech, self.sys, sw, static=self.level != "acceleration")
        out = _empty(angles, self.pairs)
        steps = np.flatnonzero(ok)
        chunk = max(1, CHUNK // max(1, self.sys.m * 3 * (self.sys.n + 1)))
        for first in range(0, steps.size, chunk):  # bounded memory: the Jacobians of a chunk at a time
            take = np.zeros(ok.size, bool)
            take[steps[first : first + chunk]] = True
            part = Motion(
                motion.pose[take],
                motion.rates[take],
                None if motion.accels is None else motion.accels[take],
                motion.angle[take],
                motion.rate[take],
                {k: v[take] for k, v in motion.named.items()},
            )
            solved = solve(
                self.mech,
                self.sys,
                part,
                about=_pivot(self.mech, self.sys, part),
                rows=partial(push_rows, self.mech, self.sys, part),
            )
            _fill(out, take, solved, self.sys, self.pairs)
        return out

    def _sweep(self, angles: np.ndarray, *, analyse: bool) -> Any:
        from mech.kinematics import sweep

        drive = self.lead if self.several else None
        return sweep(self.mech, angles, level=self.level, options=self.options, analyse=analyse, drive=drive)

    # -- angle by angle -----------------------------------------------------------------------
    def _one_by_one(self, angles: np.ndarray) -> ForceSeries:
        from mech.forces.instant import analyse

        out = _empty(angles, self.pairs)
        where = {key: i for i, key in enumerate(self.pairs)}
        flanks: dict[str, float] = {}  # the gear flanks in contact at the last step: tried first at the next
        for k, theta in enumerate(angles):
            try:
                fa = analyse(self.mech, self.options.with_(angle=float(theta)), flanks=flanks)
            except MechError:
                continue
            out.solved[k] = True
            out.determinate[k] = fa.determinate
            drive = fa.kinematics.drives[0]
            self.speed = drive.omega if drive.link is not None else drive.speed
            if fa.effort is not None:
                e = fa.effort
                out.effort[k] = e.value
                out.parts[k] = (e.loads, e.inertia, e.gravity)
            for p in fa.pairs:
                i = where.get((p.joint, p.on, p.by))
                if i is not None:
                    out.forces[k, i] = p.force
            out.shaking[k] = fa.shaking_force
            out.moment[k] = fa.shaking_moment
        return out


def _empty(angles: np.ndarray, pairs: tuple[PairKey, ...]) -> ForceSeries:
    k = angles.shape[0]

    def nan(*shape: int) -> np.ndarray:
        return np.full((k, *shape), math.nan)

    return ForceSeries(
        angles,
        nan(),
        nan(3),
        pairs,
        nan(len(pairs), 2),
        nan(2),
        nan(),
        np.zeros(k, bool),
        np.zeros(k, bool),
    )


def _motion(mech: Mechanism, sys_: Any, sw: Any, *, static: bool) -> tuple[Motion, np.ndarray]:
    """The sweep's steps as a :class:`Motion`, and which of them are finite (solved)."""
    k, n = sw.angles.shape[0], sys_.n
    point = {name: i for i, name in enumerate(sw.points)}
    column = {name: i for i, name in enumerate(sw.links)}
    pose, rates, accels = np.zeros((k, n, 3)), np.zeros((k, n, 3)), np.zeros((k, n, 3))
    for link, i in sys_.link_index.items():
        p = point[sys_.frames[link]]
        pose[:, i, :2] = sw.positions[:, p]
        pose[:, i, 2] = sw.link_angles[:, column[link]]
        rates[:, i, :2] = sw.velocities[:, p]
        rates[:, i, 2] = sw.omegas[:, column[link]]
        if not static:
            accels[:, i, :2] = sw.accelerations[:, p]
            accels[:, i, 2] = sw.alphas[:, column[link]]
    rate = _rate(mech, sw, column)
    named = {name: sw.positions[:, i] for name, i in point.items()}
    ok = sw.assembled & np.isfinite(pose).all(axis=(1, 2)) & np.isfinite(rates).all(axis=(1, 2))
    ok &= np.isfinite(rate)
    if not static:
        ok &= np.isfinite(accels).all(axis=(1, 2))
    return Motion(pose, rates, None if static else accels, np.asarray(sw.angles), rate, named), ok


def _lead_speed(mech: Mechanism, sw: Any) -> float | None:
    """The drive's speed in a sweep: a crank's ω (ccw +), or a slider drive's speed along its path."""
    if sw.drives:
        return sw.drives[0].rate  # type: ignore[no-any-return]
    return None if sw.omega is None else float(sw.omega)


def _rate(mech: Mechanism, sw: Any, column: dict[str, int]) -> np.ndarray:
    """(K,) the drive's rate: ω of the driven link relative to what it turns on, or the slider's speed."""
    d = mech.drives[0]
    if d.link is not None:
        w = np.asarray(sw.omegas[:, column[d.link]], float)
        if d.relative_to is not None and d.relative_to in column:
            w = w - sw.omegas[:, column[d.relative_to]]
        return w
    return np.asarray(sw.sliding[:, sw.slides.index(d.joint)], float)


def pair_keys(mech: Mechanism, rows: set[str]) -> tuple[PairKey, ...]:
    """The pair forces a sweep reports, named as each pair kind's forces hook names them
    (:meth:`mech.pairs.base.PairKind.forces`, asked once with a unit force on each of the
    pair's links), so that the sweep and the instant letter the same forces whatever the
    kind; joints without constraint rows of their own carry none."""
    keys: list[PairKey] = []
    for j in mech.joints:
        if j.name in rows:
            probe = {link: (1.0, 0.0, 0.0) for link in j.links}
            keys.extend((f.joint, f.on, f.by) for f in kind_of(j).forces(j, probe, None, None))
    return tuple(keys)


def _pivot(mech: Mechanism, sys_: Any, motion: Motion) -> np.ndarray:
    """(K, 2) the drive's pivot, which the shaking moment is taken about (as at an instant)."""
    from mech.forces.core import locate

    d = mech.drives[0]
    names = [d.about] if d.about is not None else []
    if d.link is not None:
        names += [j.name for j in mech.joints_of(d.link) if mech.ground in j.links]
    for name in names:
        if name is not None and (name in motion.named or name in sys_.local):
            return locate(mech, sys_, motion, name)
    return np.broadcast_to(np.asarray(sys_.centre, float), (motion.size, 2)).copy()


def _fill(out: ForceSeries, ok: np.ndarray, solved: Any, sys_: Any, pairs: tuple[PairKey, ...]) -> None:
    """The solved steps' numbers into ``out`` (the steps ``ok``)."""
    out.solved[ok] = True
    det = solved.determinate
    out.determinate[ok] = det
    out.parts[ok] = solved.effort
    out.effort[ok] = solved.effort.sum(axis=1)
    out.shaking[ok] = solved.shaking
    out.moment[ok] = solved.moment
    joints = dict.fromkeys(key[0] for key in pairs)
    for joint in joints:
        links = [key[1] for key in pairs if key[0] == joint]
        on = reactions(solved, sys_, joint, links)
        for i, key in enumerate(pairs):
            if key[0] == joint and key[1] in on:
                f = np.where(det[:, None], on[key[1]][:, :2], math.nan)
                rows = np.flatnonzero(ok)
                out.forces[rows, i] = f
