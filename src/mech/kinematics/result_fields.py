"""A solve's result from its scaled ``q, q̇, q̈``: unscaled and packaged when first read.

Every location's position, each link's state and each joint's geometry now,
vectorised, since it runs on every solve of a sweep; the
:class:`~mech.kinematics.result.Kinematics` a solve returns holds a callable
that makes them, so a caller that reads one number pays for the arrays only.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from types import MappingProxyType

import numpy as np

from mech.kinematics.assemble import complete
from mech.kinematics.compiled import Compiled
from mech.kinematics.result import Fields, JointGeom, Kinematics, LinkState
from mech.model import Drive
from mech.pairs import kind_of

__all__ = ["State", "configuration", "joint_points", "lazy_result", "result"]

_TWO_PI = 2.0 * math.pi
#: q, q̇, q̈ of a solve, scaled (q̇ and q̈ None above the level asked).
State = tuple[np.ndarray, "np.ndarray | None", "np.ndarray | None"]


def result(
    comp: Compiled,
    level: str,
    q: np.ndarray,
    qd: np.ndarray | None,
    qdd: np.ndarray | None,
    omega_ref: float,
    moved: bool,
    notes: tuple[str, ...],
    drives: tuple[Drive, ...],
) -> Kinematics:
    """The result of a solve in scaled coordinates ``q, q̇, q̈``, packaged when first read."""
    return lazy_result(comp, level, lambda: (q, qd, qdd), omega_ref, moved, notes, drives)


def lazy_result(
    comp: Compiled,
    level: str,
    state: Callable[[], State],
    omega_ref: float,
    moved: bool,
    notes: tuple[str, ...] | Callable[[], tuple[str, ...]],
    drives: tuple[Drive, ...],
) -> Kinematics:
    """The result whose fields are made from ``state()`` when first read (the notes too, if a callable)."""
    mech = comp.mech
    return Kinematics.lazy(
        mech.label,
        level,
        comp.mobility,
        drives,
        mech.ground,
        notes,
        lambda: _fields(comp, *state(), omega_ref, moved),
    )


def _fields(
    comp: Compiled,
    q: np.ndarray,
    qd: np.ndarray | None,
    qdd: np.ndarray | None,
    omega_ref: float,
    moved: bool,
) -> Fields:
    """Unscale and package; vectorised, since it runs on every solve of a sweep.

    The steps: every location's position (:func:`_positions`), each link's state
    (:func:`_link_states`), each joint's geometry (:func:`_joint_geoms`).
    """
    sys_, lay = comp.system, comp.layout
    positions, all_pos = _positions(comp, q, moved)
    links = _link_states(comp, q, qd, qdd, omega_ref, positions)
    joints = _joint_geoms(comp, q, positions, all_pos)
    carriers = {n_: c_ for n_, c_ in lay.carriers.items() if not n_.startswith("#")}
    for alias, target in lay.alias.items():
        carriers[alias] = carriers.get(target, ())
    for name, (link, p) in _own_points(comp, positions, joints).items():
        positions[name], carriers[name] = p, (link,)  # the pair's contact stays its JointGeom.at
    return Fields(
        MappingProxyType(positions),
        MappingProxyType(links),
        MappingProxyType(carriers),
        MappingProxyType(joints),
        joint_names=sys_.joint_names,
    )


def configuration(
    comp: Compiled, positions: Mapping[str, tuple[float, float]], angles: Mapping[str, float]
) -> np.ndarray | None:
    """The scaled configuration q where the named points are at ``positions`` (m) and each moving
    link is turned to ``angles`` (rad): a sweep's step, read back as the solver holds it.

    Each link's frame has its origin at a location of its own (``System.frames``), so its
    coordinates are that location's; None when a link's origin or angle is not given.
    """
    sys_ = comp.system
    cx, cy = float(sys_.centre[0]), float(sys_.centre[1])
    q = np.empty(3 * sys_.n)
    for i, link in enumerate(sys_.links):
        origin, angle = positions.get(sys_.frames.get(link, "")), angles.get(link)
        if origin is None or angle is None:
            return None
        q[3 * i : 3 * i + 3] = ((origin[0] - cx) / sys_.scale, (origin[1] - cy) / sys_.scale, angle)
    return q


def joint_points(comp: Compiled, q: np.ndarray) -> dict[str, tuple[float, float] | None]:
    """Each joint's point in the configuration ``q`` (scaled), as a solve there gives it: a pin's
    place, a slider's point, where profiles touch, a gear's pitch point (``JointGeom.at``)."""
    positions, all_pos = _positions(comp, q, True)
    return {name: g.at for name, g in _joint_geoms(comp, q, positions, all_pos).items()}


def _positions(
    comp: Compiled, q: np.ndarray, moved: bool
) -> tuple[dict[str, tuple[float, float]], dict[str, tuple[float, float]]]:
    """Every location's global position (m): the named ones, and all (``#`` synthetic ones too)."""
    sys_, lay = comp.system, comp.layout
    scale, centre = sys_.scale, sys_.centre
    cx, cy = float(centre[0]), float(centre[1])
    # every located point at once: r = R + A(θ) s, for its carrier (ground appended)
    qf = np.append(q, (0.0, 0.0, 0.0))
    idx, loc = sys_.loc_i, sys_.loc_s
    th = qf[3 * idx + 2]
    c, sn = np.cos(th), np.sin(th)
    xs = ((qf[3 * idx] + c * loc[:, 0] - sn * loc[:, 1]) * scale + cx).tolist()
    ys = ((qf[3 * idx + 1] + sn * loc[:, 0] + c * loc[:, 1]) * scale + cy).tolist()
    all_pos = dict(zip(sys_.loc_names, zip(xs, ys, strict=True), strict=True))
    positions = {n: p for n, p in all_pos.items() if not n.startswith("#")}
    if not moved:
        for n, p in sys_.contact_xy.items():
            positions[n] = (float(p[0] * scale + cx), float(p[1] * scale + cy))
    for n, locate in sys_.locators.items():  # profiles in contact: where they touch now
        p = locate(q)
        positions[n] = (float(p[0] * scale + cx), float(p[1] * scale + cy))
    if lay.contacts:
        complete(lay, positions)  # a moved gear pair: pitch point from its centres
    for alias, target in lay.alias.items():
        if target in positions:
            positions[alias] = positions[target]
    return positions, all_pos


