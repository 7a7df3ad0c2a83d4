"""Regenerate docs/images/: every kinematic example drawn with its polygons (run from the repo root).

    python docs/make_images.py

Each example with a drive and geometry gets ``<name>.svg``: the configuration
diagram, the velocity polygon and, where the file allows it, the acceleration
polygon; the four-bar and the slider crank also get ``<name>_icentres.svg``.
A cam generated from its programme gets its profile (``<name>.svg``) and its
s–v–a–j diagrams (``<name>_sva.svg``), as ``mech cam -o … --diagram …`` draws them.

The README's pictures for projection are PNGs: the shaper with both polygons and its I-centres,
the Watt six-bar's I-centres, and a screenshot of ``mech view``'s page (taken by headless
Chromium, when it is installed: ``apt-get install -y chromium``).
"""

from __future__ import annotations

from pathlib import Path

from mech.cam.analysis import analyse
from mech.draw import draw, save
from mech.draw.cam import diagram_figure, profile_figure
from mech.errors import MechError
from mech.icentres import locate
from mech.kinematics import solve
from mech.loader import load
from mech.pairs.cam.setup import cam_joints, cam_setup

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "docs" / "images"


def main() -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    for path in sorted((ROOT / "mechanisms").glob("*.yaml")):
        m = load(path)
        if cam_joints(m):
            setup = cam_setup(m)
            result = analyse(setup.layout, omega=setup.omega)
            save(profile_figure(setup, result, title=m.label), OUT / f"{path.stem}.svg")
            save(diagram_figure(result, title=m.label), OUT / f"{path.stem}_sva.svg")
            continue
        if not (m.drives and m.has_geometry):
            continue
        try:
            kin, acc = solve(m, level="acceleration"), True
        except MechError:  # e.g. a cam known only at the instant: velocities only
            kin, acc = solve(m, level="velocity"), False
        save(draw(m, kin, velocity=True, acceleration=acc), OUT / f"{path.stem}.svg")
    for stem in ("four_bar", "slider_crank"):
        m = load(ROOT / "mechanisms" / f"{stem}.yaml")
        kin = solve(m, level="velocity")
        save(draw(m, kin, icentres=locate(m, kin).centres), OUT / f"{stem}_icentres.svg")
    projected()


def projected() -> None:
    """The README's PNGs: two drawings as a teacher projects them, and the live page."""
    from mech.draw.raster import to_png

    m = load(ROOT / "mechanisms" / "crank_slotted_lever_quick_return.yaml")
    kin = solve(m, level="acceleration")
    fig = draw(m, kin, velocity=True, acceleration=True, icentres=locate(m, kin).centres)
    to_png(fig, str(OUT / "shaper_projected.png"), dpi=110)
    m = load(ROOT / "mechanisms" / "watt_six_bar.yaml")
    kin = solve(m, level="velocity")
    to_png(
        draw(m, kin, velocity=True, icentres=locate(m, kin).centres),
        str(OUT / "watt_six_bar_icentres.png"),
        dpi=110,
    )
    _page_screenshot()


def _page_screenshot() -> None:
    """``mech view``'s page of the four-bar at 100°, with headless Chromium (skipped without it)."""
    import shutil
    import subprocess
    import tempfile

    from mech.view import page

    chromium = shutil.which("chromium")
    if chromium is None:
        print("no chromium: docs/images/view_four_bar.png not redrawn (apt-get install -y chromium)")
        return
    with tempfile.TemporaryDirectory() as tmp:
        html = Path(tmp) / "four_bar.html"
        html.write_text(page(str(ROOT / "mechanisms" / "four_bar.yaml")), encoding="utf-8")
        flags = "--headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking"
        subprocess.run(
            [
                chromium,
                *flags.split(),
                "--disable-component-update",
                "--disable-sync",
                f"--user-data-dir={tmp}/p",
                "--window-size=1280,860",
                f"--screenshot={OUT / 'view_four_bar.png'}",
                html.as_uri() + "#angle=100",
            ],
            check=True,
            capture_output=True,
            timeout=120,
        )


if __name__ == "__main__":
    main()
