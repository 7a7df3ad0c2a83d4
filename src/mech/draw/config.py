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
from mech.draw.scene import (
    INK,
    PALETTE,
    Circle,
    Figure,
    Item,
    Line,
    Page,
    Poly,
    Style,
    Text,
    Transform,
    arrow,
    bbox,
    hatch,
    nice_scale,
    place_label,
    scale_bar,
)
from mech.model import Joint, Mechanism
from mech.pairs import kind_of

if TYPE_CHECKING:  # pragma: no cover
    from mech.icentres.locate import ICentre
    from mech.kinematics.result import Kinematics

__all__ = ["View", "configuration", "display_name", "link_colours", "link_members"]

Vec = tuple[float, float]

MARGIN = 14.0  # mm around the drawing, for labels and ground symbols
PIN_R = 1.3
BLOCK = (9.0, 5.5)  # slider block, mm along × across the path
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
        if (
            kind_of(j).glyph in ("slider", "slot")
            and geom is not None
            and geom.point is not None
            and geom.point in pos
        ):
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
    from mech.draw.icentres import overlay, reachable

    pos = dict(kin.positions if positions is None else positions)
    members = link_members(mech, kin, pos)
    colours = link_colours(mech)
    if view is None:
        pts = (
            list(pos.values())
            + _circle_extents(mech, kin, pos, frame=positions is not None)
            + [e for _, _, e in _follower_rods(mech, kin, pos)]
        )
        pts += [c.point for c in reachable(icentres, pts)]
        pts += [q for _label, curve, _kind in curves for q in _near(curve, pts)]
        view = fit_view(pts, room)
    tr = view.transform()
    width, height = view.size
    page = Page(width, height)
    page.add(Text((MARGIN - 6, 5.5), title, 3.4, "start", bold=True, cls="title"))

    directions = _directions(mech, kin, pos)
    if curves:
        page.extend(_curves(curves, tr, view))
    page.extend(_guides(mech, kin, pos, tr, directions, view))
    page.extend(_links(mech, members, pos, tr, colours))
    page.extend(_contacts(mech, kin, pos, tr, frame=positions is not None))
    page.extend(_ground_pivots(mech, kin, pos, tr))
    page.extend(_blocks(mech, kin, pos, tr, directions, colours))
    page.extend(_pins_and_points(mech, kin, pos, tr))
    page.extend(_labels(mech, members, pos, tr, list(page.items)))
    page.extend(_drive_arrows(mech, kin, pos, tr, [i for i in page.items if isinstance(i, Text)]))
    if icentres:
        page.extend(
            overlay(icentres, tr, (MARGIN, TITLE_H + MARGIN, width - MARGIN, height - MARGIN - FOOT_H))
        )

    factor = _unit_factor(mech.length_unit)
    page.extend(scale_bar((MARGIN - 6, height - 7), view.scale / factor, mech.length_unit))
    return page.figure(title)


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
    page.add(Text((MARGIN - 6, 5.5), title, 3.4, "start", bold=True, cls="title"))
    page.extend(_curves(curves, tr, view))
    page.extend(_ground_pivots(mech, kin, pos, tr))
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
        if geom is None or geom.direction is None or kind_of(j).glyph not in ("slider", "slot"):
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


def _guides(
    mech: Mechanism,
    kin: Kinematics,
    pos: Mapping[str, Vec],
    tr: Transform,
    directions: Mapping[str, Vec],
    view: View,
) -> list[Item]:
    """Ground guides of sliders: the line of stroke (dash-dot) and a hatched guide surface."""
    items: list[Item] = []
    centre = _centre(pos)
    for j in mech.joints:
        if kind_of(j).glyph != "slider" or j.links[1] != mech.ground or j.name not in directions:
            continue
        point = kin.joints[j.name].point
        if point is None or point not in pos:
            continue
        p, u = pos[point], directions[j.name]
        ts = [(q[0] - p[0]) * u[0] + (q[1] - p[1]) * u[1] for q in pos.values()]
        pad = view.scale / 10 * (BLOCK[0] * 0.9)
        a = (p[0] + (min(ts) - pad) * u[0], p[1] + (min(ts) - pad) * u[1])
        b = (p[0] + (max(ts) + pad) * u[0], p[1] + (max(ts) + pad) * u[1])
        items.append(Line(tr(a), tr(b), Style("#777777", 0.2, dash=(4, 1, 0.8, 1)), "stroke-line", j.name))
        # the guide surface on the side away from the rest of the mechanism
        n = (-u[1], u[0])
        away = -1.0 if (centre[0] - p[0]) * n[0] + (centre[1] - p[1]) * n[1] > 0 else 1.0
        du = _page_dir(u)
        pn = (n[0] * away, -n[1] * away)  # page normal toward the guide surface
        off = BLOCK[1] / 2
        pa, pb = tr(a), tr(b)
        sa = (pa[0] + pn[0] * off, pa[1] + pn[1] * off)
        sb = (pb[0] + pn[0] * off, pb[1] + pn[1] * off)
        side = 1.0 if (-du[1] * pn[0] + du[0] * pn[1]) > 0 else -1.0
        items.extend(hatch(sa, sb, side=side))
    return items


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


