"""Transmission angle, strokes and time ratio (mech.properties.cycle) against closed forms.

Closed forms (Norton, *Design of Machinery*, §§ 3.3, 4.10; Khurmi & Gupta § 5.5), for the
four-bar with frame d, crank a, coupler b, output c: the diagonal from the crank pin to the
output pivot is BD² = a² + d² − 2ad·cos θ, and the cosine rule in triangle BCD gives the
transmission angle cos μ = (b² + c² − BD²)/(2bc).  BD is monotonic in θ on [0, π], so for a
crank that turns fully μ is least and greatest at θ = 0 and θ = 180°.  The rocker's limit
positions are where crank and coupler lie in one line (AC = b − a and b + a).
"""

from __future__ import annotations

import json
import math

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mech.loader import load, loads
from mech.properties.cycle import cycle, transmission_angle
from mech.topology.grashof import FourBarLoop
from mechanism_texts import EXAMPLES
from oracles.transmission import crank_turns
from oracles.transmission import diagonal_range as bd_range
from oracles.transmission import transmission_angle as mu_closed
from oracles.transmission import transmission_angle_at as mu_of


def four_bar_text(d: float, a: float, b: float, c: float, angle: float = 60.0) -> str:
    return f"""
units: {{length: mm, angle: deg}}
links: [frame, crank, coupler, rocker]
joints:
  A: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  B: {{type: revolute, links: [crank, coupler]}}
  C: {{type: revolute, links: [coupler, rocker]}}
  D: {{type: revolute, links: [rocker, frame], at: [{d!r}, 0]}}
lengths: {{AB: {a!r}, BC: {b!r}, CD: {c!r}}}
drive: {{link: crank, angle: {angle!r}, rpm: 60}}
"""


@st.composite
def turning_cranks(draw: st.DrawFn) -> tuple[float, float, float, float]:
    """(d, a, b, c) of a crank-rocker (crank shortest) or a double-crank (frame shortest).

    The short link is a fraction 0.05–0.9 of the largest value that keeps the crank turning, so
    every example is one (no filtering) and clear of the toggle.
    """
    x, y, z = (draw(st.floats(min_value=60.0, max_value=200.0)) for _ in range(3))
    frac = draw(st.floats(min_value=0.05, max_value=0.9))
    if draw(st.booleans()):  # crank-rocker: frame x, coupler y, rocker z, crank short
        room = min(y + z - x, x - abs(y - z))
        assume(room > 5.0)
        return x, frac * room, y, z
    # double-crank: crank x, coupler y, rocker z, frame short: |b − c| < a − d and a + d < b + c
    room = min(y + z - x, x - abs(y - z))
    assume(room > 5.0)
    return frac * room, x, y, z


@settings(max_examples=40, deadline=None)
@given(links=turning_cranks(), angle=st.integers(min_value=0, max_value=359))
def test_transmission_angle_extremes_are_at_crank_angles_0_and_180_for_a_turning_crank(links, angle):
    d, a, b, c = links
    assert crank_turns(d, a, b, c)
    mech = loads(four_bar_text(d, a, b, c, angle))
    result = cycle(mech)
    m0, m180 = mu_closed(d, a, b, c, 0.0), mu_closed(d, a, b, c, math.pi)
    assert result.mu_min == pytest.approx(min(m0, m180), rel=1e-9, abs=1e-9)
    assert result.mu_max == pytest.approx(max(m0, m180), rel=1e-9, abs=1e-9)
    at_min = 0.0 if m0 < m180 else math.pi
    assert math.cos(result.mu_min_angle - at_min) == pytest.approx(1.0, abs=1e-9)
    loop = result.transmission.loop
    assert isinstance(loop, FourBarLoop) and loop.kind in ("crank-rocker", "double-crank")


@settings(max_examples=40, deadline=None)
@given(links=turning_cranks(), angle=st.integers(min_value=0, max_value=359))
def test_transmission_angle_at_the_instant_is_the_cosine_rule(links, angle):
    d, a, b, c = links
    from mech.kinematics import solve

    mech = loads(four_bar_text(d, a, b, c, angle))
    where, mu = transmission_angle(mech, solve(mech, "position"))
    assert (where.coupler_joint, where.joint, where.pivot) == ("B", "C", "D")
    assert mu == pytest.approx(mu_closed(d, a, b, c, math.radians(angle)), abs=1e-9)


