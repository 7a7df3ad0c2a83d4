"""The general route's rates (Φ_q q̇ = −Φ_t): what it says next to a toggle.

The closed form says how far its drive is from a toggle (tests/kinematics/test_fourbar.py);
the general route — several drives, a chain that does not decompose, ``method="newton"`` —
names the two links Φ_q's least-held motion turns and how far from in line they are.
Reference angles here are the cosine rule's, not the solver's.
"""

from __future__ import annotations

import math

import pytest

from mech.kinematics import solve
from mech.kinematics.result import Kinematics
from mech.loader import loads
from mech.model import Mechanism
from mech.options import SolveOptions

#: A five-bar driven at both ends: cranks AB = DE = 1 m on pivots 2 m apart, middle links
#: BC = CD = 1.2 m.  With the cranks mirrored (θ at A, 180° − θ at E), |BD| = 2 − 2 cos θ, and
#: BC, CD come into line where |BD| = 2.4 m: cos θ = −0.2, θ = 101.537°.
FIVE_BAR = """\
links: [frame, a, b, c, d]
joints:
  A: {{type: revolute, links: [frame, a], at: [0, 0]}}
  B: {{type: revolute, links: [a, b]}}
  C: {{type: revolute, links: [b, c], near: [1, 0.3]}}
  D: {{type: revolute, links: [c, d]}}
  E: {{type: revolute, links: [d, frame], at: [2, 0]}}
lengths: {{AB: 1, BC: 1.2, CD: 1.2, DE: 1}}
drive:
  - {{link: a, angle: {theta!r}, rpm: 60}}
  - {{link: d, angle: {other!r}, rpm: 60, direction: cw}}
"""


def five_bar(theta: float) -> Mechanism:
    return loads(FIVE_BAR.format(theta=theta, other=180 - theta), path="five_bar.yaml")


def from_in_line(theta: float) -> float:
    """How far (°) BC and CD are from in line at C, by the cosine rule on triangle BCD."""
    bd = 2 - 2 * math.cos(math.radians(theta))
    bcd = math.degrees(math.acos((1.2**2 + 1.2**2 - bd**2) / (2 * 1.2 * 1.2)))
    return 180 - bcd


def toggle_notes(kin: Kinematics) -> list[str]:
    return [n for n in kin.notes if "toggle" in n]


def test_two_drives_next_to_a_toggle_name_the_links_in_line_and_how_far():
    theta = 101.535  # 0.002° of crank short of the toggle at 101.537°
    (note,) = toggle_notes(solve(five_bar(theta), "velocity"))
    assert f"b and c are {from_in_line(theta):.3g}° from in line at C" in note
    assert "velocities grow without bound" in note


def test_two_drives_away_from_a_toggle_say_nothing_of_one():
    for theta in (90.0, 101.0):  # 22° and 7° from in line
        assert from_in_line(theta) > math.degrees(math.asin(0.02))
        assert not toggle_notes(solve(five_bar(theta), "velocity"))


def test_a_slider_crank_at_dead_centre_is_no_toggle_for_the_general_route():
    # crank and rod in line at θ = 0 and 180°, but the crank holds: the slider stops, nothing is singular
    text = """\
links: [frame, crank, rod, piston]
joints:
  O: {type: revolute, links: [frame, crank], at: [0, 0]}
  A: {type: revolute, links: [crank, rod]}
  B: {type: revolute, links: [rod, piston], near: [0.5, 0]}
  P: {type: prismatic, links: [piston, frame], path: {through: [0, 0], angle: 0}}
lengths: {OA: 0.1, AB: 0.4}
drive: {link: crank, angle: 0, rpm: 600}
"""
    m = loads(text, path="slider.yaml")
    for angle in (0.0, math.pi):
        kin = solve(m, "acceleration", SolveOptions(method="newton", angle=angle))
        assert not toggle_notes(kin)
        assert kin.links["rod"].omega == pytest.approx(-600 * 2 * math.pi / 60 * 0.1 / 0.4 * math.cos(angle))
