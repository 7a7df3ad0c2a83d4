"""Velocity and acceleration polygons, built and labelled as the lecture notes build them.

The velocity diagram starts from a pole **o** (every fixed point has zero
velocity, so all ground pivots are drawn there: "O1 and O2 are fixed points…
so they are taken as single point (o1, o2)").  Each point P of the mechanism
has its image **p** at the tip of v_P; the vector **op** is P's absolute
velocity, and for two points A, B of one link the vector **ab** is the
velocity of B relative to A — perpendicular to AB.  The images of a link's
points form a figure similar to the link (the velocity image), which is why a
ternary link's image is a triangle.

Two more kinds of image appear where the notes need them: the point of a
moving guide under a slider (the slotted lever's point under the block,
labelled a₄ when the lever is link 4, link numbers counting ground as 1), whose
vector **a₄a** is the sliding velocity along the slot; and the two points of
a higher pair's contact (c₂ on link 2, c₃ on link 3), whose vector is the slip.

The acceleration diagram is the same construction with accelerations (images
primed: o′, a′, b′ …), and each relative acceleration drawn as the notes
draw it: its normal (centripetal) component ω²·AB toward A, then its
tangential component α·AB, thin; the resultant thick.  At a slider on a
moving guide the components are the Coriolis term 2ωv and the sliding
acceleration along the path.

:func:`velocity_polygon` and :func:`acceleration_polygon` return the data
(images and vectors, SI); :func:`polygon_figure` draws it to a round scale.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING

from mech._records import dataclass
from mech.draw.config import display_name, link_colours, link_members
from mech.draw.scene import (
    Figure,
    Page,
    Transform,
    arrow,
    bbox,
    best_spot,
    clashes,
    fmt,
    item_rect,
    leader,
    nice_scale,
    place_label,
    scale_bar,
    text_box,
)
from mech.model import Joint, Mechanism
from mech.options import OutputUnits
from mech.pairs import kind_of
from mech.shapes import INK, Circle, Item, Style, Text
from mech.units import unit_factor

if TYPE_CHECKING:  # pragma: no cover
    from mech.kinematics.result import Kinematics

__all__ = ["Image", "PolygonData", "Vector", "acceleration_polygon", "polygon_figure", "velocity_polygon"]

Vec = tuple[float, float]

_SUB = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")
PRIME = "′"
MARGIN = 12.0
TITLE_H = 9.0


@dataclass(frozen=True, slots=True)
class Image:
    """A point of the polygon: ``label`` as printed, the mechanism ``point`` and ``link`` it images."""

    key: str
    label: str
    point: str | None
    link: str | None
    value: Vec


@dataclass(frozen=True, slots=True)
class Vector:
    """One drawn vector ``start → end`` (image keys), SI ``value``.

    ``kind``: ``absolute`` (from the pole), ``relative`` (two points of one
    link), ``sliding`` (slider relative to its guide), ``slip`` (at a higher
    pair), or a component of a relative acceleration: ``normal``,
    ``tangential``, ``coriolis``, ``along`` (sliding acceleration).
    Components have an empty ``name`` and are not labelled.
    """

    name: str
    start: str
    end: str
    kind: str
    link: str | None
    value: Vec


@dataclass(frozen=True, slots=True)
class PolygonData:
    """A velocity (``kind='velocity'``, m/s) or acceleration (m/s²) polygon: images and vectors.

    Image values are vectors from the pole; component vectors may end at
    construction points (keys starting with ``~``) which are not images.
    """

    kind: str
    pole: str
    images: tuple[Image, ...]
    vectors: tuple[Vector, ...]
    construction: Mapping[str, Vec]

    def image(self, key: str) -> Image:
        for im in self.images:
            if im.key == key:
                return im
        raise KeyError(key)

    def vector(self, name: str) -> Vector:
        for v in self.vectors:
            if v.name == name:
                return v
        raise KeyError(name)

    def at(self, key: str) -> Vec:
        """The polygon point of an image or construction key (the pole is ``o``)."""
        if key == "o":
            return (0.0, 0.0)
        if key in self.construction:
            return self.construction[key]
        return self.image(key).value


def _numbers(mech: Mechanism) -> dict[str, int]:
    """Link numbers as the notes use them: ground 1, the others in file order."""
    return {link.name: i + 1 for i, link in enumerate(mech.numbered_links)}


def velocity_polygon(mech: Mechanism, kin: Kinematics) -> PolygonData:
    """The velocity polygon of ``mech`` at the instant solved in ``kin`` (velocity level or more)."""
    return _build(mech, kin, "velocity")


def acceleration_polygon(mech: Mechanism, kin: Kinematics) -> PolygonData:
    """The acceleration polygon, with normal/tangential (and Coriolis) components drawn."""
    return _build(mech, kin, "acceleration")


def _build(mech: Mechanism, kin: Kinematics, kind: str) -> PolygonData:
    """The polygon as the notes build it: the images of the points, then the vectors between them."""
    b = _Builder(mech, kin, kind)
    b.point_images()
    b.contact_images()
    rank = _ranks(b.link_keys, b.order)
    b.absolute_vectors()
    b.relative_vectors(rank)
    b.sliding_vectors()
    b.slip_vectors()
    return PolygonData(
        kind, ", ".join(b.pole_names), tuple(b.images[k] for k in b.order), tuple(b.vectors), b.construction
    )


class _Builder:
    """One polygon while :func:`_build` makes it: images keyed and ordered, then vectors added step by step.

    An image's key is the point's name, ``point@link`` for the point of a
    moving guide under a slider or a higher pair's contact on each link, and
    ``o`` for the pole (every fixed point).  Private to :func:`_build`, so its
    mutation cannot leak; what leaves is a frozen :class:`PolygonData`.
    """

    def __init__(self, mech: Mechanism, kin: Kinematics, kind: str) -> None:
        self.mech, self.kin = mech, kin
        self.acc = kind == "acceleration"
        self.mark = PRIME if self.acc else ""
        self.numbers = _numbers(mech)
        self.ground = mech.ground
        self.pos = kin.positions
        self.members = link_members(mech, kin)
        self.ground_names = [n for n in self.members[self.ground] if n in self.pos]
        self.pole_names = [display_name(n, lower=True) + self.mark for n in self.ground_names] or [
            "o" + self.mark
        ]
        self.images: dict[str, Image] = {}
        self.order: list[str] = []
        self.link_keys: dict[str, list[str]] = {link.name: [] for link in mech.links}
        self.guided = _guided(mech, kin)
        self.contacts = [j for j in mech.joints if kind_of(j).role == "contact" and j.name in self.pos]
        self.vectors: list[Vector] = []
        self.construction: dict[str, Vec] = {}

    def value(self, name: str, link: str | None = None) -> Vec:
        v = self.kin.acceleration(name, link) if self.acc else self.kin.velocity(name, link)
        return (float(v[0]), float(v[1]))

    def label(self, key: str) -> str:
        return self.pole_names[0] if key == "o" else self.images[key].label

    def _add(self, image: Image) -> None:
        self.images[image.key] = image
        self.order.append(image.key)

    def point_images(self) -> None:
        """Each link's points: fixed ones at the pole, a moving guide's point under a slider apart."""
        for link in self.mech.links:
            for name in self.members[link.name]:
                key = self._point_image(name, link.name)
                if key not in self.link_keys[link.name]:
                    self.link_keys[link.name].append(key)

    def _point_image(self, name: str, link: str) -> str:
        """The key of ``name``'s image on ``link``, made the first time it is met."""
        if name in self.ground_names:
            return "o"
        if (name, link) in self.guided:
            key = f"{name}@{link}"
            if key not in self.images:
                sub = str(self.numbers[link]).translate(_SUB)
                self._add(
                    Image(
                        key,
                        display_name(name, lower=True) + sub + self.mark,
                        name,
                        link,
                        self.value(name, link),
                    )
                )
            return key
        if name not in self.images:
            self._add(Image(name, display_name(name, lower=True) + self.mark, name, link, self.value(name)))
        return name

    def contact_images(self) -> None:
        """A higher pair's contact once per moving link it joins (c₂, c₃), each with that link's motion."""
        for j in self.contacts:
            for link_name in j.links:
                if link_name == self.ground:
                    continue
                key = f"{j.name}@{link_name}"
                short = self._short(j)
                self._add(
                    Image(
                        key,
                        (display_name(short, lower=True) if len(short) <= 2 else short)
                        + str(self.numbers[link_name]).translate(_SUB)
                        + self.mark,
                        j.name,
                        link_name,
                        self.value(j.name, link_name),
                    )
                )
                self.link_keys[link_name].append(key)

    def _short(self, j: Joint) -> str:
        """A contact's letter: its name's first (``m`` for ``mesh``), unless a point or another
        contact has it, when the whole name is kept (``m12`` and ``m23``, never two ``m₃``)."""
        short = j.name if len(j.name) <= 2 else j.name[0]
        taken = {display_name(n, lower=True) for n in self.pos if n != j.name}
        others = [c.name if len(c.name) <= 2 else c.name[0] for c in self.contacts if c.name != j.name]
        if short.lower() in taken or short.lower() in {o.lower() for o in others}:
            return j.name.lower() if len(j.name) > 2 else j.name
        return short

    def absolute_vectors(self) -> None:
        """From the pole to each image, named after the fixed point of the same link, if any."""
        for key in self.order:
            im = self.images[key]
            if math.hypot(*im.value) == 0 and not self.acc:
                continue
            start_label, via = self.pole_names[0], None
            for link_name, keys in self.link_keys.items():
                if key in keys and "o" in keys and link_name != self.ground:
                    g = next(n for n in self.members[link_name] if n in self.ground_names)
                    start_label, via = display_name(g, lower=True) + self.mark, link_name
                    break
            self.vectors.append(Vector(start_label + im.label, "o", key, "absolute", via, im.value))
            if self.acc and via is not None:
                fixed = _fixed_point(self.members[via], self.ground_names)
                self._components(via, fixed, im.point, "o", key, (0.0, 0.0), im.value)

    def relative_vectors(self, rank: Mapping[str, int]) -> None:
        """Between the moving points of each link, from the one the notes reach first."""
        images, pos = self.images, self.pos
        for link in self.mech.moving_links:
            keys = [k for k in self.link_keys[link.name] if k != "o"]
            edges = _edges(keys, images, pos)
            if (
                "o" in self.link_keys[link.name]
                and len(keys) >= 2
                and len(edges) == 1
                and _collinear(
                    [pos[images[k].point] for k in keys if images[k].point in pos]  # type: ignore[index]
                    + [pos[n] for n in self.members[link.name] if n in self.ground_names]
                )
            ):
                edges = []  # a lever through its pivot: the absolute vectors already lie along it
            for a, b in edges:
                if rank[a] > rank[b] or (rank[a] == rank[b] and self.order.index(a) > self.order.index(b)):
                    a, b = b, a
                va, vb = images[a].value, images[b].value
                rel = (vb[0] - va[0], vb[1] - va[1])
                self.vectors.append(Vector(self.label(a) + self.label(b), a, b, "relative", link.name, rel))
                if self.acc:
                    self._components(link.name, images[a].point, images[b].point, a, b, va, rel)

    def sliding_vectors(self) -> None:
        """A slider relative to its moving guide; with accelerations, the Coriolis and sliding parts."""
        for (point, guide), j in self.guided.items():
            a, b = f"{point}@{guide}", point
            if a in self.images and b in self.images:
                va, vb = self.images[a].value, self.images[b].value
                rel = (vb[0] - va[0], vb[1] - va[1])
                self.vectors.append(Vector(self.label(a) + self.label(b), a, b, "sliding", j.links[0], rel))
                if self.acc:
                    cor = self.kin.coriolis(j.name)
                    mid = f"~{j.name}"
                    self.construction[mid] = (va[0] + cor[0], va[1] + cor[1])
                    self.vectors.append(Vector("", a, mid, "coriolis", guide, (cor[0], cor[1])))
                    along = (rel[0] - cor[0], rel[1] - cor[1])
                    self.vectors.append(Vector("", mid, b, "along", j.links[0], along))

    def slip_vectors(self) -> None:
        """At each higher pair, the contact on one link relative to the contact on the other."""
        for j in self.contacts:
            keys = [f"{j.name}@{link}" for link in j.links if link != self.ground]
            if len(keys) == 2:
                va, vb = self.images[keys[0]].value, self.images[keys[1]].value
                slip = (vb[0] - va[0], vb[1] - va[1])
                self.vectors.append(
                    Vector(self.label(keys[0]) + self.label(keys[1]), keys[0], keys[1], "slip", None, slip)
                )

    def _components(
        self, link: str, p: str | None, q: str | None, a: str, b: str, start: Vec, rel: Vec
    ) -> None:
        """Split a relative acceleration of two points of ``link`` into normal and tangential parts."""
        state = self.kin.links.get(link)
        if state is None or state.omega is None or state.alpha is None or p is None or q is None:
            return
        rp, rq = self.kin.positions[p], self.kin.positions[q]
        rx, ry = rq[0] - rp[0], rq[1] - rp[1]
        w2 = state.omega * state.omega
        normal = (-w2 * rx, -w2 * ry)
        tangential = (-state.alpha * ry, state.alpha * rx)
        floor = 1e-9 * max(math.hypot(*rel), 1e-300)
        if math.hypot(*normal) < floor or math.hypot(*tangential) < floor:
            return  # one part is nothing: the resultant is the whole story
        mid = f"~{a}>{b}"
        self.construction[mid] = (start[0] + normal[0], start[1] + normal[1])
        self.vectors.append(Vector("", a, mid, "normal", link, normal))
        self.vectors.append(Vector("", mid, b, "tangential", link, tangential))


