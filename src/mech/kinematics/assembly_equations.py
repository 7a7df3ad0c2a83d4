"""The equations of the drawn configuration: what the file's data say about where each location is.

Unknowns are the positions of the locations not placed by ``at``; each
equation (:class:`Eq`, one or two rows on the positions of named locations,
scaled) is a length (:class:`Dist`), a drive angle (:class:`Dir`,
:class:`RelDir`), a point on a path (:class:`OnLine`, :class:`OnLineToward`,
:class:`Same`), a relative placement (:class:`Rel`) or the weak spring that
holds a moving location to its drawing (:class:`Spring`).  :func:`equations`
writes them all from a layout; :func:`placements` reads what the file places.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np

from mech.errors import Where
from mech.kinematics.layout import Layout
from mech.model import Joint, Mechanism, Placement, Point, Ref
from mech.pairs import kind_of

__all__ = [
    "Dir",
    "Dist",
    "Eq",
    "OnLine",
    "OnLineToward",
    "Rel",
    "RelDir",
    "Same",
    "Spring",
    "equations",
    "placements",
    "where_of",
]


class Eq:
    """One equation (1 or 2 rows) on the positions of named locations (scaled)."""

    names: tuple[str, ...] = ()
    rows = 1
    text = ""  # what the equation says, in the file's words (set by each kind)
    where: Where | None = None  # the line of the file that set this equation, for messages

    def value(self, p: Sequence[np.ndarray]) -> tuple[np.ndarray, list[np.ndarray]]:
        """Residual (rows,) and its gradient (rows, 2) for each name."""
        raise NotImplementedError


class Dist(Eq):
    def __init__(self, a: str, b: str, length: float, text: str) -> None:
        self.names, self.length, self.text = (a, b), length, text

    def value(self, p: Sequence[np.ndarray]) -> tuple[np.ndarray, list[np.ndarray]]:
        w = p[1] - p[0]
        d = math.hypot(w[0], w[1])
        e = w / d if d > 0 else np.array([1.0, 0.0])
        return np.array([d - self.length]), [-e[None, :], e[None, :]]


class Dir(Eq):
    """Drive: ``b`` lies on the ray from ``o`` at angle ``phi``."""

    def __init__(self, o: str, b: str, phi: float, text: str) -> None:
        self.names, self.phi, self.text = (o, b), phi, text
        self.n = np.array([-math.sin(phi), math.cos(phi)])

    def value(self, p: Sequence[np.ndarray]) -> tuple[np.ndarray, list[np.ndarray]]:
        return np.array([self.n @ (p[1] - p[0])]), [-self.n[None, :], self.n[None, :]]

    def angle(self, p: Sequence[np.ndarray]) -> float:
        """The ray's global direction (rad) at positions ``p``."""
        del p
        return self.phi

    def forward(self, p: Sequence[np.ndarray]) -> bool:
        """True when ``b`` is on the ray itself, not on its opposite half (angle + 180°)."""
        w = p[1] - p[0]
        psi = self.angle(p)
        return bool(w[0] * math.cos(psi) + w[1] * math.sin(psi) >= 0.0)


class RelDir(Dir):
    """Drive relative to a link: ``b`` on the ray from ``o`` at ``phi`` plus the direction ``a0 → a1``.

    ``a0 → a1`` is the reference link's line, so its direction is the angle θ_a
    ``mech`` reports for that link, and ``phi`` is θ_b − θ_a (DESIGN § 1.1).
    """

    def __init__(self, o: str, b: str, a0: str, a1: str, phi: float, text: str) -> None:
        super().__init__(o, b, phi, text)
        self.names = (o, b, a0, a1)

    def angle(self, p: Sequence[np.ndarray]) -> float:
        d = p[3] - p[2]
        return self.phi + math.atan2(d[1], d[0])

    def value(self, p: Sequence[np.ndarray]) -> tuple[np.ndarray, list[np.ndarray]]:
        psi = self.angle(p)
        n = np.array([-math.sin(psi), math.cos(psi)])
        e = np.array([math.cos(psi), math.sin(psi)])
        w = p[1] - p[0]
        d = p[3] - p[2]
        dd = float(d @ d) or 1.0
        dpsi = np.array([-d[1], d[0]]) / dd  # ∂ψ/∂a1 (and −∂ψ/∂a0)
        g = -float(e @ w) * dpsi
        return np.array([n @ w]), [-n[None, :], n[None, :], -g[None, :], g[None, :]]


