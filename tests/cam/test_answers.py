"""The cam answer keys through ``mech check``: pressure angle (at the instant and largest) and lift.

Reference values are closed forms: for an in-line follower tan φ = (ds/dθ)/(r_p + s), and an
SHM rise of h over β is at s = h/2, ds/dθ = πh/2β half-way.
"""

from __future__ import annotations

import json
import math

PROBLEM = """\
units: {{length: mm, angle: deg}}
links: [frame, cam, follower]
joints:
  O: {{type: revolute, links: [frame, cam], at: [0, 0]}}
  {follower_joint}
  K: {{type: cam, links: [cam, follower],
      program: {{base_radius: 40, follower: roller, roller_radius: 10,
                segments: [{{rise: {rise}, over: 120, law: shm}}, {{dwell: 30}},
                           {{return: {rise}, over: 150, law: cycloidal}}, {{dwell: 60}}]}}}}
{more}drive: {{link: cam, angle: 60, rpm: 300, direction: cw}}
answers:
  tolerance: 0.5%
{answers}
"""
SLIDE = "S: {type: prismatic, links: [follower, frame], path: {through: [0, 0], angle: 90}}"

H, BETA, RP = 30.0, math.radians(120), 50.0
S_MID = H / 2
PHI_MID = math.degrees(math.atan(math.pi * H / (2 * BETA) / (RP + S_MID)))  # 19.093°


def check(run, write, answers: str, *, follower_joint: str = SLIDE, rise: str = "30", more: str = ""):
    path = write(PROBLEM.format(answers=answers, follower_joint=follower_joint, rise=rise, more=more))
    result = run("check", str(path), "--json")
    return result.exit_code, json.loads(result.output)


def verdicts(report) -> dict[str, str]:
    (result,) = report["results"]
    return {r["key"]: r["status"] for r in result["answers"]}


def test_right_claims_pass(run, write):
    code, report = check(run, write, f"  displacement.K: {S_MID} mm\n  pressure_angle.K: {PHI_MID:.4f} deg\n")
    assert code == 0, report
    assert set(verdicts(report).values()) == {"pass"}


def test_claims_off_by_five_percent_fail(run, write):
    code, report = check(
        run, write, f"  displacement.K: {S_MID * 1.05} mm\n  pressure_angle.K: {PHI_MID * 0.95:.4f} deg\n"
    )
    assert code == 1
    assert set(verdicts(report).values()) == {"fail"}


def test_largest_pressure_angle_is_checked_against_the_formulas_maximum(run, write):
    # the cycloidal return's maximum of |atan(s'/(r_p + s))|, found here on a fine grid
    beta = math.radians(150)
    best = 0.0
    for k in range(200_001):
        x = k / 200_000
        s = H - H * (x - math.sin(2 * math.pi * x) / (2 * math.pi))
        ds = H / beta * (1 - math.cos(2 * math.pi * x))
        best = max(best, math.degrees(math.atan(ds / (RP + s))))
    code, report = check(run, write, f"  pressure_angle.K.max: {best:.5f} deg\n")
    assert code == 0, report


def test_oscillating_followers_displacement_is_an_angle(run, write):
    # an arm of 80 mm about (90, 30): the programme's rise of 20 is then 20°, half of it at 60°
    code, report = check(
        run,
        write,
        "  displacement.K: 10 deg\n",
        follower_joint="P: {type: revolute, links: [follower, frame], at: [90, 30]}",
        rise="20",
        more="lengths: {PK: 80}\n",
    )
    assert code == 0, report


def test_key_on_a_joint_without_a_programme_is_an_error_row(run, write):
    code, report = check(run, write, "  pressure_angle.O: 10 deg\n")
    assert code == 1
    assert verdicts(report) == {"pressure_angle.O": "error"}
