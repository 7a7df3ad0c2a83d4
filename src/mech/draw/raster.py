"""A :class:`~mech.draw.scene.Figure` painted by matplotlib: PNG files and GIF frames.

matplotlib is an optional extra (``pip install 'planar-mech[plot]'``) and is
imported only here, inside the functions, so that nothing else in mech pays
its ~0.4 s import.  The painting is made deterministic: the Agg backend, a
fixed DPI, the DejaVu Sans font that ships with matplotlib (so every machine
has the same glyphs), and no metadata (no timestamp, no software version) in
the PNG.
"""

from __future__ import annotations

from typing import IO, Any

from mech.draw.scene import Figure
from mech.errors import MechError
from mech.shapes import Circle, Line, Poly, Style, Text

__all__ = ["DPI", "MissingExtraError", "render_rgb", "to_png", "use_matplotlib"]

DPI = 150
_MM = 1 / 25.4  # inches per mm
_PT = 72 / 25.4  # points per mm
INSTALL = "pip install 'planar-mech[plot]'"


class MissingExtraError(MechError, ImportError):
    """An optional dependency (matplotlib) is needed for what was asked and is not installed."""


def use_matplotlib() -> Any:
    """Import matplotlib with the Agg backend, or say how to install it (exit status 2)."""
    try:
        import matplotlib
    except ImportError:
        raise MissingExtraError(
            "PNG and GIF output need matplotlib, which is not installed",
            hint=f"{INSTALL} (or write SVG: -o drawing.svg needs nothing more)",
        ) from None
    matplotlib.use("Agg", force=True)
    return matplotlib


def _canvas(figure: Figure, dpi: int) -> tuple[Any, Any]:
    """A matplotlib figure of ``figure``: page mm as data units, items stacked in order."""
    fig, ax = _blank_page(figure, dpi)
    z = 0.0
    for item in figure.items:
        z += 1e-3
        if isinstance(item, Text):
            _add_text(ax, item, z)
        elif isinstance(item, Line):
            _add_line(ax, item, z)
        elif isinstance(item, Poly):
            _add_poly(ax, item, z)
        elif isinstance(item, Circle):
            _add_circle(ax, item, z)
    return fig, ax


def _blank_page(figure: Figure, dpi: int) -> tuple[Any, Any]:
    """A white figure the page's size, one axes over all of it, y growing down as on the page."""
    use_matplotlib()
    from matplotlib.figure import Figure as MplFigure

    fig = MplFigure(figsize=(figure.width * _MM, figure.height * _MM), dpi=dpi)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, figure.width)
    ax.set_ylim(figure.height, 0)
    ax.set_axis_off()
    ax.set_facecolor("white")
    fig.patch.set_facecolor("white")
    return fig, ax


def _stroke(s: Style) -> tuple[float, Any]:
    """(line width in points, matplotlib dash pattern) of a style; no stroke is width 0."""
    lw = s.width * _PT if s.stroke else 0.0
    dashes = (0, tuple(d * _PT / max(lw, 1e-9) for d in s.dash)) if s.dash and lw else "solid"
    return lw, dashes


def _add_text(ax: Any, item: Text, z: float) -> None:
    ax.text(
        item.at[0],
        item.at[1],
        item.text,
        fontsize=item.size / 0.73 * _PT,
        ha=_HA[item.anchor],
        va="center_baseline",
        color=item.colour,
        family="DejaVu Sans",
        style="italic" if item.italic else "normal",
        weight="bold" if item.bold else "normal",
        zorder=z,
    )


def _add_line(ax: Any, item: Line, z: float) -> None:
    s = item.style
    lw, dashes = _stroke(s)
    ax.plot(
        [item.p0[0], item.p1[0]],
        [item.p0[1], item.p1[1]],
        color=s.stroke or "none",
        lw=lw,
        linestyle=dashes,
        solid_capstyle="round",
        dash_capstyle="round",
        zorder=z,
    )


def _add_poly(ax: Any, item: Poly, z: float) -> None:
    """A polygon or polyline: its fill (with the style's opacity) under its outline."""
    from matplotlib.patches import Polygon as MplPolygon

    s = item.style
    lw, dashes = _stroke(s)
    if s.fill:
        ax.add_patch(
            MplPolygon(
                item.points,
                closed=item.closed,
                facecolor=s.fill,
                alpha=s.fill_opacity,
                edgecolor="none",
                zorder=z,
            )
        )
    if s.stroke:
        ax.add_patch(
            MplPolygon(
                item.points,
                closed=item.closed,
                facecolor="none",
                edgecolor=s.stroke,
                lw=lw,
                linestyle=dashes,
                joinstyle="round",
                zorder=z,
            )
        )


def _add_circle(ax: Any, item: Circle, z: float) -> None:
    from matplotlib.patches import Circle as MplCircle

    s = item.style
    lw, dashes = _stroke(s)
    ax.add_patch(
        MplCircle(
            item.centre,
            item.r,
            facecolor=s.fill or "none",
            edgecolor=s.stroke or "none",
            lw=lw,
            linestyle=dashes,
            alpha=None,
            zorder=z,
        )
    )


_HA = {"start": "left", "middle": "center", "end": "right"}


def to_png(figure: Figure, path: str | IO[bytes], dpi: int = DPI) -> None:
    """Write ``figure`` as a PNG at ``dpi`` (no metadata, so the file is reproducible).

    ``path``: a file name, or a binary file object (:func:`mech.draw.save` hands one
    that replaces the file atomically).
    """
    fig, _ = _canvas(figure, dpi)
    fig.savefig(path, format="png", dpi=dpi, facecolor="white", metadata={"Software": None})


def render_rgb(figure: Figure, dpi: int = DPI) -> Any:
    """The figure as an (h, w, 3) uint8 array: GIF frames and image comparisons."""
    import numpy as np
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    fig, _ = _canvas(figure, dpi)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    return np.asarray(canvas.buffer_rgba())[..., :3].copy()
