"""Regenerate docs/images/: every kinematic example drawn with its polygons (run from the repo root).

    python docs/make_images.py

Each example with a drive and geometry gets ``<name>.svg``: the configuration
diagram, the velocity polygon and, where the file allows it, the acceleration
polygon; the four-bar and the slider crank also get ``<name>_icentres.svg``.
A cam generated from its programme gets its profile (``<name>.svg``) and its
s–v–a–j diagrams (``<name>_sva.svg``), as ``mech cam -o … --diagram …`` draws them.
"""

from __future__ import annotations

from pathlib import Path

from mech.cam.analysis import analyse
from mech.cam.mechanism import cam_joints, cam_setup
from mech.draw import draw, save
from mech.draw.cam import diagram_figure, profile_figure
from mech.errors import MechError
from mech.icentres import locate
from mech.kinematics import solve
from mech.loader import load

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


if __name__ == "__main__":
    main()