@settings(max_examples=60, deadline=None)
@given(
    d=st.floats(min_value=20.0, max_value=200.0),
    a=st.floats(min_value=20.0, max_value=200.0),
    b=st.floats(min_value=20.0, max_value=200.0),
    c=st.floats(min_value=20.0, max_value=200.0),
    angle=st.integers(min_value=0, max_value=359),
)
def test_transmission_angle_extremes_of_every_grashof_class_are_at_the_ends_of_bd(d, a, b, c, angle):
    # crank-rockers and double-cranks reach the ends of BD at θ = 0 and 180°; double-rockers and
    # triple rockers at the toggles, where coupler and output lie in line (μ = 0 or 180°)
    ordered = sorted((a, b, c, d))
    assume(abs(ordered[0] + ordered[3] - ordered[1] - ordered[2]) > 1e-2 * ordered[3])  # not change-point
    # crank as long as the frame: the crank pin passes over the output pivot (B = D at θ = 0), where the
    # closed-form dyads divide by zero today (a solver bug reported to its owner, not this law's subject)
    assume(abs(d - a) > 1e-2 * ordered[3])
    th = math.radians(angle)
    bd = math.hypot(a * math.cos(th) - d, a * math.sin(th))
    lo, hi = bd_range(d, a, b, c)
    assume(lo + 0.02 * ordered[3] < bd < hi - 0.02 * ordered[3])  # assembles, clear of a toggle
    result = cycle(loads(four_bar_text(d, a, b, c, angle)))
    assert result.mu_min == pytest.approx(mu_of(b, c, lo), abs=1e-9)
    assert result.mu_max == pytest.approx(mu_of(b, c, hi), abs=1e-9)


def test_four_bar_rocker_swing_and_time_ratio_match_the_limit_positions():
    d, a, b, c = 150.0, 40.0, 150.0, 80.0  # Khurmi Ex. 7.1
    result = cycle(load("mechanisms/four_bar.yaml"))
    # rocker angle at D from the cosine rule in triangle ACD with AC = b ∓ a
    psi = [math.acos((c * c + d * d - ac * ac) / (2 * c * d)) for ac in (b - a, b + a)]
    assert result.strokes["D"].value == pytest.approx(abs(psi[1] - psi[0]), rel=1e-9)
    # crank angles of the limit positions: along AC (extended) and opposite it (folded)
    gam = [math.acos((ac * ac + d * d - c * c) / (2 * ac * d)) for ac in (b - a, b + a)]
    arc = (gam[1] - (gam[0] + math.pi)) % (2 * math.pi)
    expected = max(arc, 2 * math.pi - arc) / min(arc, 2 * math.pi - arc)
    assert result.time_ratio == pytest.approx(expected, rel=1e-9)


def test_offset_slider_crank_stroke_and_time_ratio_match_closed_forms():
    r, rod, e = 0.05, 0.2, 0.02  # offset_slider_crank.yaml
    result = cycle(load("mechanisms/offset_slider_crank.yaml"))
    stroke = math.sqrt((rod + r) ** 2 - e * e) - math.sqrt((rod - r) ** 2 - e * e)
    assert result.strokes["guide"].value == pytest.approx(stroke, rel=1e-9)
    beta = math.asin(e / (rod - r)) - math.asin(e / (rod + r))  # Norton eq. 4.28 (offset slider crank)
    assert result.time_ratio == pytest.approx((math.pi + beta) / (math.pi - beta), rel=1e-9)
    assert result.transmission is None


def test_slotted_lever_time_ratio_is_the_notes_formula():
    # crank_slotted_lever.yaml comment: (180 + 2 asin(120/500)) / (180 − 2 asin(120/500))
    g = 2 * math.degrees(math.asin(120 / 500))
    assert cycle(load("mechanisms/crank_slotted_lever.yaml")).time_ratio == pytest.approx(
        (180 + g) / (180 - g), rel=1e-9
    )


def test_check_reads_the_transmission_and_stroke_keys(write, run):
    path = write(
        four_bar_text(150, 40, 150, 80)
        + """answers:
  grashof: crank-rocker
  transmission_angle: 63.26 deg
  transmission_angle.min: 45.573 deg
  transmission_angle.max: 107.458 deg
  stroke.D: 61.885 deg
  time_ratio: 1.0883
"""
    )
    result = run("check", str(path))
    assert result.exit_code == 0, result.output