def _guided(mech: Mechanism, kin: Kinematics) -> dict[tuple[str, str], Joint]:
    """(point, guide link) → the slider's joint, for each slider on a moving guide."""
    guided: dict[tuple[str, str], Joint] = {}
    for j in mech.joints:
        geom = kin.joints.get(j.name)
        if (
            kind_of(j).role == "path"
            and geom is not None
            and geom.point is not None
            and j.links[1] != mech.ground
        ):
            guided[(geom.point, j.links[1])] = j
    return guided


def _collinear(points: list[Vec]) -> bool:
    if len(points) < 3:
        return True
    (x0, y0), (x1, y1) = max(((p, q) for p in points for q in points), key=lambda pq: math.dist(*pq))
    L = math.hypot(x1 - x0, y1 - y0) or 1.0
    return max(abs((p[0] - x0) * (y1 - y0) - (p[1] - y0) * (x1 - x0)) / L for p in points) < 1e-6 * L


def _fixed_point(names: list[str], ground_names: list[str]) -> str:
    return next(n for n in names if n in ground_names)


def _ranks(link_keys: Mapping[str, list[str]], order: list[str]) -> dict[str, int]:
    """Hops from the pole through shared links: the order in which the notes find the points."""
    rank = {"o": 0}
    frontier = ["o"]
    while frontier:
        nxt = []
        for key in frontier:
            for keys in link_keys.values():
                if key in keys:
                    for k in keys:
                        if k not in rank:
                            rank[k] = rank[key] + 1
                            nxt.append(k)
        frontier = nxt
    for k in order:
        rank.setdefault(k, len(order))
    return rank


