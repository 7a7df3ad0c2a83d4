"""How a marched sweep's parameter moves the drives: one crank, or every drive linear in it.

A law gives the row constants (the drives' targets) at parameters beyond a solved
configuration (``targets``), one step by plain continuation where the march cannot
take it (``plain``), and the start reached from the drawing (``reach``); with it the
rates of the parameter (``rate``, ``accel``, per drive ``row_rates``,
``row_accels``) and the largest step (``span``).
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any, Protocol

import numpy as np

from mech.errors import GeometryError
from mech.kinematics.compiled import Compiled
from mech.kinematics.constraints import System
from mech.kinematics.moving import continue_along, move_to
from mech.kinematics.stacked import MAX_SPAN, StackedRates, stacked_newton
from mech.model import Drive

__all__ = ["CrankLaw", "LinearLaw", "Marching"]


class Marching(Protocol):
    """What a law reads of the march it drives (:class:`~mech.kinematics.march.Marcher`)."""

    comp: Compiled
    sys: System
    rows: System
    drives: tuple[Drive, ...]
    omega_ref: float
    options: Any
    rates: StackedRates


def _c_ang(sys_: System, arow: int, c: float) -> np.ndarray:
    out = sys_.ang_c.copy()
    out[arow] = c
    return out


class CrankLaw:
    """One crank turning about the ground: the sweep's parameter is its angle (rad).

    The drive row's target is read from the crank's own angle in ``q`` (no 2π
    ambiguity); a step the march cannot take is handed to the step-by-step
    continuation of :mod:`.moving`, and the start is reached as one solve does.
    """

    def __init__(self, mr: Marching) -> None:
        sys_ = mr.sys
        drive = mr.drives[0]
        assert drive.link is not None  # Marcher.make: a crank law's one drive turns
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
        sys_, arow, ci = self.sys, self.arow, self.ci
        c_last = sys_.ang_c[arow] + (q[ci] - sys_.q0[ci])  # the drive row's target there
        q_new, _ = continue_along(
            sys_, q, _c_ang(sys_, arow, c_last), sys_.ln_c, [arow], np.array([h]), self.mr.options
        )
        return q_new

    def reach(self, angle: float) -> np.ndarray | None:
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

    def __init__(self, mr: Marching, lead: int) -> None:
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
            np.float64,
        )
        acc = np.array(
            [(d.alpha or 0.0) if d.link is not None else (d.accel or 0.0) / scale for d in mr.drives],
            np.float64,
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
        angle = self.mr.comp.drawn.drive_angles[self.lead]
        assert angle is not None  # a turning drive's angle is read from the drawing if not given
        return float(angle)

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
            q_new, conv = stacked_newton(
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
