"""Laws the solution must obey whatever the numbers: linearity, scale invariance, extremes."""

from __future__ import annotations

import math

import pytest
from builders import four_bar, slider_crank
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from cli_runner import close, mech, strict_json
from mech.errors import GeometryError
from mech.kinematics import solve
from mechanism_texts import slider_crank as slider_crank_text

angles = st.floats(min_value=0.0, max_value=2 * math.pi, allow_nan=False)
FAST = settings(max_examples=40, deadline=None)


@FAST
@given(angle=angles, rpm=st.floats(min_value=1e-6, max_value=1e6), sign=st.sampled_from([-1.0, 1.0]))
def test_velocities_are_linear_in_speed(angle, rpm, sign):
    w = sign * rpm * 2 * math.pi / 60
    ref = solve(four_bar(angle=angle, omega=1.0), "acceleration")
    kin = solve(four_bar(angle=angle, omega=w), "acceleration")
    assert kin.velocity("C") == pytest.approx(
        tuple(w * v for v in ref.velocity("C")), rel=1e-9, abs=1e-12 * abs(w)
    )
    assert kin.links["rocker"].omega == pytest.approx(w * ref.links["rocker"].omega, rel=1e-9)
    # at constant crank speed accelerations go as ω²
    a_ref = ref.acceleration("C")
    assert kin.acceleration("C") == pytest.approx(
        tuple(w * w * a for a in a_ref), rel=1e-9, abs=1e-12 * w * w
    )


@FAST
@given(angle=angles, s=st.floats(min_value=1e-6, max_value=1e6))
def test_scale_invariance(angle, s):
    ref = solve(four_bar(angle=angle, omega=3.0, alpha=1.0), "acceleration")
    kin = solve(
        four_bar(a=0.04 * s, b=0.15 * s, c=0.08 * s, d=0.15 * s, angle=angle, omega=3.0, alpha=1.0),
        "acceleration",
    )
    assert kin.links["rocker"].omega == pytest.approx(ref.links["rocker"].omega, rel=1e-9)
    assert kin.links["coupler"].alpha == pytest.approx(ref.links["coupler"].alpha, rel=1e-9, abs=1e-9)
    vc, vr = kin.velocity("C"), ref.velocity("C")
    tol = 1e-9 * math.hypot(*vr)
    assert vc[0] == pytest.approx(s * vr[0], abs=s * tol)
    assert vc[1] == pytest.approx(s * vr[1], abs=s * tol)
    assert kin.size == pytest.approx(s * ref.size, rel=1e-12)


@FAST
@given(angle=angles, offset=st.sampled_from([1e3, 1e6, -1e6]))
def test_far_from_origin_with_millimetre_links_is_accurate(angle, offset):
    """Coordinates 1e6 m away, links of a few mm: the solver works relative to a ground pivot."""
    ref = solve(four_bar(a=0.004, b=0.015, c=0.008, d=0.015, angle=angle, omega=2.0), "acceleration")
    kin = solve(
        four_bar(a=0.004, b=0.015, c=0.008, d=0.015, angle=angle, omega=2.0, origin=(offset, offset)),
        "acceleration",
    )
    # positions: the drawn data are only known to ~1e-10 m at 1e6 m
    c, cr = kin.positions["C"], ref.positions["C"]
    assert c[0] - offset == pytest.approx(cr[0], abs=1e-9)
    # 1e-10 m of rounding on 15 mm links: about 1e-8 of the drive's ω (2 rad/s) and ω² (4 rad/s²)
    assert kin.links["rocker"].omega == pytest.approx(ref.links["rocker"].omega, abs=2e-6)
    assert kin.links["rocker"].alpha == pytest.approx(ref.links["rocker"].alpha, abs=4e-6)


@FAST
@given(angle=angles)
def test_slider_crank_sliding_equals_point_velocity(angle):
    kin = solve(slider_crank(angle=angle), "velocity")
    assert kin.sliding("P") == pytest.approx(kin.velocity("B")[0], rel=1e-12, abs=1e-12)


@settings(max_examples=30, deadline=None)
@given(angle=angles)
def test_triple_rocker_solves_where_it_closes_and_is_refused_where_it_cannot(angle):
    """A non-Grashof chain: it assembles iff |BD| <= b + c (law of cosines), and then closes its loop."""
    bd = math.sqrt(0.1**2 + 0.25**2 - 2 * 0.1 * 0.25 * math.cos(angle))
    assume(abs(bd - 0.2) > 1e-6)  # not within a micrometre of the limit position
    mechanism = four_bar(a=0.1, b=0.1, c=0.1, d=0.25, angle=angle, omega=1.0)
    if bd > 0.2:
        with pytest.raises(GeometryError, match="cannot"):
            solve(mechanism, "velocity")
        return
    kin = solve(mechanism, "velocity")
    B, C = kin.positions["B"], kin.positions["C"]
    assert math.dist(B, C) == pytest.approx(0.1, rel=1e-12)
    assert math.dist(C, (0.25, 0.0)) == pytest.approx(0.1, rel=1e-12)
    r = (C[0] - 0.25, C[1])
    v = kin.velocity("C")
    assert v[0] * r[0] + v[1] * r[1] == pytest.approx(0.0, abs=1e-9 * math.hypot(*v))


def test_units_mm_report_every_length_speed_and_acceleration_times_1000(write):
    """--units mm is a change of unit only: positions, velocities, accelerations x 1000, ω alike."""
    f = write(slider_crank_text(0.1, 0.4, 30, 10))
    si = strict_json(mech("acceleration", "--json", str(f)).stdout)
    mm = strict_json(mech("acceleration", "--json", "--units", "mm", str(f)).stdout)
    for a, b in zip(si["points"], mm["points"], strict=True):
        for key in ("position", "velocity", "acceleration"):
            for x, y in zip(a[key], b[key], strict=True):
                assert close(y, 1000 * x, abs_=1e-9)
    for name in si["links"]:
        assert si["links"][name]["omega"] == pytest.approx(mm["links"][name]["omega"], rel=1e-12, abs=1e-12)
