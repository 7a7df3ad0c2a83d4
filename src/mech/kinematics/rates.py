"""Velocity and acceleration at a solved configuration: Φ_q q̇ = −Φ_t and Φ_q q̈ = γ.

In scaled units (lengths / size, time × |ω|).  One SVD of Φ_q per configuration
solves both linear systems and measures its condition: above
:data:`~mech.kinematics.linalg.SINGULAR` the configuration is singular (a
toggle) and the links the null vector moves are named; velocities there are
never printed.  A slider crank at dead centre is *not* singular for a crank
drive (the slider stops, the rod's ω is finite) and solves normally.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from mech.errors import GeometryError, UnsupportedError
from mech.kinematics.compiled import Compiled, instant_pairs, instant_why
from mech.kinematics.drives import angle_text
from mech.kinematics.linalg import (
    NEAR_SINGULAR,
    NEAR_TOGGLE,
    SINGULAR,
    blocks_of,
    lin_solve,
    padded_svd,
    pinv,
    refined,
    snap_to_error,
)
from mech.model import Drive

__all__ = ["accel_rhs", "near_toggle_note", "rate_rhs", "rates"]


def rates(
    comp: Compiled, q: np.ndarray, drives: tuple[Drive, ...], lvl: int, omega_ref: float
) -> tuple[np.ndarray | None, np.ndarray | None]:
    """q̇ and q̈ (scaled) at ``q`` by the linear solves Φ_q q̇ = −Φ_t, Φ_q q̈ = γ (None above ``lvl``).

    Each solve is refined once and each component below its own error bound
    set to zero (:func:`snap_to_error`): a 1e-12 m crank on 1 m links keeps its
    4.4e-12 m/s, a pivot's 1e-17 m/s of round-off does not show.
    """
    sys_ = comp.system
    qd = qdd = None
    if lvl >= 1:
        jac = comp.jacobian if q is sys_.q0 else sys_.jacobian(q)  # not moved: Φ_q as compiled
        lin = _checked(comp, jac, drives)
        rhs = rate_rhs(comp, drives, omega_ref)
        qd = lin(rhs)
        if lvl >= 2:
            if sys_.velocity_only:
                raise UnsupportedError(
                    f"accelerations need the curvature of the profiles at {', '.join(sys_.velocity_only)}, but "
                    f"{instant_pairs(sys_.velocity_only)} only the instant drawn "
                    f"({instant_why(comp.mech, sys_.velocity_only)}); velocities are available",
                    hint="ask for velocities (mech velocity; level='velocity' from Python)",
                )
            qdd = lin(accel_rhs(comp, q, qd, drives, omega_ref))
    return qd, qdd


def rate_rhs(comp: Compiled, drives: tuple[Drive, ...], omega_ref: float) -> np.ndarray:
    """−Φ_t: the drives' rates (scaled) in their rows, zero elsewhere."""
    sys_, drawn = comp.system, comp.drawn
    rhs = np.zeros(sys_.m)
    rates = [(d.omega if d.link is not None else d.speed / drawn.scale) / omega_ref for d in drives]  # type: ignore[operator]
    rhs[sys_.drive_rows] = rates
    return rhs


def accel_rhs(
    comp: Compiled, q: np.ndarray, qd: np.ndarray, drives: tuple[Drive, ...], omega_ref: float
) -> np.ndarray:
    """γ with the drives' angular (or linear) accelerations (scaled) in their rows."""
    sys_, drawn = comp.system, comp.drawn
    gamma = sys_.gamma(q, qd)
    acc = [
        (d.alpha if d.link is not None else (d.accel or 0.0) / drawn.scale) / omega_ref**2  # type: ignore[operator]
        for d in drives
    ]
    gamma[sys_.drive_rows] += acc
    return gamma


