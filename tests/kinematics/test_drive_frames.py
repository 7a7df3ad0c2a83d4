"""Drives are absolute (DESIGN § 1.1): angle, ω and α from the ground unless ``relative_to`` says.

A five-bar O–A–B–C–D with two inputs: crank a about the ground pivot O and
link b about the *moving* pivot A.  ``mech`` once read b's angle as absolute
but its ω and α relative to a, so b turned at ω_a + ω_b and every velocity was
off by 23–67 % with no note.  The reference values come from a closed form
written here (circle intersection for C, the loop's 2×2 velocity equations)
and from central finite differences of that closed form in time.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from mech.errors import InputError
from mech.kinematics import solve
from mech.loader import loads

OA, AB, BC, CD = 2.0, 3.0, 4.0, 3.0  # mm
D = (5.0, 0.0)
NEAR_C = (7.5, 1.5)
# the inputs, absolute: θ_a, ω_a, α_a and θ_b, ω_b, α_b (deg, rad/s, rad/s²)
TA, WA, AA = 60.0, 10.0, 40.0
TB, WB, AB_ = 20.0, 30.0, -25.0

FILE = """
name: two-crank five-bar
units: {{length: mm, angle: deg}}
ground: frame
links: [frame, a, b, c, d]
joints:
  O: {{type: revolute, links: [frame, a], at: [0, 0]}}
  A: {{type: revolute, links: [a, b]}}
  B: {{type: revolute, links: [b, c]}}
  C: {{type: revolute, links: [c, d], near: [7.5, 1.5]}}
  D: {{type: revolute, links: [d, frame], at: [5, 0]}}
lengths: {{OA: 2, AB: 3, BC: 4, CD: 3}}
drive:
  - {{link: a, angle: {ta}, omega: {wa}, alpha: {aa}}}
  - {{link: b, about: A, {rel}angle: {tb}, omega: {wb}, alpha: {ab}}}
