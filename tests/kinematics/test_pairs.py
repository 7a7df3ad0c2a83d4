"""Other pairs and drives: multi-drive, redundant chains, cams, gears, rolling, errors."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from builders import build, four_bar, slider_crank

from cli_runner import assert_bad_input, close, mech, strict_json
from mech.errors import GeometryError, InputError, UnsupportedError
from mech.kinematics import mobility, solve
from mech.options import SolveOptions
from mechanism_texts import EXAMPLES, GEARS, ROLLER_CAM_POINT_K, ladder, rack_and_pinion


def five_bar(drives):
    return build(
        ["frame", "left", "l2", "l3", "right"],
        {
            "A": {"links": ["frame", "left"], "at": (0, 0)},
            "B": {"links": ["left", "l2"]},
            "C": {"links": ["l2", "l3"]},
            "D": {"links": ["l3", "right"]},
            "E": {"links": ["right", "frame"], "at": (0.2, 0)},
        },
        lengths={"A-B": 0.05, "B-C": 0.15, "C-D": 0.15, "D-E": 0.05},
        drive=drives,
    )


def test_five_bar_takes_two_drives():
    drives = [
        {"link": "left", "angle": math.radians(80), "omega": 2.0},
        {"link": "right", "angle": math.radians(100), "omega": -1.0},
    ]
    kin = solve(five_bar(drives), "acceleration")
    B = np.array([0.05 * math.cos(math.radians(80)), 0.05 * math.sin(math.radians(80))])
    D = np.array([0.2 + 0.05 * math.cos(math.radians(100)), 0.05 * math.sin(math.radians(100))])
    assert kin.positions["B"] == pytest.approx(tuple(B), abs=1e-14)
    assert kin.positions["D"] == pytest.approx(tuple(D), abs=1e-14)
    C = np.array(kin.positions["C"])
    # C's velocity from both sides: v_B + ω2 k×BC = v_D + ω3 k×DC
    v_from_b = np.array(kin.velocity("B")) + kin.links["l2"].omega * np.array([-(C - B)[1], (C - B)[0]])
    assert kin.velocity("C") == pytest.approx(tuple(v_from_b), abs=1e-12)
    assert kin.links["right"].omega == pytest.approx(-1.0)
    assert kin.mobility.numeric == 2 and kin.mobility.kutzbach == 2


def test_too_few_or_too_many_drives_are_input_errors():
    one_drive = five_bar([{"link": "left", "angle": 1.0, "omega": 1.0}])
    with pytest.raises(GeometryError, match="does not fix where") as err:  # positions undetermined
        solve(one_drive, "position")
    assert "one drive per degree of freedom" in (err.value.hint or "") and "2 degrees of freedom" in str(
        err.value
    )
    with pytest.raises(InputError, match="it needs 2 inputs") as err:  # refused by the count, unassembled
        solve(one_drive)
    assert "one drive per degree of freedom" in (err.value.hint or "") and "2 degrees of freedom" in str(
        err.value
    )
    drawn = solve(
        five_bar(
            [{"link": "left", "angle": 1.0, "omega": 1.0}, {"link": "right", "angle": 2.0, "omega": 1.0}]
        ),
        "position",
    )
    fixed = build(
        ["frame", "left", "l2", "l3", "right"],
        {
            n: {"links": list(j), "at": drawn.positions[n]}
            for n, j in {
                "A": ("frame", "left"),
                "B": ("left", "l2"),
                "C": ("l2", "l3"),
                "D": ("l3", "right"),
                "E": ("right", "frame"),
            }.items()
        },
        drive={"link": "left", "omega": 1.0},
    )
    with pytest.raises(InputError, match=r"2 degrees of freedom .* 1 drive: it needs 2 inputs"):
        solve(fixed)
    m = four_bar()
    extra = build(
        [lk.name for lk in m.links],
        {
            "A": {"links": ["frame", "crank"], "at": (0, 0)},
            "B": {"links": ["crank", "coupler"]},
            "C": {"links": ["coupler", "rocker"]},
            "D": {"links": ["rocker", "frame"], "at": (0.15, 0)},
        },
        lengths={"A-B": 0.04, "B-C": 0.15, "C-D": 0.08},
        drive=[{"link": "crank", "angle": 1.0, "omega": 1.0}, {"link": "rocker", "omega": 1.0}],
    )
    with pytest.raises(InputError, match="more drives than it can take"):
        solve(extra)


def double_parallelogram():
    th = math.radians(60)
    B = (0.05 * math.cos(th), 0.05 * math.sin(th))
    return build(
        ["frame", "crank", "coupler", "r1", "r2"],
        {
            "A": {"links": ["frame", "crank"], "at": (0, 0)},
            "B": {"links": ["crank", "coupler"], "at": B},
            "C": {"links": ["coupler", "r1"], "at": (B[0] + 0.1, B[1])},
            "D": {"links": ["r1", "frame"], "at": (0.1, 0)},
            "F": {"links": ["coupler", "r2"], "at": (B[0] + 0.2, B[1])},
            "E": {"links": ["r2", "frame"], "at": (0.2, 0)},
        },
        drive={"link": "crank", "omega": 3.0},
    )


def test_double_parallelogram_moves_though_kutzbach_says_zero():
    m = double_parallelogram()
    mob = mobility(m)
    assert (mob.kutzbach, mob.numeric, mob.redundant) == (0, 1, 1)
    assert any("Kutzbach's count gives 0" in n for n in mob.notes)
    kin = solve(m, "acceleration", SolveOptions(angle=math.radians(100)))
    # every rocker turns with the crank; the coupler translates
    assert kin.links["r2"].omega == pytest.approx(3.0, rel=1e-10)
    assert kin.links["coupler"].omega == pytest.approx(0.0, abs=1e-12)
    assert kin.positions["F"][0] == pytest.approx(0.2 + 0.05 * math.cos(math.radians(100)), abs=1e-13)


def test_structure_is_locked():
    m = build(
        ["frame", "a", "b"],
        {
            "A": {"links": ["frame", "a"], "at": (0, 0)},
            "B": {"links": ["a", "b"], "at": (0.05, 0.05)},
            "C": {"links": ["b", "frame"], "at": (0.1, 0)},
        },
    )
    mob = mobility(m)
    assert mob.numeric == 0 and mob.kutzbach == 0
    assert mob.locked == ("a", "b") and mob.free == ()


def test_links_moved_by_a_tiny_crank_are_free_not_locked():
    # A 1e-12 m crank on 1 m links: the coupler and rocker turn at about 1e-12 of the crank's rate
    # (rocker ω = −v_A·AB / (k×DB·AB) by hand: 1.2e-12 of it at 30°), never zero: they are not locked.
    m = build(
        ["frame", "crank", "coupler", "rocker"],
        {
            "O": {"links": ["frame", "crank"], "at": (0, 0)},
            "A": {"links": ["crank", "coupler"]},
            "B": {"links": ["coupler", "rocker"], "near": (0.5, 0.9)},
            "D": {"links": ["rocker", "frame"], "at": (1, 0)},
        },
        lengths={"O-A": 1e-12, "A-B": 1.0, "B-D": 1.0},
        drive={"link": "crank", "angle": 30.0, "omega": 1.0},
    )
    mob = solve(m).mobility
    assert mob.free == ("crank", "coupler", "rocker") and mob.locked == ()


def test_a_large_chain_s_mobility_from_its_blocks_matches_the_whole_svd():
    # 20 dyads: 41 moving links, 123 unknowns, solved block by block.  The rank, the links that
    # move and those that do not are the dense SVD's (the condition number is the blocks').
    import numpy as np

    from mech.kinematics.compiled import compiled
    from mech.kinematics.linalg import blocks_of
    from mech.kinematics.mobility import numeric_mobility
    from mech.loader import loads

    mech = loads(ladder(20), path="ladder.yaml")
    comp = compiled(mech, None)
    sys_ = comp.system
    jac = sys_.jacobian(sys_.q0)
    form = blocks_of(sys_)
    assert form is not None
    dense = numeric_mobility(mech, sys_, sys_.q0, jacobian=jac)
    assert comp.mobility.numeric == dense.numeric == 1 and comp.mobility.redundant == dense.redundant == 0
    assert comp.mobility.free == dense.free and comp.mobility.locked == dense.locked == ()
    assert not comp.singular
    assert comp.mobility.condition == pytest.approx(form.condition(jac)[0]) and np.isfinite(dense.condition)


def test_mobility_of_a_gear_pair_with_an_unplaced_pivot_names_the_pivot_not_a_made_up_distance():
    from mech.loader import loads

    text = """
