"""Backend-neutral drawings: a few primitives on a page measured in millimetres.

Every diagram (configuration, velocity polygon, acceleration polygon) is built
once as a :class:`Figure` of lines, polygons, circles and text, in page
millimetres with y pointing *down* (as on paper and in SVG).  Two backends
then paint the same figure: :mod:`mech.draw.svg` (pure Python, nothing to
import) and :mod:`mech.draw.raster` (matplotlib, for PNG and GIF).  Arrowheads
and hatching are computed here as polygons and lines, so both backends draw
identical pictures and neither needs to know what an arrow is.

Because the page is in millimetres and the SVG states its size in mm, a scale
such as "1 cm = 0.5 m/s" is true on paper when the drawing is printed at 100 %.

Nothing here imports numpy: figures are tuples of frozen dataclasses.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import field, replace

from mech._records import dataclass

__all__ = [
    "Circle",
    "Figure",
    "Item",
    "Line",
    "Page",
    "Poly",
    "Style",
    "Text",
    "Transform",
    "arrow",
    "best_spot",
    "hatch",
    "nice_scale",
    "place_label",
    "scale_bar",
]

Vec = tuple[float, float]

INK = "#1a1a1a"
#: Link colours: dark enough to print, distinct enough to tell links apart, and
#: reused for the same link's edges in the velocity and acceleration polygons.
PALETTE = ("#1f4e9c", "#b8461b", "#2e7d32", "#7b3f98", "#a0761a", "#00838f", "#ad1457", "#5d4037")


@dataclass(frozen=True, slots=True)
class Style:
    """How a primitive is painted: ``width`` and ``dash`` in mm, colours as ``#rrggbb``."""

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


@dataclass(frozen=True, slots=True)
class Poly:
    """A polyline, or a polygon when ``closed`` (a link plate, an arrowhead, a slider block)."""

    points: tuple[Vec, ...]
    closed: bool = True
    style: Style = Style()
    cls: str = ""
    name: str = ""


@dataclass(frozen=True, slots=True)
class Circle:
    """A circle of radius ``r`` mm (a pin, a point, a pitch circle)."""

    centre: Vec
    r: float
    style: Style = Style()
    cls: str = ""
    name: str = ""


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


@dataclass(frozen=True, slots=True)
class Figure:
    """A finished drawing: its page size (mm), its items in painting order, a title."""

    width: float
    height: float
    items: tuple[Item, ...]
    title: str = ""


@dataclass(frozen=True, slots=True)
class Transform:
    """World (m, m/s or m/s², y up) → page (mm, y down) at ``scale`` world units per cm.

    ``origin`` is the page point of the world point ``world``.
    """

    scale: float
    world: Vec
    origin: Vec

    def __call__(self, p: Vec) -> Vec:
        k = 10.0 / self.scale
        return (self.origin[0] + (p[0] - self.world[0]) * k, self.origin[1] - (p[1] - self.world[1]) * k)

    def length(self, d: float) -> float:
        """A world distance in page mm."""
        return d * 10.0 / self.scale


def nice_scale(extent: float, room_mm: float) -> float:
    """The smallest round scale (1, 2, 2.5 or 5 × 10ⁿ world units per cm) that fits.

    Textbooks state scales such as "1 cm = 20 mm" or "1 cm = 0.5 m/s" so that a
    reader can measure the drawing; a round number is what makes that easy.
    """
    if not (extent > 0 and math.isfinite(extent)):
        return 1.0
    need = extent / (room_mm / 10.0)
    k = math.floor(math.log10(need))
    for m in (1.0, 2.0, 2.5, 5.0, 10.0):
        s = m * 10.0**k
        if s >= need * (1 - 1e-9):
            return s
    return 10.0 ** (k + 1)  # pragma: no cover


def fmt(value: float, digits: int = 4) -> str:
    """A number for a caption: ``digits`` significant figures, no trailing zeros."""
    if value == 0 or not math.isfinite(value):
        return "0" if value == 0 else str(value)
    text = f"{value:.{digits}g}"
    if "e" in text:
        mant, exp = text.split("e")
        return f"{mant}×10^{int(exp)}"
    return text


@dataclass
class Page:
    """A mutable sheet used while one figure is built; :meth:`figure` freezes it.

    The builder is private to one drawing function, so mutation cannot leak;
    what leaves is an immutable :class:`Figure`.
    """

    width: float = 0.0
    height: float = 0.0
    items: list[Item] = field(default_factory=list)

    def add(self, *items: Item) -> None:
        self.items.extend(items)

    def extend(self, items: Iterable[Item]) -> None:
        self.items.extend(items)

    def place(self, other: Figure, dx: float, dy: float) -> None:
        """Paste another figure with its top-left corner at (dx, dy)."""
        self.items.extend(shift(item, dx, dy) for item in other.items)
        self.width = max(self.width, dx + other.width)
        self.height = max(self.height, dy + other.height)

    def figure(self, title: str = "") -> Figure:
        return Figure(self.width, self.height, tuple(self.items), title)