"""

ABSOLUTE = FILE.format(ta=TA, wa=WA, aa=AA, rel="", tb=TB, wb=WB, ab=AB_)
RELATIVE = FILE.format(ta=TA, wa=WA, aa=AA, rel="relative_to: a, ", tb=TB - TA, wb=WB - WA, ab=AB_ - AA)


def closed_form(ta: float, tb: float) -> dict[str, np.ndarray]:
    """Joint positions (mm) for absolute input angles ta, tb (rad), C on the side of NEAR_C."""
    a = OA * np.array([math.cos(ta), math.sin(ta)])
    b = a + AB * np.array([math.cos(tb), math.sin(tb)])
    d = np.array(D)
    w = d - b
    dist = math.hypot(*w)
    along = (BC**2 - CD**2 + dist**2) / (2 * dist)
    h = math.sqrt(BC**2 - along**2)
    e = w / dist
    perp = np.array([-e[1], e[0]])
    options = [b + along * e + h * perp, b + along * e - h * perp]
    c = min(options, key=lambda p: math.dist(p, NEAR_C))
    return {"A": a, "B": b, "C": c}


def angle(p: np.ndarray, q: np.ndarray) -> float:
    return math.atan2(q[1] - p[1], q[0] - p[0])


def reference() -> dict[str, float]:
    """ω and α of c and d, and v_C (m/s), from the loop equations and finite differences."""
    ta, tb = math.radians(TA), math.radians(TB)
    pos = closed_form(ta, tb)
    b, c = pos["B"], pos["C"]
    # v_B from the two inputs; then v_B + ω_c k×(C − B) = ω_d k×(C − D)
    a = pos["A"]
    v_b = WA * np.array([-a[1], a[0]]) + WB * np.array([-(b - a)[1], (b - a)[0]])
    cb, cd = c - b, c - np.array(D)
    m = np.array([[-cb[1], cd[1]], [cb[0], -cd[0]]])
    w_c, w_d = np.linalg.solve(m, -v_b)
    v_c = w_d * np.array([-cd[1], cd[0]]) * 1e-3  # m/s

    # α by central differences in time of the closed-form angles (inputs on their α laws)
    def angles(t: float) -> tuple[float, float]:
        p = closed_form(ta + WA * t + 0.5 * AA * t * t, tb + WB * t + 0.5 * AB_ * t * t)
        return angle(p["B"], p["C"]), angle(np.array(D), p["C"])

    h = 1e-5  # truncation ~h²ω³ ≈ 3e-6 relative; rounding ~1e-16/h² ≈ 1e-6 rad/s²
    (c0, d0), (cp, dp), (cm, dm) = angles(0.0), angles(h), angles(-h)
    fd_w = ((cp - cm) / (2 * h), (dp - dm) / (2 * h))
    fd_al = ((cp - 2 * c0 + cm) / h**2, (dp - 2 * d0 + dm) / h**2)
    assert fd_w == pytest.approx((w_c, w_d), rel=1e-6)  # the two derivations agree
    return {"w_c": w_c, "w_d": w_d, "al_c": fd_al[0], "al_d": fd_al[1], "vcx": v_c[0], "vcy": v_c[1]}


@pytest.mark.parametrize("text", [ABSOLUTE, RELATIVE], ids=["absolute", "relative_to"])
def test_drive_about_a_moving_pivot_turns_its_link_at_the_given_absolute_rates(text):
    ref = reference()
    kin = solve(loads(text), level="acceleration")
    assert kin.links["a"].omega == pytest.approx(WA, rel=1e-12)
    assert kin.links["b"].omega == pytest.approx(WB, rel=1e-12)
    assert kin.links["b"].alpha == pytest.approx(AB_, rel=1e-12)
    assert math.degrees(kin.links["b"].angle) == pytest.approx(TB, rel=1e-12)
    assert kin.links["c"].omega == pytest.approx(ref["w_c"], rel=1e-9)
    assert kin.links["d"].omega == pytest.approx(ref["w_d"], rel=1e-9)
    assert kin.links["c"].alpha == pytest.approx(ref["al_c"], rel=1e-5)
    assert kin.links["d"].alpha == pytest.approx(ref["al_d"], rel=1e-5)
    assert kin.velocity("C") == pytest.approx((ref["vcx"], ref["vcy"]), rel=1e-9)


def test_drive_json_reports_absolute_and_relative_values(run, write):
    absolute = json.loads(run("acceleration", str(write(ABSOLUTE)), "--json").stdout)["drives"][1]
    relative = json.loads(run("acceleration", str(write(RELATIVE, "r.yaml")), "--json").stdout)["drives"][1]
    assert absolute["relative_to"] is None and relative["relative_to"] == "a"
    # the drive's own values are in its own convention …
    assert (absolute["angle"], absolute["omega"], absolute["alpha"]) == pytest.approx((TB, WB, AB_))
    assert (relative["angle"], relative["omega"], relative["alpha"]) == pytest.approx(
        (TB - TA, WB - WA, AB_ - AA)
    )
    # … and both report the other one: θ_b, ω_b, α_b from the ground and minus link a's
    for entry in (absolute, relative):
        assert [entry["absolute"][k] for k in ("angle", "omega", "alpha")] == pytest.approx([TB, WB, AB_])
        assert entry["relative"]["to"] == "a"
        assert [entry["relative"][k] for k in ("angle", "omega", "alpha")] == pytest.approx(
            [TB - TA, WB - WA, AB_ - AA]
        )


def test_drive_table_names_both_conventions(run, write):
    out = run("velocity", str(write(RELATIVE))).stdout
    text = " ".join(out.split())  # the line folds at the terminal's width
    assert "drive b relative to a, at -40.000 deg, ω = 20.000 rad/s ccw" in text
    assert "(absolute: 20.000 deg, ω = 30.000 rad/s ccw" in text


def test_drive_relative_to_a_link_without_a_line_is_refused():
    text = ABSOLUTE.replace("links: [frame, a, b, c, d]", "links: [frame, a, b, c, d, e]").replace(
        "{link: b, about: A,", "{link: b, about: A, relative_to: e,"
    )
    with pytest.raises(InputError, match="relative_to e, which has no line"):
        solve(loads(text), level="velocity")


@pytest.mark.parametrize(("value", "message"), [("zz", "unknown link 'zz'"), ("b", "relative to itself")])
def test_drive_relative_to_must_name_another_link(value, message, run, write):
    path = write(RELATIVE.replace("relative_to: a", f"relative_to: {value}"))
    result = run("velocity", str(path))
    assert result.exit_code == 2
    assert message in result.stderr
    assert f"{path.name}:" in result.stderr


# -- the drive as the file gave it (issue 11) ---------------------------------------------------
# ``angle: 60`` is read as 60·(π/180) rad; dividing by π/180 again gives 59.99999999999999.


def test_drive_json_gives_the_angle_as_the_file_wrote_it(run, write):
    text = FILE.format(ta=TA, wa=WA, aa=AA, rel="", tb=60, wb=WB, ab=AB_)
    assert math.radians(60) / (math.pi / 180) != 60.0  # the rounding this is about
    for level in ("position", "velocity", "acceleration"):
        drive = json.loads(run(level, str(write(text)), "--json").stdout)["drives"][1]
        assert drive["angle"] == 60.0, level  # exactly, not approximately
        assert drive["absolute"]["angle"] == 60.0, level


def test_a_drive_angle_read_back_from_radians_is_the_decimal_written():
    """Every angle to 0.01° in ±720°: read (× π/180) and reported, it is the number written."""
    from mech.render.kinematics import _as_read

    for hundredths in range(-72000, 72001, 7):
        written = hundredths / 100
        assert _as_read(written * (math.pi / 180), "deg") == written
    assert _as_read(0.1, "rad") == 0.1 and _as_read(None, "deg") is None


@pytest.mark.parametrize("level", ["position", "velocity"])
def test_drive_json_frame_of_its_own_convention_repeats_its_values(level, run, write):
    """α is an input (the file's, 0 by default): at velocity level the drive's α and its
    absolute α were 0.0 and null; ω likewise at position level. The frame of the drive's own
    convention is the drive itself; the other is derived from the solve (null where not solved)."""
    absolute = FILE.format(ta=TA, wa=WA, aa=AA, rel="", tb=TB, wb=WB, ab=0)
    drive = json.loads(run(level, str(write(absolute)), "--json").stdout)["drives"][1]
    for key in ("angle", "omega", "alpha"):
        assert drive["absolute"][key] == drive[key], key
    assert drive["alpha"] == 0.0 and drive["omega"] == WB
    if level == "velocity":  # ω_b − ω_a from the solve; α_a is not solved at velocity level
        assert drive["relative"]["omega"] == pytest.approx(WB - WA, rel=1e-12)
        assert drive["relative"]["alpha"] is None
    relative = FILE.format(ta=TA, wa=WA, aa=AA, rel="relative_to: a, ", tb=TB - TA, wb=WB - WA, ab=0)
    drive = json.loads(run(level, str(write(relative, "r.yaml")), "--json").stdout)["drives"][1]
    for key in ("angle", "omega", "alpha"):
        assert drive["relative"][key] == drive[key], key
    assert drive["absolute"]["alpha"] is None  # α_b = α + α_a: needs the acceleration solve