units: {length: mm}
links: [frame, pinion, wheel]
joints:
  O1: {type: revolute, links: [frame, pinion], at: [0, 0]}
  O2: {type: revolute, links: [frame, wheel]}
  mesh: {type: gear, links: [pinion, wheel], teeth: [20, 40], module: 5, pressure_angle: 20}
drive: {link: pinion, rpm: 1200}
"""
    with pytest.raises(GeometryError, match="O2 is on the ground link frame but not placed") as err:
        mobility(loads(text, path="gears.yaml"))
    assert err.value.problems[0].where.line == 6 and "at: [x, y]" in (err.value.hint or "")


def test_mobility_without_drive_or_angle_uses_some_configuration():
    m = build(
        ["frame", "crank", "coupler", "rocker"],
        {
            "A": {"links": ["frame", "crank"], "at": (0, 0)},
            "B": {"links": ["crank", "coupler"]},
            "C": {"links": ["coupler", "rocker"]},
            "D": {"links": ["rocker", "frame"], "at": (0.15, 0)},
        },
        lengths={"A-B": 0.04, "B-C": 0.15, "C-D": 0.08},
    )
    assert mobility(m).numeric == 1


def test_mobility_needs_geometry():
    m = build(["frame", "a"], {"A": {"links": ["frame", "a"]}})
    with pytest.raises(InputError, match="needs geometry"):
        mobility(m)


def cam_follower(normal=0.5235987755982988):  # 30°
    return build(
        ["frame", "cam", "follower"],
        {
            "O": {"links": ["frame", "cam"], "at": (0, 0)},
            "Q": {"links": ["follower", "frame"], "at": (0.1, 0.08)},
            "K": {"type": "cam", "links": ["cam", "follower"], "at": (0.03, 0.04), "normal": normal},
        },
        drive={"link": "cam", "omega": 10.0},
    )


def test_cam_follower_velocity_from_the_common_normal():
    n_ang = math.radians(30)
    kin = solve(cam_follower(n_ang), "velocity")
    n = np.array([math.cos(n_ang), math.sin(n_ang)])
    P, O_, Q = np.array([0.03, 0.04]), np.zeros(2), np.array([0.1, 0.08])
    cross = lambda a, b: a[0] * b[1] - a[1] * b[0]  # noqa: E731
    # n·v_cam(P) = n·v_follower(P)  →  ω_f = ω_c (P−O)×n / (P−Q)×n
    w_f = 10.0 * cross(P - O_, n) / cross(P - Q, n)
    assert kin.links["follower"].omega == pytest.approx(w_f, rel=1e-10)
    assert kin.mobility.numeric == 1 and kin.mobility.kutzbach == 1
    with pytest.raises(InputError, match="contact point") as err:
        kin.velocity("K")
    hint = err.value.hint or ""
    assert "cam" in hint and "follower" in hint and "link=" not in hint  # no Python in a user's hint
    vc, vf = np.array(kin.velocity("K", link="cam")), np.array(kin.velocity("K", link="follower"))
    assert float(n @ (vc - vf)) == pytest.approx(0.0, abs=1e-12)
    slip = kin.sliding("K")
    assert slip == pytest.approx(float(np.array([-n[1], n[0]]) @ (vc - vf)), rel=1e-12)


def test_cam_acceleration_and_moving_are_refused():
    with pytest.raises(UnsupportedError, match="curvature"):
        solve(cam_follower(), "acceleration")
    with pytest.raises(UnsupportedError, match="only the instant drawn"):
        solve(cam_follower(), "velocity", SolveOptions(angle=1.0))


def test_cam_without_normal_says_what_to_add():
    m = build(
        ["frame", "cam", "follower"],
        {
            "O": {"links": ["frame", "cam"], "at": (0, 0)},
            "Q": {"links": ["follower", "frame"], "at": (0.1, 0.08)},
            "K": {"type": "cam", "links": ["cam", "follower"], "at": (0.03, 0.04)},
        },
        drive={"link": "cam", "omega": 10.0},
    )
    with pytest.raises(InputError, match="needs normal"):
        solve(m)


def test_fixed_axis_gears_turn_in_inverse_ratio_and_accelerate():
    m = build(
        ["frame", "g1", "g2"],
        {
            "O1": {"links": ["frame", "g1"], "at": (0, 0)},
            "O2": {"links": ["frame", "g2"], "at": (0.3, 0)},
            "M": {"type": "gear", "links": ["g1", "g2"], "radii": (0.1, 0.2)},
        },
        drive={"link": "g1", "omega": 12.0, "alpha": 2.0},
    )
    kin = solve(m, "acceleration", SolveOptions(angle=1.0))
    assert kin.links["g2"].omega == pytest.approx(-6.0, rel=1e-12)
    assert kin.links["g2"].alpha == pytest.approx(-1.0, rel=1e-12)
    assert kin.positions["M"] == pytest.approx((0.1, 0.0))


def test_epicyclic_train_follows_willis():
    rs, rp, rr = 0.1, 0.2, 0.5
    m = build(
        ["frame", "sun", "arm", "planet"],
        {
            "O": {"links": ["frame", "sun", "arm"], "at": (0, 0)},
            "P": {"links": ["arm", "planet"], "at": (rs + rp, 0)},
            "SP": {"type": "gear", "links": ["sun", "planet"], "radii": (rs, rp)},
            "RP": {"type": "gear", "links": ["frame", "planet"], "radii": (rr, rp), "internal": True},
        },
        drive={"link": "sun", "omega": 10.0},
    )
    kin = solve(m, "acceleration")
    w_arm = 10.0 * rs / (rs + rr)  # ring fixed
    assert kin.links["arm"].omega == pytest.approx(w_arm, rel=1e-12)
    # (ω_p − ω_a) / (ω_s − ω_a) = −r_s / r_p
    assert kin.links["planet"].omega - w_arm == pytest.approx(-(10.0 - w_arm) * rs / rp, rel=1e-12)


def test_an_epicyclic_train_whose_sun_and_arm_turn_on_two_pins_at_one_axis_follows_willis_to_accelerations():
    # the sun pinned to the frame at O, the arm at O2 on the same point: the sun's centre is fixed in
    # the arm too, so both meshes roll relative to the arm (Willis): with the ring fixed,
    # ω_a = ω_s r_s / (r_s + r_r) and (ω_p − ω_a) = −(ω_s − ω_a) r_s / r_p, the same for α; the
    # planet's centre turns on a circle of r_s + r_p about O with the arm
    rs, rp, rr = 0.02, 0.03, 0.08
    m = build(
        ["frame", "sun", "arm", "planet"],
        {
            "O": {"links": ["frame", "sun"], "at": (0, 0)},
            "O2": {"links": ["frame", "arm"], "at": (0, 0)},
            "Q": {"links": ["arm", "planet"], "at": (rs + rp, 0)},
            "m1": {"type": "gear", "links": ["sun", "planet"], "radii": (rs, rp)},
            "m2": {"type": "gear", "links": ["planet", "frame"], "radii": (rp, rr), "internal": True},
        },
        drive={"link": "sun", "omega": 10.0, "alpha": 4.0},
    )
    kin = solve(m, "acceleration")
    w_a, a_a = 10.0 * rs / (rs + rr), 4.0 * rs / (rs + rr)
    assert kin.links["arm"].omega == pytest.approx(w_a, rel=1e-12)
    assert kin.links["arm"].alpha == pytest.approx(a_a, rel=1e-12)
    assert kin.links["planet"].omega - w_a == pytest.approx(-(10.0 - w_a) * rs / rp, rel=1e-12)
    assert kin.links["planet"].alpha - a_a == pytest.approx(-(4.0 - a_a) * rs / rp, rel=1e-12)
    r = rs + rp  # Q at (r, 0): a = (−ω² r, α r)
    assert kin.acceleration("Q") == pytest.approx((-(w_a**2) * r, a_a * r), rel=1e-12)


def test_rolling_wheel_on_ground_driven_by_its_axle():
    R = 0.05
    m = build(
        ["frame", "block", "wheel"],
        {
            "P": {
                "type": "prismatic",
                "links": ["block", "frame"],
                "path": {"through": (0, R), "angle": 0.0},
            },
            "W": {"links": ["block", "wheel"], "at": (0, R)},
            "K": {"type": "rolling", "links": ["wheel", "frame"], "at": (0, 0)},
        },
        drive={"joint": "P", "speed": 2.0},
    )
    kin = solve(m, "velocity")
    assert kin.links["wheel"].omega == pytest.approx(-2.0 / R, rel=1e-12)  # rolling right: clockwise
    assert kin.velocity("K") == pytest.approx((0.0, 0.0), abs=1e-12)  # both links agree at a rolling contact
    assert kin.mobility.redundant == 1 and kin.mobility.numeric == 1


def test_rubbing_velocity_uses_the_pin_radius():
    m = build(
        ["frame", "crank", "coupler", "rocker"],
        {
            "A": {"links": ["frame", "crank"], "at": (0, 0), "radius": 0.01},
            "B": {"links": ["crank", "coupler"], "radius": 0.005},
            "C": {"links": ["coupler", "rocker"]},
            "D": {"links": ["rocker", "frame"], "at": (0.15, 0)},
        },
        lengths={"A-B": 0.04, "B-C": 0.15, "C-D": 0.08},
        drive={"link": "crank", "angle": 1.0, "omega": -8.0},
    )
    kin = solve(m)
    assert kin.rubbing("A") == pytest.approx(8.0 * 0.01)
    assert kin.rubbing("B") == pytest.approx(abs(-8.0 - kin.links["coupler"].omega) * 0.005)
    with pytest.raises(InputError, match="no radius"):
        kin.rubbing("C")


def test_spherical_pair_is_unsupported():
    m = build(
        ["frame", "a"],
        {"A": {"type": "spherical", "links": ["frame", "a"], "at": (0, 0)}},
        drive={"link": "a", "omega": 1.0},
    )
    with pytest.raises(
        UnsupportedError, match="planar solvers cannot model a spherical pair; mech dof still counts it"
    ):
        solve(m)


def test_missing_speed_and_misused_options():
    with pytest.raises(InputError, match=r"give rpm or omega \(or --rpm\)"):
        solve(four_bar(omega=None), "velocity")
    assert solve(four_bar(omega=None), "position").links["rocker"].omega is None
    two = five_bar(
        [{"link": "left", "angle": 1.0, "omega": 1.0}, {"link": "right", "angle": 2.0, "omega": 1.0}]
    )
    with pytest.raises(InputError, match="override a single drive"):
        solve(two, options=SolveOptions(omega=3.0))
    with pytest.raises(InputError, match="level must be"):
        solve(four_bar(), "jerk")


def test_result_is_frozen_and_queries_name_their_choices():
    kin = solve(four_bar(), "velocity")
    with pytest.raises(AttributeError):
        kin.size = 2.0  # type: ignore[misc]
    with pytest.raises(TypeError):
        kin.positions["C"] = (0.0, 0.0)  # type: ignore[index]
    with pytest.raises(InputError, match="no point named Z"):
        kin.velocity("Z")
    with pytest.raises(InputError, match="accelerations were not solved"):
        kin.acceleration("C")
    assert kin.drives[0].omega == pytest.approx(-4 * math.pi)


def test_override_of_direction_and_speed_is_recorded_in_drives():
    kin = solve(slider_crank(omega=10.0), options=SolveOptions(omega=5.0, direction="cw"))
    assert kin.drives[0].omega == -5.0


def test_acceleration_command_reports_the_gear_pitch_point_on_each_gear(run):
    from pathlib import Path

    path = Path(__file__).resolve().parents[2] / "mechanisms" / "gear_pair.yaml"
    result = run("acceleration", str(path))
    assert result.exit_code == 0, result.output
    assert "mesh@pinion" in result.output and "mesh@wheel" in result.output  # DESIGN § 1.2: K@link
    # pinion 1200 rpm, r = 50 mm: ω²r = 789.57 m/s²; wheel 600 rpm, r = 100 mm: 394.78 m/s²
    assert "789.57" in result.output and "394.78" in result.output
    assert "link=" not in result.output


# -- through the command line as a user runs it (cli_runner: tracebacks shown) -----------
@pytest.mark.parametrize("size", ["teeth: [20, 40], module: 5 mm", "radii: [0.05, 0.1]"])
def test_gear_centres_that_contradict_the_pitch_radii_are_refused(write, size):
    """Pitch radii 50 + 100 mm need centres 150 mm apart; at 300 mm the teeth would slip."""
    f = write(GEARS.format(x2=0.3, size=size))
    assert_bad_input(mech("velocity", str(f)), f)


def test_consistent_gears_turn_at_the_teeth_ratio_and_the_pitch_point_moves_alike_on_both(write):
    """Centres 150 mm apart, z 20/40: ω2 = -ω1/2; the pitch point moves at ω1 r1 on both gears."""
    f = write(GEARS.format(x2=0.15, size="teeth: [20, 40], module: 5 mm"))
    p = mech("velocity", "--json", str(f))
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    w1 = 600 * 2 * math.pi / 60
    assert close(d["links"]["g2"]["omega"], -w1 / 2)
    speeds = [math.hypot(*q["velocity"]) for q in d["points"] if q["point"] == "M"]
    assert speeds and all(close(s, w1 * 0.05) for s in speeds)


def test_velocities_of_a_structure_are_refused(write):
    """Three links pinned in a triangle have no motion (dof 0): nothing to drive."""
    f = write(
        """\
