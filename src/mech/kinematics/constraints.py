"""Constraint equations Φ(q, t) = 0 in reference-point coordinates, with Jacobian and γ.

Each moving link ``i`` has coordinates ``q[3i:3i+3] = (x, y, θ)``: the global
position of its origin (its first located point, a ground pivot where it has
one) and the angle of its reference line (origin → its next located point),
so the crank's θ *is* the crank angle.  A point of link ``i`` with local
coordinates ``s`` is at ``r = R + A(θ) s``.  Ground is a link with ``q = 0``
appended as index ``n`` so that every row is written once, without cases.

Rows, in this order (Haug, *Computer-Aided Kinematics and Dynamics*, ch. 3;
Nikravesh, *Computer-Aided Analysis of Mechanical Systems*, ch. 4):

* point coincidence (2 rows): a revolute joint, per extra link;
  ``r_i(P) − r_j(P) = 0``.  Rolling contact uses the same rows at velocity level.
* point on line (1 row): ``n_G · (r_S(P) − r_G(T)) = c`` — a prismatic or slot
  joint's point on its path (``c = 0``); a slider drive (with the path
  direction for ``n`` and ``c`` the displacement); a cam, contact or gear pair
  at velocity level (the contact point stays on the common tangent).
* linear angle rows: ``Σ a_k θ_k = c`` — a prismatic joint's constant relative
  angle, a rotary drive (``θ_D − θ_ref = φ(t)``), a gear pair with fixed centres
  on one carrier (``r₁(θ₁ − θ_c) ± r₂(θ₂ − θ_c) = c``).

Velocity-level rows (cam, contact, rolling, gear without a common carrier)
are the first-order part of the contact condition at the instant drawn: they
enter velocity solves and the mobility rank but never Newton, and make
acceleration impossible without curvature data.

Everything is scaled: lengths by ``scale`` (the drawn size), time by
``1/omega_ref``; index arrays are built once so that a residual, Jacobian or
γ is a dozen vectorised numpy operations whatever the mechanism.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import field

import numpy as np

from mech._memo import Memo
from mech._records import dataclass
from mech.errors import collect
from mech.kinematics.assemble import Drawn
from mech.kinematics.layout import Layout
from mech.kinematics.rows import Build
from mech.pairs import kind_of
from mech.pairs.curves import CurveRow, curve_rows
from mech.pairs.path import PathSpec, path_angle
from mech.pairs.rows import Angle, Distance, Law, Locator, OnLine

__all__ = ["System", "build_system"]


@dataclass(eq=False)
class System:
    """The compiled constraint system of one mechanism at its drawn configuration.

    Mutable only while being built; the solvers treat it as read-only (drive
    targets are passed in, never stored).

    Shapes: ``n`` moving links, ``q`` is (3n,), rows ``m``; Jacobians are (m, 3n).
    """

    links: tuple[str, ...]  # moving links, q order; ground is index n
    ground: str
    scale: float  # m
    centre: np.ndarray  # (2,) m: the global origin of scaled coordinates
    q0: np.ndarray  # (3n,) drawn configuration, scaled
    local: dict[str, tuple[int, np.ndarray]]  # location -> (link index, local s (2,)) for one carrier
    frames: dict[str, str]  # link -> name of its origin location ('' when none)
    contact_xy: dict[str, np.ndarray]  # contact points of the instant, scaled global
    # point coincidence rows
    pc_i: np.ndarray = field(default_factory=lambda: np.zeros(0, int))
    pc_si: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    pc_j: np.ndarray = field(default_factory=lambda: np.zeros(0, int))
    pc_sj: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    # point-on-line rows
    ln_s: np.ndarray = field(default_factory=lambda: np.zeros(0, int))
    ln_sp: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    ln_g: np.ndarray = field(default_factory=lambda: np.zeros(0, int))
    ln_t: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    ln_n: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    ln_c: np.ndarray = field(default_factory=lambda: np.zeros(0))
    ln_k: np.ndarray | None = None  # per row: coefficient of θ_slider − θ_guide (rolling); None: all 0
    ln_law: tuple[tuple[int, Law], ...] = ()  # (line row, law): a follower moved by its cam's programme
    # linear angle rows: a (k, n+1) on θ of all links (ground last), constant c
    ang_a: np.ndarray = field(default_factory=lambda: np.zeros((0, 1)))
    ang_c: np.ndarray = field(default_factory=lambda: np.zeros(0))
    # distance rows (after the angle rows): ½(|r_i(P) − r_j(Q)|² − d²) = 0
    ds_i: np.ndarray = field(default_factory=lambda: np.zeros(0, int))
    ds_si: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    ds_j: np.ndarray = field(default_factory=lambda: np.zeros(0, int))
    ds_sj: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    ds_d: np.ndarray = field(default_factory=lambda: np.zeros(0))
    # curve rows (last): a closed spline profile against a point or a line (mech.kinematics.curves)
    cv: tuple[CurveRow, ...] = ()
    # bookkeeping
    locators: dict[str, Locator] = field(default_factory=dict)  # moving contact point from q (scaled)
    normals: dict[str, Locator] = field(default_factory=dict)  # its common normal (unit) from q
    contact_points: dict[str, Locator] = field(
        default_factory=dict
    )  # a pair's contact, its location elsewhere
    row_names: tuple[str, ...] = ()  # per row: the joint or drive it comes from
    notes: tuple[str, ...] = ()  # what the rows approximate (a fitted profile), for every result
    holonomic: np.ndarray = field(default_factory=lambda: np.zeros(0, bool))  # per row
    drive_rows: np.ndarray = field(default_factory=lambda: np.zeros(0, int))  # row per drive (file order)
    path_dirs: dict[str, tuple[int, np.ndarray]] = field(
        default_factory=dict
    )  # path joint -> (guide, local u)
    path_points: dict[str, tuple[int, str]] = field(default_factory=dict)  # path joint -> (slider, point)
    # every location fixed in a link, as arrays for one-shot unscaling of results
    loc_names: tuple[str, ...] = ()
    loc_i: np.ndarray = field(default_factory=lambda: np.zeros(0, int))
    loc_s: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    link_index: dict[str, int] = field(default_factory=dict)
    joint_names: frozenset[str] = frozenset()  # located joints (for the size)
    velocity_only: tuple[str, ...] = ()  # joints modelled only at velocity level (cam, contact, rolling …)
    #: What the solvers derive from the system once (block form, stacked rows): :class:`mech._memo.Memo`.
    memo: Memo = field(default_factory=Memo, repr=False)

    @property
    def n(self) -> int:
        return len(self.links)

    @property
    def m(self) -> int:
        return 2 * self.pc_i.size + self.ln_s.size + self.ang_c.size + self.ds_d.size + len(self.cv)

    # -- kinematic functions (scaled), written once with a batch axis -------------------------
    # Every function takes q as (3n,) for one configuration or (K, 3n) for K at once (a sweep's
    # stack); one configuration is a batch of one, and the answer drops the batch axis again.
    def _full(self, q: np.ndarray) -> np.ndarray:
        """q (K, 3n) with ground's three zeros appended: (K, 3n + 3)."""
        qf = np.zeros((q.shape[0], q.shape[1] + 3))
        qf[:, :-3] = q
        return qf

    @staticmethod
    def _trig(qf: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """cos and sin of every link's angle (K, n + 1), taken once per configuration."""
        th = qf[:, 2::3]
        return np.cos(th), np.sin(th)

    @staticmethod
    def _rot(
        trig: tuple[np.ndarray, np.ndarray], idx: np.ndarray, s: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """A(θ) s for the links ``idx`` (K, len(idx))."""
        c, sn = trig[0][:, idx], trig[1][:, idx]
        return c * s[:, 0] - sn * s[:, 1], sn * s[:, 0] + c * s[:, 1]

    def _line(self, trig: tuple[np.ndarray, np.ndarray], qf: np.ndarray) -> tuple[np.ndarray, ...]:
        """Of the point-on-line rows: A_S s, A_G t, A_G n and d = r_S(P) − r_G(T) (each (K, rows))."""
        sx, sy = self._rot(trig, self.ln_s, self.ln_sp)
        tx, ty = self._rot(trig, self.ln_g, self.ln_t)
        nx, ny = self._rot(trig, self.ln_g, self.ln_n)
        dx = qf[:, 3 * self.ln_s] + sx - qf[:, 3 * self.ln_g] - tx
        dy = qf[:, 3 * self.ln_s + 1] + sy - qf[:, 3 * self.ln_g + 1] - ty
        return sx, sy, tx, ty, nx, ny, dx, dy

    def _distance(self, trig: tuple[np.ndarray, np.ndarray], qf: np.ndarray) -> tuple[np.ndarray, ...]:
        """d = r_i(P) − r_j(Q) of the distance rows (K, rows), with A_i s_i and A_j s_j."""
        ax, ay = self._rot(trig, self.ds_i, self.ds_si)
        bx, by = self._rot(trig, self.ds_j, self.ds_sj)
        i3, j3 = 3 * self.ds_i, 3 * self.ds_j
        dx = qf[:, i3] + ax - qf[:, j3] - bx
        dy = qf[:, i3 + 1] + ay - qf[:, j3 + 1] - by
        return dx, dy, ax, ay, bx, by

    def _laws(self, qf: np.ndarray) -> list[tuple[int, Law, tuple[np.ndarray, np.ndarray, np.ndarray]]]:
        """Each programme row's place among the line rows, its law and h, h′, h″ at the cam's turn (K,)."""
        out = []
        for r, law in self.ln_law:
            phi = law.phi0 + law.sense * (qf[:, 3 * law.cam + 2] - qf[:, 3 * int(self.ln_g[r]) + 2])
            out.append((r, law, law.lift(phi)))
        return out

    def phi(self, q: np.ndarray, c_line: np.ndarray, c_ang: np.ndarray) -> np.ndarray:
        """Φ (m,) or (K, m) for the given line and angle constants (drive targets inside; (rows,) or (K, rows))."""
        one = q.ndim == 1
        qf = self._full(np.atleast_2d(q))
        trig = self._trig(qf)
        out = np.empty((qf.shape[0], self.m))
        k, kl, ka, kd = self.pc_i.size, self.ln_s.size, self.ang_c.size, self.ds_d.size
        ax, ay = self._rot(trig, self.pc_i, self.pc_si)
        bx, by = self._rot(trig, self.pc_j, self.pc_sj)
        out[:, 0 : 2 * k : 2] = qf[:, 3 * self.pc_i] + ax - qf[:, 3 * self.pc_j] - bx
        out[:, 1 : 2 * k : 2] = qf[:, 3 * self.pc_i + 1] + ay - qf[:, 3 * self.pc_j + 1] - by
        r = 2 * k
        if kl:
            _, _, _, _, nx, ny, dx, dy = self._line(trig, qf)
            out[:, r : r + kl] = nx * dx + ny * dy - c_line
            if self.ln_k is not None:  # rolling: the arc rolled, k (θ_slider − θ_guide)
                out[:, r : r + kl] += self.ln_k * (qf[:, 3 * self.ln_s + 2] - qf[:, 3 * self.ln_g + 2])
            for row, law, (h, _, _) in self._laws(qf):
                out[:, r + row] -= law.w * h
        r += kl
        out[:, r : r + ka] = qf[:, 2::3] @ self.ang_a.T - c_ang
        r += ka
        if kd:
            dx, dy, _, _, _, _ = self._distance(trig, qf)
            out[:, r : r + kd] = 0.5 * (dx * dx + dy * dy - self.ds_d**2)
        for k_cv, cv in enumerate(self.cv):  # a profile's rows: nearest points found for all K at once
            out[:, r + kd + k_cv] = curve_rows(cv, qf)[0]
        return out[0] if one else out

    def jacobian(self, q: np.ndarray, *, ground: bool = False) -> np.ndarray:
        """Φ_q (m, 3n) or (K, m, 3n); with ``ground``, the ground's three columns too (3n + 3): a
        force analysis reads from them what the pairs put on the frame."""
        one = q.ndim == 1
        qf = self._full(np.atleast_2d(q))
        trig = self._trig(qf)
        jac = np.zeros((qf.shape[0], self.m, qf.shape[1]))
        k, kl, ka, kd = self.pc_i.size, self.ln_s.size, self.ang_c.size, self.ds_d.size
        if k:
            ax, ay = self._rot(trig, self.pc_i, self.pc_si)
            bx, by = self._rot(trig, self.pc_j, self.pc_sj)
            rx = np.arange(0, 2 * k, 2)
            ry = rx + 1
            i3, j3 = 3 * self.pc_i, 3 * self.pc_j
            jac[:, rx, i3] = 1.0
            jac[:, ry, i3 + 1] = 1.0
            jac[:, rx, i3 + 2] = -ay
            jac[:, ry, i3 + 2] = ax
            jac[:, rx, j3] = -1.0
            jac[:, ry, j3 + 1] = -1.0
            jac[:, rx, j3 + 2] = by
            jac[:, ry, j3 + 2] = -bx
        r0 = 2 * k
        if kl:
            rows = np.arange(r0, r0 + kl)
            sx, sy, tx, ty, nx, ny, dx, dy = self._line(trig, qf)
            s3, g3 = 3 * self.ln_s, 3 * self.ln_g
            jac[:, rows, s3] = nx
            jac[:, rows, s3 + 1] = ny
            jac[:, rows, s3 + 2] = -nx * sy + ny * sx
            jac[:, rows, g3] = -nx
            jac[:, rows, g3 + 1] = -ny
            jac[:, rows, g3 + 2] = (-ny * dx + nx * dy) - (-nx * ty + ny * tx)
            if self.ln_k is not None:
                _add_at(jac, rows, s3 + 2, np.broadcast_to(self.ln_k, (qf.shape[0], kl)))
                _add_at(jac, rows, g3 + 2, np.broadcast_to(-self.ln_k, (qf.shape[0], kl)))
            for row, law, (_, h1, _) in self._laws(qf):
                g = 3 * int(self.ln_g[row]) + 2
                jac[:, r0 + row, 3 * law.cam + 2] -= law.w * law.sense * h1
                jac[:, r0 + row, g] += law.w * law.sense * h1
        r0 += kl
        if ka:
            jac[:, r0 : r0 + ka, 2::3] = self.ang_a
        r0 += ka
        if kd:
            rows = np.arange(r0, r0 + kd)
            dx, dy, ax, ay, bx, by = self._distance(trig, qf)
            i3, j3 = 3 * self.ds_i, 3 * self.ds_j
            _add_at(jac, rows, i3, dx)
            _add_at(jac, rows, i3 + 1, dy)
            _add_at(jac, rows, i3 + 2, -dx * ay + dy * ax)
            _add_at(jac, rows, j3, -dx)
            _add_at(jac, rows, j3 + 1, -dy)
            _add_at(jac, rows, j3 + 2, dx * by - dy * bx)
        r0 += kd
        for k_cv, cv in enumerate(self.cv):
            for col, v in curve_rows(cv, qf)[1].items():
                jac[:, r0 + k_cv, col] += v
        if not ground:
            jac = jac[:, :, :-3]
        return jac[0] if one else jac

    def gamma(self, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        """γ (m,) or (K, m) without drive accelerations: Φ_q q̈ = γ + (drive α rows)."""
        one = q.ndim == 1
        qf, vf = self._full(np.atleast_2d(q)), self._full(np.atleast_2d(qd))
        trig = self._trig(qf)
        out = np.zeros((qf.shape[0], self.m))
        k, kl, kd, kc = self.pc_i.size, self.ln_s.size, self.ds_d.size, len(self.cv)
        if k:
            ax, ay = self._rot(trig, self.pc_i, self.pc_si)
            bx, by = self._rot(trig, self.pc_j, self.pc_sj)
            wi2 = vf[:, 3 * self.pc_i + 2] ** 2
            wj2 = vf[:, 3 * self.pc_j + 2] ** 2
            out[:, 0 : 2 * k : 2] = wi2 * ax - wj2 * bx
            out[:, 1 : 2 * k : 2] = wi2 * ay - wj2 * by
        if kl:
            r0 = 2 * k
            sx, sy, tx, ty, nx, ny, dx, dy = self._line(trig, qf)
            s3, g3 = 3 * self.ln_s, 3 * self.ln_g
            ws, wg = vf[:, s3 + 2], vf[:, g3 + 2]
            ddx = vf[:, s3] - ws * sy - vf[:, g3] + wg * ty
            ddy = vf[:, s3 + 1] + ws * sx - vf[:, g3 + 1] - wg * tx
            out[:, r0 : r0 + kl] = (
                wg**2 * (nx * dx + ny * dy)
                - 2.0 * wg * (-ny * ddx + nx * ddy)
                + ws**2 * (nx * sx + ny * sy)
                - wg**2 * (nx * tx + ny * ty)
            )
            for row, law, (_, _, h2) in self._laws(qf):
                rate = vf[:, 3 * law.cam + 2] - vf[:, 3 * int(self.ln_g[row]) + 2]
                out[:, r0 + row] += law.w * h2 * (law.sense * rate) ** 2
        if kd:
            # ½|d|² = const: d·d̈ = −|ḋ|², and d̈ holds −ω_i² A_i s_i + ω_j² A_j s_j besides q̈
            dx, dy, ax, ay, bx, by = self._distance(trig, qf)
            i3, j3 = 3 * self.ds_i, 3 * self.ds_j
            wi, wj = vf[:, i3 + 2], vf[:, j3 + 2]
            ddx = vf[:, i3] - wi * ay - vf[:, j3] + wj * by
            ddy = vf[:, i3 + 1] + wi * ax - vf[:, j3 + 1] - wj * bx
            out[:, self.m - kc - kd : self.m - kc] = (
                -(ddx * ddx + ddy * ddy) + dx * (wi**2 * ax - wj**2 * bx) + dy * (wi**2 * ay - wj**2 * by)
            )
        for k_cv, cv in enumerate(self.cv):
            out[:, self.m - kc + k_cv] = curve_rows(cv, qf, vf)[2]
        return out[0] if one else out

    def point(self, q: np.ndarray, name: str) -> np.ndarray:
        """Scaled global position (2,) of a location in configuration ``q``."""
        if name in self.locators:
            return self.locators[name](q)
        if name in self.contact_xy:
            return self.contact_xy[name]
        i, s = self.local[name]
        if i == self.n:
            return s
        x, y, th = q[3 * i : 3 * i + 3]
        c, sn = math.cos(th), math.sin(th)
        return np.array([x + c * s[0] - sn * s[1], y + sn * s[0] + c * s[1]])


def _add_at(jac: np.ndarray, rows: np.ndarray, cols: np.ndarray, values: np.ndarray) -> None:
    """``jac[:, rows, cols] += values`` (K, len(rows)), repeated (row, column) pairs adding up."""
    np.add.at(jac.transpose(1, 2, 0), (rows, cols), np.asarray(values).T)


def build_system(lay: Layout, drawn: Drawn) -> System:
    """Compile the constraint rows of ``lay`` about its drawn configuration.

    Each joint's rows come from its kind (:meth:`mech.pairs.base.PairKind.rows`).
    The steps: the scaled frame (:func:`_scaling`), each link's drawn frame
    (:func:`_link_frames`), every location in its carrier's frame, the joints'
    rows, the drives' rows (:func:`_drive_rows`), then the rows stacked into
    arrays (:func:`_stack_rows`) and labelled (:func:`_label_rows`).

    Raises
    ------
    InputError
        A higher pair lacks what its rows need (its contact point or normal, or
        profiles that touch as drawn).
    """
    mech = lay.mech
    scale = drawn.scale
    ground = mech.ground
    links = tuple(lk.name for lk in mech.links if not lk.is_ground)
    index = {name: i for i, name in enumerate(links)}
    index[ground] = len(links)
    pos = drawn.positions
    centre, sc, scn = _scaling(lay, drawn)
    n = len(links)
    q0, frames = _link_frames(lay, drawn, links, index, scn)

    b = Build(lay, pos, index, n, q0, scale, sc, scn, {ps.joint: ps for ps in lay.paths})
    local: dict[str, tuple[int, np.ndarray]] = {}
    for name, carriers in lay.carriers.items():
        if carriers and name in pos:
            moving = [c for c in carriers if c != ground]
            carrier = moving[0] if moving else ground
            local[name] = (index[carrier], b.to_local(carrier, scn(name)))
    contact_xy = {j.name: scn(j.name) for j in lay.contacts if j.name in pos}

    for j in mech.joints:
        kind_of(j).rows(b, j)
    collect(b.problems, source=mech.source)
    drive_rows = _drive_rows(lay, b, index)

    sys_ = System(
        links=links,
        ground=ground,
        scale=scale,
        centre=centre,
        q0=q0,
        local=local,
        frames=frames,
        contact_xy=contact_xy,
    )
    _stack_rows(sys_, b, n)
    _label_rows(sys_, b)
    sys_.drive_rows = np.array(drive_rows, int)
    sys_.path_dirs = b.path_dirs
    sys_.path_points = b.path_points
    sys_.locators = b.locators
    sys_.normals = b.normals
    sys_.contact_points = b.contact_points
    sys_.notes = tuple(b.notes)
    sys_.loc_names = tuple(local)
    sys_.loc_i = np.array([local[k][0] for k in local], int)
    sys_.loc_s = np.array([local[k][1] for k in local], float).reshape(-1, 2)
    sys_.link_index = {name: i for i, name in enumerate(links)}
    sys_.joint_names = frozenset(j.name for j in mech.joints if kind_of(j).located != "none")
    # Slider drives: their constant is the drawn displacement along the path.
    n_pc, kl = len(b.coincide), len(b.online)
    sliding = [r for r in sys_.drive_rows if 2 * n_pc <= r < 2 * n_pc + kl]
    if sliding:  # Φ as drawn only when a slider is driven (a crank's rows need none of it)
        base_phi = sys_.phi(q0, sys_.ln_c, sys_.ang_c)
        for r in sliding:
            sys_.ln_c[r - 2 * n_pc] = base_phi[r]
    return sys_


def _scaling(
    lay: Layout, drawn: Drawn
) -> tuple[np.ndarray, Callable[[tuple[float, float]], np.ndarray], Callable[[str], np.ndarray]]:
    """The centre (a drawn ground pivot), and the maps to scaled coordinates about it.

    ``sc`` scales a global position; ``scn`` a named location, from the assembler's
    relative coordinates when it has them (exact far from the origin).
    """
    scale, pos, relative = drawn.scale, drawn.positions, drawn.relative
    ground_pts = [p for p in lay.on_link.get(lay.mech.ground, ()) if p in pos]
    centre = np.array(pos[ground_pts[0]] if ground_pts else next(iter(pos.values()), (0.0, 0.0)), float)
    if relative is not None:
        centre = np.array(drawn.centre, float)

    def sc(xy: tuple[float, float]) -> np.ndarray:
        return (np.asarray(xy, float) - centre) / scale

    def scn(name: str) -> np.ndarray:
        """A drawn location, scaled, from the assembler's relative coordinates when it has them."""
        if relative is not None and name in relative:
            return np.asarray(relative[name], float) / scale
        return sc(pos[name])

    return centre, sc, scn


#: Two located points of a link closer than this (scaled by the size) are one point for the
#: link's frame: a few hundred ulps, so a 1e-12 m crank on 1 m links still has its direction
#: (it had 0° for a crank drawn at 45° under the former 1e-9).
_DISTINCT = 1e-14


def _link_frames(
    lay: Layout,
    drawn: Drawn,
    links: tuple[str, ...],
    index: dict[str, int],
    scn: Callable[[str], np.ndarray],
) -> tuple[np.ndarray, dict[str, str]]:
    """Each moving link's drawn frame ``q0`` (origin at its first location, x toward the next),
    and the location each frame is anchored at.
    """
    pos = drawn.positions
    q0 = np.zeros(3 * len(links))
    frames: dict[str, str] = {}
    drive_link_angle = {
        spec.link: drawn.drive_angles[k]
        for k, spec in enumerate(lay.drives)
        if spec.link is not None and spec.toward is None
    }
    # A link with one located point has no line of its own: a slider or a guide takes its
    # path's direction (so a block and the rod sliding through it report the same angle).
    slider_dir: dict[str, PathSpec] = {}
    for ps in lay.paths:
        slider_dir.setdefault(ps.slider, ps)
    for ps in lay.paths:
        slider_dir.setdefault(ps.guide, ps)
    # A crank's frame: at its pivot, on its drive's angle (pivot → toward) as the drive gives it,
    # not as atan2 gives it back an ulp or a turn away: the closed form turns the crank by
    # phi + (q0 − drawn), and near ±π that difference of two π-sized numbers keeps only their
    # rounding (4.4e-16 rad), 2.5e-5 of a crank drawn 1e-11 rad from a dead centre.
    crank_at: dict[str, tuple[str, float]] = {}
    for k, spec in enumerate(lay.drives):
        if spec.link and spec.pivot in pos and spec.toward in pos and spec.reference == lay.mech.ground:
            w = scn(spec.toward) - scn(spec.pivot)  # type: ignore[arg-type]
            drive = drawn.drive_angles[k]
            if drive is not None and abs(math.remainder(math.atan2(w[1], w[0]) - drive, math.tau)) < 1e-9:
                crank_at[spec.link] = (spec.pivot, drive)  # type: ignore[assignment]
    for name in links:
        names = [p for p in lay.on_link.get(name, ()) if p in pos]
        if name in crank_at:
            pivot, on_drive = crank_at[name]
            origin = scn(pivot)
            frames[name] = pivot
            q0[3 * index[name] : 3 * index[name] + 3] = (origin[0], origin[1], on_drive)
            continue
        origin = scn(names[0]) if names else np.zeros(2)
        theta = None
        for other in names[1:]:
            w = scn(other) - origin
            if math.hypot(*w) > _DISTINCT:
                theta = math.atan2(w[1], w[0])
                break
        if theta is None:
            if name in drive_link_angle and drive_link_angle[name] is not None:
                theta = drive_link_angle[name]
            elif name in slider_dir:
                theta = path_angle(slider_dir[name].path, pos, lay.resolve)
            else:
                theta = 0.0
        frames[name] = names[0] if names else ""
        q0[3 * index[name] : 3 * index[name] + 3] = (origin[0], origin[1], theta)
    frames[lay.mech.ground] = ""
    return q0, frames


def _drive_rows(lay: Layout, b: Build, index: dict[str, int]) -> list[int]:
    """Drives last, in file order: rotary drives are angle rows, slider drives line rows.

    Appends them to ``b``'s rows; returns their indices in the stacked residual.
    """
    ln, ang = b.online, b.angle
    drive_at: list[tuple[str, int]] = []
    for spec in lay.drives:
        name = f"drive {spec.drive.link or spec.drive.joint}"
        if spec.link is not None:
            i, r = index[spec.link], index[spec.reference]  # type: ignore[index]
            ang.append(Angle({i: 1.0, r: -1.0}, b.theta(spec.link) - b.theta(spec.reference), name))  # type: ignore[arg-type]
            drive_at.append(("ang", len(ang) - 1))
        else:
            assert spec.joint is not None  # a drive without a link drives a slider joint (DriveSpec)
            base = next(x for x in ln if x.joint == spec.joint)
            u = b.path_dirs[spec.joint][1]
            ln.append(OnLine(base.slider, base.s, base.guide, base.t, u, 0.0, name))
            drive_at.append(("ln", len(ln) - 1))
    n_pc, kl = len(b.coincide), len(ln)
    return [2 * n_pc + (k if kind == "ln" else kl + k) for kind, k in drive_at]


def _stack_rows(sys_: System, b: Build, n: int) -> None:
    """The row records stacked into the arrays the vectorised residual and Jacobian read."""
    pc, ln, ang, ds = b.coincide, b.online, b.angle, b.distance
    if pc:
        sys_.pc_i = np.array([p.i for p in pc])
        sys_.pc_si = np.array([p.si for p in pc])
        sys_.pc_j = np.array([p.j for p in pc])
        sys_.pc_sj = np.array([p.sj for p in pc])
    if ln:
        sys_.ln_s = np.array([x.slider for x in ln])
        sys_.ln_sp = np.array([x.s for x in ln])
        sys_.ln_g = np.array([x.guide for x in ln])
        sys_.ln_t = np.array([x.t for x in ln])
        sys_.ln_n = np.array([x.n for x in ln])
        sys_.ln_c = np.array([x.c for x in ln], float)
        if any(x.k for x in ln):
            sys_.ln_k = np.array([x.k for x in ln], float)
        sys_.ln_law = tuple((r, x.law) for r, x in enumerate(ln) if x.law is not None)
    a = np.zeros((len(ang), n + 1))
    for row, rec in enumerate(ang):
        for col, v in rec.coef.items():
            a[row, col] += v
    sys_.ang_a = a
    sys_.ang_c = np.array([x.c for x in ang], float)
    if ds:
        sys_.ds_i = np.array([x.i for x in ds])
        sys_.ds_si = np.array([x.si for x in ds])
        sys_.ds_j = np.array([x.j for x in ds])
        sys_.ds_sj = np.array([x.sj for x in ds])
        sys_.ds_d = np.array([x.d for x in ds], float)
    sys_.cv = tuple(b.curves)


def _label_rows(sys_: System, b: Build) -> None:
    """Each residual row's joint, and whether it is holonomic (a velocity-only row is not)."""
    row_joints: list[str] = []
    holo_rows: list[bool] = []
    for p in b.coincide:
        row_joints += [p.joint, p.joint]
        holo_rows += [p.holonomic, p.holonomic]
    one_row: list[OnLine | Angle | Distance | CurveRow] = [*b.online, *b.angle, *b.distance, *b.curves]
    for one in one_row:
        row_joints.append(one.joint)
        holo_rows.append(one.holonomic)
    sys_.row_names = tuple(row_joints)
    sys_.holonomic = np.array(holo_rows, bool)
    sys_.velocity_only = tuple(dict.fromkeys(n for n, h in zip(row_joints, holo_rows, strict=True) if not h))