def test_check_gives_a_reason_when_a_joint_has_no_stroke():
    from mech.check import check

    (verdict,) = check(loads(four_bar_text(150, 40, 150, 80) + "answers:\n  stroke.B: 10 mm\n"))
    assert verdict.status == "error" and "neither a prismatic joint" in verdict.message


def test_check_fails_a_wrong_grashof_class(write, run):
    path = write(four_bar_text(150, 40, 150, 80) + "answers:\n  grashof: double-rocker\n")
    result = run("check", str(path))
    assert result.exit_code == 1 and "crank-rocker" in result.output


def test_properties_command_reports_the_answer_keys_in_json(run):
    result = run("properties", "mechanisms/four_bar.yaml", "--json")
    assert result.exit_code == 0
    out = json.loads(result.output)
    assert out["grashof"] == "crank-rocker"
    t = out["transmission_angle"]
    # cosine rule values of the module docstring (d 150, a 40, b 150, c 80 mm; crank at 60°)
    assert t["value"] == pytest.approx(63.256316049597, rel=1e-9)
    assert (t["min"], t["max"]) == (
        pytest.approx(45.5729959991943, rel=1e-9),
        pytest.approx(107.4576031237221, rel=1e-9),
    )
    assert out["stroke"]["D"]["value"] == pytest.approx(61.88460712452779, rel=1e-9)
    assert out["time_ratio"] == pytest.approx(1.0882704726904793, rel=1e-9)


def test_properties_of_a_mechanism_that_cannot_be_swept_says_why(run):
    result = run("properties", "mechanisms/cam_follower.yaml")
    assert result.exit_code == 0
    assert "not swept" in result.output


def test_every_prismatic_joint_has_a_stroke_on_the_frame_or_along_a_moving_guide():
    # DESIGN § 1.1: stroke.<joint> is a prismatic joint's travel.  Khurmi's shaper: the ram slides
    # on the frame (joint `stroke`), the block along the lever (joint `slot`), O1 pivots the lever.
    from mech.properties.cycle import stroke_joints

    assert sorted(stroke_joints(load("mechanisms/crank_slotted_lever_quick_return.yaml"))) == [
        "O1",
        "slot",
        "stroke",
    ]
    # crank_slotted_lever.yaml: O1O2 = 500, O2A = 120 mm; the block's distance O1A runs between
    # 500 − 120 and 500 + 120 mm as the crank turns (A on the lever's line at both ends), so it
    # travels 2·O2A = 240 mm along the lever; the lever swings 2·asin(120/500) about O1.
    result = cycle(load("mechanisms/crank_slotted_lever.yaml"))
    assert result.strokes["slot"].value == pytest.approx(0.240, rel=1e-9)
    assert result.strokes["O1"].value == pytest.approx(2 * math.asin(120 / 500), rel=1e-9)


# -- every Grashof class, change points included (issue 25, item 2) --------------------------------
GRASHOF_KINDS = ("crank-rocker", "double-crank", "double-rocker", "non-grashof", "change-point")


@st.composite
def four_bars_of_every_class(draw: st.DrawFn) -> tuple[str, int, int, int, int]:
    """(class, d, a, b, c) in whole millimetres, so that s + l = p + q holds exactly at a change point.

    s ≤ p ≤ q ≤ l: Grashof (s + l < p + q) with the shortest link as crank (crank-rocker), frame
    (double-crank) or coupler (double-rocker); non-Grashof (s + l > p + q, l < s + p + q) and
    change-point (l = p + q − s; with p = s, l = q: two pairs of equal links, a parallelogram when
    opposite) in any arrangement.  A crank as long as the frame is left out: its pin passes over
    the output pivot (B = D), where the closed-form dyad is undefined (reported to its owner).
    """
    kind = draw(st.sampled_from(GRASHOF_KINDS))
    s = draw(st.integers(min_value=20, max_value=90))
    p = draw(st.integers(min_value=s + 1, max_value=170))
    q = draw(st.integers(min_value=p, max_value=200))
    if kind == "change-point":
        if draw(st.booleans()):
            p = s
        lengths = draw(st.permutations([s, p, q, p + q - s]))
        d, a, b, c = lengths
    elif kind == "non-grashof":
        d, a, b, c = draw(
            st.permutations([s, p, q, draw(st.integers(min_value=p + q - s + 1, max_value=s + p + q - 1))])
        )
    else:
        rest = draw(st.permutations([p, q, draw(st.integers(min_value=q, max_value=p + q - s - 1))]))
        if kind == "crank-rocker":
            a, (d, b, c) = s, rest
        elif kind == "double-crank":
            d, (a, b, c) = s, rest
        else:
            b, (d, a, c) = s, rest
    assume(d != a)
    return kind, d, a, b, c


