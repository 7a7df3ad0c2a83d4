"""The closed-form (dyad) path against the general Newton solver, on every shipped example that decomposes."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from builders import four_bar, slider_crank

import mech
from mech.errors import GeometryError, UnsupportedError
from mech.kinematics import closed_form, solve
from mech.options import SolveOptions

ROOT = Path(__file__).resolve().parents[2]
DECOMPOSE = [
    "beer_johnston_engine",
    "crank_slotted_lever",
    "crank_slotted_lever_quick_return",
    "four_bar",
    "khurmi_four_bar_acceleration",
    "khurmi_six_link_slider",
    "khurmi_slider_crank_cg",
    "offset_slider_crank",
    "slider_crank",
    "steam_engine_piston",
    "stephenson_six_bar",
    "watt_six_bar",
    "whitworth_quick_return",
]


def _scales(kin):
    v = max((math.hypot(*kin.velocity(p)) for p in kin.positions), default=1.0) or 1.0
    a = max((math.hypot(*kin.acceleration(p)) for p in kin.positions), default=1.0) or 1.0
    return kin.size, v, a


@pytest.mark.parametrize("name", DECOMPOSE)
def test_closed_form_and_newton_agree_on_examples(name):
    m = mech.load(ROOT / "mechanisms" / f"{name}.yaml")
    assert closed_form(m) is not None, "this example decomposes into dyads"
    for deg in (3.0, 47.0, 101.0, 178.0, 222.0, 305.0):
        opts = SolveOptions(angle=math.radians(deg))
        try:
            ref = solve(m, "acceleration", opts.with_(method="newton"))
        except GeometryError:
            with pytest.raises(GeometryError):
                solve(m, "acceleration", opts)  # the closed form must not land where Newton cannot go
            continue
        fast = solve(m, "acceleration", opts.with_(method="closed"))
        size, vs, as_ = _scales(ref)
        for p in ref.positions:
            assert math.dist(fast.positions[p], ref.positions[p]) <= 1e-9 * size, p
            assert math.dist(fast.velocity(p), ref.velocity(p)) <= 1e-9 * vs, p
            assert math.dist(fast.acceleration(p), ref.acceleration(p)) <= 1e-9 * as_, p
        for lk, st in ref.links.items():
            w = max(abs(s.omega) for s in ref.links.values())
            assert fast.links[lk].omega == pytest.approx(st.omega, abs=1e-9 * w)


def test_lean_state_matches_the_full_result():
    m = four_bar(angle=math.radians(60), omega=-4 * math.pi)
    prog = closed_form(m)
    kin = solve(m, "acceleration", SolveOptions(angle=math.radians(130)))
    st = prog.state(math.radians(130), -4 * math.pi, 0.0)
    assert st.position("C") == pytest.approx(kin.positions["C"], abs=1e-12)
    assert st.velocity("C") == pytest.approx(kin.velocity("C"), rel=1e-10)
    assert st.acceleration("C") == pytest.approx(kin.acceleration("C"), rel=1e-10)
    assert st.omega[prog.links.index("rocker")] == pytest.approx(kin.links["rocker"].omega, rel=1e-10)


def test_lean_state_refuses_an_angle_where_the_loop_cannot_close():
    m = four_bar(a=0.1, b=0.1, c=0.05, d=0.15, angle=math.radians(30), omega=1.0)  # crank cannot turn fully
    prog = closed_form(m)
    with pytest.raises(ValueError, match="cannot close"):
        prog.state(math.radians(180), 1.0)


def test_chains_that_do_not_decompose_fall_back_to_newton():
    m = mech.load(ROOT / "mechanisms" / "double_parallelogram.yaml")  # the redundant link flips branch sign
    assert closed_form(m) is None
    kin = solve(m, "velocity", SolveOptions(angle=math.radians(75)))
    assert any("continuation" in n for n in kin.notes)
    with pytest.raises(UnsupportedError, match="does not decompose"):
        solve(m, "velocity", SolveOptions(angle=math.radians(75), method="closed"))


def test_closed_form_keeps_the_branch_of_the_drawing():
    up = solve(slider_crank(), "velocity", SolveOptions(angle=math.radians(200)))
    assert up.positions["B"][0] > 0  # the slider stays ahead of the crank, as drawn
    assert any("closed form" in n for n in up.notes)
