"""The JSON Schema is generated from the loader's key tables: it lists exactly the keys mech reads."""

from __future__ import annotations

import pytest

from mech.errors import InputError
from mech.loader import loads
from mech.schema import SCHEMA

FOUR_BAR = """\
units: {{angle: {unit}}}
links: [frame, crank, coupler, rocker]
joints:
  A: {{type: revolute, links: [frame, crank]}}
  B: {{type: revolute, links: [crank, coupler]}}
  C: {{type: revolute, links: [coupler, rocker]}}
  D: {{type: revolute, links: [rocker, frame]}}
"""


def _keys_the_loader_accepts(section_yaml: str) -> bool:
    try:
        loads(section_yaml)
    except InputError:
        return False
    return True


def test_schema_top_level_keys_are_the_keys_the_loader_accepts() -> None:
    # written out here, independently of the loader's table: DESIGN § 1, § 1.1 and § 1.4
    expected = {
        "name", "description", "source", "units", "ground", "links", "joints",
        "lengths", "drive", "points", "answers", "asks", "loads", "masses", "gravity", "flywheel",
        "vary", "keep",  # DESIGN § 1.3
    }  # fmt: skip
    assert set(SCHEMA["properties"]) == expected


def test_schema_drive_keys_are_the_crank_and_slider_keys() -> None:
    expected = {
        "link", "joint", "angle", "rpm", "omega", "direction", "alpha", "about", "relative_to",
        "speed", "accel", "acceleration",
    }  # fmt: skip
    assert set(SCHEMA["definitions"]["drive"]["properties"]) == expected


@pytest.mark.parametrize("unit", SCHEMA["properties"]["units"]["properties"]["angle"]["enum"])
def test_every_angle_unit_the_schema_offers_is_read_by_the_loader(unit: str) -> None:
    assert _keys_the_loader_accepts(FOUR_BAR.format(unit=unit))


def test_rev_is_an_angle_unit_in_the_schema_because_the_loader_reads_it() -> None:
    # `units: {angle: rev}` loads (one revolution = 2π rad); the hand-written schema refused it
    assert _keys_the_loader_accepts(FOUR_BAR.format(unit="rev"))
    assert "rev" in SCHEMA["properties"]["units"]["properties"]["angle"]["enum"]


def test_a_unit_of_another_quantity_is_neither_in_the_schema_nor_read() -> None:
    assert not _keys_the_loader_accepts(FOUR_BAR.format(unit="mm"))
    assert "mm" not in SCHEMA["properties"]["units"]["properties"]["angle"]["enum"]


BASE = """\
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker]}
  D: {type: revolute, links: [rocker, frame], at: [3, 0]}
"""

#: (schema path to a section's properties, YAML that puts KEY in that section)
SECTIONS = {
    "drive": (("definitions", "drive", "properties"), "drive: {{link: crank, {key}: 1}}\n"),
    "points": (
        ("properties", "points", "additionalProperties", "properties"),
        "points: {{P: {{link: coupler, {key}: 1}}}}\n",
    ),
    "loads": (
        ("properties", "loads", "additionalProperties", "properties"),
        "loads: {{crank: {{{key}: 1}}}}\n",
    ),
    "units": (("properties", "units", "properties"), "units: {{{key}: m}}\n"),
    # a revolute joint's keys: the common ones and its own (the schema's if/then for the type)
    "joints": ((), "  E: {{type: revolute, links: [coupler, rocker], {key}: 1}}\n"),
}


def _messages(text: str) -> list[str]:
    try:
        loads(text)
    except InputError as e:
        return [p.message for p in e.problems]
    return []


def _section_keys(path: tuple[str, ...]) -> list[str]:
    if not path:
        kinds = SCHEMA["properties"]["joints"]["additionalProperties"]["allOf"]
        revolute = next(k for k in kinds if k["if"]["properties"]["type"]["const"] == "revolute")
        return sorted(revolute["then"]["propertyNames"]["enum"])
    node = SCHEMA
    for step in path:
        node = node[step]
    return sorted(node)


@pytest.mark.parametrize("section", sorted(SECTIONS))
def test_every_key_the_schema_lists_is_known_to_the_loader(section: str) -> None:
    path, template = SECTIONS[section]
    for key in _section_keys(path):
        text = BASE + template.format(key=key)
        assert not [m for m in _messages(text) if m.startswith(f"unknown key {key!r}")], (section, key)


