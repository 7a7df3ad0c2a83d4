"""I-centres of the example mechanisms, against hand derivations and the velocity field."""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import pytest

from mech.icentres import ICentres, locate
from mech.kinematics import solve
from mech.loader import load
from mech.options import SolveOptions
from oracles.lines import line_intersection

MECHANISMS = Path(__file__).resolve().parents[2] / "mechanisms"


def example_files() -> list[Path]:
    """Every shipped example mechanism."""
    return sorted(MECHANISMS.glob("*.yaml"))


REL = 1e-9  # agreement with the velocity field / hand derivations, relative to size


def located(name: str, **options) -> tuple[ICentres, object]:
    mech = load(MECHANISMS / name)
    kin = solve(mech, level="velocity", options=SolveOptions(**options))
    return locate(mech, kin), kin


def hom(c, size):
    """An I-centre as a unit homogeneous vector in size units (for Kennedy's-theorem checks)."""
    if c.point is not None:
        v = (c.point[0] / size, c.point[1] / size, 1.0)
    else:
        v = (c.direction[0], c.direction[1], 0.0)
    n = math.hypot(*v)
    return tuple(x / n for x in v)


def det3(a, b, c):
    return (
        a[0] * (b[1] * c[2] - b[2] * c[1])
        - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
    )


def assert_laws(ic: ICentres, kin) -> None:
    """Kennedy's theorem for every triple; v_i = v_j at every finite I_ij; ω by I-centres = solver's."""
    size = kin.size
    n = ic.n
    for i, j, k in itertools.combinations(range(1, n + 1), 3):
        a, b, c = (hom(ic.by_number(*p), size) for p in ((i, j), (j, k), (i, k)))
        assert abs(det3(a, b, c)) < 1e-9, (i, j, k)
    wref = max(abs(s.omega) for s in kin.links.values())
    for c in ic.centres:
        assert c.found, c
        if c.point is not None:
            va = kin.links[c.links[0]].velocity_at(c.point)
            vb = kin.links[c.links[1]].velocity_at(c.point)
            far = max(1.0, math.hypot(*c.point) / size)
            assert math.hypot(va[0] - vb[0], va[1] - vb[1]) <= REL * wref * size * far, c.name
        if c.check is not None:
            assert c.check <= REL
    for o in ic.omegas:
        assert o.omega == pytest.approx(kin.links[o.link].omega, rel=REL, abs=REL * wref)


def test_four_bar_six_centres_with_i13_i24_from_hand_lines():
    ic, kin = located("four_bar.yaml")
    p = kin.positions
    assert ic.count == 6 and ic.formula == "N = n(n − 1)/2 = 4·3/2 = 6"
    # I13 (frame, coupler): crank line AB extended meets rocker line DC extended.
    assert ic.named("I13").point == pytest.approx(
        line_intersection(p["A"], p["B"], p["D"], p["C"]), abs=REL * kin.size
    )
    # I24 (crank, rocker): ground line AD meets coupler line BC.
    assert ic.named("I24").point == pytest.approx(
        line_intersection(p["A"], p["D"], p["B"], p["C"]), abs=REL * kin.size
    )
    assert ic.get("frame", "coupler") is ic.named("I13") and ic.by_number(3, 1) is ic.named("I13")
    assert ic.named("I13").method == "Kennedy: I12–I23 ∩ I14–I34" and not ic.named("I13").primary
    assert ic.named("I12").method == "pin A" and ic.named("I12").primary
    assert_laws(ic, kin)


def test_four_bar_omega_by_icentres_matches_khurmi_published():
    """Khurmi & Gupta Ex. 7.1: ω_CD = 4.8 rad/s cw (graphical): within drawing accuracy (2%)."""
    ic, _ = located("four_bar.yaml")
    w = ic.omega_by_icentres["rocker"]
    assert w < 0 and abs(w) == pytest.approx(4.8, rel=0.02)


