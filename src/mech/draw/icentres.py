"""I-centres over the configuration diagram: labelled points, and arrows for the far ones.

An I-centre close enough to be drawn is a small ringed cross labelled ``I13``.
One at infinity (a slider's I-centre with ground lies on the perpendicular to
its path, infinitely far) cannot be drawn, so it becomes an arrow at the
border of the drawing pointing its way, labelled ``I14 → ∞`` as the notes
write it.  A finite I-centre too far away to keep the mechanism at a useful
scale is treated the same, with its distance instead of ∞.

The I-centres come from :func:`mech.icentres.locate`; anything with ``name``,
``point`` ((x, y) or None), ``at_infinity`` and ``direction`` will do.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import Any

from mech.draw.scene import Circle, Item, Line, Style, Text, Transform, arrow, bbox

__all__ = ["REACH", "overlay", "reachable"]

Vec = tuple[float, float]

#: A finite I-centre is drawn in place when it lies within REACH mechanism sizes
#: of the mechanism's bounding box; farther ones become border arrows.
REACH = 2.5
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


def overlay(centres: Sequence[Any], tr: Transform, box: tuple[float, float, float, float]) -> list[Item]:
    """Items that mark ``centres`` on a configuration drawn by ``tr`` inside ``box`` (page mm).

    Several I-centres at one place (I12 at a pin that is also I13's place…)
    share one mark and one label "I12, I13".
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
            dist = math.dist(p, _world_centre(tr, box))
            far.append((name, (d[0] / n, d[1] / n), f"{_fmt_len(dist)} away"))
            continue
        u = getattr(c, "direction", None)
        if not getattr(c, "at_infinity", False) or u is None:
            continue  # not located at this instant: nothing to draw
        far.append((name, (u[0], -u[1]), "∞"))
    for key, names in inside.items():
        q = where[key]
        items.append(Circle(q, 1.5, Style(COLOUR, 0.35), "icentre", names[0]))
        items.append(Line((q[0] - 1.1, q[1] - 1.1), (q[0] + 1.1, q[1] + 1.1), Style(COLOUR, 0.3), "icentre"))
        items.append(Line((q[0] - 1.1, q[1] + 1.1), (q[0] + 1.1, q[1] - 1.1), Style(COLOUR, 0.3), "icentre"))
        items.append(
            Text((q[0] + 2.2, q[1] + 3.0), ", ".join(names), 2.8, "start", COLOUR, cls="icentre-label")
        )
    items.extend(_border_arrows(far, box))
    return items


def _world_centre(tr: Transform, box: tuple[float, float, float, float]) -> Vec:
    """The world point at the middle of ``box`` (inverse of ``tr``)."""
    k = tr.scale / 10.0
    cx, cy = (box[0] + box[2]) / 2, (box[1] + box[3]) / 2
    return (tr.world[0] + (cx - tr.origin[0]) * k, tr.world[1] - (cy - tr.origin[1]) * k)


def _fmt_len(d: float) -> str:
    return f"{d * 1000:.0f} mm" if d < 10 else f"{d:.3g} m"


def _border_arrows(far: list[tuple[str, Vec, str]], box: tuple[float, float, float, float]) -> list[Item]:
    """An arrow per far I-centre, from inside the border toward it; arrows of one way share it."""
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
    for u, members in groups:
        # where the ray from the centre leaves the box
        ts = []
        for edge, comp, c0 in ((x1, 0, cx), (x0, 0, cx), (y1, 1, cy), (y0, 1, cy)):
            if abs(u[comp]) > 1e-12:
                t = (edge - c0) / u[comp]
                if t > 0:
                    ts.append(t)
        t = min(ts) if ts else 0.0
        tip = (cx + u[0] * (t + 6), cy + u[1] * (t + 6))
        tail = (tip[0] - u[0] * 12, tip[1] - u[1] * 12)
        items.extend(arrow(tail, tip, COLOUR, 0.4, cls="icentre-arrow", name=members[0][0]))
        text = ", ".join(n for n, _ in members) + " → " + members[0][1]
        anchor = "start" if u[0] > 0.3 else ("end" if u[0] < -0.3 else "middle")
        side = (-u[1], u[0])
        lab = (tail[0] + side[0] * 3.5 * (1 if anchor != "end" else -1), tail[1] + side[1] * 3.5)
        if anchor == "middle":
            lab = (tail[0] + 2.5, tail[1])
            anchor = "start"
        items.append(Text(lab, text, 2.8, anchor, COLOUR, cls="icentre-label"))
    return items
