"""A cam given by its programme moves its follower by the programme's law, exactly, in every command.

The follower's lift, speed and acceleration over a sweep, in single solves at any angle, and
their extremes, are the textbook laws' closed forms (tests/oracles/cam.py, written out from
Khurmi & Gupta ch. 20, nothing of mech's) to 1e-9 of their peak inside every segment; the
mechanical advantage by virtual work is ω/v.  The sweep's angle is the cam's orientation,
counter-clockwise from its pose at the programme's start, so the programme's angle is
θ = σ·angle (σ = −1 for a cam turning clockwise).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from tests.conftest import MECHANISMS
from tests.mechanism_texts import ROLLER_CAM_POINT_K
from tests.oracles.cam import textbook_rise

from mech.kinematics import solve
from mech.kinematics.sweep import sweep
from mech.loader import load, loads
from mech.options import SolveOptions
from mech.pairs.cam.setup import cam_setup

ANGLES = np.radians(np.arange(0.0, 360.0, 2.5))

#: (rise | return | dwell, lift, over in degrees, law) of the shipped programmes and the one below.
PROGRAMMES = {
    "cam_roller_program.yaml": [("rise", 0.030, 120, "shm"), ("dwell", 0, 30, None),
                                ("return", 0.030, 150, "cycloidal"), ("dwell", 0, 60, None)],
    "cam_valve_khurmi.yaml": [("rise", 0.050, 120, "shm"), ("dwell", 0, 30, None),
                              ("return", 0.050, 60, "shm"), ("dwell", 0, 150, None)],
    "cycloidal": [("rise", 0.025, 150, "cycloidal"), ("dwell", 0, 20, None),
                  ("return", 0.025, 130, "cycloidal"), ("dwell", 0, 60, None)],
    "cam_oscillating_roller.yaml": [("rise", math.radians(20), 90, "cycloidal"), ("dwell", 0, 60, None),
                                    ("return", math.radians(20), 120, "shm"), ("dwell", 0, 90, None)],
    "cam_flat_follower.yaml": [("rise", 0.020, 120, "shm"), ("dwell", 0, 30, None),
                               ("return", 0.020, 120, "shm"), ("dwell", 0, 90, None)],
}  # fmt: skip


def oracle(
    segments, theta: np.ndarray, omega: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """s, v, a of the follower at programme angles ``theta`` (rad), and which lie strictly inside a segment."""
    th = np.mod(theta, 2 * math.pi)
    out = np.zeros((3, th.size))
    inside = np.zeros(th.size, bool)
    start, base = 0.0, 0.0
    for kind, lift, over, law in segments:
        beta = math.radians(over)
        for k, t in enumerate(th):
            if start <= t < start + beta:
                inside[k] = start + 1e-9 < t < start + beta - 1e-9
                if kind == "dwell":
                    out[:, k] = (base, 0.0, 0.0)
                else:
                    s, v, a = textbook_rise(law, t - start, lift, beta, omega)
                    sign = 1.0 if kind == "rise" else -1.0
                    out[:, k] = (base + sign * s, sign * v, sign * a)
        base += lift if kind == "rise" else -lift if kind == "return" else 0.0
        start += beta
    return out[0], out[1], out[2], inside


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


def _translating(name: str, direction: str):
    if name == "cycloidal":
        m = loads(CYCLOIDAL.replace("DIRECTION", direction), path="cycloidal.yaml")
    else:
        text = (MECHANISMS / name).read_text().replace("direction: cw", f"direction: {direction}")
        m = loads(text, path=str(MECHANISMS / name))
    return m, cam_setup(m)


@pytest.mark.parametrize("name", ["cam_roller_program.yaml", "cam_valve_khurmi.yaml", "cycloidal"])
@pytest.mark.parametrize("direction", ["cw", "ccw"])
def test_translating_follower_sweeps_by_its_law_exactly(name, direction):
    m, setup = _translating(name, direction)
    sw = sweep(m, ANGLES, level="acceleration")
    assert sw.assembled.all()
    w = abs(setup.omega)
    sigma = setup.layout.sense
    s, v, a, inside = oracle(PROGRAMMES[name], sigma * ANGLES, w)
    k = sw.points.index("K")
    u = np.array([math.cos(setup.layout.axis), math.sin(setup.layout.axis)])
    lift = (sw.positions[:, k, :] - sw.positions[:, k, :].min(axis=0)) @ u
    speed, accel = sw.velocities[:, k, :] @ u, sw.accelerations[:, k, :] @ u
    assert np.max(np.abs(lift - s)) <= 1e-9 * np.max(np.abs(s))
    assert np.max(np.abs(speed - v)) <= 1e-9 * np.max(np.abs(v))
    assert np.max(np.abs(accel[inside] - a[inside])) <= 1e-9 * np.max(np.abs(a))


@pytest.mark.parametrize("name", ["cam_roller_program.yaml", "cam_valve_khurmi.yaml"])
def test_single_solves_of_a_translating_follower_are_its_law(name):
    m, setup = _translating(name, "cw")
    w, sigma = abs(setup.omega), setup.layout.sense
    for deg in (7.0, 45.0, 95.0, 133.0, 170.0, 201.0, 262.0, 305.0):
        kin = solve(m, "acceleration", SolveOptions(angle=math.radians(deg)))
        _, v, a, inside = oracle(PROGRAMMES[name], np.array([sigma * math.radians(deg)]), w)
        peak_v = max(abs(oracle(PROGRAMMES[name], sigma * ANGLES, w)[1]))
        peak_a = max(abs(oracle(PROGRAMMES[name], sigma * ANGLES, w)[2]))
        assert inside[0]
        assert kin.velocity("K")[1] == pytest.approx(v[0], abs=1e-9 * peak_v), deg
        assert kin.acceleration("K")[1] == pytest.approx(a[0], abs=1e-9 * peak_a), deg


def test_sweep_extremes_of_the_roller_programme_are_the_laws_peaks():
    # SHM rise of 30 mm over 120°: v_max = πhω/(2β) = 0.706858 m/s; cycloidal return of 30 mm
    # over 150°: v_max = 2hω/β = 0.72 m/s (Khurmi & Gupta ch. 20), at ω = 300 rpm
    m = load(MECHANISMS / "cam_roller_program.yaml")
    sw = sweep(m, np.radians(np.linspace(0.0, 360.0, 361)), level="velocity")
    w = 300 * 2 * math.pi / 60
    ext = {e.quantity: e for e in sw.extremes}
    slide = ext["sliding.S"]  # the follower's speed along its path (up +), each stroke's peak
    assert slide.max_value == pytest.approx(math.pi * 0.030 * w / (2 * math.radians(120)), rel=1e-9)
    assert slide.min_value == pytest.approx(-2 * 0.030 * w / math.radians(150), rel=1e-9)
    assert ext["velocity.K"].max_value == pytest.approx(2 * 0.030 * w / math.radians(150), rel=1e-9)


def test_an_acceleration_that_jumps_at_a_segment_end_is_reported_as_a_jump():
    # SHM rise of h = 30 mm over β = 120° after a dwell: the follower's acceleration jumps at the
    # rise's start from 0 to π²hω²/(2β²) = 33.3099 m/s² (Khurmi & Gupta ch. 20) at ω = 300 rpm,
    # and that jump's upper side is the largest value over the turn: a jump, not a smooth peak
    m = load(MECHANISMS / "cam_roller_program.yaml")
    sw = sweep(m, np.radians(np.linspace(0.0, 360.0, 361)), level="acceleration")
    w = 300 * 2 * math.pi / 60
    peak = math.pi**2 * 0.030 * w**2 / (2 * math.radians(120) ** 2)
    acc = {e.quantity: e for e in sw.extremes}["acceleration.K"]
    assert acc.max_value == pytest.approx(peak, rel=1e-9)
    assert acc.max_jump is not None and sorted(acc.max_jump) == pytest.approx([0.0, peak], abs=1e-6 * peak)
    assert any("acceleration.K jumps at" in n for n in sw.notes)
    # a smooth quantity's extremes are not jumps: the roller's speed peaks inside its segments
    assert all(e.max_jump is None and e.min_jump is None for e in sw.extremes if e.quantity == "velocity.K")


def test_a_least_acceleration_held_over_a_dwell_is_the_dwells_not_a_jumps():
    # the follower is at rest over the programme's dwells (30° and 60°): |a| = 0 at every angle
    # of them, so the least magnitude, 0, is an extreme held over an interval; the jump at the
    # dwell's edge is the largest value's (33.3099 m/s², above), not the least's
    m = load(MECHANISMS / "cam_roller_program.yaml")
    sw = sweep(m, np.radians(np.linspace(0.0, 360.0, 361)), level="acceleration")
    acc = {e.quantity: e for e in sw.extremes}["acceleration.K"]
    assert acc.min_value == pytest.approx(0.0, abs=1e-12)
    assert acc.min_jump is None
    assert acc.max_jump is not None
    assert not any("its least value is that jump's" in n for n in sw.notes if n.startswith("acceleration.K "))


def test_no_extreme_of_a_four_bar_is_a_jump():
    sw = sweep(
        load(MECHANISMS / "four_bar.yaml"), np.radians(np.linspace(0.0, 360.0, 361)), level="acceleration"
    )
    assert [e.quantity for e in sw.extremes if e.max_jump or e.min_jump] == []


def test_oscillating_follower_turns_by_its_law_exactly():
    path = MECHANISMS / "cam_oscillating_roller.yaml"
    m = load(path)
    setup = cam_setup(m)
    sw = sweep(m, ANGLES, level="acceleration")
    assert sw.assembled.all()
    w, sigma = abs(setup.omega), setup.layout.sense
    s, v, a, inside = oracle(PROGRAMMES[path.name], sigma * ANGLES, w)
    arm = sw.links.index("arm")
    psi = np.unwrap(sw.link_angles[:, arm])
    # this arm lifts its roller away from the cam by turning clockwise (the file's geometry)
    assert np.max(np.abs(-(psi - psi.max()) - s)) <= 1e-9 * s.max()
    assert np.max(np.abs(-sw.omegas[:, arm] - v)) <= 1e-9 * np.max(np.abs(v))
    assert np.max(np.abs(-sw.alphas[inside, arm] - a[inside])) <= 1e-9 * np.max(np.abs(a))


def test_flat_faced_follower_rises_by_its_law_exactly():
    m = load(MECHANISMS / "cam_flat_follower.yaml")
    setup = cam_setup(m)
    sw = sweep(m, ANGLES, level="position")
    assert sw.assembled.all()
    s = oracle(PROGRAMMES["cam_flat_follower.yaml"], setup.layout.sense * ANGLES, 1.0)[0]
    disp = sw.displacement[:, 0]
    assert np.max(np.abs(disp - disp.min() - s)) <= 1e-9 * s.max()


def test_mechanical_advantage_of_a_cam_by_virtual_work_is_omega_over_v():
    # a force on the follower balanced by a torque on the cam: F v = T ω, so F/T = ω/v (1/m);
    # at 60° into the SHM rise v = πhω/(2β) sin(π/2) = 0.706858 m/s: ω/v = 31.4159/0.706858
    from mech.properties.advantage import mechanical_advantage

    m = load(MECHANISMS / "cam_roller_program.yaml")
    kin = solve(m, "velocity")
    adv = mechanical_advantage(m, kin, "K")
    w = 300 * 2 * math.pi / 60
    want = w / (math.pi * 0.030 * w / (2 * math.radians(120)))
    assert adv.value == pytest.approx(want, rel=1e-9)
    assert adv.by_virtual_work == pytest.approx(want, rel=1e-9)


def test_drawn_instant_is_the_files_turn_in_the_cams_sense():
    """drive.angle 60 on a clockwise cam: 60° turned clockwise, i.e. the cam's orientation is −60°."""
    m = load(MECHANISMS / "cam_roller_program.yaml")
    assert m.drives[0].angle == pytest.approx(-math.radians(60))
    assert cam_setup(m).angle == pytest.approx(math.radians(60))


