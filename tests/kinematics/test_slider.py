"""Slider crank (in-line and offset) and crank with slotted lever, against hand closed forms.

The slider crank's reference is tests/oracles/slider_crank.py; the slotted lever's is worked here.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from builders import slider_crank, slotted_lever
from hypothesis import given, settings
from hypothesis import strategies as st

from cli_runner import assert_bad_input, close, mech, no_traceback, points, strict_json
from mech.kinematics import solve
from mech.options import SolveOptions
from mechanism_texts import slider_crank as slider_crank_text
from oracles.slider_crank import slider_crank as slider_closed_form


@pytest.mark.parametrize("e", [0.0, 0.03, -0.05])
@pytest.mark.parametrize("deg", [0.0, 30.0, 45.0, 90.0, 135.0, 180.0, 250.0, 300.0])
def test_slider_crank_matches_closed_form(deg, e):
    th = math.radians(deg)
    kin = solve(slider_crank(e=e, angle=th, omega=20 * math.pi, alpha=-5.0), "acceleration")
    x, w3, v, a3, a = slider_closed_form(0.1, 0.4, e, th, 20 * math.pi, -5.0)
    assert kin.positions["B"] == pytest.approx((x, e), abs=1e-14)
    assert kin.links["rod"].omega == pytest.approx(w3, rel=1e-10, abs=1e-11)
    assert kin.velocity("B") == pytest.approx((v, 0.0), rel=1e-10, abs=1e-11)
    assert kin.sliding("P") == pytest.approx(v, rel=1e-10, abs=1e-11)
    assert kin.links["rod"].alpha == pytest.approx(a3, rel=1e-9, abs=1e-8)
    assert kin.acceleration("B") == pytest.approx((a, 0.0), rel=1e-9, abs=1e-8)
    assert kin.coriolis("P") == (0.0, 0.0)  # a fixed guide has none


def test_dead_centres_solve_with_slider_at_rest():
    for th in (0.0, math.pi):
        kin = solve(slider_crank(angle=th), "acceleration")
        assert kin.velocity("B") == pytest.approx((0.0, 0.0), abs=1e-12)  # 2πn·r ≈ 6 m/s scale
        # ω₃ = −rω cosθ / rod: finite, not singular
        assert kin.links["rod"].omega == pytest.approx(-0.1 * 20 * math.pi * math.cos(th) / 0.4, rel=1e-12)
        _x, _, _, _, a = slider_closed_form(0.1, 0.4, 0.0, th, 20 * math.pi)
        assert kin.acceleration("B")[0] == pytest.approx(a, rel=1e-12)


def test_crank_a_million_times_shorter_than_rod():
    r, rod = 1e-7, 0.1
    th = math.radians(40)
    kin = solve(slider_crank(r=r, rod=rod, angle=th, omega=100.0), "acceleration")
    x, w3, v, _a3, a = slider_closed_form(r, rod, 0.0, th, 100.0)
    assert kin.positions["B"][0] == pytest.approx(x, rel=1e-14)
    assert kin.velocity("B")[0] == pytest.approx(v, rel=1e-8)
    assert kin.links["rod"].omega == pytest.approx(w3, rel=1e-8)
    assert kin.acceleration("B")[0] == pytest.approx(a, rel=1e-8)


def test_coupler_point_velocity_by_ratio_ac_over_ab():
    # The lesson: ac = ab × AC/AB for a point C on the rod.
    m = slider_crank(points={"C": {"link": "rod", "from": "A", "toward": "B", "distance": 0.1}})
    kin = solve(m)
    ab = np.array(kin.relative_velocity("B", "A"))
    ac = np.array(kin.relative_velocity("C", "A"))
    assert ac == pytest.approx(ab * 0.1 / 0.4, rel=1e-12)


def test_slotted_lever_velocities_and_coriolis_match_hand_closed_form():
    r, d, w = 0.12, 0.3, 20 * math.pi  # the lesson's 600 rpm, O2A = 12 cm
    for deg in (0.0, 60.0, 150.0, 230.0, 300.0):
        th = math.radians(deg)
        kin = solve(slotted_lever(r=r, d=d, angle=th, omega=w), "acceleration")
        A = np.array([r * math.cos(th), r * math.sin(th)])
        O1 = np.array([0.0, -d])
        rho_v = A - O1
        rho = np.hypot(*rho_v)
        e = rho_v / rho
        perp = np.array([-e[1], e[0]])
        vA = w * np.array([-A[1], A[0]])
        aA = -w * w * A
        w_lever = float(vA @ perp) / rho  # the block's velocity across the lever
        v_slide = float(vA @ e)  # ... and along it
        # a_A = α×ρ − ω²ρ + a_s e + 2ω v_s e⊥ → across the lever: a_A·e⊥ = αρ + 2ω v_s
        al_lever = (float(aA @ perp) - 2 * w_lever * v_slide) / rho
        a_slide = float(aA @ e) + w_lever**2 * rho
        assert kin.links["lever"].omega == pytest.approx(w_lever, rel=1e-10)
        assert kin.sliding("S") == pytest.approx(v_slide, rel=1e-10, abs=1e-12)
        cor = 2 * w_lever * v_slide * perp
        assert kin.coriolis("S") == pytest.approx(tuple(cor), rel=1e-9, abs=1e-9)
        assert abs(np.hypot(*kin.coriolis("S"))) == pytest.approx(2 * abs(w_lever * v_slide), rel=1e-9)
        assert kin.links["lever"].alpha == pytest.approx(al_lever, rel=1e-9, abs=1e-9)
        # The block's point A and the lever's coincident point differ by the sliding and Coriolis terms.
        a_block = np.array(kin.acceleration("A"))
        a_lever = np.array(kin.acceleration("A", link="lever"))
        assert a_block - a_lever == pytest.approx(tuple(a_slide * e + cor), rel=1e-9, abs=1e-8)
        v_lever = np.array(kin.velocity("A", link="lever"))
        assert np.array(kin.velocity("A")) - v_lever == pytest.approx(tuple(v_slide * e), abs=1e-10)


def test_slotted_lever_lesson_example():
    # Example 3.1: 600 rpm ccw, O2A = 12 cm: v_A = 7.54 m/s (the lesson rounds to 7.53).
    kin = solve(slotted_lever(angle=math.radians(60)), "velocity")
    assert math.hypot(*kin.velocity("A")) == pytest.approx(20 * math.pi * 0.12, rel=1e-12)
    assert kin.links["lever"].omega > 0  # ccw crank drives the lever ccw here


def test_slider_speed_option_and_direction_flip():
    m = slider_crank(angle=1.0, omega=10.0)
    base = solve(m).velocity("B")[0]
    flipped = solve(m, options=SolveOptions(direction="cw")).velocity("B")[0]
    faster = solve(m, options=SolveOptions(omega=30.0)).velocity("B")[0]
    assert flipped == pytest.approx(-base, rel=1e-12)
    assert faster == pytest.approx(3 * base, rel=1e-12)


def test_pin_in_slot_moves_the_lever_like_the_sliding_block():
    from builders import build

    th = math.radians(50)
    block = solve(slotted_lever(angle=th), "acceleration")
    slot = build(
        ["frame", "crank", "lever"],
        {
            "O2": {"links": ["frame", "crank"], "at": (0.0, 0.0)},
            "A": {"type": "slot", "links": ["crank", "lever"], "path": {"through": "O1", "toward": "B"}},
            "O1": {"links": ["lever", "frame"], "at": (0.0, -0.3)},
        },
        lengths={"O2-A": 0.12, "O1-B": 0.6},
        drive={"link": "crank", "angle": th, "omega": 20 * math.pi},
        points={"B": {"link": "lever"}},
    )
    kin = solve(slot, "acceleration")
    assert kin.mobility.kutzbach == 1 and kin.mobility.numeric == 1
    assert kin.links["lever"].omega == pytest.approx(block.links["lever"].omega, rel=1e-12)
    assert kin.links["lever"].alpha == pytest.approx(block.links["lever"].alpha, rel=1e-10)
    assert kin.sliding("A") == pytest.approx(block.sliding("S"), rel=1e-12)
    assert kin.coriolis("A") == pytest.approx(block.coriolis("S"), rel=1e-10)


@pytest.mark.parametrize("method", ["newton", "closed"])
@pytest.mark.parametrize("r", [1e-12, 1e-13])
def test_tiny_crank_rates_keep_their_own_digits(r, method):
    # A 1e-12 m crank on a 1 m rod at 45°, 60 rpm: the rod's ω and the piston's speed are
    # 4.4e-12 beside the crank's 6.28 rad/s. Each must be right to its own size (closed form
    # above), not to 1e-16 of the crank's ω (which left 1e-4 of them wrong) nor set to zero.
    rod, th, w = 1.0, math.radians(45), 2 * math.pi
    kin = solve(slider_crank(r=r, rod=rod, angle=th, omega=w), "acceleration", SolveOptions(method=method))
    _, w3, v, a3, a = slider_closed_form(r, rod, 0.0, th, w)
    assert math.hypot(*kin.velocity("A")) == pytest.approx(r * w, rel=1e-12)
    assert kin.links["rod"].omega == pytest.approx(w3, rel=1e-12)
    assert kin.velocity("B")[0] == pytest.approx(v, rel=1e-12)
    assert kin.sliding("P") == pytest.approx(v, rel=1e-12)
    assert kin.links["rod"].alpha == pytest.approx(a3, rel=1e-9)
    assert kin.acceleration("B")[0] == pytest.approx(a, rel=1e-9)
    assert kin.links["crank"].angle == pytest.approx(th, rel=1e-12)  # was 0: its two points "coincided"


@settings(max_examples=40, deadline=None)
@given(
    k=st.integers(min_value=-12, max_value=6),
    deg=st.floats(min_value=5.0, max_value=175.0),
    e=st.floats(min_value=-0.05, max_value=0.05),
)
def test_velocities_scale_with_the_lengths(k, deg, e):
    # Law: scaling every length by 10^k scales every velocity and acceleration by 10^k and leaves
    # every ω and α as it was (time is untouched), to rounding, and the report prints the same.
    from mech.options import OutputUnits
    from mech.render.kinematics import kinematics_json

    th, f = math.radians(deg), 10.0**k
    base = solve(slider_crank(e=e, angle=th), "acceleration")
    big = solve(slider_crank(r=0.1 * f, rod=0.4 * f, e=e * f, angle=th), "acceleration")
    for name in ("A", "B"):
        assert np.allclose(
            np.array(big.velocity(name)) / f, base.velocity(name), rtol=1e-12, atol=1e-12 * 6.3
        )
        assert np.allclose(
            np.array(big.acceleration(name)) / f, base.acceleration(name), rtol=1e-11, atol=1e-11 * 400
        )
    assert big.links["rod"].omega == pytest.approx(base.links["rod"].omega, rel=1e-12)
    units = OutputUnits()
    jb, jf = kinematics_json(base, units=units), kinematics_json(big, units=units)
    for pb, pf in zip(jb["points"], jf["points"], strict=True):
        assert (pb["speed"] == 0.0) == (pf["speed"] == 0.0)
        # to rounding of the mechanism's own speed (ωr = 6.3 m/s), as the vectors above: near a dead
        # centre (5°, offset) B's speed is 1e-4 m/s, a difference of terms of 6 m/s, good to ε·6 m/s
        assert pf["speed"] / f == pytest.approx(pb["speed"], rel=1e-12, abs=1e-12 * 6.3)


# -- through mech velocity/acceleration --json (cli_runner: tracebacks shown) -----------------
# In-line slider crank r = 0.1, l = 0.4, ω = 10 rad/s ccw; closed forms worked beside each test.
def test_inline_slider_crank_at_90_deg_rod_translates_and_slider_moves_at_omega_r(write):
    """Crank vertical: A = (0, r), v_A = (-ω r, 0); the rod translates, so ω_rod = 0, v_B = -ω r."""
    r, L, w = 0.1, 0.4, 10.0
    f = write(slider_crank_text(r, L, 90, w))
    p = mech("velocity", "--json", str(f))
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    assert abs(d["links"]["rod"]["omega"]) <= 1e-12 * w
    assert close(d["links"]["crank"]["omega"], w)
    b = points(d)["B"]
    assert close(b["position"][0], math.sqrt(L * L - r * r))
    assert close(b["velocity"][0], -w * r)
    assert abs(b["velocity"][1]) <= 1e-12 * w * r
    assert close(abs(d["sliders"][0]["sliding"]), w * r)


@pytest.mark.parametrize("angle, sign", [(0, -1), (180, +1)])
def test_slider_crank_at_a_dead_centre_slider_stops_and_rod_turns_at_omega_r_over_l(write, angle, sign):
    """At 0 deg: v_B = (0, ω r + ω3 l) must be horizontal, ω3 = -ω r / l; at 180 deg, +ω r / l."""
    r, L, w = 0.1, 0.4, 10.0
    f = write(slider_crank_text(r, L, angle, w))
    p = mech("velocity", "--json", str(f))
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    assert close(d["links"]["rod"]["omega"], sign * w * r / L)
    b = points(d)["B"]
    assert math.hypot(*b["velocity"]) <= 1e-12 * w * r
    assert close(b["position"][0], (r + L) if angle == 0 else (L - r))


def test_offset_slider_crank_at_0_deg_matches_the_closed_form(write):
    """Path y = e: B = (r + √(l² - e²), e); ω3 = -ω r / √(l² - e²); v_Bx = -ω3 e."""
    r, L, e, w = 0.1, 0.4, 0.1, 10.0
    f = write(slider_crank_text(r, L, 0, w, offset=e))
    p = mech("velocity", "--json", str(f))
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    s = math.sqrt(L * L - e * e)
    w3 = -w * r / s
    assert close(d["links"]["rod"]["omega"], w3)
    b = points(d)["B"]
    assert close(b["position"][0], r + s)
    assert close(b["velocity"][0], -w3 * e)


def test_inline_slider_crank_acceleration_at_90_deg_matches_the_closed_form(write):
    """a_A = (0, -ω² r); a_By = 0 gives α3 = ω² r / s and a_B = ω² r² / s, s = √(l² - r²)."""
    r, L, w = 0.1, 0.4, 10.0
    f = write(slider_crank_text(r, L, 90, w))
    p = mech("acceleration", "--json", str(f))
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    s = math.sqrt(L * L - r * r)
    assert close(d["links"]["rod"]["alpha"], w * w * r / s)
    assert close(points(d)["B"]["acceleration"][0], w * w * r * r / s)
    assert close(points(d)["A"]["acceleration"][1], -w * w * r)


def test_slider_crank_far_from_the_origin_keeps_its_velocities(write):
    """O at (1e12, 1e12) m: |v_B| = ω r = 1 m/s at 90 deg (once 0.99976, solved from the far origin)."""
    f = write(slider_crank_text(0.1, 0.4, 90, 10, origin=1e12))
    p = mech("velocity", "--json", str(f))
    no_traceback(p)
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    assert close(abs(d["sliders"][0]["sliding"]), 1.0)


def test_lengths_beyond_the_working_range_are_refused_where_written(write):
    """Lengths 1e307 m once gave NaN velocities with exit 0; now the file is refused at the value."""
    f = write(slider_crank_text(1e307, 4e307, 90, 10, near_x=5e307))
    p = mech("velocity", "--json", str(f))
    assert_bad_input(p, f)
    assert "outside the range mech works in" in p.stderr
    assert p.stdout == ""


def test_velocity_directions_are_reported_in_0_to_360_deg(write):
    """A velocity along +x with a -1e-15 y component once printed direction 360.0 (Khurmi Ex. 7.2)."""
    f = write(
        """\
links: [frame, crank, rod, piston]
joints:
  O: {type: revolute, links: [frame, crank], at: [0, 0]}
  A: {type: revolute, links: [crank, rod]}
  B: {type: revolute, links: [rod, piston], near: [-700, 0]}
  P: {type: prismatic, links: [piston, frame], path: {through: [0, 0], angle: 0}}
units: {length: mm}
lengths: {OA: 150, AB: 600}
drive: {link: crank, angle: 135, rpm: 300, direction: cw}
"""
    )
    p = mech("velocity", "--json", str(f))
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    for q in d["points"]:
        if q["direction"] is not None:
            assert 0.0 <= q["direction"] < 360.0, q
    for q in d["relative"]:
        assert q.get("direction") is None or 0.0 <= q["direction"] < 360.0, q


def test_a_path_the_slider_cannot_reach_is_a_located_error_with_a_hint(write):
    """Path 1 m off a 0.5 m reach: file:line:col and a hint, as every error (cli.md)."""
    f = write(slider_crank_text(0.1, 0.4, 90, 10, offset=1.0))
    p = mech("velocity", str(f))
    assert_bad_input(p, f)
    assert "hint:" in p.stderr
