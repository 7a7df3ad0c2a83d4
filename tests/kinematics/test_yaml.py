"""The solver fed through the loader: YAML text as users write it, in mm and deg."""

from __future__ import annotations

import io
import math

import pytest
from rich.console import Console

from mech.errors import GeometryError, InputError
from mech.kinematics import solve
from mech.loader import loads
from mech.options import OutputUnits, SolveOptions
from mech.render.kinematics import kinematics_json, kinematics_table
from oracles.four_bar import four_bar as closed_form

FOUR_BAR = """
name: Four-bar chain ABCD
units: {length: mm, angle: deg}
ground: frame
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0], radius: 5}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [100, 80]}
  D: {type: revolute, links: [rocker, frame], at: [150, 0]}
lengths: {AB: 40, BC: 150, CD: 80}
drive: {link: crank, angle: 60, rpm: 120, direction: cw}
points:
  E: {link: coupler, from: B, toward: C, distance: 50}
"""


def test_design_example_four_bar_from_yaml():
    kin = solve(loads(FOUR_BAR), "acceleration")
    w = -120 * 2 * math.pi / 60
    C, _, w4, _, a4 = closed_form(0.04, 0.15, 0.08, 0.15, math.radians(60), w)
    assert kin.positions["C"] == pytest.approx(tuple(C), abs=1e-13)
    assert kin.links["rocker"].omega == pytest.approx(w4, rel=1e-10)  # the file's 4.8 rad/s
    assert kin.links["rocker"].alpha == pytest.approx(a4, rel=1e-9)
    B = kin.positions["B"]
    e = ((C[0] - B[0]) / 0.15, (C[1] - B[1]) / 0.15)
    assert kin.positions["E"] == pytest.approx((B[0] + 0.05 * e[0], B[1] + 0.05 * e[1]), abs=1e-13)
    assert kin.rubbing("A") == pytest.approx(abs(w) * 0.005)
    assert not any("default rule" in n for n in kin.notes)  # near chose the branch


def test_cli_overrides_reach_the_solver():
    m = loads(FOUR_BAR)
    kin = solve(m, "velocity", SolveOptions(angle=math.radians(100), omega=10.0, direction="ccw"))
    _, _, w4, _, _ = closed_form(0.04, 0.15, 0.08, 0.15, math.radians(100), 10.0)
    assert kin.links["rocker"].omega == pytest.approx(w4, rel=1e-9)
    assert kin.drives[0].omega == 10.0 and kin.drives[0].angle == pytest.approx(math.radians(100))


def test_gap_is_reported_in_the_files_unit():
    text = FOUR_BAR.replace("CD: 80", "CD: 10")
    with pytest.raises(GeometryError, match=r"cannot close: B and D .* mm apart .* \(gap [0-9.]+ mm\)"):
        solve(loads(text), "position")


def test_disagreeing_drawing_reported_in_mm():
    text = FOUR_BAR.replace("near: [100, 80]", "at: [160, 80]")
    with pytest.raises(InputError, match=r"length CD = 80 mm but the drawing gives 80.6226 mm"):
        solve(loads(text), "position")


# B, the lever's far end, drawn 60 cm from O1 on the line O1-A (A from the crank at 30°).
_A = (12 * math.cos(math.radians(30)), 30 + 12 * math.sin(math.radians(30)))
_B = tuple(60 * c / math.hypot(*_A) for c in _A)
SLOTTED = f"""
name: Crank and slotted lever
units: {{length: cm}}
links: [frame, crank, block, lever]
joints:
  O2: {{type: revolute, links: [frame, crank], at: [0, 30]}}
  A: {{type: revolute, links: [crank, block]}}
  slot: {{type: prismatic, links: [block, lever], path: {{through: O1, toward: B}}}}
  O1: {{type: revolute, links: [lever, frame], at: [0, 0]}}
lengths: {{O2A: 12}}
points:
  B: {{link: lever, at: [{_B[0]!r}, {_B[1]!r}]}}
drive: {{link: crank, angle: 30, rpm: 600, direction: ccw}}
"""


def test_slotted_lever_from_yaml_has_coriolis_two_omega_v():
    kin = solve(loads(SLOTTED), "acceleration")
    w = kin.links["lever"].omega
    v = kin.sliding("slot")
    assert math.hypot(*kin.coriolis("slot")) == pytest.approx(2 * abs(w * v), rel=1e-12)
    A, O1 = kin.positions["A"], kin.positions["O1"]
    assert math.hypot(*kin.velocity("A")) == pytest.approx(20 * math.pi * 0.12, rel=1e-12)
    # B on the ray O1 → A, 60 cm out
    assert math.dist(kin.positions["B"], O1) == pytest.approx(0.6, rel=1e-12)
    cross = (A[0] - O1[0]) * (kin.positions["B"][1] - O1[1]) - (A[1] - O1[1]) * (
        kin.positions["B"][0] - O1[0]
    )
    assert cross == pytest.approx(0.0, abs=1e-14)


def test_table_and_json_render_every_section():
    kin = solve(loads(SLOTTED), "acceleration")
    units = OutputUnits.named("mm")
    data = kinematics_json(kin, units=units)
    assert data["units"]["velocity"] == "mm/s"
    slot = data["sliders"][0]
    assert slot["sliding"] == pytest.approx(kin.sliding("slot") * 1000)
    assert slot["coriolis_magnitude"] == pytest.approx(math.hypot(*kin.coriolis("slot")) * 1000)
    labels = {r["label"] for r in data["relative"]}
    assert "o2a" in labels and "o1b" in labels
    out = io.StringIO()
    kinematics_table(kin, Console(file=out, width=160, color_system=None), units=units)
    text = out.getvalue()
    for heading in ("Links", "Points", "Relative motion", "Sliders and slots", "Coriolis", "mm/s²", "ccw"):
        assert heading in text
    assert "…" not in text


def test_json_at_position_level_has_nulls_not_errors():
    data = kinematics_json(solve(loads(FOUR_BAR), "position"), units=OutputUnits())
    assert data["points"][0]["velocity"] is None and data["relative"] == []
    assert data["links"]["crank"]["angle"] == pytest.approx(60.0)