# -- issue 21: the follower's own point, and programmes that broke sweeps ---------------------------


def test_naming_the_followers_point_on_its_slide_works_and_the_point_is_the_roller_centre():
    # K is the roller's centre (DESIGN § 1.2): on the follower's line x = −10 mm, at √(40² − 10²)
    # above the axis through O on the prime circle (r_p = 30 + 10 mm), plus the lift: at 60° into
    # a 120° cycloidal rise of 40 mm, x = ½: s = 20 mm, v = ω h/β (1 − cos π) = 2hω/β = 1.2 m/s
    m = loads(ROLLER_CAM_POINT_K, path="issue21.yaml")
    kin = solve(m, "velocity")
    assert kin.positions["K"] == pytest.approx((-0.010, math.sqrt(0.04**2 - 0.01**2) + 0.020), abs=1e-12)
    w = 300 * 2 * math.pi / 60
    assert kin.velocity("K") == pytest.approx((0.0, 2 * 0.040 * w / math.radians(120)), abs=1e-12)
    sw = sweep(m, ANGLES, level="velocity")
    assert sw.assembled.all()


@pytest.mark.parametrize("drawn", [0, 60, 200])
def test_a_cams_displacement_runs_from_the_paths_through_whatever_angle_it_is_drawn_at(drawn):
    # cli.md: displacement is measured along the path from its `through` (O here): the roller's
    # centre runs from the prime circle, 50 mm, to 50 + 30 mm, whatever the drive's drawn angle
    text = (MECHANISMS / "cam_roller_program.yaml").read_text().replace("angle: 60", f"angle: {drawn}")
    sw = sweep(loads(text, path="c.yaml"), ANGLES, level="position")
    disp = sw.displacement[:, 0]
    assert disp.min() == pytest.approx(0.050, abs=1e-12) and disp.max() == pytest.approx(0.080, abs=1e-12)