class OnLine(Eq):
    """``p`` on the line through ``t`` at fixed direction ``u`` (a path given by angle)."""

    def __init__(self, pt: str, t: str, u: np.ndarray, text: str) -> None:
        self.names, self.text = (pt, t), text
        self.n = np.array([-u[1], u[0]])

    def value(self, p: Sequence[np.ndarray]) -> tuple[np.ndarray, list[np.ndarray]]:
        return np.array([self.n @ (p[0] - p[1])]), [self.n[None, :], -self.n[None, :]]


class OnLineToward(Eq):
    """``p`` on the line through ``t`` and ``q``: ``(q − t) × (p − t) / |q − t| = 0``."""

    def __init__(self, pt: str, t: str, q: str, text: str) -> None:
        self.names, self.text = (pt, t, q), text

    def value(self, p: Sequence[np.ndarray]) -> tuple[np.ndarray, list[np.ndarray]]:
        w, z = p[2] - p[1], p[0] - p[1]
        m = math.hypot(w[0], w[1]) or 1.0
        c = w[0] * z[1] - w[1] * z[0]
        gp = np.array([-w[1], w[0]]) / m
        gq = np.array([z[1], -z[0]]) / m - c * w / m**3
        return np.array([c / m]), [gp[None, :], (-gp - gq)[None, :], gq[None, :]]


class Same(Eq):
    """``p = t``: a slider's synthetic point drawn at its path's ``through``."""

    rows = 2

    def __init__(self, pt: str, t: str, text: str) -> None:
        self.names, self.text = (pt, t), text

    def value(self, p: Sequence[np.ndarray]) -> tuple[np.ndarray, list[np.ndarray]]:
        return p[0] - p[1], [np.eye(2), -np.eye(2)]


class Spring(Eq):
    """A weak spring ``w·(p − drawn)``: a moving location drawn with ``at`` (precision of a drawing).

    The weight is small enough that exact data (lengths, angles) absorb only w² of any
    disagreement, and large enough to fix a location nothing else fixes.
    """

    rows = 2
    weight = 1e-3

    def __init__(self, pt: str, drawn: np.ndarray) -> None:
        self.names, self.drawn, self.text = (pt,), drawn, f"{pt} as drawn"

    def value(self, p: Sequence[np.ndarray]) -> tuple[np.ndarray, list[np.ndarray]]:
        return self.weight * (p[0] - self.drawn), [self.weight * np.eye(2)]


class Rel(Eq):
    """``p = o + u·e + v·e⊥`` with ``e`` the unit vector ``o → t`` (a relative placement)."""

    rows = 2

    def __init__(self, pt: str, o: str, t: str, u: float, v: float, text: str) -> None:
        self.names, self.u, self.v, self.text = (pt, o, t), u, v, text

    def value(self, p: Sequence[np.ndarray]) -> tuple[np.ndarray, list[np.ndarray]]:
        w = p[2] - p[1]
        m = math.hypot(w[0], w[1]) or 1.0
        e = w / m
        perp = np.array([-e[1], e[0]])
        r = p[0] - p[1] - self.u * e - self.v * perp
        rot = np.array([[0.0, -1.0], [1.0, 0.0]])
        dm = (self.u * np.eye(2) + self.v * rot) @ (np.eye(2) - np.outer(e, e)) / m
        return r, [np.eye(2), -np.eye(2) + dm, -dm]


def placements(
    lay: Layout,
) -> tuple[dict[str, tuple[float, float]], dict[str, tuple[float, float]], dict[str, Placement]]:
    """Locations drawn with ``at`` (and path coordinates), those with a ``near`` hint, every placement."""
    mech = lay.mech
    known: dict[str, tuple[float, float]] = {}
    near: dict[str, tuple[float, float]] = {}
    places: dict[str, Placement] = {}
    for j in mech.joints:
        places[j.name] = j.place
    for pt in mech.points:
        places[pt.name] = pt.place
    drawn = {j.name: at for j in mech.joints if j.place.at is None and (at := kind_of(j).drawn_at(mech, j))}
    for name in lay.carriers:
        pl = places.get(name)
        if pl is None:
            continue
        if pl.at is not None:
            known[name] = pl.at
        elif name in drawn:  # drawn by the pair's own data (a follower's point, by its programme)
            known[name] = drawn[name]
        elif pl.near is not None:
            near[name] = pl.near
    # Path references given as coordinates become synthetic known locations.
    for ps in lay.paths:
        for tag, ref in (("through", ps.path.through), ("toward", ps.path.toward)):
            if ref is not None and ref.xy is not None:
                known[f"#{ps.joint}.{tag}"] = ref.xy
    return known, near, places


