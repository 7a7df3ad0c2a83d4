"""Homogeneous primitives and Kennedy's construction on geometry built by hand (no solver)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from mech.icentres import Contact, Frame, Instant, Pin, Slide, from_instant, kennedy
from mech.icentres.homogeneous import at_infinity, ideal, join, meet, point, separation, unit
from mech.icentres.inspection import facts
from oracles.lines import line_intersection


# -- homogeneous ------------------------------------------------------------------------
def test_parallel_lines_meet_at_infinity_in_their_direction():
    l1 = join(point((0.0, 0.0)), point((1.0, 2.0)))
    l2 = join(point((3.0, 0.0)), point((4.0, 2.0)))
    m = meet(l1, l2)
    assert at_infinity(m)
    assert Frame.direction(m) == pytest.approx((1 / math.sqrt(5), 2 / math.sqrt(5)))


def test_tiny_w_is_a_clean_infinity_not_an_overflow():
    assert at_infinity((1.0, 0.0, 1e-300))
    assert at_infinity((1e-300, 0.0, 0.0))
    assert not at_infinity((1.0, 0.0, 1e-9))  # 1e9 sizes away: still a point


def test_direction_at_infinity_is_one_point_for_both_senses():
    assert Frame.direction((0.0, -1.0, 0.0)) == (0.0, 1.0)
    assert Frame.direction((-1.0, 0.0, 0.0)) == (1.0, 0.0)
    assert separation(ideal((1.0, 1.0)), ideal((-2.0, -2.0))) < 1e-15


def test_frame_round_trip():
    f = Frame((10.0, -3.0), 0.25)
    assert f.xy(f.hom((10.5, -2.0))) == pytest.approx((10.5, -2.0))


# -- Kennedy on hand-built instants ----------------------------------------------------
def four_bar_instant(a, b, c, d):
    pins = (
        Pin("A", ("frame", "crank"), a),
        Pin("B", ("crank", "coupler"), b),
        Pin("C", ("coupler", "rocker"), c),
        Pin("D", ("rocker", "frame"), d),
    )
    return Instant(("frame", "crank", "coupler", "rocker"), Frame((0.0, 0.0), 1.0), pins)


def test_four_bar_secondary_centres_are_the_hand_intersections():
    a, b, c, d = (0.0, 0.0), (0.2, 0.4), (1.1, 0.7), (1.0, 0.0)
    ic = from_instant(four_bar_instant(a, b, c, d))
    assert ic.count == 6
    assert ic.named("I13").point == pytest.approx(line_intersection(a, b, d, c), abs=1e-12)
    assert ic.named("I24").point == pytest.approx(line_intersection(a, d, b, c), abs=1e-12)
    assert ic.named("I13").method == "Kennedy: I12–I23 ∩ I14–I34"
    assert ic.named("I24").method == "Kennedy: I12–I14 ∩ I23–I34"
    assert [c.name for c in ic.centres if c.primary] == ["I12", "I14", "I23", "I34"]


def test_folded_four_bar_lines_coincide_and_kennedy_says_so():
    """All four pins on one line: both Kennedy lines of I13 are that line (no information)."""
    inst = four_bar_instant((0.0, 0.0), (1.0, 0.0), (3.0, 0.0), (2.0, 0.0))
    result = kennedy(4, facts(inst))
    assert result.missing == {
        (0, 2): "Kennedy's lines coincide here",
        (1, 3): "Kennedy's lines coincide here",
    }
    ic = from_instant(inst)
    assert not ic.named("I13").found
    assert "coincide" in ic.named("I13").method


def test_elliptic_trammel_centres_through_points_at_infinity():
    """Double slider: the bar's centre is at (x of the vertical slider's pin, y of the horizontal one's)."""
    p = (0.6, 0.0)  # pin of the block sliding along x
    q = (0.0, 0.8)  # pin of the block sliding along y
    inst = Instant(
        ("frame", "xblock", "yblock", "bar"),
        Frame((0.3, 0.4), 1.0),
        pins=(Pin("P", ("xblock", "bar"), p), Pin("Q", ("yblock", "bar"), q)),
        slides=(Slide("X", "xblock", "frame", (1.0, 0.0)), Slide("Y", "yblock", "frame", (0.0, 1.0))),
    )
    ic = from_instant(inst)
    assert ic.get("frame", "bar").point == pytest.approx((0.6, 0.8), abs=1e-12)
    assert ic.get("frame", "xblock").at_infinity and ic.get("frame", "xblock").direction == (0.0, 1.0)
    # The two blocks: on the line at infinity (I12–I13) and on the bar's line: at infinity along the bar.
    i23 = ic.get("xblock", "yblock")
    assert i23.at_infinity
    assert i23.direction == pytest.approx((0.6, -0.8)) or i23.direction == pytest.approx((-0.6, 0.8))


