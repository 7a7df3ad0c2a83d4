"""Coupler curves and centrodes: loci traced over the crank's cycle.

* The **path** of a point (a coupler curve) is its position at every step of a
  sweep; its extent (least and greatest x and y, with the crank angles) comes
  from the sweep's refined extremes of ``position.P.x`` and ``position.P.y``.
* The **fixed centrode** of a link is the locus of its I-centre relative to the
  ground (I_1k), in the ground's frame; the **moving centrode** the same
  I-centre seen from the link, in the link's own frame.  The two roll on each
  other without slipping, touching at the current I-centre (Uicker, Pennock &
  Shigley, *Theory of Machines and Mechanisms*, § 3.21).  At each step the
  I-centre follows from any point P of the link and its velocity:
  I = P + k × v_P / ω (where ω = 0 the link translates and the centre is at
  infinity: the curve breaks there).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from mech.errors import InputError
from mech.model import Mechanism
from mech.options import SolveOptions
from mech.pairs import points_of

__all__ = ["Centrodes", "PointPath", "centrodes", "point_path"]

Vec = tuple[float, float]


@dataclass(frozen=True)
class PointPath:
    """The path of ``point`` over the sweep: (N, 2) positions (m, NaN where not assembled).

    ``extent`` is (x_min, x_max, y_min, y_max) in m, ``extent_angles`` the drive
    angles (rad) where each is reached, refined between steps.
    """

    point: str
    angles: Any
    xy: Any
    extent: tuple[float, float, float, float]
    extent_angles: tuple[float, float, float, float]


@dataclass(frozen=True)
class Centrodes:
    """The fixed and moving centrodes of ``link`` over the sweep.

    ``fixed``: (N, 2) I_1k in the ground frame (m); ``moving``: (N, 2) the same
    points in the link's frame (origin at ``origin`` point of the link, x along
    the link's angle); ``moving_now``: the moving centrode carried by the link
    to where it is at the instant ``now`` (the drive angle, rad), to draw beside
    the fixed one.  NaN where the link translates (centre at infinity) or the
    chain is not assembled.
    """

    link: str
    origin: str
    angles: Any
    fixed: Any
    moving: Any
    moving_now: Any
    now: float


def _angles(steps: int) -> Any:
    import numpy as np

    return np.linspace(0.0, 2.0 * math.pi, steps + 1)


def point_path(
    mech: Mechanism, point: str, *, options: SolveOptions | None = None, steps: int = 360
) -> PointPath:
    """The path of a point over one turn of the crank, and its extent.

    Raises
    ------
    InputError
        ``point`` is not a point the sweep solves.
    """
    from mech.kinematics import sweep

    options = (options or SolveOptions()).with_(angle=None)
    keys = [f"position.{point}.x", f"position.{point}.y"]
    sw = sweep(mech, _angles(steps), level="position", options=options, quantities=keys)
    xy = sw.positions[:, sw.points.index(point), :]
    ext = {e.quantity: e for e in sw.extremes}
    lims: list[float] = []
    where: list[float] = []
    for key, col in zip(keys, (0, 1), strict=True):
        e = ext.get(key)
        if e is None:  # constant over the cycle (a pivot)
            value = float(xy[0, col])
            lims += [value, value]
            where += [0.0, 0.0]
        else:
            lims += [e.min_value, e.max_value]
            where += [e.min_angle, e.max_angle]
    return PointPath(point, sw.angles, xy, tuple(lims), tuple(where))  # type: ignore[arg-type]


def centrodes(
    mech: Mechanism, link: str, *, options: SolveOptions | None = None, steps: int = 360
) -> Centrodes:
    """The fixed and moving centrodes of ``link`` over one turn of the crank.

    Raises
    ------
    InputError
        ``link`` is the ground, unknown, or has no located point.
    """
    import numpy as np

    from mech.kinematics import solve, sweep

    names = {lk.name for lk in mech.links}
    if link not in names:
        raise InputError(f"no link named {link}", hint=f"choose from {', '.join(sorted(names))}")
    if link == mech.ground:
        raise InputError("the ground has no centrodes: it does not move")
    options = options or SolveOptions()
    if options.omega is None and not any(d.omega is not None for d in mech.drives):
        options = options.with_(omega=1.0)  # the loci do not depend on the speed
    now_kin = solve(mech, "position", options.with_(omega=None, direction=None, alpha=None))
    sw = sweep(mech, _angles(steps), level="velocity", options=options.with_(angle=None), quantities=())
    origin = next((p for p in points_of(mech, link) if p in sw.points), None)
    if origin is None or link not in sw.links:
        raise InputError(f"{link} has no located point to trace its centrodes from")
    k = sw.points.index(origin)
    p = sw.positions[:, k, :]
    v = sw.velocities[:, k, :]  # type: ignore[index]
    w = sw.omegas[:, sw.links.index(link)]  # type: ignore[index]
    scale = np.nanmax(np.abs(w)) if np.any(np.isfinite(w)) else 1.0
    with np.errstate(divide="ignore", invalid="ignore"):
        turning = np.abs(w) > 1e-9 * scale
        fixed = np.where(turning[:, None], p + np.stack([-v[:, 1], v[:, 0]], axis=1) / w[:, None], np.nan)
    phi = sw.link_angles[:, sw.links.index(link)]
    d = fixed - p
    c, s = np.cos(phi), np.sin(phi)
    moving = np.stack([c * d[:, 0] + s * d[:, 1], -s * d[:, 0] + c * d[:, 1]], axis=1)
    p_now = np.array(now_kin.positions[origin])
    phi_now = float(now_kin.links[link].angle)
    # the sweep's link angle and the solve's are the same frame angle (both θ of the link)
    cn, sn = math.cos(phi_now), math.sin(phi_now)
    moving_now = np.stack(
        [p_now[0] + cn * moving[:, 0] - sn * moving[:, 1], p_now[1] + sn * moving[:, 0] + cn * moving[:, 1]],
        axis=1,
    )
    drive = now_kin.drives[0]
    return Centrodes(link, origin, sw.angles, fixed, moving, moving_now, float(drive.angle or 0.0))
