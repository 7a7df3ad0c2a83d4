"""Drawings a teacher can project: no label on another, nothing cut at the edge, every example.

Every shipped example (the six-bars among them) and a compound gear train are drawn as
``mech draw --velocity``, ``--acceleration`` and ``--icentres`` draw them, and as ``mech
icentres --circle`` draws Kennedy's circle.  The texts are measured as matplotlib paints them
(the PNG writer: DejaVu Sans, the font the SVG asks for first), lines, outlines and circles by
their geometry with half their stroke; then

* no two texts overlap (by more than 0.05 mm: glyphs' boxes touch at their corners);
* every element lies inside the page (the view box).
"""

from __future__ import annotations

import itertools
import math
from functools import cache
from pathlib import Path

import pytest

pytest.importorskip("matplotlib")

from mech.draw import draw
from mech.draw.kennedy import circle_diagram
from mech.draw.scene import Figure
from mech.errors import MechError
from mech.icentres import locate
from mech.kinematics import solve
from mech.loader import load, loads
from mech.shapes import Circle, Line, Poly, Text
from mechanism_texts import COMPOUND_GEAR

ROOT = Path(__file__).resolve().parent.parent
MECHANISMS = ROOT / "mechanisms"
SLACK = 0.05  # mm


def _mechanisms() -> dict[str, object]:
    out: dict[str, object] = {p.stem: load(p) for p in sorted(MECHANISMS.glob("*.yaml"))}
    out["compound_gear"] = loads(COMPOUND_GEAR, path="compound_gear.yaml")
    return out


MECHS = _mechanisms()
WAYS = ("velocity", "acceleration", "icentres", "circle")


def _level(m) -> str | None:
    """How far the example solves as drawn (acceleration, or velocity where a contact has no curvature)."""
    if not m.has_geometry:
        return None
    for level in ("acceleration", "velocity"):
        try:
            solve(m, level)
            return level
        except MechError:
            continue
    return None


@cache
def _drawable(name: str, way: str) -> bool:
    """Whether the drawing ``way`` of example ``name`` exists (its solve, not its drawing)."""
    level = _level(MECHS[name])
    return level is not None and (way != "acceleration" or level == "acceleration")


@cache
def figure(name: str, way: str) -> Figure | None:
    """The drawing ``way`` of example ``name`` as the command makes it (None: that drawing does not exist)."""
    if not _drawable(name, way):
        return None
    m = MECHS[name]
    kin = solve(m, "acceleration" if way == "acceleration" else "velocity")
    if way == "velocity":
        return draw(m, kin, velocity=True)
    if way == "acceleration":
        return draw(m, kin, acceleration=True)
    ics = locate(m, kin)
    if way == "icentres":
        return draw(m, kin, icentres=list(ics.centres))
    return circle_diagram(ics, title=f"{m.label}: Kennedy's circle diagram")


# The cases are chosen by solving, not drawing: every example drawn four ways is about 14 s of CPU,
# which collection would pay in the default run, where the tests that measure them are not run.
CASES = [(name, way) for name in MECHS for way in WAYS if _drawable(name, way)]


@cache
def measured_case(name: str, way: str) -> list[tuple[object, tuple[float, float, float, float]]]:
    """:func:`measured` of one case, once for both tests."""
    fig = figure(name, way)
    assert fig is not None
    return measured(fig)


