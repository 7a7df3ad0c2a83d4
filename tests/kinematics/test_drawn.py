"""A drawing is good to its precision; the numbers a file gives are exact.

The notes' crank and slotted lever (mechanisms/crank_slotted_lever.yaml) draws
the lever's far end B rounded to 1e-3 mm, and gives the crank angle exactly.
The exact data must win: the crank sits at exactly 35°, and the lever's ω is
the closed form's to 1e-9, not the compromise of a least-squares fit.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from cli_runner import assert_bad_input, mech
from mech.errors import InputError
from mech.kinematics import solve
from mech.loader import load, loads
from mechanism_texts import DRAWN_FOUR_BAR, FIVE_BAR_ONE_DRIVE
from oracles.four_bar import four_bar

FILE = Path(__file__).resolve().parents[2] / "mechanisms" / "crank_slotted_lever.yaml"


def test_rounded_drawing_yields_to_the_exact_crank_angle():
    kin = solve(load(FILE), level="velocity")
    # closed form: O1 at the origin, O2 = (0, 0.5) m, crank 0.12 m at 35° turning 600 rpm ccw
    w2, r, th = 600 * 2 * math.pi / 60, 0.12, math.radians(35)
    ax, ay = r * math.cos(th), 0.5 + r * math.sin(th)
    va = (-w2 * r * math.sin(th), w2 * r * math.cos(th))
    d = math.hypot(ax, ay)
    n = (-ay / d, ax / d)  # perpendicular to the lever O1A
    omega_lever = (va[0] * n[0] + va[1] * n[1]) / d
    assert kin.links["crank"].angle == pytest.approx(th, abs=1e-11)
    assert kin.links["lever"].omega == pytest.approx(omega_lever, rel=1e-9)
    assert kin.positions["A"] == pytest.approx((ax, ay), rel=1e-11, abs=1e-12)
    assert any("drawn positions moved" in note for note in kin.notes)


def test_a_drawing_far_from_the_numbers_is_refused_with_the_point():
    text = FILE.read_text().replace(
        "B: {link: lever, at: [102.170, 591.237]}", "B: {link: lever, at: [140, 591.237]}"
    )
    with pytest.raises(InputError) as info:
        solve(loads(text, path="lever.yaml"), level="velocity")
    problem = info.value.problems[0]
    assert problem.message.startswith("B is drawn at")
    assert problem.where is not None and problem.where.line > 0


def test_too_few_drives_says_how_many_are_needed():
    # a five-bar (Kutzbach: n = 3(5 − 1) − 2·5 = 2) with one drive
    text = FIVE_BAR_ONE_DRIVE
    from mech.errors import MechError

    with pytest.raises(MechError) as info:
        solve(loads(text, path="five.yaml"), level="velocity")
    assert "2 degrees of freedom" in str(info.value) and "1 drive" in str(info.value)
    assert "2 of them" in (info.value.hint or "")


def test_an_unplaced_ground_pivot_is_named():
    text = FILE.parent.joinpath("four_bar.yaml").read_text()
    text = text.replace(
        "A: {type: revolute, links: [frame, crank], at: [0, 0]}", "A: {type: revolute, links: [frame, crank]}"
    )
    from mech.errors import GeometryError

    with pytest.raises(GeometryError) as info:
        solve(loads(text, path="fb.yaml"), level="position")
    assert str(info.value.problems[0].message).startswith("A is on the ground link frame but not placed")
    assert info.value.where is not None and info.value.where.line == 19


def test_sliding_acceleration_of_the_block_on_the_lever():
    # s = |O1A| along the lever: ṡ = (A·Ȧ)/|A|, s̈ = (Ȧ·Ȧ + A·Ä)/|A| − (A·Ȧ)²/|A|³ (crank at constant ω)
    kin = solve(load(FILE), level="acceleration")
    w, r, th = 600 * 2 * math.pi / 60, 0.12, math.radians(35)
    a = (r * math.cos(th), 0.5 + r * math.sin(th))
    ad = (-w * r * math.sin(th), w * r * math.cos(th))
    add = (-w * w * r * math.cos(th), -w * w * r * math.sin(th))
    n = math.hypot(*a)
    dot = a[0] * ad[0] + a[1] * ad[1]
    s_dot = dot / n
    s_ddot = (ad[0] ** 2 + ad[1] ** 2 + a[0] * add[0] + a[1] * add[1]) / n - dot**2 / n**3
    assert kin.sliding("slot") == pytest.approx(s_dot, rel=1e-9)
    assert kin.sliding_acceleration("slot") == pytest.approx(s_ddot, rel=1e-9)


def test_a_gear_pairs_unplaced_second_pivot_is_named(run, write):
    path = write(
        """