links: [frame, a, b]
joints:
  A: {type: revolute, links: [frame, a], at: [0, 0]}
  B: {type: revolute, links: [a, b], at: [1, 0]}
  C: {type: revolute, links: [b, frame], at: [1, 1]}
drive: {link: a, rpm: 60}
"""
    )
    assert_bad_input(mech("velocity", str(f)), located=False)


def test_a_five_bar_with_one_drive_is_refused_naming_the_drives(write):
    """dof 2, one drive given: located, and the message speaks of drives."""
    f = write(
        """\
links: [frame, a, b, c, d]
joints:
  A: {type: revolute, links: [frame, a], at: [0, 0]}
  B: {type: revolute, links: [a, b]}
  C: {type: revolute, links: [b, c], near: [1, 1.5]}
  D: {type: revolute, links: [c, d]}
  E: {type: revolute, links: [d, frame], at: [2, 0]}
lengths: {AB: 1, BC: 1.2, CD: 1.2, DE: 1}
drive: {link: a, angle: 80, rpm: 60}
"""
    )
    p = mech("velocity", str(f))
    assert_bad_input(p, f)
    assert "drive" in p.stderr


def test_velocities_with_a_spherical_pair_are_refused_where_it_is_written(write):
    f = write(
        """\
links: [frame, a, b]
joints:
  A: {type: spherical, links: [frame, a], at: [0, 0]}
  B: {type: revolute, links: [a, b], at: [1, 0]}