def _checked(
    comp: Compiled, jac: np.ndarray, drives: tuple[Drive, ...]
) -> Callable[[np.ndarray], np.ndarray]:
    """A solver of Φ_q x = b at a converged configuration, after refusing a singular one.

    Rank and conditioning are judged here: by one SVD (small systems), or block by
    block for a large chain (:mod:`.blocks`); at the drawn configuration (``jac`` is
    the compiled Φ_q) by the compiled mechanism's own, made once.  The solver refines
    its answer once and zeroes what is below its error bound (:func:`snap_to_error`).
    """
    drawn = jac is comp.jacobian
    form = blocks_of(comp.system)
    if form is None:
        svd = comp.drawn_svd() if drawn else padded_svd(jac)
        n = jac.shape[1]
        if n:
            s = svd[1]
            cond = float(s[0] / s[n - 1]) if s[n - 1] > 0 else math.inf
            if cond > SINGULAR:
                balanced = equilibrated_condition(jac)
                if balanced <= SINGULAR:  # only the scales differ: no links in line
                    raise GeometryError(
                        _scaled_message(comp, cond, balanced, drives),
                        hint="give links and gears sizes within about 1e9 of each other: "
                        "velocities here would carry errors of about ε·condition",
                    )
                raise GeometryError(
                    _singular_message(comp, svd[2][n - 1], cond, drives),
                    hint="analyse a slightly different angle: velocities here are undetermined",
                    **_drawn_at(comp, drawn),
                )
        inverse = (comp.drawn_inverse() if drawn else pinv(svd)) if n else None
        return lambda rhs: snap_to_error(jac, inverse, refined(jac, lambda b: lin_solve(svd, b), rhs), rhs)
    cond, null = comp.drawn_blocks(form) if drawn else form.condition(jac)
    if cond > SINGULAR:
        raise GeometryError(
            _singular_message(comp, null, cond, drives),  # type: ignore[arg-type]
            hint="analyse a slightly different angle: velocities here are undetermined",
            **_drawn_at(comp, drawn),
        )
    return lambda rhs: snap_to_error(jac, None, refined(jac, lambda b: form.solve(jac, b), rhs), rhs)


def _drawn_at(comp: Compiled, drawn: bool) -> dict[str, Any]:
    """Where a singular configuration is the file's own doing: its drive's angle, when it is the drawn one."""
    drives = comp.mech.drives
    if not drawn or not drives or drives[0].where is None:
        return {}
    return {"where": drives[0].where, "source": comp.mech.source}


def equilibrated_condition(jac: np.ndarray) -> float:
    """Φ_q's condition number with each column, then each row, scaled to unit length.

    A toggle stays singular under any scaling (links in line lose a constraint); a
    gear ratio of 1e12, or links of 1 mm beside links of 1e9 m, make Φ_q's condition
    number huge only through its scales, and equilibration (van der Sluis) removes that.
    """
    cols = np.linalg.norm(jac, axis=0)
    scaled = jac / np.where(cols > 0, cols, 1.0)
    rows = np.linalg.norm(scaled, axis=1)
    scaled = scaled / np.where(rows > 0, rows, 1.0)[:, None]
    s = np.linalg.svd(scaled, compute_uv=False)
    n = jac.shape[1]
    return float(s[0] / s[n - 1]) if n and s[n - 1] > 0 else math.inf


def _scaled_message(comp: Compiled, cond: float, balanced: float, drives: tuple[Drive, ...]) -> str:
    """An ill-conditioned solve that is no toggle: the scales of the links or gear ratios differ."""
    where = ", ".join(
        f"{d.link} at {angle_text(d.angle)}" for d in drives if d.link is not None and d.angle is not None
    )
    at = f" ({where})" if where else ""
    return (
        f"ill-conditioned configuration of {comp.mech.label}{at}: condition number {cond:.2g}, but "
        f"{balanced:.2g} with each equation and coordinate scaled to unit size — no links are in line "
        "(not a toggle): links or gear ratios of very different scales"
    )


def _turned(comp: Compiled, v: np.ndarray) -> list[str]:
    """The links a motion ``v`` of Φ_q's (near) null space moves most, the most first."""
    sys_ = comp.system
    weight = np.abs(v).reshape(-1, 3).max(axis=1)
    return [sys_.links[i] for i in np.argsort(-weight) if weight[i] > 0.2 * weight.max()]


