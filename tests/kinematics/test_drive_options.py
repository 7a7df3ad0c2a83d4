"""Command-line speeds go to the drive they fit, never reinterpreted.

A slider drive's speed is m/s along its path; --rpm/--omega are a crank's
rad/s.  Feeding one to the other once printed a crank turning 129 rad/s for
"--rpm 100" on a slider-driven file: now it is refused, and --speed exists.
"""

from __future__ import annotations

import itertools
import math

import pytest
from tests.conftest import MECHANISMS, example_files

from cli_runner import close, mech, no_traceback, strict_json
from mech.errors import InputError
from mech.kinematics import solve
from mech.kinematics.mobility import kutzbach
from mech.loader import load, loads
from mech.options import SolveOptions
from mechanism_texts import slider_crank as slider_crank_text
from oracles.slider_crank import slider_driven_crank

SLIDER_DRIVEN = """
units: {length: mm, angle: deg}
links: [frame, crank, rod, piston]
joints:
  O: {type: revolute, links: [frame, crank], at: [0, 0]}
  A: {type: revolute, links: [crank, rod], near: [40, 69]}
  B: {type: revolute, links: [rod, piston], at: [280, 0]}
  P: {type: prismatic, links: [piston, frame], path: {through: O, angle: 0}}
lengths: {OA: 80, AB: 250}
drive: {joint: P, speed: -2 m/s}
"""


def crank_omega(v_b: float) -> float:
    """ω of SLIDER_DRIVEN's crank (OA 0.08 m, AB 0.25 m) with the piston at x_B = 0.28 m moving at
    ``v_b``, A above the axis (near: [40, 69]): worked in oracles.slider_crank."""
    return slider_driven_crank(0.08, 0.25, 0.28, v_b)[1]


def test_file_speed_gives_the_crank_omega():
    kin = solve(loads(SLIDER_DRIVEN), level="velocity")
    assert kin.links["crank"].omega == pytest.approx(crank_omega(-2.0), rel=1e-9)


def test_speed_option_overrides_the_slider():
    kin = solve(loads(SLIDER_DRIVEN), level="velocity", options=SolveOptions(speed=-3.0))
    assert kin.links["crank"].omega == pytest.approx(crank_omega(-3.0), rel=1e-9)


@pytest.mark.parametrize(
    "options", [SolveOptions(omega=10.0), SolveOptions(direction="cw"), SolveOptions(alpha=1.0)]
)
def test_crank_options_on_a_slider_drive_are_refused(options):
    with pytest.raises(InputError, match="is a slider"):
        solve(loads(SLIDER_DRIVEN), level="velocity", options=options)


def test_speed_on_a_crank_drive_is_refused():
    text = SLIDER_DRIVEN.replace("drive: {joint: P, speed: -2 m/s}", "drive: {link: crank, rpm: 60}")
    with pytest.raises(InputError, match="--speed sets a slider drive"):
        solve(loads(text), level="velocity", options=SolveOptions(speed=1.0))


# -- through the command line as a user runs it (cli_runner: tracebacks shown) -----------
def test_slider_driven_crank_near_dead_centre_matches_the_closed_form(write):
    """v_B = (1, 0) with B at x = 0.45: A from the two circles, then
    ω2 (a_x a_y/(a_x - x) - a_y) = 1 and ω3 = ω2 a_x / (a_x - x)."""
    r, L, x = 0.1, 0.4, 0.45
    f = write(
        f"""\
links: [frame, crank, rod, piston]
joints:
  O: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  A: {{type: revolute, links: [crank, rod], near: [0.05, 0.08]}}
  B: {{type: revolute, links: [rod, piston], at: [{x}, 0]}}
  P: {{type: prismatic, links: [piston, frame], path: {{through: [0, 0], angle: 0}}}}
lengths: {{OA: {r}, AB: {L}}}
drive: {{joint: P, speed: 1 m/s}}
"""
    )
    p = mech("velocity", "--json", str(f))
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    ax = (r * r - L * L + x * x) / (2 * x)
    ay = math.sqrt(r * r - ax * ax)
    w2 = 1 / (ay * ax / (ax - x) - ay)
    w3 = w2 * ax / (ax - x)
    assert close(d["links"]["crank"]["omega"], w2)
    assert close(d["links"]["rod"]["omega"], w3)


def test_a_huge_angle_override_is_refused_not_reduced(write):
    """1e300° is held only to ~1e284° in floating point: no crank position is known there, so it is
    refused (exit 2) as a sweep refuses it, not reduced to a turn it does not name (issue 21.6)."""
    f = write(slider_crank_text(0.1, 0.4, 90, 10))
    p = mech("position", "--json", str(f), "--angle", "1e300")
    no_traceback(p)
    assert p.returncode == 2
    assert "held only to" in p.stderr


@pytest.mark.parametrize("where", ["file", "option"])
def test_an_omega_too_large_to_square_is_refused_from_file_or_option(write, where):
    """ω = 1e200 once raised OverflowError (ω²) even at velocity level: bad input, exit 2."""
    if where == "file":
        f = write(slider_crank_text(0.1, 0.4, 90, 10).replace("omega: 10", "omega: 1e200"))
        p = mech("velocity", "--json", str(f))
    else:
        f = write(slider_crank_text(0.1, 0.4, 90, 10))
        p = mech("velocity", "--json", str(f), "--omega", "1e200")
    assert "Traceback" not in p.stderr, p.stderr[-800:]
    assert p.returncode == 2, p.stdout[-800:]
    assert p.stderr.strip()


