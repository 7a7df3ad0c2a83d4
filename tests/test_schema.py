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
    # written out here, independently of the loader's table: DESIGN § 1 and § 1.1
    expected = {
        "name", "description", "source", "units", "ground", "links", "joints",
        "lengths", "drive", "points", "answers", "asks", "loads",
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