def _edges(keys: list[str], images: Mapping[str, Image], pos: Mapping[str, Vec]) -> list[tuple[str, str]]:
    """Pairs of a link's moving points to join: the one pair, a link's outline, or a line's steps."""
    if len(keys) < 2:
        return []
    if len(keys) == 2:
        return [(keys[0], keys[1])]
    pts = {k: pos[images[k].point] for k in keys if images[k].point in pos}  # type: ignore[index]
    if len(pts) != len(keys):
        return list(itertools.pairwise(keys))
    cx = sum(p[0] for p in pts.values()) / len(pts)
    cy = sum(p[1] for p in pts.values()) / len(pts)
    # collinear: join neighbours along the line; otherwise the outline in angular order
    (x0, y0), (x1, y1) = max(((pts[a], pts[b]) for a in keys for b in keys), key=lambda pq: math.dist(*pq))
    L = math.hypot(x1 - x0, y1 - y0) or 1.0
    off = max(abs((p[0] - x0) * (y1 - y0) - (p[1] - y0) * (x1 - x0)) / L for p in pts.values())
    if off < 1e-6 * L:  # a bar with points on its line: one vector end to end, the others on it
        along = sorted(keys, key=lambda k: (pts[k][0] - x0) * (x1 - x0) + (pts[k][1] - y0) * (y1 - y0))
        return [(along[0], along[-1])]
    ring = sorted(keys, key=lambda k: math.atan2(pts[k][1] - cy, pts[k][0] - cx))
    return [(ring[i], ring[(i + 1) % len(ring)]) for i in range(len(ring))]


