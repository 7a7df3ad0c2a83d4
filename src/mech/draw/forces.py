"""Forces drawn: the force vectors on the configuration, a link's free-body diagram, the
turning-moment diagram.

The configuration is :mod:`mech.draw.config`'s own drawing, at a view widened
to hold the arrows; the forces go on top of it from here, lettered as a
textbook letters them (F₂₃ the force on link 3 from link 2, W₃ link 3's weight,
T the input torque), each arrow's tail at the point the force acts on, at one
round force scale stated under the drawing ("forces: 1 cm = 2000 N").  Inertia
forces (d'Alembert's −m a_G) are dashed, so that a reader sees at once which
forces are real.

A free-body diagram (:func:`free_body_panel`) cuts one link free: its outline
through its points, every pair's force on it, its loads, its weight, the input
torque where it is the driven link, and dashed its inertia force at G and
inertia couple; the numbers are :mod:`mech.forces.freebody`'s, so the diagram
agrees with ``mech forces --explain``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from mech.draw.config import MARGIN, TITLE_AT, configuration, fit_view, link_colours
from mech.draw.scene import Figure, Page, Transform, arrow, nice_scale
from mech.draw.scene import place_label as _place
from mech.shapes import INK, Circle, Item, Line, Poly, Style, Text

if TYPE_CHECKING:  # pragma: no cover
    from mech.forces.cycle import ForceCycle
    from mech.forces.freebody import FreeBody
    from mech.forces.result import ForceAnalysis
    from mech.model import Mechanism

__all__ = ["ARROW", "forces_drawing", "free_body_panel", "turning_moment_plot"]

Vec = tuple[float, float]

#: Length (mm) of the largest force's arrow on paper; the force scale is rounded from it.
ARROW = 24.0
_FORCE = "#b8001f"
_INERTIA = "#6a1b9a"
_GAP = 6.0


def _scale(forces: Sequence[float]) -> float:
    """Newtons per cm of paper: a round number that draws the largest force about :data:`ARROW` long."""
    largest = max((f for f in forces if math.isfinite(f)), default=0.0)
    return nice_scale(largest, ARROW) if largest > 0 else 1.0


def _tip(tr: Transform, at: Vec, force: Vec, per_cm: float) -> tuple[Vec, Vec]:
    """Page points of an arrow for ``force`` with its tail at the world point ``at``."""
    p0 = tr(at)
    k = 10.0 / per_cm
    return p0, (p0[0] + force[0] * k, p0[1] - force[1] * k)


_SUBS = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def _couple(
    centre: Vec,
    value: float,
    label: str,
    colour: str,
    drawn: Sequence[Item],
    *,
    r: float = 7.5,
    dash: tuple[float, ...] = (),
) -> list[Item]:
    """A curved arrow round ``centre`` (page mm) in the couple's sense, its label placed clear."""
    sweep = math.radians(240) * (-1 if value > 0 else 1)  # ccw in the world turns the other way on the page
    a0 = math.radians(-30) - sweep / 2
    pts = [
        (centre[0] + r * math.cos(a0 + sweep * t / 16), centre[1] + r * math.sin(a0 + sweep * t / 16))
        for t in range(17)
    ]
    items: list[Item] = [Poly(tuple(pts[:-1]), False, Style(colour, 0.35, dash=dash), "couple", label)]
    items.extend(arrow(pts[-3], pts[-1], colour, 0.35, cls="couple", name=label, head=1.9))
    items.append(
        _place(
            pts[8],
            label,
            2.8,
            (pts[8][0] - centre[0], pts[8][1] - centre[1]),
            [*drawn, *items],
            colour=colour,
            italic=True,
            cls="couple",
        )
    )
    return items


def _names(mech: Mechanism) -> dict[str, int]:
    from mech.forces.freebody import numbers

    return numbers(mech)


def _pair_label(by: int, on: int) -> str:
    from mech.forces.freebody import subscript

    return subscript(f"F{by}{on}" if max(by, on) < 10 else f"F{by},{on}")


def _inertia_label(n: int) -> str:
    return f"−m{n}a_G{n}".translate(_SUBS)


