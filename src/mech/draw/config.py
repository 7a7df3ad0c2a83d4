"""The configuration (space) diagram: the mechanism drawn to scale at the analysed instant.

Drawn as the lecture notes draw it: binary links as bars, ternary (and larger)
links as plates, pins as small open circles, ground pivots on a hatched
base, sliders as blocks on a hatched guide with the line of stroke
dash-dotted, named points as dots, every joint and point labelled (``O2``
printed as O₂), and the scale stated ("1 cm = 50 mm") under a scale bar.

What a link "is" comes from the solved result: the points it carries
(``kin.carriers``), plus the slider points running on it when it is a
moving guide (a slotted lever is drawn through the block it guides).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from typing import TYPE_CHECKING, Any

from mech._records import dataclass
from mech.draw.glyphs import Sheet, glyphs, paint, world_points
from mech.draw.scene import (
    PALETTE,
    Figure,
    Page,
    Transform,
    arrow,
    bbox,
    leader,
    nice_scale,
    place_label,
    scale_bar,
)
from mech.model import Mechanism
from mech.pairs import kind_of
from mech.shapes import INK, Circle, Item, Line, Poly, Style, Text

if TYPE_CHECKING:  # pragma: no cover
    from mech.icentres.locate import ICentre
    from mech.kinematics.result import Kinematics

__all__ = ["View", "configuration", "display_name", "link_colours", "link_members"]

Vec = tuple[float, float]

MARGIN = 14.0  # mm around the drawing, for labels and ground symbols
#: Where a drawing's title sits (mm): a fitted sheet that grows moves it, and so tells by how much.
TITLE_AT = (MARGIN - 6, 5.5)
TITLE_H = 9.0
FOOT_H = 11.0
_SUB = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def display_name(name: str, lower: bool = False) -> str:
    """``O2`` → ``O₂`` (a letter and a number, as the notes write O_2); other names unchanged."""
    head = name.rstrip("0123456789")
    if len(head) == 1 and head.isalpha() and len(name) > 1:
        name = head + name[1:].translate(_SUB)
    return name.lower() if lower and len(head) == 1 else name


def link_colours(mech: Mechanism) -> dict[str, str]:
    """One colour per moving link, the same in every diagram (ground is ink)."""
    out = {mech.ground: INK}
    for i, link in enumerate(mech.moving_links):
        out[link.name] = PALETTE[i % len(PALETTE)]
    return out


def link_members(
    mech: Mechanism, kin: Kinematics, positions: Mapping[str, Vec] | None = None
) -> dict[str, list[str]]:
    """Located names fixed in each link, in file order, plus the slider points it guides.

    The slider point of a prismatic or slot joint is not fixed in the guide,
    but at this instant the guide's coincident point is there: a slotted lever
    is drawn through its block.
    """
    pos = kin.positions if positions is None else positions
    members: dict[str, list[str]] = {link.name: [] for link in mech.links}
    for name, links in kin.carriers.items():
        if name in pos:
            for link in links:
                if name not in members[link]:
                    members[link].append(name)
    for j in mech.joints:
        geom = kin.joints.get(j.name)
        if kind_of(j).role == "path" and geom is not None and geom.point is not None and geom.point in pos:
            guide = j.links[1]
            if guide != mech.ground and geom.point not in members[guide]:
                members[guide].append(geom.point)
    return members


@dataclass(frozen=True, slots=True)
class View:
    """The world window and scale of a configuration diagram.

    Frames of an animation share one view so that the mechanism does not
    jump about or change scale from frame to frame.
    """

    xmin: float
    ymin: float
    xmax: float
    ymax: float
    scale: float  # metres per cm of paper

    def transform(self) -> Transform:
        return Transform(self.scale, (self.xmin, self.ymax), (MARGIN, TITLE_H + MARGIN))

    @property
    def size(self) -> Vec:
        """Page width and height, mm."""
        return (
            max(2 * MARGIN + (self.xmax - self.xmin) * 10 / self.scale, 72.0),  # room for the title
            TITLE_H + 2 * MARGIN + FOOT_H + (self.ymax - self.ymin) * 10 / self.scale,
        )


def fit_view(points: Iterable[Vec], room: Vec = (120.0, 90.0)) -> View:
    """The smallest round-scaled view that holds ``points`` in ``room`` (mm)."""
    pts = list(points)
    x0, y0, x1, y1 = bbox(pts)
    w, h = max(x1 - x0, 1e-12), max(y1 - y0, 1e-12)
    if w == 1e-12 and h == 1e-12:
        w = h = 1.0
    scale = nice_scale(w, room[0]) if w / room[0] >= h / room[1] else nice_scale(h, room[1])
    return View(x0, y0, x1, y1, scale)


def configuration(
    mech: Mechanism,
    kin: Kinematics,
    *,
    positions: Mapping[str, Vec] | None = None,
    view: View | None = None,
    icentres: Sequence[ICentre] = (),
    title: str = "Configuration diagram",
    room: Vec = (130.0, 95.0),
    curves: Sequence[tuple[str, Sequence[Vec], str]] = (),
) -> Figure:
    """The configuration diagram of ``mech`` as solved in ``kin``.

    Parameters
    ----------
    mech
        The mechanism (for link names, joint types and the file's length unit).
    kin
        A :class:`mech.kinematics.Kinematics` (any level): positions, carriers
        and joint directions are read from it.
    positions
        Other positions of the same mechanism (an animation frame); the
        directions of moving guides are turned with their links.
    view
        A fixed window and scale (animation); by default the drawing is
        fitted to ``room`` (mm) at a round scale.
    icentres
        I-centres to overlay (objects with ``name``, ``point``, ``at_infinity``,
        ``direction``); see :mod:`mech.draw.icentres`.
    curves
        Loci to trace, each ``(label, points, kind)``: a point's path
        (``kind="path"``), a fixed or moving centrode (``"fixed centrode"``,
        ``"moving centrode"``).  Points are world coordinates (m); a NaN breaks
        the curve.  Parts far outside the mechanism (a centrode running off to
        infinity) are cut at twice its extent.

    Returns
    -------
    Figure
        In page millimetres; the caption states the scale in the file's unit.
    """
    from mech.draw.icentres import marks, overlay, reachable

    pos = dict(kin.positions if positions is None else positions)
    members = link_members(mech, kin, pos)
    colours = link_colours(mech)
    frame = positions is not None
    directions = _directions(mech, kin, pos)

    def sheet(tr: Transform) -> Sheet:
        carried = None if frame else (lambda link: _carried(mech, kin, link))
        return Sheet(mech, kin, pos, directions, tr, colours, frame=frame, carried=carried)

    if view is None:
        pts = list(pos.values())
        pts += world_points(glyphs(mech, sheet(fit_view(pts, room).transform())))
        pts += [c.point for c in reachable(icentres, pts)]
        pts += [q for _label, curve, _kind in curves for q in _near(curve, pts)]
        view = fit_view(pts, room)
    tr = view.transform()
    shapes = glyphs(mech, sheet(tr))
    width, height = view.size
    page = Page(width, height)
    page.add(Text(TITLE_AT, title, 3.4, "start", bold=True, cls="title"))
    factor = _unit_factor(mech.length_unit)  # the scale first: what is placed later keeps off it
    page.extend(scale_bar((MARGIN - 6, height - 7), view.scale / factor, mech.length_unit))

    if curves:
        page.extend(_curves(curves, tr, view))
    page.extend(paint(shapes, tr, "under"))
    page.extend(_links(mech, members, pos, tr, colours))
    for layer in ("contact", "ground", "block", "pin"):
        page.extend(paint(shapes, tr, layer))
    page.extend(_points(mech, pos, tr, page.items))
    box = (MARGIN, TITLE_H + MARGIN, width - MARGIN, height - MARGIN - FOOT_H)
    spots = marks(icentres, tr, box) if icentres else []  # the joints' labels and ω keep off them
    page.extend(_labels(mech, members, pos, tr, [*page.items, *spots]))
    near = [i.centre for i in spots if isinstance(i, Circle)]
    page.extend(_drive_arrows(mech, kin, pos, tr, [i for i in page.items if isinstance(i, Text)], near))
    if icentres:
        page.extend(spots)
        unit = (mech.length_unit, _unit_factor(mech.length_unit))
        origin = _first_pivot(mech, pos)
        page.extend(overlay(icentres, tr, box, drawn=page.items, origin=origin, unit=unit, marked=True))

    return page.figure(title, fit=not frame)


def curves_figure(
    mech: Mechanism,
    kin: Kinematics,
    curves: Sequence[tuple[str, Sequence[Vec], str]],
    *,
    title: str = "Coupler curves",
    room: Vec = (130.0, 95.0),
) -> Figure:
    """The traced curves alone, to scale, with the frame's pivots for reference."""
    pos = dict(kin.positions)
    pivots = [pos[j.name] for j in mech.joints if mech.ground in j.links and j.name in pos]
    pts = [q for _label, curve, _kind in curves for q in curve if math.isfinite(q[0]) and math.isfinite(q[1])]
    view = fit_view(pts + pivots, room)
    tr = view.transform()
    width, height = view.size
    page = Page(width, height)
    page.add(Text(TITLE_AT, title, 3.4, "start", bold=True, cls="title"))
    page.extend(_curves(curves, tr, view))
    sheet = Sheet(mech, kin, pos, {}, tr, link_colours(mech))
    pivots_only = [
        s
        for j in mech.joints
        if mech.ground in j.links and kind_of(j).role == "pin"
        for s in kind_of(j).glyph(sheet, j)
    ]
    for layer in ("ground", "pin"):
        page.extend(paint(pivots_only, tr, layer))
    for j in mech.joints:
        if mech.ground in j.links and j.name in pos:
            x, y = tr(pos[j.name])
            page.add(Text((x + 3.0, y + 9.0), display_name(j.name), 3.0, "start", cls="label"))
    factor = _unit_factor(mech.length_unit)
    page.extend(scale_bar((MARGIN - 6, height - 7), view.scale / factor, mech.length_unit))
    return page.figure(title)


# -- pieces ---------------------------------------------------------------------------
_CURVE_STYLE = {
    "path": Style(stroke="#1f77b4", width=0.3),
    "fixed centrode": Style(stroke="#2ca02c", width=0.3, dash=(1.6, 0.8)),
    "moving centrode": Style(stroke="#d62728", width=0.3, dash=(0.6, 0.6)),
}


def _near(curve: Sequence[Vec], around: Sequence[Vec]) -> list[Vec]:
    """The finite points of a curve within twice the extent of ``around`` from its centre."""
    fin = [p for p in around if math.isfinite(p[0]) and math.isfinite(p[1])]
    if not fin:
        return []
    x0, y0, x1, y1 = bbox(fin)
    cx, cy, r = (x0 + x1) / 2, (y0 + y1) / 2, max(x1 - x0, y1 - y0, 1e-12)
    return [
        (float(p[0]), float(p[1]))
        for p in curve
        if math.isfinite(p[0]) and math.isfinite(p[1]) and abs(p[0] - cx) <= r and abs(p[1] - cy) <= r
    ]


def _curves(curves: Sequence[tuple[str, Sequence[Vec], str]], tr: Transform, view: View) -> list[Item]:
    """Polylines of loci, broken at NaN and where they leave the view; a label at their last point."""
    items: list[Item] = []
    for label, curve, kind in curves:
        style = _CURVE_STYLE.get(kind, _CURVE_STYLE["path"])
        runs: list[list[Vec]] = [[]]
        for p in curve:
            x, y = float(p[0]), float(p[1])
            inside = (
                math.isfinite(x)
                and math.isfinite(y)
                and view.xmin <= x <= view.xmax
                and view.ymin <= y <= view.ymax
            )
            if inside:
                runs[-1].append(tr((x, y)))
            elif runs[-1]:
                runs.append([])
        drawn = [run for run in runs if len(run) >= 2]
        for run in drawn:
            items.append(Poly(tuple(run), closed=False, style=style, cls=kind.replace(" ", "-"), name=label))
        if drawn:  # the label beside the middle of the longest piece
            longest = max(drawn, key=len)
            at = longest[len(longest) // 2]
            items.append(
                Text((at[0] + 1.5, at[1] - 1.0), label, 2.6, "start", style.stroke or INK, cls="curve-label")
            )
    return items


def _unit_factor(unit: str) -> float:
    from mech.units import unit_factor

    try:
        return unit_factor(unit)[1]
    except Exception:  # an unknown unit cannot reach here from a loaded file
        return 1.0


def _directions(mech: Mechanism, kin: Kinematics, pos: Mapping[str, Vec]) -> dict[str, Vec]:
    """Each path's direction in ``pos``: the solved one, turned with a moving guide."""
    out: dict[str, Vec] = {}
    for j in mech.joints:
        geom = kin.joints.get(j.name)
        if geom is None or geom.direction is None or kind_of(j).role != "path":
            continue
        u = geom.direction
        guide = j.links[1]
        if guide != mech.ground and pos is not kin.positions:
            turn = _turn(kin, guide, pos)
            c, s = math.cos(turn), math.sin(turn)
            u = (c * u[0] - s * u[1], s * u[0] + c * u[1])
        out[j.name] = u
    return out


def _turn(kin: Kinematics, link: str, pos: Mapping[str, Vec]) -> float:
    """How far ``link`` has turned from ``kin`` to ``pos`` (from two of its points)."""
    names = [n for n, links in kin.carriers.items() if link in links and n in pos and n in kin.positions]
    if len(names) < 2:
        return 0.0
    a, b = names[0], names[1]
    p0, p1 = kin.positions[a], kin.positions[b]
    q0, q1 = pos[a], pos[b]
    return math.atan2(q1[1] - q0[1], q1[0] - q0[0]) - math.atan2(p1[1] - p0[1], p1[0] - p0[0])


def _page_dir(u: Vec) -> Vec:
    return (u[0], -u[1])


def _centre(pos: Mapping[str, Vec]) -> Vec:
    n = max(len(pos), 1)
    return (sum(p[0] for p in pos.values()) / n, sum(p[1] for p in pos.values()) / n)


def _hull(points: list[Vec]) -> list[Vec]:
    """Convex hull, counter-clockwise (Andrew's monotone chain)."""
    pts = sorted(set(points))
    if len(pts) <= 2:
        return pts

    def cross(o: Vec, a: Vec, b: Vec) -> float:
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower: list[Vec] = []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    upper: list[Vec] = []
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def _spread(points: list[Vec]) -> float:
    """Area of the hull relative to its perimeter²: ~0 for points on one line."""
    hull = _hull(points)
    if len(hull) < 3:
        return 0.0
    area = 0.5 * abs(sum(hull[i][0] * hull[i - 1][1] - hull[i - 1][0] * hull[i][1] for i in range(len(hull))))
    per = sum(math.dist(hull[i], hull[i - 1]) for i in range(len(hull)))
    return area / (per * per)


def _links(
    mech: Mechanism,
    members: Mapping[str, list[str]],
    pos: Mapping[str, Vec],
    tr: Transform,
    colours: Mapping[str, str],
) -> list[Item]:
    """Bars for binary links, plates for links of three or more points not in one line."""
    plates: list[Item] = []
    bars: list[Item] = []
    for link in mech.moving_links:
        pts = [tr(pos[n]) for n in members[link.name] if n in pos]
        if len(pts) < 2:
            continue
        colour = colours[link.name]
        if len(pts) >= 3 and _spread(pts) > 0.01:
            hull = tuple(_hull(pts))
            plates.append(
                Poly(hull, True, Style(colour, 0.6, fill=colour, fill_opacity=0.16), "link", link.name)
            )
            # members inside the plate still get a visible bar to the nearest corner
            continue
        # collinear: one bar from end to end
        a, b = max(((p, q) for p in pts for q in pts), key=lambda pq: math.dist(*pq))
        bars.append(Line(a, b, Style(colour, 1.0), "link", link.name))
    return plates + bars


def _carried(mech: Mechanism, kin: Kinematics, link: str) -> Any:
    """A function taking a point of ``link`` as drawn to where the link has carried it in ``kin``."""
    if link == mech.ground:
        return lambda p: p
    try:
        from mech.kinematics.solve import compiled

        sys_ = compiled(mech, None).system
    except Exception:  # the drawing itself is refused elsewhere, with its message
        return None
    i = sys_.link_index.get(link)
    state = kin.links.get(link)
    if i is None or state is None:
        return None
    x0, y0, th0 = sys_.q0[3 * i : 3 * i + 3]
    ox, oy = x0 * sys_.scale + sys_.centre[0], y0 * sys_.scale + sys_.centre[1]
    turn = state.angle - th0
    c, s = math.cos(turn), math.sin(turn)
    nx, ny = state.origin

    def move(p: Vec) -> Vec:
        dx, dy = p[0] - ox, p[1] - oy
        return (nx + c * dx - s * dy, ny + s * dx + c * dy)

    return move


def _first_pivot(mech: Mechanism, pos: Mapping[str, Vec]) -> tuple[str, Vec] | None:
    """The frame's first pivot (in the file's order), from which far I-centres are measured."""
    for j in mech.joints:
        if mech.ground in j.links and kind_of(j).role == "pin" and j.name in pos:
            return display_name(j.name), pos[j.name]
    return None


def _points(mech: Mechanism, pos: Mapping[str, Vec], tr: Transform, drawn: Sequence[Item]) -> list[Item]:
    """A dot for every named point that no glyph has drawn as a pin."""
    pins = {i.name for i in drawn if isinstance(i, Circle) and i.cls == "pin"}
    return [
        Circle(tr(pos[p.name]), 0.85, Style(INK, 0.2, fill=INK), "point", p.name)
        for p in mech.points
        if p.name in pos and p.name not in pins
    ]


def _drive_arrows(
    mech: Mechanism,
    kin: Kinematics,
    pos: Mapping[str, Vec],
    tr: Transform,
    labels: Sequence[Text] = (),
    marks: Sequence[Vec] = (),
) -> list[Item]:
    """A curved arrow round each driven pivot showing the sense of ω, as the notes draw it.

    It turns away from the links, the labels and the ``marks`` (I-centres) near the pivot.
    """
    items: list[Item] = []
    for d in getattr(kin, "drives", ()):
        if d.link is None or d.omega is None or d.omega == 0:
            continue
        pivot = d.about or next(
            (j.name for j in mech.joints if d.link in j.links and mech.ground in j.links and j.name in pos),
            None,
        )
        if pivot is None or pivot not in pos:
            continue
        cx, cy = tr(pos[pivot])
        r = 6.5
        # page angles (y down) of what leaves the pivot: its links, and the ground symbol below
        busy = [math.pi / 2, math.pi / 3, 2 * math.pi / 3]
        for name, links in kin.carriers.items():
            if (
                pivot in pos
                and name != pivot
                and name in pos
                and set(links) & set(kin.carriers.get(pivot, ()))
            ):
                q = tr(pos[name])
                busy.append(math.atan2(q[1] - cy, q[0] - cx))
        busy += [math.atan2(t.at[1] - cy, t.at[0] - cx) for t in labels if math.dist(t.at, (cx, cy)) < 12]
        busy += [math.atan2(q[1] - cy, q[0] - cx) for q in marks if 0.5 < math.dist(q, (cx, cy)) < 12]
        centre = max(
            (math.radians(15 * k) for k in range(24)),
            key=lambda a: min(abs(math.remainder(a - b, 2 * math.pi)) for b in busy),
        )
        sweep = math.radians(90) * (1 if d.omega < 0 else -1)  # cw in the world is +angle on the page
        a0 = centre - sweep / 2
        pts = [
            (cx + r * math.cos(a0 + sweep * t / 12), cy + r * math.sin(a0 + sweep * t / 12))
            for t in range(13)
        ]
        items.append(Poly(tuple(pts[:-1]), False, Style(INK, 0.3), "omega"))
        items.extend(arrow(pts[-3], pts[-1], INK, 0.3, cls="omega", head=1.8))
        end = pts[6]
        lx, ly = cx + (end[0] - cx) * 1.45, cy + (end[1] - cy) * 1.45
        items.append(Text((lx, ly), "ω", 3.0, "middle", italic=True, cls="omega"))
    return items


def _labels(
    mech: Mechanism,
    members: Mapping[str, list[str]],
    pos: Mapping[str, Vec],
    tr: Transform,
    drawn: list[Item],
) -> list[Item]:
    """Each joint and point named beside it, away from the links that meet there and clear of lines."""
    items: list[Item] = []
    done = set()
    contacts = [
        j.name for j in mech.joints if j.name in pos and not any(j.name in m for m in members.values())
    ]
    for name in contacts:
        _label_at(items, tr(pos[name]), display_name(name), 3.0, (0.6, -0.8), drawn)
        done.add(name)
    for names in members.values():
        for name in names:
            if name in done or name not in pos:
                continue
            done.add(name)
            here = tr(pos[name])
            dx = dy = 0.0
            for other_link, others in members.items():
                if name not in others or other_link == mech.ground:
                    continue
                for o in others:
                    if o != name and o in pos:
                        q = tr(pos[o])
                        d = math.dist(q, here)
                        if d > 1e-9:
                            dx += (here[0] - q[0]) / d
                            dy += (here[1] - q[1]) / d
            n = math.hypot(dx, dy)
            prefer = (dx / n, dy / n) if n > 0.3 else (0.6, -0.8)
            _label_at(items, here, display_name(name), 3.4, prefer, drawn)
    return items


def _label_at(items: list[Item], here: Vec, text: str, size: float, prefer: Vec, drawn: list[Item]) -> None:
    """Place a joint's label (and its leader line, if it stands off) into ``items``."""
    label = place_label(here, text, size, prefer, drawn + items, cls="label")
    line = leader(here, label)
    if line is not None:
        items.append(line)
    items.append(label)