# -- drawing ------------------------------------------------------------------------------
def polygon_figure(
    mech: Mechanism,
    data: PolygonData,
    *,
    room: Vec = (90.0, 90.0),
    scale: float | None = None,
    units: OutputUnits | None = None,
) -> Figure:
    """The polygon drawn to a round scale, with its scale bar and the value of each vector.

    Returns a :class:`Figure` in page mm.  Vector shafts carry ``class="vector"``
    and ``data-name`` (``ab``), components ``class="component"``.
    """
    acc = data.kind == "acceleration"
    units = units or OutputUnits()
    unit = units.acceleration if acc else units.velocity
    factor = unit_factor(unit)[1]  # SI per shown unit
    unit = unit.replace("^2", "²")
    colours = link_colours(mech)
    pts: list[Vec] = [(0.0, 0.0)] + [im.value for im in data.images] + list(data.construction.values())
    x0, y0, x1, y1 = bbox(pts)
    at_rest = max(x1 - x0, y1 - y0) <= 1e-200  # every image at the pole: nothing moves
    w, h = max(x1 - x0, 1e-300), max(y1 - y0, 1e-300)
    if scale is None:
        # at rest there is no extent to fit: a nominal 1 unit per cm, not 1e-301
        scale = (
            1.0 * factor
            if at_rest
            else (nice_scale(w, room[0]) if w / room[0] >= h / room[1] else nice_scale(h, room[1]))
        )
    tr = Transform(scale, (x0, y1), (MARGIN, TITLE_H + MARGIN))
    pw, ph = tr.length(w), tr.length(h)
    tiny = 1e-9 * max((math.hypot(*p) for p in pts), default=1.0)
    named = [v for v in data.vectors if v.name and math.hypot(*v.value) > tiny]
    width = max(2 * MARGIN + pw + 10.0, 62.0)  # labels may stand out to the right
    list_h = 4.0 * len(named) + 4
    page = Page(width, TITLE_H + 2 * MARGIN + ph + 10 + list_h)
    title = "Acceleration diagram" if acc else "Velocity diagram"
    page.add(Text((MARGIN - 6, 5.5), title, 3.4, "start", bold=True, cls="title"))
    if at_rest:
        what = "acceleration" if acc else "velocity"
        page.add(
            Text(
                (MARGIN - 6, 10.0),
                f"every {what} is zero: the polygon is the pole o",
                2.7,
                "start",
                "#333333",
                cls="value",
            )
        )

    def at(key: str) -> Vec:
        return tr(data.at(key))

    drawn, labelled = _vector_items(data, at, colours, tiny)
    drawn[:0] = page.items  # the title: no label on it
    _add_image_points(drawn, data, at, tr(((x0 + x1) / 2, (y0 + y1) / 2)))
    _add_vector_names(drawn, labelled, at)
    page.items = drawn
    # the scale and the values go under everything drawn, labels that stand out included
    lowest = max(
        (item_rect(i)[3] for i in drawn if not (isinstance(i, Text) and i.cls == "title")), default=0.0
    )
    y = max(TITLE_H + 2 * MARGIN + ph, lowest + 4.5)
    page.height += y - (TITLE_H + 2 * MARGIN + ph)
    page.extend(scale_bar((MARGIN - 6, y), scale / factor, unit))
    y += 7
    for v in named:
        mag = math.hypot(*v.value) / factor
        # in the acceleration polygon the coincident points' difference holds the Coriolis term too
        sliding = "  (Coriolis + sliding)" if acc else "  (sliding)"
        what = {"sliding": sliding, "slip": "  (slip)"}.get(v.kind, "")
        page.add(
            Text((MARGIN - 6, y), f"{v.name} = {fmt(mag)} {unit}{what}", 2.7, "start", "#333333", cls="value")
        )
        y += 4.0
    return page.figure(title)


