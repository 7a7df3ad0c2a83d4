"""Reading masses, gravity, the flywheel and loads over the cycle (DESIGN § 1.4): SI, located errors."""

from __future__ import annotations

import math

import pytest

from mech.errors import InputError
from mech.loader import loads

BASE = """\
units: {length: mm, angle: deg}
links: [frame, crank, rod, piston]
joints:
  O: {type: revolute, links: [frame, crank], at: [0, 0]}
  A: {type: revolute, links: [crank, rod]}
  B: {type: revolute, links: [rod, piston], near: [600, 0]}
  P: {type: prismatic, links: [piston, frame], path: {through: [0, 0], angle: 0}}
lengths: {OA: 150, AB: 600}
points:
  G: {link: rod, from: A, toward: B, distance: 200}
drive: {link: crank, angle: 40, rpm: 600}
"""


def test_masses_are_read_in_kg_and_kg_m2_whatever_the_length_unit():
    m = loads(
        BASE + 'masses: {rod: {mass: "5 kg", centre: G, inertia: "0.08 kg m^2"}, piston: {mass: 2, centre: B,'
        " radius_of_gyration: 50}}\ngravity: [0, -9.81]\nflywheel: {fluctuation: 2%}\n"
    )
    rod, piston = m.masses
    assert (rod.link, rod.mass, rod.centre, rod.inertia) == ("rod", 5.0, "G", pytest.approx(0.08))
    assert piston.inertia == pytest.approx(2 * 0.05**2)  # I = m k², k = 50 mm
    assert m.gravity == (0.0, -9.81)
    assert m.flywheel is not None and m.flywheel.fluctuation == pytest.approx(0.02)


def test_a_file_without_masses_is_massless_and_has_no_gravity():
    m = loads(BASE)
    assert m.masses == () and m.gravity is None and m.flywheel is None


@pytest.mark.parametrize(
    ("extra", "message", "line"),
    [
        (
            "masses: {rod: {mass: 5, centre: B2}}",
            "centre of mass of rod is 'B2', which is not a point of rod",
            12,
        ),
        ("masses: {rod: {mass: 5}}", "the mass of rod has no `centre`", 12),
        ("masses: {frame: {mass: 5, centre: O}}", "frame is the ground", 12),
        ("masses: {rod: {mass: 5 m, centre: G}}", "'m' is a unit of length", 12),
        ("friction: {P: 0.1}", "friction", 12),
        ("flywheel: {fluctuation: 200%}", "between 0 and 100 %", 12),
        ("loads: {B: {force: [100, 0], on: crank}}", "which B is not a point of", 12),
        ("loads: {rod: {torque: {table: [[0, 1], [0, 2]]}}}", "must rise from row to row", 12),
    ],
)
def test_bad_dynamics_are_located_input_errors(extra, message, line):
    with pytest.raises(InputError) as err:
        loads(BASE + extra + "\n", path="e.yaml")
    assert message in str(err.value)
    assert f"e.yaml:{line}:" in str(err.value)


def test_a_bare_fluctuation_above_one_is_said_to_be_read_as_a_fraction():
    # a bare number is a fraction (0.02 is 2 %): 2 is 200 %, meant as 2 % or 0.02
    with pytest.raises(InputError) as err:
        loads(BASE + "flywheel: {fluctuation: 2}\n", path="e.yaml")
    text = str(err.value)
    assert "e.yaml:12:25" in text
    assert "2 is read as a fraction, 200 %" in text and "write 2 % or 0.02" in text


def test_a_load_table_is_read_in_the_files_units_and_spans_its_cycle():
    m = loads(BASE + "loads: {B: {force: {table: [[0, 0, 0], [360, -1000, 0], [720, 0, 0]]}, on: piston}}\n")
    (load,) = m.loads
    assert load.table == (
        (0.0, 0.0, 0.0),
        (pytest.approx(2 * math.pi), -1000.0, 0.0),
        (pytest.approx(4 * math.pi), 0.0, 0.0),
    )
    assert load.period == pytest.approx(4 * math.pi)  # a four-stroke engine's two turns
    assert load.on == "piston" and load.is_force


def test_a_load_at_one_links_point_of_a_contact_says_what_to_load_instead():
    # K@cam is the cam's point at the contact (DESIGN § 1.2), an answer key's name; a load is put
    # on K (the follower's own point) or a point placed there, not refused as an unknown name
    from tests.mechanism_texts import EXAMPLES

    text = (EXAMPLES / "cam_roller_program.yaml").read_text().split("\nanswers:")[0]
    with pytest.raises(InputError) as err:
        loads(text + "\nloads:\n  K@cam: {force: [0, -100]}\n", path="cam.yaml")
    problem = err.value.problems[0]
    assert "the point of cam at K's contact" in problem.message
    assert problem.hint is not None and problem.hint.startswith("load K, the follower's own point")
