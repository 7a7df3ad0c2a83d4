"""Nearly parallel lines, dead centres, parallelograms, a mechanism at rest: clean answers, never NaN."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from mech.icentres import locate
from mech.kinematics import solve
from mech.loader import load
from mech.options import SolveOptions

MECHANISMS = Path(__file__).resolve().parents[2] / "mechanisms"


def clean(ic) -> None:
    """Every centre is finite numbers or a clean direction at infinity."""
    for c in ic.centres:
        assert c.found, c
        if c.at_infinity:
            assert c.point is None and all(math.isfinite(v) for v in c.direction)
            assert math.hypot(*c.direction) == pytest.approx(1.0)
        else:
            assert c.direction is None and all(math.isfinite(v) for v in c.point), c
    for o in ic.omegas:
        assert math.isfinite(o.omega)


@pytest.mark.parametrize("angle", [0.0, 1e-9, -1e-9, math.pi - 1e-9, math.pi])
def test_slider_crank_at_and_near_dead_centre(angle):
    mech = load(MECHANISMS / "slider_crank.yaml")
    kin = solve(mech, level="velocity", options=SolveOptions(angle=angle))
    ic = locate(mech, kin)
    clean(ic)
    a, b = kin.positions["A"], kin.positions["B"]
    # Hand: I13 is on x = b_x and on the crank line; I24 on x = 0 and on the rod line.
    assert ic.named("I13").point == pytest.approx((b[0], a[1] / a[0] * b[0]), abs=1e-9 * kin.size)
    assert ic.named("I24").point[0] == pytest.approx(0.0, abs=1e-9 * kin.size)
    assert ic.named("I14").at_infinity


PARALLELOGRAM = """\
units: {length: mm, angle: deg}
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [120, 35]}
  D: {type: revolute, links: [rocker, frame], at: [100, 0]}
lengths: {AB: 40, BC: 100, CD: ROCKER}
drive: {link: crank, angle: 60, rpm: 60, direction: ccw}
"""


def test_parallelogram_coupler_translates_centres_at_infinity(write):
    mech = load(write(PARALLELOGRAM.replace("ROCKER", "40")))
    ic = locate(mech, solve(mech, level="velocity"))
    clean(ic)
    i13, i24 = ic.named("I13"), ic.named("I24")
    assert i13.at_infinity and i13.direction == pytest.approx((0.5, math.sqrt(3) / 2))  # along the cranks
    assert i24.at_infinity and i24.direction == pytest.approx((1.0, 0.0), abs=1e-12)  # along the frame
    w = ic.omega_by_icentres
    assert w["coupler"] == 0.0 and w["rocker"] == pytest.approx(w["crank"], rel=1e-12)


@pytest.mark.parametrize("eps", [1e-9, 1e-12, 1e-15])
def test_nearly_parallelogram_is_finite_or_clean_infinity(write, eps):
    mech = load(write(PARALLELOGRAM.replace("ROCKER", repr(40 * (1 + eps)))))
    ic = locate(mech, solve(mech, level="velocity"))
    clean(ic)


def test_mechanism_at_rest_still_gets_kennedy_centres(run):
    mech = load(MECHANISMS / "four_bar.yaml")
    ic = locate(mech, solve(mech, level="velocity", options=SolveOptions(omega=0.0)))
    clean(ic)
    assert all(c.check is None for c in ic.centres)
    assert any("at rest" in note for note in ic.notes)
    assert ic.named("I13").method.startswith("Kennedy")


def test_position_level_solve_gives_kennedy_without_a_cross_check():
    mech = load(MECHANISMS / "watt_six_bar.yaml")
    ic = locate(mech, solve(mech, level="position"))
    assert ic.count == 15 and all(c.found and c.check is None for c in ic.centres)
    assert ic.omegas == ()