KNIFE_NO_DWELL = """\
units: {length: mm, angle: deg}
links: [frame, cam, follower]
joints:
  O: {type: revolute, links: [frame, cam], at: [0, 0]}
  S: {type: prismatic, links: [follower, frame], path: {through: [0, 0], angle: 90}}
  K: {type: cam, links: [cam, follower],
      program: {base_radius: 40, follower: FOLLOWER, EXTRA
                segments: [{rise: 25, over: 150, law: LAW}, {return: 25, over: 210, law: cycloidal}]}}
drive: {link: cam, angle: 0, rpm: 200, direction: ccw}
"""


@pytest.mark.parametrize(
    ("follower", "extra", "law"),
    [("knife", "", "cycloidal"), ("roller", "roller_radius: 12,", "uniform"), ("flat", "", "uniform")],
)
def test_programmes_that_broke_sweeps_sweep_by_their_law(follower, extra, law):
    # a knife edge with no dwell at 0°/360° crashed the sweep; a roller (and a flat face) on a
    # uniform-velocity rise stopped at 118° or sat 0.77 mm off the programme: each lift is the law's
    text = KNIFE_NO_DWELL.replace("FOLLOWER", follower).replace("EXTRA", extra).replace("LAW", law)
    m = loads(text, path="p.yaml")
    sw = sweep(m, np.radians(np.linspace(0.0, 360.0, 721)), level="velocity")
    assert sw.assembled.all()
    s = oracle(
        [("rise", 0.025, 150, law), ("return", 0.025, 210, "cycloidal")],
        np.radians(np.linspace(0, 360, 721)),
        1.0,
    )[0]
    disp = sw.displacement[:, 0]
    assert np.max(np.abs(disp - disp.min() - s)) <= 1e-9 * 0.025


def test_a_flat_faced_followers_acceleration_extremes_are_the_shm_peaks():
    # SHM rise and return of 20 mm over 120° each at 500 rpm: |a| ≤ π² h ω² / (2β²) = 61.685 m/s²,
    # reached at each segment's ends (it was reported as 180 and −6,100 m/s² through a fitted profile)
    text = (
        (MECHANISMS / "cam_flat_follower.yaml")
        .read_text()
        .replace("direction: cw", "rpm: 500, direction: cw")
    )
    sw = sweep(loads(text, path="f.yaml"), np.radians(np.linspace(0.0, 360.0, 721)), level="acceleration")
    w = 500 * 2 * math.pi / 60
    peak = math.pi**2 * 0.020 * w**2 / (2 * math.radians(120) ** 2)
    a = sw.accelerations[:, sw.points.index("K"), 1]
    assert np.max(np.abs(a)) == pytest.approx(peak, rel=1e-9)
