"""The page's data: one sweep of the mechanism, turned into what the page draws at every step.

A sweep (:func:`mech.kinematics.sweep`) gives positions, velocities and accelerations of
the points and the links' angles, ω and α at every step.  From those alone this module
makes, for each step, a :class:`~mech.kinematics.result.Kinematics` (:func:`instant`),
so that the velocity and acceleration polygons the page shows are built by the very code
that draws them in ``mech draw`` (:mod:`mech.draw.polygon`), and the numbers in the
page's table are the keys and SI values ``mech velocity --json`` gives.

The I-centres come from the velocity field of each pair of links: link i moves as
``v(P) = a_i + ω_i k×P``, so I_ij, where the two agree, is ``P = −k×(a_j − a_i)/(ω_i − ω_j)``,
at infinity (perpendicular to ``a_j − a_i``) when ω_i = ω_j.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

import numpy as np

from mech.answers import icentre_name
from mech.kinematics.result import JointGeom, Kinematics, LinkState
from mech.pairs import kind_of

if TYPE_CHECKING:  # pragma: no cover
    from mech.kinematics.sweep import Sweep
    from mech.model import Mechanism

__all__ = ["as_list", "icentres", "instant", "own_step", "round_sig"]

Vec = tuple[float, float]


def round_sig(x: float, digits: int = 7) -> float | None:
    """``x`` to ``digits`` significant figures (None for NaN): the page's numbers, small and exact enough."""
    if not math.isfinite(x):
        return None
    return float(f"{x:.{digits}g}")


def _origin(kin: Kinematics, sw: Sweep, link: str) -> int | None:
    """The index in ``sw.points`` of a point fixed in ``link`` (its state's origin)."""
    for k, name in enumerate(sw.points):
        if link in kin.carriers.get(name, ()):
            return k
    return None


def instant(
    mech: Mechanism,
    drawn: Kinematics,
    sw: Sweep,
    i: int,
    own: int = 0,
    ats: Mapping[str, Vec | None] | None = None,
) -> Kinematics:
    """The mechanism at step ``i`` of ``sw`` as a :class:`Kinematics`, carriers and joints as ``drawn``.

    Joints keep their type and links; a path's direction turns with its guide.  ``ats`` gives
    a joint's point the sweep does not carry (a cam's contact, a gear's pitch point:
    :func:`mech.view.data.contact_points`), so that ``K@cam`` is asked of the result as of a
    solve; without it such a point is left out.  ``own`` is the step drawn as ``drawn`` is
    (where the guides' directions are the drawn ones).
    """
    pos: dict[str, Vec] = {
        n: (float(x), float(y)) for n, (x, y) in zip(sw.points, sw.positions[i], strict=True)
    }
    vel = sw.velocities[i] if sw.velocities is not None else None
    acc = sw.accelerations[i] if sw.accelerations is not None else None
    links: dict[str, LinkState] = {
        mech.ground: LinkState(mech.ground, (0.0, 0.0), 0.0, (0.0, 0.0), 0.0, (0.0, 0.0), 0.0)
    }
    turned: dict[str, float] = {}
    for li, name in enumerate(sw.links):
        k = _origin(drawn, sw, name)
        angle = float(sw.link_angles[i, li])
        turned[name] = angle - float(sw.link_angles[own, li])
        origin = pos[sw.points[k]] if k is not None else (0.0, 0.0)
        links[name] = LinkState(
            name,
            origin,
            angle % (2 * math.pi),
            None if vel is None or k is None else (float(vel[k, 0]), float(vel[k, 1])),
            None if sw.omegas is None else float(sw.omegas[i, li]),
            None if acc is None or k is None else (float(acc[k, 0]), float(acc[k, 1])),
            None if sw.alphas is None else float(sw.alphas[i, li]),
        )
    joints: dict[str, JointGeom] = {}
    for name, g in drawn.joints.items():
        direction = g.direction
        if direction is not None and kind_of(g.type).role == "path":
            t = turned.get(g.links[1], 0.0)
            c, s = math.cos(t), math.sin(t)
            direction = (c * direction[0] - s * direction[1], s * direction[0] + c * direction[1])
        at = pos.get(g.point) if g.point is not None else None
        if ats is not None and ats.get(name) is not None:
            at = ats[name]
        joints[name] = JointGeom(g.name, g.type, g.links, g.point, direction, g.radius, at)
    return Kinematics(
        drawn.mechanism,
        sw.level,
        pos,
        MappingProxyType(links),
        drawn.size,
        drawn.mobility,
        (),
        drawn.drives,
        drawn.carriers,
        MappingProxyType(joints),
        mech.ground,
    )


