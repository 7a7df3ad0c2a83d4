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
* **Singular steps are not reported as numbers.**  Where the dyad
  condition number exceeds :data:`~mech.kinematics.dyads.ACCURATE_COND`
  (1e5, within about 1e-10 rad of a toggle: rates there are good to less
  than 1e-6), velocities and accelerations are NaN and a note says how
  many; the largest condition met is reported.  Newton sweeps use the
  solver's own :data:`~mech.kinematics.solve.SINGULAR`.
* **Extremes and dead centres are refined**, not read off the grid: the
  closed form is evaluated on a fine sub-grid round each candidate, zooming
  in 16× per round until the bracket is at rounding, so an extreme value is
  exact to about 1e-15 relative and its angle to about 1e-8 rad (the top of
  a smooth maximum is flat: value changes only as Δθ²); a dead centre's
  angle, a root, is found to about 1e-15 rad.  A Newton sweep refines each
  one between its neighbouring steps by Brent's method (extremes) or regula
  falsi (dead centres) on Newton solves warm-started along the sweep's own
  branch (:class:`_Walk`), to the solver's tolerance.  Over a full turn only
  a quantity that comes back to its first value is taken as periodic (a
  2:1 wheel is not); nothing is extrapolated beyond the range swept.
* **Bounded memory.**  A sweep whose arrays would exceed
  :data:`MEMORY_BUDGET` (1 GiB, estimated per angle from the chain) is
  refused before solving, with the number of angles that fit.

The quick-return time ratio is the crank angle of the slow stroke over that
of the fast one, between the two dead centres of the output (the last slider
on a fixed guide, else the last link pivoted on the frame), over a full,
gap-free revolution (Khurmi & Gupta, *Theory of Machines*, ch. 5, the crank
and slotted lever: cutting / return = (360° − β)/β, β the crank angle of the
return stroke).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from mech._records import dataclass
from mech.errors import GeometryError, InputError, UnsupportedError
from mech.kinematics.dyads import ACCURATE_COND, SLACK, DyadProgram, closing_edge, numpy_namespace, program
from mech.kinematics.march import Marcher
from mech.kinematics.result import Kinematics
from mech.kinematics.solve import SINGULAR, Compiled, compiled, continuation, instant_pairs, solve
from mech.model import JointType, Mechanism
from mech.options import SolveOptions

__all__ = ["Event", "Extreme", "Gap", "Sweep", "TimeRatio", "sweep"]

LEVELS = ("position", "velocity", "acceleration")
_TWO_PI = 2.0 * math.pi


@dataclass(frozen=True, slots=True)
class Gap:
    """Drive angles ``start``–``end`` (rad) where the mechanism cannot be assembled.

    ``miss`` is how far the loop is from closing at worst (m), ``what`` the
    dyad that fails (which links cannot reach).
    """

    start: float
    end: float
    miss: float
    what: str


@dataclass(frozen=True, slots=True)
class Event:
    """A located event: a toggle (``kind="toggle"``) or a dead centre (``"dead centre"``).

    ``angle`` is the drive angle (rad); ``subject`` the output or the links in
    line; ``value`` the output's position there (slider displacement, m, or
    link angle, rad), None for a toggle.
    """

    kind: str
    angle: float
    subject: str
    value: float | None = None


@dataclass(frozen=True, slots=True)
class Extreme:
    """Largest and smallest value of one quantity over the sweep, with the drive angles (rad)."""

    quantity: str
    unit: str
    max_angle: float
    max_value: float
    min_angle: float
    min_value: float


@dataclass(frozen=True, slots=True)
class TimeRatio:
    """Quick return: crank angles (rad) of the slow and fast strokes of ``output`` and their ratio."""

    output: str
    slow: float
    fast: float

    @property
    def ratio(self) -> float:
        """Slow stroke over fast stroke (cutting / return for a shaper), ≥ 1."""
        return self.slow / self.fast


def _frozen(a: np.ndarray | None) -> np.ndarray | None:
    if a is not None:
        a.flags.writeable = False
    return a


@dataclass(frozen=True)
class Sweep:
    """A mechanism solved over an array of drive angles.  Arrays are read-only.

    Attributes
    ----------
    mechanism, level, method
        The mechanism's label, the level solved, ``"closed form"`` or ``"newton"``.
    drive
        The driving link; ``omega``/``alpha`` its speed (rad/s, ccw +; None
        at position level without a speed) and angular acceleration.
    angles
        (N,) drive angles, rad, in the order swept.
    points
        Names of the points, in the order of the second axis of ``positions``.
    positions, velocities, accelerations
        (N, P, 2) arrays, m, m/s, m/s² (None above the level); NaN where not
        assembled (and velocities, accelerations NaN where singular).
    links
        Moving links; ``link_angles`` (N, L) rad, unwrapped along the sweep;
        ``omegas``, ``alphas`` (N, L) rad/s, rad/s².
    slides
        Prismatic and slot joints; ``displacement`` (N, S) the slider point's
        position along its path from the path's ``through`` point, m;
        ``sliding`` (N, S) its speed along the path relative to the guide, m/s.
    assembled
        (N,) bool.
    condition
        (N,) the largest dyad condition number at each step (Newton: of Φ_q).
    gaps, toggles, dead_centres, extremes, time_ratio, notes
        What the sweep found (see the classes).
    """

    mechanism: str
    level: str
    method: str
    drive: str
    omega: float | None
    alpha: float
    angles: np.ndarray
    points: tuple[str, ...]
    positions: np.ndarray
    velocities: np.ndarray | None
    accelerations: np.ndarray | None
    links: tuple[str, ...]
    link_angles: np.ndarray
    omegas: np.ndarray | None
    alphas: np.ndarray | None
    slides: tuple[str, ...]
    displacement: np.ndarray
    sliding: np.ndarray | None
    assembled: np.ndarray
    condition: np.ndarray
    gaps: tuple[Gap, ...]
    toggles: tuple[Event, ...]
    dead_centres: tuple[Event, ...]
    extremes: tuple[Extreme, ...]
    time_ratio: TimeRatio | None
    notes: tuple[str, ...]

    def series(self, quantity: str) -> np.ndarray:
        """The (N,) values of one quantity (see :func:`quantity_unit` for the keys)."""
        return _series(self, quantity)

    @property
    def max_condition(self) -> float:
        """The largest condition number met at an assembled step."""
        c = self.condition[self.assembled]
        return float(np.max(c)) if c.size else math.nan


