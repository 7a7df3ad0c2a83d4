"""Moving the drawn configuration to another drive angle by Newton–Raphson continuation.

When ``--angle`` asks for another angle and the closed form does not apply,
the mechanism is *moved* there from the drawn configuration: steps of at most
15°, each predicted with the velocity solution and corrected by Newton, halved
on failure, so it stays on the drawn assembly branch.  It goes the short way
round, then the long way if a limit position blocks the short one; on the way,
a change point (det Φ_q changing sign with the loop closed on both sides) is
located and passed on the branch with a continuous tangent.  Where the angle
cannot be reached, the message names the limit and the joint left most open.
"""

from __future__ import annotations

import math

import numpy as np

from mech.errors import GeometryError, UnsupportedError
from mech.kinematics.compiled import Compiled, instant_pairs, instant_why
from mech.kinematics.constraints import System
from mech.kinematics.drives import angle_text
from mech.kinematics.geometry import wrap_angle
from mech.kinematics.linalg import square_solve
from mech.model import Drive
from mech.options import SolveOptions

__all__ = ["WATCH_MAX", "continue_along", "move_from_drawing", "move_to"]

_MAX_STEP = math.radians(15.0)
_TWO_PI = 2.0 * math.pi


def move_from_drawing(
    comp: Compiled,
    drives: tuple[Drive, ...],
    options: SolveOptions,
    targets: list[float | None],
    notes: list[str],
) -> np.ndarray:
    """q at the drives' targets by Newton continuation from the drawing; what it did goes to ``notes``."""
    sys_, drawn = comp.system, comp.drawn
    if sys_.velocity_only:
        raise UnsupportedError(
            f"cannot move {comp.mech.label} to another angle: {instant_pairs(sys_.velocity_only)} "
            f"only the instant drawn ({instant_why(comp.mech, sys_.velocity_only)})",
            hint="analyse the drawn angle, or draw the mechanism at the angle you need",
        )
    passed: list[float] = []
    q = move_to(comp, drives, options, passed)
    shown = [
        f"{angle_text(a)} → {angle_text(t)}"
        for a, t in zip(drawn.drive_angles, targets, strict=False)
        if a is not None
    ]
    notes.append(f"moved from the drawn angle by continuation ({', '.join(shown)}), keeping its branch")
    notes += [
        f"passed a change point at {math.degrees(at):.6f}° (the constraint Jacobian loses rank with the loop "
        "closed on both sides) and continued on the branch with a continuous tangent"
        for at in passed
    ]
    return q


def move_to(
    comp: Compiled, drives: tuple[Drive, ...], options: SolveOptions, passed: list[float] | None = None
) -> np.ndarray:
    """Carry the drawn configuration to the drives' target angles, keeping its branch.

    With ``passed`` (a list), the angles (rad) of the first moving drive where
    the continuation passed a change point are appended (see :func:`continue_along`).
    """
    sys_, drawn = comp.system, comp.drawn
    c_line = sys_.ln_c.copy()
    base_ang = sys_.ang_c.copy()
    offset = 2 * sys_.pc_i.size + sys_.ln_s.size
    deltas = np.zeros(len(drives))
    rows = []
    for k, (d, a) in enumerate(zip(drives, drawn.drive_angles, strict=False)):
        rows.append(sys_.drive_rows[k] - offset)
        if d.link is not None and a is not None:
            deltas[k] = wrap_angle(d.angle - a)  # type: ignore[operator]
    tries = [deltas]
    if np.count_nonzero(deltas) == 1:
        k = int(np.flatnonzero(deltas)[0])
        other = deltas.copy()
        other[k] -= math.copysign(_TWO_PI, deltas[k])
        tries.append(other)
    reached = []
    for total in tries:
        found: list[float] | None = [] if passed is not None and np.count_nonzero(total) == 1 else None
        q, fraction = continue_along(sys_, sys_.q0, base_ang, c_line, rows, total, options, found)
        if q is not None:
            if found:
                k = int(np.flatnonzero(total)[0])
                a = drawn.drive_angles[k]
                passed.extend(float(a) + f * float(total[k]) for f in found if a is not None)  # type: ignore[union-attr]
            return q
        reached.append(fraction)
    c_ang = base_ang.copy()
    c_ang[rows] += deltas
    gap, miss = _closest_gap(comp, c_line, c_ang)
    d = next(d for d in drives if d.link is not None)
    hint = "a rocker or a slider has limits: choose an angle between them (mech sweep shows them)"
    if miss <= 1e-9:
        hint = "that configuration is on another circuit: draw the mechanism there (at/near) to analyse it"
    raise GeometryError(_unreachable_message(comp, drives, reached[0], gap, miss), where=d.where, hint=hint)