def _ground_pivots(mech: Mechanism, kin: Kinematics, pos: Mapping[str, Vec], tr: Transform) -> list[Item]:
    """A small triangle under each ground pivot, standing on a hatched base."""
    items: list[Item] = []
    for j in mech.joints:
        if kind_of(j).glyph == "pin" and mech.ground in j.links and j.name in pos:
            x, y = tr(pos[j.name])
            tri = ((x, y), (x - 3.2, y + 5.0), (x + 3.2, y + 5.0))
            items.append(Poly(tri, True, Style(INK, 0.35, fill="#ffffff"), "ground-pivot", j.name))
            items.extend(hatch((x - 5.0, y + 5.0), (x + 5.0, y + 5.0), side=-1.0))
    return items


def _blocks(
    mech: Mechanism,
    kin: Kinematics,
    pos: Mapping[str, Vec],
    tr: Transform,
    directions: Mapping[str, Vec],
    colours: Mapping[str, str],
) -> list[Item]:
    """Slider blocks (prismatic) and slots (pin in a slot), oriented along their paths."""
    items: list[Item] = []
    for j in mech.joints:
        if j.name not in directions:
            continue
        point = kin.joints[j.name].point
        if point is None or point not in pos:
            continue
        c = tr(pos[point])
        du = _page_dir(directions[j.name])
        nv = (-du[1], du[0])
        if kind_of(j).glyph == "slider":
            a, b = BLOCK[0] / 2, BLOCK[1] / 2
            corners = tuple(
                (c[0] + du[0] * sa * a + nv[0] * sb * b, c[1] + du[1] * sa * a + nv[1] * sb * b)
                for sa, sb in ((-1, -1), (1, -1), (1, 1), (-1, 1))
            )
            colour = colours.get(j.links[0], INK)
            items.append(Poly(corners, True, Style(colour, 0.6, fill="#ffffff"), "slider", j.name))
            items.append(
                Poly(corners, True, Style(None, 0, fill=colour, fill_opacity=0.16), "slider-fill", j.name)
            )
        else:  # slot: two parallel lines along the path, in the slot link's colour
            colour = colours.get(j.links[1], INK)
            half, w = 9.0, PIN_R + 0.6
            for s in (-1, 1):
                p0 = (c[0] - du[0] * half + nv[0] * s * w, c[1] - du[1] * half + nv[1] * s * w)
                p1 = (c[0] + du[0] * half + nv[0] * s * w, c[1] + du[1] * half + nv[1] * s * w)
                items.append(Line(p0, p1, Style(colour, 0.45), "slot", j.name))
    return items


def _contacts(
    mech: Mechanism, kin: Kinematics, pos: Mapping[str, Vec], tr: Transform, *, frame: bool = False
) -> list[Item]:
    """Higher pairs at the drawn instant: pitch circles of gears, the common normal of cams."""
    items: list[Item] = []
    for j in mech.joints:
        if kind_of(j).glyph not in ("contact", "pitch"):
            continue
        if j.name not in pos:
            continue
        c = tr(pos[j.name])
        items.extend(_profiles(mech, kin, j, pos, tr, frame=frame))
        if kind_of(j).glyph == "pitch" and not _profile_list(mech, kin, j, pos[j.name]):
            for link in j.links:
                centre = _pivot_of(mech, link, pos)
                if centre is not None:
                    pc = tr(centre)
                    items.append(
                        Circle(
                            pc,
                            math.dist(pc, c),
                            Style(link_colours(mech).get(link, INK), 0.6, dash=(3, 1, 0.6, 1)),
                            "pitch-circle",
                            link,
                        )
                    )
        normal = j.normal
        geom = kin.joints.get(j.name)
        if normal is None and geom is not None and geom.direction is not None:
            normal = math.atan2(geom.direction[1], geom.direction[0]) - math.pi / 2
        if normal is not None:
            u = (math.cos(normal), -math.sin(normal))
            items.append(
                Line(
                    (c[0] - 14 * u[0], c[1] - 14 * u[1]),
                    (c[0] + 14 * u[0], c[1] + 14 * u[1]),
                    Style("#555555", 0.25, dash=(3, 1, 0.6, 1)),
                    "normal",
                    j.name,
                )
            )
            t = (-u[1], u[0])
            items.append(
                Line(
                    (c[0] - 6 * t[0], c[1] - 6 * t[1]),
                    (c[0] + 6 * t[0], c[1] + 6 * t[1]),
                    Style(INK, 0.5),
                    "tangent",
                    j.name,
                )
            )
        colours = link_colours(mech)
        for link in j.links:
            if kind_of(j).glyph == "pitch" or _profile_list(mech, kin, j, pos[j.name]):
                continue
            body = [n for n, links in kin.carriers.items() if link in links and n in pos]
            for n in body:  # the profile is unknown: show which points the contact belongs to
                items.append(
                    Line(tr(pos[n]), c, Style(colours.get(link, INK), 0.5, dash=(2.0, 1.0)), "body", link)
                )
            if not body and link != mech.ground:
                items.extend(_follower(mech, kin, link, pos[j.name], tr, colours.get(link, INK)))
        items.append(Circle(c, 0.9, Style(INK, 0.3, fill=INK), "contact", j.name))
    return items


