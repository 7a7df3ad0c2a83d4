"""Nearly parallel lines, dead centres, parallelograms, a mechanism at rest: clean answers, never NaN."""

from __future__ import annotations

import json
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


# A four-bar of millimetre links drawn a million metres from the origin (issue 25, item 11): its
# points are held only to the spacing of floats there (1.2e-10 m, 1e-7 of its size), and the
# cross-check of Kennedy's centres against the velocity field must allow for that, not call the
# rounding a bug.  Closed form: B from the crank angle, C the circles' intersection above AD, then
# I13 = AB ∩ DC and I24 = AD ∩ BC.
FAR = """\
units: {{length: m, angle: deg}}
links: [frame, crank, coupler, rocker]
joints:
  A: {{type: revolute, links: [frame, crank], at: [{x}, {y}]}}
  B: {{type: revolute, links: [crank, coupler]}}
  C: {{type: revolute, links: [coupler, rocker], near: [{cx}, {cy}]}}
  D: {{type: revolute, links: [rocker, frame], at: [{dx}, {y}]}}
lengths: {{AB: 0.0004, BC: 0.0015, CD: 0.0008}}
drive: {{link: crank, angle: 60, rpm: 120, direction: cw}}
"""


def _meet(p, q, r, s):
    """The intersection of lines pq and rs."""
    d = (q[0] - p[0]) * (s[1] - r[1]) - (q[1] - p[1]) * (s[0] - r[0])
    t = ((r[0] - p[0]) * (s[1] - r[1]) - (r[1] - p[1]) * (s[0] - r[0])) / d
    return (p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]))


@pytest.mark.parametrize("offset", [0.0, 1e4, 1e6, 1e7])
def test_icentres_of_a_small_four_bar_far_from_the_origin_are_located(write, run, offset):
    a, b, c, d, th = 0.0004, 0.0015, 0.0008, 0.0015, math.radians(60.0)
    bx, by = a * math.cos(th), a * math.sin(th)
    dist = math.hypot(d - bx, by)
    along = (b * b - c * c + dist * dist) / (2 * dist)
    h = math.sqrt(b * b - along * along)
    ux, uy = (d - bx) / dist, -by / dist
    cx, cy = bx + along * ux - h * uy, by + along * uy + h * ux
    text = FAR.format(x=offset, y=offset, dx=offset + d, cx=offset + cx, cy=offset + cy)
    result = run("icentres", str(write(text)), "--json")
    assert result.exit_code == 0, result.output + result.stderr
    got = {c["name"]: c["point"] for c in json.loads(result.output)["icentres"]}
    held = 64 * 2.2e-16 * max(offset, d) + 1e-9 * d  # the float spacing there, 64 ulps; 1e-9 of the size
    i13 = _meet((0.0, 0.0), (bx, by), (d, 0.0), (cx, cy))
    i24 = _meet((0.0, 0.0), (d, 0.0), (bx, by), (cx, cy))
    for name, (x, y) in (("I13", i13), ("I24", i24)):
        assert got[name][0] - offset == pytest.approx(x, abs=10 * held), name
        assert got[name][1] - offset == pytest.approx(y, abs=10 * held), name
