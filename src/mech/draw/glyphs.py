"""The joints of a configuration diagram: what each pair kind's glyph gives, painted.

Each kind says how it is drawn (:meth:`mech.pairs.base.PairKind.glyph`) in the small
vocabulary of :mod:`mech.pairs.glyph`; this module is the other side of that protocol: a
:class:`Sheet` that answers what a glyph may read (positions, directions, the transform,
colours), and :func:`paint`, which turns the shapes into the scene's items.  Nothing here
asks which kind a joint is.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping
from typing import TYPE_CHECKING

from mech.draw.scene import INK, Circle, Item, Line, Poly, Style, Transform, bbox, hatch
from mech.model import Joint, Mechanism
from mech.pairs import kind_of
from mech.pairs.glyph import LAYERS, Hatch, Outline, Pen, Ring, Segment, Shape

if TYPE_CHECKING:  # pragma: no cover
    from mech.kinematics.result import Kinematics

__all__ = ["Sheet", "glyphs", "paint", "world_points"]

Vec = tuple[float, float]


class Sheet:
    """What a glyph may read of one configuration diagram (:class:`mech.pairs.glyph.GlyphView`)."""

    def __init__(
        self,
        mech: Mechanism,
        kin: Kinematics,
        positions: Mapping[str, Vec],
        directions: Mapping[str, Vec],
        transform: Transform,
        colours: Mapping[str, str],
        *,
        frame: bool = False,
        carried: Callable[[str], Callable[[Vec], Vec] | None] | None = None,
    ) -> None:
        self.mech, self.kin, self.positions, self.frame = mech, kin, positions, frame
        self._dirs, self._tr, self._colours, self._carried = directions, transform, colours, carried
        fin = [p for p in positions.values() if math.isfinite(p[0]) and math.isfinite(p[1])]
        x0, y0, x1, y1 = bbox(fin) if fin else (0.0, 0.0, 0.0, 0.0)
        self._extent = max(x1 - x0, y1 - y0)

    def point(self, j: Joint) -> str | None:
        geom = self.kin.joints.get(j.name)
        name = geom.point if geom is not None and geom.point is not None else j.name
        return name if name in self.positions else None

    def direction(self, j: Joint) -> Vec | None:
        if j.name in self._dirs:
            return self._dirs[j.name]
        geom = self.kin.joints.get(j.name)
        return geom.direction if geom is not None else None

    def page(self, p: Vec) -> Vec:
        return self._tr(p)

    def colour(self, link: str) -> str:
        return self._colours.get(link, INK)

    def pivot(self, link: str) -> Vec | None:
        for j in self.mech.joints:
            if (
                kind_of(j).role == "pin"
                and link in j.links
                and self.mech.ground in j.links
                and j.name in self.positions
            ):
                return self.positions[j.name]
        return None

    def body(self, link: str) -> list[Vec]:
        return [
            self.positions[n]
            for n, links in self.kin.carriers.items()
            if link in links and n in self.positions
        ]

    def guide(self, link: str) -> Vec | None:
        for j in self.mech.joints:
            if kind_of(j).role == "path" and j.links[0] == link and j.links[1] == self.mech.ground:
                return self.direction(j)
        return None

    def carried(self, link: str) -> Callable[[Vec], Vec] | None:
        return self._carried(link) if self._carried is not None else None

    def extent(self) -> float:
        return self._extent


def glyphs(mech: Mechanism, sheet: Sheet) -> list[Shape]:
    """Every joint's glyph, in the file's order, a shape given twice (a pin and a slot's pin) once."""
    out: dict[Shape, None] = {}
    for j in mech.joints:
        for shape in kind_of(j).glyph(sheet, j):
            out.setdefault(shape, None)
    return list(out)


def world_points(shapes: Iterable[Shape]) -> list[Vec]:
    """The world points the glyphs reach (ends of stems, boxes round pitch circles and profiles)."""
    out: list[Vec] = []
    for s in shapes:
        if isinstance(s, Segment) and s.world:
            out += [s.p0, s.p1]
        elif isinstance(s, Outline) and s.world:
            out += list(s.points)
        elif isinstance(s, Ring) and s.world:
            c, r = s.centre, s.r
            out += [(c[0] - r, c[1] - r), (c[0] + r, c[1] + r)]
    return out


def _style(pen: Pen) -> Style:
    return Style(pen.stroke, pen.width, pen.fill, pen.fill_opacity, pen.dash)


def paint(shapes: Iterable[Shape], tr: Transform, layer: str) -> list[Item]:
    """The scene's items of the shapes on ``layer`` (one of :data:`mech.pairs.glyph.LAYERS`)."""
    assert layer in LAYERS, layer
    items: list[Item] = []
    for s in shapes:
        if s.layer != layer:
            continue
        if isinstance(s, Hatch):
            items.extend(hatch(s.p0, s.p1, side=s.side, depth=s.depth))
        elif isinstance(s, Segment):
            p0, p1 = (tr(s.p0), tr(s.p1)) if s.world else (s.p0, s.p1)
            items.append(Line(p0, p1, _style(s.pen), s.cls, s.name))
        elif isinstance(s, Outline):
            pts = tuple(tr(p) for p in s.points) if s.world else s.points
            items.append(Poly(pts, s.closed, _style(s.pen), s.cls, s.name))
        elif isinstance(s, Ring):
            centre = tr(s.centre) if s.world else s.centre
            items.append(Circle(centre, tr.length(s.r) if s.world else s.r, _style(s.pen), s.cls, s.name))
    return items
