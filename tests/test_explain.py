"""The construction written out (mech.explain; --explain on velocity, acceleration, icentres).

The polygon is rebuilt from the explained steps alone — each known vector laid from its start
with its magnitude and direction, each pair of lines intersected, each image scaled and turned —
and must land every image on the solver's velocity (acceleration).  The notes' Example 3.1 (the
crank and slotted lever) and Khurmi's four-bar read in the notes' order with the computed numbers.
"""

from __future__ import annotations

import json
import math

import pytest

from mech.explain import Construction, explain, explain_icentres
from mech.kinematics import solve
from mech.loader import load
from oracles.lines import meet_along

EXAMPLES = [
    "mechanisms/four_bar.yaml",
    "mechanisms/slider_crank.yaml",
    "mechanisms/offset_slider_crank.yaml",
    "mechanisms/crank_slotted_lever.yaml",
    "mechanisms/khurmi_four_bar_acceleration.yaml",
    "mechanisms/watt_six_bar.yaml",
    "mechanisms/stephenson_six_bar.yaml",
    "mechanisms/crank_slotted_lever_quick_return.yaml",
    "mechanisms/whitworth_quick_return.yaml",
    "mechanisms/khurmi_six_link_slider.yaml",
    "mechanisms/khurmi_slider_crank_cg.yaml",
    "mechanisms/gate_four_bar_translating_coupler.yaml",
    "mechanisms/beer_johnston_engine.yaml",
]


def rebuild(c: Construction) -> dict[str, tuple[float, float]]:
    """The polygon's points from the steps' data alone."""
    pts = {c.pole: (0.0, 0.0)}
    for s in c.steps:
        for k in s.known:
            x, y = pts[k.start]
            pts[k.end] = (x + k.magnitude * math.cos(k.direction), y + k.magnitude * math.sin(k.direction))
        if s.image is not None:
            a, b, ratio, angle = s.image
            dx, dy = pts[b][0] - pts[a][0], pts[b][1] - pts[a][1]
            ca, sa = math.cos(angle), math.sin(angle)
            pts[s.result] = (pts[a][0] + ratio * (ca * dx - sa * dy), pts[a][1] + ratio * (sa * dx + ca * dy))
        elif s.lines:
            (p, u), (q, w) = ((pts[ln.through], ln.direction) for ln in s.lines)
            pts[s.result] = meet_along(p, (math.cos(u), math.sin(u)), q, (math.cos(w), math.sin(w)))
        else:
            assert s.result in pts, f"step {s.number} locates {s.result} from nothing"
    return pts


def point_of(label: str) -> str:
    return label.rstrip("′").upper()


@pytest.mark.parametrize("path", EXAMPLES)
@pytest.mark.parametrize("kind", ["velocity", "acceleration"])
def test_polygon_rebuilt_from_the_steps_alone_is_the_solution(path, kind):
    mech = load(path)
    kin = solve(mech, "acceleration")
    c = explain(mech, kin, kind=kind)
    pts = rebuild(c)
    scale = max(
        math.hypot(*(kin.velocity(n) if kind == "velocity" else kin.acceleration(n))) for n in kin.positions
    )
    checked = 0
    for s in c.steps:
        name = point_of(s.result)
        if name in kin.positions and not any(ch in s.result for ch in "₀₁₂₃₄₅₆₇₈₉"):
            want = kin.velocity(name) if kind == "velocity" else kin.acceleration(name)
            got = pts[s.result]
            assert math.dist(got, want) <= 1e-9 * scale, (s.number, s.result)
            checked += 1
        for m in s.measured:  # what is read off the polygon is what the rebuilt polygon shows
            assert math.dist(pts[m.start], pts[m.end]) == pytest.approx(
                m.magnitude, rel=1e-9, abs=1e-12 * scale
            )
    assert checked >= 2