def test_slider_crank_i14_at_infinity_and_i13_derived_by_hand():
    ic, kin = located("slider_crank.yaml")
    # Closed form (Khurmi Ex. 7.2): crank 150 at 135°, rod 600, piston on the x axis to the left.
    r, rod, th = 0.150, 0.600, math.radians(135)
    a = (r * math.cos(th), r * math.sin(th))
    b = (a[0] - math.sqrt(rod * rod - a[1] ** 2), 0.0)
    i14 = ic.named("I14")
    assert ic.count == 6 and i14.at_infinity and i14.point is None
    assert i14.direction == pytest.approx((0.0, 1.0), abs=1e-15)  # ⟂ to the horizontal path
    assert i14.method == "slider P: ⟂ path at infinity"
    # I13: crank line OA extended meets the perpendicular to the path through B (x = b_x).
    i13 = (b[0], a[1] / a[0] * b[0])
    assert ic.named("I13").point == pytest.approx(i13, abs=REL * kin.size)
    # I24: the perpendicular to the path through O (x = 0) meets the rod line AB.
    i24 = (0.0, a[1] - a[0] * (b[1] - a[1]) / (b[0] - a[0]))
    assert ic.named("I24").point == pytest.approx(i24, abs=REL * kin.size)
    # ω of the rod by I-centres: v_A = ω_rod · I13A.
    w_rod = r * 300 * 2 * math.pi / 60 / math.dist(i13, a)
    assert abs(ic.omega_by_icentres["rod"]) == pytest.approx(w_rod, rel=REL)
    assert_laws(ic, kin)


def test_crank_and_slotted_lever_khurmi_quick_return():
    """Khurmi Ex. 5.1 geometry: A = (120, 240), O1 = (0, 0), O2 = (0, 240) mm, crank horizontal."""
    ic, kin = located("crank_slotted_lever_quick_return.yaml")
    assert ic.count == 15
    mm = 1e-3
    i34 = ic.get("block", "lever")  # slider on a moving guide: ⟂ the lever, at infinity
    assert i34.at_infinity and i34.direction == pytest.approx((-2 / math.sqrt(5), 1 / math.sqrt(5)))
    # I13: crank line y = 240 meets the normal to the lever through O1 (y = −x/2): x = −480.
    assert ic.get("frame", "block").point == pytest.approx((-480 * mm, 240 * mm), abs=REL * kin.size)
    # I24: line O1O2 (x = 0) meets the normal to the lever through A: y = (120² + 240²)/240 = 300.
    assert ic.get("crank", "lever").point == pytest.approx((0.0, 300 * mm), abs=REL * kin.size)
    # ω_lever = ω_crank · I12I24 / I14I24 = π · 60/300, same sense (cw).
    assert ic.omega_by_icentres["lever"] == pytest.approx(-math.pi * 60 / 300, rel=REL)
    assert_laws(ic, kin)


def test_crank_and_slotted_lever_notes_example():
    ic, kin = located("crank_slotted_lever.yaml")
    assert ic.get("block", "lever").at_infinity
    assert abs(ic.omega_by_icentres["lever"]) == pytest.approx(9.25, rel=0.02)  # notes' answer
    assert_laws(ic, kin)


def test_pin_in_slot_centre_on_the_normal_to_the_slot(write):
    ax, ay = 100 * math.cos(math.radians(30)), 300 + 100 * math.sin(math.radians(30))
    k = 500 / math.hypot(ax, ay)
    path = write(
        "units: {length: mm, angle: deg}\n"
        "links: [frame, crank, lever]\n"
        "joints:\n"
        "  O2: {type: revolute, links: [frame, crank], at: [0, 300]}\n"
        "  O1: {type: revolute, links: [frame, lever], at: [0, 0]}\n"
        "  A: {type: slot, links: [crank, lever], path: {through: O1, toward: B}}\n"
        "lengths: {O2A: 100}\n"
        f"points: {{B: {{link: lever, at: [{ax * k!r}, {ay * k!r}]}}}}\n"
        "drive: {link: crank, angle: 30, rpm: 60, direction: ccw}\n"
    )
    mech = load(path)
    kin = solve(mech, level="velocity")
    ic = locate(mech, kin)
    # Normal to the slot through A meets O1O2 (x = 0) at y = |O1A|²/A_y.
    assert ic.get("crank", "lever").point == pytest.approx(
        (0.0, (ax**2 + ay**2) / ay * 1e-3), abs=REL * kin.size
    )
    assert ic.get("crank", "lever").method == "Kennedy: normal to slot A ∩ I12–I13"
    assert_laws(ic, kin)


