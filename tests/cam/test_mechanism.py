"""A programme's profiles handed to the pair-kind registry (``mech.cam.program_profiles``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mech.loader import loads
from mech.pairs.cam.setup import program_profiles
from mech.specs import Circle, Curve, Knife, Line

TEXT = """\
units: {{length: mm, angle: deg}}
links: [frame, cam, follower]
joints:
  O: {{type: revolute, links: [frame, cam], at: [10, 20]}}
  S: {{type: prismatic, links: [follower, frame], path: {{through: [10, 20], angle: 90}}}}
  K: {{type: cam, links: [cam, follower],
      program: {{base_radius: 40, follower: {follower}, {extra}
                segments: [{{rise: 30, over: 120, law: shm}}, {{dwell: 30}},
                           {{return: 30, over: 150, law: cycloidal}}, {{dwell: 60}}]}}}}
drive: {{link: cam, angle: 60, rpm: 300, direction: cw}}
"""


def profiles(follower: str, extra: str = ""):
    m = loads(TEXT.format(follower=follower, extra=extra))
    return program_profiles(m, m.joint("K"))


def test_roller_programme_gives_a_curve_on_the_cam_touching_the_roller():
    got = profiles("roller", "roller_radius: 10,")
    cam, roller = got["cam"], got["follower"]
    assert isinstance(cam, Curve) and isinstance(roller, Circle)
    # at 60° into a 120° SHM rise of 30 mm: the roller centre is 40 + 10 + 15 mm above O
    assert roller.centre.xy == pytest.approx((0.010, 0.020 + 0.065))
    assert roller.radius == pytest.approx(0.010)
    pts = np.array(cam.points)
    gap = np.min(np.hypot(*(pts - np.array(roller.centre.xy)).T)) - roller.radius
    assert gap == pytest.approx(0.0, abs=1e-5 * 0.08)  # the roller touches the curve


def test_knife_programme_gives_a_knife_on_the_curve():
    got = profiles("knife")
    knife = got["follower"]
    assert isinstance(knife, Knife)
    assert knife.point.xy == pytest.approx((0.010, 0.020 + 0.055))
    pts = np.array(got["cam"].points)
    assert np.min(np.hypot(*(pts - np.array(knife.point.xy)).T)) < 0.0005


def test_flat_programme_gives_a_line_square_to_the_stroke_touching_the_curve():
    got = profiles("flat")
    face = got["follower"]
    assert isinstance(face, Line)
    assert face.angle == pytest.approx(math.pi)  # square to the vertical line of stroke
    # the face is tangent to the cam: the cam lies below it and touches it
    pts = np.array(got["cam"].points)
    assert np.max(pts[:, 1]) == pytest.approx(face.through.xy[1], abs=1e-6)
    assert face.through.xy[1] == pytest.approx(0.020 + 0.040 + 0.015)