def test_notes_example_3_1_reads_like_the_notes():
    mech = load("mechanisms/crank_slotted_lever.yaml")
    c = explain(mech, solve(mech, "velocity"))
    texts = [s.text for s in c.steps]
    # Step 1: the fixed points at one pole, oa ⊥ O2A = ω × O2A (notes: 20π × 0.12 = 7.53 m/s)
    assert texts[0].startswith("O1, O2 are fixed points, so they are taken as the single point o")
    assert "draw vector oa perpendicular to O2A" in texts[0]
    assert "ω × O2A = 62.83 rad/s × 0.12 m = 7.54 m/s" in texts[0]
    # Step 2: along the slot from a, ⊥ O1A from o, meeting at the lever's point a₄ (the notes' c)
    assert "from a draw a line parallel to the slot" in texts[1]
    assert "from o draw a line ⊥ O1A" in texts[1] and "intersect at a₄" in texts[1]
    # Step 3: b by proportion o1b / o1c = O1B / O1C (notes: 5.55 m/s by measurement; 5.523 with this geometry)
    assert (
        texts[2].startswith("Locate b by the velocity image of lever") and "ob = v_B = 5.523 m/s" in texts[2]
    )
    assert c.results == (
        "Angular velocity of lever: ω = v_BO1 / O1B = 5.523 / 0.6 = 9.204 rad/s (counter-clockwise)",
    )
    assert len(c.steps) == 3


def test_four_bar_reads_like_the_notes():
    mech = load("mechanisms/four_bar.yaml")  # Khurmi Ex. 7.1: vB 0.503, vC 0.385 m/s, ω_CD 4.8 rad/s cw
    c = explain(mech, solve(mech, "velocity"))
    first, second = (s.text for s in c.steps)
    assert "draw vector ob perpendicular to AB" in first and "0.5027 m/s" in first
    assert "from b draw a line ⊥ BC" in second and "from o draw a line ⊥ DC" in second
    assert "They intersect at c" in second and "oc = v_CD = 0.3828 m/s" in second
    assert "Angular velocity of rocker: ω = v_DC / CD = 0.3828 / 0.08 = 4.785 rad/s (clockwise)" in c.results


def test_acceleration_steps_give_normal_and_coriolis_components():
    mech = load("mechanisms/crank_slotted_lever.yaml")  # Coriolis 2ωv = 98.48 m/s² (file's closed form)
    c = explain(mech, solve(mech, "acceleration"), kind="acceleration")
    assert "normal (centripetal) acceleration ω²·O2A" in c.steps[0].text
    (cor,) = [k for k in c.steps[1].known if k.what.startswith("Coriolis")]
    assert cor.magnitude == pytest.approx(98.48, rel=1e-3)
    assert "2ωv = 2 × 9.204 rad/s × 5.35 m/s = 98.48 m/s²" in c.steps[1].text


def test_kennedy_circle_diagram_names_each_diagonal_and_its_triangles():
    from mech.icentres import locate

    mech = load("mechanisms/four_bar.yaml")
    lines = explain_icentres(locate(mech, solve(mech, "velocity")), unit="mm")
    assert lines[1].startswith("By inspection") and "1–2: I12 pin A" in lines[1]
    assert lines[2].startswith("1. Draw the diagonal 1–3: it closes the triangles 1-2-3 and 1-3-4")
    assert "meet at (212.1, 367.3) mm" in lines[2]  # the file's I13 = (212.05, 367.29) mm
    assert "meet at (-92.23, 0) mm" in lines[3]


def test_explain_options_on_the_command_line(run):
    out = run("velocity", "mechanisms/slider_crank.yaml", "--explain")
    assert (
        out.exit_code == 0
        and "Step 2. The velocity of B with respect to A is perpendicular to AB" in out.output
    )
    record = json.loads(run("acceleration", "mechanisms/four_bar.yaml", "--explain", "--json").output)
    assert (
        record["construction"]["kind"] == "acceleration" and record["construction"]["steps"][0]["step"] == 1
    )
    ic = run("icentres", "mechanisms/four_bar.yaml", "--explain")
    assert "Kennedy's circle diagram" in ic.output


def test_explain_refuses_what_does_not_decompose(run):
    result = run("velocity", "mechanisms/cam_follower.yaml", "--explain")
    assert result.exit_code == 2 and "does not decompose into a crank and dyads" in result.stderr


