"""Pair kinds: every joint type has an entry in every layer's registry; each kind reads its own keys."""

from __future__ import annotations

import json
import textwrap

import pytest

from mech.errors import InputError
from mech.loader import loads
from mech.pairs.registry import KINDS
from mech.specs import (
    Circle,
    ContactSpec,
    Curve,
    GearSpec,
    Knife,
    Line,
    PinSpec,
    RollingSpec,
    SlideSpec,
)


@pytest.mark.parametrize("jtype", list(KINDS))
def test_every_kind_entry_is_for_its_own_type(jtype):
    assert KINDS[jtype].name == jtype


def _joint(text: str):
    doc = textwrap.dedent(
        """
        units: {length: mm}
        links: [frame, a, b]
        joints:
          O: {type: revolute, links: [frame, a], at: [0, 0]}
          Q: {type: revolute, links: [frame, b], at: [100, 0]}
        """
    )
    return loads(doc + "  K: " + text + "\n", path="t.yaml").joint("K")


def test_joint_carries_the_typed_spec_of_its_kind():
    assert isinstance(_joint("{type: revolute, links: [a, b], radius: 5}").spec, PinSpec)
    assert isinstance(_joint("{type: slot, links: [a, b], path: {through: Q, angle: 0}}").spec, SlideSpec)
    gear = _joint("{type: gear, links: [a, b], teeth: [20, 40], module: 2}")
    assert isinstance(gear.spec, GearSpec)
    assert gear.spec.pitch_radii == pytest.approx((0.02, 0.04))
    assert gear.radii is None and gear.teeth == (20, 40)  # the flat attributes still read the spec


def test_profiles_are_read_in_si_and_keyed_by_link():
    j = _joint(
        "{type: cam, links: [a, b], profiles: {a: {circle: {centre: O, radius: 40}}, "
        "b: {line: {through: [0, 60], angle: 90}}}}"
    )
    assert isinstance(j.spec, ContactSpec)
    circle, line = j.profile_of["a"], j.profile_of["b"]
    assert isinstance(circle, Circle) and circle.centre.name == "O" and circle.radius == pytest.approx(0.04)
    assert isinstance(line, Line) and line.through.xy == pytest.approx((0.0, 0.06))
    assert line.angle == pytest.approx(1.5707963267948966)


def test_knife_and_curve_profiles_are_read():
    j = _joint(
        "{type: contact, links: [a, b], profiles: {a: {curve: [[0, 0], [10, 0], [10, 10], [0, 10]]}, "
        "b: {point: Q}}}"
    )
    assert isinstance(j.profile_of["a"], Curve) and len(j.profile_of["a"].points) == 4
    assert isinstance(j.profile_of["b"], Knife) and j.profile_of["b"].point.name == "Q"


def test_rolling_radii_take_null_for_a_straight_line():
    j = _joint("{type: rolling, links: [a, frame], radii: [50, null]}")
    assert isinstance(j.spec, RollingSpec)
    assert j.radii == (pytest.approx(0.05), None)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("{type: cam, links: [a, b], profiles: {c: {point: O}}}", "which it does not join"),
        ("{type: cam, links: [a, b], profiles: {a: {circle: {centre: O}}}}", "has no `radius`"),
        (
            "{type: cam, links: [a, b], profiles: {a: {circle: {centre: O, radius: 4}, point: O}}}",
            "exactly one",
        ),
        ("{type: cam, links: [a, b], profiles: {a: {curve: [[0, 0], [1, 1]]}}}", "at least 3 points"),
        ("{type: rolling, links: [a, b], radii: [null, null]}", "both null"),
        ("{type: revolute, links: [a, b], profiles: {a: {point: O}}}", "unknown key 'profiles'"),
    ],
)
def test_bad_profiles_are_located_input_errors(text, message):
    with pytest.raises(InputError) as err:
        _joint(text)
    assert message in str(err.value)
    assert "t.yaml:7:" in str(err.value)


def test_schema_joint_keys_come_from_the_registry(run):
    jsonschema = pytest.importorskip("jsonschema")
    schema = json.loads(run("schema").output)
    joint = schema["properties"]["joints"]["additionalProperties"]
    assert set(joint["properties"]) >= {key for k in KINDS.values() for key in k.keys}
    validator = jsonschema.Draft7Validator(schema)
    doc = {
        "links": ["frame", "w"],
        "joints": {"W": {"type": "rolling", "links": ["w", "frame"], "radii": [50, None]}},
    }
    assert validator.is_valid(doc)
    doc["joints"]["W"]["radius"] = 5  # a pin's key on a rolling pair
    assert not validator.is_valid(doc)


@pytest.mark.parametrize("jtype", list(KINDS))
def test_every_kind_says_what_the_solvers_make_of_it(jtype):
    k = KINDS[jtype]
    assert k.role in ("pin", "path", "contact", "spatial")
    assert (k.role == "spatial") == (not k.planar)
    assert k.located in ("all", "first", "none")


def test_a_profile_naming_a_point_of_another_link_is_a_located_error():
    with pytest.raises(InputError) as err:
        _joint("{type: cam, links: [a, b], profiles: {a: {circle: {centre: Q, radius: 4}}, b: {point: Q}}}")
    text = str(err.value)
    assert "t.yaml:7:" in text and "'Q', which is not a point of a" in text
