"""A crank that cannot turn fully has limit positions; beyond them lies another circuit.

The double rocker below (O2B = 90, BC = 40, O4C = 100, O2O4 = 120 mm) is
non-Grashof: the input can be assembled only while |O4B| stays between
|BC − O4C| = 60 and BC + O4C = 140 mm, i.e. within two separate ranges of the
input angle (by the cosine rule, |O4B|² = 90² + 120² − 2·90·120·cos θ).  The
drawing (θ = 50°) is in the first; the second is reachable only by taking the
mechanism apart, and mech must say so rather than move there.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mech.errors import GeometryError
from mech.kinematics import solve, sweep
from mech.loader import loads
from mech.options import SolveOptions

DOUBLE_ROCKER = """
units: {length: mm, angle: deg}
links: [frame, input, coupler, output]
joints:
  O2: {type: revolute, links: [frame, input], at: [0, 0]}
  B:  {type: revolute, links: [input, coupler]}
  C:  {type: revolute, links: [coupler, output], near: [88, 95]}
  O4: {type: revolute, links: [output, frame], at: [120, 0]}
lengths: {O2B: 90, BC: 40, O4C: 100}
drive: {link: input, angle: 50, rpm: 60, direction: cw}
"""


def limits() -> tuple[float, float]:
    """Input angles (deg) bounding the drawing's range: |O4B| = 60 mm and |O4B| = 140 mm."""

    def at(distance: float) -> float:
        return math.degrees(math.acos((90**2 + 120**2 - distance**2) / (2 * 90 * 120)))

    return at(60.0), at(140.0)  # |O4B| grows with θ from 30 mm at θ = 0


def test_the_sweep_names_the_separate_circuits():
    s = sweep(loads(DOUBLE_ROCKER), np.radians(np.linspace(0, 360, 361)), level="position")
    note = next(n for n in s.notes if "separate circuits" in n)
    first, _ = note.split("are separate circuits")
    assert "the drawing lies on 29°–82°" in note
    lo, hi = limits()
    assert lo == pytest.approx(28.955, abs=1e-3) and hi == pytest.approx(82.284, abs=1e-3)
    assert "278°–331°" in first


def test_an_angle_on_the_other_circuit_is_refused_as_unreachable():
    with pytest.raises(GeometryError) as info:
        solve(loads(DOUBLE_ROCKER), level="velocity", options=SolveOptions(angle=math.radians(300)))
    assert "another circuit" in str(info.value)
    assert "open by" not in str(info.value)


def test_a_newton_sweep_starts_from_the_drawing_not_from_the_first_angle():
    # The GATE four-bar's input AB is a rocker (CD = 20 mm is the shortest link and turns fully);
    # a sweep from 0° starts beyond its limit.  Newton continuation must begin at the drawing
    # (90°), reach both limits, and agree with the closed form on the steps it solves.
    from pathlib import Path

    path = Path(__file__).resolve().parents[2] / "mechanisms" / "gate_four_bar_translating_coupler.yaml"
    m = loads(path.read_text(), path=str(path))
    angles = np.radians(np.linspace(0, 360, 361))
    newton = sweep(m, angles, level="velocity", options=SolveOptions(method="newton"), analyse=False)
    closed = sweep(m, angles, level="velocity", options=SolveOptions(method="closed"), analyse=False)
    solved = np.flatnonzero(newton.assembled)
    # limits: |BD| = BC ∓ CD = 30 or 70 mm with |BD|² = 50² + 40² − 2·50·40·cos θ,
    # i.e. cos θ = 0.8 (36.87°) and −0.2 (101.54°)
    assert solved.min() == 37 and solved.max() == 101
    assert np.allclose(
        newton.series("omega.rocker")[solved], closed.series("omega.rocker")[solved], rtol=1e-9
    )
