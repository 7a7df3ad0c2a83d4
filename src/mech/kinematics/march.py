"""Newton sweeps marched in stacks: many steps of a sweep solved at once, warm-started.

A mechanism that does not decompose into dyads (a double parallelogram, a gear
train) is swept by Newton continuation.  Step by step, each solve costs a
residual, a Jacobian, one or two linear solves and γ — each a dozen small
numpy calls, ~200 µs a step whatever the mechanism's size.  Here the sweep is
*marched*: from the last solved step, the next K steps are predicted at once
by the Taylor series ``q + q′h + q″h²/2`` (q′, q″ the configuration's
derivatives along the crank, which the velocity and acceleration solves give
anyway), Newton corrects all K together on stacked arrays, and the
velocities and accelerations of all K come from one stacked SVD (which also
gives each step's condition, so singular steps are judged exactly as one
solve judges them).  K grows while whole stacks converge, within
:data:`MAX_SPAN` of crank, and shrinks when a step does not; a step that
still fails alone, or follows a singular one, is handed to the step-by-step
continuation of :mod:`.solve`, and the march resumes after it.  Branches are
kept as continuation keeps them: every step is corrected from a prediction
off its own branch, and a correction larger than :data:`JUMP` (scaled) is
refused as a jump.

The stacked residual, Jacobian and γ are the constraint system's own
(:class:`~mech.kinematics.constraints.System`), which are written once with a
leading batch axis: K configurations at once, one being a batch of one.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import numpy as np

from mech.errors import GeometryError
from mech.kinematics.constraints import System
from mech.kinematics.solve import snap_to_error

__all__ = ["MAX_SPAN", "LinearLaw", "Marcher", "Walker", "march"]

#: Largest crank angle one stack may span (rad); continuation's own step limit.
MAX_SPAN = math.radians(15.0)
#: Largest Newton correction (scaled: fractions of the mechanism's size) accepted for a step.
JUMP = 0.05
_FIRST = 8  # steps in the first stack; doubles while stacks converge whole
_EDGE_PROBES = 8192  # Newton probes one limit may take (a wide stroke walked in half-steps, then halving)


def square_rows(sys_: System) -> np.ndarray | None:
    """Rows of Φ_q that determine q̇ on their own (drive rows first), or None when there are too many.

    A redundant system (a double parallelogram: 13 rows, 12 unknowns) is
    consistent, so a square subset of independent rows gives the same
    solutions; chosen once, at the drawn configuration, greedily by rank.
    Along the sweep a step where the subset is ill-conditioned is solved on
    all rows instead (see :class:`_Rates`).
    """
    m, n = sys_.m, 3 * sys_.n
    if m == n:
        return np.arange(m)
    if m < n or m > 60:
        return None
    jac = sys_.jacobian(sys_.q0)
    order = [int(r) for r in sys_.drive_rows] + [
        r for r in range(m) if r not in set(sys_.drive_rows.tolist())
    ]
    keep: list[int] = []
    for r in order:
        s = np.linalg.svd(jac[[*keep, r]], compute_uv=False)
        if s[-1] > 1e-8 * s[0]:
            keep.append(r)
        if len(keep) == n:
            return np.array(sorted(keep))
    return None


def _lin(jac: np.ndarray, rhs: np.ndarray, keep: np.ndarray) -> np.ndarray:
    """Stacked Newton steps: one LU per step on the square subset of rows."""
    return np.linalg.solve(jac[:, keep, :], rhs[:, keep, None])[..., 0]


class _Rates:
    """Velocities and accelerations of stacked configurations: one stacked inverse of Φ_q each.

    Conditioning is judged once per step: the 1-norm condition number from
    the inverse bounds the 2-norm one within a factor n either way, so only
    steps within that factor of :data:`~mech.kinematics.solve.SINGULAR` are
    judged by an SVD (and solved by it, on all rows, exactly as one solve
    does); the others are certainly regular.
    """

    def __init__(
        self,
        rows: System,
        keep: np.ndarray,
        drive_row: np.ndarray,
        rate: np.ndarray,
        accel: np.ndarray,
        singular: float,
    ):
        # per drive: its row, its rate (scaled) and its acceleration (scaled) in that row
        self.rows, self.keep, self.rate, self.accel, self.singular = rows, keep, rate, accel, singular
        self.drive_row = drive_row

    def __call__(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(bad, q̇, q̈) for configurations ``q`` (K, 3n): ``bad`` marks the singular ones.

        Each solve is refined once and its components below their own error
        bound set to zero, by the rule one solve uses
        (:func:`~mech.kinematics.solve.snap_to_error`): a 1e-12 m crank on 1 m
        links keeps its 5e-13 rad/s, a pivot's round-off does not show.
        """
        full = self.rows.jacobian(q)
        jac = full[:, self.keep, :]
        k, n = q.shape[0], jac.shape[2]
        try:
            inv = np.linalg.inv(jac)
            norm1 = np.abs(jac).sum(axis=1).max(axis=1) * np.abs(inv).sum(axis=1).max(axis=1)
            unsure = ~(n * norm1 <= self.singular)  # NaN or large: decide by the SVD
        except np.linalg.LinAlgError:  # one step exactly singular: every step by the SVD
            inv = np.zeros_like(jac)
            unsure = np.ones(k, bool)
        svds: dict[int, tuple[np.ndarray, np.ndarray, np.ndarray]] = {}
        bad = np.zeros(k, bool)
        for t in np.flatnonzero(unsure).tolist():
            u, s, vt = np.linalg.svd(full[t], full_matrices=False)
            svds[t] = (u, s, vt)
            bad[t] = not (s[-1] > 0 and s[0] / s[-1] <= self.singular)
        rhs = np.zeros((k, full.shape[1]))
        rhs[:, self.drive_row] = self.rate
        qd = self._solve(full, jac, inv, svds, rhs)
        gamma = self.rows.gamma(q, qd)
        gamma[:, self.drive_row] += self.accel[None, :]
        return bad, qd, self._solve(full, jac, inv, svds, gamma)

    def _solve(
        self,
        full: np.ndarray,
        jac: np.ndarray,
        inv: np.ndarray,
        svds: dict[int, tuple[np.ndarray, np.ndarray, np.ndarray]],
        rhs: np.ndarray,
    ) -> np.ndarray:
        """x with Φ_q x = b for every step (K, 3n): refined once, then snapped to its error bound."""
        b = rhs[:, self.keep]
        x = np.einsum("kij,kj->ki", inv, b)
        x += np.einsum("kij,kj->ki", inv, b - np.einsum("kij,kj->ki", jac, x))
        x = snap_to_error(jac, inv, x, b)
        for t, (u, s, vt) in svds.items():  # on all rows, as one solve does
            y = _svd_solve(u, s, vt, rhs[t])
            y += _svd_solve(u, s, vt, rhs[t] - full[t] @ y)
            with np.errstate(divide="ignore", invalid="ignore"):
                pinv = vt.T @ (u.T / np.where(s > 0, s, np.inf)[:, None])
            x[t] = snap_to_error(full[t], pinv, y, rhs[t])
        return x


