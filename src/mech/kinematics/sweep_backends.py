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
from mech.kinematics.march_arrays import point_or_nan
from mech.kinematics.quantities import LEVELS
from mech.kinematics.result import Kinematics
from mech.kinematics.solve import Compiled, continuation
from mech.model import Mechanism
from mech.options import SolveOptions

__all__ = ["Closed", "Newton", "Walk", "law_series", "newton_series", "stack_rows"]

_TWO_PI = 2.0 * math.pi


def shifted(phi: np.ndarray, steps: np.ndarray, shift: np.ndarray, usable: np.ndarray) -> np.ndarray:
    """``phi`` each moved by the ``shift`` of its nearest ``usable`` step (of ``steps``)."""
    a = np.asarray(phi, float)
    if not steps.size or not np.any(shift) or not np.any(usable):
        return a
    have = np.flatnonzero(usable)
    order = have[np.argsort(steps[have])]
    sp = steps[order]
    j = np.clip(np.searchsorted(sp, a), 1, max(sp.size - 1, 1))
    j = np.where(np.abs(a - sp[j - 1]) <= np.abs(a - sp[j]), j - 1, j)
    return a + shift[order][j]


def seam_shifts(phi: np.ndarray, ok: np.ndarray, k0: int) -> np.ndarray:
    """Per step of a crank's full turn, the turn (±2π) to add to reach it from the drawing through 0°.

    The motion from the drawing (step ``k0``) runs along its stretch of assembled steps; where
    that stretch meets one end of the turn and the steps at the other end are assembled too,
    it goes on through 0° ≡ 360° into them: they are reached by turning the other way, and a
    change point passed on that way is passed (the crank cannot cross the gap between).
    Zero everywhere else, and for a sweep that is not one full turn.
    """
    shift = np.zeros(phi.size)
    full = phi.size > 2 and abs(abs(float(phi[-1] - phi[0])) - _TWO_PI) < 1e-9
    if not full or ok.all() or not (ok[0] and ok[-1] and ok[k0]):
        return shift
    spans = [(i, j) for i, j in _runs(ok)]
    mine = next(r for r in spans if r[0] <= k0 < r[1])
    turn = _TWO_PI if phi[-1] > phi[0] else -_TWO_PI
    if mine[0] == 0 and spans[-1] != mine:  # the drawing's stretch starts the turn: on into its end
        i, j = spans[-1]
        shift[i:j] = -turn
    elif mine[1] == phi.size and spans[0] != mine:  # it ends the turn: on into its start
        i, j = spans[0]
        shift[i:j] = turn
    return shift


def _runs(mask: np.ndarray) -> list[tuple[int, int]]:
    edges = np.flatnonzero(np.diff(np.concatenate(([0], mask.astype(np.int8), [0]))))
    return [(int(i), int(j)) for i, j in zip(edges[0::2], edges[1::2], strict=True)]


