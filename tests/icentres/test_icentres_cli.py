"""``mech icentres``: the table, the JSON, the errors."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from cli_runner import assert_bad_input, mech, no_traceback, strict_json
from mechanism_texts import GEARS, TOGGLE_FOUR_BAR
from oracles.field_cases import IC_CASES

MECHANISMS = Path(__file__).resolve().parents[2] / "mechanisms"


FOUR_BAR = str(MECHANISMS / "four_bar.yaml")
SLIDER = str(MECHANISMS / "slider_crank.yaml")


def test_icentres_table_shows_the_count_methods_and_omegas(run):
    result = run("icentres", FOUR_BAR, "--units", "mm")
    assert result.exit_code == 0, result.stderr
    out = result.output
    assert "N = n(n − 1)/2 = 4·3/2 = 6" in out
    assert "Kennedy: I12–I23 ∩ I14–I34" in out and "pin A" in out
    assert "212.055" in out and "367.289" in out  # I13 in mm
    assert "6 of 6 agree" in out
    assert "4.78457 cw" in out  # the rocker's ω by I-centres and by the solver


def test_icentres_at_infinity_prints_a_direction(run):
    result = run("icentres", SLIDER)
    assert result.exit_code == 0
    assert "∞ at 90°" in result.output and "slider P: ⟂ path at infinity" in result.output


def test_a_parallelogram_s_centres_at_infinity_point_along_its_links_with_no_rounding_shown(run, write):
    # AB = CD = 40, AD = BC = 150 mm, crank at 60°: the coupler translates, so I13 is at infinity
    # along the crank (60°); crank and rocker stay parallel, so I24 is at infinity along AD (0°),
    # found from rounded velocities 1e-14° off it: shown as 0°, every direction in [0°, 180°)
    path = write(
        "units: {length: mm, angle: deg}\nlinks: [frame, crank, coupler, rocker]\njoints:\n"
        "  A: {type: revolute, links: [frame, crank], at: [0, 0]}\n"
        "  B: {type: revolute, links: [crank, coupler]}\n"
        "  C: {type: revolute, links: [coupler, rocker], near: [180, 35]}\n"
        "  D: {type: revolute, links: [rocker, frame], at: [150, 0]}\n"
        "lengths: {AB: 40, BC: 150, CD: 40}\ndrive: {link: crank, angle: 60, rpm: 60}\n"
    )
    result = run("icentres", str(path))
    assert "∞ at 60°" in result.output and "∞ at 0°" in result.output, result.output
    data = json.loads(run("icentres", str(path), "--json").output)
    angles = {c["name"]: c["angle"] for c in data["icentres"] if c["at_infinity"]}
    assert angles == {"I13": pytest.approx(60.0, abs=1e-9), "I24": 0.0}


def test_icentres_json_structure(run):
    result = run("icentres", SLIDER, "--json", "--units", "mm", "--angle", "135", "--rpm", "300")
    data = json.loads(result.output)
    assert data["count"] == 6 and data["units"]["length"] == "mm"
    assert [lk["name"] for lk in data["links"]] == ["frame", "crank", "rod", "piston"]
    by_name = {c["name"]: c for c in data["icentres"]}
    assert by_name["I14"]["at_infinity"] is True and by_name["I14"]["point"] is None
    assert by_name["I14"]["angle"] == 90.0
    assert by_name["I12"]["point"] == [0.0, 0.0] and by_name["I12"]["primary"] is True
    assert by_name["I13"]["method"] == "Kennedy: I12–I23 ∩ I14–I34" and by_name["I13"]["step"] == 1
    assert data["max_check"] < 1e-9
    rod = next(o for o in data["omega"] if o["link"] == "rod")
    assert abs(rod["by_icentres"] - rod["solver"]) < 1e-9 * abs(rod["solver"])


def test_icentres_bad_file_exits_2_without_traceback(run, write):
    path = write("links: [frame, crank]\njoints:\n  A: {type: revolute, links: [frame, crankk]}\n")
    result = run("icentres", str(path))
    assert result.exit_code == 2
    assert "unknown link 'crankk'" in result.stderr and "Traceback" not in result.stderr


def test_icentres_without_geometry_orders_the_centres_without_coordinates(run):
    """A file with nothing placed (four_bar_dof.yaml counts only): the centres by name and
    Kennedy's order, no coordinates; --explain, which draws lines in the plane, needs positions."""
    result = run("icentres", str(MECHANISMS / "four_bar_dof.yaml"))
    assert result.exit_code == 0
    assert "4 primary by inspection, 2 by Kennedy's theorem, 0 not reached" in result.stdout
    refused = run("icentres", "--explain", str(MECHANISMS / "four_bar_dof.yaml"))
    assert refused.exit_code == 2
    assert "positions need geometry" in refused.stderr and "Traceback" not in refused.stderr


# -- through the command line as a user runs it (cli_runner: in process, tracebacks shown) --
def test_icentres_units_mm_scale_points_not_directions_or_omega(tmp_path):
    """--units mm multiplies every finite point by 1000 and leaves directions and ω alone."""
    m = tmp_path / "m.yaml"
    m.write_text(IC_CASES["slotted_lever"][0], encoding="utf-8")
    si = strict_json(mech("icentres", "--json", str(m)).stdout)
    mm = strict_json(mech("icentres", "--json", "--units", "mm", str(m)).stdout)
    assert mm["units"]["length"] == "mm"
    for a, b in zip(si["icentres"], mm["icentres"], strict=True):
        if a["point"] is None:
            assert b["point"] is None and b["direction"] == pytest.approx(a["direction"])
        else:
            assert b["point"] == pytest.approx([1000 * v for v in a["point"]], rel=1e-12, abs=1e-9)
    assert [o["by_icentres"] for o in mm["omega"]] == pytest.approx([o["by_icentres"] for o in si["omega"]])


def test_icentres_of_coincident_ground_pivots_turn_as_one_body_and_a_toggle_is_refused(tmp_path):
    """Pivots A = D: crank, coupler, rocker turn as one body about A (exit 0); a toggle is exit 2."""
    m = tmp_path / "c.yaml"
    m.write_text(
        """\
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler], at: [1, 0]}
  C: {type: revolute, links: [coupler, rocker], at: [0.5, 1]}
  D: {type: revolute, links: [rocker, frame], at: [0, 0]}
drive: {link: crank, omega: 10}
""",
        encoding="utf-8",
    )
    p = mech("icentres", "--json", str(m))
    no_traceback(p)
    assert p.returncode == 0
    d = strict_json(p.stdout)
    by = {i["name"]: i for i in d["icentres"]}
    assert by["I13"]["point"] == pytest.approx([0, 0], abs=1e-12)  # the body turns about A = D
    assert all(o["by_icentres"] == pytest.approx(10.0) for o in d["omega"])
    t = tmp_path / "t.yaml"
    t.write_text(TOGGLE_FOUR_BAR, encoding="utf-8")
    p = mech("icentres", str(t))
    no_traceback(p)
    assert p.returncode == 2 and "error:" in p.stderr


def test_icentres_of_gears_whose_centres_contradict_their_radii_is_located_bad_input(write):
    """Pitch radii 50 + 100 mm need centres 150 mm apart, not 300: input error, not a traceback."""
    f = write(GEARS.format(x2=0.3, size="radii: [0.05, 0.1]"))
    assert_bad_input(mech("icentres", str(f)), f)
