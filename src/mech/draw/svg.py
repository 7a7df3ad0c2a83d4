"""A :class:`~mech.draw.scene.Figure` as SVG text: a writer of our own, no dependency.

SVG is a handful of elements (``line``, ``polygon``, ``polyline``, ``circle``,
``text``); writing them directly costs nothing to import and gives files that
are byte-for-byte reproducible (no timestamps, no generator ids), which keeps
the shipped drawings stable under version control.

The root element states its size in millimetres with a matching ``viewBox``,
so one user unit is one millimetre and the scales printed on the drawing hold
on paper.  Items keep their ``cls`` as ``class`` and their ``name`` as
``data-name``, which is how tests find "the vector ab" in the output.
"""

from __future__ import annotations

from xml.sax.saxutils import escape, quoteattr

from mech._text import xml_safe
from mech.draw.scene import Figure
from mech.shapes import Circle, Item, Line, Poly, Style, Text

__all__ = ["to_svg"]

FONT = "DejaVu Sans, Verdana, Arial, Helvetica, sans-serif"


def _n(x: float) -> str:
    """A coordinate with 0.01 mm resolution, without noise such as ``-0``."""
    text = f"{x:.2f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _style(s: Style) -> str:
    parts = [f'stroke="{s.stroke}"' if s.stroke else 'stroke="none"']
    if s.stroke:
        parts.append(f'stroke-width="{_n(s.width)}"')
    parts.append(f'fill="{s.fill}"' if s.fill else 'fill="none"')
    if s.fill and s.fill_opacity < 1:
        parts.append(f'fill-opacity="{_n(s.fill_opacity)}"')
    if s.dash:
        parts.append(f'stroke-dasharray="{" ".join(_n(d) for d in s.dash)}"')
    return " ".join(parts)


def _tags(cls: str, name: str) -> str:
    out = f" class={quoteattr(cls)}" if cls else ""
    return out + (f" data-name={quoteattr(name)}" if name else "")


def _item(item: Item) -> str:
    if isinstance(item, Line):
        (x1, y1), (x2, y2) = item.p0, item.p1
        return (
            f'<line x1="{_n(x1)}" y1="{_n(y1)}" x2="{_n(x2)}" y2="{_n(y2)}" {_style(item.style)}'
            f' stroke-linecap="round"{_tags(item.cls, item.name)}/>'
        )
    if isinstance(item, Poly):
        pts = " ".join(f"{_n(x)},{_n(y)}" for x, y in item.points)
        tag = "polygon" if item.closed else "polyline"
        return (
            f'<{tag} points="{pts}" {_style(item.style)} stroke-linejoin="round"'
            f"{_tags(item.cls, item.name)}/>"
        )
    if isinstance(item, Circle):
        (cx, cy) = item.centre
        return f'<circle cx="{_n(cx)}" cy="{_n(cy)}" r="{_n(item.r)}" {_style(item.style)}{_tags(item.cls, item.name)}/>'
    assert isinstance(item, Text)
    x, y = item.at
    extra = ' font-style="italic"' if item.italic else ""
    extra += ' font-weight="bold"' if item.bold else ""
    # SVG's font-size is the em size; our size is about the cap height (≈ 0.73 em).
    return (
        f'<text x="{_n(x)}" y="{_n(y)}" font-size="{_n(item.size / 0.73)}" text-anchor="{item.anchor}"'
        f' dominant-baseline="central" fill="{item.colour}"{extra}{_tags(item.cls, "")}>'
        f"{escape(item.text)}</text>"
    )


def to_svg(figure: Figure) -> str:
    """The SVG document (UTF-8 text) of a figure; deterministic for a given figure."""
    w, h = figure.width, figure.height
    head = (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{_n(w)}mm" height="{_n(h)}mm"'
        f' viewBox="0 0 {_n(w)} {_n(h)}" font-family="{FONT}">\n'
    )
    title = f"<title>{escape(figure.title)}</title>\n" if figure.title else ""
    body = [f'<rect x="0" y="0" width="{_n(w)}" height="{_n(h)}" fill="white"/>']
    body += [_item(item) for item in figure.items]
    return xml_safe(head + title + "\n".join(body) + "\n</svg>\n")
