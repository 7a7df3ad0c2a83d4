"""Solves of K configurations at once, on the constraint system's stacked rows.

What a marched sweep (:mod:`.march`) and its laws of motion (:mod:`.march_laws`)
share: the square subset of rows that determines q̇ (:func:`square_rows`),
Newton–Raphson on a stack of predictions (:func:`stacked_newton`), and the
velocities and accelerations of a stack with each step's conditioning judged as
one solve judges it (:class:`StackedRates`).  The residual, Jacobian and γ are
the constraint system's own (:class:`~mech.kinematics.constraints.System`),
written once with a leading batch axis.
"""

from __future__ import annotations

import math

import numpy as np

from mech.kinematics.constraints import System
from mech.kinematics.linalg import snap_to_error

__all__ = ["JUMP", "MAX_SPAN", "StackedRates", "square_rows", "stacked_newton"]

#: Largest crank angle one stack may span (rad); continuation's own step limit.
MAX_SPAN = math.radians(15.0)
#: Largest Newton correction (scaled: fractions of the mechanism's size) accepted for a step.
JUMP = 0.05


def square_rows(sys_: System) -> np.ndarray | None:
    """Rows of Φ_q that determine q̇ on their own (drive rows first), or None when there are too many.

    A redundant system (a double parallelogram: 13 rows, 12 unknowns) is
    consistent, so a square subset of independent rows gives the same
    solutions; chosen once, at the drawn configuration, greedily by rank.
    Along the sweep a step where the subset is ill-conditioned is solved on
    all rows instead (see :class:`StackedRates`).
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


class StackedRates:
    """Velocities and accelerations of stacked configurations: one stacked inverse of Φ_q each.

    Conditioning is judged once per step: the 1-norm condition number from
    the inverse bounds the 2-norm one within a factor n either way, so only
    steps within that factor of :data:`~mech.kinematics.linalg.SINGULAR` are
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
        (:func:`~mech.kinematics.linalg.snap_to_error`): a 1e-12 m crank on 1 m
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


def stacked_newton(
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