def drawn_four_bar(d: float, a: float, b: float, c: float, theta: float) -> str:
    """The four-bar drawn at crank angle ``theta`` (rad) with C left of B→D (near the closed form's C)."""
    bx, by = a * math.cos(theta), a * math.sin(theta)
    f = math.hypot(d - bx, by)
    x = (b * b - c * c + f * f) / (2 * f)
    h = math.sqrt(b * b - x * x)
    cx, cy = bx + x * (d - bx) / f + h * by / f, by - x * by / f + h * (d - bx) / f
    text = four_bar_text(d, a, b, c, math.degrees(theta))
    return text.replace("links: [coupler, rocker]}", f"links: [coupler, rocker], near: [{cx!r}, {cy!r}]}}")


@settings(max_examples=40, deadline=None)
@given(bar=four_bars_of_every_class(), mirror=st.booleans())
def test_transmission_angle_extremes_and_strokes_of_every_grashof_class_are_the_closed_forms(bar, mirror):
    # μ depends on BD alone (cosine rule in triangle BCD): its extremes are at the ends of the
    # range BD takes while the loop closes, 0° or 180° where coupler and rocker fold into line (a
    # toggle, a change point).  Drawn where BD is midway, clear of both.  The rocker's swing is
    # the closed form's along the branch with a continuous tangent (oracles.four_bar.rocker_swing),
    # none when it turns right round.  Neither may change with the number of steps.
    from oracles.four_bar import rocker_swing

    kind, d, a, b, c = bar
    lo, hi = bd_range(d, a, b, c)
    mid = 0.5 * (lo + hi)
    theta = math.acos(max(-1.0, min(1.0, (a * a + d * d - mid * mid) / (2 * a * d))))
    theta = 2 * math.pi - theta if mirror else theta
    mech = loads(drawn_four_bar(d, a, b, c, theta))
    coarse, fine = cycle(mech), cycle(mech, steps=3600)
    for result in (coarse, fine):
        assert result.mu_min == pytest.approx(mu_of(b, c, lo), abs=1e-9), (kind, result.mu_min)
        assert result.mu_max == pytest.approx(mu_of(b, c, hi), abs=1e-9), (kind, result.mu_max)
    assert (coarse.mu_min, coarse.mu_max) == pytest.approx((fine.mu_min, fine.mu_max), abs=1e-12)
    if coarse.gaps:  # the crank cannot turn: the swing depends on where the circuits lie
        return
    swing = rocker_swing(a, b, c, d, theta)
    # an extreme at a change point (two branches meet) is known to about √ε there, in mech and
    # in the closed form alike (the discriminant's rounding under a square root)
    tol = 1e-6 if kind == "change-point" else 1e-9
    for result in (coarse, fine):
        if swing is None:
            assert "D" in result.turning and "D" not in result.strokes, kind
        else:
            stroke = result.strokes["D"].value if "D" in result.strokes else 0.0  # a rocker at rest
            assert stroke == pytest.approx(swing, abs=tol), kind


@pytest.mark.parametrize("steps", [36, 360, 3600])
def test_parallelogram_transmission_angle_is_0_and_180_and_its_rocker_turns(steps, run, write):
    # AB = CD = 40, BC = AD = 150, C near (190, 10): the rocker stays parallel to the crank on the
    # drawn branch, passing the change points at 0° and 180° (all four pins in line), where
    # μ = ∠BCD is 0° and 180° exactly; the rocker turns right round: no stroke.
    text = four_bar_text(150, 40, 150, 40).replace(
        "links: [coupler, rocker]}", "links: [coupler, rocker], near: [190, 10]}"
    )
    result = cycle(loads(text), steps=steps)
    assert (result.mu_min, result.mu_max) == (0.0, math.pi)
    assert math.cos(result.mu_min_angle) == pytest.approx(1.0) and math.cos(
        result.mu_max_angle
    ) == pytest.approx(-1.0)
    assert "D" in result.turning and not result.strokes
    sweep = run("sweep", str(write(text)), "--steps", str(steps), "--quantity", "included.B.C.D", "--json")
    (ext,) = json.loads(sweep.output)["extremes"]
    assert (ext["min"], ext["max"]) == (0.0, 180.0)
    checked = run(
        "check",
        str(
            write(
                text + "answers:\n  transmission_angle.min: 0 deg\n  transmission_angle.max: 180 deg\n",
                "a.yaml",
            )
        ),
    )
    assert checked.exit_code == 0, checked.output