drive: {link: a, rpm: 60}
"""
    )
    assert_bad_input(mech("velocity", str(f)), f)


def test_a_cam_without_a_contact_point_is_a_located_error_naming_it(write):
    """A cam joint with no `at` once raised KeyError 'T' in constraints.build_system."""
    f = write(
        """\
links: [frame, cam, follower]
joints:
  O: {type: revolute, links: [frame, cam], at: [0, 0]}
  F: {type: prismatic, links: [follower, frame], path: {through: [0, 0], angle: 90}, point: T}
  T: {type: cam, links: [cam, follower]}
drive: {link: cam, angle: 0, rpm: 60}
"""
    )
    p = mech("velocity", str(f))
    assert_bad_input(p, f)
    assert "T" in p.stderr


# -- a higher pair's points (DESIGN § 1.2, issue 21 item 1) ---------------------------------------


def test_a_cam_joint_is_the_followers_point_and_k_at_link_each_links_point_at_the_contact(write):
    from mech.loader import load

    kin = solve(load(write(ROLLER_CAM_POINT_K)), "acceleration")
    w = -300 * 2 * math.pi / 60  # cw
    # the roller's centre from the cycloidal law, half-way up a 40 mm rise over 120°:
    # v = |ω| h/β (1 − cos 2πx) = 31.416 × 40 mm / 2.0944 × 2 = 1.2 m/s, along the path
    beta = math.radians(120)
    v_law = abs(w) * 0.040 / beta * (1 - math.cos(math.pi))
    assert kin.velocity("K") == pytest.approx((0.0, v_law), abs=1e-9)
    assert kin.position("K") == pytest.approx((-0.010, math.sqrt(0.040**2 - 0.010**2) + 0.020), abs=1e-12)
    # K@follower: the roller's point at the contact, one roller radius from its centre; a
    # translating follower's points all move alike
    c = kin.position("K@cam")
    assert kin.position("K@follower") == c
    assert math.dist(c, kin.position("K")) == pytest.approx(0.010, rel=1e-9)
    assert kin.velocity("K@follower") == pytest.approx((0.0, v_law), abs=1e-9)
    # K@cam: the cam's point there turns about O, v = ω × r, a = −ω² r
    assert kin.velocity("K@cam") == pytest.approx((-w * c[1], w * c[0]), rel=1e-12)
    assert kin.acceleration("K@cam") == pytest.approx((-(w**2) * c[0], -(w**2) * c[1]), rel=1e-12)
    # the two points at a contact move alike along the common normal (no gap opens, none closes)
    k = kin.position("K")
    n = ((k[0] - c[0]) / 0.010, (k[1] - c[1]) / 0.010)
    vc, vf = kin.velocity("K@cam"), kin.velocity("K@follower")
    assert (vc[0] - vf[0]) * n[0] + (vc[1] - vf[1]) * n[1] == pytest.approx(0.0, abs=1e-9 * v_law)
    with pytest.raises(InputError, match="frame is not a link of joint K"):
        kin.velocity("K@frame")


def test_a_contact_points_acceleration_refused_names_the_k_at_link_syntax():
    # a gear's pitch point: both gears' points there share a velocity but not an acceleration
    from mech.loader import load

    kin = solve(load(Path(__file__).resolve().parents[2] / "mechanisms" / "gear_pair.yaml"), "acceleration")
    with pytest.raises(InputError) as err:
        kin.acceleration("mesh")
    assert "mesh@pinion or mesh@wheel" in (err.value.hint or "")
    # pinion 1200 rpm on r = 50 mm, wheel 600 rpm on r = 100 mm: ω²r toward each centre
    w1, w2 = 1200 * math.pi / 30, 600 * math.pi / 30
    assert kin.acceleration("mesh@pinion") == pytest.approx((-(w1**2) * 0.050, 0.0), rel=1e-9, abs=1e-9)
    assert kin.acceleration("mesh@wheel") == pytest.approx((w2**2 * 0.100, 0.0), rel=1e-9, abs=1e-9)


@pytest.mark.parametrize(
    ("name", "own"),
    [("eccentric_cam.yaml", "F"), ("eccentric_cam_roller.yaml", "C")],
)
def test_a_profile_cams_joint_is_the_followers_own_point_and_k_at_link_the_contact(name, own):
    # DESIGN § 1.2: a flat face's point on the follower's axis (here F, on x = 0, at e sin θ + R),
    # a roller's centre (C, at e sin θ + √((R + r)² − e² cos² θ)); θ = 30°, e = 15, R = 40, r = 10 mm
    from mech.loader import load

    kin = solve(load(Path(__file__).resolve().parents[2] / "mechanisms" / name), "acceleration")
    w, e, th = 10 * math.pi, 0.015, math.radians(30)
    y = e * math.sin(th) + (0.040 if own == "F" else math.sqrt(0.050**2 - (e * math.cos(th)) ** 2))
    assert kin.position("K") == pytest.approx((0.0, y), abs=1e-12)
    assert kin.velocity("K") == pytest.approx(kin.velocity(own), abs=1e-12)
    # the contact: a flat face touches straight above E (x = e cos θ), a roller on the line E–C
    c = kin.position("K@cam")
    if own == "F":
        assert c == pytest.approx((e * math.cos(th), y), abs=1e-12)
    else:
        ex, ey = e * math.cos(th), e * math.sin(th)
        assert math.dist(c, (ex, ey)) == pytest.approx(0.040, rel=1e-9)
        assert math.dist(c, (0.0, y)) == pytest.approx(0.010, rel=1e-9)
    assert kin.velocity("K@cam") == pytest.approx((-w * c[1], w * c[0]), rel=1e-12)
    assert kin.velocity("K@follower") == pytest.approx(kin.velocity(own), abs=1e-12)


@pytest.mark.parametrize(("name", "own"), [("eccentric_cam.yaml", "F"), ("eccentric_cam_roller.yaml", "C")])
def test_point_k_on_a_profile_cams_slide_is_the_followers_own_point(name, own):
    # DESIGN § 1.2: `point: K` on the follower's slide means the follower's own point.  The same
    # files with `point: K` for `point: F` (a flat face) or `point: C` (a roller's centre): the
    # follower moves as before, y = e sin θ + R (flat) or e sin θ + S, S = √((R + r)² − e² cos² θ)
    # (roller), so v = ω y′ and a = ω² y″ (θ = 30°, e = 15, R = 40, r = 10 mm, 300 rpm ccw):
    # y′ = e cos θ (+ e² sin θ cos θ / S), y″ = −e sin θ (+ e² cos 2θ / S − (e² sin θ cos θ)² / S³)
    from mech.loader import loads

    path = Path(__file__).resolve().parents[2] / "mechanisms" / name
    text = path.read_text(encoding="utf-8").replace(f"point: {own}}}", "point: K}")
    assert "point: K}" in text
    kin = solve(loads(text, path=name), "acceleration")
    w, e, th = 10 * math.pi, 0.015, math.radians(30)
    y, dy, d2y = 0.040 + e * math.sin(th), e * math.cos(th), -e * math.sin(th)
    if own == "C":
        root, sc = math.sqrt(0.050**2 - (e * math.cos(th)) ** 2), e * e * math.sin(th) * math.cos(th)
        y, dy, d2y = y - 0.040 + root, dy + sc / root, d2y + e * e * math.cos(2 * th) / root - sc**2 / root**3
    assert kin.position("K") == pytest.approx((0.0, y), abs=1e-12)
    assert kin.velocity("K") == pytest.approx((0.0, w * dy), abs=1e-12)
    assert kin.acceleration("K") == pytest.approx((0.0, w**2 * d2y), abs=1e-9)
    assert kin.velocity(own) == pytest.approx(kin.velocity("K"), abs=1e-12)


def test_tables_and_json_name_each_links_point_at_a_contact_k_at_link(run, write):
    path = write(ROLLER_CAM_POINT_K)
    table = run("acceleration", str(path))
    assert table.exit_code == 0, table.output
    assert "K@cam" in table.output and "K@follower" in table.output
    data = json.loads(run("velocity", str(path), "--json").output)
    rows = {(p["point"], p["link"]) for p in data["points"]}
    assert {("K", None), ("K@cam", "cam"), ("K@follower", "follower")} <= rows
    gear = Path(__file__).resolve().parents[2] / "mechanisms" / "gear_pair.yaml"
    rows = {p["point"] for p in json.loads(run("acceleration", str(gear), "--json").output)["points"]}
    assert {"mesh@pinion", "mesh@wheel"} <= rows


def test_a_high_gear_ratio_solve_is_called_ill_conditioned_not_a_toggle(run, write):
    # a 1e12 mm pinion on a 1 mm wheel: Φ_q's condition number is 2e12 at every angle only through
    # its scales (issue 21 item 6); no links are in line, so no toggle may be named
    text = """