def forces_drawing(mech: Mechanism, fa: ForceAnalysis, *, free_body: Sequence[str] = ()) -> Figure:
    """The configuration with every pair force, load, weight and inertia force drawn on it and the
    input torque round its pivot, and the free bodies of the links named in ``free_body`` beside it."""
    from mech.forces.freebody import free_body as cut

    kin = fa.kinematics
    panels = [_configuration_panel(mech, fa)]
    for link in free_body:
        panels.append(free_body_panel(mech, cut(mech, kin, fa, link)))
    page = Page()
    page.add(Text((8.0, 6.0), mech.label, 4.0, "start", bold=True, cls="heading"))
    # the drive's angle as mech forces and mech velocity state it (−60° for a cw cam, not 300°)
    state = "forces at the drive's angle" + (
        f" {math.degrees(fa.drive_angle):.4g}°" if fa.drive_angle is not None else ""
    )
    if fa.effort is not None:
        unit = "N·m" if fa.effort.kind == "torque" else "N"
        state += f"; input {fa.effort.kind} {fa.effort.value:.5g} {unit} (ccw +)"
    if fa.note:
        state += "; the pairs' forces are indeterminate"
    page.add(Text((8.0, 11.5), state, 3.0, "start", "#333333", cls="state"))
    x = 0.0
    for panel in panels:
        page.place(panel, x, 14.0)
        x += panel.width + _GAP
    page.width = max(page.width, 8.0 + 3.0 * len(mech.label) + 8)
    return page.figure(mech.label)


def _configuration_panel(mech: Mechanism, fa: ForceAnalysis) -> Figure:
    """The configuration diagram with the forces on it, at a view that holds the arrows."""
    kin, num = fa.kinematics, _names(mech)
    pos = dict(kin.positions)
    arrows = [(p.at, p.force, _pair_label(num[p.by], num[p.on]), False) for p in fa.pairs if p.at is not None]
    for r in fa.inertia:
        if r.force[0] or r.force[1]:
            arrows.append((r.centre, r.force, _inertia_label(num[r.link]), True))
    arrows += _load_arrows(mech, fa)
    per_cm = _scale([math.hypot(*f) for _, f, _, _ in arrows])
    view = fit_view(list(pos.values()))
    for _ in range(2):  # the view, widened to hold the arrows at the force scale
        k = view.scale / per_cm
        tips = [(a[0] + f[0] * k, a[1] + f[1] * k) for a, f, _, _ in arrows]
        view = fit_view(list(pos.values()) + tips, (130.0, 95.0))
    fig = configuration(mech, kin, view=view, title="Forces on the configuration")
    page = Page(fig.width, fig.height + 6.0, list(fig.items))
    tr = _as_drawn(fig, view.transform())
    drawn: list[Item] = list(fig.items)
    for at, f, label, dashed in arrows:
        colour = _INERTIA if dashed else _FORCE
        p0, p1 = _tip(tr, at, f, per_cm)
        items = arrow(p0, p1, colour, 0.45, cls="force", name=label, dash=(1.2, 0.8) if dashed else ())
        lab = _place(
            p1,
            label,
            2.9,
            (p1[0] - p0[0], p1[1] - p0[1]),
            drawn + items,
            colour=colour,
            italic=True,
            cls="force",
        )
        page.extend([*items, lab])
        drawn.extend([*items, lab])
    e = fa.effort
    if e is not None and e.kind == "torque" and e.value and math.isfinite(e.value):
        page.extend(_couple(tr(fa.about), e.value, f"T = {abs(e.value):.4g} N·m", _FORCE, drawn, r=10.0))
    page.add(
        Text((MARGIN - 6, fig.height + 1.5), f"forces: 1 cm = {per_cm:g} N", 2.8, "start", INK, cls="scale")
    )
    return page.figure("Forces on the configuration")


def _as_drawn(fig: Figure, tr: Transform) -> Transform:
    """``tr`` moved as the drawing was: a sheet grows (its items moved) so that a pitch circle or a
    cam's profile past the view's edge is not cut, and the arrows must go where the pins went."""
    title = next((i for i in fig.items if isinstance(i, Text) and i.cls == "title"), None)
    if title is None:
        return tr
    dx, dy = title.at[0] - TITLE_AT[0], title.at[1] - TITLE_AT[1]
    return Transform(tr.scale, tr.world, (tr.origin[0] + dx, tr.origin[1] + dy))


def _load_arrows(mech: Mechanism, fa: ForceAnalysis) -> list[tuple[Vec, Vec, str, bool]]:
    """The file's force loads and the weights, as arrows."""
    import numpy as np

    from mech.forces.core import load_value
    from mech.forces.freebody import subscript

    kin, num = fa.kinematics, _names(mech)
    out: list[tuple[Vec, Vec, str, bool]] = []
    for load in mech.loads:
        if load.is_force and load.target in kin.positions:
            v = load_value(load, np.array([fa.drive_angle or 0.0]))
            out.append(
                (
                    tuple(kin.positions[load.target]),
                    (float(v[0, 0]), float(v[0, 1])),
                    f"P at {load.target}",
                    False,
                )
            )
    for r in fa.inertia:
        if r.weight[0] or r.weight[1]:
            out.append((r.centre, r.weight, subscript(f"W{num[r.link]}"), False))
    return out