@pytest.mark.parametrize("steps", [36, 360, 3600])
def test_a_crank_driven_by_its_rocker_swings_between_the_toggles_of_the_drawn_circuit_only(steps):
    # Khurmi's crank-rocker (AD 150, AB 40, BC 150, CD 80 mm) driven by the rocker, drawn at 100°
    # with the crank at 102.33° (C above AD). The rocker reaches only 72.54°–134.43° on this
    # circuit; turned right round, the closed form also assembles the mirror circuit (C below AD,
    # 225.57°–287.46°), which no motion reaches from the drawing. The crank stops where it and the
    # coupler lie in line (cosine rule in triangle ACD): stretched, AC = b + a = 190 mm, the crank
    # along AC at acos((190² + 150² − 80²)/(2·190·150)) = 23.68°; folded, AC = b − a = 110 mm, the
    # crank opposite C at 180° + acos((110² + 150² − 80²)/(2·110·150)) = 211.29°. Its swing on the
    # drawn circuit is their difference, 187.61°; both circuits together gave 234.97°.
    d, a, b, c = 150.0, 40.0, 150.0, 80.0
    stretched = math.acos(((b + a) ** 2 + d * d - c * c) / (2 * (b + a) * d))
    folded = math.pi + math.acos(((b - a) ** 2 + d * d - c * c) / (2 * (b - a) * d))
    text = four_bar_text(d, a, b, c).replace(
        "drive: {link: crank, angle: 60.0, rpm: 60}", "drive: {link: rocker, angle: 100, rpm: 60}"
    )
    result = cycle(loads(text), steps=steps)
    stroke = result.strokes["A"]
    assert (stroke.low, stroke.high) == pytest.approx((stretched, folded), abs=1e-9)
    assert stroke.value == pytest.approx(folded - stretched, abs=1e-9)  # 187.6085°
    # the toggles met are the drawn circuit's, where the rocker stops: 180° − ∠ADC at AC = 190 and
    # 110 mm (cosine rule), 72.54° and 134.43°; not the mirror circuit's 225.57° and 287.46°
    rocker_at = sorted(math.degrees(t.angle) % 360.0 for t in result.sweep.toggles)
    adc = [math.degrees(math.acos((d * d + c * c - ac**2) / (2 * d * c))) for ac in (b + a, b - a)]
    assert rocker_at == pytest.approx(sorted(180.0 - x for x in adc), abs=1e-6)


# -- issue 21, items 2 and 4: dwells, strokes, one angle convention ------------------------------
def test_cam_follower_limit_positions_are_its_dwells_at_lowest_and_highest():
    # The shipped roller cam: prime circle 40 + 10 = 50 mm, rise 30 mm.  Its follower rests at
    # 50 mm (bottom dwell) and 80 mm (top dwell): those are its limit positions, one row each, never
    # a dead centre at every degree of a dwell (there were 92).
    c = cycle(load("mechanisms/cam_roller_program.yaml"))
    assert [(lp.value, lp.until is not None) for lp in c.limits] == [
        (pytest.approx(0.05, rel=1e-12), True),
        (pytest.approx(0.08, rel=1e-12), True),
    ]
    assert c.strokes["S"].value == pytest.approx(0.03, rel=1e-12)


COMPOUND_TRAIN = """
units: {length: mm, angle: deg}
ground: frame
links: [frame, gear1, gear23, gear4]
joints:
  O1: {type: revolute, links: [frame, gear1], at: [0, 0]}
  O2: {type: revolute, links: [frame, gear23], at: [200, 0]}
  O3: {type: revolute, links: [frame, gear4], at: [200, 200]}
  m12: {type: gear, links: [gear1, gear23], teeth: [20, 60], module: 5}
  m34: {type: gear, links: [gear23, gear4], teeth: [20, 60], module: 5}
drive: {link: gear1, angle: 0, rpm: 100, direction: ccw}
"""