def test_a_crank_with_angular_acceleration_adds_its_tangential_component():
    from mech.options import SolveOptions

    mech = load("mechanisms/four_bar.yaml")
    kin = solve(mech, "acceleration", SolveOptions(alpha=50.0))
    c = explain(mech, kin, kind="acceleration")
    (tangential,) = [k for k in c.steps[0].known if k.what.startswith("tangential")]
    assert tangential.magnitude == pytest.approx(50.0 * 0.04, rel=1e-12)  # α·AB
    pts = rebuild(c)
    for name in ("B", "C"):
        assert math.dist(pts[name.lower() + "′"], kin.acceleration(name)) <= 1e-9 * 10


def test_kennedy_circle_drawing_has_a_chord_per_icentre(tmp_path, run):
    out = tmp_path / "k.svg"
    result = run("icentres", "mechanisms/watt_six_bar.yaml", "--circle", str(out))
    assert result.exit_code == 0
    svg = out.read_text()
    # 15 I-centres of six links: 7 pins by inspection, 8 diagonals by Kennedy's theorem
    assert svg.count('class="kennedy-primary"') == 7
    assert svg.count('class="kennedy-diagonal"') == 8


MOVING_GUIDE = """
name: slider on a moving lever
units: {length: mm, angle: deg}
links: [frame, crank, block1, lever, rod, block2]
joints:
  O: {type: revolute, links: [frame, crank], at: [0, 0]}
  A: {type: revolute, links: [crank, block1]}
  slot1: {type: prismatic, links: [block1, lever], path: {through: Q, toward: R}}
  Q: {type: revolute, links: [lever, frame], at: [0, -200]}
  P: {type: revolute, links: [crank, rod], from: O, toward: A, distance: 60}
  B: {type: revolute, links: [rod, block2], near: [60, 100]}
  slot2: {type: prismatic, links: [block2, lever], path: {through: Q, toward: R}}
lengths: {OA: 100, PB: 150}
points:
  R: {link: lever, at: [130.93073414, 177.96447301]}
drive: {link: crank, angle: 30, rpm: 60, direction: ccw, alpha: 3}
"""


@pytest.mark.parametrize("kind", ["velocity", "acceleration"])
def test_a_slider_on_a_moving_guide_starts_from_the_guides_point_under_it(kind):
    from mech.loader import loads

    mech = loads(MOVING_GUIDE)
    kin = solve(mech, "acceleration")
    c = explain(mech, kin, kind=kind)
    mark = "′" if kind == "acceleration" else ""
    located = [s.result for s in c.steps]
    assert located.index("b₄" + mark) < located.index("b" + mark)  # the lever's point first, then b
    pts = rebuild(c)
    want = kin.velocity("B") if kind == "velocity" else kin.acceleration("B")
    assert math.dist(pts["b" + mark], want) <= 1e-9 * math.hypot(*want)
    if kind == "acceleration":
        assert any(k.what.startswith("Coriolis") for s in c.steps for k in s.known)


# -- cams and gear trains worked out (issue 21) ------------------------------------------------
CAMS = [
    ("mechanisms/cam_roller_program.yaml", (7.0, 60.0, 131.0, 200.0, 300.0)),
    ("mechanisms/cam_valve_khurmi.yaml", (20.0, 170.0, 230.0)),
    ("mechanisms/cam_oscillating_roller.yaml", (45.0, 100.0, 250.0)),
]


