"""The sweep's arrays (SI) from a march's stacked scaled q, q̇, q̈: what step-by-step results would give.

Positions and velocities of the named points, link angles and rates, each
prismatic or slot joint's displacement and sliding speed; steps not solved are
NaN, singular ones keep their positions only.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["point_or_nan", "sweep_arrays"]


def sweep_arrays(
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
    extra = tuple(getattr(backend, "extra", ()))
    pick = np.array([where[p] for p in backend.points if p not in extra], int)
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
    if extra:  # a link's point at a contact (K@cam), after the located points
        more = _contact_columns(extra, comp, q, qd, qdd, ok, good, omega_ref, lvl)
        for key, arr in zip(("positions", "velocities", "accelerations"), more, strict=True):
            if key in res:
                res[key] = np.concatenate([res[key], arr], axis=1)
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


def _contact_columns(
    names: tuple[str, ...],
    comp: Any,
    q: np.ndarray,
    qd: np.ndarray,
    qdd: np.ndarray,
    ok: np.ndarray,
    good: np.ndarray,
    omega_ref: float,
    lvl: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Position, velocity and acceleration (SI) of each ``K@link`` per step, NaN where not solved.

    Where a higher pair touches moves along both profiles, so it is no located point of
    the system: each step's result is packaged (:func:`~.result_fields.result`) and asked,
    as a single solve is — one truth for where the contact is and how each link's point
    there moves.  Only the points a sweep is asked for pay this.
    """
    from mech.kinematics.result_fields import result

    levels = ("position", "velocity", "acceleration")
    shape = (q.shape[0], len(names), 2)
    pos, vel, acc = np.full(shape, np.nan), np.full(shape, np.nan), np.full(shape, np.nan)
    for k in np.flatnonzero(ok):
        use = lvl if good[k] else 0
        kin = result(
            comp,
            levels[use],
            q[k],
            qd[k] if use >= 1 else None,
            qdd[k] if use >= 2 else None,
            omega_ref,
            True,
            (),
            (),
        )
        for i, name in enumerate(names):
            pos[k, i] = kin.position(name)
            if use >= 1:
                vel[k, i] = kin.velocity(name)
            if use >= 2:
                acc[k, i] = point_or_nan(kin.acceleration, name)
    return pos, vel, acc


def point_or_nan(read: Any, name: str) -> tuple[float, float]:
    """A point's vector, or NaN where it has none of its own (a rolling pair's pitch point has
    one velocity but two accelerations: asked for its velocity, its acceleration is not given)."""
    from mech.errors import InputError

    try:
        return read(name)  # type: ignore[no-any-return]
    except InputError:
        return (math.nan, math.nan)


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
