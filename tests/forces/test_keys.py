"""The force answer keys of ``mech check`` (DESIGN § 1.4), each against an independent derivation.

- ``force.<joint>`` (+ ``.x``, ``.y`` on the second link named), ``input_torque`` with inertia
  and gravity, ``shaking_force`` and ``shaking_moment``: a four-bar with masses solved by
  Newton–Euler link by link (tests/oracles/newton_euler.py), the shaking from its a_G and α;
- ``input_torque`` without masses: virtual work on a gear pair's load (T r₂ / r₁);
- ``torque.mean``, ``energy.fluctuation``, ``flywheel.inertia``: a four-stroke engine's torque in
  closed form integrated on a fine grid (tests/oracles/engine_torque.py);
- a key that has no value here is an error row saying why, never a number.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from tests.mechanism_texts import EXAMPLES, slider_crank
from tests.oracles.engine_torque import cycle_integrals, engine_torque
from tests.oracles.newton_euler import four_bar_forces

from mech.check import ERROR, FAIL, PASS, check
from mech.loader import loads

MASSES = {
    "crank": (0.4, 0.0002, 0.015),
    "coupler": (1.5, 0.004, 0.070),
    "rocker": (1.8, 1.8 * 0.06**2, 0.090),
}
BASE = (EXAMPLES / "four_bar_inertia_forces.yaml").read_text()
BASE = BASE[: BASE.index("\nanswers:")] + "\n"


def _verdicts(text: str, answers: dict[str, str]) -> dict[str, object]:
    block = "answers:\n  tolerance: 1e-6%\n" + "".join(f"  {k}: {v}\n" for k, v in answers.items())
    m = loads(text + block, path="keys.yaml")
    return {v.key: v for v in check(m)}


def _oracle(deg: float) -> dict[str, object]:
    return four_bar_forces(
        (0.040, 0.150, 0.170, 0.150), math.radians(deg), 10 * math.pi, MASSES, (0.0, -9.81)
    )


@pytest.mark.parametrize("deg", [60.0, 200.0])
def test_pin_force_keys_are_the_newton_euler_forces_on_the_second_link(deg):
    ne = _oracle(deg)
    text = BASE.replace("angle: 60,", f"angle: {deg:g},")
    answers = {
        "force.A": f"{np.linalg.norm(ne['A']):.12g} N",
        "force.B.x": f"{ne['B'][0]:.12g} N",  # B: [crank, coupler], on the coupler from the crank
        "force.B.y": f"{ne['B'][1]:.12g} N",
        "force.C": f"{np.linalg.norm(ne['C']):.12g} N",
        "force.D.x": f"{-ne['D'][0]:.12g} N",  # D: [rocker, frame], on the frame from the rocker
        "force.D.y": f"{-ne['D'][1]:.12g} N",
        "input_torque": f"{ne['T']:.12g} N m",
    }
    verdicts = _verdicts(text, answers)
    assert {k: v.status for k, v in verdicts.items()} == {k: PASS for k in answers}


def test_shaking_keys_are_minus_the_sum_of_the_links_inertia():
    ne = _oracle(60.0)
    aG, G, alpha = ne["aG"], ne["G"], ne["alpha"]
    force = -sum(MASSES[k][0] * aG[k] for k in MASSES)  # type: ignore[index]
    moment = -sum(
        G[k][0] * MASSES[k][0] * aG[k][1] - G[k][1] * MASSES[k][0] * aG[k][0] + MASSES[k][1] * alpha[k]  # type: ignore[index]
        for k in MASSES
    )
    sense = "ccw" if moment > 0 else "cw"
    answers = {
        "shaking_force": f"{np.linalg.norm(force):.12g} N",
        "shaking_moment": f"{abs(moment):.12g} N m {sense}",
    }
    verdicts = _verdicts(BASE, answers)
    assert {k: v.status for k, v in verdicts.items()} == {k: PASS for k in answers}
    wrong = _verdicts(BASE, {"shaking_moment": f"{abs(moment):.12g} N m {'cw' if sense == 'ccw' else 'ccw'}"})
    assert wrong["shaking_moment"].status == FAIL


def test_input_torque_without_masses_is_the_loads_alone_by_virtual_work():
    # 10 N·m on the 100 mm wheel driven by the 50 mm pinion: the pinion takes 5 N·m (cw pinion, ccw wheel:
    # the pinion's torque is ccw, +5, to hold the wheel's load)
    text = (EXAMPLES / "gear_pair.yaml").read_text()
    text = text[: text.index("\nanswers:")] + "\nloads: {wheel: {torque: 10}}\n"
    verdicts = _verdicts(text, {"input_torque": "5 N m"})
    assert verdicts["input_torque"].status == PASS


W_ENGINE = 1500 * 2 * math.pi / 60
TABLE = [(0, 0), (10, 80), (170, 80), (180, 0), (270, -1500), (330, -5000), (360, -11800),
         (375, -31400), (400, -20000), (450, -8000), (540, -2400), (550, -160), (710, -160), (720, 0)]  # fmt: skip


def test_cycle_keys_are_the_closed_form_engines_integrals():
    th = np.radians(np.linspace(0.0, 720.0, 2 * 288_000 + 1))
    torque = engine_torque(
        th, r=0.05, rod=0.2, w=W_ENGINE, m_p=1.2, m_r=1.5, g=0.06, inertia=0.006, table=TABLE
    )
    mean, de, _, _, inertia = cycle_integrals(torque, th, W_ENGINE, 0.01)
    text = (EXAMPLES / "engine_turning_moment.yaml").read_text()
    text = text[: text.index("\nanswers:")] + "\n"
    answers = {
        "torque.mean": f"{abs(mean):.12g} N m {'ccw' if mean > 0 else 'cw'}",
        "energy.fluctuation": f"{de:.12g} J",
        "flywheel.inertia": f"{inertia:.12g} kg m^2",
    }
    verdicts = _verdicts(text, answers)
    assert {k: v.status for k, v in verdicts.items()} == {k: PASS for k in answers}
    assert verdicts["torque.mean"].computed == pytest.approx(mean, rel=1e-9)


def test_keys_without_a_value_here_are_errors_that_say_why():
    text = (EXAMPLES / "engine_turning_moment.yaml").read_text()
    text = text[: text.index("\nflywheel:")] + "\n"
    verdicts = _verdicts(text, {"flywheel.inertia": "4 kg m^2", "force.P": "1 N", "input_force": "1 N"})
    assert verdicts["flywheel.inertia"].status == ERROR and "flywheel" in verdicts["flywheel.inertia"].message
    assert verdicts["input_force"].status == ERROR and "input_torque" in verdicts["input_force"].message
    assert verdicts["force.P"].status == FAIL  # it has a value: the cylinder wall's side thrust
    dp = (EXAMPLES / "double_parallelogram.yaml").read_text()
    dp = dp[: dp.index("\nanswers:")] + "\nmasses: {coupler: {mass: 1, centre: F}}\n"
    verdicts = _verdicts(dp, {"force.B": "1 N"})
    assert verdicts["force.B"].status == ERROR and "indeterminate" in verdicts["force.B"].message


# A force at the pin B of rod and piston (DESIGN § 1.4: such a load "says which link it acts on:
# on: piston").  Statics of the in-line slider crank, r = 50, l = 200 mm, crank at 60°, P = 1000 N
# along the line of stroke: on the piston, the rod (a two-force member) carries |P| / cos φ at A
# and B, sin φ = r sin θ / l; on the rod, the pin B carries only the guide's share, |P| tan φ
# (Hibbeler, *Engineering Mechanics: Statics*, § 6.6).  A's force is the same either way.
PIN = slider_crank(50, 200, mm=True, drive="{link: crank, angle: 60, rpm: 0, direction: ccw}")


@pytest.mark.parametrize("on", ["piston", "rod", None])
def test_a_load_at_a_pin_of_two_moving_links_acts_on_the_link_it_names_and_without_one_the_pins_force_is_not_given(
    on,
):
    sin_phi = 50 * math.sin(math.radians(60)) / 200
    cos_phi = math.sqrt(1 - sin_phi**2)
    load = "loads: {B: {force: [-1000, 0]" + (f", on: {on}" if on else "") + "}}\n"
    b = {"piston": 1000 / cos_phi, "rod": 1000 * sin_phi / cos_phi, None: 0.0}[on]
    verdicts = _verdicts(PIN + load, {"force.A": f"{1000 / cos_phi!r} N", "force.B": f"{b!r} N"})
    assert verdicts["force.A"].status == PASS
    if on is not None:
        assert verdicts["force.B"].status == PASS
    else:
        assert verdicts["force.B"].status == ERROR
        assert "B joins rod and piston" in verdicts["force.B"].message
        assert "on: rod" in verdicts["force.B"].message and "on: piston" in verdicts["force.B"].message
        from mech.forces import analyse
        from mech.options import SolveOptions

        (note,) = analyse(loads(PIN + load, path="pin.yaml"), SolveOptions()).notes  # mech forces says so
        assert note.startswith("B joins rod and piston") and note.endswith("shown with the load on rod")
        from mech.forces.cycle import force_cycle  # and so does mech sweep --level forces

        assert note in force_cycle(loads(PIN + load, path="pin.yaml"), SolveOptions(), steps=36).notes