@pytest.mark.parametrize(("path", "angles"), CAMS)
def test_a_cams_working_rebuilt_from_its_lines_is_the_solution(path, angles):
    # each line carries its inputs: the law's s, ds/dθ, d²s/dθ² are rebuilt here from the textbook
    # (tests/oracles/cam.py) at the line's h, β and x, and must be the line's values, which must be
    # the solver's motion of the follower (the arm's ω for an oscillating one, K's speed otherwise)
    from mech.cam.profile import evaluate
    from mech.options import SolveOptions
    from mech.pairs.cam.setup import cam_setup
    from oracles.cam import textbook_rise

    m = load(path)
    setup = cam_setup(m)
    for deg in angles:
        kin = solve(m, "acceleration", SolveOptions(angle=math.radians(deg)))
        work = explain(m, kin)
        lines = {ln.quantity: ln for ln in work.lines}
        inp = lines["s"].inputs
        law = (
            next(seg.law for seg in setup.layout.program.segments if seg.over == inp["beta"] and seg.law)
            if inp["h"]
            else None
        )
        w = lines["v"].inputs["omega"]
        s, v, a = (
            textbook_rise(law, inp["x"] * inp["beta"], inp["h"], inp["beta"], w) if law else (0.0, 0.0, 0.0)
        )
        sign = inp["sign"]
        assert lines["s"].value == pytest.approx(inp["base"] + sign * s, abs=1e-12)
        assert lines["v"].value == pytest.approx(sign * v, abs=1e-9 * max(abs(v), 1))
        assert lines["a"].value == pytest.approx(sign * a, abs=1e-9 * max(abs(a), 1))
        if setup.layout.oscillating:
            assert abs(kin.links["arm"].omega) == pytest.approx(abs(lines["v"].value), rel=1e-9, abs=1e-12)
        else:
            assert abs(kin.velocity("K")[1]) == pytest.approx(abs(lines["v"].value), rel=1e-9, abs=1e-12)
        theta = lines["theta"].value
        got = lines["pressure"]
        if got.formula and got.formula.startswith("atan2"):
            p = got.inputs
            assert got.value == pytest.approx(
                math.atan2(p["ds/dtheta"] - p["e"], math.sqrt(p["rp"] ** 2 - p["e"] ** 2) + p["s"])
            )
        assert abs(got.value) == pytest.approx(
            abs(float(evaluate(setup.layout, [theta]).pressure[0])), abs=1e-9
        )


def test_the_shipped_cams_explained_pressure_angle_is_its_answer():
    # mechanisms/cam_roller_program.yaml: pressure angle at 60° = atan(22.5 / (50 + 15)) = 19.093°
    m = load("mechanisms/cam_roller_program.yaml")
    work = explain(m, solve(m, "velocity"))
    (pressure,) = [ln for ln in work.lines if ln.quantity == "pressure"]
    assert math.degrees(pressure.value) == pytest.approx(math.degrees(math.atan(22.5 / 65)), rel=1e-9)
    assert "19.093°" in work.text()


GEAR_TRAIN = """\
units: {length: mm, angle: deg}
links: [frame, a, bc, d]
joints:
  Oa: {type: revolute, links: [frame, a], at: [0, 0]}
  Ob: {type: revolute, links: [frame, bc], at: [150, 0]}
  Od: {type: revolute, links: [frame, d], at: [150, 105]}
  m1: {type: gear, links: [a, bc], teeth: [20, 40], module: 5}
  m2: {type: gear, links: [bc, d], teeth: [15, 27], module: 5}
drive: {link: a, rpm: 1200, direction: ccw}
"""


def test_a_compound_train_is_worked_out_stage_by_stage_and_its_value_rebuilt():
    # 20 → 40 on one shaft with 15 → 27: the train value is (−20/40)(−15/27) = +5/18 (Khurmi ch. 13)
    from mech.loader import loads

    m = loads(GEAR_TRAIN, path="train.yaml")
    kin = solve(m, "velocity")
    work = explain(m, kin)
    stages = [ln for ln in work.lines if ln.quantity and ln.quantity.startswith("omega.") and ln.inputs]
    assert [ln.quantity for ln in stages] == ["omega.bc", "omega.d"]
    for ln in stages:
        p = ln.inputs
        k = (p["r_a"] / p["r_b"]) * (1.0 if p["internal"] else -1.0)
        assert ln.value == pytest.approx(p["omega_arm"] + k * (p["omega_a"] - p["omega_arm"]), rel=1e-12)
        assert ln.value == pytest.approx(kin.links[ln.quantity.split(".")[1]].omega, rel=1e-9)
    (value,) = [ln for ln in work.lines if ln.quantity == "train_value"]
    assert value.value == pytest.approx(5 / 18, rel=1e-9)
