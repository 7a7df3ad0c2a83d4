"""I-centres over the configuration diagram: labelled points, and arrows for the far ones.

An I-centre close enough to be drawn is a small ringed cross labelled ``I13``.
One at infinity (a slider's I-centre with ground lies on the perpendicular to
its path, infinitely far) cannot be drawn, so it becomes an arrow at the
border of the drawing pointing its way, labelled ``I14 → ∞`` as the notes
write it.  A finite I-centre too far away to keep the mechanism at a useful
scale (more than three quarters of the mechanism's size beyond it) is treated the same, with its
true distance from a named point, the frame's first pivot: ``I15 → 1148 mm from O₂``.

The I-centres come from :func:`mech.icentres.locate`; anything with ``name``,
``point`` ((x, y) or None), ``at_infinity`` and ``direction`` will do.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import Any

from mech.draw.scene import Transform, arrow, bbox, fmt, leader, place_label
from mech.shapes import Circle, Item, Line, Style, Text

__all__ = ["REACH", "overlay", "reachable"]

Vec = tuple[float, float]

#: A finite I-centre is drawn in place when it lies within REACH mechanism sizes
#: of the mechanism's bounding box; farther ones become border arrows.
REACH = 0.75
COLOUR = "#c62828"


def _label(name: str) -> str:
    return name


def reachable(centres: Iterable[Any], points: Sequence[Vec]) -> list[Any]:
    """The finite I-centres near enough to the mechanism's ``points`` to be drawn in place."""
    if not points:
        return []
    x0, y0, x1, y1 = bbox(points)
    size = max(x1 - x0, y1 - y0, 1e-12)
    out = []
    for c in centres:
        p = getattr(c, "point", None)
        if p is None or getattr(c, "at_infinity", False):
            continue
        if x0 - REACH * size <= p[0] <= x1 + REACH * size and y0 - REACH * size <= p[1] <= y1 + REACH * size:
            out.append(c)
    return out


def overlay(
    centres: Sequence[Any],
    tr: Transform,
    box: tuple[float, float, float, float],
    *,
    drawn: Sequence[Item] = (),
    origin: tuple[str, Vec] | None = None,
    unit: tuple[str, float] = ("m", 1.0),
    marked: bool = False,
) -> list[Item]:
    """Items that mark ``centres`` on a configuration drawn by ``tr`` inside ``box`` (page mm).

    Several I-centres at one place (I12 at a pin that is also I13's place…)
    share one mark and one label "I12, I13".  Labels keep clear of what is
    ``drawn`` (and of each other), with a leader line when they stand off.  A far
    I-centre's distance is measured from ``origin`` (the frame's first pivot: its
    label and world point) and written in ``unit`` (name, metres per unit).  ``marked``: the
    marks are already drawn (:func:`marks`, before the configuration's own labels, so that
    those keep off them); only the labels and the far centres' arrows are given.
    """
    items: list[Item] = []
    x0, y0, x1, y1 = box
    inside: dict[tuple[int, int], list[str]] = {}
    where: dict[tuple[int, int], Vec] = {}
    far: list[tuple[str, Vec, str]] = []
    for c in centres:
        name = _label(c.name)
        p = getattr(c, "point", None)
        if p is not None and not getattr(c, "at_infinity", False):
            q = tr(p)
            if x0 - 1e-6 <= q[0] <= x1 + 1e-6 and y0 - 1e-6 <= q[1] <= y1 + 1e-6:
                key = (round(q[0] * 4), round(q[1] * 4))
                inside.setdefault(key, []).append(name)
                where[key] = q
                continue
            cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
            d = (q[0] - cx, q[1] - cy)
            n = math.hypot(*d)
            what = "far" if origin is None else _fmt_len(math.dist(p, origin[1]), unit)
            far.append((name, (d[0] / n, d[1] / n), what))
            continue
        u = getattr(c, "direction", None)
        if not getattr(c, "at_infinity", False) or u is None:
            continue  # not located at this instant: nothing to draw
        far.append((name, (u[0], -u[1]), "∞"))
    if origin is not None and any(w not in ("∞", "far") for _, _, w in far):
        note = f"far I-centres: arrows at the edge, their distances from {origin[0]}"
        items.append(Text((x0 - 6, y1 + 11.5), note, 2.6, "start", COLOUR, cls="icentre-note"))
    if not marked:
        items.extend(_marks(where, inside))
    for key, names in inside.items():
        q = where[key]
        label = place_label(
            q, ", ".join(names), 2.8, (0.6, 0.8), [*drawn, *items], colour=COLOUR, cls="icentre-label"
        )
        line = leader(q, label, COLOUR)
        items.extend([line, label] if line is not None else [label])
    items.extend(_border_arrows(far, box, [*drawn, *items]))
    return items


