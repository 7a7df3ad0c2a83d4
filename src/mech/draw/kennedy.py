"""Kennedy's circle diagram as a drawing: the links numbered round a circle, I-centres as chords.

Each I-centre I_ij is the chord joining numbers i and j: solid for those found
by inspection (pins, sliders, rolling contacts), dashed and numbered in the
order the Aronhold-Kennedy construction found them (a diagonal that closes two
triangles of known sides).  The same construction :func:`mech.explain.explain_icentres`
writes out.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from mech.draw.scene import Figure, Page, best_spot, text_width
from mech.shapes import INK, Circle, Line, Style, Text

if TYPE_CHECKING:  # pragma: no cover
    from mech.icentres.locate import ICentres

__all__ = ["circle_diagram"]

R = 32.0  # circle radius, mm
MARGIN = 22.0
_GAP = 3.2  # mm from a node's centre to its label (the node is 1.2 in radius)


def circle_diagram(ics: ICentres, *, title: str = "Kennedy's circle diagram") -> Figure:
    """The circle diagram of located I-centres (:func:`mech.icentres.locate`)."""
    n = len(ics.links)
    cy = MARGIN + R
    widest = max((text_width(f"{k} {link}", 3.0) for k, link in enumerate(ics.links, 1)), default=0.0)
    cx = max(MARGIN + R + 20.0, R + _GAP + widest + 6.0)  # a side label's whole width outside the circle
    page = Page(2 * cx, 2 * (MARGIN + R) + 12.0)
    page.add(Text((6.0, 6.0), title, 3.4, "start", bold=True, cls="title"))
    page.add(Circle((cx, cy + 6.0), R, Style("#999999", 0.25), "kennedy-circle"))

    def spot(k: int) -> tuple[float, float]:  # number k (1-based), clockwise from the top
        a = math.pi / 2 - 2 * math.pi * (k - 1) / n
        return (cx + R * math.cos(a), cy + 6.0 - R * math.sin(a))

    later = sorted(
        (c for c in ics.centres if not c.primary),
        key=lambda c: (c.step if c.step is not None else 99, c.numbers),
    )
    order = {c.numbers: k for k, c in enumerate(later, 1)}
    steps: list[tuple[tuple[float, float], tuple[float, float], str]] = []
    for c in ics.centres:
        p, q = spot(c.numbers[0]), spot(c.numbers[1])
        if c.primary:
            page.add(Line(p, q, Style(INK, 0.45), "kennedy-primary", c.name))
        else:
            page.add(Line(p, q, Style("#1f77b4", 0.35, dash=(1.5, 1.0)), "kennedy-diagonal", c.name))
            steps.append((p, q, f"{order[c.numbers]}"))
    _step_numbers(page, steps)
    for k, link in enumerate(ics.links, 1):
        x, y = spot(k)
        page.add(Circle((x, y), 1.2, Style(INK, 0.3, fill="#ffffff"), "kennedy-node", link))
        page.add(_node_label((x, y), (cx, cy + 6.0), f"{k} {link}"))
    page.add(
        Text(
            (6.0, page.height - 3.0),
            "solid: by inspection; dashed: by Kennedy's theorem, numbered in order",
            2.6,
            "start",
            "#333333",
            cls="caption",
        )
    )
    return page.figure(title)


def _node_label(node: tuple[float, float], centre: tuple[float, float], text: str) -> Text:
    """A link's number and name outside its node, clear of the node's circle and of the chords.

    Beside the node on the circle's sides (starting or ending at it, so a long name grows away
    from the circle), above or below it at the top and bottom.
    """
    ox, oy = node[0] - centre[0], node[1] - centre[1]
    d = math.hypot(ox, oy) or 1.0
    ux, uy = ox / d, oy / d
    anchor = "start" if ux > 0.3 else "end" if ux < -0.3 else "middle"
    px, py = node[0] + _GAP * ux, node[1] + _GAP * uy
    baseline = py + 1.05 + (1.05 * uy if uy > 0 else 1.9 * uy) * (anchor == "middle")  # 1.05: half a cap
    return Text((px, baseline), text, 3.0, anchor, cls="kennedy-label")


def _step_numbers(page: Page, steps: list[tuple[tuple[float, float], tuple[float, float], str]]) -> None:
    """Each diagonal's step number beside it, where it lies on no other number (chords cross)."""
    for p, q, text in steps:
        length = math.dist(p, q) or 1.0
        n = (-(q[1] - p[1]) / length, (q[0] - p[0]) / length)
        cands = []
        for t, bonus in (
            (1 / 3, 0.3),
            (0.25, 0.2),
            (0.42, 0.2),
            (0.5, 0.1),
            (0.58, 0.1),
            (0.67, 0.0),
            (0.75, 0.0),
        ):
            m = (p[0] + (q[0] - p[0]) * t, p[1] + (q[1] - p[1]) * t)
            for side in (1.0, -1.0):
                cands.append(((m[0] + 1.8 * side * n[0], m[1] + 1.8 * side * n[1]), bonus))
        at = best_spot(cands, text, 2.6, page.items)
        page.add(Text(at, text, 2.6, "middle", "#1f77b4", cls="kennedy-step"))
