"""The joints of a configuration diagram: what each pair kind's glyph gives, painted.

Each kind says how it is drawn (:meth:`mech.pairs.base.PairKind.glyph`) in the shapes every
drawing is made of (:mod:`mech.shapes`); this module is the other side of that protocol: a
:class:`Sheet` that answers what a glyph may read (positions, directions, the transform,
colours), and :func:`paint`, which puts one layer of the shapes on the page (a shape in world
metres placed by the transform, the others as they are).  Nothing here asks which kind a joint
is.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import replace
from typing import TYPE_CHECKING

from mech.draw.scene import Transform, bbox
from mech.model import Joint, Mechanism
from mech.pairs import kind_of
from mech.pairs.glyph import LAYERS, SHAPES, Shape
from mech.shapes import INK, Item, Line, Poly

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
    """Every joint's glyph, in the file's order, a shape given twice (a pin and a slot's pin) once.

    Raises
    ------
    TypeError
        A kind's glyph gave something other than a line, outline or circle of :mod:`mech.shapes`
        on one of :data:`mech.pairs.glyph.LAYERS` (a plug-in's mistake, named).
    """
    out: dict[Shape, None] = {}
    for j in mech.joints:
        kind = kind_of(j)
        for shape in kind.glyph(sheet, j):
            if not isinstance(shape, SHAPES) or shape.layer not in LAYERS:
                raise TypeError(
                    f"the {kind.name} pair's glyph gave {shape!r}: a glyph gives mech.shapes' "
                    f"Line, Poly or Circle, each on one of the layers {', '.join(LAYERS)}"
                )
            out.setdefault(shape, None)
    return list(out)


def world_points(shapes: Iterable[Shape]) -> list[Vec]:
    """The world points the glyphs reach (ends of stems, boxes round pitch circles and profiles)."""
    out: list[Vec] = []
    for s in shapes:
        if not s.world:
            continue
        if isinstance(s, Line):
            out += [s.p0, s.p1]
        elif isinstance(s, Poly):
            out += list(s.points)
        else:
            c, r = s.centre, s.r
            out += [(c[0] - r, c[1] - r), (c[0] + r, c[1] + r)]
    return out


def paint(shapes: Iterable[Shape], tr: Transform, layer: str) -> list[Item]:
    """The shapes on ``layer`` (one of :data:`mech.pairs.glyph.LAYERS`), on the page: in page mm."""
    assert layer in LAYERS, layer
    return [_placed(s, tr) if s.world else s for s in shapes if s.layer == layer]


def _placed(s: Shape, tr: Transform) -> Shape:
    """A shape given in world metres, placed on the page by ``tr``."""
    if isinstance(s, Line):
        return replace(s, p0=tr(s.p0), p1=tr(s.p1), world=False)
    if isinstance(s, Poly):
        return replace(s, points=tuple(tr(p) for p in s.points), world=False)
    return replace(s, centre=tr(s.centre), r=tr.length(s.r), world=False)