class Rotating:
    """A link turning at ``omega`` about ``centre`` (hand-made motion, not the solver's)."""

    def __init__(self, omega, centre=(0.0, 0.0)):
        self.omega, self.centre = omega, centre

    def velocity_at(self, p):
        return (-self.omega * (p[1] - self.centre[1]), self.omega * (p[0] - self.centre[0]))


class Translating:
    def __init__(self, v):
        self.omega, self.v = 0.0, v

    def velocity_at(self, p):
        return self.v


def test_cam_and_follower_centre_on_the_common_normal():
    """mechanisms/cam_follower.yaml by hand: I23 = normal ∩ horizontal through O = (15.566, 0) mm."""
    mm = 1e-3
    contact = (0.0, 45.332 * mm)
    n = (math.cos(math.radians(108.951)), math.sin(math.radians(108.951)))
    inst = Instant(
        ("frame", "cam", "follower"),
        Frame((0.0, 0.02), 0.05),
        pins=(Pin("O", ("frame", "cam"), (0.0, 0.0)),),
        slides=(Slide("guide", "follower", "frame", (0.0, 1.0)),),
        contacts=(Contact("contact", "cam", ("cam", "follower"), contact, n),),
    )
    w = 300 * 2 * math.pi / 60
    cam = Rotating(w)
    vc = cam.velocity_at(contact)
    vy = (vc[0] * n[0] + vc[1] * n[1]) / n[1]  # the follower keeps the normal component
    motion = {"frame": Rotating(0.0), "cam": cam, "follower": Translating((0.0, vy))}
    ic = from_instant(inst, motion, drivers=("cam",))
    i23 = ic.get("cam", "follower")
    assert i23.point == pytest.approx((15.566 * mm, 0.0), abs=0.002 * mm)
    assert i23.method == "Kennedy: normal at contact ∩ I12–I13"
    assert i23.check is not None and i23.check < 1e-9
    assert vy == pytest.approx(0.4890, rel=1e-3)  # the file's follower speed
    assert ic.omega_by_icentres["follower"] == 0.0


def test_a_wrong_centre_is_a_loud_bug_not_a_printed_answer():
    from mech.icentres import ICentreDisagreement

    inst = four_bar_instant((0.0, 0.0), (0.2, 0.4), (1.1, 0.7), (1.0, 0.0))
    wrong = {
        "frame": Rotating(0.0),
        "crank": Rotating(1.0),
        "coupler": Rotating(0.5, (0.3, 0.3)),
        "rocker": Rotating(2.0, (1.0, 0.0)),
    }
    with pytest.raises(ICentreDisagreement, match="velocity field"):
        from_instant(inst, wrong)


def test_unit_of_zero_stays_zero():
    assert unit((0.0, 0.0, 0.0)) == (0.0, 0.0, 0.0)


def test_a_flat_faced_programme_cams_centre_is_on_the_normal_at_the_contact_not_at_its_axis():
    # mechanisms/cam_flat_follower.yaml: an SHM rise of 20 mm over 120°, in-line flat face. The cam
    # joint K stands for the face's point on the follower's axis (DESIGN § 1.2), but the common
    # normal passes through the contact, ds/dθ from the axis: I23 is there, where v_follower =
    # ω·x. At 45° into the rise ds/dθ = πh/(2β) sin(πx) with x = 45/120 (the notes' SHM law).
    from mech.icentres import locate
    from mech.kinematics import solve
    from mech.loader import load
    from mech.options import SolveOptions

    m = load(Path(__file__).resolve().parents[2] / "mechanisms" / "cam_flat_follower.yaml")
    kin = solve(m, "velocity", SolveOptions(angle=math.radians(-45), omega=10.0, direction="cw"))
    ic = locate(m, kin)
    i23 = ic.get("cam", "follower").point
    x = math.pi * 0.020 / (2 * math.radians(120)) * math.sin(math.pi * 45 / 120)
    assert abs(i23[0]) == pytest.approx(x, rel=1e-9)
    assert i23[1] == pytest.approx(0.0, abs=1e-12)


def test_an_epicyclic_trains_gear_centres_are_its_pitch_points_by_kennedy():
    # sun 20, planet 30, ring 80 mm fixed (the frame, pinned to sun and arm at one axis): the ring
    # mesh's normal meets the line of the arm's pins (I13, I34) at the pitch point (80, 0) mm, and
    # the sun mesh's normal then meets the frame's line I12–I14 at (20, 0) mm
    import json

    from cli_runner import mech
    from mechanism_texts import epicyclic

    text = epicyclic(pressure=", pressure_angle: 20")
    run = mech("icentres", "-", "--json", input=text)
    assert run.returncode == 0, run.stderr
    found = {c["name"]: c for c in json.loads(run.stdout)["icentres"]}
    for name, x in (("I14", 0.080), ("I24", 0.020)):
        assert "Kennedy" in found[name]["method"], found[name]
        assert found[name]["point"] == pytest.approx([x, 0.0], abs=1e-15)
