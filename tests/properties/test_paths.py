"""Coupler curves and centrodes (mech.properties.paths; mech sweep --path, mech draw --path/--centrodes).

References are built here from the geometry alone: the four-bar's positions by circle
intersection, the coupler's I-centre I13 as the meeting point of the lines AB and DC (Kennedy:
I13 lies on I12–I23 and on I14–I34).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mech.loader import loads
from mech.properties.paths import centrodes, point_path
from oracles.lines import meet

D, A, B, C = 0.15, 0.04, 0.15, 0.08  # Khurmi Ex. 7.1, m
U, V = 0.06, 0.03  # coupler point E: 60 mm along BC and 30 mm to its left

TEXT = """
units: {length: mm, angle: deg}
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [160, 80]}
  D: {type: revolute, links: [rocker, frame], at: [150, 0]}
lengths: {AB: 40, BC: 150, CD: 80}
points:
  E: {link: coupler, from: B, toward: C, offset: [60, 30]}
drive: {link: crank, angle: 60, rpm: 120, direction: cw}
"""


def closed_form(theta: float) -> dict[str, tuple[float, float]]:
    """B, C (C above the line BD, as drawn) and E by circle intersection."""
    b = (A * math.cos(theta), A * math.sin(theta))
    dx, dy = D - b[0], -b[1]
    s = math.hypot(dx, dy)
    along = (B * B - C * C + s * s) / (2 * s)
    h = math.sqrt(B * B - along * along)
    c = (b[0] + along * dx / s - h * dy / s, b[1] + along * dy / s + h * dx / s)
    ux, uy = (c[0] - b[0]) / B, (c[1] - b[1]) / B
    e = (b[0] + U * ux - V * uy, b[1] + U * uy + V * ux)
    return {"B": b, "C": c, "E": e}


def test_coupler_curve_is_the_closed_form_position_at_every_step():
    path = point_path(loads(TEXT), "E", steps=72)
    for theta, (x, y) in zip(path.angles, path.xy, strict=True):
        ex, ey = closed_form(float(theta))["E"]
        assert (x, y) == (pytest.approx(ex, abs=1e-12), pytest.approx(ey, abs=1e-12))


def test_coupler_curve_extent_bounds_a_dense_sample_and_is_reached():
    path = point_path(loads(TEXT), "E", steps=36)  # a coarse sweep: the extent is refined between steps
    dense = np.array([closed_form(t)["E"] for t in np.linspace(0, 2 * math.pi, 200_001)])
    xmin, xmax, ymin, ymax = path.extent
    assert xmax == pytest.approx(dense[:, 0].max(), abs=1e-9) and xmax >= dense[:, 0].max() - 1e-15
    assert xmin == pytest.approx(dense[:, 0].min(), abs=1e-9) and xmin <= dense[:, 0].min() + 1e-15
    assert ymax == pytest.approx(dense[:, 1].max(), abs=1e-9)
    assert ymin == pytest.approx(dense[:, 1].min(), abs=1e-9)
    # each extreme is the point's position at the crank angle reported for it
    assert closed_form(path.extent_angles[1])["E"][0] == pytest.approx(xmax, abs=1e-12)


def test_fixed_centrode_is_the_locus_of_the_kennedy_icentre():
    cen = centrodes(loads(TEXT), "coupler", steps=36)
    for theta, fixed in zip(cen.angles, cen.fixed, strict=True):
        pts = closed_form(float(theta))
        i13 = meet((0.0, 0.0), pts["B"], (D, 0.0), pts["C"])  # line AB ∩ line DC
        assert tuple(fixed) == (pytest.approx(i13[0], abs=1e-9), pytest.approx(i13[1], abs=1e-9))


def test_moving_centrode_is_the_icentre_in_the_couplers_frame():
    cen = centrodes(loads(TEXT), "coupler", steps=36)
    assert cen.origin == "B"
    turns = []
    for theta, moving in zip(cen.angles, cen.moving, strict=True):
        pts = closed_form(float(theta))
        i13 = meet((0.0, 0.0), pts["B"], (D, 0.0), pts["C"])
        phi = math.atan2(pts["C"][1] - pts["B"][1], pts["C"][0] - pts["B"][0])  # the coupler's BC direction
        rx, ry = i13[0] - pts["B"][0], i13[1] - pts["B"][1]
        local = (math.cos(phi) * rx + math.sin(phi) * ry, -math.sin(phi) * rx + math.cos(phi) * ry)
        # the link's frame angle may differ from BC's direction by a constant: compare distances to B and
        # the angle from BC, which are frame-free
        assert math.hypot(*moving) == pytest.approx(math.hypot(*local), rel=1e-9)
        turns.append(math.atan2(moving[1], moving[0]) - math.atan2(local[1], local[0]))
    # and the same direction up to that one constant angle
    assert np.ptp(np.unwrap(turns)) == pytest.approx(0.0, abs=1e-9)
    # the two centrodes touch at the instant's I-centre (drive angle 60° is a step of the sweep)
    k = int(np.argmin(np.abs(np.asarray(cen.angles) - math.radians(60.0))))
    assert tuple(cen.moving_now[k]) == (
        pytest.approx(cen.fixed[k][0], abs=1e-12),
        pytest.approx(cen.fixed[k][1], abs=1e-12),
    )


def test_sweep_path_writes_csv_columns_and_an_svg(tmp_path, write, run):
    path = write(TEXT)
    csv_file, svg_file = tmp_path / "e.csv", tmp_path / "e.svg"
    result = run(
        "sweep", str(path), "--path", "E", "--csv", str(csv_file), "--svg", str(svg_file), "--steps", "36"
    )
    assert result.exit_code == 0, result.output
    header = csv_file.read_text().splitlines()[0]
    assert "position.E.x [m]" in header and "position.E.y [m]" in header
    assert 'class="path"' in svg_file.read_text() or "path of E" in svg_file.read_text()


def test_draw_traces_paths_and_centrodes(tmp_path, write, run):
    out = tmp_path / "d.svg"
    result = run("draw", str(write(TEXT)), "-o", str(out), "--path", "E", "--centrodes", "coupler", "--json")
    assert result.exit_code == 0, result.output
    svg = out.read_text()
    for label in ("path of E", "fixed centrode of coupler", "moving centrode of coupler"):
        assert label in svg


def test_centrodes_of_the_ground_are_refused(write, run):
    result = run("draw", str(write(TEXT)), "-o", "x.svg", "--centrodes", "frame")
    assert result.exit_code == 2 and "ground has no centrodes" in result.stderr


def test_sweep_animation_traces_the_path(tmp_path, write, run, monkeypatch):
    pytest.importorskip("matplotlib")
    import mech.draw.plot as plot

    seen = {}
    real = plot.animate

    def spy(path, mech, kin, frames, **kw):
        seen["curves"] = kw.get("curves")
        return real(path, mech, kin, frames[:2], **kw)  # two frames are enough to write a GIF

    monkeypatch.setattr(plot, "animate", spy)
    out = tmp_path / "a.gif"
    result = run("sweep", str(write(TEXT)), "--path", "E", "--animate", str(out), "--steps", "12")
    assert result.exit_code == 0, result.output
    ((label, points, kind),) = seen["curves"]
    assert (label, kind, len(points)) == ("path of E", "path", 13)
    assert out.stat().st_size > 0