units: {length: mm, angle: deg}
links: [frame, pinion, wheel]
joints:
  O1: {type: revolute, links: [frame, pinion], at: [0, 0]}
  O2: {type: revolute, links: [frame, wheel]}
  mesh: {type: gear, links: [pinion, wheel], teeth: [20, 40], module: 5}
drive: {link: pinion, rpm: 1200, direction: cw}
"""
    )
    for command in ("position", "velocity", "icentres", "sweep"):
        result = run(command, str(path))
        assert result.exit_code == 2, command
        assert f"{path.name}:6:3: error: O2 is on the ground link frame but not placed" in result.stderr


# -- through the command line as a user runs it (cli_runner: tracebacks shown) -----------
# DRAWN_FOUR_BAR draws B at 90 deg from A (at [0, 1]); AB 1, BC 2, CD 1.
def test_a_drive_angle_opposite_to_the_drawing_is_an_error_saying_by_how_much(write):
    """DESIGN.md: a drive angle given with a drawing must agree with it; 270 vs 90 is off by 180."""
    f = write(DRAWN_FOUR_BAR.format(ab=1, angle=270))
    p = mech("velocity", str(f))
    assert p.returncode == 2, p.stdout
    assert "180" in p.stderr


def test_an_angle_override_does_not_excuse_a_drive_angle_opposite_to_the_drawing(write):
    """The file contradicts itself whatever --angle asks (once B landed at 280 deg, silently)."""
    f = write(DRAWN_FOUR_BAR.format(ab=1, angle=270))
    p = mech("position", "--json", str(f), "--angle", "100")
    assert_bad_input(p, f)
    assert f"{f}:8:8:" in p.stderr and "off by 180°" in p.stderr
    assert p.stdout == ""


def test_a_drawing_within_drawing_precision_is_accepted_and_one_beyond_it_refused(write):
    """The figure is 2 m (BC): AB = 1.001 m where B is drawn 1 m from A is 5e-4 of the size,
    within drawing precision (1e-3): B moves 1 mm along the crank, with the note. AB = 1.01 m
    is 5e-3 of the size: refused at the length. (1.001 was refused while moving drawn points
    were held to 1e-6 of the size, the rule for exact data.)"""
    ok = mech("velocity", str(write(DRAWN_FOUR_BAR.format(ab="1.0000001", angle=90), "ok.yaml")))
    assert ok.returncode == 0, ok.stderr
    moved = mech("velocity", str(write(DRAWN_FOUR_BAR.format(ab="1.001", angle=90), "moved.yaml")))
    assert moved.returncode == 0, moved.stderr
    assert "note: drawn positions moved by up to 0.001 m (B)" in moved.stdout
    f = write(DRAWN_FOUR_BAR.format(ab="1.01", angle=90), "bad.yaml")
    bad = mech("velocity", str(f))
    assert_bad_input(bad, f)
    assert f"{f}:7:11: error: length AB = 1.01 m but the drawing gives 1 m (off by 0.01 m)" in bad.stderr


def test_a_length_disagreeing_with_the_drawing_is_located_at_the_length(write):
    """AB = 1.5 m where the drawing gives 1 m: file:line:col and the 0.5 m it is off by."""
    f = write(DRAWN_FOUR_BAR.format(ab=1.5, angle=90))
    p = mech("velocity", str(f))
    assert_bad_input(p, f)
    assert "0.5" in p.stderr


def test_a_drawing_copied_to_one_decimal_is_accepted_and_the_numbers_win():
    # B copied as (102.2, 591.2) mm instead of (102.170, 591.237): 0.035 mm off on a figure of
    # about 600 mm (6e-5 of its size, within drawing precision 1e-3). It was refused (1e-6).
    # The exact crank angle and lengths still decide: the closed form of the first test.
    text = FILE.read_text().replace(
        "B: {link: lever, at: [102.170, 591.237]}", "B: {link: lever, at: [102.2, 591.2]}"
    )
    kin = solve(loads(text, path="lever.yaml"), level="velocity")
    w2, r, th = 600 * 2 * math.pi / 60, 0.12, math.radians(35)
    ax, ay = r * math.cos(th), 0.5 + r * math.sin(th)
    d = math.hypot(ax, ay)
    omega_lever = (-w2 * r * math.sin(th) * -ay / d + w2 * r * math.cos(th) * ax / d) / d
    assert kin.links["crank"].angle == pytest.approx(th, abs=1e-11)
    assert kin.links["lever"].omega == pytest.approx(omega_lever, rel=1e-9)
    assert any("drawn positions moved" in n and "B" in n for n in kin.notes)


# -- Khurmi's four-bar (mechanisms/four_bar.yaml) with its moving joints copied to two decimals -----
# AB = 40 mm at 60°, BC = 150, CD = 80, A = (0, 0), D = (150, 0) mm; the book's figure has C above AD.
FOUR_BAR = FILE.parent / "four_bar.yaml"
_B_LINE = "B: {type: revolute, links: [crank, coupler]}"
_C_LINE = "C: {type: revolute, links: [coupler, rocker], near: [160, 80]}"


def _four_bar_drawn(b: str = "[20.00, 34.64]", c: str = "[163.33, 78.88]") -> str:
    text = FOUR_BAR.read_text()
    assert _B_LINE in text and _C_LINE in text
    text = text.replace(_B_LINE, f"B: {{type: revolute, links: [crank, coupler], at: {b}}}")
    return text.replace(_C_LINE, f"C: {{type: revolute, links: [coupler, rocker], at: {c}}}")


def test_a_four_bar_drawn_to_two_decimals_is_moved_to_where_the_exact_lengths_put_it():
    """B and C copied to 0.01 mm were refused ("length CD = 80 mm but the drawing gives
    79.9984"): the lengths were checked against the drawing at 1e-6 of the size. Now the
    exact data win: B and C land where the circles about B and D meet (oracles.four_bar),
    and the note says how far the drawing was moved (C: |drawn − exact|, by hand)."""
    kin = solve(loads(_four_bar_drawn(), path="four_bar.yaml"), level="velocity")
    w2 = -120 * 2 * math.pi / 60  # 120 rpm clockwise
    c_mm, _w3, w4, _a3, _a4 = four_bar(40, 150, 80, 150, math.radians(60), w2)
    b_mm = (40 * math.cos(math.radians(60)), 40 * math.sin(math.radians(60)))
    assert kin.positions["B"] == pytest.approx((b_mm[0] / 1000, b_mm[1] / 1000), rel=1e-12, abs=1e-15)
    assert kin.positions["C"] == pytest.approx((c_mm[0] / 1000, c_mm[1] / 1000), rel=1e-12)
    assert kin.links["crank"].angle == pytest.approx(math.radians(60), abs=1e-12)
    assert kin.links["rocker"].omega == pytest.approx(w4, rel=1e-9)
    moved_c = math.hypot(163.33 - c_mm[0], 78.88 - c_mm[1])  # 0.00337 mm; B moves 0.00102 mm
    assert moved_c > math.hypot(20.00 - b_mm[0], 34.64 - b_mm[1])
    assert f"drawn positions moved by up to {moved_c:.6g} mm (C)" in " ".join(kin.notes)


def test_a_four_bar_drawn_to_two_decimals_passes_the_command_line_with_the_note(write):
    f = write(_four_bar_drawn(), "four_bar.yaml")
    p = mech("velocity", str(f))
    assert p.returncode == 0, p.stderr
    assert "note: drawn positions moved by up to 0.00336744 mm (C)" in p.stdout  # as above


def test_a_four_bar_drawn_one_percent_off_is_refused_at_the_length(write):
    """C drawn 1.5 mm (1% of the 150 mm figure) above where the lengths put it: CD measures
    hypot(13.33, 80.38) = 81.4778 mm on the drawing, beyond drawing precision (0.15 mm)."""
    f = write(_four_bar_drawn(c="[163.33, 80.38]"), "four_bar.yaml")
    p = mech("velocity", str(f))
    assert_bad_input(p, f)
    assert f"{f}:23:28: error: length CD = 80 mm but the drawing gives 81.4778 mm" in p.stderr


def test_a_length_between_ground_pivots_off_by_1e_5_of_the_size_is_refused(write):
    """Two ground pivots are exact data, not a drawing: AD = 150 mm with D drawn at 150.0015 mm
    (1e-5 of the size) is refused, while B and C, drawn to two decimals, are moved."""
    text = _four_bar_drawn().replace("at: [150, 0]", "at: [150.0015, 0]")
    text = text.replace("lengths: {AB: 40,", "lengths: {AD: 150, AB: 40,")
    f = write(text, "four_bar.yaml")
    p = mech("velocity", str(f))
    assert_bad_input(p, f)
    assert f"{f}:23:11: error: length AD = 150 mm but the drawing gives" in p.stderr
    assert "(off by 0.0015 mm)" in p.stderr
    assert p.stderr.count("error:") == 1  # not AB, BC, CD: their drawn ends may move


def test_a_slider_crank_drawn_to_0_01_mm_is_moved_onto_its_lengths():
    """Khurmi's slider crank (mechanisms/slider_crank.yaml): OA = 150 mm at 135°, AB = 600 mm,
    the piston behind O on the x axis: A = r(cos θ, sin θ), x_B = r cos θ − √(l² − r² sin² θ)
    (by hand), both drawn rounded to 0.01 mm (OA then measures 150.0055 mm: it was refused)."""
    r, rod, th = 150.0, 600.0, math.radians(135)
    a = (r * math.cos(th), r * math.sin(th))
    x_b = a[0] - math.sqrt(rod**2 - a[1] ** 2)  # −696.617 mm
    text = FILE.parent.joinpath("slider_crank.yaml").read_text()
    joints = {
        "A: {type: revolute, links: [crank, rod]}": f"A: {{type: revolute, links: [crank, rod], at: [{a[0]:.2f}, {a[1]:.2f}]}}",
        "B: {type: revolute, links: [rod, piston], near: [-700, 0]}": f"B: {{type: revolute, links: [rod, piston], at: [{x_b:.2f}, 0]}}",
    }
    for old, new in joints.items():
        assert old in text
        text = text.replace(old, new)
    kin = solve(loads(text, path="slider_crank.yaml"), level="velocity")
    assert kin.positions["A"] == pytest.approx((a[0] / 1000, a[1] / 1000), rel=1e-12)
    assert kin.positions["B"] == pytest.approx((x_b / 1000, 0.0), rel=1e-12, abs=1e-15)
    assert any("drawn positions moved" in n for n in kin.notes)


@pytest.mark.parametrize("name", ["stephenson_six_bar.yaml", "watt_six_bar.yaml"])
def test_a_six_bar_drawn_to_two_decimals_solves_as_its_lengths_alone(name):
    """Every moving joint copied to 0.01 mm from the file's own solution (lengths, drive angle,
    near): the drawing only chooses the branch, so positions and ω are those of the file
    without it, to rounding."""
    text = FILE.parent.joinpath(name).read_text()
    exact = solve(loads(text, path=name), level="velocity")
    for j in loads(text, path=name).joints:
        if j.place.at is None:
            x, y = (round(v * 1000, 2) for v in exact.positions[j.name])
            text, count = re.subn(
                rf"^(  {j.name}: \{{.*?)(, near: \[[^]]*\])?\}}$", rf"\1, at: [{x}, {y}]}}", text, flags=re.M
            )
            assert count == 1, j.name
    kin = solve(loads(text, path=name), level="velocity")
    for n, xy in exact.positions.items():
        assert kin.positions[n] == pytest.approx(xy, rel=1e-12, abs=1e-15), n
    for link, state in exact.links.items():
        assert kin.links[link].omega == pytest.approx(state.omega, rel=1e-12, abs=1e-15), link
    assert any("drawn positions moved" in n for n in kin.notes)


def test_a_file_that_places_nothing_is_refused_at_its_first_ground_joint(write):
    f = write(
        "links: [frame, crank]\njoints:\n  A: {type: revolute, links: [frame, crank]}\n"
        "drive: {link: crank, angle: 0, rpm: 10}\n"
    )
    p = mech("velocity", str(f))
    assert_bad_input(p, f)
    assert f"{f}:3:3: error: positions need geometry" in p.stderr and "at: [x, y]" in p.stderr