units: {length: mm, angle: deg}
links: [frame, pinion, wheel]
joints:
  O1: {type: revolute, links: [frame, pinion], at: [0, 0]}
  O2: {type: revolute, links: [frame, wheel], at: [1000000000001, 0]}
  mesh: {type: gear, links: [pinion, wheel], radii: [1000000000000, 1]}
drive: {link: pinion, rpm: 1200, direction: cw}
"""
    result = run("velocity", str(write(text)))
    assert result.exit_code == 2
    assert "toggle or dead-centre" not in result.stderr
    assert "ill-conditioned" in result.stderr and "not a toggle" in result.stderr


@pytest.mark.parametrize(
    ("example", "point", "hint"),
    [
        # the contact of a rolling pair runs round the wheel as it rolls: nothing names a point of it
        (
            "rolling_wheel.yaml",
            "  T: {link: wheel, from: B, toward: W, offset: [0, 10]}\n",
            "points fixed in the link",
        ),
        # a profile cam's contact runs round both profiles; its follower's own point is the roller's centre C
        (
            "eccentric_cam_roller.yaml",
            "  T: {link: follower, from: K, toward: C, distance: 5}\n",
            "place it from C",
        ),
    ],
)
def test_a_point_placed_from_a_contact_is_refused_at_its_line_naming_what_to_use(write, example, point, hint):
    text = (EXAMPLES / example).read_text(encoding="utf-8").split("\nanswers:")[0]
    if "\npoints:\n" in text:
        text = text.replace("\npoints:\n", "\npoints:\n" + point, 1)
    else:
        text += "\npoints:\n" + point
    path = write(text)
    line = text.splitlines().index(point.rstrip("\n")) + 1
    for command in ("position", "velocity", "icentres", "properties"):
        run = mech(command, str(path))
        assert_bad_input(run, path)
        assert f"{path}:{line}:3: error: T is placed" in run.stderr
        assert hint in run.stderr


GEAR_PAIR = """
units: {{length: mm, angle: deg}}
links: [frame, pinion, wheel]
joints:
  O1: {{type: revolute, links: [frame, pinion], at: [0, 0]}}
  O2: {{type: revolute, links: [frame, wheel], at: [150, 0]}}
  mesh: {{type: gear, links: [pinion, wheel], teeth: [20, 40], {fields}}}
