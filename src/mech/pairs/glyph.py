"""What a pair kind's glyph is made of, and what a glyph may read of the drawing.

A configuration diagram draws each joint with its kind's :meth:`~mech.pairs.base.PairKind.glyph`:
a few of the shapes every drawing is made of (:class:`~mech.shapes.Line`,
:class:`~mech.shapes.Poly`, :class:`~mech.shapes.Circle` of :mod:`mech.shapes`), each on one of
the :data:`LAYERS` and in page millimetres (y down, from :meth:`GlyphView.page`) or, when
``world`` is set, in world metres (y up) — a pitch circle or a follower's stem belongs to the
mechanism's size and tells the drawing how much of the world it must hold.  The drawing
(:mod:`mech.draw.config`) paints what the kinds give, layer by layer, and never asks a kind's
name.

A glyph reads only :class:`GlyphView`: positions and directions at the instant drawn, the
world-to-page transform, the links' colours, and a few facts about the links (pivots, the
points they carry, how a drawn profile has moved).  The helpers below are the notes' signs,
shared by the kinds: the frame's hatching, a pin (an open circle; a triangle on a hatched base at
a ground pivot), a block on its guide, a slot, profiles and pitch circles, the common normal and
tangent.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Protocol

from mech.shapes import INK, Circle, Line, Poly, Style, Vec

if TYPE_CHECKING:
    from mech.model import Joint, Mechanism

__all__ = [
    "LAYERS",
    "SHAPES",
    "GlyphView",
    "Shape",
    "contact",
    "hatch",
    "pin",
    "slider",
    "slot",
]

#: Painting order: ``under`` the links (a line of stroke, a guide), then the links, then
#: ``contact`` (profiles, normals), ``ground`` (pivots), ``block`` (sliders), ``pin`` (on top).
LAYERS = ("under", "contact", "ground", "block", "pin")
PIN_R = 1.3  # mm
BLOCK = (9.0, 5.5)  # a slider block, mm along × across its path


#: What a glyph gives: lines, outlines and circles, each with its ``layer`` (one of :data:`LAYERS`).
Shape = Line | Poly | Circle
SHAPES = (Line, Poly, Circle)


class GlyphView(Protocol):
    """What a glyph may read of the drawing (implemented by :mod:`mech.draw.config`)."""

    @property
    def mech(self) -> Mechanism: ...
    @property
    def positions(self) -> Mapping[str, Vec]:
        """Every located point at the instant drawn (world, m)."""
        ...

    @property
    def frame(self) -> bool:
        """True in an animation frame (profiles drawn by coordinates are not carried there)."""
        ...

    def point(self, j: Joint) -> str | None:
        """The name of the joint's own point (a pin, a slider's point, a contact), if located."""
        ...

    def direction(self, j: Joint) -> Vec | None:
        """The joint's path direction, or a contact's common tangent, now (world unit vector)."""
        ...

    def page(self, p: Vec) -> Vec:
        """World (m, y up) → page (mm, y down)."""
        ...

    def colour(self, link: str) -> str:
        """The link's colour (the frame's is ink)."""
        ...

    def pivot(self, link: str) -> Vec | None:
        """Where ``link`` is pinned to the frame, if it is."""
        ...

    def body(self, link: str) -> list[Vec]:
        """The located points fixed in ``link``, now."""
        ...

    def guide(self, link: str) -> Vec | None:
        """The direction of the path on which ``link`` slides along the frame, if it does."""
        ...

    def carried(self, link: str) -> Callable[[Vec], Vec] | None:
        """Takes a point of ``link`` as the file draws it to where the link has carried it."""
        ...

    def extent(self) -> float:
        """The mechanism's size (the largest side of the box round its points, m)."""
        ...


# -- the notes' signs ----------------------------------------------------------------------------
def hatch(
    p0: Vec, p1: Vec, side: float = 1.0, depth: float = 2.0, *, layer: str = "ground", pitch: float = 1.6
) -> list[Shape]:
    """The frame: a base line ``p0 → p1`` (page mm) with short slanted strokes on one ``side`` (±1).

    This is the textbook sign for "fixed to the frame" under pivots and along slider guides.
    """
    dx, dy = p1[0] - p0[0], p1[1] - p0[1]
    n = math.hypot(dx, dy)
    if n == 0:
        return []
    ux, uy = dx / n, dy / n
    nx, ny = -uy * side, ux * side  # page normal toward the hatched side
    out: list[Shape] = [Line(p0, p1, Style(INK, 0.35), "ground", "", layer)]
    count = max(int(n / pitch), 1)
    for i in range(count + 1):
        t = i * n / count
        a = (p0[0] + ux * t, p0[1] + uy * t)
        b = (a[0] + nx * depth - ux * depth * 0.8, a[1] + ny * depth - uy * depth * 0.8)
        out.append(Line(a, b, Style(INK, 0.2), "hatch", "", layer))
    return out