def equations(
    lay: Layout,
    places: dict[str, Placement],
    scale: float,
    drive_angles: Sequence[float | None] | None,
    fmt: Callable[[float], str],
) -> tuple[list[Eq], list[float | None]]:
    """Every equation the file's data give (lengths, drive angles, paths, relative placements),
    and each drive's angle (the file's, else ``drive_angles``', else None: read from the drawing).
    """
    mech = lay.mech
    eqs: list[Eq] = []
    for ln in mech.lengths:
        a, b = lay.resolve(ln.a), lay.resolve(ln.b)
        eqs.append(Dist(a, b, ln.value / scale, f"length {ln.a}{ln.b} = {fmt(ln.value)}"))
        eqs[-1].where = ln.where
    resolved_angles: list[float | None] = []
    deg = mech.angle_unit == "deg"
    for k, spec in enumerate(lay.drives):
        angle = spec.drive.angle
        if angle is None and drive_angles is not None and k < len(drive_angles):
            angle = drive_angles[k]
        resolved_angles.append(angle)
        if spec.link is None or angle is None or spec.toward is None:
            continue
        shown = f"{math.degrees(angle):.6g}°" if deg else f"{angle:.6g} rad"
        if spec.reference_line is not None:
            a0, a1 = spec.reference_line
            text = f"drive angle {shown} relative to {spec.reference}"
            eqs.append(RelDir(spec.pivot, spec.toward, a0, a1, angle, text))  # type: ignore[arg-type]
        else:
            eqs.append(Dir(spec.pivot, spec.toward, angle, f"drive angle {shown}"))  # type: ignore[arg-type]
        eqs[-1].where = spec.drive.where
    eqs += _path_equations(lay)
    for name, pl in places.items():
        if pl.origin is None or pl.toward is None or name not in lay.carriers:
            continue
        if pl.offset is not None:
            u, v = pl.offset
        else:
            u, v = (pl.distance or 0.0), 0.0
        eqs.append(
            Rel(
                name,
                lay.resolve(pl.origin),
                lay.resolve(pl.toward),
                u / scale,
                v / scale,
                f"{name} placed from {pl.origin} toward {pl.toward}",
            )
        )
        eqs[-1].where = where_of(mech, name)
    return eqs, resolved_angles


def _path_equations(lay: Layout) -> list[Eq]:
    """A prismatic or slot joint's point on its path (through a point, toward another or at an angle)."""

    def ref_name(ps_joint: str, tag: str, ref: Ref) -> str:
        return lay.resolve(ref.name) if ref.name is not None else f"#{ps_joint}.{tag}"

    eqs: list[Eq] = []
    for ps in lay.paths:
        path_where = lay.mech.joint(ps.joint).where
        t = ref_name(ps.joint, "through", ps.path.through)
        text = f"{ps.point} on the path of {ps.type} joint {ps.joint}"
        if ps.point.startswith("#"):
            eqs.append(Same(ps.point, t, f"the point of {ps.slider} on the path of {ps.joint}"))
            eqs[-1].where = path_where
            continue
        if ps.path.toward is not None:
            eqs.append(OnLineToward(ps.point, t, ref_name(ps.joint, "toward", ps.path.toward), text))
            eqs[-1].where = path_where
        elif ps.path.angle is not None:
            stroke = ps.path.angle
            eqs.append(OnLine(ps.point, t, np.array([math.cos(stroke), math.sin(stroke)]), text))
            eqs[-1].where = path_where
    return eqs


def where_of(mech: Mechanism, name: str) -> Where | None:
    """The line of the file that defines the joint or point ``name`` (None if neither)."""
    located: list[Joint | Point] = [*mech.joints, *mech.points]
    return next((x.where for x in located if x.name == name), None)
