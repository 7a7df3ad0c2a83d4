"""Regenerate docs/images/: every kinematic example drawn with its polygons (run from the repo root).

    python docs/make_images.py

Each example with a drive and geometry gets ``<name>.svg``: the configuration
diagram, the velocity polygon and, where the file allows it, the acceleration
polygon; the four-bar and the slider crank also get ``<name>_icentres.svg``.
"""

from __future__ import annotations

from pathlib import Path

from mech.draw import draw, save
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
