"""Block-triangular solves of Φ_q (mech.kinematics.blocks) and the large chains that use them."""

from __future__ import annotations

import math

import numpy as np
import pytest
from builders import build
from hypothesis import given, settings
from hypothesis import strategies as st

from mech.kinematics import solve
from mech.kinematics.blocks import block_form
from mech.options import SolveOptions
from oracles.four_bar import four_bar

FRAME, COUPLER, ROCKER, CRANK = 0.15, 0.15, 0.08, 0.04


def dyad_chain(n_links: int, angle_deg: float = 60.0):
    """A crank driving (n − 2)/2 coupler–rocker dyads from its pin B, each a Grashof crank-rocker
    turned round A, so every stage assembles and turns fully (as tests/benchmarks/bench_growth.py)."""
    stages = (n_links - 2) // 2
    links = ["frame", "crank"]
    joints = {"A": {"type": "revolute", "links": ["frame", "crank"], "at": [0.0, 0.0]}}
    lengths = {"A-B": CRANK}
    on_b = ["crank"]
    for i in range(1, stages + 1):
        beta = 2 * math.pi * (i - 1) / stages
        links += [f"coupler{i}", f"rocker{i}"]
        on_b.append(f"coupler{i}")
        joints[f"J{i}"] = {
            "type": "revolute",
            "links": [f"coupler{i}", f"rocker{i}"],
            "near": stage(math.radians(angle_deg), beta)[0],  # the branch left of G→B
        }
        joints[f"G{i}"] = {
            "type": "revolute",
            "links": [f"rocker{i}", "frame"],
            "at": [FRAME * math.cos(beta), FRAME * math.sin(beta)],
        }
        lengths[f"B-J{i}"] = COUPLER
        lengths[f"G{i}-J{i}"] = ROCKER
    joints["B"] = {"type": "revolute", "links": on_b}
    return build(
        links,
        joints,
        lengths=lengths,
        drive={"link": "crank", "angle": math.radians(angle_deg), "omega": 10.0},
    )


def stage(theta: float, beta: float, omega: float = 0.0) -> tuple[list[float], tuple[float, float]]:
    """J of one stage, left of G→B, and the (coupler, rocker) ω there, independent of mech.

    The stage is oracles.four_bar's chain with its frame A→G turned by ``beta``: worked at
    crank angle θ − β and turned back (turning the whole chain leaves every ω as it is).
    Left of G→B is right of B→G, the oracle's ``upper=False``.
    """
    C, w3, w4, _, _ = four_bar(CRANK, COUPLER, ROCKER, FRAME, theta - beta, omega, upper=False)
    cos_b, sin_b = math.cos(beta), math.sin(beta)
    return [cos_b * C[0] - sin_b * C[1], sin_b * C[0] + cos_b * C[1]], (w3, w4)


@settings(max_examples=40, deadline=None)
@given(st.integers(1, 12), st.integers(0, 2**31 - 1))
def test_block_form_solves_a_permuted_block_triangular_system_like_a_dense_solve(k, seed):
    rng = np.random.default_rng(seed)
    sizes = rng.integers(1, 4, size=k)
    n = int(sizes.sum())
    a = np.zeros((n, n))
    start = 0
    for s in sizes:  # block lower-triangular, well-conditioned diagonal blocks
        a[start : start + s, start : start + s] = rng.normal(size=(s, s)) + 4 * np.eye(s)
        a[start : start + s, :start] = rng.normal(size=(s, start)) * (rng.random((s, start)) < 0.3)
        start += s
    pr, pc = rng.permutation(n), rng.permutation(n)
    m = a[pr][:, pc]
    form = block_form(m != 0)
    assert form is not None
    assert form.largest <= max(sizes)  # never coarser than the blocks it was built from
    b = rng.normal(size=n)
    assert np.allclose(form.solve(m, b), np.linalg.solve(m, b), rtol=1e-10, atol=1e-12)


def test_block_form_refuses_a_pattern_without_a_perfect_matching():
    pattern = np.array([[True, True, False], [True, True, False], [True, True, False]])  # column 2 empty
    assert block_form(pattern) is None
    assert block_form(np.ones((2, 3), bool)) is None  # not square


def test_block_condition_names_the_singular_block():
    m = np.array([[2.0, 0.0, 0.0], [1.0, 1.0, 1.0], [0.0, 1.0, 1.0]])  # block {1, 2} singular
    form = block_form(m != 0)
    assert form is not None
    cond, null = form.condition(m)
    assert cond > 1e15
    assert (
        null is not None and null[0] == 0.0 and abs(null[1] + null[2]) < 1e-12
    )  # moves 1 and 2 against each other


@pytest.mark.parametrize("n_links", [60, 200])
def test_large_chain_newton_matches_each_stage_closed_form(n_links):
    m = dyad_chain(n_links)
    theta = math.radians(65.0)
    kin = solve(m, "velocity", SolveOptions(angle=theta, method="newton"))
    stages = (n_links - 2) // 2
    for i in (1, stages // 2, stages):
        beta = 2 * math.pi * (i - 1) / stages
        got = (kin.links[f"coupler{i}"].omega, kin.links[f"rocker{i}"].omega)
        _, drawn = stage(theta, beta, 10.0)  # each J drawn near the left branch
        assert math.dist(got, drawn) < 1e-9 * 10.0


def test_large_chain_newton_agrees_with_the_closed_form_to_rounding():
    m = dyad_chain(120)
    opts = dict(angle=math.radians(200.0))
    newton = solve(m, "acceleration", SolveOptions(method="newton", **opts))
    closed = solve(m, "acceleration", SolveOptions(**opts))
    size = closed.size
    for p in closed.positions:
        assert math.dist(newton.positions[p], closed.positions[p]) < 1e-12 * size
        assert math.dist(newton.acceleration(p), closed.acceleration(p)) < 1e-11 * 100.0 * size
