"""Backend-neutral drawings: the shapes of :mod:`mech.shapes` on a page measured in millimetres.

Every diagram (configuration, velocity polygon, acceleration polygon) is built
once as a :class:`Figure` of lines, polygons, circles and text (:mod:`mech.shapes`),
in page millimetres with y pointing *down* (as on paper and in SVG).  Two backends
then paint the same figure: :mod:`mech.draw.svg` (pure Python, nothing to
import) and :mod:`mech.draw.raster` (matplotlib, for PNG and GIF).  Arrowheads
and scale bars are computed here as polygons and lines, so both backends draw
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
from mech.shapes import INK, Circle, Item, Line, Poly, Style, Text, Vec

__all__ = [
    "Figure",
    "Page",
    "Transform",
    "arrow",
    "best_spot",
    "clashes",
    "item_rect",
    "leader",
    "nice_scale",
    "place_label",
    "scale_bar",
    "text_rect",
    "text_width",
]

#: Link colours: dark enough to print, distinct enough to tell links apart, and
#: reused for the same link's edges in the velocity and acceleration polygons.
PALETTE = ("#1f4e9c", "#b8461b", "#2e7d32", "#7b3f98", "#a0761a", "#00838f", "#ad1457", "#5d4037")


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
        return f"{mant}×10{superscript(int(exp))}"
    return text


_SUPER = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")


def superscript(n: int) -> str:
    """An exponent typeset as superscript characters (``-5`` → ``⁻⁵``), as print writes 10⁻⁵."""
    return str(n).translate(_SUPER)


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

    def figure(self, title: str = "", *, fit: bool = True) -> Figure:
        """The finished figure; with ``fit``, grown (and its items moved) so that nothing is cut.

        A label placed beyond the sheet's edge, or a title longer than the sheet is wide,
        makes the sheet larger rather than being clipped: the page stays in millimetres, so
        every scale on it still holds.  Animation frames keep their size (``fit=False``).
        """
        if fit and self.items:
            x0, y0, x1, y1 = bbox([p for item in self.items for p in _corners(item_rect(item))])
            dx, dy = max(0.0, EDGE - x0), max(0.0, EDGE - y0)
            if dx or dy:
                self.items = [shift(item, dx, dy) for item in self.items]
            self.width = max(self.width + dx, x1 + dx + EDGE)
            self.height = max(self.height + dy, y1 + dy + EDGE)
        return Figure(self.width, self.height, tuple(self.items), title)


#: The least white (mm) round everything drawn on a fitted sheet.
EDGE = 1.5


def _corners(box: tuple[float, float, float, float]) -> tuple[Vec, Vec]:
    return ((box[0], box[1]), (box[2], box[3]))


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


# -- composite shapes: arrows, scale bars ---------------------------------------
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
_ADVANCE = (  # DejaVu Sans advance widths of " " … "~" (em/1000, four digits each), regular then bold
    (
        "031804010460083806360950078002750390039005000838031803610318033706360636063606360636063606360636"
        "063606360337033708380838083805311000068406860698077006320575077507520295029506560557086307480787"
        "060307870695063506110732068409890685061106850390033703900838050005000613063505500635061503520635"
        "06340278027805790278097406340612063506350411052103920634059208180592059205250636033706360838"
    ),
    (
        "034804560521083806961002087203060457045705230838038004150380036506960696069606960696069606960696"
        "069606960400040008380838083805801000077407620734083006830683082108370372037207750637099508370850"
        "073308500770072006820812077411030771072407250457036504570838050005000675071605930716067804350716"
        "07120343034306650343104207120687071607160493059504780712065209240645065205820712036507120838"
    ),
)
_SCRIPT = set("₀₁₂₃₄₅₆₇₈₉⁰¹²³⁴⁵⁶⁷⁸⁹")


def text_width(text: str, size: float, bold: bool = False) -> float:
    """A text's width (mm) as DejaVu Sans sets it at cap height ``size`` (the font's em is size/0.73).

    Printable ASCII from the font's own advance widths (regular or bold; the oblique
    faces have the same); sub- and superscript digits 0.44 em, a prime 0.27 em, any other
    character (ω, →, ∞, ×) 0.87 em, the widest of them; 5 % added (matplotlib sets a line
    about 2.5 % wider than the sum of its advances).
    """
    table = _ADVANCE[1 if bold else 0]
    em = 0.0
    for ch in text:
        code = ord(ch) - 32
        if 0 <= code < 95:
            em += int(table[4 * code : 4 * code + 4]) / 1000
        elif ch in _SCRIPT:
            em += 0.44
        elif ch == "′":
            em += 0.27
        else:
            em += 0.87
    return em * size / 0.73 * 1.05


#: A text's box above and below the point it is placed at, in units of its size (as painted).
_ABOVE, _BELOW = 0.58, 0.88

Box = tuple[float, float, float, float]


def text_rect(t: Text) -> Box:
    """The box (x0, y0, x1, y1, mm) a text covers on the page, as placed by its anchor."""
    w = text_width(t.text, t.size, t.bold)
    x0 = t.at[0] - {"start": 0.0, "middle": w / 2, "end": w}[t.anchor]
    return (x0, t.at[1] - _ABOVE * t.size, x0 + w, t.at[1] + _BELOW * t.size)


def item_rect(item: Item) -> Box:
    """The box an item covers, its stroke included."""
    if isinstance(item, Text):
        return text_rect(item)
    half = item.style.width / 2 if item.style.stroke else 0.0
    if isinstance(item, Line):
        pts: Sequence[Vec] = (item.p0, item.p1)
    elif isinstance(item, Poly):
        pts = item.points
    else:
        (cx, cy), r = item.centre, item.r
        pts = ((cx - r, cy - r), (cx + r, cy + r))
    x0, y0, x1, y1 = bbox(pts)
    return (x0 - half, y0 - half, x1 + half, y1 + half)


def _overlap(a: Box, b: Box, gap: float = 0.0) -> bool:
    return a[0] < b[2] + gap and b[0] < a[2] + gap and a[1] < b[3] + gap and b[1] < a[3] + gap


def _obstacles(
    items: Sequence[Item],
) -> tuple[list[tuple[Vec, Vec, float]], list[tuple[Vec, float]], list[Box]]:
    """Segments (with a softness bonus, mm), discs and texts' boxes already drawn.

    Dashed construction lines are soft: a label may sit closer to them than
    to a link or a vector.  A text is a hard obstacle: no label is put on another.
    """
    segs: list[tuple[Vec, Vec, float]] = []
    discs: list[tuple[Vec, float]] = []
    rects: list[Box] = []
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
        elif item.text.strip():
            rects.append(text_rect(item))
    return segs, discs, rects


def _seg_dist(p: Vec, a: Vec, b: Vec) -> float:
    dx, dy = b[0] - a[0], b[1] - a[1]
    n2 = dx * dx + dy * dy
    t = 0.0 if n2 == 0 else max(0.0, min(1.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / n2))
    return math.dist(p, (a[0] + t * dx, a[1] + t * dy))


def _crosses(a: Vec, b: Vec, box: Box, inset: float) -> bool:
    """Whether the segment a–b passes through the box (shrunk by ``inset``): a line through a label."""
    x0, y0, x1, y1 = box[0] + inset, box[1] + inset, box[2] - inset, box[3] - inset
    if max(a[0], b[0]) < x0 or min(a[0], b[0]) > x1 or max(a[1], b[1]) < y0 or min(a[1], b[1]) > y1:
        return False
    # Liang–Barsky: clip the segment's parameter range to the box's slabs
    t0, t1 = 0.0, 1.0
    d = (b[0] - a[0], b[1] - a[1])
    for p, q in ((-d[0], a[0] - x0), (d[0], x1 - a[0]), (-d[1], a[1] - y0), (d[1], y1 - a[1])):
        if p == 0:
            if q < 0:
                return False
        elif p < 0:
            t0 = max(t0, q / p)
        else:
            t1 = min(t1, q / p)
    return t0 <= t1


#: Clearance beyond this (mm) gains a label nothing: a segment farther from all of a candidate's
#: samples cannot change its score, and is not measured (a traced path of 10,000 steps has
#: 10,000 segments, nearly all of them far from any one label).
_CAP = 3.0
#: A circle smaller than this (mm) is a mark (a pin, a point, an I-centre): no label is put on it.
_MARK = 3.0


def _near_segments(
    segs: Sequence[tuple[Vec, Vec, float]], box: Box, reach: float
) -> list[tuple[Vec, Vec, float]]:
    """The segments whose bounding box comes within ``reach`` of ``box`` on both axes.

    Any other segment lies at least ``reach`` from every point of the box: it neither
    crosses the label nor comes nearer to its samples than :data:`_CAP` when ``reach`` is that.
    """
    x0, y0, x1, y1 = box[0] - reach, box[1] - reach, box[2] + reach, box[3] + reach
    return [
        s
        for s in segs
        if min(s[0][0], s[1][0]) <= x1
        and max(s[0][0], s[1][0]) >= x0
        and min(s[0][1], s[1][1]) <= y1
        and max(s[0][1], s[1][1]) >= y0
    ]


def text_box(text: str, size: float, bold: bool = False) -> Vec:
    """Half the width and half the height (mm) of a label centred on its point."""
    return (text_width(text, size, bold) / 2, (_ABOVE + _BELOW) / 2 * size)


def _centred(c: Vec, text: str, size: float, bold: bool) -> Box:
    return text_rect(Text(c, text, size, "middle", bold=bold))


def best_spot(
    candidates: Sequence[tuple[Vec, float]],
    text: str,
    size: float,
    drawn: Sequence[Item],
    *,
    bold: bool = False,
) -> Vec:
    """Of candidate label centres (each with a preference bonus), the one clearest of ``drawn``.

    A spot where the label would lie on a text or a mark already drawn is taken only when
    every spot would (then the least overlapped).  Otherwise clearance from lines and circles
    is sampled over the label's box and capped at 3 mm (beyond that, nothing is gained by
    moving further), then the bonus decides.
    """
    segs, discs, rects = _obstacles(drawn)
    marks = [(c[0] - r, c[1] - r, c[0] + r, c[1] + r) for c, r in discs if r < _MARK]
    boxes = [_centred(c, text, size, bold) for c, _ in candidates]
    if boxes:  # first the segments near any candidate (one pass), then near each
        hull = (
            min(b[0] for b in boxes),
            min(b[1] for b in boxes),
            max(b[2] for b in boxes),
            max(b[3] for b in boxes),
        )
        segs = _near_segments(segs, hull, _CAP)
    best: tuple[float, Vec] | None = None
    for (c, bonus), box in zip(candidates, boxes, strict=True):
        hits = sum(1 for r in rects if _overlap(box, r, 0.3))
        hits += sum(1 for r in marks if _overlap(box, r, 0.0))  # a pin or an I-centre's mark under it
        xs, ys = (
            (box[0], (box[0] + box[2]) / 2, box[2]),
            (box[1] + 0.1 * size, (box[1] + box[3]) / 2, box[3] - 0.2 * size),
        )
        samples = [(x, y) for x in xs for y in ys]
        near = _near_segments(segs, box, _CAP)
        clear = min(
            [_seg_dist(q, a, b) + soft for q in samples for a, b, soft in near]
            + [math.dist(q, dc) - dr for q in samples for dc, dr in discs]
            + [9.0]
        )
        crossed = sum(4.5 if soft == 0 else 1.5 for a, b, soft in near if _crosses(a, b, box, 0.15 * size))
        score = min(clear, _CAP) + bonus - 100.0 * hits - crossed
        if best is None or score > best[0] + 1e-9:
            best = (score, c)
    assert best is not None
    return best[1]


#: Distances (mm beyond the label's edge) at which labels are tried, and what each costs.
RINGS = ((2.6, 0.0), (4.6, 0.5), (7.0, 1.8), (10.0, 2.6), (14.0, 3.4), (19.0, 4.2))


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

    Sixteen directions at growing distances are tried, with a small bonus for the
    ``prefer`` direction (away from the lines meeting there) and for being near; a label
    never lies on another unless there is no room at all.  A label put far from its point
    gets a leader line (:func:`leader`).
    """
    half_w, half_h = text_box(text, size, bold)
    candidates = []
    for k in range(16):
        a = 2 * math.pi * k / 16
        u = (math.cos(a), math.sin(a))
        edge = min(abs(u[0]) * half_w + abs(u[1]) * half_h, max(half_w, half_h))
        for r, cost in RINGS:
            c = (here[0] + u[0] * (r + edge), here[1] + u[1] * (r + edge) - (_BELOW - _ABOVE) / 2 * size)
            candidates.append((c, 0.6 * (u[0] * prefer[0] + u[1] * prefer[1]) - cost))
    c = best_spot(candidates, text, size, drawn, bold=bold)
    return Text(c, text, size, "middle", colour, italic=italic, bold=bold, cls=cls)


def clashes(label: Text, drawn: Sequence[Item]) -> int:
    """How many texts already ``drawn`` the label would lie on."""
    box = text_rect(label)
    return sum(
        1 for t in drawn if isinstance(t, Text) and t.text.strip() and _overlap(box, text_rect(t), 0.3)
    )


def leader(here: Vec, label: Text, colour: str = "#777777") -> Line | None:
    """A thin line from near the point ``here`` to its label's box, when the label stands off (> 5 mm)."""
    x0, y0, x1, y1 = text_rect(label)
    edge = (min(max(here[0], x0), x1), min(max(here[1], y0 + 0.3 * label.size), y1 - 0.3 * label.size))
    d = math.dist(here, edge)
    if d <= 5.0:
        return None
    u = ((edge[0] - here[0]) / d, (edge[1] - here[1]) / d)
    start = (here[0] + 1.6 * u[0], here[1] + 1.6 * u[1])
    end = (edge[0] - 0.5 * u[0], edge[1] - 0.5 * u[1])
    return Line(start, end, Style(colour, 0.18), "leader")