def near_toggle_note(comp: Compiled, q: np.ndarray) -> tuple[str, ...]:
    """The general route's note next to a toggle: which two links are close to in line, and how close.

    The closed form knows its dyads and says how far the drive is from the toggle
    (:func:`mech.kinematics.solve._near_toggle_note`); the general route (several drives, a chain
    that does not decompose) knows Φ_q.  Its least-held motion (the singular vector of the
    smallest singular value) turns the two links that lose a constraint at the toggle; when they
    are two binary links pinned together, the note gives how far from in line they are, judged
    by the same sine as the dyads' (:data:`NEAR_TOGGLE`).  Looked for only where Φ_q, scaled
    (:func:`equilibrated_condition`), is worse conditioned than :data:`NEAR_SINGULAR`; a large
    chain solved block by block has no SVD of the whole and gets no note.
    """
    sys_ = comp.system
    if blocks_of(sys_) is not None or not sys_.n:
        return ()
    jac = comp.jacobian if q is sys_.q0 else sys_.jacobian(q)
    cond = equilibrated_condition(jac)
    if cond < NEAR_SINGULAR:
        return ()
    svd = comp.drawn_svd() if q is sys_.q0 else padded_svd(jac)
    turned = _turned(comp, svd[2][jac.shape[1] - 1])
    if len(turned) != 2:
        return ()
    a, b = sorted(turned, key=sys_.links.index)  # in the file's order
    grows = (
        f"where velocities grow without bound (condition number {cond:.3g}, scaled; "
        f"refused from 1e{round(math.log10(SINGULAR))})"
    )
    lay = comp.layout
    pinned = [n for n in lay.on_link.get(a, ()) if b in lay.carriers.get(n, ()) and not n.startswith("#")]
    ends = [[n for n in lay.on_link.get(k, ()) if not n.startswith("#")] for k in (a, b)]
    if len(pinned) != 1 or any(len(e) != 2 or not set(e) <= sys_.local.keys() for e in ends):
        # no two bars to measure: judged by the condition alone, where the measured four-bar and
        # five-bar reach NEAR_TOGGLE (about 5/sin, see NEAR_SINGULAR)
        return (
            (f"next to a toggle: {a} and {b} are close to in line, {grows}",)
            if cond * NEAR_TOGGLE >= 5
            else ()
        )
    joint = pinned[0]
    p, u, w = (_scaled_at(sys_, q, n) for n in (joint, *(n for e in ends for n in e if n != joint)))
    d1, d2 = u - p, w - p
    sine = abs(float(d1[0] * d2[1] - d1[1] * d2[0])) / (float(np.hypot(*d1) * np.hypot(*d2)) or 1.0)
    if sine >= NEAR_TOGGLE:
        return ()
    return (
        f"next to a toggle: {a} and {b} are {math.degrees(math.asin(sine)):.3g}° from in line at {joint}, {grows}",
    )


def _scaled_at(sys_: Any, q: np.ndarray, name: str) -> np.ndarray:
    """Where location ``name`` is at ``q`` (scaled coordinates, on its carrier)."""
    i, s = sys_.local[name]
    if i >= sys_.n:  # on the ground: its local coordinates are global
        return np.asarray(s, dtype=float)
    x, y, th = q[3 * i : 3 * i + 3]
    c, sn = math.cos(th), math.sin(th)
    return np.array([x + c * s[0] - sn * s[1], y + sn * s[0] + c * s[1]])


def _singular_message(comp: Compiled, v: np.ndarray, cond: float, drives: tuple[Drive, ...]) -> str:
    moving = _turned(comp, v)
    where = ", ".join(
        f"{d.link} at {angle_text(d.angle)}" for d in drives if d.link is not None and d.angle is not None
    )
    at = f" ({where})" if where else ""
    if len(moving) == 2:
        what = f"{moving[0]} and {moving[1]} are in line"
    elif len(moving) == 1:
        what = f"{moving[0]} is not held by its joints"
    else:
        what = f"{', '.join(moving)} can move with the drive held (links in line)"
    return (
        f"singular configuration of {comp.mech.label}{at}: {what} — a toggle or dead-centre "
        f"position (condition number {cond:.2g})"
    )
