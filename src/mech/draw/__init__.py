"""Drawings of a solved mechanism: configuration diagram, velocity and acceleration polygons.

::

    from mech.draw import draw, save
    fig = draw(mech, kin, velocity=True, icentres=ic)     # a Figure, in page mm
    save(fig, "four_bar.svg")                              # or .png (needs matplotlib)

The drawings are built once as backend-neutral figures (:mod:`.scene`) and
painted by our own SVG writer (:mod:`.svg`, nothing to import) or by
matplotlib (:mod:`.raster`, PNG and GIF, the optional ``plot`` extra).  This
package is imported only by ``mech draw`` (and sweeps that plot), never by
``mech dof`` or ``mech check``.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from mech.draw.config import configuration
from mech.draw.polygon import acceleration_polygon, polygon_figure, velocity_polygon
from mech.draw.scene import Figure, Page
from mech.errors import InputError
from mech.model import Mechanism
from mech.options import OutputUnits
from mech.shapes import Text

if TYPE_CHECKING:  # pragma: no cover
    from mech.icentres.locate import ICentre
    from mech.kinematics.result import Kinematics

__all__ = ["FORMATS", "draw", "save"]

FORMATS = (".svg", ".png")
GAP = 6.0


def draw(
    mech: Mechanism,
    kin: Kinematics,
    *,
    velocity: bool = False,
    acceleration: bool = False,
    icentres: Iterable[ICentre] | None = None,
    units: OutputUnits | None = None,
    curves: Sequence[tuple[str, Sequence[tuple[float, float]], str]] = (),
) -> Figure:
    """The configuration diagram, with the asked polygons beside it and I-centres over it.

    Parameters
    ----------
    mech
        The mechanism.
    kin
        Its solution (:func:`mech.kinematics.solve`) at the level the
        polygons need: ``velocity`` for the velocity polygon, ``acceleration``
        for the acceleration polygon.
    velocity, acceleration
        Add the velocity / acceleration polygon to the right.
    icentres
        I-centres (from :func:`mech.icentres.locate`) to mark on the configuration.
    units
        Units of the polygons' scales and values (default SI: m/s, m/s²).
    curves
        Loci traced on the configuration: ``(label, points, kind)`` with kind
        ``path``, ``fixed centrode`` or ``moving centrode``
        (:mod:`mech.properties.paths`).

    Returns
    -------
    Figure
        Panels side by side under a header naming the mechanism and its state.
    """
    centres = list(icentres) if icentres is not None else []
    panels = [configuration(mech, kin, icentres=centres, curves=curves)]
    if velocity:
        panels.append(polygon_figure(mech, velocity_polygon(mech, kin), units=units))
    if acceleration:
        panels.append(polygon_figure(mech, acceleration_polygon(mech, kin), units=units))
    page = Page()
    page.add(Text((8.0, 6.0), mech.label, 4.0, "start", bold=True, cls="heading"))
    state = _state_line(kin)
    if state:
        page.add(Text((8.0, 11.5), state, 3.0, "start", "#333333", cls="state"))
    x, top = 0.0, 14.0
    for panel in panels:
        page.place(panel, x, top)
        x += panel.width + GAP
    page.width = max(page.width, 8.0 + 3.0 * len(mech.label) + 8)  # the heading must fit
    return page.figure(mech.label)


def _state_line(kin: Kinematics) -> str:
    """ "crank at 60°, 120 rpm cw" for each drive: the instant the drawing shows."""
    parts = []
    for d in getattr(kin, "drives", ()):
        if d.link is not None and d.angle is not None:
            text = f"{d.link} at {math.degrees(d.angle) % 360:.4g}°"
            if d.omega:
                rpm = abs(d.omega) * 60 / (2 * math.pi)
                text += f", {rpm:.4g} rpm {'ccw' if d.omega > 0 else 'cw'}"
            parts.append(text)
        elif d.joint is not None and d.speed is not None:
            parts.append(f"slider {d.joint} at {d.speed:.4g} m/s")
    return "; ".join(parts)


def save(figure: Figure, path: str | Path) -> None:
    """Write a figure as SVG or PNG, chosen by the file's extension.

    Written atomically by :func:`mech._files.writing`: a full disk or a failed
    drawing leaves the previous file whole, a link's target is written, a device is
    written through; a file that cannot be written is an InputError naming it.
    """
    from mech._files import write_file, write_with

    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in (".svg", ".png"):
        raise InputError(
            f"cannot write a drawing as {suffix or 'a file without an extension'}: {path}",
            hint="name the output .svg or .png",
        )
    if suffix == ".svg":
        from mech.draw.svg import to_svg

        write_file(path, to_svg(figure))
    else:
        from mech.draw.raster import to_png

        write_with(path, lambda f: to_png(figure, f))