def _profiles(
    mech: Mechanism, kin: Kinematics, j: Joint, pos: Mapping[str, Vec], tr: Transform, *, frame: bool = False
) -> list[Item]:
    """Each link's profile where it is now: a circle about its centre, a flat face along the
    tangent at the contact, a closed curve (a cam's surface) carried with its link.

    A knife edge is the contact dot itself.  Profiles given by coordinates (as drawn) are
    carried by their link's motion from the drawing; in an animation frame (``frame``) only
    those placed by named points are drawn.
    """
    from mech.specs import Circle as CircleProfile
    from mech.specs import Curve as CurveProfile
    from mech.specs import Line as LineProfile

    items: list[Item] = []
    colours = link_colours(mech)
    contact = pos.get(j.name)
    for link, prof in _profile_list(mech, kin, j, contact):
        colour = colours.get(link, INK)
        move = None if frame else _carried(mech, kin, link)
        if isinstance(prof, CircleProfile):
            centre = pos.get(prof.centre.name) if prof.centre.name is not None else None
            if centre is None and prof.centre.xy is not None and move is not None:
                centre = move(prof.centre.xy)
            if centre is None:
                continue
            pc = tr(centre)
            r_page = tr((centre[0] + prof.radius, centre[1]))[0] - pc[0]
            items.append(Circle(pc, abs(r_page), Style(colour, 0.6), "profile", link))
        elif isinstance(prof, CurveProfile) and move is not None:
            pts = tuple(tr(move(p)) for p in prof.points)
            items.append(Poly(pts, True, Style(colour, 0.6), "profile", link))
        elif isinstance(prof, LineProfile) and contact is not None:
            geom = kin.joints.get(j.name)
            if geom is None or geom.direction is None:
                continue
            c, u = tr(contact), _page_dir(geom.direction)
            items.append(
                Line(
                    (c[0] - 12 * u[0], c[1] - 12 * u[1]),
                    (c[0] + 12 * u[0], c[1] + 12 * u[1]),
                    Style(colour, 1.0),
                    "profile",
                    link,
                )
            )
    return items


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


def _profile_list(mech: Mechanism, kin: Kinematics, j: Joint, contact: Vec | None) -> list[tuple[str, Any]]:
    """The profiles to draw: what the pair's kind draws on its links (given, generated, or radii)."""
    return kind_of(j).drawn_profiles(mech, j, contact)


def _follower_rods(mech: Mechanism, kin: Kinematics, pos: Mapping[str, Vec]) -> list[tuple[str, Vec, Vec]]:
    """Followers known only by a contact and a guide: (link, tip, far end) of a rod along the guide.

    The rod is half the mechanism's size long and leaves the cam, as a
    knife-edge follower does in the notes' figures.
    """
    out = []
    pts = list(pos.values())
    x0, y0, x1, y1 = bbox(pts) if pts else (0.0, 0.0, 0.0, 0.0)
    length = 0.6 * max(x1 - x0, y1 - y0, 1e-9)
    for j in mech.joints:
        if kind_of(j).glyph != "contact" or j.profiles or j.name not in pos:
            continue
        for link in j.links:
            if link == mech.ground or any(link in links and n in pos for n, links in kin.carriers.items()):
                continue
            guide = next(
                (
                    g
                    for g in mech.joints
                    if kind_of(g).glyph == "slider"
                    and g.links[0] == link
                    and g.name in kin.joints
                    and kin.joints[g.name].direction
                ),
                None,
            )
            if guide is None:
                continue
            u = kin.joints[guide.name].direction
            if u is None:  # a guide without a direction solved: nothing to draw along
                continue
            tip = pos[j.name]
            other = next((lk for lk in j.links if lk != link), None)
            pivot = _pivot_of(mech, other, pos) if other else None
            if pivot is not None and (tip[0] - pivot[0]) * u[0] + (tip[1] - pivot[1]) * u[1] < 0:
                u = (-u[0], -u[1])
            out.append((link, tip, (tip[0] + length * u[0], tip[1] + length * u[1])))
    return out


