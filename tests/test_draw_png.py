"""PNG output compared with stored references, and the sweep plots (matplotlib: the plot extra).

The references in tests/data were rendered by mech itself (``python
tests/test_draw_png.py`` rewrites them after an intended change).  The
comparison is of 8×8-block-averaged grayscale images, with a tolerance that
anti-aliasing or a freetype version cannot break but a moved link can.
"""

from __future__ import annotations

import itertools
import math
import re
from dataclasses import replace
from pathlib import Path

import pytest

pytest.importorskip("matplotlib")
PIL_Image = pytest.importorskip("PIL.Image")

import numpy as np  # noqa: E402

from mech.draw import draw  # noqa: E402
from mech.draw.plot import Series, animate, extremes, sweep_plot, thin  # noqa: E402
from mech.draw.raster import to_png  # noqa: E402
from mech.kinematics import solve  # noqa: E402
from mech.loader import load  # noqa: E402
from mech.options import SolveOptions  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
DATA = Path(__file__).resolve().parent / "data"
DPI = 60
# Mean absolute difference of 8×8-averaged grayscale (0..1).  Measured at 60 dpi: every label
# moved by 0.7 px (a different font rasteriser at worst) gives 0.0024; the velocity polygon's
# vectors missing give 0.0040.  Geometry is ours and exact, so only glyphs can differ by machine.
TOLERANCE = 0.003
CASES = {"four_bar": ("four_bar.yaml", True), "slider_crank": ("slider_crank.yaml", True)}


def _figure(name: str, angle: float | None = None):
    file, velocity = CASES[name]
    m = load(ROOT / "mechanisms" / file)
    options = SolveOptions(angle=None if angle is None else math.radians(angle))
    kin = solve(m, level="velocity", options=options)
    return draw(m, kin, velocity=velocity)


