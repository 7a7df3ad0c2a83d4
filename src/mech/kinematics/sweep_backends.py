"""The two ways a sweep evaluates a mechanism: the closed form and Newton continuation.

:class:`Closed` evaluates the dyad program (:mod:`.dyads`) at any array of
angles at once.  :class:`Newton` sweeps step by step (or in stacks,
:mod:`.march`) from the drawing, each step started from the last one's
solution moved by its velocity; :class:`Walk` sends one such continuation
from angle to angle for the refinements, so every probe stays on the sweep's
branch.  Both give the same dict of arrays (``positions``, ``link_angles``,
``omegas`` …, ``assembled``, ``condition``, ``disc``, ``miss``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from mech.errors import GeometryError
from mech.kinematics.dyads import SLACK, DyadProgram, branches, numpy_namespace
from mech.kinematics.march import Marcher
from mech.kinematics.quantities import LEVELS
from mech.kinematics.result import Kinematics
from mech.kinematics.solve import Compiled, continuation
from mech.model import Mechanism
from mech.options import SolveOptions

__all__ = ["Closed", "Newton", "Walk", "law_series", "newton_series", "stack_rows"]

_TWO_PI = 2.0 * math.pi


class Closed:
    """Evaluate the dyad program at any array of angles, with everything a sweep derives."""

    method = "closed form"
    vectorised = True  # evaluate() takes any array of angles: refinement on grids

    def __init__(self, comp: Compiled, prog: DyadProgram, omega: float, alpha: float, lvl: int) -> None:
        self.comp, self.prog, self.omega, self.alpha, self.lvl = comp, prog, omega, alpha, lvl
        # where the sweep's branch is the drawn one: the drawn angle, or whole turns from it (set by
        # the sweep); past a change point a dyad's sign flips (mech.kinematics.dyads.branches)
        self.ref = prog.drawn_angle
        sys_ = comp.system
        lay = comp.layout
        self.points = tuple(p for p in prog.points if not p.startswith("#"))
        self._pidx = np.array([prog.points.index(p) for p in self.points], int)
        self.links = prog.links
        self.slides = tuple(ps.joint for ps in lay.paths)
        scale = sys_.scale
        # per slide: guide index (n = ground), local through (m) and u, slider point index
        self._slide = []
        for k, ps in enumerate(lay.paths):
            g, u = sys_.path_dirs[ps.joint]
            self._slide.append((g, sys_.ln_t[k] * scale, np.asarray(u, float), prog.points.index(ps.point)))

    def evaluate(self, phi: np.ndarray) -> dict[str, np.ndarray]:
        """Every array a sweep needs at angles ``phi`` (any shape)."""
        prog, lvl = self.prog, self.lvl
        shape = np.shape(phi)
        phi = np.asarray(phi, float)
        with np.errstate(all="ignore"):  # a dyad that cannot close or a toggle: masked below, never used
            branch = branches(prog, self.ref, phi)
            out = prog.raw(phi, self.omega, self.alpha, level=lvl, xp=numpy_namespace(), branch=branch)
        parts = prog.split(out, lvl)

        def stack(seq: tuple) -> np.ndarray:
            """(…, K) from K outputs, some of them constants (a ground point)."""
            arr = np.empty((*shape, len(seq)))
            for k, v in enumerate(seq):
                arr[..., k] = v
            return arr

        nd = len(prog.dyads)
        res: dict[str, np.ndarray] = {}
        disc = stack(parts["disc"]) if nd else np.ones((*shape, 1))
        sins = np.abs(stack(parts["sin"])) if nd else np.ones((*shape, 1))
        res["disc"] = disc
        res["miss"] = stack(parts["miss"]) if nd else np.zeros((*shape, 1))
        res["assembled"] = np.all(disc >= -SLACK, axis=-1)
        with np.errstate(divide="ignore"):
            res["condition"] = 1.0 / np.min(sins, axis=-1)
        cx, cy = prog.centre
        px = stack(parts["px"]) + cx
        py = stack(parts["py"]) + cy
        res["positions"] = np.stack([px, py], axis=-1)
        lt = stack(parts["lt"])
        lx, ly = stack(parts["lx"]), stack(parts["ly"])
        res["link_angles"] = lt
        res["displacement"] = self._slides(lx, ly, lt, px - cx, py - cy, None)
        if lvl >= 1:
            res["velocities"] = np.stack([stack(parts["pvx"]), stack(parts["pvy"])], axis=-1)
            res["omegas"] = stack(parts["lw"])
            res["sliding"] = self._slides(
                lx,
                ly,
                lt,
                px - cx,
                py - cy,
                (stack(parts["lvx"]), stack(parts["lvy"]), res["omegas"], res["velocities"]),
            )
        if lvl >= 2:
            res["accelerations"] = np.stack([stack(parts["pax"]), stack(parts["pay"])], axis=-1)
            res["alphas"] = stack(parts["lal"])
        return res

    def _slides(
        self, lx: np.ndarray, ly: np.ndarray, lt: np.ndarray, px: np.ndarray, py: np.ndarray, vel: Any
    ) -> np.ndarray:
        """Slider displacement along its path (vel None) or sliding speed relative to the guide."""
        cols = []
        n = len(self.links)
        for g, t_l, u_l, p in self._slide:
            if g == n:
                c, s = np.ones_like(px[..., 0]), np.zeros_like(px[..., 0])
                gx = gy = np.zeros_like(px[..., 0])
            else:
                c, s = np.cos(lt[..., g]), np.sin(lt[..., g])
                gx, gy = lx[..., g], ly[..., g]
            ux, uy = c * u_l[0] - s * u_l[1], s * u_l[0] + c * u_l[1]
            if vel is None:
                tx = gx + c * t_l[0] - s * t_l[1]
                ty = gy + s * t_l[0] + c * t_l[1]
                cols.append((px[..., p] - tx) * ux + (py[..., p] - ty) * uy)
            else:
                lvx, lvy, lw, pv = vel
                if g == n:
                    rel_x, rel_y = pv[..., p, 0], pv[..., p, 1]
                else:
                    rx, ry = px[..., p] - gx, py[..., p] - gy
                    rel_x = pv[..., p, 0] - (lvx[..., g] - lw[..., g] * ry)
                    rel_y = pv[..., p, 1] - (lvy[..., g] + lw[..., g] * rx)
                cols.append(rel_x * ux + rel_y * uy)
        if not cols:
            return np.zeros((*px.shape[:-1], 0))
        return np.stack(cols, axis=-1)


class Newton:
    """Newton continuation, step by step: the fallback for chains that do not decompose."""

    method = "newton"

    def __init__(
        self,
        mech: Mechanism,
        comp: Compiled,
        options: SolveOptions,
        omega: float,
        alpha: float,
        lvl: int,
        lead: int | None = None,
    ) -> None:
        self.mech, self.comp, self.lvl = mech, comp, lvl
        # lead: the drive whose coordinate is the parameter when every drive follows a linear law
        # (a slider drive, several drives; mech.kinematics.march.LinearLaw): the file's speeds hold
        self.lead = lead
        self.options = (
            options.with_(method="newton")
            if lead is not None
            else options.with_(
                omega=abs(omega), direction="ccw" if omega >= 0 else "cw", alpha=alpha, method="newton"
            )
        )
        self.links = comp.system.links
        self.slides = tuple(ps.joint for ps in comp.layout.paths)
        self.points = tuple(p for p in comp.system.loc_names if not p.startswith("#"))
        self.marcher: Marcher | None = None  # set when the series was marched: grids can then be evaluated

    @property
    def vectorised(self) -> bool:
        """True when :meth:`evaluate` can refine on grids (the series was marched)."""
        return self.marcher is not None

    def evaluate(self, phi: np.ndarray) -> dict[str, np.ndarray]:
        """Every array a sweep needs at angles ``phi`` between the marched steps (see Marcher.evaluate)."""
        assert self.marcher is not None
        return self.marcher.evaluate(phi)

    def series(self, phi: np.ndarray) -> list[dict[str, Any] | None]:
        """Warm-started continuation along ``phi`` (see :func:`~mech.kinematics.solve.continuation`)."""
        return [
            None if k is None else self._arrays(k)
            for k in continuation(self.mech, list(phi), LEVELS[self.lvl], self.options)
        ]

    def _arrays(self, kin: Kinematics) -> dict[str, Any]:
        lay = self.comp.layout
        singular = kin.level != LEVELS[self.lvl]
        res: dict[str, Any] = {
            "positions": np.array([kin.positions[p] for p in self.points]),
            "link_angles": np.array([kin.links[lk].angle for lk in self.links]),
            "condition": math.inf if singular else 1.0,
        }
        disp, slid = [], []
        for ps in lay.paths:
            j = kin.joints[ps.joint]
            u = j.direction or (1.0, 0.0)
            at = j.at or (0.0, 0.0)
            through = ps.path.through
            t = lay.ref_xy(through, kin.positions)
            disp.append(
                (at[0] - t[0]) * u[0] + (at[1] - t[1]) * u[1] if ps.guide == self.mech.ground else math.nan
            )
            if self.lvl >= 1 and not singular:
                slid.append(kin.sliding(ps.joint))
        res["displacement"] = np.array(disp)
        nan_p = np.full((len(self.points), 2), np.nan)
        nan_l = np.full(len(self.links), np.nan)
        if self.lvl >= 1:
            res["velocities"] = nan_p if singular else np.array([kin.velocity(p) for p in self.points])
            res["omegas"] = nan_l if singular else np.array([kin.links[lk].omega for lk in self.links])
            res["sliding"] = np.full(len(self.slides), np.nan) if singular else np.array(slid)
        if self.lvl >= 2:
            res["accelerations"] = nan_p if singular else np.array([kin.acceleration(p) for p in self.points])
            res["alphas"] = nan_l if singular else np.array([kin.links[lk].alpha for lk in self.links])
        return res


class Walk:
    """One Newton continuation sent from angle to angle, each solve warm from the last one.

    Refinement needs solutions between the steps *on the sweep's branch*: a
    solve from the drawing would turn the crank the short way round, and a
    gear train is then elsewhere (a 2:1 wheel at crank 350° is at −175° along
    the sweep, +5° from the drawing).  So the walk starts where the sweep
    started and continues along the crank to every angle it is sent to, by the
    same predictor–corrector as the sweep
    (:func:`~mech.kinematics.solve.continuation`, which reads its angles one
    at a time: the route is a list that grows as the walk goes).  Once a solve
    fails the walk is lost (continuation cannot jump) and starts again.
    """

    def __init__(self, backend: Newton, start: float) -> None:
        self.backend, self.start = backend, float(start)
        marcher = Marcher.make(backend)  # stacked rows: one marched step per probe (mech.kinematics.march)
        self._fast = None if marcher is None else marcher.walker(self.start)
        if self._fast is None:
            self._begin()

    def _begin(self) -> None:
        self._route = [self.start]
        self._steps = continuation(
            self.backend.mech, self._route, LEVELS[self.backend.lvl], self.backend.options
        )
        self.lost = next(self._steps) is None

    def to(self, angle: float) -> dict[str, Any] | None:
        """The sweep's arrays for one step at ``angle``, or None where it cannot be reached."""
        if self._fast is not None:
            return self._fast.to(angle)
        if self.lost:
            self._begin()
            if self.lost:
                return None
        self._route.append(float(angle))
        kin = next(self._steps)
        if kin is None:
            self.lost = True
            return None
        return self.backend._arrays(kin)