def _vector_items(
    data: PolygonData, at: Callable[[str], Vec], colours: Mapping[str, str], tiny: float
) -> tuple[list[Item], list[tuple[Vector, str]]]:
    """The vectors' arrows (components thin and dashed, under the rest) and the named ones to label."""
    comps: list[Item] = []
    main: list[Item] = []
    labelled: list[tuple[Vector, str]] = []
    for v in data.vectors:
        colour = colours.get(v.link, INK) if v.link else "#444444"
        if math.hypot(*v.value) <= tiny:
            continue  # a zero vector (no slip at a pitch point): nothing to draw or list
        if not v.name:
            comps.extend(
                arrow(at(v.start), at(v.end), colour, 0.25, cls="component", head=1.6, dash=(1.2, 0.8))
            )
            continue
        width_mm = 0.55 if v.kind != "absolute" or v.link else 0.4
        main.extend(arrow(at(v.start), at(v.end), colour, width_mm, cls="vector", name=v.name))
        labelled.append((v, colour))
    return comps + main, labelled


def _add_image_points(drawn: list[Item], data: PolygonData, at: Callable[[str], Vec], centre: Vec) -> None:
    """A dot at each image and its label, away from ``centre`` (images at one place share one: "a, d")."""
    spots: dict[tuple[int, int], tuple[Vec, list[str]]] = {}
    for key, lab in [("o", data.pole)] + [(im.key, im.label) for im in data.images]:
        q = at(key)
        k = (round(q[0] * 2), round(q[1] * 2))
        entry = spots.setdefault(k, (q, []))
        if lab not in entry[1]:
            entry[1].append(lab)
    for q, _ in spots.values():
        drawn.append(Circle(q, 0.7, Style(INK, 0.2, fill=INK), "image"))
    for q, labs in spots.values():
        dx, dy = q[0] - centre[0], q[1] - centre[1]
        n = math.hypot(dx, dy)
        prefer = (dx / n, dy / n) if n > 1 else (-0.7, 0.7)
        label = place_label(q, ", ".join(labs), 3.2, prefer, drawn, italic=True, bold=True, cls="image-label")
        line = leader(q, label)
        drawn.extend([line, label] if line is not None else [label])