def shift(item: Item, dx: float, dy: float) -> Item:
    """The same item moved by (dx, dy) mm."""

    def m(p: Vec) -> Vec:
        return (p[0] + dx, p[1] + dy)

    if isinstance(item, Line):
        return replace(item, p0=m(item.p0), p1=m(item.p1))
    if isinstance(item, Poly):
        return replace(item, points=tuple(m(p) for p in item.points))
    if isinstance(item, Circle):
        return replace(item, centre=m(item.centre))
    return replace(item, at=m(item.at))


# -- composite shapes: arrows, hatching, scale bars ---------------------------------------
def arrow(
    p0: Vec,
    p1: Vec,
    colour: str = INK,
    width: float = 0.35,
    *,
    cls: str = "",
    name: str = "",
    head: float = 2.2,
    dash: tuple[float, ...] = (),
) -> list[Item]:
    """A vector ``p0 → p1`` (page mm): its shaft as a :class:`Line`, its head as a filled triangle.

    The shaft is the whole vector (so its length can be read back from the
    SVG); the head is drawn over its end.  A vector shorter than the head gets
    no head: a dot-sized arrow would only hide the point.
    """
    out: list[Item] = [Line(p0, p1, Style(colour, width, dash=dash), cls, name)]
    dx, dy = p1[0] - p0[0], p1[1] - p0[1]
    n = math.hypot(dx, dy)
    if n > 1.5 * head:
        ux, uy = dx / n, dy / n
        bx, by = p1[0] - ux * head, p1[1] - uy * head
        w = head * 0.36
        tri = ((p1[0], p1[1]), (bx - uy * w, by + ux * w), (bx + uy * w, by - ux * w))
        out.append(Poly(tri, True, Style(None, 0.0, fill=colour), "arrowhead", name))
    return out


def hatch(
    p0: Vec, p1: Vec, side: float = 1.0, depth: float = 2.0, pitch: float = 1.6, colour: str = INK
) -> list[Item]:
    """Ground: a base line ``p0 → p1`` with short slanted strokes on one side (``side`` ±1).

    This is the textbook sign for "fixed to the frame" under pivots and along
    slider guides.
    """
    dx, dy = p1[0] - p0[0], p1[1] - p0[1]
    n = math.hypot(dx, dy)
    if n == 0:
        return []
    ux, uy = dx / n, dy / n
    nx, ny = -uy * side, ux * side  # page normal toward the hatched side
    items: list[Item] = [Line(p0, p1, Style(colour, 0.35), "ground")]
    count = max(int(n / pitch), 1)
    for i in range(count + 1):
        t = i * n / count
        a = (p0[0] + ux * t, p0[1] + uy * t)
        b = (a[0] + nx * depth - ux * depth * 0.8, a[1] + ny * depth - uy * depth * 0.8)
        items.append(Line(a, b, Style(colour, 0.2), "hatch"))
    return items


def scale_bar(at: Vec, scale: float, unit: str, cm: int = 2, colour: str = INK) -> list[Item]:
    """A bar ``cm`` centimetres long with a tick per cm and the caption "1 cm = … unit".

    ``at`` is the bar's left end (page mm).  The caption states the scale the
    way the notes do, so a reader with a ruler can measure the diagram.
    """
    x, y = at
    items: list[Item] = [Line((x, y), (x + 10 * cm, y), Style(colour, 0.4), "scalebar")]
    for i in range(cm + 1):
        items.append(Line((x + 10 * i, y - 1.2), (x + 10 * i, y + 1.2), Style(colour, 0.3), "scalebar"))
    items.append(
        Text((x + 10 * cm + 2.5, y), f"1 cm = {fmt(scale)} {unit}", 3.0, "start", colour, cls="scale")
    )
    return items


def bbox(points: Sequence[Vec]) -> tuple[float, float, float, float]:
    """(xmin, ymin, xmax, ymax) of some points."""
    xs = [p[0] for p in points]
    ys = [p[1] for p in points]
    return min(xs), min(ys), max(xs), max(ys)


# -- label placement ----------------------------------------------------------------------
def _obstacles(items: Sequence[Item]) -> tuple[list[tuple[Vec, Vec, float]], list[tuple[Vec, float]]]:
    """Segments (with a softness bonus, mm) and discs already drawn, which labels keep clear of.

    Dashed construction lines are soft: a label may sit closer to them than
    to a link or a vector.
    """
    segs: list[tuple[Vec, Vec, float]] = []
    discs: list[tuple[Vec, float]] = []
    for item in items:
        if isinstance(item, Line):
            segs.append((item.p0, item.p1, 1.2 if item.style.dash else 0.0))
        elif isinstance(item, Poly):
            pts = item.points
            soft = 1.2 if item.style.dash else 0.0
            segs.extend(
                (a, b, soft) for a, b in zip(pts, pts[1:] + (pts[:1] if item.closed else ()), strict=False)
            )
        elif isinstance(item, Circle):
            discs.append((item.centre, item.r))
        elif isinstance(item, Text):
            discs.append((item.at, 0.3 * item.size * len(item.text)))
    return segs, discs