@pytest.mark.parametrize(
    "opts",
    [
        ["--rpm", "nan"],
        ["--rpm", "-5"],
        ["--omega", "inf"],
        ["--angle", "inf"],
        ["--angle", "nan"],
        ["--tol", "0"],
        ["--tol", "2"],
        ["--tol", "nan"],
        ["--rpm", "1", "--omega", "1"],
    ],
)
def test_bad_solver_options_are_exit_2_with_nothing_on_stdout(write, opts):
    p = mech("velocity", str(write(slider_crank_text())), *opts)
    assert p.returncode == 2 and "Traceback" not in p.stderr and p.stdout == ""


def test_alpha_nan_is_exit_2(write):
    p = mech("acceleration", str(write(slider_crank_text())), "--alpha", "nan")
    assert p.returncode == 2 and "Traceback" not in p.stderr


def test_rpm_zero_gives_every_link_omega_zero(write):
    p = mech("velocity", "--json", str(write(slider_crank_text())), "--rpm", "0")
    assert p.returncode == 0
    d = strict_json(p.stdout)
    assert all(v["omega"] == 0 for v in d["links"].values())


# -- fewer drives than degrees of freedom: refused by the count, before the assembly -------------
FIVE_BAR = """
name: five-bar
links: [frame, a, b, c, d]
joints:
  A: {type: revolute, links: [frame, a], at: [0, 0]}
  B: {type: revolute, links: [a, b]}
  C: {type: revolute, links: [b, c]}
  D: {type: revolute, links: [c, d]}
  E: {type: revolute, links: [d, frame], at: [0.1, 0]}
lengths: {AB: 0.04, BC: 0.07, CD: 0.07, DE: 0.04}
drive: {link: a, angle: 80, rpm: 60}
"""


def seven_link_ring(length: float = 1.0) -> str:
    """Seven links (frame and six moving) in one ring of seven pins, the ends 1 m apart."""
    names = ["frame", *(f"l{i}" for i in range(1, 7)), "frame"]
    joints = "\n".join(
        f"  J{i}: {{type: revolute, links: [{a}, {b}]"
        + (", at: [0, 0]}" if i == 0 else ", at: [1, 0]}" if i == 6 else "}")
        for i, (a, b) in enumerate(itertools.pairwise(names))
    )
    lengths = ", ".join(f"J{i}J{i + 1}: {length}" for i in range(6))
    return (
        "name: ring\nlinks: [frame, l1, l2, l3, l4, l5, l6]\njoints:\n"
        + joints
        + f"\nlengths: {{{lengths}}}\ndrive: {{link: l1, angle: 60, rpm: 60}}\n"
    )


@pytest.mark.parametrize("level", ["velocity", "acceleration"])
def test_a_five_bar_with_one_drive_is_refused_as_needing_two_inputs(level):
    # Kutzbach by hand: l = 5, j = 5: 3·4 − 2·5 = 2 freedoms, one drive given
    with pytest.raises(InputError, match=r"2 degrees of freedom .* but 1 drive: it needs 2 inputs") as err:
        solve(loads(FIVE_BAR, path="five.yaml"), level)
    assert err.value.problems[0].where is not None and err.value.problems[0].where.line == 11  # the drive
    assert "(2 of them)" in (err.value.hint or "")


def test_a_seven_link_ring_with_one_drive_needs_four_inputs_even_where_it_cannot_close():
    # l = 7, j = 7 (a single loop): 3·6 − 2·7 = 4.  Links of 0.1 m cannot span the 1 m between the
    # ground pins: the count refuses first, so the message is the count's, not the assembler's gap.
    for text in (seven_link_ring(), seven_link_ring(0.1)):
        with pytest.raises(InputError, match=r"4 degrees of freedom .* but 1 drive: it needs 4 inputs"):
            solve(loads(text, path="ring.yaml"), "velocity")
    with pytest.raises(InputError, match="it needs 4 inputs"):  # moving it to an angle needs them too
        solve(loads(seven_link_ring(), path="ring.yaml"), "position", SolveOptions(angle=30.0))


def test_a_double_parallelogram_below_kutzbach_is_not_refused_by_the_count():
    # Kutzbach 3·4 − 2·6 = 0 < 1 drive, but the third crank repeats a constraint: it moves.
    # Parallel equal cranks turn together: every crank at 60 rpm = 2π rad/s ccw, the coupler translates.
    kin = solve(load(MECHANISMS / "double_parallelogram.yaml"), "velocity")
    assert kin.mobility.kutzbach == 0 and kin.mobility.numeric == 1
    assert kin.links["crank_3"].omega == pytest.approx(2 * math.pi, rel=1e-9)
    assert kin.links["coupler"].omega == pytest.approx(0.0, abs=1e-9)


def test_kutzbach_counts_at_least_the_rows_the_solver_writes():
    # Why the count may refuse: rank Φ_q ≤ rows ≤ 2j + h, so mobility = 3(l − 1) − rank ≥ Kutzbach.
    from mech.errors import MechError
    from mech.kinematics.solve import compiled

    checked = 0
    for path in example_files():
        mech = load(path)
        if not mech.has_geometry:
            continue
        try:
            sys_ = compiled(mech, None, allow_free=True).system
        except MechError:
            continue
        rows = sys_.m - len(sys_.drive_rows)
        assert rows <= 3 * sys_.n - kutzbach(mech), mech.label
        checked += 1
    assert checked >= 20
