"""``mech cam``: the report, its JSON, the profile drawn to scale and the s–v–a–j diagrams."""

from __future__ import annotations

import json
import math
import re

import pytest
from tests.conftest import MECHANISMS

from mech.errors import InputError, UnsupportedError
from mech.loader import loads
from mech.pairs.cam.setup import cam_setup

EXAMPLE = str(MECHANISMS / "cam_roller_program.yaml")

HEAD = """\
units: {length: mm, angle: deg}
links: [frame, cam, follower]
joints:
  O: {type: revolute, links: [frame, cam], at: [0, 0]}
"""
PROGRAM = (
    "{base_radius: 40, follower: knife, segments: [{rise: 20, over: 180, law: cycloidal}, "
    "{return: 20, over: 180, law: cycloidal}]}"
)


def test_report_has_units_on_every_quantity(run):
    result = run("cam", EXAMPLE)
    assert result.exit_code == 0, result.output
    out = result.output
    for phrase in (
        "clockwise at 300 rpm",
        "roller radius 10 mm",
        "base circle 40 mm, prime circle 50 mm, stroke 30 mm",
        "v (m/s)",
        "a (m/s^2)",
        "j (m/s^3)",
        "pressure angle (°)",
        "ρ (mm)",
        "no undercut",
        "0.72 m/s",
    ):
        assert phrase in out, phrase
    # at the drive angle (60°, mid-rise): half the lift
    assert re.search(r"at θ = 60°: s = 15 mm, v = 0\.70686 m/s", out)


def test_json_has_the_documented_keys(run):
    result = run("cam", EXAMPLE, "--json", "--step", "90")
    d = json.loads(result.output)
    for key in (
        "joint",
        "follower_kind",
        "motion",
        "sense",
        "omega",
        "base_radius",
        "prime_radius",
        "stroke",
        "segments",
        "velocity_max",
        "acceleration_max",
        "jerk_max",
        "infinite_acceleration_at",
        "infinite_jerk_at",
        "pressure_angle_max",
        "least_radius",
        "undercut",
        "cusp",
        "at",
        "motion_table",
    ):
        assert key in d, key
    assert [r["theta"] for r in d["motion_table"]] == [0.0, 90.0, 180.0, 270.0]
    assert d["sense"] == "cw"
    assert d["omega"] == pytest.approx(10 * math.pi)
    assert d["infinite_jerk_at"] == pytest.approx([0.0, 120.0])  # SHM's ends
    assert d["infinite_acceleration_at"] == []


def test_rpm_and_direction_options_override_the_drive(run):
    d = json.loads(run("cam", EXAMPLE, "--json", "--rpm", "600", "--direction", "ccw").output)
    assert d["sense"] == "ccw"
    assert d["segments"][0]["v_max"] == pytest.approx(2 * 0.70686, rel=1e-5)


def test_profile_svg_is_drawn_to_its_stated_scale(run, tmp_path):
    out = tmp_path / "cam.svg"
    result = run("cam", EXAMPLE, "-o", str(out))
    assert result.exit_code == 0
    svg = out.read_text()
    scale = re.search(r"1 cm = ([\d.]+) mm", svg)
    assert scale is not None
    mm_per_page_mm = float(scale.group(1)) / 10
    pts = re.search(r'<polygon points="([^"]+)"[^>]*class="cam-profile"', svg)
    assert pts is not None
    xy = [tuple(map(float, p.split(","))) for p in pts.group(1).split()]
    ys = [y for _, y in xy]
    xs = [x for x, _ in xy]
    # the cam turned 60° clockwise from the start; its extent across any direction is at most
    # the largest radius twice, and the base circle (40 mm) fits inside it
    width = (max(xs) - min(xs)) * mm_per_page_mm
    height = (max(ys) - min(ys)) * mm_per_page_mm
    assert 80 - 0.1 <= width <= 140 + 0.1
    assert 80 - 0.1 <= height <= 140 + 0.1
    # the base circle's radius on the page is 40 mm at the stated scale
    base = re.search(r'<circle cx="[^"]+" cy="[^"]+" r="([\d.]+)"[^>]*class="base-circle"', svg)
    assert base is not None and float(base.group(1)) * mm_per_page_mm == pytest.approx(40, abs=0.01)
    assert 'class="roller"' in svg and 'class="pitch-curve"' in svg


def test_diagram_svg_has_s_v_a_j_panels(run, tmp_path):
    out = tmp_path / "sva.svg"
    assert run("cam", EXAMPLE, "--diagram", str(out)).exit_code == 0
    svg = out.read_text()
    for label in ("s", "v", "a", "j"):
        assert f'data-name="{label}"' in svg
    assert "cam angle θ (°)" in svg


def test_drawing_to_an_unknown_format_is_refused_with_exit_2(run, tmp_path):
    result = run("cam", EXAMPLE, "-o", str(tmp_path / "cam.pdf"))
    assert result.exit_code == 2 and ".svg or .png" in result.stderr