drive: {{link: pinion, rpm: 1200}}
"""


@pytest.mark.parametrize("angle", ["95", "90", "-5"])
def test_a_gear_pressure_angle_outside_0_to_90_degrees_is_refused_where_written(angle):
    # the tooth load along the normal has a torque arm r·cos φ: none at 90°, the wrong side past it
    from mech.loader import loads

    text = GEAR_PAIR.format(fields=f"module: 5, pressure_angle: {angle}")
    with pytest.raises(InputError) as err:
        loads(text, path="gears.yaml")
    column = text.splitlines()[6].index("pressure_angle: ") + len("pressure_angle: ") + 1
    assert f"gears.yaml:7:{column}" in str(err.value) and "90°" in str(err.value)
    assert "20°" in (err.value.hint or "")


def test_a_negative_gear_module_is_said_to_be_not_positive_not_missing():
    from mech.loader import loads

    with pytest.raises(InputError) as err:
        loads(GEAR_PAIR.format(fields="module: -5, pressure_angle: 20"), path="gears.yaml")
    assert "module must be greater than zero" in str(err.value)
    assert "need a `module`" not in str(err.value)


def test_gears_whose_centres_no_one_link_holds_are_refused_accelerations_saying_why():
    # each gear turns on an arm of its own: the pitch circles are given, but no link holds both
    # centres, so the pair is known only as it touches now (not for want of a profile)
    text = """\