class Closed:
    """Evaluate the dyad program at any array of angles, with everything a sweep derives."""

    method = "closed form"
    vectorised = True  # evaluate() takes any array of angles: refinement on grids

    def __init__(self, comp: Compiled, prog: DyadProgram, omega: float, alpha: float, lvl: int) -> None:
        self.comp, self.prog, self.omega, self.alpha, self.lvl = comp, prog, omega, alpha, lvl
        # where the sweep's branch is the drawn one: the drawn angle, or whole turns from it (set by
        # the sweep); past a change point a dyad's sign flips (mech.kinematics.dyads.branches)
        self.ref = prog.drawn_angle
        # steps reached from the drawing the other way round a full turn (seam_shifts): the branch
        # there is counted along that way
        self.steps, self.shift = np.zeros(0), np.zeros(0)
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
            way = (
                shifted(phi, self.steps, self.shift, np.ones(self.steps.size, bool))
                if self.steps.size
                else phi
            )
            branch = branches(prog, self.ref, way)
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
        extra: tuple[str, ...] = (),
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
        # the located points, then any link's point at a contact asked for (K@cam: DESIGN § 1.2)
        located = tuple(p for p in comp.system.loc_names if not p.startswith("#"))
        self.extra = tuple(p for p in extra if p not in located)
        self.points = located + self.extra
        self.marcher: Marcher | None = None  # set when the series was marched: grids can then be evaluated
        # the marched series' steps and, per step, where the march solved it: the marcher's own step
        # (index) and the parameter's shift (a whole period, for a step reached round the other way)
        self.steps = np.zeros(0)
        self.index = np.zeros(0, int)
        self.shift = np.zeros(0)

    @property
    def vectorised(self) -> bool:
        """True when :meth:`evaluate` can refine on grids (the series was marched)."""
        return self.marcher is not None

    def marched(
        self, phi: np.ndarray, index: np.ndarray | None = None, shift: np.ndarray | None = None
    ) -> None:
        """Say where the marcher solved each step of ``phi`` (default: step k at its own k)."""
        self.steps = np.asarray(phi, float)
        self.index = np.arange(phi.size) if index is None else index
        self.shift = np.zeros(phi.size) if shift is None else shift

    def _shifted(self, phi: np.ndarray) -> np.ndarray:
        """Parameters as the marcher solved them: each moved by the shift of its nearest step."""
        return shifted(phi, self.steps, self.shift, self.index >= 0)

    def evaluate(self, phi: np.ndarray) -> dict[str, np.ndarray]:
        """Every array a sweep needs at angles ``phi`` between the marched steps (see Marcher.evaluate)."""
        assert self.marcher is not None
        return self.marcher.evaluate(self._shifted(phi))

    def corrected(self, a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Configurations at the parameters ``a`` and whether each converged (Marcher.corrected)."""
        assert self.marcher is not None
        return self.marcher.corrected(self._shifted(a))

    def solved_q(self) -> np.ndarray:
        """The marched configurations (n, 3n), in the order of the sweep's steps (NaN where not solved)."""
        assert self.marcher is not None
        q = self.marcher.solved[1]
        out = np.full((self.index.size, q.shape[1]), np.nan)
        have = self.index >= 0
        out[have] = q[self.index[have]]
        return out

    def edge(self, k: int, bad: float) -> float:
        """The last parameter reached going from step ``k`` toward ``bad`` (Marcher.edge), unshifted."""
        assert self.marcher is not None
        shift = float(self.shift[k])
        return self.marcher.edge(int(self.index[k]), float(bad) + shift) - shift

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
            "positions": np.array([kin.position(p) for p in self.points]),
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
            res["accelerations"] = (
                nan_p if singular else np.array([point_or_nan(kin.acceleration, p) for p in self.points])
            )
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
        marched = around(backend, marcher, phi, k0, marcher.series(phi, k0))
        backend.marcher = marcher  # refinement then evaluates grids between the steps, as the closed form's
        _unreached_note(marched["assembled"], phi, k0, notes, lambda p: f"{math.degrees(p):.6g}°")
        if not marched["assembled"].any():
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
    marched = around(backend, marcher, phi, k0, marcher.series(phi, k0))
    backend.marcher = marcher
    _unreached_note(marched["assembled"], phi, k0, notes, fmt)
    if not marched["assembled"].any():
        raise GeometryError("the mechanism cannot be moved to any parameter asked")
    return marched


def _unreached_note(
    ok: np.ndarray, phi: np.ndarray, k0: int, notes: list[str], fmt: Callable[[float], str]
) -> None:
    """Say which steps the continuation did not reach: the first ones past each reached stretch."""
    if ok.all():
        return
    stops = [
        k
        for k in range(phi.size)
        if not ok[k] and ((k > 0 and ok[k - 1]) or (k + 1 < phi.size and ok[k + 1]))
    ]
    notes.append(
        "Newton continuation from the drawing cannot reach "
        + " or ".join(fmt(float(phi[k])) for k in (stops or [k0]))
        + " (a limit position, or out of reach): the steps beyond are not solved"
    )


def period_of(marcher: Marcher) -> float | None:
    """2π when a turn of the sweep's parameter brings the mechanism back to itself, else None.

    A crank's angle, or drives turning whole numbers of turns per turn of the lead (the
    two-crank five-bar: 1 and −2), come back after 2π; a wheel geared to turn a fraction of
    a turn, a wheel rolling along a line, a slider drive do not.  Tried on the drawing: the
    constraint rows, every drive a turn on, must hold at the drawn configuration with each
    link's angle turned the whole number of turns the angle rows ask (by least squares).
    """
    law, sys_ = marcher.law, marcher.sys
    line = getattr(law, "line", None)
    if line is not None and bool(np.any(line)):
        return None  # a slider drive: its stroke does not come round
    q0 = np.asarray(sys_.q0, float)
    p0 = float(getattr(law, "p0", 0.0))
    c_line, c_ang = law.targets(q0, p0, np.array([0.0, _TWO_PI]))
    c_line = np.broadcast_to(c_line, (2, np.shape(c_line)[-1]))  # one crank's law: the same line rows
    if not np.allclose(c_line[1], c_line[0], rtol=0.0, atol=1e-12):
        return None
    turns = (c_ang[1] - c_ang[0]) / _TWO_PI
    a = np.asarray(sys_.ang_a, float)[:, : sys_.n]
    m = np.linalg.lstsq(a, turns, rcond=None)[0] if a.size else np.zeros(sys_.n)
    whole = np.round(m)
    if a.size and (np.max(np.abs(m - whole)) > 1e-9 or np.max(np.abs(a @ whole - turns)) > 1e-9):
        return None
    q = q0.copy()
    q[2::3] += _TWO_PI * whole
    residual = marcher.rows.phi(q[None, :], c_line[1:], c_ang[1:])
    return _TWO_PI if float(np.max(np.abs(residual), initial=0.0)) <= 1e-9 else None


def around(
    backend: Newton, marcher: Marcher, phi: np.ndarray, k0: int, marched: dict[str, np.ndarray]
) -> dict[str, np.ndarray]:
    """The series continued round the parameter's period to the steps the march did not reach.

    The march from the drawing stops each way at the first step it cannot reach (a limit) or at
    the end of the range.  A step beyond a limit may still be reached the other way round: the
    two-crank five-bar, drawn at 90°, closes from 0° to 123.6° and from 169.52° to 360°, and 0°
    is 360°.  Where a turn of the parameter brings the mechanism back to itself
    (:func:`period_of`), each step not reached is marched to at its image a period away, on
    the far side of the stretch reached (or, equally, inside it), in one march outward from the
    drawing; the arrays come back in the order of ``phi``, and the backend knows where each
    step was solved (:meth:`Newton.marched`).
    """
    ok = marched["assembled"]
    backend.marched(phi)
    period = period_of(marcher) if (phi.size > 1 and ok.any() and not ok.all()) else None
    if period is None:
        return marched
    sgn = 1.0 if phi[-1] >= phi[0] else -1.0
    u = sgn * phi  # increasing along the sweep
    reached = np.flatnonzero(ok)
    a, b = int(reached[0]), int(reached[-1])
    if u[b] - u[a] >= period * (1.0 - 1e-12):
        return marched
    rest = np.flatnonzero(~ok)
    image = u[rest] - period * np.floor((u[rest] - u[a]) / period)  # in [u_a, u_a + period)
    beyond = image > u[b]
    ext = np.unique(np.concatenate([image[beyond] - period, u[a : b + 1], image]))
    got = marcher.series(sgn * ext, int(np.searchsorted(ext, u[k0])))
    index = np.full(phi.size, -1)
    index[a : b + 1] = np.searchsorted(ext, u[a : b + 1])
    shift = np.zeros(phi.size)
    for k, x, out in zip(rest, image, beyond, strict=True):
        for c in [x - period, x] if out else [x]:
            j = int(np.searchsorted(ext, c))
            if j < ext.size and ext[j] == c and got["assembled"][j]:
                index[k], shift[k] = j, sgn * (c - u[k])
                break
    backend.marched(phi, index, shift)
    return _taken(got, index)


def _taken(arrays: dict[str, np.ndarray], index: np.ndarray) -> dict[str, np.ndarray]:
    """Rows ``index`` of every array (a step not solved, index −1: not assembled, NaN)."""
    have = index >= 0
    out: dict[str, np.ndarray] = {}
    for key, arr in arrays.items():
        taken = arr[np.where(have, index, 0)]
        shape = (index.size,) + (1,) * (arr.ndim - 1)
        if arr.dtype == bool:
            out[key] = taken & have.reshape(shape)
        else:
            out[key] = np.where(have.reshape(shape), taken, -1.0 if key == "disc" else np.nan)
    return out