def test_file_without_a_programme_is_refused_with_exit_2(run):
    result = run("cam", str(MECHANISMS / "cam_follower.yaml"))
    assert result.exit_code == 2
    assert "cam_follower.yaml: error: this mechanism has no cam joint with a `program`" in result.stderr


def mech(follower_joint: str, k_extra: str = "", drive: str = "", program: str = PROGRAM, more: str = ""):
    text = (
        HEAD
        + follower_joint
        + f"  K: {{type: cam, links: [cam, follower], {k_extra}program: {program}}}\n"
        + more
        + drive
    )
    return loads(text, path="cam.yaml")


@pytest.mark.parametrize(("direction", "sign"), [("ccw", 1), ("cw", -1)])
def test_offset_is_positive_where_the_cams_surface_moves_with_the_rise(direction, sign):
    """Path through x = +12 mm, rising along +y: a ccw cam's surface there moves up."""
    m = mech(
        "  S: {type: prismatic, links: [follower, frame], path: {through: [12, -5], angle: 90}}\n",
        drive=f"drive: {{link: cam, rpm: 60, direction: {direction}}}\n",
    )
    setup = cam_setup(m)
    assert setup.layout.offset == pytest.approx(sign * 0.012)
    assert setup.layout.sense == sign


def test_programme_offset_that_disagrees_with_the_path_says_by_how_much():
    program = PROGRAM.replace("follower: knife,", "follower: knife, offset: 10,")
    m = mech(
        "  S: {type: prismatic, links: [follower, frame], path: {through: [12, 0], angle: 90}}\n",
        program=program,
    )
    with pytest.raises(InputError) as info:
        cam_setup(m)
    assert "0.01 m disagrees" in str(info.value) and "0.012 m" in str(info.value)


def test_oscillating_follower_needs_its_arm_length():
    m = mech(
        "  P: {type: revolute, links: [follower, frame], at: [90, 30]}\n",
        program=PROGRAM.replace("rise: 20", "rise: 15").replace("return: 20", "return: 15"),
    )
    with pytest.raises(InputError) as info:
        cam_setup(m)
    assert "has no length" in str(info.value)
    assert info.value.where is not None and info.value.where.line == 6


def test_oscillating_follower_near_hint_chooses_the_branch():
    for near, branch in (("[10, 40]", -1), ("[40, -20]", 1)):  # +1: left of P → O, here below
        m = mech(
            "  P: {type: revolute, links: [follower, frame], at: [90, 30]}\n",
            k_extra=f"near: {near}, ",
            more="lengths: {PK: 80}\n",
        )
        assert cam_setup(m).layout.branch == branch


def test_cam_joint_drawn_away_from_the_programmes_point_is_refused():
    m = mech(
        "  S: {type: prismatic, links: [follower, frame], path: {through: [0, 0], angle: 90}}\n",
        k_extra="at: [0, 45], ",
        drive="drive: {link: cam, angle: 90}\n",
    )
    with pytest.raises(InputError) as info:
        cam_setup(m)
    # at 90° into a 180° cycloidal rise of 20 mm the edge is at 40 + 10 = 50 mm
    assert "drawn 0.005 m from where the programme puts" in str(info.value)


def test_cam_joint_drawn_where_the_programme_puts_it_is_accepted():
    m = mech(
        "  S: {type: prismatic, links: [follower, frame], path: {through: [0, 0], angle: 90}}\n",
        k_extra="at: [0, 50], ",
        drive="drive: {link: cam, angle: 90}\n",
    )
    assert cam_setup(m).angle == pytest.approx(math.pi / 2)


def test_offset_beyond_the_prime_circle_is_refused():
    m = mech("  S: {type: prismatic, links: [follower, frame], path: {through: [45, 0], angle: 90}}\n")
    with pytest.raises(InputError) as info:
        cam_setup(m)
    assert "misses the cam" in str(info.value)


def test_two_cams_need_the_joint_option():
    text = (
        HEAD
        + "  O2: {type: revolute, links: [frame, cam2], at: [200, 0]}\n"
        + "  S: {type: prismatic, links: [follower, frame], path: {through: [0, 0], angle: 90}}\n"
        + "  S2: {type: prismatic, links: [f2, frame], path: {through: [200, 0], angle: 90}}\n"
        + f"  K: {{type: cam, links: [cam, follower], program: {PROGRAM}}}\n"
        + f"  K2: {{type: cam, links: [cam2, f2], program: {PROGRAM}}}\n"
    ).replace("links: [frame, cam, follower]", "links: [frame, cam, follower, cam2, f2]")
    m = loads(text)
    with pytest.raises(UnsupportedError):
        cam_setup(m)
    assert cam_setup(m, "K2").centre == pytest.approx((0.2, 0.0))