def free_body_panel(mech: Mechanism, body: FreeBody) -> Figure:
    """One link's free-body diagram: its outline, its actions, its inertia force and couple dashed,
    and under it each force's value (its label on the drawing is the textbook's name alone)."""
    from mech.forces.freebody import subscript

    forces = [a for a in body.actions if a.force is not None and a.at is not None]
    inertia: list[tuple[Vec, Vec, str]] = []
    if body.mass > 0 and (body.m_a[0] or body.m_a[1]):
        inertia.append((body.about_at, (-body.m_a[0], -body.m_a[1]), _inertia_label(body.number)))
    sizes = [math.hypot(*a.force) for a in forces if a.force is not None] + [
        math.hypot(*f) for _, f, _ in inertia
    ]
    per_cm = _scale(sizes)
    outline = _outline(body)
    view = fit_view(outline)
    for _ in range(2):
        k = view.scale / per_cm
        tips = [(a.at[0] + a.force[0] * k, a.at[1] + a.force[1] * k) for a in forces if a.at and a.force]
        tips += [(at[0] + f[0] * k, at[1] + f[1] * k) for at, f, _ in inertia]
        view = fit_view(outline + tips, (90.0, 80.0))
    tr = view.transform()
    width, height = view.size
    legend = _legend(body)
    page = Page(max(width, 60.0), height + 4.2 * len(legend))
    title = f"Free body of link {body.number} ({body.link})"
    page.add(Text(TITLE_AT, title, 3.4, "start", bold=True, cls="title"))
    page.extend(_outline_items(outline, tr, link_colours(mech).get(body.link, INK)))
    drawn: list[Item] = list(page.items)
    for a in forces:
        drawn += _force_items(page, tr, a.at, a.force, subscript(a.label), per_cm, _FORCE, drawn)  # type: ignore[arg-type]
    for at, f, label in inertia:
        drawn += _force_items(page, tr, at, f, label, per_cm, _INERTIA, drawn, dashed=True)
    centre, r = tr(body.about_at), 7.0
    for a in body.actions:
        if a.force is None:
            items = _couple(centre, a.couple, subscript(a.label), _FORCE, drawn, r=r)
            page.extend(items)
            drawn += items
            r += 3.5
    if body.mass > 0 and body.i_alpha:
        label = f"−I_G{body.number}α{body.number}".translate(_SUBS)
        page.extend(_couple(centre, -body.i_alpha, label, _INERTIA, drawn, r=r, dash=(1.2, 0.8)))
    page.add(Circle(centre, 0.9, Style(INK, 0.3, fill=INK), "centre", body.about))
    y = height - 4.0
    for line in [f"forces: 1 cm = {per_cm:g} N", *legend]:
        page.add(
            Text(
                (MARGIN - 6, y),
                line,
                2.7,
                "start",
                INK,
                cls="scale" if line.startswith("forces") else "legend",
            )
        )
        y += 4.2
    return page.figure(title)


def _legend(body: FreeBody) -> list[str]:
    """Each action's value, for the lines under a free-body diagram."""
    from mech.forces.freebody import subscript

    lines = []
    for a in body.actions:
        if a.force is None:
            lines.append(f"{subscript(a.label)} = {a.couple:.5g} N·m (ccw +): {a.what}")
        else:
            ang = math.degrees(math.atan2(a.force[1], a.force[0])) % 360
            lines.append(f"{subscript(a.label)} = {math.hypot(*a.force):.5g} N at {ang:.4g}°: {a.what}")
    if body.mass > 0:
        n = body.number
        lines.append(
            f"{_inertia_label(n)} = {math.hypot(*body.m_a):.5g} N, "
            + f"−I_G{n}α{n}".translate(_SUBS)
            + f" = {-body.i_alpha:.5g} N·m (inertia, dashed)"
        )
    return lines


def _outline(body: FreeBody) -> list[Vec]:
    """The link's points: where its actions act and its reference point."""
    pts: list[Vec] = []
    for a in body.actions:
        if a.at is not None and all(math.dist(a.at, q) > 1e-12 for q in pts):
            pts.append(a.at)
    if all(math.dist(body.about_at, q) > 1e-12 for q in pts):
        pts.append(body.about_at)
    return pts