def _closest_gap(comp: Compiled, c_line: np.ndarray, c_ang: np.ndarray) -> tuple[str, float]:
    """The joint left most open by the least-squares closest configuration (file's unit).

    Also returns that miss relative to the mechanism's size: about zero when the
    angle can be assembled, but only on another circuit than the drawing's.
    """
    sys_ = comp.system
    q = sys_.q0.copy()
    for _ in range(100):
        r = sys_.phi(q, c_line, c_ang)
        jac = sys_.jacobian(q)
        dq = np.linalg.lstsq(jac, -r, rcond=None)[0]
        t, norm = 1.0, float(np.linalg.norm(r))
        while t > 1e-6 and float(np.linalg.norm(sys_.phi(q + t * dq, c_line, c_ang))) >= norm:
            t /= 2
        if t <= 1e-6:
            break
        q = q + t * dq
    r = sys_.phi(q, c_line, c_ang)
    k = sys_.pc_i.size
    miss = np.concatenate([np.hypot(r[0 : 2 * k : 2], r[1 : 2 * k : 2]), np.abs(r[2 * k :])])
    names = [sys_.row_names[2 * i] for i in range(k)] + list(sys_.row_names[2 * k :])
    worst = int(np.argmax(miss))
    from mech.units import to_unit

    unit = comp.mech.length_unit
    text = f"the closest configuration leaves {names[worst]} open by {to_unit(miss[worst] * sys_.scale, unit):.4g} {unit}"
    return text, float(miss[worst])


def continue_along(
    sys_: System,
    q: np.ndarray,
    base_ang: np.ndarray,
    c_line: np.ndarray,
    rows: list[int],
    total: np.ndarray,
    options: SolveOptions,
    crossings: list[float] | None = None,
) -> tuple[np.ndarray | None, float]:
    """Step the drive angles from 0 to ``total`` (rad); returns (q, 1.0) or (None, fraction reached).

    With ``crossings`` (a list), the fractions of ``total`` where the path
    passes a singular configuration with the loop closed on both sides (a
    change point: det Φ_q changes sign between two steps) are appended,
    located by bisection; watched only on square systems of at most
    :data:`WATCH_MAX` unknowns (a determinant per step).
    """
    done, step = 0.0, min(1.0, _MAX_STEP / max(float(np.max(np.abs(total))), 1e-300))
    rhs_rows = sys_.drive_rows
    watch = crossings is not None and sys_.m == 3 * sys_.n <= WATCH_MAX
    sign = _det_sign(sys_, q) if watch else 0.0
    while done < 1.0:
        h = min(step, 1.0 - done)
        # predictor: q̇ for a unit rate along the total change
        jac = sys_.jacobian(q)
        rhs = np.zeros(sys_.m)
        rhs[rhs_rows] = total
        try:
            pred = q + h * square_solve(sys_, jac, rhs)
        except np.linalg.LinAlgError:  # a singular start (a toggle drawn): the least-squares rate
            pred = q + h * np.linalg.lstsq(jac, rhs, rcond=None)[0]
        c_ang = base_ang.copy()
        c_ang[rows] += (done + h) * total
        q_new = _newton(sys_, pred, c_line, c_ang, options)
        if q_new is None:
            step = h / 2.0
            if step * float(np.max(np.abs(total))) < 1e-7:
                return None, done
            continue
        if watch and crossings is not None:
            now = _det_sign(sys_, q_new)
            if now * sign < 0.0:  # passed a zero of det Φ_q: locate it between the two steps
                crossings.append(
                    _crossing(sys_, q, base_ang, c_line, rows, total, done, done + h, sign, options)
                )
            sign = now or sign
        q, done = q_new, done + h
        step = min(step * 2.0, 1.0)
        step = min(step, _MAX_STEP / max(float(np.max(np.abs(total))), 1e-300))
    return q, 1.0


