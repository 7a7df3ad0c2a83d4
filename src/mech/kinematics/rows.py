"""Constraint rows as named records, and the kinematics registry of pair kinds (:data:`ROWS`).

Each joint kind says here which rows it adds to Φ(q) = 0 (reference-point
coordinates, see :mod:`mech.kinematics.constraints`).  There are four row
shapes, each a record with the curvature (γ) term that goes with it written
once in :class:`~mech.kinematics.constraints.System`:

:class:`Coincide`  (2 rows) ``r_i(P) − r_j(Q) = 0``: a pin; rolling at the instant.
:class:`OnLine`    (1 row)  ``n_G·(r_S(P) − r_G(T)) + k(θ_S − θ_G) = c``: a point on a line
                   fixed in a guide (a path, a circle on a flat face with ``c = ±r``,
                   a wheel's no-slip condition with ``n`` along the line and ``k = ±r``).
:class:`Angle`     (1 row)  ``Σ a_k θ_k = c``: a prismatic pair's fixed angle, a drive, gears
                   on one carrier.
:class:`Distance`  (1 row)  ``½(|r_i(P) − r_j(Q)|² − d²) = 0``: two circles (or a knife edge
                   and a circle) in contact, ``d`` the sum or difference of their radii.

``holonomic`` is False for a row that holds only at the drawn instant (a higher
pair given by its contact point and normal): it enters the velocity solve and
the mobility rank, never Newton, and refuses accelerations and sweeps.

Adding a kind: a function ``rows(ctx, joint)`` that appends records to the
:class:`Build` context, registered in :data:`ROWS` under the joint type.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import field
from typing import TYPE_CHECKING

import numpy as np

from mech._records import dataclass
from mech.errors import Problem, UnsupportedError
from mech.model import Joint, JointType

if TYPE_CHECKING:
    from mech.kinematics.curves import CurveRow
    from mech.kinematics.layout import Layout, PathSpec

__all__ = ["ROWS", "Angle", "Build", "Coincide", "Distance", "OnLine"]


@dataclass(frozen=True, slots=True)
class Coincide:
    """Point ``si`` of link ``i`` on point ``sj`` of link ``j`` (local, scaled): 2 rows."""

    i: int
    si: np.ndarray
    j: int
    sj: np.ndarray
    joint: str
    holonomic: bool = True


@dataclass(frozen=True, slots=True)
class OnLine:
    """Point ``s`` of ``slider`` on the line through ``t`` of ``guide`` with normal ``n`` (local): 1 row.

    ``c`` is the signed distance kept from the line; ``k`` multiplies the
    relative angle θ_slider − θ_guide (a rolling wheel's arc length).
    """

    slider: int
    s: np.ndarray
    guide: int
    t: np.ndarray
    n: np.ndarray
    c: float
    joint: str
    holonomic: bool = True
    k: float = 0.0


@dataclass(frozen=True, slots=True)
class Angle:
    """``Σ coef[link] · θ_link = c`` (link indices, ground = n): 1 row."""

    coef: dict[int, float]
    c: float
    joint: str
    holonomic: bool = True


@dataclass(frozen=True, slots=True)
class Distance:
    """Point ``si`` of link ``i`` kept at distance ``d`` from point ``sj`` of link ``j``: 1 row."""

    i: int
    si: np.ndarray
    j: int
    sj: np.ndarray
    d: float
    joint: str
    holonomic: bool = True


Locator = Callable[[np.ndarray], np.ndarray]


@dataclass(eq=False)
class Build:
    """What a kind's row function reads (the drawn configuration) and where it writes its rows.

    Coordinates are scaled (divided by the mechanism's size) and relative to
    ``centre``; ``index`` maps link names to q blocks (ground is ``n``).
    """

    lay: Layout
    pos: dict[str, tuple[float, float]]
    index: dict[str, int]
    n: int
    q0: np.ndarray
    scale: float
    sc: Callable[[tuple[float, float]], np.ndarray]
    scn: Callable[[str], np.ndarray]
    paths: dict[str, PathSpec]
    coincide: list[Coincide] = field(default_factory=list)
    online: list[OnLine] = field(default_factory=list)
    angle: list[Angle] = field(default_factory=list)
    distance: list[Distance] = field(default_factory=list)
    curves: list[CurveRow] = field(default_factory=list)
    problems: list[Problem] = field(default_factory=list)
    path_dirs: dict[str, tuple[int, np.ndarray]] = field(default_factory=dict)
    path_points: dict[str, tuple[int, str]] = field(default_factory=dict)
    locators: dict[str, Locator] = field(default_factory=dict)  # moving contact point, from q
    normals: dict[str, Locator] = field(default_factory=dict)  # its common normal (unit), from q

    def theta(self, link: str) -> float:
        i = self.index[link]
        return 0.0 if i == self.n else float(self.q0[3 * i + 2])

    def to_local(self, link: str, xy: np.ndarray) -> np.ndarray:
        """Global scaled ``xy`` in ``link``'s frame as drawn."""
        i = self.index[link]
        if i == self.n:
            return np.array(xy, float)
        x, y, th = self.q0[3 * i : 3 * i + 3].tolist()  # Python floats: the same IEEE operations
        c, s = math.cos(th), math.sin(th)
        dx, dy = float(xy[0]) - x, float(xy[1]) - y
        return np.array([c * dx + s * dy, -s * dx + c * dy])

    def dir_local(self, link: str, angle: float) -> np.ndarray:
        """A global direction (rad) as drawn, in ``link``'s frame."""
        th = self.theta(link)
        return np.array([math.cos(angle - th), math.sin(angle - th)])

    def where(self, ref: object) -> np.ndarray:
        """A :class:`~mech.model.Ref` (coordinates or a name) as drawn, scaled."""
        xy = getattr(ref, "xy", None)
        if xy is not None:
            return self.sc(xy)
        return self.scn(self.lay.resolve(ref.name))  # type: ignore[attr-defined]


# -- the kinds ----------------------------------------------------------------------------------
def _revolute(b: Build, j: Joint) -> None:
    if j.name not in b.pos:
        return
    xy = b.scn(j.name)
    first = j.links[0]
    for other in j.links[1:]:
        b.coincide.append(
            Coincide(b.index[first], b.to_local(first, xy), b.index[other], b.to_local(other, xy), j.name)
        )


def _sliding(b: Build, j: Joint) -> None:
    from mech.kinematics.constraints import path_angle

    ps = b.paths.get(j.name)
    if ps is None:  # reported by the layout already
        return
    t_xy = b.where(ps.path.through)
    a = path_angle(b.lay, ps, b.pos)
    u = b.dir_local(ps.guide, a)
    b.online.append(
        OnLine(
            b.index[ps.slider],
            b.to_local(ps.slider, b.scn(ps.point)),
            b.index[ps.guide],
            b.to_local(ps.guide, t_xy),
            np.array([-u[1], u[0]]),
            0.0,
            ps.joint,
        )
    )
    b.path_dirs[ps.joint] = (b.index[ps.guide], u)
    b.path_points[ps.joint] = (b.index[ps.slider], ps.point)
    if ps.type is JointType.PRISMATIC:
        coef = {b.index[ps.slider]: 1.0, b.index[ps.guide]: -1.0}
        b.angle.append(Angle(coef, b.theta(ps.slider) - b.theta(ps.guide), ps.joint))


def _instant_point(b: Build, j: Joint) -> np.ndarray | None:
    if j.name not in b.pos:
        b.problems.append(
            Problem(
                f"{j.type.value} joint {j.name} needs at (the contact point of the instant) for velocities",
                j.where,
                "or give each link's curve under `profiles` (then the pair moves)",
            )
        )
        return None
    return b.scn(j.name)


def _instant_normal(b: Build, j: Joint, normal: float | None) -> None:
    """The velocity-level row of a higher pair at the drawn instant: no relative motion along the normal."""
    xy = _instant_point(b, j)
    if xy is None:
        return
    if normal is None:
        b.problems.append(
            Problem(
                f"{j.type.value} joint {j.name} needs normal (the common normal's angle) for velocities",
                j.where,
            )
        )
        return
    a_link, b_link = j.links
    u = b.dir_local(b_link, normal)
    b.online.append(
        OnLine(
            b.index[a_link],
            b.to_local(a_link, xy),
            b.index[b_link],
            b.to_local(b_link, xy),
            u,
            0.0,
            j.name,
            holonomic=False,
        )
    )


def _cam(b: Build, j: Joint) -> None:
    from mech.kinematics.profiles import moving_contact

    if moving_contact(b, j):
        return
    _instant_normal(b, j, j.normal)


def _rolling(b: Build, j: Joint) -> None:
    from mech.kinematics.profiles import moving_contact

    if moving_contact(b, j):
        return
    xy = _instant_point(b, j)
    if xy is None:
        return
    a_link, b_link = j.links
    b.coincide.append(
        Coincide(
            b.index[a_link],
            b.to_local(a_link, xy),
            b.index[b_link],
            b.to_local(b_link, xy),
            j.name,
            holonomic=False,
        )
    )


def _gear(b: Build, j: Joint) -> None:
    from mech.kinematics.constraints import gear_normal, gear_row

    holo = gear_row(b.lay, j, b.pos, b.index, b.q0, b.n)
    if holo is not None:
        b.angle.append(Angle(holo[0], holo[1], j.name))
        return
    from mech.kinematics.profiles import moving_contact

    if j.profiles and moving_contact(b, j):  # pitch curves that roll: a rack and pinion
        return
    normal = j.normal if j.normal is not None else gear_normal(b.lay, j, b.pos)
    _instant_normal(b, j, normal)


def _spatial(b: Build, j: Joint) -> None:
    raise UnsupportedError(  # the layout refuses these first; kept so no kind falls through silently
        f"joint {j.name} is a {j.type.value} pair: planar solvers cannot model it", where=j.where
    )


#: Joint type → ``rows(build, joint)``, appending that joint's constraint records.
ROWS: dict[JointType, Callable[[Build, Joint], None]] = {
    JointType.REVOLUTE: _revolute,
    JointType.PRISMATIC: _sliding,
    JointType.SLOT: _sliding,
    JointType.ROLLING: _rolling,
    JointType.CAM: _cam,
    JointType.CONTACT: _cam,
    JointType.GEAR: _gear,
    JointType.SCREW: _spatial,
    JointType.SPHERICAL: _spatial,
}