def _seg_dist(p: Vec, a: Vec, b: Vec) -> float:
    dx, dy = b[0] - a[0], b[1] - a[1]
    n2 = dx * dx + dy * dy
    t = 0.0 if n2 == 0 else max(0.0, min(1.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / n2))
    return math.dist(p, (a[0] + t * dx, a[1] + t * dy))


#: Clearance beyond this (mm) gains a label nothing: a segment farther from all of a candidate's
#: samples cannot change its score, and is not measured (a traced path of 10,000 steps has
#: 10,000 segments, nearly all of them far from any one label).
_CAP = 3.0


def _near_segments(
    segs: Sequence[tuple[Vec, Vec, float]], c: Vec, reach_x: float, reach_y: float
) -> list[tuple[Vec, Vec, float]]:
    """The segments whose bounding box comes within ``reach`` of ``c`` on both axes.

    Any other segment lies at least :data:`_CAP` from every sample of the label's box
    (the samples are within half its width and 0.8 of half its height of ``c``).
    """
    x0, x1, y0, y1 = c[0] - reach_x, c[0] + reach_x, c[1] - reach_y, c[1] + reach_y
    return [
        s
        for s in segs
        if min(s[0][0], s[1][0]) <= x1
        and max(s[0][0], s[1][0]) >= x0
        and min(s[0][1], s[1][1]) <= y1
        and max(s[0][1], s[1][1]) >= y0
    ]


def text_box(text: str, size: float) -> Vec:
    """Approximate half width and half height (mm) of a label: enough to keep labels apart."""
    return (0.33 * size * len(text) + 0.4, 0.55 * size)


def best_spot(candidates: Sequence[tuple[Vec, float]], text: str, size: float, drawn: Sequence[Item]) -> Vec:
    """Of candidate label centres (each with a preference bonus), the one clearest of ``drawn``.

    Clearance is sampled over the label's box and capped at 3 mm (beyond
    that, nothing is gained by moving further), then the bonus decides.
    """
    segs, discs = _obstacles(drawn)
    half_w, half_h = text_box(text, size)
    xs, ys = [c[0] for c, _ in candidates], [c[1] for c, _ in candidates]
    if xs:  # first the segments near any candidate (one pass), then near each
        middle = ((min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2)
        spread = ((max(xs) - min(xs)) / 2, (max(ys) - min(ys)) / 2)
        segs = _near_segments(segs, middle, spread[0] + half_w + _CAP, spread[1] + 0.8 * half_h + _CAP)
    best: tuple[float, Vec] | None = None
    for c, bonus in candidates:
        samples = [(c[0] + dx * half_w, c[1] + dy * half_h) for dx in (-1, 0, 1) for dy in (-0.8, 0, 0.8)]
        near = _near_segments(segs, c, half_w + _CAP, 0.8 * half_h + _CAP)
        clear = min(
            [_seg_dist(q, a, b) + soft for q in samples for a, b, soft in near]
            + [math.dist(q, dc) - dr for q in samples for dc, dr in discs]
            + [9.0]
        )
        score = min(clear, _CAP) + bonus
        if best is None or score > best[0] + 1e-9:
            best = (score, c)
    assert best is not None
    return best[1]


def place_label(
    here: Vec,
    text: str,
    size: float,
    prefer: Vec,
    drawn: Sequence[Item],
    *,
    colour: str = INK,
    italic: bool = False,
    bold: bool = False,
    cls: str = "label",
) -> Text:
    """A label beside the point ``here`` where it overlaps the least of what is ``drawn``.

    Sixteen directions at two distances are tried, with a small bonus for the
    ``prefer`` direction (away from the lines meeting there) and for being near.
    """
    half_w, half_h = text_box(text, size)
    candidates = []
    for k in range(16):
        a = 2 * math.pi * k / 16
        u = (math.cos(a), math.sin(a))
        edge = min(abs(u[0]) * half_w + abs(u[1]) * half_h, max(half_w, half_h))
        for r, cost in ((2.6, 0.0), (4.6, 0.5)):
            c = (here[0] + u[0] * (r + edge), here[1] + u[1] * (r + edge))
            candidates.append((c, 0.6 * (u[0] * prefer[0] + u[1] * prefer[1]) - cost))
    c = best_spot(candidates, text, size, drawn)
    return Text(c, text, size, "middle", colour, italic=italic, bold=bold, cls=cls)