#: Largest square system (unknowns) whose det Φ_q a single solve's continuation watches for change points.
WATCH_MAX = 120


def _det_sign(sys_: System, q: np.ndarray) -> float:
    """The sign of det Φ_q (0 where it is singular to rounding)."""
    return float(np.linalg.slogdet(sys_.jacobian(q))[0])


def _crossing(
    sys_: System,
    q: np.ndarray,
    base_ang: np.ndarray,
    c_line: np.ndarray,
    rows: list[int],
    total: np.ndarray,
    lo: float,
    hi: float,
    sign: float,
    options: SolveOptions,
) -> float:
    """The fraction of ``total`` in (lo, hi) where det Φ_q changes sign, bisected from ``q`` (at lo).

    Each probe is one predicted Newton solve from ``q``; Newton is good to about
    √tol next to the singular configuration, so the fraction is good to about that.
    """
    rhs = np.zeros(sys_.m)
    rhs[sys_.drive_rows] = total
    try:
        rate = square_solve(sys_, sys_.jacobian(q), rhs)
    except np.linalg.LinAlgError:
        return 0.5 * (lo + hi)
    start = lo
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        c_ang = base_ang.copy()
        c_ang[rows] += mid * total
        q_mid = _newton(sys_, q + (mid - start) * rate, c_line, c_ang, options)
        if q_mid is None:
            break
        if _det_sign(sys_, q_mid) * sign > 0.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def _newton(
    sys_: System, q: np.ndarray, c_line: np.ndarray, c_ang: np.ndarray, options: SolveOptions
) -> np.ndarray | None:
    """Newton–Raphson on Φ(q) = 0 (scaled); None when it does not converge quadratically."""
    prev = math.inf
    for _ in range(options.max_iter):
        r = sys_.phi(q, c_line, c_ang)
        norm = float(np.max(np.abs(r))) if r.size else 0.0
        if norm <= options.tol:
            return q
        if not math.isfinite(norm) or (norm > 0.5 * prev and prev < 1e-3):
            return None
        prev = norm
        jac = sys_.jacobian(q)
        try:
            dq = square_solve(sys_, jac, -r)
        except np.linalg.LinAlgError:
            return None
        if float(np.max(np.abs(dq))) > 1.0:  # more than a mechanism size: lost
            return None
        q = q + dq
    r = sys_.phi(q, c_line, c_ang)
    return q if float(np.max(np.abs(r))) <= options.tol else None


def _unreachable_message(
    comp: Compiled, drives: tuple[Drive, ...], reached: float | None, gap: str, miss: float
) -> str:
    d = next(d for d in drives if d.link is not None)
    a = comp.drawn.drive_angles[0]
    limit = ""
    if reached is not None and a is not None and d.angle is not None:
        stop = a + reached * wrap_angle(d.angle - a)
        limit = f"moving {d.link} from the drawn {angle_text(a)} it locks near {angle_text(stop)} (a limit position)"
    if miss <= 1e-9:  # it closes there, but not on the drawing's circuit
        return (
            f"{comp.mech.label} cannot reach {d.link} at {angle_text(d.angle)} from its drawing: "
            f"{limit or 'a limit position lies between'}; that angle belongs to another circuit "
            "(it can be assembled there only by taking the mechanism apart)"
        )
    return f"{comp.mech.label} cannot be assembled with {d.link} at {angle_text(d.angle)}: {gap}" + (
        f"; {limit}" if limit else ""
    )
