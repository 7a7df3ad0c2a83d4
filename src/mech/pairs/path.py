"""What the path pairs share (prismatic, slot): a point of the first link on a line of the second.

``path`` is the line, fixed in the guide (the second link); ``point`` names the
slider's point that runs on it.  The row (one :class:`~mech.pairs.rows.OnLine`)
keeps that point on the line; a prismatic pair adds an
:class:`~mech.pairs.rows.Angle` row, the block turning with its guide.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from types import MappingProxyType
from typing import TYPE_CHECKING

from mech.fields import NAME, PATH, Fields, Reader, read_path
from mech.pairs.base import PairForce, PairKind
from mech.specs import Path, PathSpec, Ref, SlideSpec

if TYPE_CHECKING:
    from mech.model import Joint
    from mech.pairs.base import InstantView, Wrench
    from mech.pairs.rows import RowBuilder

__all__ = ["PathPair", "PathSpec", "path_angle", "path_direction"]

Vec = tuple[float, float]


def path_angle(path: Path, positions: Mapping[str, Vec], resolve: Callable[[str], str]) -> float:
    """Global direction (rad) of a path in the configuration ``positions`` (drawn, or solved).

    ``toward`` a point keeps the path fixed to the guide's points; otherwise the
    path's ``angle`` (0 when it gives neither, which the reader refuses anyway).
    ``resolve`` turns a joint's name into the location it stands for.
    """

    def xy(ref: Ref) -> Vec:
        return ref.xy if ref.xy is not None else positions[resolve(ref.name or "")]

    if path.toward is not None:
        (tx, ty), (qx, qy) = xy(path.through), xy(path.toward)
        return math.atan2(qy - ty, qx - tx)
    return float(path.angle or 0.0)


def path_direction(path: Path, positions: Mapping[str, Vec]) -> Vec | None:
    """A path's unit direction from the file (``toward`` a point, or its ``angle``) in ``positions``."""

    def where(ref: Ref | None) -> Vec | None:
        if ref is None:
            return None
        return ref.xy if ref.xy is not None else positions.get(ref.name or "")

    if path.toward is not None:
        p, q = where(path.through), where(path.toward)
        if p is not None and q is not None:
            n = math.hypot(q[0] - p[0], q[1] - p[1])
            return None if n == 0.0 else ((q[0] - p[0]) / n, (q[1] - p[1]) / n)
    if path.angle is not None:
        return (math.cos(path.angle), math.sin(path.angle))
    return None


class PathPair(PairKind):
    """A point of the slider (the first link) running on a straight line fixed in the guide."""

    keys = MappingProxyType({"path": PATH, "point": NAME})
    spec = SlideSpec()
    role = "path"
    dyad = "path of an rrp or rpr dyad"

    def read(self, r: Reader, fields: Fields, what: str, links: tuple[str, ...]) -> SlideSpec:
        path = r.optional(fields, "path", lambda n: read_path(r, n, what))
        point = r.optional(fields, "point", lambda n: r.name(n, f"`point` of {what}"))
        return SlideSpec(path=path, point=point)

    def rows(self, b: RowBuilder, j: Joint) -> None:
        """The point on its line (and, keeping the angle, the block turning with its guide)."""
        import numpy as np

        from mech.pairs.rows import Angle, OnLine

        ps = b.path(j.name)
        if ps is None:  # reported by the layout already
            return
        u = b.dir_local(ps.guide, b.path_angle(ps))
        slider, guide = b.index[ps.slider], b.index[ps.guide]
        s = b.to_local(ps.slider, b.scn(ps.point))
        t = b.to_local(ps.guide, b.where(ps.path.through))
        b.online.append(OnLine(slider, s, guide, t, np.array([-u[1], u[0]]), 0.0, ps.joint))
        b.path_dirs[ps.joint] = (guide, u)
        b.path_points[ps.joint] = (slider, ps.point)
        if self.keeps_angle:
            coef = {slider: 1.0, guide: -1.0}
            b.angle.append(Angle(coef, b.theta(ps.slider) - b.theta(ps.guide), ps.joint))

    def inspect(self, seen: InstantView, j: Joint) -> None:
        """A straight path: the I-centre at infinity perpendicular to it; a pin that may turn in a
        slot puts it on the normal through the pin."""
        u = seen.direction(j)
        if u is None and j.path is not None:
            u = path_direction(j.path, seen.positions)
        if u is not None:
            seen.slide(j.name, j.links[0], j.links[1], u, seen.at(j), turns=not self.keeps_angle)

    def forces(
        self, j: Joint, wrenches: Mapping[str, Wrench], at: Vec | None, direction: Vec | None
    ) -> list[PairForce]:
        """The normal force the guide (the second link) takes from the slider, and where it acts.

        Without friction the force is square to the path, ``N = F·n`` (n = k × u); with the
        pair's couple about the slider's point it acts ``offset = M/N`` along the path from
        that point (a block's side thrust is off its centre when the block is held from turning).
        """
        guide = j.links[1]
        if guide not in wrenches or at is None:
            return super().forces(j, wrenches, at, direction)
        fx, fy, m = wrenches[guide]
        u = direction or (1.0, 0.0)
        normal = float(-u[1] * fx + u[0] * fy)
        if normal == 0.0:  # no normal force: the guide takes a couple alone, acting nowhere
            return [PairForce(j.name, guide, j.links[0], (fx, fy), at, normal=normal, couple=float(m))]
        offset = float(m / normal)
        acts = (float(at[0] + offset * u[0]), float(at[1] + offset * u[1]))
        return [
            PairForce(
                j.name, guide, j.links[0], (fx, fy), acts, normal=normal, offset=offset, couple=float(m)
            )
        ]