def test_compound_gear_train_turning_on_has_no_stroke(run):
    # 20:60 twice: gear23 turns a third of a turn (120°) and gear4 a ninth (40°) per turn of gear1,
    # always the same way.  DESIGN § 1.2: a stroke belongs to an output that reverses; these were
    # given "O2 gear23 120 deg from -120 at crank 0 to 0 at crank 0".
    c = cycle(loads(COMPOUND_TRAIN))
    assert c.strokes == {} and set(c.turning) == {"O2", "O3"}
    out = json.loads(run("properties", "-", "--json", input=COMPOUND_TRAIN).output)
    assert out["stroke"] == {} and out["turns_fully_at"] == ["O2", "O3"]


def test_an_output_angle_reads_the_same_under_limit_positions_and_strokes_in_0_to_360(run, write):
    # A crank-rocker (AD 150, AB 20, BC 180, CD 60 mm) with its frame turned −60°, so that the
    # rocker swings across 0°.  Its limits, crank and coupler in line (AC = b ± a), are at D→C =
    # −60° + 180° − ∠ADC, ∠ADC by the law of cosines (C left of A→D).  The same angles, in
    # [0°, 360°), under Limit positions and Strokes (Strokes printed 391.59° for 31.592°; the
    # issue's file, −58.447° for 301.55°).
    a, b, c, d = 20.0, 180.0, 60.0, 150.0
    adc = [math.degrees(math.acos((c * c + d * d - ac * ac) / (2 * c * d))) for ac in (b + a, b - a)]
    expected = sorted((120.0 - x) % 360.0 for x in adc)
    dx, dy = d * math.cos(math.radians(-60)), d * math.sin(math.radians(-60))
    text = four_bar_text(d, a, b, c, 0.0).replace(f"at: [{d!r}, 0]", f"at: [{dx!r}, {dy!r}]")
    out = json.loads(run("properties", str(write(text)), "--json").output)
    limits = sorted(lp["position"] for lp in out["limit_positions"])
    s = out["stroke"]["D"]
    assert limits == pytest.approx(expected, rel=1e-9)
    assert sorted((s["low"], s["high"])) == pytest.approx(expected, rel=1e-9)
    assert s["value"] == pytest.approx(adc[0] - adc[1], rel=1e-9)


def test_least_transmission_angle_at_the_seam_is_at_crank_0_not_360(run):
    # Watt's first loop (crank 30, coupler 110, rocker 70, frame 100 mm): μ is least with the crank
    # toward O4, crank angle 0: cos μ = (b² + c² − (d − a)²)/(2bc) = 110/140.  It read "at crank
    # 360.0000°".
    out = run("properties", "mechanisms/watt_six_bar.yaml")
    mu = math.degrees(math.acos(110 / 140))
    assert f"least {mu:.4f}° at crank 0.0000°" in out.output and "360.0000" not in out.output
    t = json.loads(run("properties", "mechanisms/watt_six_bar.yaml", "--json").output)["transmission_angle"]
    assert t["min_crank_angle"] == 0.0


def test_a_stroke_names_the_link_that_moves_the_slider_s_block_beside_its_joint():
    from pathlib import Path

    shaper = load(
        Path(__file__).resolve().parents[2] / "mechanisms" / "crank_slotted_lever_quick_return.yaml"
    )
    strokes = cycle(shaper, steps=72).strokes
    assert {j: (s.subject, s.link) for j, s in strokes.items()} == {
        "slot": ("slot", "block"),  # the block slides in the lever's slot
        "O1": ("lever", "lever"),
        "stroke": ("stroke", "ram"),  # the ram on the frame's guide
    }


# /tmp/audit2/findings/F2_triple_rocker_swing.yaml: a non-Grashof crank that cannot turn fully
TRIPLE_ROCKER = """
name: non-Grashof four-bar at its toggle
units: {length: mm, angle: deg}
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [60, 40]}
  D: {type: revolute, links: [rocker, frame], at: [40, 0]}
lengths: {AB: 60, BC: 45, CD: 70}
drive: {link: crank, angle: 90, rpm: 60}
"""


