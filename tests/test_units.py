"""The unit table: every spelling the format promises reads to the right SI value."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from mech.units import Dimension, parse_number, parse_quantity, to_unit

RPM = 2 * math.pi / 60


@pytest.mark.parametrize(
    ("text", "value", "dimension"),
    [
        ("40 mm", 0.04, Dimension.LENGTH),
        ("0.5 m", 0.5, Dimension.LENGTH),
        ("12 cm", 0.12, Dimension.LENGTH),
        ("2 in", 0.0508, Dimension.LENGTH),
        ("1 ft", 0.3048, Dimension.LENGTH),
        ("60 deg", math.pi / 3, Dimension.ANGLE),
        ("1.2 rad", 1.2, Dimension.ANGLE),
        ("600 rpm", 600 * RPM, Dimension.ANGULAR_VELOCITY),
        ("600 RPM", 600 * RPM, Dimension.ANGULAR_VELOCITY),
        ("62.8 rad/s", 62.8, Dimension.ANGULAR_VELOCITY),
        ("8.15 m/s", 8.15, Dimension.VELOCITY),
        ("385 mm/s", 0.385, Dimension.VELOCITY),
        ("126 m/s^2", 126.0, Dimension.ACCELERATION),
        ("126 m/s²", 126.0, Dimension.ACCELERATION),
        ("126 m/s2", 126.0, Dimension.ACCELERATION),
        ("5 rad/s^2", 5.0, Dimension.ANGULAR_ACCELERATION),
        ("1e3", 1000.0, None),
        ("-3.5e-2 m", -0.035, Dimension.LENGTH),
    ],
)
def test_spellings_read_to_si(text, value, dimension):
    q = parse_quantity(text)
    assert q.value == pytest.approx(value, rel=1e-15)
    assert q.dimension is dimension


@pytest.mark.parametrize(
    ("text", "sense"), [("4.8 rad/s cw", "cw"), ("10 rpm ccw", "ccw"), ("3 rad/s", None)]
)
def test_sense_is_read_after_the_unit(text, sense):
    assert parse_quantity(text).sense == sense


@pytest.mark.parametrize("text", ["nan", ".inf", "abc", "", "1..2"])
def test_not_numbers_are_refused(text):
    # "1..2" reads as 1 followed by the unknown unit ".2": refused either way
    with pytest.raises((ValueError, KeyError)):
        parse_quantity(text)


def test_unknown_unit_is_named_as_written():
    with pytest.raises(KeyError) as info:
        parse_quantity("4.8 rad/s cww")
    assert info.value.args[0] == "rad/s cww"


def test_overflow_in_si_is_refused():
    with pytest.raises(ValueError, match="overflows"):
        parse_quantity("1e308 km")


def test_parse_number_reads_exponents_yaml_would_not():
    assert parse_number("1e3") == 1000.0
    assert parse_number("1_000") == 1000.0


@given(st.floats(min_value=-1e12, max_value=1e12, allow_nan=False), st.sampled_from(["mm", "cm", "in", "ft"]))
def test_to_unit_inverts_parsing(value, unit):
    assert to_unit(parse_quantity(f"{value!r} {unit}").value, unit) == pytest.approx(
        value, rel=1e-12, abs=1e-300
    )
