"""Follower motion laws against their textbook formulas and against finite differences.

The reference formulas are written out here from Khurmi & Gupta, *Theory of
Machines*, ch. 20 (displacement, velocity and acceleration of the follower in
terms of the stroke S, the cam angle θ_O of the outstroke and ω), not taken
from mech.cam.laws.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mech.cam.laws import LAWS, rise
from mech.cam.program import CamProgram, Segment, follower_motion
from oracles.cam import textbook_rise

S = 0.04  # stroke, m
BETA = math.radians(120)  # outstroke angle θ_O
OMEGA = 25.0  # rad/s


def programme(law: str, ret: str | None = None) -> CamProgram:
    ret = ret or law
    return CamProgram(
        base_radius=0.05,
        follower="knife",
        segments=(
            Segment("rise", BETA, S, law),
            Segment("dwell", math.radians(30)),
            Segment("return", math.radians(150), S, ret),
            Segment("dwell", math.radians(60)),
        ),
    )


ANGLES = [math.radians(d) for d in (5, 17.5, 40, 59, 60, 61, 90, 113)]


@pytest.mark.parametrize("law", sorted(LAWS))
def test_rise_matches_textbook_formula_at_several_angles(law):
    m = follower_motion(programme(law), ANGLES)
    for k, th in enumerate(ANGLES):
        s, v, a = textbook_rise(law, th, S, BETA, OMEGA)
        assert m.s[k] == pytest.approx(s, rel=1e-12, abs=1e-15 * S)
        assert m.ds[k] * OMEGA == pytest.approx(v, rel=1e-12, abs=1e-15)
        assert m.d2s[k] * OMEGA**2 == pytest.approx(a, rel=1e-12, abs=1e-12)


@pytest.mark.parametrize("law", sorted(LAWS))
def test_return_is_the_rise_mirrored_after_the_dwell(law):
    start = BETA + math.radians(30)
    span = math.radians(150)
    angles = [start + f * span for f in (0.1, 0.3, 0.5, 0.77, 0.95)]
    m = follower_motion(programme("shm", law), angles)
    for k, th in enumerate(angles):
        x = (th - start) / span
        # the rise formula for a rise over `span`: s_return = S − s_rise
        ref = rise(law, [x], S, span)
        assert m.s[k] == pytest.approx(S - float(ref.s[0]), rel=1e-12)
        assert m.ds[k] == pytest.approx(-float(ref.ds[0]), rel=1e-12, abs=1e-15)
        assert m.d2s[k] == pytest.approx(-float(ref.d2s[0]), rel=1e-12, abs=1e-12)


@pytest.mark.parametrize("law", sorted(LAWS))
def test_derivatives_equal_finite_differences_of_the_lift(law):
    prog = programme(law)
    h = 1e-5
    # interior points of the rise and of the return, away from where a derivative jumps
    for th in (0.3, 0.7, 1.3, 1.9, 3.4, 4.2, 4.9):
        if law == "parabolic" and abs(th - BETA / 2) < 0.01:
            continue
        m = follower_motion(prog, [th - h, th, th + h])
        assert m.ds[1] == pytest.approx((m.s[2] - m.s[0]) / (2 * h), rel=1e-6, abs=1e-9 * S)
        assert m.d2s[1] == pytest.approx((m.ds[2] - m.ds[0]) / (2 * h), rel=1e-6, abs=1e-9 * S)
        assert m.d3s[1] == pytest.approx((m.d2s[2] - m.d2s[0]) / (2 * h), rel=1e-6, abs=1e-8 * S)


@pytest.mark.parametrize(
    ("law", "smooth_to"),
    [("uniform", 0), ("shm", 1), ("parabolic", 1), ("cycloidal", 2)],
)
def test_continuity_at_segment_boundaries_is_the_laws_own(law, smooth_to):
    """Lift is continuous for every law; velocity for all but uniform; acceleration for cycloidal only."""
    prog = programme(law)
    eps = 1e-9
    names = ("s", "ds", "d2s")
    for boundary in (*prog.starts[1:], 2 * math.pi):
        before = follower_motion(prog, [boundary - eps])
        after = follower_motion(prog, [boundary % (2 * math.pi)])
        for order in range(3):
            gap = abs(float(before[order][0] - after[order][0]))
            scale = S / BETA**order
            if order <= smooth_to:
                assert gap < 1e-6 * scale, (names[order], math.degrees(boundary))
    # and where the law is not smooth, the jump is there (at the rise's start)
    if smooth_to < 2:
        before = follower_motion(prog, [2 * math.pi - eps])
        after = follower_motion(prog, [0.0])
        order = smooth_to + 1
        assert abs(float(before[order][0] - after[order][0])) > 0.1 * S / BETA**order


def test_parabolic_acceleration_changes_sign_at_mid_rise():
    m = follower_motion(programme("parabolic"), [BETA / 2 - 1e-9, BETA / 2 + 1e-9])
    assert m.d2s[0] == pytest.approx(4 * S / BETA**2)
    assert m.d2s[1] == pytest.approx(-4 * S / BETA**2)
    assert m.s[0] == pytest.approx(S / 2, rel=1e-8)


@pytest.mark.parametrize("law", sorted(LAWS))
def test_whole_turn_sweep_matches_formula(law):
    """Over a whole turn sampled every degree: the rise's formula, the dwell at S, back to 0."""
    theta = np.radians(np.arange(360.0))
    m = follower_motion(programme(law), theta)
    for k, th in enumerate(theta):
        if th < BETA:
            s, v, a = textbook_rise(law, float(th), S, BETA, OMEGA)
            assert m.s[k] == pytest.approx(s, rel=1e-12, abs=1e-15)
            assert m.ds[k] * OMEGA == pytest.approx(v, rel=1e-12, abs=1e-15)
            if not (law == "parabolic" and th == BETA / 2):
                assert m.d2s[k] * OMEGA**2 == pytest.approx(a, rel=1e-12, abs=1e-12)
        elif th < BETA + math.radians(30):
            assert (m.s[k], m.ds[k], m.d2s[k]) == (S, 0.0, 0.0)
        elif th >= math.radians(300):
            assert (m.s[k], m.ds[k], m.d2s[k]) == (0.0, 0.0, 0.0)


@settings(max_examples=60, deadline=None)
@given(
    law=st.sampled_from(sorted(LAWS)),
    h=st.floats(1e-4, 10.0),
    beta=st.floats(0.05, 2 * math.pi),
    x=st.floats(0.0, 1.0),
)
def test_every_law_rises_monotonically_from_zero_to_h_and_is_point_symmetric(law, h, beta, x):
    m = rise(law, [0.0, x, 1.0 - x, 1.0], h, beta)
    assert m.s[0] == pytest.approx(0.0, abs=1e-12 * h)
    assert m.s[3] == pytest.approx(h, rel=1e-12)
    assert m.ds[1] >= -1e-12 * h / beta
    # each law is symmetric about mid-rise: s(x) + s(1 − x) = h
    assert m.s[1] + m.s[2] == pytest.approx(h, rel=1e-9)
    # velocity ratio to the mean lift rate: the textbooks' peak factors (1, π/2, 2, 2)
    peak = {"uniform": 1.0, "shm": math.pi / 2, "parabolic": 2.0, "cycloidal": 2.0}[law]
    assert m.ds[1] <= peak * h / beta * (1 + 1e-12)


def test_unknown_law_is_a_key_error():
    with pytest.raises(KeyError):
        rise("harmonic", [0.5], 1.0, 1.0)
