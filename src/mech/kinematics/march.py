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
continuation of :mod:`.moving`, and the march resumes after it.  Branches are
kept as continuation keeps them: every step is corrected from a prediction
off its own branch, and a correction larger than :data:`JUMP` (scaled) is
refused as a jump.

The stacked solves are :mod:`.stacked`'s, the laws that move the drives
:mod:`.march_laws`' and the arrays the sweep reads :mod:`.march_arrays`'.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from mech.kinematics.constraints import System
from mech.kinematics.drives import drives_as_used, omega_ref_of
from mech.kinematics.linalg import SINGULAR
from mech.kinematics.march_arrays import sweep_arrays
from mech.kinematics.march_laws import CrankLaw, LinearLaw
from mech.kinematics.stacked import MAX_SPAN, StackedRates, square_rows, stacked_newton

__all__ = ["MAX_SPAN", "LinearLaw", "Marcher", "Walker", "march"]

_FIRST = 8  # steps in the first stack; doubles while stacks converge whole
_EDGE_PROBES = 8192  # Newton probes one limit may take (a wide stroke walked in half-steps, then halving)


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
        comp = backend.comp
        sys_ = comp.system
        self.backend, self.comp, self.sys, self.rows = backend, comp, sys_, rows
        self.options = backend.options
        self.lvl = max(backend.lvl, 1)
        self.drives = drives_as_used(comp.mech, comp.layout, comp.drawn, self.options, self.lvl)
        self.omega_ref = omega_ref_of(self.drives, comp.drawn.scale)
        lead = getattr(backend, "lead", None)
        self.law: CrankLaw | LinearLaw = (
            CrankLaw(self) if lead is None else LinearLaw(self, lead)  # type: ignore[arg-type]
        )
        self.rate, self.accel = self.law.rate, self.law.accel
        self.rates = StackedRates(
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
        return sweep_arrays(self.backend, self.comp, q, qd, qdd, ok, bad, self.omega_ref, self.lvl)

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
        out = sweep_arrays(self.backend, self.comp, q, qd, qdd, ok, bad, self.omega_ref, self.lvl)
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
            q_n, conv = stacked_newton(
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
            q_new, conv = stacked_newton(
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
        arrays = sweep_arrays(
            mr.backend, mr.comp, q[-1:], qd[-1:], qdd[-1:], ok[-1:], bad[-1:], mr.omega_ref, mr.lvl
        )
        return {k: v[0] for k, v in arrays.items() if k not in ("assembled", "disc", "miss")}


def _walk(
    rows: System,
    rates: StackedRates,
    law: CrankLaw | LinearLaw,
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
            q_acc, conv = stacked_newton(rows, rates.keep, pred, c_line, c_ang, options.tol, options.max_iter)
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
