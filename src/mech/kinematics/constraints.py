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
from mech.kinematics.assemble import Drawn, gear_centre
from mech.kinematics.curves import CurveRow, curve_row
from mech.kinematics.layout import Layout, PathSpec
from mech.kinematics.rows import ROWS, Angle, Build, Distance, Locator, OnLine
from mech.model import Joint

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
    row_names: tuple[str, ...] = ()  # per row: the joint or drive it comes from
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

    # -- kinematic functions (scaled) ------------------------------------------------
    def _full(self, q: np.ndarray) -> np.ndarray:
        qf = np.zeros(q.size + 3)
        qf[:-3] = q
        return qf

    @staticmethod
    def _rot(qf: np.ndarray, idx: np.ndarray, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        th = qf[3 * idx + 2]
        c, sn = np.cos(th), np.sin(th)
        return c * s[:, 0] - sn * s[:, 1], sn * s[:, 0] + c * s[:, 1]

    def phi(self, q: np.ndarray, c_line: np.ndarray, c_ang: np.ndarray) -> np.ndarray:
        """Φ(q) (m,) for the given line and angle constants (drive targets inside)."""
        qf = self._full(q)
        k = self.pc_i.size
        out = np.empty(self.m)
        ax, ay = self._rot(qf, self.pc_i, self.pc_si)
        bx, by = self._rot(qf, self.pc_j, self.pc_sj)
        out[0 : 2 * k : 2] = qf[3 * self.pc_i] + ax - qf[3 * self.pc_j] - bx
        out[1 : 2 * k : 2] = qf[3 * self.pc_i + 1] + ay - qf[3 * self.pc_j + 1] - by
        r = 2 * k
        kl = self.ln_s.size
        if kl:
            sx, sy = self._rot(qf, self.ln_s, self.ln_sp)
            tx, ty = self._rot(qf, self.ln_g, self.ln_t)
            nx, ny = self._rot(qf, self.ln_g, self.ln_n)
            dx = qf[3 * self.ln_s] + sx - qf[3 * self.ln_g] - tx
            dy = qf[3 * self.ln_s + 1] + sy - qf[3 * self.ln_g + 1] - ty
            out[r : r + kl] = nx * dx + ny * dy - c_line
            if self.ln_k is not None:
                out[r : r + kl] += self.ln_k * (qf[3 * self.ln_s + 2] - qf[3 * self.ln_g + 2])
        r += kl
        ka = self.ang_c.size
        out[r : r + ka] = self.ang_a @ qf[2::3] - c_ang
        r += ka
        kd = self.ds_d.size
        if kd:
            dx, dy, _, _, _, _ = self._distance(qf)
            out[r : r + kd] = 0.5 * (dx * dx + dy * dy - self.ds_d**2)
        for k, row in enumerate(self.cv):
            out[r + kd + k] = curve_row(row, qf)[0]
        return out

    def _distance(self, qf: np.ndarray) -> tuple[np.ndarray, ...]:
        """d = r_i(P) − r_j(Q) of the distance rows, with A_i s_i and A_j s_j."""
        ax, ay = self._rot(qf, self.ds_i, self.ds_si)
        bx, by = self._rot(qf, self.ds_j, self.ds_sj)
        i3, j3 = 3 * self.ds_i, 3 * self.ds_j
        dx = qf[i3] + ax - qf[j3] - bx
        dy = qf[i3 + 1] + ay - qf[j3 + 1] - by
        return dx, dy, ax, ay, bx, by

    def jacobian(self, q: np.ndarray) -> np.ndarray:
        """Φ_q (m, 3n)."""
        qf = self._full(q)
        n3 = qf.size
        k = self.pc_i.size
        jac = np.zeros((self.m, n3))
        if k:
            ax, ay = self._rot(qf, self.pc_i, self.pc_si)
            bx, by = self._rot(qf, self.pc_j, self.pc_sj)
            rx = np.arange(0, 2 * k, 2)
            ry = rx + 1
            i3, j3 = 3 * self.pc_i, 3 * self.pc_j
            jac[rx, i3] = 1.0
            jac[ry, i3 + 1] = 1.0
            jac[rx, i3 + 2] = -ay
            jac[ry, i3 + 2] = ax
            jac[rx, j3] = -1.0
            jac[ry, j3 + 1] = -1.0
            jac[rx, j3 + 2] = by
            jac[ry, j3 + 2] = -bx
        r0 = 2 * k
        kl = self.ln_s.size
        if kl:
            rows = np.arange(r0, r0 + kl)
            sx, sy = self._rot(qf, self.ln_s, self.ln_sp)
            tx, ty = self._rot(qf, self.ln_g, self.ln_t)
            nx, ny = self._rot(qf, self.ln_g, self.ln_n)
            dx = qf[3 * self.ln_s] + sx - qf[3 * self.ln_g] - tx
            dy = qf[3 * self.ln_s + 1] + sy - qf[3 * self.ln_g + 1] - ty
            s3, g3 = 3 * self.ln_s, 3 * self.ln_g
            jac[rows, s3] = nx
            jac[rows, s3 + 1] = ny
            jac[rows, s3 + 2] = -nx * sy + ny * sx
            jac[rows, g3] = -nx
            jac[rows, g3 + 1] = -ny
            jac[rows, g3 + 2] = (-ny * dx + nx * dy) - (-nx * ty + ny * tx)
            if self.ln_k is not None:
                np.add.at(jac, (rows, s3 + 2), self.ln_k)
                np.add.at(jac, (rows, g3 + 2), -self.ln_k)
        r0 += kl
        ka = self.ang_c.size
        if ka:
            jac[r0 : r0 + ka, 2::3] = self.ang_a
        r0 += ka
        if self.ds_d.size:
            rows = np.arange(r0, r0 + self.ds_d.size)
            dx, dy, ax, ay, bx, by = self._distance(qf)
            i3, j3 = 3 * self.ds_i, 3 * self.ds_j
            np.add.at(jac, (rows, i3), dx)
            np.add.at(jac, (rows, i3 + 1), dy)
            np.add.at(jac, (rows, i3 + 2), -dx * ay + dy * ax)
            np.add.at(jac, (rows, j3), -dx)
            np.add.at(jac, (rows, j3 + 1), -dy)
            np.add.at(jac, (rows, j3 + 2), dx * by - dy * bx)
        r0 += self.ds_d.size
        for k, row in enumerate(self.cv):
            for col, v in curve_row(row, qf)[1].items():
                jac[r0 + k, col] += v
        return jac[:, :-3]

    def gamma(self, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        """γ (m,) without drive accelerations: Φ_q q̈ = γ + (drive α rows)."""
        qf, vf = self._full(q), self._full(qd)
        k = self.pc_i.size
        out = np.zeros(self.m)
        if k:
            ax, ay = self._rot(qf, self.pc_i, self.pc_si)
            bx, by = self._rot(qf, self.pc_j, self.pc_sj)
            wi2 = vf[3 * self.pc_i + 2] ** 2
            wj2 = vf[3 * self.pc_j + 2] ** 2
            out[0 : 2 * k : 2] = wi2 * ax - wj2 * bx
            out[1 : 2 * k : 2] = wi2 * ay - wj2 * by
        kl = self.ln_s.size
        if kl:
            r0 = 2 * k
            sx, sy = self._rot(qf, self.ln_s, self.ln_sp)
            tx, ty = self._rot(qf, self.ln_g, self.ln_t)
            nx, ny = self._rot(qf, self.ln_g, self.ln_n)
            s3, g3 = 3 * self.ln_s, 3 * self.ln_g
            dx = qf[s3] + sx - qf[g3] - tx
            dy = qf[s3 + 1] + sy - qf[g3 + 1] - ty
            ws, wg = vf[s3 + 2], vf[g3 + 2]
            ddx = vf[s3] - ws * sy - vf[g3] + wg * ty
            ddy = vf[s3 + 1] + ws * sx - vf[g3 + 1] - wg * tx
            out[r0 : r0 + kl] = (
                wg**2 * (nx * dx + ny * dy)
                - 2.0 * wg * (-ny * ddx + nx * ddy)
                + ws**2 * (nx * sx + ny * sy)
                - wg**2 * (nx * tx + ny * ty)
            )
        if self.ds_d.size:
            # ½|d|² = const: d·d̈ = −|ḋ|², and d̈ holds −ω_i² A_i s_i + ω_j² A_j s_j besides q̈
            dx, dy, ax, ay, bx, by = self._distance(qf)
            i3, j3 = 3 * self.ds_i, 3 * self.ds_j
            wi, wj = vf[i3 + 2], vf[j3 + 2]
            ddx = vf[i3] - wi * ay - vf[j3] + wj * by
            ddy = vf[i3 + 1] + wi * ax - vf[j3 + 1] - wj * bx
            end = self.m - len(self.cv)
            out[end - self.ds_d.size : end] = (
                -(ddx * ddx + ddy * ddy) + dx * (wi**2 * ax - wj**2 * bx) + dy * (wi**2 * ay - wj**2 * by)
            )
        for k, row in enumerate(self.cv):
            out[self.m - len(self.cv) + k] = curve_row(row, qf, vf)[2]
        return out

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


def build_system(lay: Layout, drawn: Drawn) -> System:
    """Compile the constraint rows of ``lay`` about its drawn configuration.

    Each joint's rows come from its kind's entry in :data:`mech.kinematics.rows.ROWS`.
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
        ROWS[j.type](b, j)
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
    sys_.loc_names = tuple(local)
    sys_.loc_i = np.array([local[k][0] for k in local], int)
    sys_.loc_s = np.array([local[k][1] for k in local], float).reshape(-1, 2)
    sys_.link_index = {name: i for i, name in enumerate(links)}
    sys_.joint_names = frozenset(j.name for j in mech.joints if j.type.kind.located != "none")
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
    for name in links:
        names = [p for p in lay.on_link.get(name, ()) if p in pos]
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
                theta = path_angle(lay, slider_dir[name], pos)
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


def path_angle(lay: Layout, ps: PathSpec, pos: dict[str, tuple[float, float]]) -> float:
    """Global direction (rad) of a path in the drawn configuration."""
    if ps.path.toward is not None:
        t = ps.path.through
        t_xy = lay.ref_xy(t, pos)
        q_xy = lay.ref_xy(ps.path.toward, pos)
        return math.atan2(q_xy[1] - t_xy[1], q_xy[0] - t_xy[0])
    return float(ps.path.angle or 0.0)


def _carrier_of(lay: Layout, link: str, pos: dict[str, tuple[float, float]]) -> dict[str, str]:
    """Revolute joints of ``link`` with their other link: ``{other_link: joint}``."""
    out: dict[str, str] = {}
    for name in lay.on_link.get(link, ()):
        carriers = lay.carriers.get(name, ())
        if len(carriers) >= 2 and name in pos:
            for c in carriers:
                if c != link:
                    out.setdefault(c, name)
    return out


def gear_row(
    lay: Layout,
    j: Joint,
    pos: dict[str, tuple[float, float]],
    index: dict[str, int],
    q0: np.ndarray,
    n: int,
) -> tuple[dict[int, float], float] | None:
    """A gear pair with both centres pinned to one carrier: ``r₁(θ₁−θc) ± r₂(θ₂−θc) = const``.

    The pitch circles roll on each other relative to the carrier (ground for a
    fixed-axis pair, the arm of an epicyclic train), which is holonomic: the
    pair then moves, and accelerates, like any lower pair.  External pairs
    turn opposite ways (+), internal pairs the same way (−).  Returns None
    when there is no common carrier or no radii.
    """
    g1, g2 = j.links
    c1, c2 = _carrier_of(lay, g1, pos), _carrier_of(lay, g2, pos)
    common = [c for c in c1 if c in c2 and c not in (g1, g2)]
    if not common:
        return None
    carrier = common[0]
    o1, o2 = pos[c1[carrier]], pos[c2[carrier]]
    given = (
        getattr(j.spec, "pitch_radii", None) or j.radii
    )  # a gear's (teeth × module / 2), or rolling circles
    internal = j.internal
    radii: tuple[float, float]
    if given is not None and given[0] is not None and given[1] is not None:
        radii = (given[0], given[1])
    else:
        if j.name not in pos:
            return None
        p = pos[j.name]
        r1 = math.hypot(p[0] - o1[0], p[1] - o1[1])
        r2 = math.hypot(p[0] - o2[0], p[1] - o2[1])
        d = math.hypot(o2[0] - o1[0], o2[1] - o1[1])
        internal = internal or abs(abs(r1 - r2) - d) < abs(r1 + r2 - d)
        radii = (r1, r2)
    sign = -1.0 if internal else 1.0
    i1, i2, ic = index[g1], index[g2], index[carrier]
    coef: dict[int, float] = {}
    for col, v in ((i1, radii[0]), (i2, sign * radii[1]), (ic, -radii[0] - sign * radii[1])):
        coef[col] = coef.get(col, 0.0) + v / (max(radii) or 1.0)  # O(1) coefficients
    theta = {i: (0.0 if i == n else q0[3 * i + 2]) for i in coef}
    return coef, sum(v * theta[i] for i, v in coef.items())


def gear_normal(lay: Layout, j: Joint, pos: dict[str, tuple[float, float]]) -> float | None:
    """Line of action of a gear pair: the common tangent turned by the pressure angle."""
    centres = [gear_centre(lay, lk, pos) for lk in j.links]
    if None in centres:
        return None
    (x1, y1), (x2, y2) = centres  # type: ignore[misc]
    return math.atan2(y2 - y1, x2 - x1) + math.pi / 2.0 - (j.pressure_angle or 0.0)