def pin(view: GlyphView, name: str, *, ground: bool = False) -> list[Shape]:
    """An open circle at the point ``name``; at a ground pivot, a triangle on a hatched base under it."""
    at = view.positions.get(name)
    if at is None:
        return []
    x, y = view.page(at)
    out: list[Shape] = []
    if ground:
        tri = ((x, y), (x - 3.2, y + 5.0), (x + 3.2, y + 5.0))
        out.append(Poly(tri, True, Style(INK, 0.35, fill="#ffffff"), "ground-pivot", name, "ground"))
        out += hatch((x - 5.0, y + 5.0), (x + 5.0, y + 5.0), side=-1.0)
    out.append(Circle((x, y), PIN_R, Style(INK, 0.4, fill="#ffffff"), "pin", name, "pin"))
    return out


def slider(view: GlyphView, j: Joint) -> list[Shape]:
    """A block on its path; on the frame, the line of stroke dash-dotted and the guide hatched."""
    name, u = view.point(j), view.direction(j)
    if name is None or u is None or name not in view.positions:
        return []
    p = view.positions[name]
    out: list[Shape] = []
    if j.links[1] == view.mech.ground:
        out += _guide(view, j, p, u)
    c, du = view.page(p), (u[0], -u[1])
    nv = (-du[1], du[0])
    a, b = BLOCK[0] / 2, BLOCK[1] / 2
    corners = tuple(
        (c[0] + du[0] * sa * a + nv[0] * sb * b, c[1] + du[1] * sa * a + nv[1] * sb * b)
        for sa, sb in ((-1, -1), (1, -1), (1, 1), (-1, 1))
    )
    colour = view.colour(j.links[0])
    out.append(Poly(corners, True, Style(colour, 0.6, fill="#ffffff"), "slider", j.name, "block"))
    out.append(
        Poly(corners, True, Style(None, 0, fill=colour, fill_opacity=0.16), "slider-fill", j.name, "block")
    )
    return out


def _guide(view: GlyphView, j: Joint, p: Vec, u: Vec) -> list[Shape]:
    """The line of stroke over the mechanism's reach, and the guide surface away from the mechanism."""
    pos = view.positions
    ts = [(q[0] - p[0]) * u[0] + (q[1] - p[1]) * u[1] for q in pos.values()]
    pa, pb = view.page(p), view.page((p[0] + u[0], p[1] + u[1]))
    per_mm = 1.0 / max(math.dist(pa, pb), 1e-300)  # world metres per page mm
    pad = per_mm * BLOCK[0] * 0.9
    a = (p[0] + (min(ts) - pad) * u[0], p[1] + (min(ts) - pad) * u[1])
    b = (p[0] + (max(ts) + pad) * u[0], p[1] + (max(ts) + pad) * u[1])
    out: list[Shape] = [
        Line(
            view.page(a),
            view.page(b),
            Style("#777777", 0.2, dash=(4, 1, 0.8, 1)),
            "stroke-line",
            j.name,
            "under",
        )
    ]
    n = (-u[1], u[0])
    cx = sum(q[0] for q in pos.values()) / max(len(pos), 1)
    cy = sum(q[1] for q in pos.values()) / max(len(pos), 1)
    away = -1.0 if (cx - p[0]) * n[0] + (cy - p[1]) * n[1] > 0 else 1.0
    du = (u[0], -u[1])
    pn = (n[0] * away, -n[1] * away)  # page normal toward the guide surface
    off = BLOCK[1] / 2
    sa, sb = view.page(a), view.page(b)
    sa = (sa[0] + pn[0] * off, sa[1] + pn[1] * off)
    sb = (sb[0] + pn[0] * off, sb[1] + pn[1] * off)
    side = 1.0 if (-du[1] * pn[0] + du[0] * pn[1]) > 0 else -1.0
    out += hatch(sa, sb, side=side, layer="under")
    return out


def slot(view: GlyphView, j: Joint) -> list[Shape]:
    """Two lines along the path round the pin, in the slotted link's colour, and the pin."""
    name, u = view.point(j), view.direction(j)
    if name is None or u is None or name not in view.positions:
        return []
    c, du = view.page(view.positions[name]), (u[0], -u[1])
    nv = (-du[1], du[0])
    colour = view.colour(j.links[1])
    half, w = 9.0, PIN_R + 0.6
    out: list[Shape] = []
    for s in (-1, 1):
        p0 = (c[0] - du[0] * half + nv[0] * s * w, c[1] - du[1] * half + nv[1] * s * w)
        p1 = (c[0] + du[0] * half + nv[0] * s * w, c[1] + du[1] * half + nv[1] * s * w)
        out.append(Line(p0, p1, Style(colour, 0.45), "slot", j.name, "block"))
    return out + pin(view, name)