def measured(fig: Figure) -> list[tuple[object, tuple[float, float, float, float]]]:
    """Every item with its box (x0, y0, x1, y1) in page mm: texts as matplotlib paints them."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from mech.draw.raster import _canvas

    mfig, ax = _canvas(fig, 100)
    renderer = FigureCanvasAgg(mfig).get_renderer()
    inverse = ax.transData.inverted()
    texts = iter(ax.texts)
    out = []
    for item in fig.items:
        if isinstance(item, Text):
            if not item.text.strip():
                next(texts)
                continue
            bb = next(texts).get_window_extent(renderer)
            (x0, y0), (x1, y1) = inverse.transform([(bb.x0, bb.y0), (bb.x1, bb.y1)])
            out.append((item, (min(x0, x1), min(y0, y1), max(x0, x1), max(y0, y1))))
            continue
        half = item.style.width / 2 if item.style.stroke else 0.0
        if isinstance(item, Line):
            pts = [item.p0, item.p1]
        elif isinstance(item, Poly):
            pts = list(item.points)
        else:
            assert isinstance(item, Circle)
            (cx, cy), r = item.centre, item.r
            pts = [(cx - r, cy - r), (cx + r, cy + r)]
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        out.append((item, (min(xs) - half, min(ys) - half, max(xs) + half, max(ys) + half)))
    return out


def _overlap(a, b) -> float:
    """How far two boxes overlap: the smaller of their overlaps in x and in y (mm), 0 if apart."""
    return max(0.0, min(min(a[2], b[2]) - max(a[0], b[0]), min(a[3], b[3]) - max(a[1], b[1])))


@pytest.mark.slow
@pytest.mark.parametrize(("name", "way"), CASES, ids=[f"{n}-{w}" for n, w in CASES])
def test_no_two_texts_of_a_drawing_overlap(name, way):
    texts = [(item, box) for item, box in measured_case(name, way) if isinstance(item, Text)]
    clashes = [
        f"{a.text!r} on {b.text!r} by {_overlap(ba, bb):.2f} mm"
        for (a, ba), (b, bb) in itertools.combinations(texts, 2)
        if _overlap(ba, bb) > SLACK
    ]
    assert not clashes, f"{name} {way}: " + "; ".join(clashes)


@pytest.mark.slow
@pytest.mark.parametrize(("name", "way"), CASES, ids=[f"{n}-{w}" for n, w in CASES])
def test_every_element_of_a_drawing_lies_in_its_view_box(name, way):
    fig = figure(name, way)
    outside = [
        f"{getattr(item, 'text', None) or type(item).__name__ + ' ' + getattr(item, 'cls', '')} at "
        f"({box[0]:.1f}, {box[1]:.1f})–({box[2]:.1f}, {box[3]:.1f})"
        for item, box in measured_case(name, way)
        if box[0] < -SLACK or box[1] < -SLACK or box[2] > fig.width + SLACK or box[3] > fig.height + SLACK
    ]
    assert not outside, f"{name} {way} ({fig.width:.1f} × {fig.height:.1f} mm): " + "; ".join(outside)


#: A circle smaller than this (mm) is a mark: a pin, a point, an I-centre, a node of Kennedy's circle.
MARK = 3.0


@pytest.mark.slow
@pytest.mark.parametrize(("name", "way"), CASES, ids=[f"{n}-{w}" for n, w in CASES])
def test_no_text_of_a_drawing_lies_on_a_pin_or_a_mark(name, way):
    """A label struck through by a pin or an I-centre's mark (O₂ under I24) cannot be read."""
    items = measured_case(name, way)
    texts = [(item, box) for item, box in items if isinstance(item, Text)]
    marks = [(item, box) for item, box in items if isinstance(item, Circle) and item.r < MARK]
    clashes = [
        f"{t.text!r} on {c.cls} {c.name} by {_overlap(bt, bc):.2f} mm"
        for t, bt in texts
        for c, bc in marks
        if _overlap(bt, bc) > 0.2
    ]
    assert not clashes, f"{name} {way}: " + "; ".join(clashes)


def test_the_cases_cover_every_drawable_example_and_the_six_bars():
    names = {n for n, _ in CASES}
    assert {
        "watt_six_bar",
        "stephenson_six_bar",
        "crank_slotted_lever_quick_return",
        "compound_gear",
    } <= names
    drawable = {n for n, m in MECHS.items() if _level(m) is not None}
    assert names == drawable


@pytest.mark.slow
def test_every_case_is_drawn_on_a_page_of_finite_size():
    assert all(math.isfinite(figure(n, w).width) and math.isfinite(figure(n, w).height) for n, w in CASES)
