"""A cam given by its programme, swept by the linkage solver through its generated profile.

The solver knows nothing of the programme: it moves the follower on the profile's spline
(mech.kinematics.profiles).  The follower's positions and speeds over the sweep must be the
programme's s(θ) and ω·ds/dθ.  The sweep's angle is the cam's orientation, counter-clockwise
from its pose at the programme's start, so the programme's angle is θ = σ·angle (σ = −1 for a
cam turning clockwise).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from tests.conftest import MECHANISMS

from mech.cam.program import follower_motion
from mech.kinematics.sweep import sweep
from mech.loader import load, loads
from mech.pairs.cam.setup import cam_setup

ANGLES = np.radians(np.arange(0.0, 360.0, 2.5))


def swept(text: str, path: str):
    m = loads(text, path=path)
    setup = cam_setup(m)
    sigma = setup.layout.sense
    sw = sweep(m, ANGLES, level="velocity")
    assert sw.assembled.all()
    motion = follower_motion(setup.layout.program, sigma * ANGLES)
    return m, setup, sw, motion


def dwell_index(setup, sigma: int) -> int:
    """The sample nearest the middle of the programme's last dwell: a reference far from any jump."""
    prog = setup.layout.program
    (start, seg) = next(
        (s, g) for s, g in reversed(list(zip(prog.starts, prog.segments, strict=True))) if g.kind == "dwell"
    )
    mid = start + seg.over / 2
    theta = np.mod(sigma * ANGLES, 2 * math.pi)
    return int(np.argmin(np.abs(theta - mid)))


def away_from_jumps(setup, sigma: int, margin_deg: float = 6.0) -> np.ndarray:
    """Angles more than ``margin_deg`` from a segment's start.

    Where a law's acceleration jumps (SHM, uniform acceleration) the profile's curvature
    jumps, and the solver's C² spline through the profile's points (mech.kinematics.curves)
    gets its slope there only to O(h) (0.1 % of the peak speed at 720 points) and its
    position to about 1e-5 of the cam's size, both falling to rounding within a few steps.
    The cycloidal-only programme below has no jump and is checked at every angle.
    """
    theta = np.degrees(np.mod(sigma * ANGLES, 2 * math.pi))
    starts = np.degrees(np.array(setup.layout.program.starts))
    gap = np.abs((theta[:, None] - starts[None, :] + 180.0) % 360.0 - 180.0)
    return np.min(gap, axis=1) > margin_deg


@pytest.mark.parametrize("name", ["cam_roller_program.yaml", "cam_valve_khurmi.yaml"])
@pytest.mark.parametrize("direction", ["cw", "ccw"])
def test_translating_follower_sweeps_through_the_programme(name, direction):
    path = MECHANISMS / name
    text = path.read_text().replace("direction: cw", f"direction: {direction}")
    _, setup, sw, motion = swept(text, str(path))
    disp = sw.displacement[:, 0]
    size = setup.layout.prime_radius + setup.layout.program.stroke
    k = dwell_index(setup, setup.layout.sense)
    ok = away_from_jumps(setup, setup.layout.sense)
    assert ok.sum() > 100
    np.testing.assert_allclose(disp[ok] - disp[k], motion.s[ok] - motion.s[k], rtol=0, atol=1e-7 * size)
    w = setup.omega
    assert w is not None
    np.testing.assert_allclose(sw.sliding[ok, 0], motion.ds[ok] * w, rtol=0, atol=1e-6 * w * size)


CYCLOIDAL = """\
units: {length: mm, angle: deg}
links: [frame, cam, follower]
joints:
  O: {type: revolute, links: [frame, cam], at: [0, 0]}
  S: {type: prismatic, links: [follower, frame], path: {through: [8, 0], angle: 90}}
  K: {type: cam, links: [cam, follower],
      program: {base_radius: 40, follower: roller, roller_radius: 12,
                segments: [{rise: 25, over: 150, law: cycloidal}, {dwell: 20},
                           {return: 25, over: 130, law: cycloidal}, {dwell: 60}]}}
drive: {link: cam, angle: 0, rpm: 240, direction: DIRECTION}
"""


@pytest.mark.parametrize("direction", ["cw", "ccw"])
def test_offset_cycloidal_programme_sweeps_with_its_speeds_at_every_angle(direction):
    """No acceleration jumps: the profile is C² and the solver's speeds are the programme's everywhere."""
    _, setup, sw, motion = swept(CYCLOIDAL.replace("DIRECTION", direction), "cycloidal.yaml")
    size = 0.04 + 0.012 + 0.025
    w = setup.omega
    assert w is not None
    disp = sw.displacement[:, 0]
    k = dwell_index(setup, setup.layout.sense)
    np.testing.assert_allclose(disp - disp[k], motion.s - motion.s[k], rtol=0, atol=1e-7 * size)
    np.testing.assert_allclose(sw.sliding[:, 0], motion.ds * w, rtol=0, atol=1e-6 * w * size)


def test_oscillating_follower_sweeps_through_the_programme():
    path = MECHANISMS / "cam_oscillating_roller.yaml"
    _, setup, sw, motion = swept(path.read_text(), str(path))
    arm = sw.links.index("arm")
    psi = sw.link_angles[:, arm]
    k = dwell_index(setup, setup.layout.sense)
    ok = away_from_jumps(setup, setup.layout.sense)
    # this arm lifts its roller away from the cam by turning clockwise (the file's geometry)
    np.testing.assert_allclose(-(psi[ok] - psi[k]), motion.s[ok] - motion.s[k], rtol=0, atol=1e-7)
    w = setup.omega
    assert w is not None and sw.omegas is not None
    np.testing.assert_allclose(-sw.omegas[ok, arm], motion.ds[ok] * w, rtol=0, atol=1e-6 * w)


def test_flat_faced_follower_sweeps_through_the_programme():
    m = load(MECHANISMS / "cam_flat_follower.yaml")
    setup = cam_setup(m)
    sw = sweep(m, ANGLES, level="position")
    assert sw.assembled.all()
    s = follower_motion(setup.layout.program, setup.layout.sense * ANGLES).s
    disp = sw.displacement[:, 0]
    k = dwell_index(setup, setup.layout.sense)
    ok = away_from_jumps(setup, setup.layout.sense)  # SHM: the curvature jumps at each segment's ends
    np.testing.assert_allclose(disp[ok] - disp[k], s[ok] - s[k], rtol=0, atol=1e-7 * 0.045)


def test_drawn_instant_is_the_files_turn_in_the_cams_sense():
    """drive.angle 60 on a clockwise cam: 60° turned clockwise, i.e. the cam's orientation is −60°."""
    m = load(MECHANISMS / "cam_roller_program.yaml")
    assert m.drives[0].angle == pytest.approx(-math.radians(60))
    assert cam_setup(m).angle == pytest.approx(math.radians(60))