def _add_vector_names(
    drawn: list[Item], labelled: list[tuple[Vector, str]], at: Callable[[str], Vec]
) -> None:
    """Each vector's name beside its shaft, where it collides least with what is drawn."""
    for v, colour in labelled:
        p0, p1 = at(v.start), at(v.end)
        n = math.dist(p0, p1)
        if n < 3:
            continue
        ux, uy = (p1[0] - p0[0]) / n, (p1[1] - p0[1]) / n
        hw, hh = text_box(v.name, 2.9, bold=True)
        cands = []
        for extra, cost in ((1.2, 0.0), (3.0, 0.6), (5.5, 1.4)):
            off = extra + abs(ux) * hh + abs(uy) * hw
            for t, bonus in (
                (0.5, 0.3),
                (0.4, 0.2),
                (0.6, 0.2),
                (0.3, 0.1),
                (0.7, 0.1),
                (0.2, 0.0),
                (0.8, 0.0),
            ):
                m = (p0[0] + (p1[0] - p0[0]) * t, p0[1] + (p1[1] - p0[1]) * t)
                for side, sb in ((1, 0.05), (-1, 0.0)):
                    cands.append(
                        ((m[0] + uy * off * side, m[1] - ux * off * side - 0.15 * 2.9), bonus + sb - cost)
                    )
        spot = best_spot(cands, v.name, 2.9, drawn, bold=True)
        label = Text(spot, v.name, 2.9, "middle", colour, italic=True, bold=True, cls="vector-label")
        if clashes(label, drawn):  # no room beside the shaft: farther off, with a leader to its middle
            mid = ((p0[0] + p1[0]) / 2, (p0[1] + p1[1]) / 2)
            label = place_label(
                mid, v.name, 2.9, (uy, -ux), drawn, colour=colour, italic=True, bold=True, cls="vector-label"
            )
            line = leader(mid, label, colour)
            if line is not None:
                drawn.append(line)
        drawn.append(label)
