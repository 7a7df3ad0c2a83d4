"""Drawings of a cam: its profile to scale, and the follower's s–v–a–j diagrams.

Both are :class:`~mech.draw.scene.Figure` s (page millimetres), written as SVG
by :mod:`mech.draw.svg` like every other drawing of mech.  The profile is drawn
at a round scale ("1 cm = 20 mm", full size when it fits), in the drawn
configuration (the cam turned by its drive angle), with the base circle, the
prime circle and pitch curve of a roller follower, the follower in place and
its line of stroke.  The diagrams plot the lift, velocity, acceleration and
jerk against cam angle on one shared axis, as the textbooks draw them, with the
segments' boundaries marked.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from mech.cam.analysis import CamAnalysis
from mech.cam.profile import evaluate
from mech.draw.scene import PALETTE, Figure, Page, Transform, fmt, nice_scale, scale_bar
from mech.pairs.cam.setup import CamSetup
from mech.shapes import INK, Circle, Line, Poly, Style, Text

__all__ = ["diagram_figure", "profile_figure", "profile_points"]

Vec = tuple[float, float]
CAM = PALETTE[0]
FOLLOWER = PALETTE[1]
THIN = Style(stroke="#777777", width=0.25, dash=(1.5, 1.0))


def _rot(p: np.ndarray, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.stack([c * p[:, 0] - s * p[:, 1], s * p[:, 0] + c * p[:, 1]], axis=-1)


def profile_points(setup: CamSetup, a: CamAnalysis) -> list[Vec]:
    """The cam's profile in the drawn configuration (global coordinates, m), closed, no repeat.

    This is the format's ``curve`` profile: the generated surface fixed in the
    cam link, turned by the drive angle.
    """
    turned = _rot(a.state.profile, a.layout.sense * setup.angle)
    cx, cy = setup.centre
    return [(float(x + cx), float(y + cy)) for x, y in turned]


def profile_figure(setup: CamSetup, a: CamAnalysis, *, title: str = "") -> Figure:
    """The cam to scale, with its follower at the drive angle."""
    lay = a.layout
    prog = lay.program
    pts = np.array(profile_points(setup, a))
    now = evaluate(lay, [setup.angle])
    cx, cy = setup.centre
    point = (float(now.point[0][0] + cx), float(now.point[0][1] + cy))
    contact = (float(now.contact[0][0] + cx), float(now.contact[0][1] + cy))
    reach = prog.base_radius + prog.stroke * (0 if lay.oscillating else 1) + 2 * lay.roller
    page, tf, scale = _profile_sheet(setup, a, pts, point, reach)
    if title:
        page.add(Text((page.width / 2, 6.0), title, size=3.6, bold=True))
    _draw_cam(page, tf, setup, a, pts)
    _draw_follower(page, tf, setup, a, point, contact, reach)
    page.add(Circle(tf(contact), 0.7, Style(stroke=None, fill=FOLLOWER), cls="contact"))
    caption = (
        f"θ = {fmt(math.degrees(setup.angle))}° · base circle {fmt(prog.base_radius * 1000)} mm"
        + (f" · roller {fmt(lay.roller * 1000)} mm" if lay.roller else "")
        + f" · largest pressure angle {fmt(math.degrees(abs(a.pressure.value)), 3)}°"
    )
    page.add(Text((_MARGIN, page.height - 14), caption, size=2.8, anchor="start"))
    page.extend(scale_bar((_MARGIN, page.height - 7), scale * 1000, "mm"))
    return page.figure(title or "cam profile")


_MARGIN = 14.0  # page mm around the drawn cam


def _profile_sheet(
    setup: CamSetup, a: CamAnalysis, pts: np.ndarray, point: Vec, reach: float
) -> tuple[Page, Transform, float]:
    """An empty page sized to the cam, the follower and its reach, with the round scale (m per cm)."""
    lay = a.layout
    cx, cy = setup.centre
    extra: list[Vec] = [point]
    if lay.oscillating and lay.pivot is not None:
        extra.append((lay.pivot[0] + cx, lay.pivot[1] + cy))
    allpts = np.vstack([pts, np.array(extra), np.array([[cx - reach, cy - reach], [cx + reach, cy + reach]])])
    xmin, ymin = allpts.min(axis=0)
    xmax, ymax = allpts.max(axis=0)
    room = 150.0
    extent = max(xmax - xmin, ymax - ymin)
    scale = nice_scale(extent, room)  # m per cm
    drawn = (xmax - xmin) * 10.0 / scale
    width = max(drawn + 2 * _MARGIN, 190.0)
    tf = Transform(scale, (float(xmin), float(ymax)), ((width - drawn) / 2, _MARGIN + 6))
    page = Page()
    page.width, page.height = width, tf.length(ymax - ymin) + 2 * _MARGIN + 18
    return page, tf, scale


def _draw_cam(page: Page, tf: Transform, setup: CamSetup, a: CamAnalysis, pts: np.ndarray) -> None:
    """The base circle, a roller's prime circle and pitch curve, the profile and the cam's centre O."""
    lay = a.layout
    cx, cy = setup.centre
    centre = tf((cx, cy))
    page.add(Circle(centre, tf.length(lay.program.base_radius), THIN, cls="base-circle"))
    if lay.roller:
        page.add(
            Circle(
                centre,
                tf.length(lay.prime_radius),
                Style(stroke="#aaaaaa", width=0.2, dash=(0.6, 0.8)),
                cls="prime-circle",
            )
        )
        pitch = _rot(a.state.pitch, lay.sense * setup.angle) + np.array([cx, cy])
        page.add(
            Poly(
                tuple(tf((float(x), float(y))) for x, y in pitch),
                style=Style(stroke="#888888", width=0.25, dash=(2.0, 1.0)),
                cls="pitch-curve",
            )
        )
    page.add(
        Poly(
            tuple(tf((float(x), float(y))) for x, y in pts),
            style=Style(stroke=CAM, width=0.5, fill=CAM, fill_opacity=0.12),
            cls="cam-profile",
            name=setup.cam,
        )
    )
    page.add(Circle(centre, 1.0, Style(stroke=INK, fill="white"), cls="cam-centre"))
    page.add(Text((centre[0] - 1.6, centre[1] + 2.8), "O", size=2.8, anchor="end"))


def _draw_follower(
    page: Page, tf: Transform, setup: CamSetup, a: CamAnalysis, point: Vec, contact: Vec, reach: float
) -> None:
    """The follower at the drive angle: its arm and pivot or its stem and line of stroke, its roller or face."""
    lay = a.layout
    prog = lay.program
    cx, cy = setup.centre
    fstyle = Style(stroke=FOLLOWER, width=0.5)
    if lay.oscillating:
        assert lay.pivot is not None
        pv = tf((lay.pivot[0] + cx, lay.pivot[1] + cy))
        page.add(Circle(pv, 1.0, Style(stroke=INK, fill="white"), cls="follower-pivot"))
        if prog.follower != "flat":
            page.add(Line(pv, tf(point), fstyle, cls="follower", name=setup.follower))
    else:
        u = (math.cos(lay.axis), math.sin(lay.axis))
        top = (point[0] + u[0] * 0.6 * reach, point[1] + u[1] * 0.6 * reach)
        page.add(Line(tf(point), tf(top), fstyle, cls="follower", name=setup.follower))
        back = (point[0] - u[0] * 1.2 * reach, point[1] - u[1] * 1.2 * reach)
        page.add(Line(tf(back), tf(top), THIN, cls="line-of-stroke"))
    if prog.follower == "roller":
        page.add(
            Circle(
                tf(point),
                tf.length(lay.roller),
                Style(stroke=FOLLOWER, width=0.45, fill="white"),
                cls="roller",
            )
        )
    elif prog.follower == "flat":
        a0, a1 = _flat_face(setup, a, point, contact, reach)
        page.add(Line(tf(a0), tf(a1), Style(stroke=FOLLOWER, width=0.6), cls="flat-face"))


def _flat_face(setup: CamSetup, a: CamAnalysis, point: Vec, contact: Vec, reach: float) -> tuple[Vec, Vec]:
    """A flat face's ends: along the contact's line, a little beyond the contact either way."""
    lay = a.layout
    if lay.oscillating:
        assert lay.pivot is not None
        cx, cy = setup.centre
        pv_w = (lay.pivot[0] + cx, lay.pivot[1] + cy)
        d = (contact[0] - pv_w[0], contact[1] - pv_w[1])
        length = math.hypot(*d) or 1.0
        dirn = (d[0] / length, d[1] / length)
        return pv_w, (contact[0] + dirn[0] * 0.2 * reach, contact[1] + dirn[1] * 0.2 * reach)
    t = (-math.sin(lay.axis), math.cos(lay.axis))
    half = max(abs(a.face[0]), abs(a.face[1])) * 1.2 if a.face else 0.3 * reach
    return (point[0] - t[0] * half, point[1] - t[1] * half), (point[0] + t[0] * half, point[1] + t[1] * half)


def diagram_figure(a: CamAnalysis, *, title: str = "", jerk: bool = True) -> Figure:
    """The s, v, a (and j) diagrams against cam angle, one panel each, shared θ axis."""
    st = a.state
    theta = np.degrees(st.theta)
    ang = a.follower_angular
    w = a.omega
    panels: list[tuple[str, str, np.ndarray]] = [
        ("s", "°" if ang else "mm", np.degrees(st.s) if ang else st.s * 1000)
    ]
    u = "rad" if ang else "m"
    if w is not None:
        panels.append(("v", f"{u}/s", st.ds * w))
        panels.append(("a", f"{u}/s²", st.d2s * w**2))
        if jerk:
            panels.append(("j", f"{u}/s³", st.d3s * w**3))
    else:
        panels.append(("ds/dθ", f"{'rad' if ang else 'mm'}/rad", st.ds * (1 if ang else 1000)))
        panels.append(("d²s/dθ²", f"{'rad' if ang else 'mm'}/rad²", st.d2s * (1 if ang else 1000)))
    left, right, top = 26.0, 8.0, 12.0
    pw, ph, gap = 150.0, 38.0, 9.0
    page = Page()
    page.width = left + pw + right
    page.height = top + len(panels) * (ph + gap) + 10
    if title:
        page.add(Text((page.width / 2, 5.0), title, size=3.4, bold=True))
    starts = [math.degrees(s) for s in a.layout.program.starts]
    x_of = lambda t: left + pw * t / 360.0  # noqa: E731
    for k, (label, unit, values) in enumerate(panels):
        y0 = top + k * (ph + gap)
        finite = values[np.isfinite(values)]
        lo, hi = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
        lo, hi = min(lo, 0.0), max(hi, 0.0)
        if hi - lo <= 0:
            hi = lo + 1.0
        y_of = lambda v, y0=y0, lo=lo, hi=hi: y0 + ph - (v - lo) / (hi - lo) * ph  # noqa: E731
        colour = PALETTE[k % len(PALETTE)]
        page.add(
            Poly(
                ((left, y0), (left + pw, y0), (left + pw, y0 + ph), (left, y0 + ph)),
                style=Style(stroke="#bbbbbb", width=0.2),
            )
        )
        page.add(Line((left, y_of(0.0)), (left + pw, y_of(0.0)), Style(stroke="#999999", width=0.2)))
        for s in starts[1:]:
            page.add(
                Line((x_of(s), y0), (x_of(s), y0 + ph), Style(stroke="#cccccc", width=0.2, dash=(1.0, 1.0)))
            )
        # broken where a derivative may jump: at each segment's start and at a law's own knot
        pts = _broken(theta, values, x_of, y_of, a.layout.program.breaks)
        for run in pts:
            page.add(
                Poly(
                    tuple(run),
                    closed=False,
                    style=Style(stroke=colour, width=0.45),
                    cls="diagram",
                    name=label,
                )
            )
        page.add(Text((left - 2, y0 + 3), f"{fmt(hi, 3)}", size=2.4, anchor="end"))
        page.add(Text((left - 2, y0 + ph - 1), f"{fmt(lo, 3)}", size=2.4, anchor="end"))
        page.add(Text((4, y0 + ph / 2), f"{label} ({unit})", size=2.8, anchor="start", colour=colour))
    ybase = top + len(panels) * (ph + gap) - gap + 4
    for t in range(0, 361, 60):
        page.add(Text((x_of(t), ybase), f"{t}", size=2.4))
    page.add(Text((left + pw / 2, ybase + 5), "cam angle θ (°)", size=2.8))
    return page.figure(title or "s–v–a diagrams")


def _broken(
    theta: np.ndarray, values: np.ndarray, x_of: object, y_of: object, starts: Sequence[float]
) -> list[list[Vec]]:
    """Polyline runs, broken where a value jumps at ``starts`` (the programme's breaks): a jump is drawn as a jump."""
    assert callable(x_of) and callable(y_of)
    finite = values[np.isfinite(values)]
    span = float(finite.max() - finite.min()) if finite.size else 0.0
    # the sample at a break may hold either side's value (a segment's start the later one's, a
    # parabolic law's knot the earlier one's): a jump just before or just after it is cut
    cuts = {
        int(np.searchsorted(theta, math.degrees(s), side=side)) for s in starts for side in ("left", "right")
    }
    runs: list[list[Vec]] = [[]]
    for i, (t, v) in enumerate(zip(theta, values, strict=True)):
        if i in cuts and runs[-1] and abs(float(v) - float(values[i - 1])) > 0.02 * span:
            runs.append([])
        runs[-1].append((x_of(float(t)), y_of(float(v))))
    if abs(float(values[0]) - float(values[-1])) <= 0.02 * span:
        runs[-1].append((x_of(360.0), y_of(float(values[0]))))
    return [r for r in runs if len(r) > 1]