def own_step(sw: Sweep, drawn: Kinematics) -> int:
    """The step nearest the file's own instant: where every point is nearest where ``drawn`` has it."""
    ref = np.array([drawn.positions.get(n, (np.nan, np.nan)) for n in sw.points], dtype=float)
    miss = np.nansum(np.hypot(*(sw.positions - ref[None]).transpose(2, 0, 1)), axis=1)
    miss[~sw.assembled] = np.inf
    return int(np.argmin(miss))


def icentres(mech: Mechanism, drawn: Kinematics, sw: Sweep) -> tuple[list[str], np.ndarray]:
    """Every I-centre at every step from the velocity field: names, and (N, C, 3) rows ``x, y, w``.

    ``w`` is 1 for a point, 0 for a point at infinity (``x, y`` then its direction), NaN where
    it is not defined (two links moving alike, or a step not assembled).
    """
    numbered = [lk.name for lk in mech.numbered_links]
    n = sw.angles.shape[0]
    a = np.full((n, len(numbered), 2), np.nan)
    w = np.full((n, len(numbered)), np.nan)
    for li, name in enumerate(numbered):
        if name == mech.ground:
            a[:, li], w[:, li] = 0.0, 0.0
            continue
        k = _origin(drawn, sw, name)
        if k is None or name not in sw.links or sw.velocities is None or sw.omegas is None:
            continue
        om = sw.omegas[:, sw.links.index(name)]
        p, v = sw.positions[:, k], sw.velocities[:, k]
        # a_i = v_O − ω k×O ; k×(x, y) = (−y, x)
        a[:, li, 0] = v[:, 0] + om * p[:, 1]
        a[:, li, 1] = v[:, 1] - om * p[:, 0]
        w[:, li] = om
    names: list[str] = []
    rows = []
    spin = np.nanmax(np.abs(w), axis=1, initial=0.0)
    size = drawn.size or 1.0
    for i in range(len(numbered)):
        for j in range(i + 1, len(numbered)):
            names.append(icentre_name(i + 1, j + 1))
            d = a[:, j] - a[:, i]
            dw = w[:, i] - w[:, j]
            with np.errstate(divide="ignore", invalid="ignore"):
                finite = np.abs(dw) > 1e-12 * np.maximum(spin, 1e-300)
                px, py = d[:, 1] / dw, -d[:, 0] / dw
                dn = np.hypot(d[:, 0], d[:, 1])
                moving = dn > 1e-12 * np.maximum(spin * size, 1e-300)
                ux, uy = -d[:, 1] / dn, d[:, 0] / dn
            row = np.where(
                finite[:, None],
                np.stack([px, py, np.ones(n)], axis=1),
                np.where(moving[:, None], np.stack([ux, uy, np.zeros(n)], axis=1), np.nan),
            )
            rows.append(row)
    return names, np.stack(rows, axis=1) if rows else np.zeros((n, 0, 3))


def link_members(mech: Mechanism, kin: Kinematics) -> Mapping[str, list[str]]:
    """The points each link is drawn through (as the configuration diagram draws it)."""
    from mech.draw.config import link_members as members

    return members(mech, kin)


def as_list(a: np.ndarray, digits: int = 7) -> list[Any]:
    """A nested list of rounded numbers (None for NaN) for the page's JSON."""
    if a.ndim == 0:
        return round_sig(float(a), digits)  # type: ignore[return-value]
    return [as_list(x, digits) for x in a]
