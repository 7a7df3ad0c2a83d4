"""The linear algebra of Φ_q: square solves, block forms of large chains, the componentwise error bound.

Shared by one solve (:mod:`.rates`, :mod:`.moving`), the compiled mechanism's
drawn checks (:mod:`.compiled`) and the stacked solves of a marched sweep
(:mod:`.stacked`): each rule is written here once.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from mech.kinematics.blocks import BlockForm, block_form
from mech.kinematics.constraints import System

__all__ = [
    "BLOCK_MIN",
    "NOISE_FACTOR",
    "SINGULAR",
    "blocks_of",
    "is_singular",
    "lin_solve",
    "padded_svd",
    "pinv",
    "refined",
    "snap_to_error",
    "square_solve",
]

#: Condition number of Φ_q (scaled) above which a configuration is refused as singular.
#: Positions near a toggle are only as accurate as ε·cond and velocities lose
#: another factor cond, so velocity errors grow like ε·cond² (measured: 2e-7 at
#: cond 7e5, 3e-5 at 7e6 on a triple-rocker approaching its limit).  1e6 keeps
#: answers to about 1e-6 relative; beyond it they would be silently wrong.
SINGULAR = 1e6

#: Two links within this sine of in line at their joint (about 1.1°) are next to a toggle, and
#: a solve says so: the closed form by its dyads' own sines, the general route by the two links
#: Φ_q's least-held motion turns (:func:`mech.kinematics.rates.near_toggle_note`).
NEAR_TOGGLE = 0.02

#: Φ_q's condition number, each equation and coordinate scaled to unit size, from which the
#: general route looks for links next to a toggle.  Near one it goes as a few over the sine
#: between the links (4.2/sin on a four-bar's coupler and rocker, 6.2/sin on a five-bar's middle
#: links, measured), so below 50 no two links are within NEAR_TOGGLE of in line.
NEAR_SINGULAR = 50.0


#: Unknowns (3 per moving link) from which square systems are solved block by block
#: (:mod:`.blocks`) rather than densely: below it one dense LU or SVD is cheaper than
#: a Python loop over the blocks.
BLOCK_MIN = 90


def blocks_of(sys_: System) -> BlockForm | None:
    """The block-triangular form of ``sys_``'s Φ_q (kept in its memo), or None: small, redundant or irreducible.

    The sparsity is read from Φ_q at the drawn configuration and at a perturbed
    one, so that an entry that happens to vanish as drawn (a link at 0°) is
    still counted.
    """
    n3 = 3 * sys_.n
    if n3 < BLOCK_MIN or sys_.m != n3:
        return None
    return sys_.memo.get("blocks", lambda: _block_form(sys_))


def _block_form(sys_: System) -> BlockForm | None:
    n3 = 3 * sys_.n
    wiggle = np.random.default_rng(0).uniform(-0.1, 0.1, n3)
    pattern = (sys_.jacobian(sys_.q0) != 0) | (sys_.jacobian(sys_.q0 + wiggle) != 0)
    form = block_form(pattern)
    if form is not None and form.largest * 2 > n3:
        form = None  # one block holds most of it: nothing to gain over the dense path
    return form


def square_solve(sys_: System, jac: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """x with Φ_q x = rhs: one LU (block by block for a large chain), least squares when not square."""
    if jac.shape[0] != jac.shape[1]:
        return np.linalg.lstsq(jac, rhs, rcond=None)[0]
    form = blocks_of(sys_)
    return form.solve(jac, rhs) if form is not None else np.linalg.solve(jac, rhs)


#: Safety factor on the first-order error bound below which a rate is shown as zero.
NOISE_FACTOR = 64.0
_EPS = float(np.finfo(float).eps)


def refined(jac: np.ndarray, solve: Callable[[np.ndarray], np.ndarray], rhs: np.ndarray) -> np.ndarray:
    """x with Φ_q x = b, improved by one step of iterative refinement.

    The SVD (or LU) leaves every component with an error of about ε times the
    largest one: on a 1e-12 m crank in a 1 m linkage, where the crank's ω is 1
    and the rod's is 4.4e-12 (scaled), that was 1e-4 of the rod's ω.  One
    refinement step x += solve(b − Φ_q x) makes the solve componentwise
    backward stable (Skeel 1980; Higham, *Accuracy and Stability of Numerical
    Algorithms*, § 12.2): each component is then good to its own size.
    """
    x = solve(rhs)
    return x + solve(rhs - jac @ x)


def pinv(svd: tuple) -> np.ndarray:
    """Φ_q⁺ = V Σ⁻¹ Uᵀ from its SVD (for the componentwise error bound)."""
    u, s, vt = svd
    return vt.T @ (u.T / s[:, None])


def snap_to_error(jac: np.ndarray, inverse: np.ndarray | None, x: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """Components of ``x`` within their own error bound of zero set to exactly zero.

    The bound is Skeel's first-order componentwise one for a refined solve,
    |δx| ≤ ε |Φ_q⁺| (|Φ_q| |x| + |b|), times :data:`NOISE_FACTOR`: each rate is
    judged against the rates and lengths it is computed from, never against the
    mechanism's fastest part, so a real 4.4e-12 rad/s beside 6.3 rad/s is kept.
    Without the inverse (a large chain solved block by block) the bound is the
    normwise one, ε·NOISE_FACTOR·max|x|·1e3 (about 1e-13 of the largest rate).
    """
    if x.size == 0:
        return x
    if inverse is None:
        floor = np.full(x.shape, 1e3 * NOISE_FACTOR * _EPS * float(np.max(np.abs(x))))
    elif x.ndim == 2:  # a stack of K solves (march): jac (K, m, n), inverse (K, n, m), x (K, n), rhs (K, m)
        bound = np.abs(jac) @ np.abs(x)[..., None] + np.abs(rhs)[..., None]
        floor = NOISE_FACTOR * _EPS * (np.abs(inverse) @ bound)[..., 0]
    else:
        floor = NOISE_FACTOR * _EPS * (np.abs(inverse) @ (np.abs(jac) @ np.abs(x) + np.abs(rhs)))
    x[np.abs(x) <= floor] = 0.0
    return x


def padded_svd(jac: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The SVD of Φ_q (thin), zero rows added when it has fewer rows than unknowns so that the null vector shows."""
    n = jac.shape[1]
    if jac.shape[0] < n:
        jac = np.vstack([jac, np.zeros((n - jac.shape[0], n))])
    u, s, vt = np.linalg.svd(jac, full_matrices=False)
    return u, s, vt


def is_singular(jac: np.ndarray, s: np.ndarray) -> bool:
    """True when Φ_q (with drive rows) does not determine q̇: fewer rows, or its singular values ``s``
    spread beyond :data:`SINGULAR`."""
    m, n = jac.shape
    if n == 0:
        return False
    if m < n:
        return True
    return bool(s[n - 1] <= s[0] / SINGULAR)


def lin_solve(svd: tuple, rhs: np.ndarray) -> np.ndarray:
    """x = V Σ⁻¹ Uᵀ b: exact for square systems, least squares for consistent redundant rows."""
    u, s, vt = svd
    return vt.T @ ((u.T @ rhs) / s)
