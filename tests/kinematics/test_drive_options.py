"""Command-line speeds go to the drive they fit, never reinterpreted.

A slider drive's speed is m/s along its path; --rpm/--omega are a crank's
rad/s.  Feeding one to the other once printed a crank turning 129 rad/s for
"--rpm 100" on a slider-driven file: now it is refused, and --speed exists.
"""

from __future__ import annotations

import math

import pytest

from mech.errors import InputError
from mech.kinematics import solve
from mech.loader import loads
from mech.options import SolveOptions

SLIDER_DRIVEN = """
units: {length: mm, angle: deg}
links: [frame, crank, rod, piston]
joints:
  O: {type: revolute, links: [frame, crank], at: [0, 0]}
  A: {type: revolute, links: [crank, rod], near: [40, 69]}
  B: {type: revolute, links: [rod, piston], at: [280, 0]}
  P: {type: prismatic, links: [piston, frame], path: {through: O, angle: 0}}
lengths: {OA: 80, AB: 250}
drive: {joint: P, speed: -2 m/s}
"""


def crank_omega(v_b: float) -> float:
    """ω of the crank driven by the piston at x_B = 0.28 m, by hand.

    A = (r cos θ, r sin θ) with |A − B| = l; differentiating
    (r cos θ − x)² + (r sin θ)² = l² gives ω = ẋ (r cos θ − x) / (r x sin θ).
    """
    r, rod, x = 0.08, 0.25, 0.28
    cos_t = (r * r + x * x - rod * rod) / (2 * r * x)
    th = math.acos(cos_t)  # A above the axis (near: [40, 69])
    return v_b * (r * math.cos(th) - x) / (r * x * math.sin(th))


def test_file_speed_gives_the_crank_omega():
    kin = solve(loads(SLIDER_DRIVEN), level="velocity")
    assert kin.links["crank"].omega == pytest.approx(crank_omega(-2.0), rel=1e-9)


def test_speed_option_overrides_the_slider():
    kin = solve(loads(SLIDER_DRIVEN), level="velocity", options=SolveOptions(speed=-3.0))
    assert kin.links["crank"].omega == pytest.approx(crank_omega(-3.0), rel=1e-9)


@pytest.mark.parametrize(
    "options", [SolveOptions(omega=10.0), SolveOptions(direction="cw"), SolveOptions(alpha=1.0)]
)
def test_crank_options_on_a_slider_drive_are_refused(options):
    with pytest.raises(InputError, match="is a slider"):
        solve(loads(SLIDER_DRIVEN), level="velocity", options=options)


def test_speed_on_a_crank_drive_is_refused():
    text = SLIDER_DRIVEN.replace("drive: {joint: P, speed: -2 m/s}", "drive: {link: crank, rpm: 60}")
    with pytest.raises(InputError, match="--speed sets a slider drive"):
        solve(loads(text), level="velocity", options=SolveOptions(speed=1.0))
