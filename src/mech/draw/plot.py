"""Sweep plots and animations (matplotlib, the optional ``plot`` extra).

The sweep itself (solving at every crank angle) is not done here: these
functions take arrays — crank angles, the quantities against them, the dead
centres and frames of positions — so that they can be tested on synthetic
data and reused by any command that produces a sweep.

Output is deterministic for given data: Agg backend, fixed DPI, DejaVu Sans,
no PNG metadata; GIF frames are painted by the same figure code as the
configuration diagram (:mod:`mech.draw.config`), so an animation looks like
the still drawing.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from mech._files import write_with
from mech._records import dataclass
from mech.draw.raster import DPI, use_matplotlib

if TYPE_CHECKING:  # pragma: no cover
    from mech.kinematics.result import Kinematics
    from mech.model import Mechanism

__all__ = ["Series", "animate", "extremes", "sweep_figure", "sweep_plot", "thin"]

Vec = tuple[float, float]


@dataclass(frozen=True, slots=True)
class Series:
    """One quantity against crank angle: ``label`` (``v_C``), ``unit`` (``m/s``), ``values``.

    NaN marks an angle where the quantity is undefined (a toggle): the line is
    broken there rather than joined across.
    """

    label: str
    unit: str
    values: Sequence[float]
    #: The extremes refined between steps, ((angle, largest), (angle, smallest)), when the sweep
    #: found them: what the plot labels (the grid's own extremes are only near them).
    refined: tuple[tuple[float, float], tuple[float, float]] | None = None


def extremes(
    angles: Sequence[float], values: Sequence[float]
) -> tuple[tuple[float, float], tuple[float, float]]:
    """((angle, value) of the maximum, (angle, value) of the minimum), ignoring NaN."""
    pairs = [(a, v) for a, v in zip(angles, values, strict=True) if not math.isnan(v)]
    if not pairs:
        raise ValueError("no finite values to find extremes of")
    hi = max(pairs, key=lambda p: p[1])
    lo = min(pairs, key=lambda p: p[1])
    return hi, lo


def sweep_plot(
    path: str | Path,
    angles: Sequence[float],
    series: Sequence[Series],
    *,
    dead_centres: Sequence[float] = (),
    mark_extremes: bool = True,
    title: str = "",
    xlabel: str = "crank angle θ (°)",
) -> None:
    """Plot quantities against crank angle (degrees) into a PNG, one panel per unit.

    Series sharing a unit share a panel (v_B and v_C together, ω's apart).
    Dead centres are dashed vertical lines labelled "dead centre"; the largest
    and smallest value of each series is marked and annotated with its angle
    (the refined extremes where the series carries them), inside the axes.
    """
    fig = sweep_figure(
        angles, series, dead_centres=dead_centres, mark_extremes=mark_extremes, title=title, xlabel=xlabel
    )
    write_with(
        path, lambda f: fig.savefig(f, format="png", dpi=DPI, facecolor="white", metadata={"Software": None})
    )


def sweep_figure(
    angles: Sequence[float],
    series: Sequence[Series],
    *,
    dead_centres: Sequence[float] = (),
    mark_extremes: bool = True,
    title: str = "",
    xlabel: str = "crank angle θ (°)",
) -> Any:
    """The matplotlib figure :func:`sweep_plot` writes (for tests, and for a caller's own use)."""
    use_matplotlib()
    from matplotlib.figure import Figure as MplFigure

    groups: dict[str, list[Series]] = {}
    for s in series:
        if len(s.values) != len(angles):
            raise ValueError(f"{s.label}: {len(s.values)} values for {len(angles)} angles")
        groups.setdefault(s.unit, []).append(s)
    n = max(len(groups), 1)
    fig = MplFigure(figsize=(7.0, 2.4 * n + 0.6), dpi=DPI)
    axes = fig.subplots(n, 1, sharex=True, squeeze=False)[:, 0]
    colours = ("#1f4e9c", "#b8461b", "#2e7d32", "#7b3f98", "#a0761a", "#00838f")
    for ax, (unit, members) in zip(axes, groups.items(), strict=False):
        for k, s in enumerate(members):
            colour = colours[k % len(colours)]
            ax.plot(angles, s.values, color=colour, lw=1.4, label=s.label)
            if mark_extremes:
                _mark_extremes(ax, angles, s, colour)
        for d in dead_centres:
            ax.axvline(d, color="#777777", lw=0.8, ls="--")
        ax.margins(y=0.22)  # room inside the axes for the extremes' labels
        ax.set_ylabel(unit)
        ax.grid(True, color="#dddddd", lw=0.5)
        ax.axhline(0, color="#999999", lw=0.6)
        ax.legend(loc="upper right", fontsize=8, frameon=False)
    if dead_centres:
        top = axes[0]
        for d in dead_centres:
            top.annotate(
                "dead centre",
                (d, 1.0),
                xycoords=("data", "axes fraction"),
                xytext=(2, -10),
                textcoords="offset points",
                fontsize=7,
                color="#555555",
                rotation=90,
                va="top",
            )
    lo, hi = min(angles), max(angles)
    axes[-1].set_xlim(lo, hi)
    if hi - lo >= 180:
        axes[-1].set_xticks([lo + 30 * k for k in range(int((hi - lo) // 30) + 1)])
    axes[-1].set_xlabel(xlabel)
    if title:
        fig.suptitle(title, fontsize=10, fontweight="bold")
    fig.tight_layout()
    return fig


def _mark_extremes(ax: Any, angles: Sequence[float], s: Series, colour: str) -> None:
    """Dots at the largest and smallest values, labelled inside the axes with value and angle.

    The refined extremes where the sweep found them (the table's numbers), else the grid's.
    A label leans away from the nearer side of the axes and away from the curve's extreme
    (below a maximum, above a minimum), so it stays inside.
    """
    from mech.draw.scene import fmt

    (ah, vh), (al, vl) = s.refined if s.refined is not None else extremes(angles, s.values)
    lo, hi = min(angles), max(angles)
    for a, v, word, up in ((ah, vh, "max", False), (al, vl, "min", True)):
        ax.plot([a], [v], marker="o", ms=4, color=colour)
        right = a > lo + 0.6 * (hi - lo)
        where = f"{a:.2f}".rstrip("0").rstrip(".") if s.refined is not None else f"{a:.0f}"
        ax.annotate(
            f"{word} {fmt(v)} at {where}°",
            (a, v),
            textcoords="offset points",
            xytext=(-4 if right else 4, 5 if up else -5),
            ha="right" if right else "left",
            va="bottom" if up else "top",
            fontsize=7,
            color=colour,
            annotation_clip=True,
        )


def thin(points: Sequence[Vec], resolution: float) -> list[Vec]:
    """``points`` without those closer than ``resolution`` to the last one kept.

    A traced path of 10,000 steps has far more points than a frame has pixels along it; each
    one would be drawn, and measured against by every label of every frame.  A point is kept
    when it is at least ``resolution`` from the point kept before it, and always at either
    end of a run (a NaN breaks a run and is kept): a path already as coarse as the
    resolution is returned unchanged.
    """
    out: list[Vec] = []
    last: Vec | None = None
    for i, p in enumerate(points):
        if not (math.isfinite(p[0]) and math.isfinite(p[1])):
            out.append(p)
            last = None
            continue
        end = i + 1 == len(points) or not (
            math.isfinite(points[i + 1][0]) and math.isfinite(points[i + 1][1])
        )
        if last is None or end or math.dist(p, last) >= resolution:
            out.append(p)
            last = p
    return out


def animate(
    path: str | Path,
    mech: Mechanism,
    kin: Kinematics,
    frames: Sequence[Mapping[str, Vec]],
    *,
    fps: int = 24,
    dpi: int = 100,
    curves: Sequence[tuple[str, Sequence[Vec], str]] = (),
) -> None:
    """An animated GIF of the mechanism over a cycle, one frame per set of positions.

    ``curves`` (label, points, kind) are traced in every frame (a coupler
    point's path: the point runs along it), thinned to a frame's pixel (:func:`thin`).

    ``kin`` is one solve of the mechanism (it tells which points each link
    carries and how the guides lie); ``frames`` are the positions at each
    step of the sweep.  All frames share one window and scale, fitted to every
    frame, so the mechanism moves and the paper does not.
    """
    use_matplotlib()
    from PIL import Image

    from mech.draw.config import configuration, fit_view
    from mech.draw.raster import render_rgb

    if not frames:
        raise ValueError("no frames to animate")
    view = fit_view([p for frame in frames for p in frame.values()])
    pixel = 25.4 / dpi * view.scale / 10  # one pixel of a frame, in metres (scale: m per cm)
    curves = [(label, thin(points, pixel), kind) for label, points, kind in curves]
    images = []
    for frame in frames:
        fig = configuration(
            mech, kin, positions=frame, view=view, title=getattr(mech, "label", ""), curves=curves
        )
        images.append(Image.fromarray(render_rgb(fig, dpi=dpi)).convert("P", palette=Image.Palette.ADAPTIVE))
    write_with(
        path,
        lambda f: images[0].save(
            f,
            format="GIF",
            save_all=True,
            append_images=images[1:],
            duration=round(1000 / fps),
            loop=0,
            optimize=False,
            disposal=2,
        ),
    )