def stack_rows(rows: list[dict[str, Any] | None], shape: tuple[int, ...]) -> dict[str, np.ndarray]:
    """Per-step dicts of arrays → one dict of (shape, …) arrays, NaN where a step is None."""
    template = next((r for r in rows if r is not None), None)
    if template is None:
        raise GeometryError("the mechanism cannot be moved to any angle asked")
    res: dict[str, np.ndarray] = {}
    for key, val in template.items():
        arr = np.full((len(rows), *np.shape(val)), np.nan)
        for k, r in enumerate(rows):
            if r is not None:
                arr[k] = r[key]
        res[key] = arr.reshape(*shape, *np.shape(val))
    ok = np.array([r is not None for r in rows]).reshape(shape)
    res["assembled"] = ok
    res["condition"] = np.where(ok, res["condition"], np.nan)
    res["disc"] = np.where(ok, 1.0, -1.0)[..., None]
    res["miss"] = np.full((*shape, 1), np.nan)
    return res


def newton_series(
    backend: Newton, phi: np.ndarray, notes: list[str], drawn: float | None = None
) -> dict[str, np.ndarray]:
    """Per-step Newton continuation outward from the step nearest the drawing.

    The drawn configuration is the one place known to be assembled: the sweep
    continues from there forward and backward, each way until the first angle it
    cannot reach (a limit position), and says where it stopped.  Starting at the
    range's first angle instead would fail outright when that angle lies beyond
    a rocker's limits.
    """
    k0 = 0
    if drawn is not None and phi.size:
        k0 = int(np.argmin(np.abs(np.remainder(phi - drawn + math.pi, _TWO_PI) - math.pi)))
    marcher = Marcher.make(backend) if phi.size > 1 else None
    if marcher is not None:  # many steps at once (mech.kinematics.march); the same walk, outward from k0
        marched = marcher.series(phi, k0)
        backend.marcher = marcher  # refinement then evaluates grids between the steps, as the closed form's
        ok = marched["assembled"]
        if not ok.all():
            reached = np.flatnonzero(ok)
            stops = (
                [k for k in (reached[0] - 1, reached[-1] + 1) if 0 <= k < phi.size] if reached.size else [k0]
            )
            notes.append(
                "Newton continuation from the drawing cannot reach "
                + " or ".join(f"{math.degrees(phi[k]):.6g}°" for k in stops)
                + " (a limit position, or out of reach): the steps beyond are not solved"
            )
        if not ok.any():
            raise GeometryError("the mechanism cannot be moved to any angle asked")
        return marched
    forward = backend.series(phi[k0:])
    backward = backend.series(phi[: k0 + 1][::-1])[::-1] if k0 > 0 else []
    for part in (forward, backward):  # after a failure, nothing beyond it is trusted
        order = range(len(part)) if part is forward else range(len(part) - 1, -1, -1)
        failed = False
        for k in order:
            failed = failed or part[k] is None
            if failed:
                part[k] = None
    rows = backward[:-1] + forward
    solved = [k for k, r in enumerate(rows) if r is not None]
    if len(solved) < len(rows):
        # the first steps it could not reach, on either side of the solved run
        stops = [k for k in (solved[0] - 1, solved[-1] + 1) if 0 <= k < len(rows)] if solved else [k0]
        notes.append(
            "Newton continuation from the drawing cannot reach "
            + " or ".join(f"{math.degrees(phi[k]):.6g}°" for k in stops)
            + " (a limit position, or out of reach): the steps beyond are not solved"
        )
    return stack_rows(rows, (phi.size,))


def law_series(
    backend: Newton, marcher: Marcher, phi: np.ndarray, notes: list[str], fmt: Callable[[float], str]
) -> dict[str, np.ndarray]:
    """The series of a sweep whose drives follow linear laws in its parameter, marched from the drawing.

    As :func:`newton_series`: outward from the step nearest the drawn
    parameter, each way until a step cannot be reached (said in the notes,
    ``fmt`` writing a parameter value).
    """
    p0 = marcher.law.p0  # type: ignore[union-attr]
    k0 = int(np.argmin(np.abs(phi - p0)))
    marched = marcher.series(phi, k0)
    backend.marcher = marcher
    ok = marched["assembled"]
    if not ok.all():
        reached = np.flatnonzero(ok)
        stops = [k for k in (reached[0] - 1, reached[-1] + 1) if 0 <= k < phi.size] if reached.size else [k0]
        notes.append(
            "Newton continuation from the drawing cannot reach "
            + " or ".join(fmt(float(phi[k])) for k in stops)
            + " (a limit position, or out of reach): the steps beyond are not solved"
        )
    if not ok.any():
        raise GeometryError("the mechanism cannot be moved to any parameter asked")
    return marched
