"""Mobility: Kutzbach's count and the true count from the rank of the constraint Jacobian.

Kutzbach's ``3(l − 1) − 2j − h`` only counts pairs; the Jacobian's rank sees
geometry: the double parallelogram (Kutzbach 0) moves (numeric 1) because one
of its constraints repeats the others.  The SVD of Φ_q (drive rows left out)
gives the rank with a tolerance scaled to its largest singular value, and
its null space says which links can move (free) and which cannot (locked).

:func:`mech.kinematics.mobility` (the rank at the drawn configuration of a file)
is :func:`mech.kinematics.compiled.mobility`: it needs the compiled system, and the
solver imports this module, never the other way round.
"""

from __future__ import annotations

import numpy as np

from mech.kinematics.blocks import BlockForm
from mech.kinematics.constraints import System
from mech.kinematics.result import Mobility
from mech.model import Mechanism
from mech.pairs import kind_of

__all__ = ["kutzbach", "numeric_mobility"]

#: singular values below this fraction of the largest count as zero (scaled units)
RANK_TOL = 1e-9
#: a null vector's component below this times the condition number is rounding (64 ε)
_NOISE = 64 * float(np.finfo(float).eps)


def kutzbach(mech: Mechanism) -> int:
    """``3(l − 1) − 2j − h``: j counts a joint of k links as k − 1; slot, cam, gear, contact are h.

    Counted once per mechanism (its memo): every solve asks it, to refuse an under-driven file
    before assembling it.
    """
    return mech.memo.get(("kutzbach",), lambda: _kutzbach(mech))


def _kutzbach(mech: Mechanism) -> int:
    j = sum(joint.equivalent_binary for joint in mech.joints if not kind_of(joint).higher)
    h = sum(1 for joint in mech.joints if kind_of(joint).higher)
    return 3 * (len(mech.links) - 1) - 2 * j - h


def numeric_mobility(
    mech: Mechanism,
    system: System,
    q: np.ndarray,
    notes: tuple[str, ...] = (),
    *,
    jacobian: np.ndarray | None = None,
    nonsingular: tuple[BlockForm, float] | None = None,
) -> Mobility:
    """Mobility of ``system`` at ``q`` from the SVD of Φ_q without drive rows.

    ``jacobian``: Φ_q at ``q`` with the drive rows, when the caller has it already.
    ``nonsingular``: the block form of that (square) Φ_q and its largest block
    condition number, when every block is regular (:mod:`.blocks`): then Φ_q's
    rows are independent, the rank without the d drive rows is exact (mobility
    d, nothing redundant), the null space is Φ_q⁻¹ applied to the drive rows'
    unit vectors, and ``condition`` is that block condition number: no SVD of the
    whole, which is cubic in the chain.
    """
    k = kutzbach(mech)
    full = system.jacobian(q) if jacobian is None else jacobian
    if nonsingular is not None:
        return _block_mobility(mech, system, full, nonsingular, notes)
    keep = np.ones(system.m, bool)
    keep[system.drive_rows] = False
    jac = full[keep]
    ncols = jac.shape[1]
    if ncols == 0:
        return Mobility(k, 0, 1.0, (), (), int(jac.shape[0]), notes)
    if jac.shape[0] == 0:
        return Mobility(k, ncols, 1.0, system.links, (), 0, notes)
    _, s, vt = np.linalg.svd(jac)
    tol = RANK_TOL * s[0] if s.size and s[0] > 0 else RANK_TOL
    rank = int(np.sum(s > tol))
    numeric = ncols - rank
    redundant = jac.shape[0] - rank
    condition = float(s[0] / s[rank - 1]) if rank else 1.0
    null = vt[rank:]
    weight = (
        np.sqrt(np.sum(null**2, axis=0)).reshape(-1, 3).max(axis=1)
        if null.size
        else np.zeros(len(system.links))
    )
    free, locked = _touched(system, weight, condition)
    extra = list(notes)
    if numeric != k:
        why = f" ({redundant} redundant constraint{'s' if redundant != 1 else ''})" if redundant else ""
        extra.append(
            f"Kutzbach's count gives {k} but the constraint Jacobian's rank gives mobility "
            f"{numeric}{why} at the drawn configuration"
        )
    return Mobility(k, numeric, condition, free, locked, redundant, tuple(extra))


def _block_mobility(
    mech: Mechanism,
    system: System,
    jac: np.ndarray,
    nonsingular: tuple[BlockForm, float],
    notes: tuple[str, ...],
) -> Mobility:
    """Mobility of a square, regular Φ_q from its block form: d drives, d freedoms, none redundant."""
    form, condition = nonsingular
    k = kutzbach(mech)
    drives = np.asarray(system.drive_rows, int)
    basis = np.empty((jac.shape[1], drives.size))
    for c, row in enumerate(drives):  # each column keeps every equation but one drive's
        unit = np.zeros(jac.shape[0])
        unit[row] = 1.0
        basis[:, c] = form.solve(jac, unit)
    null = np.linalg.qr(basis)[0] if drives.size else basis  # orthonormal: the same weights as an SVD's
    weight = np.sqrt(np.sum(null**2, axis=1)).reshape(-1, 3).max(axis=1)
    free, locked = _touched(system, weight, condition)
    extra = list(notes)
    if drives.size != k:
        extra.append(
            f"Kutzbach's count gives {k} but the constraint Jacobian's rank gives mobility "
            f"{drives.size} at the drawn configuration"
        )
    return Mobility(k, int(drives.size), condition, free, locked, 0, tuple(extra))


def _touched(system: System, weight: np.ndarray, condition: float) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """The links a null space touches (free) and those it leaves at rounding (locked).

    ``weight``: per link, the largest over its three coordinates of the null
    space's component (its orthonormal basis' root sum of squares).  A link the
    null space does not touch has components at rounding, ε·condition (Wedin's
    bound for the null space of a perturbed matrix); a fixed 1e-6 called the
    coupler of a 1e-12 m crank locked while it turns at 1.2e-12 of the crank's rate.
    """
    touch = min(1e-6, _NOISE * condition)
    free = tuple(name for name, w in zip(system.links, weight, strict=False) if w > touch)
    locked = tuple(name for name, w in zip(system.links, weight, strict=False) if w <= touch)
    return free, locked