units: {length: mm, angle: deg}
links: [frame, a, b, g1, g2]
joints:
  P1: {type: revolute, links: [frame, a], at: [0, 0]}
  P2: {type: revolute, links: [frame, b], at: [200, 0]}
  Q1: {type: revolute, links: [a, g1], at: [70, 0]}
  Q2: {type: revolute, links: [b, g2], at: [130, 0]}
  m: {type: gear, links: [g1, g2], radii: [30, 30]}
drive:
  - {link: a, angle: 0, rpm: 10}
  - {link: b, angle: 180, rpm: 10, direction: cw}
  - {link: g1, angle: 0, rpm: 60, relative_to: a, about: Q1}
"""
    from mech.loader import loads

    m = loads(text, path="apart.yaml")
    solve(m, "velocity")  # the instant's rates are known
    with pytest.raises(UnsupportedError) as err:
        solve(m, "acceleration")
    assert "no one link, an arm or the frame, holds both centres" in str(err.value)
    assert "no profile is given" not in str(err.value)


def test_a_gear_with_a_null_radius_is_a_rack_that_moves_with_its_pinion():
    # radii: [50, null] (DESIGN § 1.1, as for rolling): the pinion's pitch circle rolls on the rack's
    # pitch line under it, so the rack slides r ω per unit time and r θ over a turn θ
    from mech.kinematics import sweep
    from mech.loader import loads

    m = loads(rack_and_pinion(loads=""), path="rack.yaml")
    kin = solve(m, "acceleration", SolveOptions(alpha=3.0))
    w = 2 * math.pi
    assert kin.velocity("R") == pytest.approx((0.05 * w, 0.0), abs=1e-12)
    assert kin.acceleration("R") == pytest.approx((0.05 * 3.0, 0.0), abs=1e-12)
    sw = sweep(m, [0.0, math.pi / 2, math.pi], level="position", quantities=["displacement.S"])
    assert sw.series("displacement.S") == pytest.approx([0.0, 0.05 * math.pi / 2, 0.05 * math.pi], abs=1e-12)


@pytest.mark.parametrize(
    ("mesh", "says", "hint"),
    [
        ("teeth: [20, null], module: 5", "a rack has no tooth count", "radii: [r, null]"),
        ("radii: [50, null], internal: true", "a rack (a null radius) has no inside", "leave internal out"),
    ],
)
def test_a_rack_written_as_a_gear_pair_is_refused_where_it_cannot_be_one(mesh, says, hint):
    from mech.loader import loads

    with pytest.raises(InputError) as err:
        loads(rack_and_pinion(mesh, pressure="", loads=""), path="rack.yaml")
    problem = err.value.problems[0]
    assert says in problem.message and hint in (problem.hint or "")
    assert problem.where is not None and problem.where.line == 6


def test_a_racks_radius_given_to_the_rack_is_refused_with_the_order_to_write(write):
    # radii follow links: [null, 50] for links [pinion, rack] gives the circle to the rack, which
    # slides on no pin; the message says so and how to write it, where it was "needs at"
    path = write(rack_and_pinion("radii: [null, 50]", pressure="", loads=""))
    run = mech("velocity", str(path))
    assert_bad_input(run, path)
    assert "the pitch circle is given to rack, which turns on no single pin" in run.stderr
    assert "write radii: [50, null]" in run.stderr