def test_triple_rocker_swing_is_over_both_branches_joined_at_the_input_toggles():
    # AD = 40, AB = 60, BC = 45, CD = 70: s + l = 110 > p + q = 105, no link turns fully.  The
    # crank stops at its toggles (B, C, D in line, BD = CD − BC = 25: cos θ = (60² + 40² − 25²)/
    # (2·60·40), θ = ±17.61°) and goes back on the other closure of C: one circuit of two branches.
    # The rocker's limits are where crank and coupler lie in line, AC = AB + BC = 105; in triangle
    # ACD cos ∠ADC = (AD² + CD² − AC²)/(2·AD·CD) = (1600 + 4900 − 11025)/5600, so ψ = 180° ∓ ∠ADC
    # (36.0955° and 323.9045°), at crank ±∠CAD, cos ∠CAD = (AC² + AD² − CD²)/(2·AC·AD) = 7725/8400.
    # The crank's toggle (342.39°, rocker 313.43°) is the input's limit, not the rocker's.
    adc = math.acos((40**2 + 70**2 - 105**2) / (2 * 40 * 70))
    cad = math.acos((105**2 + 40**2 - 70**2) / (2 * 105 * 40))
    result = cycle(loads(TRIPLE_ROCKER))
    stroke = result.strokes["D"]
    assert stroke.low == pytest.approx(math.pi - adc, abs=1e-9)
    assert stroke.high == pytest.approx(math.pi + adc, abs=1e-9)
    assert stroke.value == pytest.approx(2 * adc, abs=1e-9)  # 287.81°
    assert (stroke.low_angle, stroke.high_angle) == pytest.approx((cad, 2 * math.pi - cad), abs=1e-7)
    limits = sorted((lp.crank_angle, lp.value) for lp in result.limits if lp.output == "rocker")
    expected = [(cad, math.pi - adc), (2 * math.pi - cad, math.pi + adc)]
    assert [x for lp in limits for x in lp] == pytest.approx([x for lp in expected for x in lp], abs=1e-7)


def test_a_slider_whose_dyad_folds_at_the_inputs_toggles_travels_over_both_branches():
    # Khurmi's six-link slider (mechanisms/khurmi_six_link_slider.yaml): the crank OA = 28 stops
    # where the rod BD = 46 stands square to the guide y = −76 mm, and goes back with D on the
    # rod's other closure: x_D = x_B ± √(46² − (y_B + 76)²), B from the four-bar O-A-B-C (AB = 44,
    # BC = 49, C at (0, −65)).  The travel over the circuit is the greatest x_D of the drawn closure
    # less the least of the other, each found here by a fine scan of θ refined by golden sections.
    def b_of(theta: float, near: tuple[float, float]) -> tuple[float, float] | None:
        a = (28 * math.cos(theta), 28 * math.sin(theta))
        d = math.dist(a, (0, -65))
        if not abs(44 - 49) <= d <= 44 + 49:
            return None
        along = (44**2 - 49**2 + d * d) / (2 * d)
        h = math.sqrt(max(44**2 - along**2, 0.0))
        ux, uy = (0 - a[0]) / d, (-65 - a[1]) / d
        base = (a[0] + along * ux, a[1] + along * uy)
        two = [(base[0] - h * uy, base[1] + h * ux), (base[0] + h * uy, base[1] - h * ux)]
        return min(two, key=lambda p: math.dist(p, near))

    def x_d(theta: float, sign: float) -> float | None:
        b = b_of(theta, (45.6, -47.1))
        if b is None or abs(b[1] + 76) > 46:
            return None
        return b[0] + sign * math.sqrt(46**2 - (b[1] + 76) ** 2)

    def extreme(sign: float) -> float:
        f = lambda t: -sign * (x_d(t, sign) or -sign * math.inf)  # noqa: E731  (least of −sign·x)
        grid = [math.radians(k / 20) for k in range(360 * 20)]
        t = min(grid, key=f)
        lo, hi = t - math.radians(0.05), t + math.radians(0.05)
        for _ in range(80):
            m1, m2 = lo + (hi - lo) * 0.382, lo + (hi - lo) * 0.618
            lo, hi = (lo, m2) if f(m1) < f(m2) else (m1, hi)
        return x_d((lo + hi) / 2, sign)  # type: ignore[return-value]

    travel = (extreme(+1) - extreme(-1)) / 1000
    result = cycle(load(EXAMPLES / "khurmi_six_link_slider.yaml"))
    assert result.strokes["guide"].value == pytest.approx(travel, rel=1e-9)
    # the lever, which the rod's closure does not move, has its dead centre listed once
    assert len([lp for lp in result.limits if lp.output == "lever"]) == 1
