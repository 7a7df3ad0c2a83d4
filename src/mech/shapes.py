"""The shapes a drawing is made of: lines, polylines and polygons, circles, texts, and their style.

One set of frozen records, read by everything that draws.  A pair kind's glyph
(:meth:`mech.pairs.base.PairKind.glyph`, the notes' signs in :mod:`mech.pairs.glyph`) gives
them, every diagram of :mod:`mech.draw` is a :class:`~mech.draw.scene.Figure` of them, and the
SVG writer and matplotlib paint them; nothing converts one vocabulary into another.

Coordinates are page millimetres, y down (as on paper and in SVG).  Two fields serve a
glyph, which is made before the drawing's scale is final: ``world`` says a shape's
coordinates and radius are world metres, y up (a pitch circle, a follower's stem: they belong
to the mechanism's size, and the drawing keeps them in view), and ``layer`` says where among
the links it is painted (:data:`mech.pairs.glyph.LAYERS`).  What a figure holds is on the
page, in painting order: ``world`` false, ``layer`` no longer read.

Nothing here imports numpy: a figure is tuples of frozen dataclasses.
"""

from __future__ import annotations

from mech._records import dataclass

__all__ = ["INK", "Circle", "Item", "Line", "Poly", "Style", "Text", "Vec"]

Vec = tuple[float, float]

INK = "#1a1a1a"


@dataclass(frozen=True, slots=True)
class Style:
    """How a shape is painted: ``width`` and ``dash`` in mm, colours as ``#rrggbb``."""

    stroke: str | None = INK
    width: float = 0.35
    fill: str | None = None
    fill_opacity: float = 1.0
    dash: tuple[float, ...] = ()


@dataclass(frozen=True, slots=True)
class Line:
    """A straight segment ``p0 → p1``.  ``cls``/``name`` tag it in the SVG (tests read them)."""

    p0: Vec
    p1: Vec
    style: Style = Style()
    cls: str = ""
    name: str = ""
    layer: str = ""
    world: bool = False


@dataclass(frozen=True, slots=True)
class Poly:
    """A polyline, or a polygon when ``closed`` (a link plate, an arrowhead, a slider block)."""

    points: tuple[Vec, ...]
    closed: bool = True
    style: Style = Style()
    cls: str = ""
    name: str = ""
    layer: str = ""
    world: bool = False


@dataclass(frozen=True, slots=True)
class Circle:
    """A circle of radius ``r`` (mm, or metres when ``world``): a pin, a point, a pitch circle."""

    centre: Vec
    r: float
    style: Style = Style()
    cls: str = ""
    name: str = ""
    layer: str = ""
    world: bool = False


@dataclass(frozen=True, slots=True)
class Text:
    """A label whose ``anchor`` (start, middle, end) and vertical middle sit at ``at``.

    ``size`` is the cap-to-baseline height in mm of the font (3.5 mm ≈ 10 pt).
    """

    at: Vec
    text: str
    size: float = 3.2
    anchor: str = "middle"
    colour: str = INK
    italic: bool = False
    bold: bool = False
    cls: str = ""


Item = Line | Poly | Circle | Text
