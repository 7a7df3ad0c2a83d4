"""``mech key``: every problem's answers to its questions, from closed forms worked here.

* The in-line slider crank of tests/test_check.py (crank r = 0.1 m at 90°, ω = 10 rad/s ccw, rod
  0.3 m): A = (0, r) moves at ω r = 1.0 m/s along x, and so does B: the rod translates, ω_rod = 0.
* The four-bar of tests/test_check_diagnose.py (AB = 40, BC = 150, CD = 80, AD = 150 mm, crank at
  60°, 120 rpm cw): ω of the rocker by its vector loop, there.
* Kutzbach for a four-bar: n = 3(4 − 1) − 2·4 = 1; four binary links.
"""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path

import pytest

from cli_runner import mech, strict_json
from test_check_diagnose import FB, FOUR_BAR

SLIDER = """\
links: [frame, crank, rod, piston]
joints:
  O: {type: revolute, links: [frame, crank], at: [0, 0]}
  A: {type: revolute, links: [crank, rod]}
  B: {type: revolute, links: [rod, piston], near: [0.3, 0]}
  P: {type: prismatic, links: [piston, frame], path: {through: [0, 0], angle: 0}}
lengths: {OA: 0.1, AB: 0.3}
drive: {link: crank, angle: 90, omega: 10, direction: ccw}
asks: {velocity.B: 3, omega.rod: 1}
"""

COUNT = """\
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker]}
  D: {type: revolute, links: [rocker, frame]}
asks: [dof, links.binary]
"""


def _problems(tmp_path: Path) -> Path:
    (tmp_path / "slider.yaml").write_text(SLIDER)
    (tmp_path / "count.yaml").write_text(COUNT)
    (tmp_path / "four_bar.yaml").write_text(FOUR_BAR.replace("answers:\n", "asks: [omega.rocker]\n"))
    return tmp_path


def test_key_gives_each_question_its_closed_form_answer_and_marks(tmp_path: Path) -> None:
    folder = _problems(tmp_path)
    p = mech("key", str(folder), "--json", "--csv", str(tmp_path / "key.csv"))
    assert p.returncode == 0, p.stderr
    got = {(Path(r["problem"]).name, r["key"]): r for r in strict_json(p.stdout)["answers"]}
    assert got["slider.yaml", "velocity.B"]["value"] == pytest.approx(1.0, rel=1e-9)
    assert got["slider.yaml", "velocity.B"]["marks"] == 3
    assert got["slider.yaml", "omega.rod"]["value"] == 0.0  # the rod translates (not 2e-16)
    assert (got["count.yaml", "dof"]["value"], got["count.yaml", "links.binary"]["value"]) == (1, 4)
    w4 = got["four_bar.yaml", "omega.rocker"]
    assert math.isclose(w4["value"], FB["w4"], rel_tol=1e-9) and w4["text"].endswith(" cw")
    rows = list(csv.DictReader(io.StringIO((tmp_path / "key.csv").read_text())))
    assert list(rows[0]) == ["problem", "key", "value", "unit"] and len(rows) == 5
    table = mech("key", str(folder)).stdout
    assert "velocity.B  1 m/s  (3 marks)" in table


def test_key_of_an_uncomputable_acceleration_says_why_and_gives_the_rest(tmp_path: Path) -> None:
    from test_check import ROLLING_AT_AN_INSTANT

    (tmp_path / "w.yaml").write_text(ROLLING_AT_AN_INSTANT)
    p = mech("key", str(tmp_path / "w.yaml"), "--json")
    assert p.returncode == 1
    got = {r["key"]: r for r in strict_json(p.stdout)["answers"]}
    assert got["acceleration.B"]["value"] is None and "curvature" in got["acceleration.B"]["error"]
    assert got["velocity.B"]["error"] is None and got["velocity.B"]["value"] > 0


def test_key_of_an_unreadable_file_is_located_and_exit_2(tmp_path: Path) -> None:
    (tmp_path / "bad.yaml").write_text("links: [frame\n")
    (tmp_path / "count.yaml").write_text(COUNT)
    p = mech("key", str(tmp_path))
    assert p.returncode == 2 and "bad.yaml:" in p.stderr and "links.binary" in p.stdout


def test_key_gives_a_pivoted_links_stroke_as_an_angle(tmp_path: Path) -> None:
    # the rocker's swing between its dead centres, where A, B, C are in line (AC = BC ± AB):
    # the angle ADC by the law of cosines in triangle ADC, its change between the two
    ab, bc, cd, ad = 40.0, 150.0, 80.0, 150.0

    def adc(ac: float) -> float:
        return math.acos((ad**2 + cd**2 - ac**2) / (2 * ad * cd))

    swing = abs(adc(bc + ab) - adc(bc - ab))
    (tmp_path / "fb.yaml").write_text(FOUR_BAR.replace("answers:\n", "asks: [stroke.D]\n"))
    (row,) = strict_json(mech("key", str(tmp_path / "fb.yaml"), "--json").stdout)["answers"]
    assert row["unit"] == "rad" and row["value"] == pytest.approx(swing, rel=1e-6)