def test_cam_and_follower_file():
    ic, kin = located("cam_follower.yaml")
    assert ic.count == 3
    assert ic.get("cam", "follower").point == pytest.approx((15.566e-3, 0.0), abs=2e-6)
    assert_laws(ic, kin)


@pytest.mark.parametrize("deg", [0.0, 30.0, 100.0, 250.0])
def test_moving_eccentric_cam_centre_lies_on_the_common_normal_under_the_disc_centre(deg):
    # The flat face's normal at the contact passes through the disc's centre E, and the
    # follower translates: Kennedy puts I23 on that vertical through E, on the line of
    # centres (the x axis): x = e cos θ, where the cam's speed ω·x is the follower's.
    ic, kin = located("eccentric_cam.yaml", angle=math.radians(deg))
    assert ic.get("cam", "follower").point == pytest.approx(
        (0.015 * math.cos(math.radians(deg)), 0.0), abs=REL * 0.05
    )
    assert_laws(ic, kin)


def test_rolling_wheel_centre_with_the_ground_is_the_contact_point():
    ic, kin = located("rolling_wheel.yaml", angle=math.radians(200))
    x_b = kin.positions["B"][0]
    assert ic.get("frame", "wheel").point == pytest.approx((x_b, 0.0), abs=REL * 0.1)
    assert_laws(ic, kin)


@pytest.mark.parametrize(
    "name", ["watt_six_bar.yaml", "stephenson_six_bar.yaml", "whitworth_quick_return.yaml"]
)
def test_six_link_chains_give_15_that_agree_with_the_velocity_field(name):
    ic, kin = located(name)
    assert ic.count == 15 and ic.formula.endswith("6·5/2 = 15")
    assert all(c.step is not None for c in ic.centres)  # Kennedy reaches all of them
    assert all(c.check is not None and c.check <= REL for c in ic.centres)
    assert_laws(ic, kin)


EIGHT_LINK = """\
name: eight-link chain some of whose I-centres Kennedy cannot reach
units: {length: mm, angle: deg}
links: [frame, L1, crank, L3, L4, L5, L6, L7]
joints:
  P02: {type: revolute, links: [frame, crank], at: [32.383, 15.085]}
  P03: {type: revolute, links: [frame, L3], at: [65.093, 7.244]}
  P06: {type: revolute, links: [frame, L6], at: [53.588, 36.569]}
  P12: {type: revolute, links: [L1, crank], at: [5.800, 50.744]}
  P14: {type: revolute, links: [L1, L4], at: [3.750, 43.365]}
  P15: {type: revolute, links: [L1, L5], at: [6.986, 9.071]}
  P35: {type: revolute, links: [L3, L5], at: [42.452, 82.685]}
  P46: {type: revolute, links: [L4, L6], at: [12.380, 22.324]}
  P47: {type: revolute, links: [L4, L7], at: [62.743, 94.771]}
  P57: {type: revolute, links: [L5, L7], at: [57.710, 39.668]}
drive: {link: crank, rpm: 60, direction: ccw}
"""


def test_centres_kennedy_cannot_reach_come_from_the_velocity_field_and_say_so(write):
    mech = load(write(EIGHT_LINK))
    kin = solve(mech, level="velocity")
    ic = locate(mech, kin)
    assert ic.count == 28
    field = [c for c in ic.centres if c.step is None]
    assert field and all(c.method == "velocity field (not reachable by Kennedy)" for c in field)
    assert_laws(ic, kin)  # the completed set still obeys Kennedy's theorem for every triple


def claims():
    for path in example_files():
        for claim in load(path).answers:
            if claim.key.startswith("icentre."):
                yield pytest.param(path, claim, id=f"{path.stem}:{claim.key}")


@pytest.mark.parametrize(("path", "claim"), list(claims()))
def test_icentre_answers_in_the_examples(path, claim):
    mech = load(path)
    kin = solve(mech, level="velocity")  # a file that claims I-centres is one mech must solve
    _, a, b = claim.key.split(".")
    c = locate(mech, kin).get(a, b)
    if claim.value == "infinity":
        assert c.at_infinity
        return
    expected = claim.value  # SI, as cli.md says (the files write units on each coordinate)
    tol = claim.tolerance or mech.tolerance
    allowed = tol.value * kin.size if tol.relative else tol.value
    assert c.point is not None and math.dist(c.point, expected) <= allowed
