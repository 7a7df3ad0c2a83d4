"""A drawing is good to its precision; the numbers a file gives are exact.

The notes' crank and slotted lever (mechanisms/crank_slotted_lever.yaml) draws
the lever's far end B rounded to 1e-3 mm, and gives the crank angle exactly.
The exact data must win: the crank sits at exactly 35°, and the lever's ω is
the closed form's to 1e-9, not the compromise of a least-squares fit.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from cli_runner import assert_bad_input, mech
from mech.errors import InputError
from mech.kinematics import solve
from mech.loader import load, loads
from mechanism_texts import DRAWN_FOUR_BAR

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
    text = """
units: {length: mm}
links: [frame, a, b, c, d]
joints:
  A: {type: revolute, links: [frame, a], at: [0, 0]}
  B: {type: revolute, links: [a, b]}
  C: {type: revolute, links: [b, c], near: [60, 80]}
  D: {type: revolute, links: [c, d]}
  E: {type: revolute, links: [d, frame], at: [120, 0]}
lengths: {AB: 40, BC: 70, CD: 70, DE: 40}
drive: {link: a, angle: 80, rpm: 60}
"""
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


def test_a_drawing_agreeing_to_1e_7_is_accepted_and_one_off_by_1e_3_refused(write):
    ok = mech("velocity", str(write(DRAWN_FOUR_BAR.format(ab="1.0000001", angle=90), "ok.yaml")))
    assert ok.returncode == 0, ok.stderr
    bad = mech("velocity", str(write(DRAWN_FOUR_BAR.format(ab="1.001", angle=90), "bad.yaml")))
    assert bad.returncode == 2 and "0.001" in bad.stderr and "Traceback" not in bad.stderr


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