def _svd_solve(u: np.ndarray, s: np.ndarray, vt: np.ndarray, b: np.ndarray) -> np.ndarray:
    with np.errstate(divide="ignore", invalid="ignore"):
        return vt.T @ ((u.T @ b) / np.where(s > 0, s, np.inf))


def march(backend: Any, phi: np.ndarray, k0: int) -> dict[str, np.ndarray] | None:
    """The Newton series of a sweep along ``phi``, outward from step ``k0``, in stacks.

    ``backend`` is the sweep's Newton backend (mechanism, compiled data,
    options, level, point/link/slide names).  Returns the stacked arrays the
    sweep reads (as step-by-step continuation would give them), or None when
    the mechanism cannot be marched (rows of the instant only, no square subset of
    rows, not one crank): the caller sweeps step by step.
    """
    marcher = Marcher.make(backend)
    return None if marcher is None else marcher.series(phi, k0)


class Marcher:
    """What a marched series or walk of one sweep shares: stacked rows, the drive, the rate solver."""

    def __init__(self, backend: Any, rows: System, keep: np.ndarray) -> None:
        from mech.kinematics.solve import SINGULAR, drives_as_used, omega_ref_of

        comp = backend.comp
        sys_ = comp.system
        self.backend, self.comp, self.sys, self.rows = backend, comp, sys_, rows
        self.options = backend.options
        self.lvl = max(backend.lvl, 1)
        self.drives = drives_as_used(comp.mech, comp.layout, comp.drawn, self.options, self.lvl)
        self.omega_ref = omega_ref_of(self.drives, comp.drawn.scale)
        lead = getattr(backend, "lead", None)
        self.law: _CrankLaw | LinearLaw = (
            _CrankLaw(self) if lead is None else LinearLaw(self, lead)  # type: ignore[arg-type]
        )
        self.rate, self.accel = self.law.rate, self.law.accel
        self.rates = _Rates(
            rows, keep, sys_.drive_rows.astype(int), self.law.row_rates, self.law.row_accels, SINGULAR
        )
        self.solved: tuple[np.ndarray, ...] = (np.zeros(0),) * 4 + (np.zeros(0, bool),)

    @classmethod
    def make(cls, backend: Any) -> Marcher | None:
        """A marcher for ``backend``'s mechanism, or None: velocity-only rows, no square subset, not one crank.

        A backend with a ``lead`` (a slider drive, or several drives following
        linear laws in the sweep's parameter, :class:`LinearLaw`) is marched
        whatever its drives; otherwise the mechanism has one turning drive.
        """
        sys_ = backend.comp.system
        keep = square_rows(sys_)
        if keep is None or sys_.velocity_only:
            return None
        if getattr(backend, "lead", None) is None and (
            len(sys_.drive_rows) != 1 or len(backend.mech.drives) != 1 or backend.mech.drives[0].link is None
        ):
            return None
        return cls(backend, sys_, keep)

    def start(self, angle: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool] | None:
        """(q, q̇, q̈, singular) at ``angle``, reached from the drawing as one solve does; None if not."""
        q0 = self.law.reach(float(angle))
        if q0 is None:
            return None
        b0, qd0, qdd0 = self.rates(q0[None, :])
        return q0, qd0[0], qdd0[0], bool(b0[0])

    def fill(
        self, phi: np.ndarray, k0: int, state: tuple[np.ndarray, np.ndarray, np.ndarray, bool] | None
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """q, q̇, q̈ (n, 3n), solved and singular masks along ``phi``, marched both ways from ``k0``."""
        n, n3 = phi.size, 3 * self.sys.n
        q_all = np.full((n, n3), np.nan)
        qd_all = np.full((n, n3), np.nan)
        qdd_all = np.full((n, n3), np.nan)
        ok = np.zeros(n, bool)
        bad = np.zeros(n, bool)
        if state is not None:
            q_all[k0], qd_all[k0], qdd_all[k0], bad[k0] = state
            ok[k0] = True
            for order in (np.arange(k0 + 1, n), np.arange(k0 - 1, -1, -1)):
                _walk(
                    self.rows,
                    self.rates,
                    self.law,
                    self.options,
                    phi,
                    k0,
                    order,
                    q_all,
                    qd_all,
                    qdd_all,
                    ok,
                    bad,
                )
        return q_all, qd_all, qdd_all, ok, bad

    def series(self, phi: np.ndarray, k0: int) -> dict[str, np.ndarray]:
        """The sweep's arrays along ``phi``, marched outward from ``k0`` (reached from the drawing).

        The solved steps are kept: :meth:`evaluate` starts from them.
        """
        q, qd, qdd, ok, bad = self.fill(phi, k0, self.start(float(phi[k0])))
        self.solved = (np.asarray(phi, float), q, qd, qdd, ok & ~bad)
        return _arrays(self.backend, self.comp, q, qd, qdd, ok, bad, self.omega_ref, self.lvl)

    def evaluate(self, angles: np.ndarray) -> dict[str, np.ndarray]:
        """The sweep's arrays at ``angles`` (any shape) between the steps of the last :meth:`series`.

        Each angle is predicted from the nearest regular solved step — on the
        sweep's own branch, at most half a step away — and corrected with the
        others in one stack, so refining every extreme and dead centre of a
        sweep costs a few stacked solves (as the closed form's grids do), not a
        continuation per probe.  Angles that do not converge are NaN.
        """
        shape = np.shape(angles)
        a = np.asarray(angles, float).ravel()
        q_n, conv = self.corrected(a)
        n_out, n3 = a.size, 3 * self.sys.n
        q = np.full((n_out, n3), np.nan)
        qd = np.full((n_out, n3), np.nan)
        qdd = np.full((n_out, n3), np.nan)
        ok = np.zeros(n_out, bool)
        bad = np.zeros(n_out, bool)
        if conv.any():
            b, v, acc = self.rates(q_n[conv])
            q[conv], qd[conv], qdd[conv], ok[conv], bad[conv] = q_n[conv], v, acc, True, b
        out = _arrays(self.backend, self.comp, q, qd, qdd, ok, bad, self.omega_ref, self.lvl)
        return {k: v.reshape(*shape, *v.shape[1:]) for k, v in out.items()}

    def corrected(self, a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Configurations (K, 3n) at the parameters ``a`` (K,) and whether each converged.

        Predicted from the nearest regular solved step of the last :meth:`series`
        (on the sweep's branch, within :data:`MAX_SPAN`) and corrected in one stack.
        """
        phi, q_s, qd_s, qdd_s, usable = self.solved
        cand = np.flatnonzero(usable)
        n_out = a.size
        q_n = np.full((n_out, 3 * self.sys.n), np.nan)
        conv = np.zeros(n_out, bool)
        if cand.size and n_out:
            order = np.argsort(phi[cand])
            sp = phi[cand][order]
            pos = (
                np.clip(np.searchsorted(sp, a), 1, max(sp.size - 1, 1))
                if sp.size > 1
                else np.zeros(n_out, int)
            )
            if sp.size > 1:
                pos = np.where(np.abs(a - sp[pos - 1]) <= np.abs(a - sp[pos]), pos - 1, pos)
            anchor = cand[order][pos]
            h = a - phi[anchor]
            d1 = qd_s[anchor] / self.rate
            d2 = (qdd_s[anchor] - self.accel * d1) / self.rate**2
            pred = q_s[anchor] + h[:, None] * d1 + 0.5 * (h * h)[:, None] * d2
            c_line, c_ang = self.law.targets(q_s[anchor], phi[anchor], h)
            q_n, conv = _newton(
                self.rows, self.rates.keep, pred, c_line, c_ang, self.options.tol, self.options.max_iter
            )
            conv &= np.abs(h) <= self.law.span
        return q_n, conv

    def inverse_condition(self, q: np.ndarray) -> np.ndarray:
        """σ_min / σ_max of Φ_q (its square rows) at each configuration (K,); NaN where ``q`` is.

        Zero where two assembly branches meet (a change point) or at a limit.
        """
        out = np.full(q.shape[0], np.nan)
        good = np.all(np.isfinite(q), axis=1)
        if good.any():
            s = np.linalg.svd(self.rows.jacobian(q[good])[:, self.rates.keep, :], compute_uv=False)
            out[good] = s[:, -1] / s[:, 0]
        return out

    def edge(self, k: int, bad: float) -> float:
        """The last parameter reached going from solved step ``k`` toward ``bad`` (a limit: a toggle).

        Continuation toward ``bad`` with step halving: each probe is one predicted
        Newton solve from the last configuration reached, so it stays on the
        sweep's branch; a probe that fails halves the step, one that succeeds
        doubles it again (never past half the continuation's own step,
        ``law.span``, nor past half the room left), until the step is at rounding
        of the parameter: there Newton stops converging, at the toggle.  A failed
        probe never marks its parameter unreachable: one Newton solve that fails
        across a wide step says nothing about what it jumped over (bisection that
        did so put an elliptic trammel's limit, swept in steps of 40 km, at 79 mm
        instead of its rod's 200 mm).
        """
        phi, q_s = self.solved[0], self.solved[1]
        good, q = float(phi[k]), q_s[k]
        bad = float(bad)
        reach = 0.5 * self.law.span
        step = reach
        for _ in range(_EDGE_PROBES):
            h = math.copysign(min(step, 0.5 * abs(bad - good)), bad - good)
            probe = good + h
            if probe in (good, bad) or abs(h) <= 4.0 * math.ulp(max(abs(good), self.law.span)):
                break
            _, qd, _ = self.rates(q[None, :])
            c_line, c_ang = self.law.targets(q, good, np.array([h]))
            q_new, conv = _newton(
                self.rows,
                self.rates.keep,
                q[None, :] + h * qd / self.rate,
                c_line,
                c_ang,
                self.options.tol,
                self.options.max_iter,
            )
            if conv[0] and np.all(np.isfinite(qd)):
                good, q, step = probe, q_new[0], min(2.0 * abs(h), reach)
            else:
                step = 0.5 * abs(h)
        return good

    def walker(self, start: float) -> Walker:
        return Walker(self, start)


class Walker:
    """One marched continuation sent from angle to angle (the sweep's refinement probes).

    It starts where the sweep started and continues along the crank to every
    angle it is sent to, through intermediate steps of at most half
    :data:`MAX_SPAN`, so it stays on the sweep's branch (a gear train's wheel
    is where the sweep had it, not where a solve from the drawing would put
    it).  Once a step fails the walk is lost and starts again from the start.
    """

    def __init__(self, marcher: Marcher, start: float) -> None:
        self.marcher, self.start = marcher, float(start)
        self.state: tuple[float, tuple[np.ndarray, np.ndarray, np.ndarray, bool]] | None = None

    def to(self, angle: float) -> dict[str, Any] | None:
        """The sweep's arrays for one step at ``angle`` (per-step shapes), or None where not reached."""
        mr = self.marcher
        if self.state is None:
            first = mr.start(self.start)
            if first is None:
                return None
            self.state = (self.start, first)
        here, state = self.state
        pieces = max(1, math.ceil(abs(angle - here) / (0.5 * mr.law.span)))
        route = np.linspace(here, angle, pieces + 1)
        q, qd, qdd, ok, bad = mr.fill(route, 0, state)
        if not ok[-1]:
            self.state = None  # lost: the next probe starts again from the start
            return None
        self.state = (float(angle), (q[-1], qd[-1], qdd[-1], bool(bad[-1])))
        arrays = _arrays(
            mr.backend, mr.comp, q[-1:], qd[-1:], qdd[-1:], ok[-1:], bad[-1:], mr.omega_ref, mr.lvl
        )
        return {k: v[0] for k, v in arrays.items() if k not in ("assembled", "disc", "miss")}


def _walk(
    rows: System,
    rates: _Rates,
    law: _CrankLaw | LinearLaw,
    options: Any,
    phi: np.ndarray,
    k0: int,
    order: np.ndarray,
    q_all: np.ndarray,
    qd_all: np.ndarray,
    qdd_all: np.ndarray,
    ok: np.ndarray,
    bad: np.ndarray,
) -> None:
    """March from ``k0`` through the steps ``order`` (one direction), filling the arrays in place."""
    last, size, i = k0, _FIRST, 0
    anchor = None if bad[k0] else k0  # the last step with derivatives to predict from
    rate, accel = law.rate, law.accel

    def plain(h: float) -> np.ndarray | None:
        """One step from ``last`` by step-by-step continuation (its own predictor, step halving)."""
        q_new = law.plain(q_all[last], float(phi[last]), h)
        return None if q_new is None else q_new[None, :]

    while i < order.size:
        idx = order[i : i + size]
        if anchor is None:  # nothing to predict from (a singular start): one plain step
            q_acc = plain(float(phi[idx[0]] - phi[last]))
            if q_acc is None:
                return  # a limit position: nothing beyond is reached
            got, idx = 1, idx[:1]
        else:
            # predict from the last regular step, across a singular one if it came since
            q = q_all[anchor]
            d1 = qd_all[anchor] / rate
            d2 = (qdd_all[anchor] - accel * d1) / rate**2
            h = phi[idx] - phi[anchor]
            within = np.abs(h) <= law.span
            cut = idx.size if within.all() else max(1, int(np.argmin(within)))
            idx, h = idx[:cut], h[:cut]
            pred = q + h[:, None] * d1 + 0.5 * (h * h)[:, None] * d2
            c_line, c_ang = law.targets(q, float(phi[anchor]), h)
            q_acc, conv = _newton(rows, rates.keep, pred, c_line, c_ang, options.tol, options.max_iter)
            got = int(np.argmin(conv)) if not conv.all() else conv.size
            if got == 0:
                if size > 1:
                    size = max(1, size // 4)
                    continue
                # one step that does not converge from its prediction: plain continuation decides
                q_acc = plain(float(phi[idx[0]] - phi[last]))
                if q_acc is None:
                    return
                got = 1
            q_acc = q_acc[:got]
        take = idx[:got]
        b, qd, qdd = rates(q_acc)
        q_all[take], ok[take], bad[take] = q_acc, True, b
        qd_all[take], qdd_all[take] = qd, qdd
        last = int(take[-1])
        regular = take[~b]
        if regular.size:
            anchor = int(regular[-1])
        i += got
        size = min(size * 2, 4096) if got == idx.size else max(1, got)


def _c_ang(sys_: System, arow: int, c: float) -> np.ndarray:
    out = sys_.ang_c.copy()
    out[arow] = c
    return out


class _CrankLaw:
    """One crank turning about the ground: the sweep's parameter is its angle (rad).

    The drive row's target is read from the crank's own angle in ``q`` (no 2π
    ambiguity); a step the march cannot take is handed to the step-by-step
    continuation of :mod:`.solve`, and the start is reached as one solve does.
    """

    def __init__(self, mr: Marcher) -> None:
        sys_ = mr.sys
        drive = mr.drives[0]
        self.mr, self.sys = mr, sys_
        self.rate = drive.omega / mr.omega_ref  # type: ignore[operator]
        self.accel = (drive.alpha or 0.0) / mr.omega_ref**2
        self.row_rates, self.row_accels = np.array([self.rate]), np.array([self.accel])
        offset = 2 * sys_.pc_i.size + sys_.ln_s.size
        self.arow = int(sys_.drive_rows[0]) - offset  # the drive's row among the angle rows
        self.ci = 3 * sys_.link_index[drive.link] + 2
        self.span = MAX_SPAN

    def targets(self, q: np.ndarray, p: Any, h: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(line, angle) row constants for the steps ``h`` (rad) beyond the solved ``q``."""
        sys_ = self.sys
        c_ang = np.tile(sys_.ang_c, (np.size(h), 1))
        c_ang[:, self.arow] = sys_.ang_c[self.arow] + (q[..., self.ci] - sys_.q0[self.ci]) + h
        return sys_.ln_c, c_ang

    def plain(self, q: np.ndarray, p: float, h: float) -> np.ndarray | None:
        from mech.kinematics.solve import continue_along

        sys_, arow, ci = self.sys, self.arow, self.ci
        c_last = sys_.ang_c[arow] + (q[ci] - sys_.q0[ci])  # the drive row's target there
        q_new, _ = continue_along(
            sys_, q, _c_ang(sys_, arow, c_last), sys_.ln_c, [arow], np.array([h]), self.mr.options
        )
        return q_new

    def reach(self, angle: float) -> np.ndarray | None:
        from mech.kinematics.solve import move_to

        base = self.mr.options.with_(angle=angle, method="newton")
        try:
            return move_to(self.mr.comp, tuple(replace(d, angle=angle) for d in self.mr.drives), base)
        except GeometryError:
            return None


class LinearLaw:
    """Every drive linear in the sweep's parameter p: a slider drive, or several drives.

    p is the lead drive's coordinate in SI: its angle (rad) for a turning drive,
    its slider point's position along its path from the path's ``through``
    point (m) for a slider.  Drive k's row constant (its angle, relative to its
    reference; its slider's position, scaled) is ``c_k(p) = c_k,drawn + r_k (p −
    p_drawn)``: every drive is where the file draws it when the lead is, and
    moves in proportion to its speed, ``r_k`` its rate over the lead's (the
    others advance as they would in time).  Steps are limited so that no drive
    moves more than :data:`MAX_SPAN` (rad, or that fraction of the size) at once.
    """

    def __init__(self, mr: Marcher, lead: int) -> None:
        sys_, drawn = mr.sys, mr.comp.drawn
        self.mr, self.sys, self.lead = mr, sys_, lead
        scale, w = drawn.scale, mr.omega_ref
        n_pc, kl = sys_.pc_i.size, sys_.ln_s.size
        rows = sys_.drive_rows.astype(int)
        self.line = (rows >= 2 * n_pc) & (rows < 2 * n_pc + kl)  # slider drives: line rows
        self.local = np.where(self.line, rows - 2 * n_pc, rows - 2 * n_pc - kl)
        # each drive's rate in its row's units per unit of time, SI (rad/s, or scaled length per s)
        si = np.array(
            [d.omega if d.link is not None else d.speed / scale for d in mr.drives],  # type: ignore[operator]
            float,
        )
        acc = np.array(
            [(d.alpha or 0.0) if d.link is not None else (d.accel or 0.0) / scale for d in mr.drives], float
        )
        lead_si = si[lead] * (scale if self.line[lead] else 1.0)  # dp/dt: rad/s, or m/s
        self.ratio = si / lead_si  # dc_k/dp
        self.row_rates, self.row_accels = si / w, acc / w**2
        self.rate = lead_si / w  # dp/dτ
        self.accel = self.row_accels[lead] / self.ratio[lead]
        self.c0 = np.array(
            [(sys_.ln_c if ln else sys_.ang_c)[i] for ln, i in zip(self.line, self.local, strict=True)]
        )
        self.p0 = float(self.c0[lead] / self.ratio[lead]) if self.line[lead] else self.drawn_angle()
        self.span = MAX_SPAN / float(np.max(np.abs(self.ratio)))

    def drawn_angle(self) -> float:
        """The lead crank's drawn angle (rad): where its row constant stands in the drawing."""
        return float(self.mr.comp.drawn.drive_angles[self.lead])

    def targets(self, q: np.ndarray, p: Any, h: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(line, angle) row constants (K, …) at the parameters ``p + h``."""
        sys_ = self.sys
        at = p + np.atleast_1d(h)
        c = self.c0[None, :] + (at - self.p0)[:, None] * self.ratio[None, :]
        c_line = np.tile(sys_.ln_c, (at.size, 1))
        c_ang = np.tile(sys_.ang_c, (at.size, 1))
        c_line[:, self.local[self.line]] = c[:, self.line]
        c_ang[:, self.local[~self.line]] = c[:, ~self.line]
        return c_line, c_ang

    def plain(self, q: np.ndarray, p: float, h: float) -> np.ndarray | None:
        """From ``q`` at ``p`` to ``p + h`` by first-order steps, halved where Newton fails."""
        mr, done, step = self.mr, 0.0, min(abs(h), self.span)
        while abs(h - done) > 1e-14 * abs(h):
            rest = h - done
            step = rest if abs(rest) <= abs(step) else math.copysign(abs(step), rest)
            _, qd, _ = mr.rates(q[None, :])
            c_line, c_ang = self.targets(q, p + done, np.array([step]))
            pred = q[None, :] + step * qd / self.rate
            q_new, conv = _newton(
                mr.rows, mr.rates.keep, pred, c_line, c_ang, mr.options.tol, mr.options.max_iter
            )
            if not conv[0] or not np.all(np.isfinite(qd)):
                step /= 2.0
                if abs(step) < 1e-9 * self.span:
                    return None
                continue
            q, done = q_new[0], done + step
            step = min(abs(step) * 2.0, self.span)
        return q

    def reach(self, p: float) -> np.ndarray | None:
        """The configuration at ``p``, continued from the drawing (where p is ``p0``)."""
        h = p - self.p0
        return self.sys.q0.copy() if h == 0 else self.plain(self.sys.q0.copy(), self.p0, h)


def _newton(
    rows: System,
    keep: np.ndarray,
    q: np.ndarray,
    c_line: np.ndarray,
    c_ang: np.ndarray,
    tol: float,
    max_iter: int,
) -> tuple[np.ndarray, np.ndarray]:
    """Stacked Newton–Raphson; (q, converged) with converged False where a step stalls or jumps."""
    start = q
    q = q.copy()
    lost = np.zeros(q.shape[0], bool)
    prev = np.full(q.shape[0], np.inf)
    for _ in range(max_iter):
        r = rows.phi(q, c_line, c_ang)
        norm = np.max(np.abs(r), axis=1) if r.shape[1] else np.zeros(q.shape[0])
        done = norm <= tol
        lost |= ~np.isfinite(norm) | ((norm > 0.5 * prev) & (prev < 1e-3) & ~done)
        if np.all(done | lost):
            break
        prev = norm
        live = ~(done | lost)
        try:
            dq = _lin(rows.jacobian(q[live]), -r[live], keep)
        except np.linalg.LinAlgError:
            lost |= live
            break
        big = np.max(np.abs(dq), axis=1) > 1.0
        lost[np.flatnonzero(live)[big]] = True
        q[live] += np.where(big[:, None], 0.0, dq)
    # one more correction of the converged steps: within ``tol`` is only tol-accurate, and one
    # quadratic step from there lands at rounding (a prediction may start within tol already).
    # Taken only where it is tiny (< 1e-6 of the size): there it cannot make things worse.
    live = ~lost & (norm <= tol)
    if live.any():
        try:
            dq = _lin(rows.jacobian(q[live]), -r[live], keep)
        except np.linalg.LinAlgError:
            dq = np.zeros((int(live.sum()), q.shape[1]))
        small = np.max(np.abs(dq), axis=1) < 1e-6
        q[np.flatnonzero(live)[small]] += dq[small]
    jumped = np.max(np.abs(q - start), axis=1) > JUMP
    return q, (norm <= tol) & ~lost & ~jumped


def _arrays(
    backend: Any,
    comp: Any,
    q: np.ndarray,
    qd: np.ndarray,
    qdd: np.ndarray,
    ok: np.ndarray,
    bad: np.ndarray,
    omega_ref: float,
    lvl: int,
) -> dict[str, np.ndarray]:
    """The sweep's arrays (SI) from stacked scaled q, q̇, q̈: what step-by-step results would give."""
    sys_ = comp.system
    scale, (cx, cy) = sys_.scale, (float(sys_.centre[0]), float(sys_.centre[1]))
    n_steps = q.shape[0]
    where = {name: k for k, name in enumerate(sys_.loc_names)}
    pick = np.array([where[p] for p in backend.points], int)
    idx, loc = sys_.loc_i, sys_.loc_s  # every located name ('#' ones too: slides may sit on them)
    zeros = np.zeros((n_steps, 3))
    qf = np.concatenate([q, zeros], axis=1)
    th = qf[:, 3 * idx + 2]
    c, s = np.cos(th), np.sin(th)
    ox, oy = c * loc[:, 0] - s * loc[:, 1], s * loc[:, 0] + c * loc[:, 1]  # A(θ) s, scaled
    px = (qf[:, 3 * idx] + ox) * scale + cx
    py = (qf[:, 3 * idx + 1] + oy) * scale + cy
    li = np.array([sys_.link_index[lk] for lk in backend.links], int)
    res: dict[str, np.ndarray] = {
        "positions": np.stack([px[:, pick], py[:, pick]], axis=-1),
        "link_angles": np.mod(q[:, 3 * li + 2], 2 * math.pi),
        "condition": np.where(bad, np.inf, 1.0),
    }
    good = ok & ~bad
    nan_mask = ~good[:, None]
    v_unit, a_unit = scale * omega_ref, scale * omega_ref**2
    vx = vy = w = None
    if lvl >= 1:
        vf = np.concatenate([qd, zeros], axis=1)
        w = vf[:, 3 * idx + 2]
        vx = (vf[:, 3 * idx] - w * oy) * v_unit
        vy = (vf[:, 3 * idx + 1] + w * ox) * v_unit
        res["velocities"] = np.where(
            nan_mask[..., None], np.nan, np.stack([vx[:, pick], vy[:, pick]], axis=-1)
        )
        res["omegas"] = np.where(nan_mask, np.nan, qd[:, 3 * li + 2] * omega_ref)
    if lvl >= 2:
        af = np.concatenate([qdd, zeros], axis=1)
        al = af[:, 3 * idx + 2]
        w2 = w * w  # type: ignore[operator]
        ax_ = (af[:, 3 * idx] - al * oy - w2 * ox) * a_unit
        ay_ = (af[:, 3 * idx + 1] + al * ox - w2 * oy) * a_unit
        res["accelerations"] = np.where(
            nan_mask[..., None], np.nan, np.stack([ax_[:, pick], ay_[:, pick]], axis=-1)
        )
        res["alphas"] = np.where(nan_mask, np.nan, qdd[:, 3 * li + 2] * omega_ref**2)
    res["displacement"], sliding = _slides(backend, comp, qf, qd, px, py, omega_ref, lvl)
    if lvl >= 1:
        res["sliding"] = np.where(nan_mask, np.nan, sliding)
    for key in list(res):
        if key != "condition":
            shape = (n_steps,) + (1,) * (res[key].ndim - 1)
            res[key] = np.where(ok.reshape(shape), res[key], np.nan)
    res["assembled"] = ok
    res["condition"] = np.where(ok, res["condition"], np.nan)
    res["disc"] = np.where(ok, 1.0, -1.0)[:, None]
    res["miss"] = np.full((n_steps, 1), np.nan)
    return res


def _slides(
    backend: Any,
    comp: Any,
    qf: np.ndarray,
    qd: np.ndarray,
    px: np.ndarray,
    py: np.ndarray,
    omega_ref: float,
    lvl: int,
) -> tuple[np.ndarray, np.ndarray]:
    """Displacement (m) and sliding speed (m/s) at every prismatic or slot joint, per step."""
    sys_, lay, mech = comp.system, comp.layout, backend.mech
    n_steps = qf.shape[0]
    if not lay.paths:
        return np.zeros((n_steps, 0)), np.zeros((n_steps, 0))
    scale, cx, cy = sys_.scale, float(sys_.centre[0]), float(sys_.centre[1])
    where = {name: k for k, name in enumerate(sys_.loc_names)}
    n = sys_.n
    vf = np.concatenate([qd, np.zeros((n_steps, 3))], axis=1) if lvl >= 1 else None
    disp, slid = [], []
    for ps in lay.paths:
        g, u = sys_.path_dirs[ps.joint]
        th_g = qf[:, 3 * g + 2]
        ux = np.cos(th_g) * u[0] - np.sin(th_g) * u[1]
        uy = np.sin(th_g) * u[0] + np.cos(th_g) * u[1]
        point = sys_.path_points[ps.joint][1]
        at_x, at_y = px[:, where[point]], py[:, where[point]]
        through = ps.path.through
        if through.xy is not None:
            tx, ty = through.xy
        else:
            k = where[lay.resolve(through.name)]
            tx, ty = px[:, k], py[:, k]
        if ps.guide == mech.ground:
            disp.append((at_x - tx) * ux + (at_y - ty) * uy)
        else:
            disp.append(np.full(n_steps, np.nan))
        if vf is not None:
            j = next(jt for jt in mech.joints if jt.name == ps.joint)
            a, b = j.links
            rel = []
            for lk in (a, b):
                i = sys_.link_index.get(lk, n)
                ox = (qf[:, 3 * i] * scale + cx) if i < n else None
                oy = (qf[:, 3 * i + 1] * scale + cy) if i < n else None
                if i == n:  # ground: at rest
                    rel.append((np.zeros(n_steps), np.zeros(n_steps)))
                    continue
                w = vf[:, 3 * i + 2] * omega_ref
                vx = vf[:, 3 * i] * scale * omega_ref - w * (at_y - oy)
                vy = vf[:, 3 * i + 1] * scale * omega_ref + w * (at_x - ox)
                rel.append((vx, vy))
            slid.append((rel[0][0] - rel[1][0]) * ux + (rel[0][1] - rel[1][1]) * uy)
    empty = np.zeros((n_steps, 0))
    return (
        np.stack(disp, axis=-1) if disp else empty,
        np.stack(slid, axis=-1) if slid else empty,
    )