def _outline_items(points: list[Vec], tr: Transform, colour: str) -> list[Item]:
    """A bar between two points, a plate round more (their hull), a pin circle at each."""
    page_pts = [tr(p) for p in points]
    items: list[Item] = []
    if len(page_pts) == 2:
        items.append(Line(page_pts[0], page_pts[1], Style(colour, 1.4), "link"))
    elif len(page_pts) > 2:
        c = (sum(p[0] for p in page_pts) / len(page_pts), sum(p[1] for p in page_pts) / len(page_pts))
        ring = sorted(page_pts, key=lambda p: math.atan2(p[1] - c[1], p[0] - c[0]))
        items.append(Poly(tuple(ring), True, Style(colour, 0.8, fill=colour, fill_opacity=0.12), "link"))
    items.extend(Circle(p, 1.2, Style(INK, 0.3, fill="#ffffff"), "pin") for p in page_pts)
    return items


def _force_items(
    page: Page,
    tr: Transform,
    at: Vec,
    force: Vec,
    label: str,
    per_cm: float,
    colour: str,
    drawn: list[Item],
    *,
    dashed: bool = False,
) -> list[Item]:
    """A force's arrow, its tail at the point it acts on, and its name placed clear."""
    p0, p1 = _tip(tr, at, force, per_cm)
    items: list[Item] = list(
        arrow(p0, p1, colour, 0.45, cls="force", name=label, dash=(1.2, 0.8) if dashed else ())
    )
    items.append(
        _place(
            p1,
            label,
            2.8,
            (p1[0] - p0[0], p1[1] - p0[1]),
            drawn + items,
            colour=colour,
            italic=True,
            cls="force",
        )
    )
    page.extend(items)
    return items


def turning_moment_plot(path: str | Path, cycle: ForceCycle) -> None:
    """The turning-moment diagram as a PNG: the input effort against the drive's angle with its
    mean, the flywheel's energy with its greatest and least, and every pair force's magnitude."""
    from mech.draw.raster import DPI, use_matplotlib

    use_matplotlib()
    from matplotlib.figure import Figure as MplFigure

    s = cycle.series
    deg = cycle.kind == "torque"
    x = [math.degrees(a) if deg else a for a in s.angles.tolist()]
    conv = math.degrees if deg else (lambda a: a)
    fig = MplFigure(figsize=(7.0, 7.4), dpi=DPI)
    ax1, ax2, ax3 = fig.subplots(3, 1, sharex=True)
    unit = "N·m" if deg else "N"
    ax1.plot(
        x, s.effort.tolist(), color="#1f4e9c", lw=1.4, label="input torque T" if deg else "input force F"
    )
    if cycle.mean is not None:
        ax1.axhline(cycle.mean, color="#b8461b", lw=1.0, ls="--", label=f"mean {cycle.mean:.4g} {unit}")
        ax1.fill_between(x, s.effort.tolist(), cycle.mean, color="#1f4e9c", alpha=0.12)
    ax1.set_ylabel(unit)
    ax1.legend(loc="upper right", fontsize=8, frameon=False)
    ax2.plot(x, cycle.energy.tolist(), color="#2e7d32", lw=1.4, label="E = ∫(T_mean − T) dθ")
    for point, word in ((cycle.greatest, "greatest"), (cycle.least, "least")):
        if point is not None:
            ax2.plot([conv(point[0])], [point[1]], marker="o", ms=4, color="#2e7d32")
            ax2.annotate(
                f"{word} at {conv(point[0]):.1f}°" if deg else word,
                (conv(point[0]), point[1]),
                textcoords="offset points",
                xytext=(4, 4),
                fontsize=7,
                color="#2e7d32",
            )
    title = "energy (J)" if cycle.fluctuation is None else f"energy (J): ΔE = {cycle.fluctuation:.4g} J"
    ax2.set_ylabel("J")
    ax2.legend(loc="upper right", fontsize=8, frameon=False, title=title, title_fontsize=8)
    from mech.forces.cycle import pair_quantity

    for i, pair in enumerate(s.pairs):
        ax3.plot(x, s.magnitude(i).tolist(), lw=1.0, label=pair_quantity(pair, s.pairs))
    ax3.set_ylabel("N")
    if s.pairs:
        ax3.legend(loc="upper right", fontsize=7, frameon=False, ncol=2)
    for ax in (ax1, ax2, ax3):
        ax.grid(True, color="#dddddd", lw=0.5)
        ax.axhline(0, color="#999999", lw=0.6)
    ax3.set_xlabel("crank angle θ (°)" if deg else "position (m)")
    ax3.set_xlim(min(x), max(x))
    if deg and max(x) - min(x) >= 180:
        ax3.set_xticks([min(x) + 90 * k for k in range(int((max(x) - min(x)) // 90) + 1)])
    fig.suptitle(f"{cycle.mechanism}: turning-moment diagram", fontsize=10, fontweight="bold")
    fig.tight_layout()
    fig.savefig(str(path), format="png", dpi=DPI, facecolor="white", metadata={"Software": None})
