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


def _eccentric(name: str, answers: str) -> str:
    from pathlib import Path

    text = (Path(__file__).resolve().parents[2] / "mechanisms" / name).read_text(encoding="utf-8")
    return text + answers


def test_displacement_of_an_eccentric_cams_follower_is_its_lift_from_the_lowest(run, write):
    # DESIGN § 1.2: any cam that moves. Eccentric disc R = 40, e = 15 mm at θ = 30°: a flat face
    # stands at e sin θ + R, lowest R − e, so its lift is e(1 + sin θ) = 22.5 mm; a roller r = 10 at
    # e sin θ + √((R + r)² − e² cos² θ) = 55.783 mm, lowest R + r − e = 35 mm: 20.783 mm.
    # The joint's name K stands for the follower's own point, so displacement.K is the same.
    e, th = 15.0, math.radians(30)
    flat = e * (1 + math.sin(th))
    roller = e * math.sin(th) + math.sqrt(50**2 - (e * math.cos(th)) ** 2) - 35
    for name, point, lift in (("eccentric_cam.yaml", "F", flat), ("eccentric_cam_roller.yaml", "C", roller)):
        path = write(_eccentric(name, f"  displacement.{point}: {lift} mm\n  displacement.K: {lift} mm\n"))
        result = run("check", str(path), "--json")
        report = json.loads(result.output)
        assert result.exit_code == 0, report
        assert set(verdicts(report).values()) == {"pass"}
        wrong = write(_eccentric(name, f"  displacement.{point}: {lift * 1.05} mm\n"), name="wrong.yaml")
        assert run("check", str(wrong)).exit_code == 1


def test_answer_keys_name_each_links_point_at_a_cam_contact(run, write):
    # K@cam turns with the cam: v = ω r, a = ω² r at the contact, r = |O K@cam|; K@follower moves with
    # the follower along its path at ds/dθ ω (SHM half-way: π h / 2β ω)
    from mech.kinematics import solve
    from mech.loader import load

    path = write(PROBLEM.format(answers="  dof: 1\n", follower_joint=SLIDE, rise="30", more=""))
    contact = solve(load(path), "velocity").position("K@cam")
    w = 10 * math.pi
    r = math.hypot(*contact)
    v_f = math.pi * 0.030 / (2 * BETA) * w
    code, report = check(
        run,
        write,
        f"  velocity.K@cam: {w * r} m/s\n  acceleration.K@cam: {w * w * r} m/s^2\n"
        f"  velocity.K@follower: {v_f} m/s\n  velocity.K: {v_f} m/s\n",
    )
    assert code == 0, report
    assert set(verdicts(report).values()) == {"pass"}


def test_a_follower_that_dwells_at_both_limits_has_the_time_ratio_of_its_strokes(run, write):
    # DESIGN § 1.2: two limit positions, so a time ratio.  The rise takes 120° of the cam's turn and
    # the return 150°; the dwells (30° at the top, 60° at the bottom) belong to neither: 150/120.
    code, report = check(run, write, "  time_ratio.S: 1.25\n  time_ratio: 1.25\n  time_ratio.follower: 0.8")
    assert verdicts(report) == {"time_ratio.S": "pass", "time_ratio": "pass", "time_ratio.follower": "fail"}
    assert code == 1