@pytest.mark.parametrize("section", sorted(SECTIONS))
def test_a_key_the_schema_does_not_list_is_refused_by_the_loader(section: str) -> None:
    path, template = SECTIONS[section]
    assert "colour" not in _section_keys(path)
    assert any(m.startswith("unknown key 'colour'") for m in _messages(BASE + template.format(key="colour")))


# DESIGN §§ 1.3 and 1.4 as written there: every key with the value forms the text gives.
DESIGN_1_3_1_4 = (
    "units: {length: mm, angle: deg}\n"
    + BASE
    + """\
lengths: {AB: 40, BC: 150, CD: 80}
drive: {link: crank, angle: 60, rpm: 120, direction: cw}
points: {G3: {link: coupler, from: B, toward: C, distance: 75}, G4: {link: rocker, from: D, toward: C, distance: 40}}
masses:
  coupler: {mass: 5, centre: G3, inertia: 0.08}
  rocker:  {mass: "2 kg", centre: G4, inertia: "0.012 kg m^2"}
  crank: {mass: 1, centre: B, radius_of_gyration: 20}
gravity: [0, -9.81]
flywheel: {fluctuation: 2%}
loads:
  C: {force: {table: [[0, 0, 0], [360, 0, -500]]}, "on": rocker}
  rocker: {torque: {table: [[0, 0], [720, 20]]}}
vary:
  lengths.AB: {from: 30, to: 50, step: 1}
  drive.angle: {from: 30, to: 150, step: 5}
  drive.rpm: [100, 120, 150, 200]
keep:
  grashof: crank-rocker
  transmission_angle.min: {at_least: 35 deg}
asks: {omega.rocker: 2, velocity.C: 3, acceleration.C: 5}
answers:
  omega.rocker: {value: 4.8 rad/s, marks: 2}
  force.C.x: 10 N
"""
)


def _schema_errors(text: str) -> list[str]:
    jsonschema = pytest.importorskip("jsonschema")
    import yaml

    return [
        f"{list(e.absolute_path)}: {e.message}"
        for e in jsonschema.Draft7Validator(SCHEMA).iter_errors(yaml.safe_load(text))
    ]


def test_design_1_3_and_1_4_as_written_are_valid_to_the_schema_and_to_mech() -> None:
    assert _schema_errors(DESIGN_1_3_1_4) == []
    assert _messages(DESIGN_1_3_1_4) == []


@pytest.mark.parametrize(
    ("old", "new", "where"),
    [
        ("{from: 30, to: 50, step: 1}", "{from: 30, upto: 50, step: 1}", "['vary', 'lengths.AB']"),
        ("{from: 30, to: 50, step: 1}", "{from: 30, to: 50, step: 0}", "['vary', 'lengths.AB']"),
        ("[100, 120, 150, 200]", "[]", "['vary', 'drive.rpm']"),
        ("{at_least: 35 deg}", "{at_lest: 35 deg}", "['keep', 'transmission_angle.min']"),
    ],
)
def test_the_schema_refuses_a_vary_or_keep_that_mech_variants_refuses(old: str, new: str, where: str) -> None:
    assert any(e.startswith(where) for e in _schema_errors(DESIGN_1_3_1_4.replace(old, new, 1)))


def test_a_bare_mass_inertia_gravity_or_load_is_described_in_its_own_si_unit_not_the_files() -> None:
    # DESIGN § 1.4: "Masses are in kg and inertias in kg·m² when bare, whatever the file's length
    # unit"; gravity in m/s²; § 1.1: a force in N, a torque in N·m; answers: a bare number is SI
    masses = SCHEMA["properties"]["masses"]["additionalProperties"]["properties"]
    loads_ = SCHEMA["properties"]["loads"]["additionalProperties"]["properties"]
    cases = {
        "kg": masses["mass"],
        "kg·m²": masses["inertia"],
        "the file's length unit": masses["radius_of_gyration"],
        "m/s²": SCHEMA["properties"]["gravity"]["items"],
        "N": loads_["force"]["oneOf"][0]["items"],
        "N·m": loads_["torque"]["oneOf"][0],
        "SI": SCHEMA["properties"]["answers"]["additionalProperties"]["oneOf"][1]["items"],
    }
    for unit, fragment in cases.items():
        assert f"bare number is in {unit}" in fragment["description"], (unit, fragment["description"])