def marks(centres: Sequence[Any], tr: Transform, box: tuple[float, float, float, float]) -> list[Item]:
    """The marks (a circle and a cross) of the I-centres inside ``box``, as :func:`overlay` draws them.

    Drawn before the configuration's labels, they are obstacles those labels keep clear of.
    """
    where: dict[tuple[int, int], Vec] = {}
    inside: dict[tuple[int, int], list[str]] = {}
    x0, y0, x1, y1 = box
    for c in centres:
        p = getattr(c, "point", None)
        if p is None or getattr(c, "at_infinity", False):
            continue
        q = tr(p)
        if x0 - 1e-6 <= q[0] <= x1 + 1e-6 and y0 - 1e-6 <= q[1] <= y1 + 1e-6:
            key = (round(q[0] * 4), round(q[1] * 4))
            inside.setdefault(key, []).append(_label(c.name))
            where[key] = q
    return _marks(where, inside)


def _marks(where: dict[tuple[int, int], Vec], inside: dict[tuple[int, int], list[str]]) -> list[Item]:
    items: list[Item] = []
    for key in inside:
        q = where[key]
        items.append(Circle(q, 1.5, Style(COLOUR, 0.35), "icentre", inside[key][0]))
        items.append(Line((q[0] - 1.1, q[1] - 1.1), (q[0] + 1.1, q[1] + 1.1), Style(COLOUR, 0.3), "icentre"))
        items.append(Line((q[0] - 1.1, q[1] + 1.1), (q[0] + 1.1, q[1] - 1.1), Style(COLOUR, 0.3), "icentre"))
    return items


def _fmt_len(d: float, unit: tuple[str, float]) -> str:
    """A distance (m) in the file's unit, to four figures."""
    return f"{fmt(d / unit[1], 4)} {unit[0]}"


def _border_arrows(
    far: list[tuple[str, Vec, str]],
    box: tuple[float, float, float, float],
    drawn: Sequence[Item],
) -> list[Item]:
    """An arrow per direction of far I-centres, from inside the border toward them, each labelled.

    I-centres the same way share the arrow; the label names each with its own distance
    ("I15 → 1148 mm, I16 → 990 mm", from the point the drawing's note names) or ∞.
    """
    items: list[Item] = []
    x0, y0, x1, y1 = box
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    groups: list[tuple[Vec, list[tuple[str, str]]]] = []
    for name, u, what in far:
        for gu, members in groups:
            if gu[0] * u[0] + gu[1] * u[1] > 0.995:
                members.append((name, what))
                break
        else:
            groups.append((u, [(name, what)]))
    tails: list[tuple[Vec, Vec, str]] = []
    for u, members in groups:
        # where the ray from the centre leaves the box
        ts = []
        for edge, comp, c0 in ((x1, 0, cx), (x0, 0, cx), (y1, 1, cy), (y0, 1, cy)):
            if abs(u[comp]) > 1e-12:
                t = (edge - c0) / u[comp]
                if t > 0:
                    ts.append(t)
        t = min(ts) if ts else 0.0
        tip = (cx + u[0] * (t + 10), cy + u[1] * (t + 10))  # in the margin, clear of the mechanism
        tail = (tip[0] - u[0] * 9, tip[1] - u[1] * 9)
        items.extend(arrow(tail, tip, COLOUR, 0.4, cls="icentre-arrow", name=members[0][0]))
        tails.append((tail, u, ", ".join(f"{n} → {w}" for n, w in members)))
    for tail, u, text in tails:  # every arrow first, then the labels, which keep clear of them all
        label = place_label(
            tail, text, 2.8, (-u[1], u[0]), [*drawn, *items], colour=COLOUR, cls="icentre-label"
        )
        line = leader(tail, label, COLOUR)
        items.extend([line, label] if line is not None else [label])
    return items