def _link_states(
    comp: Compiled,
    q: np.ndarray,
    qd: np.ndarray | None,
    qdd: np.ndarray | None,
    omega_ref: float,
    positions: dict[str, tuple[float, float]],
) -> dict[str, LinkState]:
    """Each link's origin, angle and (up to the level solved) velocities and accelerations, SI."""
    sys_, lay, mech = comp.system, comp.layout, comp.mech
    scale, centre = sys_.scale, sys_.centre
    v_unit, a_unit = scale * omega_ref, scale * omega_ref**2
    cx, cy = float(centre[0]), float(centre[1])
    n_links = sys_.n
    qs = q.tolist()
    vs = (
        (qd * np.repeat([[v_unit, v_unit, omega_ref]], n_links, axis=0).ravel()).tolist()
        if qd is not None
        else None
    )
    acc_units = np.repeat([[a_unit, a_unit, omega_ref**2]], n_links, axis=0).ravel()
    as_ = (qdd * acc_units).tolist() if qdd is not None else None
    links: dict[str, LinkState] = {}
    zero = (0.0, 0.0)
    for lk in mech.links:
        if lk.is_ground:
            gpts = [positions[p] for p in lay.on_link.get(lk.name, ()) if p in positions]
            links[lk.name] = LinkState(
                lk.name,
                gpts[0] if gpts else (cx, cy),
                0.0,
                zero if vs is not None else None,
                0.0 if vs is not None else None,
                zero if as_ is not None else None,
                0.0 if as_ is not None else None,
            )
            continue
        i = 3 * sys_.link_index[lk.name]
        links[lk.name] = LinkState(
            lk.name,
            (qs[i] * scale + cx, qs[i + 1] * scale + cy),
            qs[i + 2] % _TWO_PI,
            (vs[i], vs[i + 1]) if vs is not None else None,
            vs[i + 2] if vs is not None else None,
            (as_[i], as_[i + 1]) if as_ is not None else None,
            as_[i + 2] if as_ is not None else None,
        )
    return links