# -- quantities -------------------------------------------------------------------------------
_UNITS = {
    "angle": "rad",
    "omega": "rad/s",
    "alpha": "rad/s^2",
    "velocity": "m/s",
    "acceleration": "m/s^2",
    "position": "m",
    "displacement": "m",
    "sliding": "m/s",
    "included": "rad",
}
_NEEDS = {"omega": 1, "velocity": 1, "sliding": 1, "alpha": 2, "acceleration": 2}


def quantity_unit(quantity: str) -> str:
    """SI unit of a quantity key.

    Keys: ``angle.<link>``, ``omega.<link>``, ``alpha.<link>`` (signed, ccw +);
    ``velocity.<point>``, ``acceleration.<point>`` (magnitudes) or with
    ``.x``/``.y`` (components); ``position.<point>.x|y``;
    ``displacement.<joint>`` and ``sliding.<joint>`` (a slider along its path);
    ``included.<p>.<q>.<r>``: the angle p–q–r at q, 0 to π (a transmission angle).
    """
    return _UNITS[quantity.split(".", 1)[0]]


def _check_quantity(
    sw_points: Sequence[str], links: Sequence[str], slides: Sequence[str], key: str, lvl: int
) -> None:
    parts = key.split(".")
    kind = parts[0]
    if kind not in _UNITS or len(parts) < 2:
        raise InputError(
            f"unknown quantity {key!r}",
            hint="angle.LINK, omega.LINK, alpha.LINK, velocity.POINT[.x|.y], acceleration.POINT[.x|.y], "
            "position.POINT.x|y, displacement.JOINT, sliding.JOINT, included.P.Q.R",
        )
    if kind == "included":
        if len(parts) != 4:
            raise InputError(f"{key}: an included angle names three points, included.P.Q.R (the angle at Q)")
        for name in parts[1:]:
            if name not in sw_points:
                raise InputError(f"{key}: no point named {name}", hint=f"choose from {', '.join(sw_points)}")
        return
    if _NEEDS.get(kind, 0) > lvl:
        raise InputError(f"{key} needs level {LEVELS[_NEEDS[kind]]} (give --level {LEVELS[_NEEDS[kind]]})")
    name = parts[1]
    pool = {"angle": links, "omega": links, "alpha": links, "displacement": slides, "sliding": slides}.get(
        kind, sw_points
    )
    if name not in pool:
        raise InputError(
            f"{key}: no {'link' if kind in ('angle', 'omega', 'alpha') else 'joint' if kind in ('displacement', 'sliding') else 'point'} named {name}",
            hint=f"choose from {', '.join(pool)}",
        )
    comp = parts[2] if len(parts) > 2 else None
    if comp not in (None, "x", "y") or (kind == "position" and comp is None) or (len(parts) > 3):
        raise InputError(
            f"{key}: a component is .x or .y" + (" (position needs one)" if kind == "position" else "")
        )


def _pick(arrays: dict[str, Any], names: dict[str, tuple[str, ...]], key: str) -> np.ndarray:
    """A quantity from arrays shaped (..., P, 2) / (..., L) / (..., S)."""
    parts = key.split(".")
    kind, name = parts[0], parts[1]
    comp = parts[2] if len(parts) > 2 else None
    if kind in ("angle", "omega", "alpha"):
        arr = arrays[{"angle": "link_angles", "omega": "omegas", "alpha": "alphas"}[kind]]
        return arr[..., names["links"].index(name)]
    if kind in ("displacement", "sliding"):
        return arrays[kind][..., names["slides"].index(name)]
    if kind == "included":  # the angle p–q–r at q, 0 to π
        pos = arrays["positions"]
        p, q, r = (pos[..., names["points"].index(n), :] for n in parts[1:4])
        u, w = p - q, r - q
        cross = u[..., 0] * w[..., 1] - u[..., 1] * w[..., 0]
        dot = u[..., 0] * w[..., 0] + u[..., 1] * w[..., 1]
        return np.abs(np.arctan2(cross, dot))
    arr = arrays[{"position": "positions", "velocity": "velocities", "acceleration": "accelerations"}[kind]]
    v = arr[..., names["points"].index(name), :]
    if comp == "x":
        return v[..., 0]
    if comp == "y":
        return v[..., 1]
    return np.hypot(v[..., 0], v[..., 1])


def _series(sw: Sweep, key: str) -> np.ndarray:
    _check_quantity(sw.points, sw.links, sw.slides, key, LEVELS.index(sw.level))
    arrays = {
        "link_angles": sw.link_angles,
        "omegas": sw.omegas,
        "alphas": sw.alphas,
        "displacement": sw.displacement,
        "sliding": sw.sliding,
        "positions": sw.positions,
        "velocities": sw.velocities,
        "accelerations": sw.accelerations,
    }
    return _pick(arrays, {"links": sw.links, "slides": sw.slides, "points": sw.points}, key)


def default_quantities(
    points: Sequence[str], links: Sequence[str], slides: Sequence[str], lvl: int, drive: str
) -> list[str]:
    """What a sweep reports extremes of when none are asked: per level, the textbook quantities."""
    out = [f"displacement.{s}" for s in slides]
    out += [f"angle.{lk}" for lk in links if lk != drive]
    if lvl >= 1:
        out += [f"omega.{lk}" for lk in links if lk != drive]
        out += [f"velocity.{p}" for p in points]
        out += [f"sliding.{s}" for s in slides]
    if lvl >= 2:
        out += [f"alpha.{lk}" for lk in links if lk != drive]
        out += [f"acceleration.{p}" for p in points]
    return out