def _follower(
    mech: Mechanism, kin: Kinematics, link: str, tip: Vec, tr: Transform, colour: str
) -> list[Item]:
    """The rod of a knife-edge follower, with its guide hatched on both sides."""
    for name, t, end in _follower_rods(mech, kin, kin.positions):
        if name != link or t != tip:
            continue
        c, e = tr(t), tr(end)
        L = math.dist(c, e)
        u = ((e[0] - c[0]) / L, (e[1] - c[1]) / L)
        items: list[Item] = [Line(c, e, Style(colour, 1.0), "link", link)]
        n = (-u[1], u[0])
        for s in (-1, 1):
            g0 = (c[0] + 0.45 * L * u[0] + n[0] * s * 1.6, c[1] + 0.45 * L * u[1] + n[1] * s * 1.6)
            g1 = (c[0] + 0.8 * L * u[0] + n[0] * s * 1.6, c[1] + 0.8 * L * u[1] + n[1] * s * 1.6)
            items.extend(hatch(g0, g1, side=s, depth=1.6))
        return items
    return []


def _contact_partners(mech: Mechanism, link: str) -> list[str]:
    return [
        lk
        for j in mech.joints
        if kind_of(j).glyph == "contact" and link in j.links
        for lk in j.links
        if lk != link
    ]


def _circle_extents(
    mech: Mechanism, kin: Kinematics, pos: Mapping[str, Vec], *, frame: bool = False
) -> list[Vec]:
    """Corners of the boxes round gears' pitch circles, so the view holds them."""
    out: list[Vec] = []
    for j in mech.joints:
        for link, prof in _profile_list(mech, kin, j, pos.get(j.name)):
            points = getattr(prof, "points", None)
            move = None if frame else _carried(mech, kin, link)
            if points is not None and move is not None:
                out += [move(p) for p in points]
            centre = getattr(prof, "centre", None)
            if centre is not None:
                c = centre.xy if centre.name is None else pos.get(centre.name)
                if c is not None:
                    out += [
                        (c[0] - prof.radius, c[1] - prof.radius),
                        (c[0] + prof.radius, c[1] + prof.radius),
                    ]
        if kind_of(j).glyph == "pitch" and j.name in pos:
            for link in j.links:
                c = _pivot_of(mech, link, pos)
                if c is not None:
                    r = math.dist(c, pos[j.name])
                    out += [(c[0] - r, c[1] - r), (c[0] + r, c[1] + r)]
    return out


def _pivot_of(mech: Mechanism, link: str, pos: Mapping[str, Vec]) -> Vec | None:
    for j in mech.joints:
        if kind_of(j).glyph == "pin" and link in j.links and mech.ground in j.links and j.name in pos:
            return pos[j.name]
    return None


def _drive_arrows(
    mech: Mechanism, kin: Kinematics, pos: Mapping[str, Vec], tr: Transform, labels: Sequence[Text] = ()
) -> list[Item]:
    """A curved arrow round each driven pivot showing the sense of ω, as the notes draw it."""
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


def _pins_and_points(mech: Mechanism, kin: Kinematics, pos: Mapping[str, Vec], tr: Transform) -> list[Item]:
    """An open circle for every pin (revolute joint, or slot pin), a dot for every named point."""
    items: list[Item] = []
    pins: dict[str, None] = {}  # in the file's order: a set's order changes with the hash seed
    for j in mech.joints:
        if kind_of(j).glyph == "pin" and j.name in pos:
            pins[j.name] = None
        elif kind_of(j).glyph == "slot":
            point = kin.joints[j.name].point if j.name in kin.joints else None
            if point is not None and point in pos:
                pins[point] = None
    for name in pins:
        items.append(Circle(tr(pos[name]), PIN_R, Style(INK, 0.4, fill="#ffffff"), "pin", name))
    for p in mech.points:
        if p.name in pos and p.name not in pins:
            items.append(Circle(tr(pos[p.name]), 0.85, Style(INK, 0.2, fill=INK), "point", p.name))
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
        items.append(
            place_label(tr(pos[name]), display_name(name), 3.0, (0.6, -0.8), drawn + items, cls="label")
        )
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
            label = place_label(here, display_name(name), 3.4, prefer, drawn + items, cls="label")
            items.append(label)
    return items