def _joint_geoms(
    comp: Compiled,
    q: np.ndarray,
    positions: dict[str, tuple[float, float]],
    all_pos: dict[str, tuple[float, float]],
) -> dict[str, JointGeom]:
    """Each joint's point and direction now: a path's line, a contact's common tangent."""
    sys_, lay, mech = comp.system, comp.layout, comp.mech
    n_links = sys_.n
    joints: dict[str, JointGeom] = {}
    for j in mech.joints:
        direction = None
        point: str | None = lay.resolve(j.name)
        if j.name in sys_.path_dirs:
            g, u = sys_.path_dirs[j.name]
            th_g = 0.0 if g == n_links else float(q[3 * g + 2])
            c_g, s_g = math.cos(th_g), math.sin(th_g)
            direction = (c_g * u[0] - s_g * u[1], s_g * u[0] + c_g * u[1])
            point = sys_.path_points[j.name][1]
        elif j.name in sys_.normals:  # profiles in contact: the common tangent now
            nx, ny = sys_.normals[j.name](q)
            direction = (-float(ny), float(nx))
        elif kind_of(j).role == "contact" and j.normal is not None:
            direction = (-math.sin(j.normal), math.cos(j.normal))
        at = positions.get(point) or all_pos.get(point)  # type: ignore[arg-type]
        if j.name in sys_.contact_points:  # the pair touches away from its location (a follower's point)
            p = sys_.contact_points[j.name](q) * sys_.scale + sys_.centre
            at = (float(p[0]), float(p[1]))
        if point is not None and (point.startswith("#") or point not in positions):
            point = None
        joints[j.name] = JointGeom(j.name, j.type, tuple(j.links), point, direction, j.radius, at)
    return joints


def _own_points(
    comp: Compiled, positions: dict[str, tuple[float, float]], joints: dict[str, JointGeom]
) -> dict[str, tuple[str, tuple[float, float]]]:
    """A cam given by profiles: its joint's name is the follower's own point (DESIGN § 1.2).

    The roller's centre (a circle's), the knife edge, or a translating flat face's point on
    the follower's path; a programme cam's is already so (its joint is a point of the
    follower).  A follower whose profile is a free curve, or an oscillating flat face, has
    no such point: there the name stays the contact point, and ``K@link`` says whose.
    """
    from mech.specs import Circle, Knife, Line

    mech = comp.mech
    out: dict[str, tuple[str, tuple[float, float]]] = {}
    for j in mech.joints:
        kind = kind_of(j)
        if not j.profiles or not kind.higher or kind.rolls or getattr(j.spec, "program", None) is not None:
            continue
        follower = j.links[1]
        prof = dict(j.profiles).get(follower)
        ref = prof.centre if isinstance(prof, Circle) else prof.point if isinstance(prof, Knife) else None
        if ref is not None and ref.name is not None and ref.name in positions:
            out[j.name] = (follower, positions[ref.name])
        elif isinstance(prof, Line):
            p = _face_on_path(mech, follower, prof, positions, joints)
            if p is not None:
                out[j.name] = (follower, p)
    return out


def _face_on_path(
    mech: object,
    follower: str,
    face: object,
    positions: dict[str, tuple[float, float]],
    joints: dict[str, JointGeom],
) -> tuple[float, float] | None:
    """Where a translating follower's flat face crosses its path now (None: no slide, or parallel)."""
    ground = mech.ground  # type: ignore[attr-defined]
    slide = next(
        (g for g in joints.values() if g.links == (follower, ground) and kind_of(g.type).keeps_angle), None
    )
    through = face.through  # type: ignore[attr-defined]
    if slide is None or slide.at is None or slide.direction is None or through.name not in positions:
        return None
    p = positions[through.name]
    toward = face.toward  # type: ignore[attr-defined]
    if toward is not None and toward.name in positions:
        q = positions[toward.name]
        d = (q[0] - p[0], q[1] - p[1])
    elif face.angle is not None:  # type: ignore[attr-defined]
        d = (math.cos(face.angle), math.sin(face.angle))  # type: ignore[attr-defined]
    else:
        return None
    (ax, ay), (ux, uy) = slide.at, slide.direction
    den = ux * d[1] - uy * d[0]
    if abs(den) <= 1e-12 * math.hypot(*d):
        return None
    t = ((p[0] - ax) * d[1] - (p[1] - ay) * d[0]) / den  # at + t u lies on the face
    return (ax + t * ux, ay + t * uy)