def contact(
    view: GlyphView, j: Joint, profiles: Sequence[tuple[str, object]], *, pitch: bool = False
) -> list[Shape]:
    """A higher pair at the instant: the links' profiles (or, for ``pitch`` pairs, pitch circles
    about the pivots), the common normal and tangent, what the contact belongs to, the contact dot.

    ``profiles`` are the pair's :meth:`~mech.pairs.base.PairKind.drawn_profiles`.
    """
    at = view.positions.get(j.name)
    if at is None:
        return []
    c = view.page(at)
    out: list[Shape] = []
    for link, prof in profiles:
        out += _profile(view, j, link, prof, at)
    if pitch and not profiles:
        for link in j.links:
            centre = view.pivot(link) if link != view.mech.ground else None
            if centre is not None:
                dash = Style(view.colour(link), 0.6, dash=(3, 1, 0.6, 1))
                out.append(Circle(centre, math.dist(centre, at), dash, "pitch-circle", link, "contact", True))
    out += _normal(view, j, c)
    if not pitch and not profiles:
        for link in j.links:
            out += _belongs(view, j, link, at)
    for link in j.links:
        out += stem(view, j, link, at)
    out.append(Circle(c, 0.9, Style(INK, 0.3, fill=INK), "contact", j.name, "contact"))
    return out


def _normal(view: GlyphView, j: Joint, c: Vec) -> list[Shape]:
    normal = j.normal
    u = view.direction(j)
    if normal is None and u is not None:
        normal = math.atan2(u[1], u[0]) - math.pi / 2
    if normal is None:
        return []
    n = (math.cos(normal), -math.sin(normal))
    t = (-n[1], n[0])
    return [
        Line(
            (c[0] - 14 * n[0], c[1] - 14 * n[1]),
            (c[0] + 14 * n[0], c[1] + 14 * n[1]),
            Style("#555555", 0.25, dash=(3, 1, 0.6, 1)),
            "normal",
            j.name,
            "contact",
        ),
        Line(
            (c[0] - 6 * t[0], c[1] - 6 * t[1]),
            (c[0] + 6 * t[0], c[1] + 6 * t[1]),
            Style(INK, 0.5),
            "tangent",
            j.name,
            "contact",
        ),
    ]


def _belongs(view: GlyphView, j: Joint, link: str, at: Vec) -> list[Shape]:
    """With no profile known: dashed lines from the link's points to the contact it belongs to."""
    style = Style(view.colour(link), 0.5, dash=(2.0, 1.0))
    return [Line(view.page(p), view.page(at), style, "body", link, "contact") for p in view.body(link)]


def stem(view: GlyphView, j: Joint, link: str, at: Vec) -> list[Shape]:
    """A follower on a guide of the frame with no bar of its own: its stem, and the guide round it.

    The stem runs from the contact along the guide, away from the other link's pivot, 0.6 of
    the mechanism's size long, as ``mech cam -o`` and the notes draw a translating follower.
    """
    if link == view.mech.ground or len(view.body(link)) >= 2:
        return []
    u = view.guide(link)
    if u is None:
        return []
    other = next((lk for lk in j.links if lk != link), None)
    pivot = view.pivot(other) if other is not None else None
    if pivot is not None and (at[0] - pivot[0]) * u[0] + (at[1] - pivot[1]) * u[1] < 0:
        u = (-u[0], -u[1])
    length = 0.6 * max(view.extent(), 1e-12)
    end = (at[0] + length * u[0], at[1] + length * u[1])
    colour = view.colour(link)
    out: list[Shape] = [Line(at, end, Style(colour, 1.0), "stem", link, "under", world=True)]
    c, e = view.page(at), view.page(end)
    L = max(math.dist(c, e), 1e-9)
    w = ((e[0] - c[0]) / L, (e[1] - c[1]) / L)
    n = (-w[1], w[0])
    for s in (-1, 1):
        g0 = (c[0] + 0.45 * L * w[0] + n[0] * s * 1.6, c[1] + 0.45 * L * w[1] + n[1] * s * 1.6)
        g1 = (c[0] + 0.8 * L * w[0] + n[0] * s * 1.6, c[1] + 0.8 * L * w[1] + n[1] * s * 1.6)
        out += hatch(g0, g1, side=s, depth=1.6, layer="under")
    return out


def _profile(view: GlyphView, j: Joint, link: str, prof: object, at: Vec) -> list[Shape]:
    """One link's profile where it is now: a circle about its centre, a curve carried with its
    link, a flat face along the common tangent.  A knife edge is the contact dot itself."""
    from mech import specs

    colour = view.colour(link)
    move = None if view.frame else view.carried(link)
    if isinstance(prof, specs.Circle):
        centre = view.positions.get(prof.centre.name) if prof.centre.name is not None else None
        if centre is None and prof.centre.xy is not None and move is not None:
            centre = move(prof.centre.xy)
        if centre is None:
            return []
        return [Circle(centre, prof.radius, Style(colour, 0.6), "profile", link, "contact", True)]
    if isinstance(prof, specs.Curve) and move is not None:
        points = tuple(move(p) for p in prof.points)
        return [Poly(points, True, Style(colour, 0.6), "profile", link, "contact", True)]
    u = view.direction(j)
    if isinstance(prof, specs.Line) and u is not None:
        c, du = view.page(at), (u[0], -u[1])
        return [
            Line(
                (c[0] - 12 * du[0], c[1] - 12 * du[1]),
                (c[0] + 12 * du[0], c[1] + 12 * du[1]),
                Style(colour, 1.0),
                "profile",
                link,
                "contact",
            )
        ]
    return []
