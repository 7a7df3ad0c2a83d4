"""Free bodies (mech.forces.freebody, ``mech forces --explain``): every link balances, and the explained
numbers alone rebuild a result.

The free bodies are built from the analysis's own forces, so what is checked here is what a
student checks: that ΣF = m a_G and ΣM_G = I_G α hold link by link with the numbers written out,
and that those numbers, read back (from the JSON, and from the text a person reads, at the
digits it prints), give the input torque and a pin force that ``mech forces`` reports — and the
Newton–Euler oracle's (tests/oracles/newton_euler.py).
"""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest
from tests.mechanism_texts import EXAMPLES
from tests.oracles.newton_euler import four_bar_forces

from cli_runner import mech as run_mech
from mech.forces import analyse
from mech.forces.freebody import free_bodies, free_body, subscript
from mech.loader import load

FOUR_BAR = str(EXAMPLES / "four_bar_inertia_forces.yaml")
ENGINE = str(EXAMPLES / "khurmi_engine_forces.yaml")
MASSES = {
    "crank": (0.4, 0.0002, 0.015),
    "coupler": (1.5, 0.004, 0.070),
    "rocker": (1.8, 1.8 * 0.06**2, 0.090),
}


def _oracle() -> dict[str, object]:
    return four_bar_forces((0.040, 0.150, 0.170, 0.150), math.radians(60), 10 * math.pi, MASSES, (0.0, -9.81))


@pytest.mark.parametrize("path", [FOUR_BAR, ENGINE, str(EXAMPLES / "engine_turning_moment.yaml")])
def test_every_moving_link_balances_newton_euler(path):
    m = load(path)
    fa = analyse(m)
    bodies = free_bodies(m, fa.kinematics, fa)
    assert [b.link for b in bodies] == [lk.name for lk in m.moving_links]
    for b in bodies:
        scale = max([math.hypot(*a.force) for a in b.actions if a.force is not None] + [1.0])
        assert b.sum_force == pytest.approx(b.m_a, abs=1e-9 * scale)
        assert b.sum_moment == pytest.approx(b.i_alpha, abs=1e-9 * scale)


def test_the_input_torque_rebuilds_from_the_cranks_explained_moments():
    out = run_mech("forces", FOUR_BAR, "--explain", "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    crank = next(b for b in data["free_bodies"] if b["link"] == "crank")
    # ΣM_G = I_G α: the input torque is what the other moments leave
    others = sum(a["moment"] for a in crank["actions"] if a["label"] != "T")
    torque = crank["i_alpha"] - others
    assert torque == pytest.approx(data["input"]["value"], rel=1e-12)
    assert torque == pytest.approx(_oracle()["T"], rel=1e-9)


def test_a_pin_force_rebuilds_from_its_links_force_equation():
    data = json.loads(run_mech("forces", FOUR_BAR, "--explain", "--json").stdout)
    coupler = next(b for b in data["free_bodies"] if b["link"] == "coupler")
    # ΣF = m a_G on the coupler: F₂₃ = m a_G − F₄₃ − W₃
    rest = np.sum([a["force"] for a in coupler["actions"] if a["label"] != "F23"], axis=0)
    f23 = np.array(coupler["m_a"]) - rest
    assert f23 == pytest.approx(_oracle()["B"], rel=1e-9)


_NUMBER = r"[−-]?\d+(?:\.\d+)?(?:e[−-]?\d+)?"


def _num(text: str) -> float:
    return float(text.replace("−", "-"))


def test_the_explained_text_has_the_digits_to_rebuild_the_input_torque():
    out = run_mech("forces", ENGINE, "--explain")
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    start = next(i for i, ln in enumerate(lines) if ln.startswith("link 2 (crank)"))
    body = []
    for ln in lines[start + 1 :]:
        if not ln.startswith("  "):
            break
        body.append(ln)
    moments = {
        m.group(1): _num(m.group(2))
        for ln in body
        if (m := re.match(rf"  (\S+) .*moment ({_NUMBER}) N·m", ln)) is not None
    }
    torque_line = next(ln for ln in body if ln.startswith("  T = "))
    written = _num(re.match(rf"  T = ({_NUMBER})", torque_line).group(1))  # type: ignore[union-attr]
    rebuilt = -sum(moments.values())  # a massless crank about O: ΣM = 0
    assert rebuilt == pytest.approx(written, rel=1e-8)
    fa = analyse(load(ENGINE))
    assert fa.effort is not None and rebuilt == pytest.approx(fa.effort.value, rel=1e-8)
    assert subscript("F12") in out.stdout and "ΣM_O" in out.stdout


def test_the_frame_takes_what_the_pairs_put_on_it():
    # cut free, the frame carries the pins' reactions, by Newton's third law what holds the moving
    # links: Σ F_on frame = −(Σ m a_G − Σ W) = the shaking force plus the weights
    m = load(FOUR_BAR)
    fa = analyse(m)
    frame = free_body(m, fa.kinematics, fa, "frame")
    weights = np.sum([r.weight for r in fa.inertia], axis=0)
    assert np.array(frame.sum_force) == pytest.approx(np.array(fa.shaking_force) + weights, rel=1e-9)


def test_an_indeterminate_chain_has_no_free_bodies_and_says_so():
    text = (EXAMPLES / "double_parallelogram.yaml").read_text()
    m_text = text[: text.index("\nanswers:")] + "\nloads: {coupler: {torque: 5}}\n"
    from mech.loader import loads

    m = loads(m_text, path="dp.yaml")
    fa = analyse(m)
    assert free_bodies(m, fa.kinematics, fa) == ()
