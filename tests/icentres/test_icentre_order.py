"""I-centres from the joints alone: the primary ones by inspection and the order Kennedy finds the rest."""

from __future__ import annotations

import glob
import json
from pathlib import Path

import pytest

from mech.icentres.order import kennedy_order
from mech.loader import load, loads

ROOT = Path(__file__).resolve().parents[2]

FOUR_BAR_TOPOLOGY = """\
name: four-bar, joints only
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker]}
  D: {type: revolute, links: [rocker, frame]}
"""


def test_a_four_bar_has_four_pins_as_primary_centres_and_kennedy_gives_i13_then_i24():
    # Khurmi & Gupta, Theory of Machines, §6.9 (four-bar): I12, I23, I34, I14 at the pins;
    # I13 at the meeting of I12-I23 and I14-I34; I24 at the meeting of I12-I14 and I23-I34.
    order = kennedy_order(loads(FOUR_BAR_TOPOLOGY, path="f.yaml"))
    assert order.count == 6
    assert {c.name: c.how for c in order.primary} == {
        "I12": "pin A",
        "I14": "pin D",
        "I23": "pin B",
        "I34": "pin C",
    }
    secondary = [(c.name, c.step, c.lines) for c in order.centres if c.step]
    assert secondary == [
        ("I13", 1, (("I12", "I23"), ("I14", "I34"))),
        ("I24", 2, (("I12", "I14"), ("I23", "I34"))),
    ]
    assert order.unreached == ()


def test_a_slider_crank_puts_the_sliders_centre_at_infinity():
    order = kennedy_order(load(str(ROOT / "mechanisms" / "slider_crank.yaml")))
    i14 = next(c for c in order.centres if c.name == "I14")
    assert i14.step == 0 and "at infinity, perpendicular to the path" in i14.how


def test_a_cams_centre_is_on_its_common_normal_and_one_kennedy_line_fixes_it():
    order = kennedy_order(load(str(ROOT / "mechanisms" / "eccentric_cam.yaml")))
    (i23,) = [c for c in order.centres if c.name == "I23"]
    assert i23.step == 1 and "common normal" in i23.lines[0][0] and i23.lines[1] == ("I12", "I13")


def test_a_two_degree_of_freedom_five_bar_leaves_every_secondary_centre_to_the_velocities():
    # five pins, ten centres: each secondary one needs two known pairs through a third link,
    # and in a single five-link loop no third link has both: Kennedy cannot start.
    order = kennedy_order(load(str(ROOT / "mechanisms" / "five_bar.yaml")))
    assert order.count == 10 and len(order.primary) == 5
    assert {c.name for c in order.unreached} == {"I13", "I14", "I24", "I25", "I35"}


def test_a_ternary_pin_is_the_centre_of_each_of_its_three_pairs():
    order = kennedy_order(load(str(ROOT / "mechanisms" / "six_link_ternary_joint.yaml")))
    ternary = [c for c in order.primary if "pin" in c.how]
    by_pin: dict[str, int] = {}
    for c in ternary:
        by_pin[c.how] = by_pin.get(c.how, 0) + 1
    assert 3 in by_pin.values()


PLACED = [p for p in sorted(glob.glob(str(ROOT / "mechanisms" / "*.yaml"))) if load(p).has_geometry]


@pytest.mark.parametrize("path", PLACED)
def test_the_joints_alone_reach_the_centres_the_located_construction_reaches(path):
    """The same theorem run on coordinates (mech.icentres.locate, lines met in the plane)
    reaches by inspection and Kennedy exactly the centres the topology says it can."""
    mechanism = load(path)
    from mech.analysis import Request, analyse
    from mech.options import SolveOptions

    # a drive without a speed is given one: where the centres lie does not depend on it
    speed = (
        SolveOptions(omega=1.0) if len(mechanism.drives) == 1 and mechanism.drives[0].link else SolveOptions()
    )
    located = analyse(mechanism, Request(level="velocity", options=speed, icentres=True)).icentres
    assert located is not None
    order = kennedy_order(mechanism)
    assert {c.name for c in order.primary} == {c.name for c in located.centres if c.primary}
    reached = {c.name for c in order.centres if c.step is not None}
    assert reached == {c.name for c in located.centres if c.primary or c.step is not None}


def test_mech_icentres_on_a_file_that_places_nothing_lists_the_order(run, write):
    result = run("icentres", str(write(FOUR_BAR_TOPOLOGY)))
    assert result.exit_code == 0, result.stderr
    assert "instantaneous centres: N = n(n − 1)/2 = 4·3/2 = 6" in result.stdout
    assert "I13        frame–coupler     step 1   Kennedy: on I12–I23 and on I14–I34" in result.stdout
    assert "4 primary by inspection, 2 by Kennedy's theorem, 0 not reached" in result.stdout


def test_mech_icentres_json_on_a_file_that_places_nothing_has_no_coordinates(run, write):
    path = write(FOUR_BAR_TOPOLOGY)
    data = json.loads(run("icentres", str(path), "--json").stdout)
    assert (data["command"], data["file"], data["name"]) == ("icentres", str(path), "four-bar, joints only")
    assert data["count"] == 6 and data["located"] is False
    assert [(c["name"], c["step"]) for c in data["centres"]] == [
        ("I12", 0),
        ("I14", 0),
        ("I23", 0),
        ("I34", 0),
        ("I13", 1),
        ("I24", 2),
    ]
    assert data["centres"][4]["lines"] == [["I12", "I23"], ["I14", "I34"]]
