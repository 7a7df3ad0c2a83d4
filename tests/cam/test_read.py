"""A cam joint's ``program`` as the file writes it: read in the file's units, every mistake located."""

from __future__ import annotations

import math

import pytest

from mech.errors import InputError
from mech.loader import loads
from mech.pairs.cam.setup import cam_setup, joint_program

HEAD = """\
units: {length: mm, angle: deg}
links: [frame, cam, follower]
joints:
  O: {type: revolute, links: [frame, cam], at: [0, 0]}
"""
SLIDE = "  S: {type: prismatic, links: [follower, frame], path: {through: [0, 0], angle: 90}}\n"
PIVOT = "  P: {type: revolute, links: [follower, frame], at: [90, 30]}\n"


def cam(program: str, follower_joint: str = SLIDE) -> str:
    return HEAD + follower_joint + f"  K: {{type: cam, links: [cam, follower], program: {program}}}\n"


GOOD = (
    "{base_radius: 40, follower: roller, roller_radius: 10, offset: 0, "
    "segments: [{rise: 30, over: 120, law: shm}, {dwell: 30}, "
    "{return: 30, over: 150, law: cycloidal}, {dwell: 60}]}"
)


def problems(text: str) -> list[tuple[int, int, str]]:
    with pytest.raises(InputError) as info:
        loads(text, path="cam.yaml")
    return [(p.where.line, p.where.column, p.message) for p in info.value.problems if p.where]


def test_programme_is_read_in_the_files_units():
    prog = cam_setup(loads(cam(GOOD))).layout.program
    assert prog.base_radius == pytest.approx(0.040)
    assert prog.roller_radius == pytest.approx(0.010)
    assert prog.motion == "translating"
    assert [s.kind for s in prog.segments] == ["rise", "dwell", "return", "dwell"]
    assert prog.segments[0].lift == pytest.approx(0.030)
    assert prog.segments[2].over == pytest.approx(math.radians(150))
    assert prog.segments[2].law == "cycloidal"


def test_oscillating_followers_rise_is_an_angle():
    text = cam(
        "{base_radius: 40, follower: knife, segments: [{rise: 20, over: 180, law: shm}, "
        "{return: 20, over: 180, law: shm}]}",
        PIVOT,
    )
    raw = joint_program(loads(text).joint("K"))
    assert raw is not None and raw.motion is None  # not known until the follower's joint is
    assert raw.segments[0].as_length == pytest.approx(0.020)
    assert raw.segments[0].as_angle == pytest.approx(math.radians(20))
    prog = cam_setup(loads(text + "lengths: {PK: 80}\n")).layout.program
    assert prog.motion == "oscillating"
    assert prog.segments[0].lift == pytest.approx(math.radians(20))


def test_rise_with_a_unit_of_the_wrong_kind_is_located_at_its_segment():
    text = cam(
        '{base_radius: 40, follower: knife, segments: [{rise: "20 deg", over: 180, law: shm}, '
        '{return: "20 deg", over: 180, law: shm}]}'
    )
    m = loads(text)  # a rise in degrees is fine until the follower turns out to slide
    with pytest.raises(InputError) as info:
        cam_setup(m)
    lines = {(p.where.line, p.where.column) for p in info.value.problems}
    assert len(info.value.problems) == 2
    for line, col in lines:
        assert text.splitlines()[line - 1][col - 1 :].startswith(("{rise", "{return"))
    assert "this follower slides: its rise is a length" in info.value.problems[0].message


def test_segments_short_of_a_turn_are_reported_with_what_to_add():
    text = cam(GOOD.replace("{dwell: 60}", "{dwell: 50}"))
    ((line, _col, message),) = problems(text)
    assert line == 6 and "350°, not 360°" in message


def test_return_further_than_the_rise_is_located_at_the_return():
    text = cam(GOOD.replace("{return: 30,", "{return: 35,"))
    found = problems(text)
    assert len(found) == 1
    line, col, message = found[0]
    assert text.splitlines()[line - 1][col - 1 :].startswith("{return: 35")
    assert "only risen" in message


def test_follower_left_above_its_start_is_reported():
    text = cam(GOOD.replace("{return: 30,", "{return: 20,"))
    ((_, _, message),) = problems(text)
    assert "ends the turn" in message


@pytest.mark.parametrize(
    ("change", "start", "words"),
    [
        (("law: shm", "law: harmonic"), "harmonic", "unknown motion law"),
        (("follower: roller", "follower: needle"), "needle", "unknown follower"),
        (("roller_radius: 10, ", ""), "roller", "needs `roller_radius`"),
        (("over: 120, law: shm", "law: shm"), "{rise", "needs `over`"),
        (("{dwell: 30}", "{dwell: 30, rise: 5}"), "{dwell", "not rise and dwell together"),
        (("base_radius: 40", "base_radius: -40"), "-40", "greater than zero"),
        (("offset: 0", "offsett: 0"), "offsett", "unknown key"),
    ],
)
def test_each_mistake_in_a_programme_is_located(change, start, words):
    text = cam(GOOD.replace(*change))
    found = problems(text)
    assert any(words in m for _, _, m in found), found
    line, col, _ = next(f for f in found if words in f[2])
    assert text.splitlines()[line - 1][col - 1 :].startswith(start)


def test_follower_with_neither_slide_nor_pivot_is_refused_at_the_cam_joint():
    text = cam(GOOD, "  B: {type: revolute, links: [follower, cam]}\n")
    with pytest.raises(InputError) as info:
        cam_setup(loads(text))
    assert "must either slide" in str(info.value)
    assert info.value.where is not None and info.value.where.line == 6


def test_offset_on_an_oscillating_roller_is_refused():
    text = cam(GOOD, PIVOT) + "lengths: {PK: 80}\n"
    with pytest.raises(InputError) as info:
        cam_setup(loads(text))
    assert "`offset` belongs to a translating follower" in str(info.value)


def test_program_on_a_joint_that_is_not_a_cam_is_an_unknown_key():
    text = (
        HEAD
        + "  S: {type: prismatic, links: [follower, frame], path: {through: [0, 0], angle: 90}, program: {}}\n"
    )
    found = problems(text)
    assert any("unknown key 'program'" in m for _, _, m in found)


def test_bad_programme_through_the_command_line_exits_2_with_file_line_col(run, write):
    path = write(cam(GOOD.replace("{dwell: 60}", "{dwell: 70}")))
    result = run("cam", str(path))
    assert result.exit_code == 2
    assert f"{path}:6:" in result.stderr
    assert "370°, not 360°" in result.stderr
    assert "Traceback" not in result.stderr