def _gray(path: Path) -> np.ndarray:
    img = np.asarray(PIL_Image.open(path).convert("L"), dtype=float) / 255.0
    h, w = (img.shape[0] // 8) * 8, (img.shape[1] // 8) * 8
    return img[:h, :w].reshape(h // 8, 8, w // 8, 8).mean(axis=(1, 3))


def _difference(a: Path, b: Path) -> float:
    ga, gb = _gray(a), _gray(b)
    assert ga.shape == gb.shape, f"image sizes differ: {ga.shape} vs {gb.shape}"
    return float(np.abs(ga - gb).mean())


@pytest.mark.parametrize("name", sorted(CASES))
def test_png_matches_reference(name, tmp_path):
    out = tmp_path / f"{name}.png"
    to_png(_figure(name), str(out), dpi=DPI)
    assert _difference(out, DATA / f"draw_{name}.png") < TOLERANCE


def test_png_comparison_sees_a_missing_polygon(tmp_path):
    fig = _figure("four_bar")
    polygon = {"vector", "arrowhead", "image", "image-label", "vector-label"}
    without = replace(fig, items=tuple(i for i in fig.items if getattr(i, "cls", "") not in polygon))
    out = tmp_path / "without.png"
    to_png(without, str(out), dpi=DPI)
    # the tolerance is not so loose that a drawing missing its vectors passes
    assert _difference(out, DATA / "draw_four_bar.png") > TOLERANCE


def test_png_has_no_timestamp(tmp_path):
    a, b = tmp_path / "a.png", tmp_path / "b.png"
    fig = _figure("four_bar")
    to_png(fig, str(a), dpi=DPI)
    to_png(fig, str(b), dpi=DPI)
    assert a.read_bytes() == b.read_bytes()


# -- sweep plots and animation (synthetic data) -------------------------------------------
def test_extremes_ignore_nan():
    angles = [0, 90, 180, 270]
    assert extremes(angles, [1.0, float("nan"), 3.0, -2.0]) == ((180, 3.0), (270, -2.0))


def test_sweep_plot_writes_png(tmp_path):
    angles = list(range(0, 361, 5))
    series = [
        Series("v_B", "m/s", [math.sin(math.radians(a)) for a in angles]),
        Series("v_C", "m/s", [0.5 * math.cos(math.radians(a)) for a in angles]),
        Series("ω_rod", "rad/s", [2 * math.sin(math.radians(2 * a)) for a in angles]),
    ]
    out = tmp_path / "sweep.png"
    sweep_plot(out, angles, series, dead_centres=[0, 180], title="synthetic")
    img = PIL_Image.open(out)
    assert img.size[0] > 500 and img.size[1] > 500  # two panels: m/s and rad/s


def test_sweep_plot_labels_the_refined_extremes_inside_the_axes():
    """The labels give the sweep's refined extremes (not the grid's) and stay inside their axes."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from mech.draw.plot import sweep_figure
    from mech.kinematics import sweep

    m = load(ROOT / "mechanisms" / "four_bar.yaml")
    sw = sweep(m, np.radians(np.arange(0, 361, 1.0)), level="velocity")
    series = []
    for key in ("velocity.C", "omega.rocker"):
        e = next(x for x in sw.extremes if x.quantity == key)
        refined = ((math.degrees(e.max_angle), e.max_value), (math.degrees(e.min_angle), e.min_value))
        series.append(Series(key, "u" + key, list(sw.series(key)), refined))
    fig = sweep_figure(list(np.degrees(sw.angles)), series)
    renderer = FigureCanvasAgg(fig).get_renderer()
    labels = [(ax, t) for ax in fig.axes for t in ax.texts if t.get_text().startswith(("max", "min"))]
    assert len(labels) == 4
    for ax, t in labels:
        box, inside = t.get_window_extent(renderer), ax.get_window_extent(renderer)
        assert inside.x0 <= box.x0 and box.x1 <= inside.x1 and inside.y0 <= box.y0 and box.y1 <= inside.y1, (
            t.get_text()
        )
    texts = " | ".join(t.get_text() for _, t in labels)

    # the rocker's speed is zero at its dead centres, where crank and coupler are in line (C above
    # AD): extended, AC = 40 + 150 and the crank along AC; folded, AC = 150 − 40 and the crank
    # opposite; ∠CAD by the cosine rule with AD = 150, CD = 80.  The label says 0, at one of them
    def along(ac: float) -> float:
        return math.degrees(math.acos((150**2 + ac**2 - 80**2) / (2 * 150 * ac)))

    dead = (along(190.0), 180.0 + along(110.0))
    said = re.search(r"min 0 at ([0-9.]+)°", texts)
    assert said is not None, texts
    assert min(abs(float(said.group(1)) - d) for d in dead) < 0.006, (said.group(1), dead)
    # a small value is written with ×10⁻ⁿ, never with a caret
    tiny = Series(
        "v", "m/s", [3e-7 * math.sin(math.radians(a)) for a in range(361)], ((90.0, 3e-7), (270.0, -3e-7))
    )
    small = sweep_figure(list(range(361)), [tiny])
    written = " | ".join(t.get_text() for ax in small.axes for t in ax.texts)
    assert "×10⁻" in written and "^" not in written, written


def test_sweep_plot_rejects_mismatched_lengths(tmp_path):
    with pytest.raises(ValueError, match="values for"):
        sweep_plot(tmp_path / "x.png", [0, 1, 2], [Series("v", "m/s", [1.0, 2.0])])


def test_animate_writes_one_gif_frame_per_position_set(tmp_path):
    m = load(ROOT / "mechanisms" / "four_bar.yaml")
    frames = [
        solve(m, level="position", options=SolveOptions(angle=math.radians(a))).positions
        for a in (60, 150, 240, 330)
    ]
    kin = solve(m, level="position")
    out = tmp_path / "four_bar.gif"
    animate(out, m, kin, frames, fps=10, dpi=40)
    gif = PIL_Image.open(out)
    assert gif.n_frames == 4


def test_thinning_leaves_a_path_as_coarse_as_the_resolution_unchanged():
    circle = [(math.cos(t), math.sin(t)) for t in np.linspace(0, 2 * math.pi, 100)]
    step = 2 * math.sin(math.pi / 99)  # the chord between neighbours
    assert thin(circle, 0.999 * step) == circle
    broken = [*circle[:40], (math.nan, math.nan), *circle[40:]]
    assert thin(broken, 0.999 * step) == broken


def test_thinning_a_dense_path_keeps_its_ends_and_spaces_the_rest_by_the_resolution():
    dense = [(math.cos(t), math.sin(t)) for t in np.linspace(0, 2 * math.pi, 10_001)]
    kept = thin(dense, 0.01)
    assert kept[0] == dense[0] and kept[-1] == dense[-1]
    gaps = [math.dist(a, b) for a, b in itertools.pairwise(kept[:-1])]  # the last may be nearer
    assert min(gaps) >= 0.01 and max(gaps) < 0.011  # 2π / 0.01 ≈ 628 points, not 10,001
    assert 600 < len(kept) < 640


def test_an_animation_of_a_coarse_path_draws_the_same_frames(tmp_path, monkeypatch):
    """Thinning to the frame's pixel changes nothing where the path is already that coarse."""
    import mech.draw.plot as plot

    m = load(ROOT / "mechanisms" / "four_bar.yaml")
    angles = [math.radians(a) for a in range(0, 360, 12)]
    solved = [solve(m, level="position", options=SolveOptions(angle=a)).positions for a in angles]
    path = [solved_at["B"] for solved_at in solved]  # the crank pin: 12° apart on a circle
    kin = solve(m, level="position")
    curves = [("path of B", path, "path")]
    animate(tmp_path / "thinned.gif", m, kin, solved[:3], dpi=40, curves=curves)
    monkeypatch.setattr(plot, "thin", lambda points, resolution: list(points))
    animate(tmp_path / "whole.gif", m, kin, solved[:3], dpi=40, curves=curves)
    assert (tmp_path / "thinned.gif").read_bytes() == (tmp_path / "whole.gif").read_bytes()


if __name__ == "__main__":  # regenerate the references after an intended change
    DATA.mkdir(exist_ok=True)
    for case in CASES:
        to_png(_figure(case), str(DATA / f"draw_{case}.png"), dpi=DPI)
