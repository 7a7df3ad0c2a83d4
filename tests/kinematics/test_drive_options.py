"""Command-line speeds go to the drive they fit, never reinterpreted.

A slider drive's speed is m/s along its path; --rpm/--omega are a crank's
rad/s.  Feeding one to the other once printed a crank turning 129 rad/s for
"--rpm 100" on a slider-driven file: now it is refused, and --speed exists.
"""

from __future__ import annotations

import math

import pytest

from cli_runner import close, mech, no_traceback, points, strict_json
from mech.errors import InputError
from mech.kinematics import solve
from mech.loader import loads
from mech.options import SolveOptions
from mechanism_texts import slider_crank as slider_crank_text

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
    """ω of the crank driven by the piston at x_B = 0.28 m, by hand.

    A = (r cos θ, r sin θ) with |A − B| = l; differentiating
    (r cos θ − x)² + (r sin θ)² = l² gives ω = ẋ (r cos θ − x) / (r x sin θ).
    """
    r, rod, x = 0.08, 0.25, 0.28
    cos_t = (r * r + x * x - rod * rod) / (2 * r * x)
    th = math.acos(cos_t)  # A above the axis (near: [40, 69])
    return v_b * (r * math.cos(th) - x) / (r * x * math.sin(th))


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


def test_a_huge_angle_override_is_reduced_exactly_in_degrees(write):
    """1e300 deg is a whole number of turns (math.fmod gives 0): A at (r, 0), not near 266 deg."""
    assert math.fmod(1e300, 360.0) == 0.0
    f = write(slider_crank_text(0.1, 0.4, 90, 10))
    p = mech("position", "--json", str(f), "--angle", "1e300")
    no_traceback(p)
    assert p.returncode == 0, p.stderr
    ax, ay = points(strict_json(p.stdout))["A"]["position"]
    assert close(ax, 0.1) and abs(ay) < 1e-12


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
