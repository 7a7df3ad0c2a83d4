"""The result of a solve: built from the solve's lean state when read, read-only, picklable."""

from __future__ import annotations

import itertools
import math
import pickle

import pytest
from builders import four_bar
from hypothesis import given, settings
from hypothesis import strategies as st

from mech.kinematics import closed_form, solve
from mech.kinematics.result import Fields
from mech.options import SolveOptions


def test_result_read_after_later_solves_keeps_its_own_angle():
    m = four_bar(angle=math.radians(60), omega=-4 * math.pi)
    prog = closed_form(m)
    first = solve(m, "acceleration", SolveOptions(angle=math.radians(100)))
    for deg in (140, 200, 260):  # solves in between must not leak into the unread first result
        solve(m, "acceleration", SolveOptions(angle=math.radians(deg)))
    st_ = prog.state(math.radians(100), -4 * math.pi, 0.0)
    assert first.positions["C"] == pytest.approx(st_.position("C"), abs=1e-12)
    assert first.velocity("C") == pytest.approx(st_.velocity("C"), rel=1e-10)
    assert first.acceleration("C") == pytest.approx(st_.acceleration("C"), rel=1e-10)


def test_result_attributes_cannot_be_set():
    kin = solve(four_bar(angle=math.radians(60), omega=1.0), "velocity")
    with pytest.raises(AttributeError):
        kin.level = "acceleration"  # type: ignore[misc]
    with pytest.raises(AttributeError):
        kin.extra = 1  # type: ignore[attr-defined]


def test_result_pickles_with_its_values():
    kin = solve(four_bar(angle=math.radians(60), omega=2.0), "acceleration", SolveOptions(angle=1.0))
    back = pickle.loads(pickle.dumps(kin))
    assert dict(back.positions) == dict(kin.positions)
    assert back.links["rocker"] == kin.links["rocker"]
    assert back.size == kin.size and back.notes == kin.notes and back.level == kin.level
    assert back.acceleration("C") == kin.acceleration("C")


def test_size_of_a_four_bar_is_its_longest_joint_distance():
    # frame 0.15 m and coupler 0.15 m dominate the crank-rocker at 60°: the largest
    # joint distance is the diagonal A–C or the frame A–D, whichever is longer
    kin = solve(four_bar(angle=math.radians(60), omega=1.0), "position")
    p = kin.positions
    expected = max(math.dist(p[a], p[b]) for a, b in itertools.combinations("ABCD", 2))
    assert kin.size == pytest.approx(expected, rel=1e-15)


@settings(max_examples=25, deadline=None)
@given(st.lists(st.tuples(st.floats(-1e3, 1e3), st.floats(-1e3, 1e3)), min_size=2, max_size=300))
def test_size_of_many_points_is_their_largest_pairwise_distance(points):
    names = [f"P{k}" for k in range(len(points))]
    fields = Fields(dict(zip(names, points, strict=True)), {}, {}, {}, joint_names=frozenset(names))
    brute = max(math.dist(a, b) for a, b in itertools.combinations(points, 2))
    assert fields.measure() == pytest.approx(brute, rel=1e-12, abs=1e-12)