# -- evaluation backends ------------------------------------------------------------------------
class _Closed:
    """Evaluate the dyad program at any array of angles, with everything a sweep derives."""

    method = "closed form"
    vectorised = True  # evaluate() takes any array of angles: refinement on grids

    def __init__(self, comp: Compiled, prog: DyadProgram, omega: float, alpha: float, lvl: int) -> None:
        self.comp, self.prog, self.omega, self.alpha, self.lvl = comp, prog, omega, alpha, lvl
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
        with np.errstate(all="ignore"):  # a dyad that cannot close or a toggle: masked below, never used
            out = prog.raw(np.asarray(phi, float), self.omega, self.alpha, level=lvl, xp=numpy_namespace())
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


class _Newton:
    """Newton continuation, step by step: the fallback for chains that do not decompose."""

    method = "newton"

    def __init__(
        self, mech: Mechanism, comp: Compiled, options: SolveOptions, omega: float, alpha: float, lvl: int
    ) -> None:
        self.mech, self.comp, self.lvl = mech, comp, lvl
        self.options = options.with_(
            omega=abs(omega), direction="ccw" if omega >= 0 else "cw", alpha=alpha, method="newton"
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


class _Walk:
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

    def __init__(self, backend: _Newton, start: float) -> None:
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


def _stack_rows(rows: list[dict[str, Any] | None], shape: tuple[int, ...]) -> dict[str, np.ndarray]:
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


# -- refinement ----------------------------------------------------------------------------------
def _zoom(
    fn: Callable[[np.ndarray], np.ndarray],
    lo: np.ndarray,
    hi: np.ndarray,
    mode: str,
    rounds: int = 14,
    m: int = 33,
) -> tuple[np.ndarray, np.ndarray]:
    """Refine K brackets at once: maxima, minima (``mode``) or sign changes (``"root"``).

    Each round evaluates ``fn`` on an (K, m) sub-grid of every bracket and
    keeps the two sub-steps round the best point (or the sign change), so a
    bracket shrinks 16× per round: 14 rounds take it from a sweep step to
    rounding.  Returns (angles, values) at the refined points.
    """
    lo, hi = lo.astype(float).copy(), hi.astype(float).copy()
    k = np.arange(lo.size)
    t = np.linspace(0.0, 1.0, m)
    for _ in range(rounds):
        grid = lo[:, None] + (hi - lo)[:, None] * t[None, :]
        vals = fn(grid)
        if mode == "root":
            s = np.sign(vals)
            change = (s[:, :-1] * s[:, 1:]) <= 0
            j = np.where(change.any(axis=1), np.argmax(change, axis=1), m // 2 - 1)
            lo, hi = grid[k, j], grid[k, j + 1]
        else:
            v = np.where(np.isnan(vals), -np.inf if mode == "max" else np.inf, vals)
            j = np.argmax(v, axis=1) if mode == "max" else np.argmin(v, axis=1)
            jl, jh = np.maximum(j - 1, 0), np.minimum(j + 1, m - 1)
            lo, hi = grid[k, jl], grid[k, jh]
        # a root to rounding; a maximum only to 1e-11 rad: its value is then exact (it moves as Δθ²)
        # (a bracket may run downwards, lo > hi, as a descending sweep gives it: measure its width)
        if np.all(np.abs(hi - lo) <= (4e-16 if mode == "root" else 1e-11) * np.maximum(np.abs(lo), 1.0)):
            break
    mid = 0.5 * (lo + hi)
    if mode == "root":
        return mid, fn(mid[:, None])[:, 0]
    grid = lo[:, None] + (hi - lo)[:, None] * t[None, :]
    vals = fn(grid)
    v = np.where(np.isnan(vals), -np.inf if mode == "max" else np.inf, vals)
    j = np.argmax(v, axis=1) if mode == "max" else np.argmin(v, axis=1)
    return grid[k, j], vals[k, j]


# -- the sweep -------------------------------------------------------------------------------
def sweep(
    mech: Mechanism,
    angles: Sequence[float] | np.ndarray | None = None,
    *,
    level: str = "velocity",
    options: SolveOptions | None = None,
    quantities: Sequence[str] | None = None,
    analyse: bool = True,
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
        Not one turning drive (a slider drive, several drives), or pairs known
        only at the drawn instant (cam, contact): they cannot be moved.
    GeometryError
        The mechanism cannot be assembled as drawn, or at none of the angles.

    Examples
    --------
    >>> s = sweep(mech, np.radians(np.arange(0, 360.5, 0.5)), level="acceleration")  # doctest: +SKIP
    >>> [(math.degrees(e.angle), e.subject) for e in s.dead_centres]                  # doctest: +SKIP
    [(0.0, 'P'), (180.0, 'P')]
    """
    options = options or SolveOptions()
    if level not in LEVELS:
        raise InputError(f"level must be one of {', '.join(LEVELS)}, not {level!r}")
    if options.angle is not None:
        raise InputError(
            "a sweep sets the crank angle itself", hint="give the range (--from, --to) instead of --angle"
        )
    lvl = LEVELS.index(level)
    if len(mech.drives) != 1 or mech.drives[0].link is None:
        raise UnsupportedError(
            f"a sweep turns one crank; {mech.label} has "
            + ("a slider drive" if mech.drives and mech.drives[0].joint else f"{len(mech.drives)} drives"),
            hint="give one drive: {link: crank, angle: …, rpm: …}",
        )
    base = solve(
        mech, "position", options.with_(omega=None, direction=None, alpha=None)
    )  # validates, assembles
    comp = compiled(mech, None)
    if comp.system.velocity_only:
        raise UnsupportedError(
            f"cannot sweep {mech.label}: {instant_pairs(comp.system.velocity_only)} only the instant drawn "
            "(no profile is given)",
        )
    drive = base.drives[0]
    omega = _drive_omega(mech, options)
    if lvl >= 1 and omega is None:
        raise InputError(
            f"drive of {drive.link} has no speed: give rpm or omega (or --rpm)", where=drive.where
        )
    alpha = options.alpha if options.alpha is not None else (mech.drives[0].alpha or 0.0)
    w_int = omega if omega else 1.0  # velocities are needed for dead centres even at position level
    lvl_int = max(lvl, 1)
    phi = np.radians(np.arange(0.0, 360.5, 1.0)) if angles is None else np.asarray(angles, float).ravel()
    if phi.size == 0 or not np.all(np.isfinite(phi)):
        raise InputError("the sweep needs at least one finite angle")

    prog = program(comp) if options.method != "newton" else None
    if options.method == "closed" and prog is None:
        raise UnsupportedError(
            f"{mech.label} does not decompose into dyads driven by one crank", hint="use method auto"
        )
    _check_precision(phi)
    _check_memory(comp, prog, phi.size, lvl_int)
    notes: list[str] = list(comp.drawn.notes)
    fine, pick = _analysis_grid(phi, comp, prog, lvl_int, notes) if analyse else (phi, None)
    if prog is not None:
        backend: Any = _Closed(comp, prog, w_int, alpha, lvl_int)
        data = backend.evaluate(fine)
        notes.append("closed form: " + "; ".join(prog.steps))
    else:
        backend = _Newton(mech, comp, options, w_int, alpha, lvl_int)
        data = _newton_series(backend, fine, notes, comp.drawn.drive_angles[0])

    ok = data["assembled"]
    cond = np.where(ok, data["condition"], np.nan)
    singular = ok & (cond > (ACCURATE_COND if prog is not None else SINGULAR))
    for key in ("positions", "link_angles", "displacement"):
        data[key] = np.where(_expand(ok, data[key]), data[key], np.nan)
    for key in ("velocities", "omegas", "sliding", "accelerations", "alphas"):
        if key in data:
            data[key] = np.where(_expand(ok & ~singular, data[key]), data[key], np.nan)
    data["link_angles"] = _unwrap(data["link_angles"], ok)

    names = {"points": backend.points, "links": backend.links, "slides": backend.slides}
    keys = (
        list(quantities)
        if quantities
        else default_quantities(backend.points, backend.links, backend.slides, lvl, drive.link or "")
    )
    for key in keys:
        _check_quantity(backend.points, backend.links, backend.slides, key, lvl)
    gaps: tuple[Gap, ...] = ()
    toggles: tuple[Event, ...] = ()
    dead: tuple[Event, ...] = ()
    extremes: tuple[Extreme, ...] = ()
    ratio = None
    if analyse:
        gaps, toggles = _gaps(backend, fine, data, ok)
        dead, outputs = _dead_centres(backend, comp, fine, data, ok, names)
        extremes = _extremes(backend, fine, data, ok & ~singular, names, keys)
        ratio = _time_ratio(fine, ok, dead, outputs)
    if pick is not None:  # the series at the steps asked; what was found came from the finer grid
        data = {
            k: v[pick] if isinstance(v, np.ndarray) and v.shape[:1] == fine.shape else v
            for k, v in data.items()
        }
        ok, cond, singular = ok[pick], cond[pick], singular[pick]
    if np.any(singular):
        notes.append(
            f"{int(np.sum(singular))} step(s) next to a toggle (condition number above "
            f"{ACCURATE_COND if prog is not None else SINGULAR:.0e}): velocities and accelerations there "
            "would be good to less than 1e-6 and are not reported"
        )
    circuits = _circuits(phi, ok, comp.drawn.drive_angles[0])
    if circuits:
        notes.append(circuits)
    if ratio is not None and abs(ratio.ratio - 1.0) > 1e-9:
        notes.append(
            f"quick return: {ratio.output} strokes take {math.degrees(ratio.slow):.4f}° and {math.degrees(ratio.fast):.4f}° of crank (ratio {ratio.ratio:.6g})"
        )

    vel = data.get("velocities") if lvl >= 1 else None
    return Sweep(
        mechanism=mech.label,
        level=level,
        method=backend.method,
        drive=drive.link or "",
        omega=omega,
        alpha=alpha,
        angles=_frozen(phi.copy()),  # type: ignore[arg-type]
        points=backend.points,
        positions=_frozen(data["positions"]),  # type: ignore[arg-type]
        velocities=_frozen(vel),
        accelerations=_frozen(data.get("accelerations")) if lvl >= 2 else None,
        links=backend.links,
        link_angles=_frozen(data["link_angles"]),  # type: ignore[arg-type]
        omegas=_frozen(data.get("omegas")) if lvl >= 1 else None,
        alphas=_frozen(data.get("alphas")) if lvl >= 2 else None,
        slides=backend.slides,
        displacement=_frozen(data["displacement"]),  # type: ignore[arg-type]
        sliding=_frozen(data.get("sliding")) if lvl >= 1 else None,
        assembled=_frozen(ok.copy()),  # type: ignore[arg-type]
        condition=_frozen(cond),  # type: ignore[arg-type]
        gaps=gaps,
        toggles=toggles,
        dead_centres=dead,
        extremes=extremes,
        time_ratio=ratio,
        notes=tuple(notes),
    )


MEMORY_BUDGET = 1 << 30
"""Bytes a sweep's arrays may take (1 GiB); more angles are refused before solving."""


def _per_angle(comp: Compiled, prog: DyadProgram | None, lvl: int) -> int:
    """Bytes a sweep keeps per angle (an estimate, on the safe side; see :func:`_check_memory`)."""
    if prog is not None:
        with np.errstate(all="ignore"):
            outputs = len(prog.raw(np.zeros(1), 1.0, 0.0, level=lvl, xp=numpy_namespace()))
        return 20 * outputs + 128
    sys_ = comp.system
    values = (lvl + 1) * (2 * len(sys_.loc_names) + len(sys_.links)) + 2 * len(comp.layout.paths)
    return 1200 + 32 * values


def _check_memory(comp: Compiled, prog: DyadProgram | None, n: int, lvl: int) -> None:
    """Refuse a sweep whose arrays would exceed :data:`MEMORY_BUDGET` (an estimate, kept on the safe side).

    Closed form: the generated program's outputs and what is derived from them,
    about 20 bytes per output per angle (measured: 650 bytes per angle for a
    four-bar at velocity level, 1,360 for a six-bar at acceleration level).
    Newton: one small record per step, about 1,200 bytes plus 32 per value kept.
    """
    per = _per_angle(comp, prog, lvl)
    if n * per <= MEMORY_BUDGET:
        return
    fit = MEMORY_BUDGET // per
    raise InputError(
        f"a sweep of {n:,} angles would need about {n * per / 2**30:.1f} GiB for its arrays "
        f"({per:,} bytes per angle for {comp.mech.label}), more than the {MEMORY_BUDGET / 2**30:g} GiB "
        f"a sweep may use",
        hint=f"give at most {fit:,} angles (--steps {fit - 1}), or sweep the range in parts",
    )


#: The analysis grid's largest step (rad): events (dead centres, extremes, gaps) are looked
#: for between angles at most this far apart, whatever steps the series is printed at.
RESOLVE = math.radians(1.0)
#: The float spacing (rad) the largest angle of a sweep may have: beyond it (angles past
#: about 2.6e8°) an angle is not known well enough to locate anything on it.
ANGLE_PRECISION = 1e-9


def _check_precision(phi: np.ndarray) -> None:
    """Refuse angles so large that their float spacing exceeds :data:`ANGLE_PRECISION`."""
    big = float(np.max(np.abs(phi)))
    spacing = float(np.spacing(big))
    if spacing > ANGLE_PRECISION:
        raise InputError(
            f"crank angles as large as {math.degrees(big):.4g}° are held only to "
            f"{math.degrees(spacing):.2g}° in floating point: nothing on them can be located",
            hint="sweep the same crank positions nearer 0 (subtract whole turns of 360°)",
        )


def _analysis_grid(
    phi: np.ndarray, comp: Compiled, prog: DyadProgram | None, lvl: int, notes: list[str]
) -> tuple[np.ndarray, np.ndarray | None]:
    """The angles to analyse: ``phi`` with each step cut into parts of at most :data:`RESOLVE`.

    Returns the grid and the indices of ``phi``'s angles in it (None when no step
    needed cutting).  Two dead centres between two steps leave no sign change to
    refine, so a sweep of 3 steps over two turns saw 2 of its 4; on the finer grid
    it sees them all.  When the finer grid would exceed the memory budget the
    steps given are analysed: a step of more than half a turn is then refused
    (the motion between its ends is unknown), a smaller one gets a note that
    events between steps may be missed.
    """
    if phi.size < 2:
        return phi, None
    widths = np.abs(np.diff(phi))
    parts = np.maximum(1, np.ceil(widths / RESOLVE * (1.0 - 1e-12))).astype(np.int64)
    if int(parts.max()) == 1:
        return phi, None
    total = int(parts.sum()) + 1
    per = _per_angle(comp, prog, lvl)
    if total * per > MEMORY_BUDGET:
        widest = math.degrees(float(widths.max()))
        span = math.degrees(abs(float(phi[-1] - phi[0])))
        fit = max(int(MEMORY_BUDGET // per) - 1, 1)
        if widest > 180.0:
            raise InputError(
                f"steps of {widest:.4g}° are more than half a turn: the crank's motion between them "
                f"is unknown, and resolving it ({total:,} angles at 1°) exceeds the memory a sweep may use",
                hint=f"give at least --steps {math.ceil(span / 180.0)} (1° steps: --steps "
                f"{math.ceil(span * (1 - 1e-12))}), at most {fit:,}; or sweep the range in parts",
            )
        notes.append(
            f"steps of {widest:.4g}° analysed as given (a 1° grid would exceed the memory budget): "
            "a dead centre or extreme between two steps may be missed; give more --steps to resolve it"
        )
        return phi, None
    starts = np.concatenate(([0], np.cumsum(parts)))
    offset = np.arange(total - 1) - np.repeat(starts[:-1], parts)
    fine = np.repeat(phi[:-1], parts) + np.repeat(np.diff(phi) / parts, parts) * offset
    return np.append(fine, phi[-1]), starts


def _expand(mask: np.ndarray, arr: np.ndarray) -> np.ndarray:
    return mask.reshape(mask.shape + (1,) * (arr.ndim - mask.ndim))


def _unwrap(a: np.ndarray, ok: np.ndarray) -> np.ndarray:
    """Link angles continuous along each assembled run (no 2π jumps), first value in [0, 2π)."""
    out = a.copy()
    for start, end in _runs(ok):
        run = np.unwrap(out[start:end], axis=0)
        run -= np.floor(run[0] / _TWO_PI) * _TWO_PI
        out[start:end] = run
    return out


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


def _newton_series(
    backend: _Newton, phi: np.ndarray, notes: list[str], drawn: float | None = None
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
    return _stack_rows(rows, (phi.size,))


def _runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """Index ranges [i, j) where ``mask`` is True."""
    edges = np.flatnonzero(np.diff(np.concatenate(([0], mask.astype(np.int8), [0]))))
    return [(int(i), int(j)) for i, j in zip(edges[0::2], edges[1::2], strict=True)]


def _circuits(phi: np.ndarray, ok: np.ndarray, drawn: float | None) -> str | None:
    """Say so when the assembled steps fall into separate ranges: separate circuits.

    A crank that cannot turn fully between two limit positions reaches only the
    range its drawing lies in; another assembled range (same branch sign of the
    dyads) is a different circuit, reachable only by taking the mechanism apart.
    A full turn whose first and last steps are both assembled wraps into one range.
    """
    runs: list[list[int]] = []
    for i, good in enumerate(ok):
        if good and runs and runs[-1][1] == i - 1:
            runs[-1][1] = i
        elif good:
            runs.append([i, i])
    full_turn = phi.size > 1 and abs(abs(phi[-1] - phi[0]) - _TWO_PI) < 1e-9
    if full_turn and len(runs) > 1 and runs[0][0] == 0 and runs[-1][1] == phi.size - 1:
        runs[0][0] = runs.pop()[0]  # wrapped: the last range continues into the first
    if len(runs) < 2:
        return None

    def span(run: list[int]) -> str:
        return f"{math.degrees(phi[run[0]]):.4g}°–{math.degrees(phi[run[1]]):.4g}°"

    def holds(run: list[int]) -> bool:
        if drawn is None:
            return False
        lo, hi = phi[run[0]], phi[run[1]]
        if lo > hi:  # wrapped range
            return bool(wrap(drawn - lo) >= 0 or wrap(drawn - hi) <= 0)
        k = math.floor((lo - drawn) / _TWO_PI + 1.0)
        a = drawn + k * _TWO_PI
        return bool(lo - 1e-12 <= a <= hi + 1e-12 or lo - 1e-12 <= a - _TWO_PI <= hi + 1e-12)

    def wrap(x: float) -> float:
        return (x + math.pi) % _TWO_PI - math.pi

    mine = [r for r in runs if holds(r)]
    ranges = ", ".join(span(r) for r in runs)
    if mine:
        return (
            f"the assembled ranges {ranges} are separate circuits: the drawing lies on {span(mine[0])}; "
            "the others are the same branch on another circuit, reached only by taking the mechanism apart"
        )
    return f"the assembled ranges {ranges} are separate circuits, and none holds the drawn angle"


def _gaps(
    backend: Any, phi: np.ndarray, data: dict[str, np.ndarray], ok: np.ndarray
) -> tuple[tuple[Gap, ...], tuple[Event, ...]]:
    """Unassembled runs, their edges located as toggles (closed form: bisection on the discriminant)."""
    gaps: list[Gap] = []
    toggles: list[Event] = []
    prog = getattr(backend, "prog", None)
    for s, e in _runs(~ok):
        miss = data["miss"][s:e]
        worst = int(np.argmax(np.max(miss, axis=0))) if miss.size else 0
        what = prog.dyads[worst][2] if prog is not None and prog.dyads else "the loop cannot close"
        start, end = float(phi[s]), float(phi[e - 1])
        if prog is not None:
            if s > 0:
                start = _edge(backend, phi[s - 1], phi[s])
                toggles.append(Event("toggle", start, what))
            if e < phi.size:
                end = _edge(backend, phi[e], phi[e - 1])
                toggles.append(Event("toggle", end, what))
        gaps.append(Gap(start, end, float(np.max(miss)) if miss.size else math.nan, what))
    return tuple(gaps), tuple(sorted(toggles, key=lambda t: t.angle))


def _edge(backend: _Closed, good: float, bad: float) -> float:
    """Bisect on the worst dyad discriminant to the last angle that still closes."""
    return closing_edge(backend.prog, float(good), float(bad))


def _outputs(comp: Compiled, names: dict[str, tuple[str, ...]], drive: str) -> list[tuple[str, str]]:
    """Candidate outputs for dead centres: sliders on the frame, then links pivoted on the frame."""
    lay, mech = comp.layout, comp.mech
    out: list[tuple[str, str]] = []
    for ps in lay.paths:
        if ps.guide == mech.ground:
            out.append(("slide", ps.joint))
    pivoted = []
    for j in mech.joints:
        if j.type is JointType.REVOLUTE and mech.ground in j.links:
            for lk in j.links:
                if lk not in (mech.ground, drive) and lk in names["links"] and lk not in pivoted:
                    pivoted.append(lk)
    out += [("link", lk) for lk in pivoted]
    return out


def _refiner(
    backend: Any, names: dict[str, tuple[str, ...]], keys: Sequence[str], refs: np.ndarray
) -> Callable[[np.ndarray], np.ndarray]:
    """fn(grid (K, m)) → values (K, m) of ``keys[k]`` on row k, one backend call for all rows.

    Angles of links are brought to the branch of ``refs[k]`` (the grid value
    the row refines), since the closed form returns them in (−π, π].
    """

    groups: dict[str, list[int]] = {}
    for k, key in enumerate(keys):
        groups.setdefault(key, []).append(k)
    index = {key: np.array(rows) for key, rows in groups.items()}

    def fn(grid: np.ndarray) -> np.ndarray:
        data = backend.evaluate(grid)
        out = np.empty(grid.shape)
        for key, rows in index.items():
            vals = _pick(data, names, key)[rows]
            if key.startswith("angle."):
                ref = refs[rows][:, None]
                vals = np.where(np.isfinite(ref), vals + _TWO_PI * np.round((ref - vals) / _TWO_PI), vals)
            out[rows] = vals
        return out

    return fn


def _dedupe(events: list[Event], phi: np.ndarray) -> list[Event]:
    """One event per place: over a full cycle 0° and 360° are the same crank position."""
    full = abs(abs(phi[-1] - phi[0]) - _TWO_PI) < 1e-9
    out: list[Event] = []
    for e in sorted(events, key=lambda e: e.angle):
        same = [
            o
            for o in out
            if o.subject == e.subject
            and (abs(o.angle - e.angle) < 1e-9 or (full and abs(abs(o.angle - e.angle) - _TWO_PI) < 1e-9))
        ]
        if not same:
            out.append(e)
    return out


def _dead_centres(
    backend: Any,
    comp: Compiled,
    phi: np.ndarray,
    data: dict[str, np.ndarray],
    ok: np.ndarray,
    names: dict[str, tuple[str, ...]],
) -> tuple[tuple[Event, ...], list[tuple[str, str]]]:
    """Where each output reverses: the sign change of its speed, root-found to rounding.

    Closed form: a bracket zoom on the speed.  Newton: regula falsi (Illinois)
    with a solve per iterate.
    """
    outputs = _outputs(comp, names, comp.layout.drives[0].link or "")
    brackets: list[tuple[str, str, float, float, float, float]] = []  # name, key, lo, hi, v_lo, v_hi
    for kind, name in outputs:
        key = f"sliding.{name}" if kind == "slide" else f"omega.{name}"
        v = _pick(data, names, key)
        finite = v[np.isfinite(v)]
        tiny = 1e-12 * (float(np.max(np.abs(finite))) if finite.size else 1.0)
        sgn = np.where(np.abs(v) <= tiny, 0.0, np.sign(v))
        for s, e in _runs(ok & np.isfinite(v)):
            for k in range(s, e):
                if sgn[k] == 0.0:  # on a grid angle: refine only if the neighbours bracket it
                    if s < k < e - 1 and sgn[k - 1] * sgn[k + 1] < 0:
                        brackets.append((name, key, phi[k - 1], phi[k + 1], v[k - 1], v[k + 1]))
                    else:
                        brackets.append((name, key, phi[k], phi[k], v[k], v[k]))
                elif k + 1 < e and sgn[k] * sgn[k + 1] < 0:
                    brackets.append((name, key, phi[k], phi[k + 1], v[k], v[k + 1]))
    if not brackets:
        return (), outputs
    lo = np.array([b[2] for b in brackets], float)
    hi = np.array([b[3] for b in brackets], float)
    keys = [b[1] for b in brackets]
    pos_keys = [f"displacement.{b[0]}" if b[1].startswith("sliding") else f"angle.{b[0]}" for b in brackets]
    if backend.vectorised:
        roots, _ = _zoom(_refiner(backend, names, keys, np.full(len(keys), np.nan)), lo, hi, "root")
        at = _refiner(backend, names, pos_keys, np.full(len(keys), np.nan))(roots[:, None])[:, 0]
    else:  # one bracket at a time along a warm-started walk, on the sweep's branch
        roots, at = np.empty(len(brackets)), np.empty(len(brackets))
        walk = _Walk(backend, phi[0])
        for i in sorted(range(len(brackets)), key=lambda i: abs(lo[i] - phi[0])):  # along the sweep
            probe = _probe(walk, names, keys[i], math.nan)
            roots[i] = _illinois(
                lambda g, probe=probe: np.array([[probe(float(g[0, 0]))]]),  # type: ignore[misc]
                lo[i : i + 1],
                hi[i : i + 1],
                np.array([brackets[i][4]]),
                np.array([brackets[i][5]]),
            )[0]
            at[i] = _probe(walk, names, pos_keys[i], math.nan)(float(roots[i]))
    at = np.where(
        [k.startswith("angle.") for k in pos_keys], np.mod(at, _TWO_PI), at
    )  # link angles in [0, 2π)
    events = [
        Event("dead centre", float(r), b[0], float(x)) for r, x, b in zip(roots, at, brackets, strict=True)
    ]
    return tuple(_dedupe(events, phi)), outputs


def _illinois(
    fn: Callable[[np.ndarray], np.ndarray],
    a: np.ndarray,
    b: np.ndarray,
    fa: np.ndarray,
    fb: np.ndarray,
    iters: int = 12,
) -> np.ndarray:
    """Regula falsi (Illinois) on K brackets at once: superlinear, a dozen solves each (Newton sweeps)."""
    a, b, fa, fb = a.copy(), b.copy(), fa.copy(), fb.copy()
    side = np.zeros(a.size)
    for _ in range(iters):
        with np.errstate(invalid="ignore", divide="ignore"):
            c = np.where(fb != fa, b - fb * (b - a) / (fb - fa), a)
        done = (np.abs(b - a) <= 1e-15 * np.maximum(np.abs(a), 1.0)) | (fa == 0) | (fb == 0)
        if np.all(done):
            break
        fc = fn(c[:, None])[:, 0]
        left = np.sign(fc) == np.sign(fa)
        a, fa = np.where(left, c, a), np.where(left, fc, fa)
        b, fb = np.where(left, b, c), np.where(left, fb, fc)
        fb = np.where(left & (side == 1), fb / 2, fb)
        fa = np.where(~left & (side == -1), fa / 2, fa)
        side = np.where(left, 1, -1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(fb != fa, b - fb * (b - a) / (fb - fa), a)


def _extremes(
    backend: Any,
    phi: np.ndarray,
    data: dict[str, np.ndarray],
    ok: np.ndarray,
    names: dict[str, tuple[str, ...]],
    keys: Sequence[str],
) -> tuple[Extreme, ...]:
    """Grid extremes of every quantity, refined between the neighbouring steps.

    Closed form: all at once by :func:`_zoom`.  Newton: Brent's method on the
    Newton solve, along a :class:`_Walk` (warm-started, on the sweep's branch).
    Over a full turn a quantity that comes back to its first value (periodic)
    is refined across the seam (0° and 360° are neighbours); one that does not
    (a 2:1 wheel turns half a turn) is refined only inside the range, never
    extrapolated beyond it.  A quantity that does not vary (a piston's angle)
    or a link that turns right round (its unwrapped angle only grows) has no
    extreme worth reporting and is left out.
    """
    turn = phi.size > 2 and abs(abs(phi[-1] - phi[0]) - _TWO_PI) < 1e-9 and bool(np.all(ok))
    rows: list[tuple[str, str, int, float, float, float]] = []  # key, mode, k, lo, hi, grid value
    wraps: dict[str, bool] = {}
    for key in keys:
        v = _pick(data, names, key)
        valid = ok & np.isfinite(v)
        if not np.any(valid):
            continue
        size = max(float(np.max(np.abs(v[valid]))), 1e-300)
        span = float(np.max(v[valid]) - np.min(v[valid]))
        if span <= 1e-12 * size:
            continue
        if key.startswith("angle.") and span >= _TWO_PI - 1e-9:
            continue
        # periodic over the range: back to its first value after the turn (to the solver's accuracy)
        full = wraps[key] = turn and bool(valid[0] and valid[-1] and abs(v[-1] - v[0]) <= 1e-8 * size)
        for mode in ("max", "min"):
            vv = np.where(valid, v, -np.inf if mode == "max" else np.inf)
            k = int(np.argmax(vv) if mode == "max" else np.argmin(vv))
            lo = (
                phi[k - 1]
                if k > 0 and valid[k - 1]
                else (phi[-2] - _TWO_PI * np.sign(phi[-1] - phi[0]) if full and k == 0 else phi[k])
            )
            hi = (
                phi[k + 1]
                if k + 1 < phi.size and valid[k + 1]
                else (phi[1] + _TWO_PI * np.sign(phi[-1] - phi[0]) if full and k == phi.size - 1 else phi[k])
            )
            rows.append((key, mode, k, min(lo, hi), max(lo, hi), float(v[k])))
    sign = np.array([1.0 if r[1] == "max" else -1.0 for r in rows])
    ang, val = np.full(len(rows), np.nan), np.full(len(rows), np.nan)
    if rows and backend.vectorised:
        # minima are maxima of −v: one zoom refines every extreme of every quantity at once
        inner = _refiner(backend, names, [r[0] for r in rows], np.array([r[5] for r in rows]))
        ang, val = _zoom(
            lambda g: sign[:, None] * inner(g),
            np.array([r[3] for r in rows]),
            np.array([r[4] for r in rows]),
            "max",
        )
    elif rows:
        walk = _Walk(backend, phi[0])
        for i in sorted(range(len(rows)), key=lambda i: abs(phi[rows[i][2]] - phi[0])):  # along the sweep
            key, _mode, k, lo, hi, grid = rows[i]
            probe, sg = _probe(walk, names, key, grid), float(sign[i])
            x, fx = _brent(lambda a, p=probe, sg=sg: -sg * p(a), lo, hi, float(phi[k]), -sg * grid)  # type: ignore[misc]
            ang[i], val[i] = x, -fx
    results: dict[tuple[str, str], tuple[float, float]] = {}
    for i, r in enumerate(rows):
        x = sign[i] * val[i]
        better = (x >= r[5]) if r[1] == "max" else (x <= r[5])
        results[(r[0], r[1])] = (
            (float(ang[i]), float(x)) if better and math.isfinite(x) else (float(phi[r[2]]), r[5])
        )
    out = []
    for key in dict.fromkeys(r[0] for r in rows):
        (amax, vmax), (amin, vmin) = results[(key, "max")], results[(key, "min")]
        if wraps[key]:
            amax, amin = _into(amax, phi), _into(amin, phi)
        out.append(Extreme(key, quantity_unit(key), amax, vmax, amin, vmin))
    return tuple(out)


def _into(a: float, phi: np.ndarray) -> float:
    """An angle of a full-cycle sweep brought into the swept range."""
    lo, hi = min(phi[0], phi[-1]), max(phi[0], phi[-1])
    while a < lo:
        a += _TWO_PI
    while a > hi:
        a -= _TWO_PI
    return a


def _probe(walk: _Walk, names: dict[str, tuple[str, ...]], key: str, ref: float) -> Callable[[float], float]:
    """fn(angle) → ``key`` there along the walk (NaN where not reached); a link's angle on ``ref``'s turn."""

    def fn(angle: float) -> float:
        arrays = walk.to(angle)
        if arrays is None:
            return math.nan
        v = float(_pick(arrays, names, key))
        if key.startswith("angle.") and math.isfinite(ref) and math.isfinite(v):
            v += _TWO_PI * round((ref - v) / _TWO_PI)
        return v

    return fn


_GOLD = 0.5 * (3.0 - math.sqrt(5.0))


def _brent(
    f: Callable[[float], float], a: float, b: float, x: float, fx: float, xtol: float = 1e-10
) -> tuple[float, float]:
    """Brent's minimisation of ``f`` on [a, b] from the best known point ``x`` (value ``fx``).

    Parabolic steps where the function is smooth, golden-section ones where it
    is not (the V of a speed's magnitude through zero); NaN counts as +∞.  The
    bracket shrinks to about ``xtol`` rad, some 10–40 solves.  Returns the best
    point seen, never worse than the start (Brent, *Algorithms for Minimization
    without Derivatives*, 1973, ch. 5).
    """

    def g(u: float) -> float:
        val = f(u)
        return val if math.isfinite(val) else math.inf

    w = v = x
    fw = fv = fx
    d = e = 0.0
    for _ in range(100):
        m = 0.5 * (a + b)
        tol1 = xtol + 4e-16 * abs(x)
        tol2 = 2.0 * tol1
        if abs(x - m) <= tol2 - 0.5 * (b - a):
            break
        golden = True
        if abs(e) > tol1 and math.isfinite(fw) and math.isfinite(fv):  # a parabola through x, w, v
            r = (x - w) * (fx - fv)
            q = (x - v) * (fx - fw)
            p = (x - v) * q - (x - w) * r
            q = 2.0 * (q - r)
            if q > 0.0:
                p = -p
            q = abs(q)
            e_old, e = e, d
            if abs(p) < abs(0.5 * q * e_old) and q * (a - x) < p < q * (b - x):
                d = p / q
                if (x + d) - a < tol2 or b - (x + d) < tol2:
                    d = math.copysign(tol1, m - x)
                golden = False
        if golden:
            e = (a - x) if x >= m else (b - x)
            d = _GOLD * e
        u = x + d if abs(d) >= tol1 else x + math.copysign(tol1, d)
        fu = g(u)
        if fu <= fx:
            if u >= x:
                a = x
            else:
                b = x
            v, fv, w, fw, x, fx = w, fw, x, fx, u, fu
        else:
            if u < x:
                a = u
            else:
                b = u
            if fu <= fw or w == x:
                v, fv, w, fw = w, fw, u, fu
            elif fu <= fv or v in (x, w):
                v, fv = u, fu
    return x, fx


def _time_ratio(
    phi: np.ndarray, ok: np.ndarray, dead: tuple[Event, ...], outputs: list[tuple[str, str]]
) -> TimeRatio | None:
    """Slow/fast stroke of the primary output over one full, gap-free revolution."""
    if phi.size < 3 or not np.all(ok) or abs(phi[-1] - phi[0]) < _TWO_PI - 1e-9:
        return None
    order = [name for kind, name in outputs if kind == "slide"][-1:] or [name for kind, name in outputs][-1:]
    if not order:
        return None
    out = order[0]
    start = min(phi[0], phi[-1])
    angles = sorted({round((e.angle - start) % _TWO_PI, 12) for e in dead if e.subject == out})
    if len(angles) != 2:
        return None
    arc = angles[1] - angles[0]
    slow, fast = max(arc, _TWO_PI - arc), min(arc, _TWO_PI - arc)
    return TimeRatio(out, slow, fast) if fast > 0 else None
