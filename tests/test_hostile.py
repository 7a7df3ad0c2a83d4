"""Hostile-input and hand-solved-number tests (QA audit).

Every test runs the real ``mech`` the way a user does (``python -m mech`` in a
subprocess), so exit statuses, stderr and even crashes of the interpreter
(a segfault in the YAML parser) are seen exactly as on a terminal.

Expected behaviour comes from cli.md / DESIGN.md:

* bad input -> exit 2, ``file:line:column: error: ...`` and a ``hint:``, never a traceback;
* a failed check -> exit 1; one bad file in a batch never stops the others;
* numbers are right or refused, never silently wrong.

Expected numbers are derived here in closed form, never taken from mech.

Tests marked ``# Audit defect, fixed`` pinned a defect the audit found; the comment
says what used to happen.  The others guard hostile inputs that always held.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from cli_runner import mech, strict_json

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "mechanisms"

REL = 1e-9  # relative accuracy asked of velocities against closed forms


# -- helpers ------------------------------------------------------------------------------
def assert_bad_input(proc, path: Path | str | None = None, *, located: bool = True) -> None:
    """Exit 2, an ``error:`` on stderr (located when asked), never a traceback."""
    assert "Traceback" not in proc.stderr, proc.stderr[-2000:]
    assert proc.returncode == 2, (proc.returncode, proc.stdout[-500:], proc.stderr[-1500:])
    assert "error:" in proc.stderr
    if located and path is not None:
        import re

        assert re.search(re.escape(str(path)) + r":\d+:\d+: error:", proc.stderr), proc.stderr


def points(data: dict) -> dict[str, dict]:
    """Points of a kinematics JSON by name (first entry per name)."""
    out: dict[str, dict] = {}
    for p in data["points"]:
        out.setdefault(p["point"], p)
    return out


def close(a: float, b: float, rel: float = REL, abs_: float = 0.0) -> bool:
    return abs(a - b) <= max(rel * max(abs(a), abs(b)), abs_)


@pytest.fixture
def yaml_file(tmp_path: Path):
    def _write(text: str, name: str = "m.yaml") -> Path:
        path = tmp_path / name
        path.write_text(text, encoding="utf-8")
        return path

    return _write


def slider_crank(
    r: float = 0.1,
    L: float = 0.4,
    angle: float = 90,
    omega: float = 10,
    offset: float = 0.0,
    origin: float = 0.0,
    near_x: float | None = None,
    extra: str = "",
) -> str:
    """In-line (or offset) slider crank, crank O at (origin, origin), path y = origin + offset."""
    nx = origin + (near_x if near_x is not None else r + L)
    return f"""\
links: [frame, crank, rod, piston]
joints:
  O: {{type: revolute, links: [frame, crank], at: [{origin!r}, {origin!r}]}}
  A: {{type: revolute, links: [crank, rod]}}
  B: {{type: revolute, links: [rod, piston], near: [{nx!r}, {origin + offset!r}]}}
  P: {{type: prismatic, links: [piston, frame], path: {{through: [{origin!r}, {origin + offset!r}], angle: 0}}}}
lengths: {{OA: {r!r}, AB: {L!r}}}
drive: {{link: crank, angle: {angle!r}, omega: {omega!r}, direction: ccw}}
{extra}"""


FOUR_BAR_PARALLELOGRAM = """\
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [1.3, 0.4]}
  D: {type: revolute, links: [rocker, frame], at: [1, 0]}
lengths: {AB: 0.5, BC: 1, CD: 0.5}
drive: {link: crank, angle: 60, omega: 10, direction: ccw}
"""


# =========================================================================================
# 1. Numbers against closed forms (all pass today)
# =========================================================================================
def test_inline_slider_crank_at_90deg_rod_omega_zero_slider_speed_omega_r(yaml_file):
    # crank vertical: A = (0, r), vA = (-w r, 0); the rod translates, so w_rod = 0, vB = -w r.
    r, L, w = 0.1, 0.4, 10.0
    f = yaml_file(slider_crank(r, L, 90, w))
    p = mech("velocity", "--json", str(f))
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    assert abs(d["links"]["rod"]["omega"]) <= 1e-12 * w
    assert close(d["links"]["crank"]["omega"], w)
    b = points(d)["B"]
    assert close(b["position"][0], math.sqrt(L * L - r * r))
    assert close(b["velocity"][0], -w * r)
    assert abs(b["velocity"][1]) <= 1e-12 * w * r
    assert close(abs(d["sliders"][0]["sliding"]), w * r)


@pytest.mark.parametrize("angle, sign", [(0, -1), (180, +1)])
def test_slider_crank_at_dead_centre_slider_stops_rod_omega_is_w_r_over_l(yaml_file, angle, sign):
    # At 0 deg: A = (r, 0), vA = (0, w r); B - A = (l, 0): vB = vA + w3 k x (B-A) = (0, w r + w3 l)
    # must be horizontal -> w3 = -w r / l.  At 180 deg: A = (-r, 0), vA = (0, -w r) -> w3 = +w r / l.
    r, L, w = 0.1, 0.4, 10.0
    f = yaml_file(slider_crank(r, L, angle, w))
    p = mech("velocity", "--json", str(f))
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    assert close(d["links"]["rod"]["omega"], sign * w * r / L)
    b = points(d)["B"]
    assert math.hypot(*b["velocity"]) <= 1e-12 * w * r
    assert close(b["position"][0], (r + L) if angle == 0 else (L - r))


def test_parallelogram_coupler_translates_and_rocker_turns_with_crank(yaml_file):
    f = yaml_file(FOUR_BAR_PARALLELOGRAM)
    p = mech("velocity", "--json", str(f))
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    assert abs(d["links"]["coupler"]["omega"]) <= 1e-12 * 10
    assert close(d["links"]["rocker"]["omega"], 10.0)
    pts = points(d)
    # B = 0.5 (cos60, sin60); vB = w k x B; C = B + (1, 0) has the same velocity
    vb = (-10 * 0.5 * math.sin(math.radians(60)), 10 * 0.5 * math.cos(math.radians(60)))
    for name in ("B", "C"):
        assert close(pts[name]["velocity"][0], vb[0])
        assert close(pts[name]["velocity"][1], vb[1])


def test_offset_slider_crank_at_0deg_closed_form(yaml_file):
    # A = (r, 0), path y = e: B = (r + sqrt(l^2 - e^2), e).  vA = (0, w r).
    # vB = vA + w3 (-(e), sqrt(l^2-e^2)) horizontal -> w3 = -w r / sqrt(l^2 - e^2); vBx = -w3 e.
    r, L, e, w = 0.1, 0.4, 0.1, 10.0
    f = yaml_file(slider_crank(r, L, 0, w, offset=e))
    p = mech("velocity", "--json", str(f))
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    s = math.sqrt(L * L - e * e)
    w3 = -w * r / s
    assert close(d["links"]["rod"]["omega"], w3)
    b = points(d)["B"]
    assert close(b["position"][0], r + s)
    assert close(b["velocity"][0], -w3 * e)


def test_inline_slider_crank_acceleration_at_90deg_closed_form(yaml_file):
    # Constant w.  aA = (0, -w^2 r).  B - A = (s, -r), s = sqrt(l^2 - r^2); w_rod = 0 at this instant.
    # aB = aA + alpha3 k x (B - A) = (alpha3 r, -w^2 r + alpha3 s) with aBy = 0:
    # alpha3 = w^2 r / s, aB = w^2 r^2 / s.
    r, L, w = 0.1, 0.4, 10.0
    f = yaml_file(slider_crank(r, L, 90, w))
    p = mech("acceleration", "--json", str(f))
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    s = math.sqrt(L * L - r * r)
    assert close(d["links"]["rod"]["alpha"], w * w * r / s)
    assert close(points(d)["B"]["acceleration"][0], w * w * r * r / s)
    assert close(points(d)["A"]["acceleration"][1], -w * w * r)


def test_slider_driven_crank_near_dead_centre_closed_form(yaml_file):
    # Slider drive vB = (1, 0) with B at x = 0.45: A from the two circles, then
    # w2 (ax ay/(ax - x) - ay) = 1, w3 = w2 ax / (ax - x).
    r, L, x = 0.1, 0.4, 0.45
    f = yaml_file(
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


def test_units_mm_is_si_times_1000(yaml_file):
    f = yaml_file(slider_crank(0.1, 0.4, 30, 10))
    si = strict_json(mech("acceleration", "--json", str(f)).stdout)
    mm = strict_json(mech("acceleration", "--json", "--units", "mm", str(f)).stdout)
    for a, b in zip(si["points"], mm["points"], strict=True):
        for key in ("position", "velocity", "acceleration"):
            for x, y in zip(a[key], b[key], strict=True):
                assert close(y, 1000 * x, abs_=1e-9)
    for name in si["links"]:
        assert si["links"][name]["omega"] == pytest.approx(mm["links"][name]["omega"], rel=1e-12, abs=1e-12)


# =========================================================================================
# 2. Singular configurations must be refused, never printed as huge numbers (pass today)
# =========================================================================================
def test_four_bar_exactly_at_toggle_velocities_refused(yaml_file):
    # Passes.  Guard: during the audit the uncommitted closed-form dyad path (kinematics/dyads.py)
    # briefly raised ZeroDivisionError (a traceback) here; this test caught it.
    # AB = BC = CD = 1, AD = 2: coupler and rocker in line when |BD| = 2, i.e. cos(theta) = 1/4.
    f = yaml_file(
        """\
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [1.1, 0.5]}
  D: {type: revolute, links: [rocker, frame], at: [2, 0]}
lengths: {AB: 1, BC: 1, CD: 1}
drive: {link: crank, angle: 60, omega: 10}
"""
    )
    p = mech("velocity", "--json", str(f), "--angle", repr(math.degrees(math.acos(0.25))))
    assert_bad_input(p, located=False)
    assert "singular" in p.stderr or "toggle" in p.stderr
    assert p.stdout == ""


@pytest.mark.parametrize("angle", ["0", "180"])
def test_parallelogram_folded_flat_is_refused(yaml_file, angle):
    # Passes.  Guard: briefly a ZeroDivisionError traceback from the uncommitted closed-form dyad
    # path (kinematics/dyads.py) during the audit.
    f = yaml_file(FOUR_BAR_PARALLELOGRAM)
    p = mech("velocity", "--json", str(f), "--angle", angle)
    assert_bad_input(p, located=False)
    assert p.stdout == ""


def test_structure_asked_for_velocities_is_refused(yaml_file):
    f = yaml_file(
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


def test_five_bar_with_one_drive_is_refused_and_mentions_drives(yaml_file):
    f = yaml_file(
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


def test_spherical_pair_velocity_refused_with_location(yaml_file):
    f = yaml_file(
        """\
links: [frame, a, b]
joints:
  A: {type: spherical, links: [frame, a], at: [0, 0]}
  B: {type: revolute, links: [a, b], at: [1, 0]}
drive: {link: a, rpm: 60}
"""
    )
    assert_bad_input(mech("velocity", str(f)), f)


# =========================================================================================
# 3. Defects: silently wrong numbers
# =========================================================================================
DRAWN_FOUR_BAR = """\
links: [frame, crank, coupler, rocker]
joints:
  A: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  B: {{type: revolute, links: [crank, coupler], at: [0, 1]}}
  C: {{type: revolute, links: [coupler, rocker], at: [2, 1]}}
  D: {{type: revolute, links: [rocker, frame], at: [2, 0]}}
lengths: {{AB: {ab}, BC: 2, CD: 1}}
drive: {{link: crank, angle: {angle}, omega: 1}}
"""


def test_drive_angle_opposite_to_the_drawing_is_an_error(yaml_file):
    # Audit defect, fixed: the drawing puts B at 90 deg from A; the file says the crank is at 270 deg.
    # DESIGN.md: drive.angle given with a drawing "must agree with it (else an error that says by
    # how much)".  mech checks only the *line* of the crank (n . (B - A) = 0), so 270 == 90 to it:
    # exit 0, the header says "at 270 deg" while the table shows the crank at 90 deg.
    f = yaml_file(DRAWN_FOUR_BAR.format(ab=1, angle=270))
    p = mech("velocity", str(f))
    assert p.returncode == 2, p.stdout
    assert "180" in p.stderr


def test_drive_angle_opposite_to_drawing_then_angle_override_lands_on_wrong_side(yaml_file):
    # Audit defect, fixed: same file, `--angle 100` puts B at 280 deg (silently wrong position) because
    # the continuation starts from "270 deg" while the drawing is at 90 deg.
    f = yaml_file(DRAWN_FOUR_BAR.format(ab=1, angle=270))
    p = mech("position", "--json", str(f), "--angle", "100")
    if p.returncode == 2:  # refused: acceptable
        assert "Traceback" not in p.stderr
        return
    bx, by = points(strict_json(p.stdout))["B"]["position"]
    assert math.degrees(math.atan2(by, bx)) % 360 == pytest.approx(100.0, abs=1e-9)


def test_drawing_that_agrees_is_accepted_and_slight_disagreement_refused(yaml_file):
    # passes today (guard): 1e-7 relative is "agreement", 1e-3 is refused with the amount.
    ok = mech("velocity", str(yaml_file(DRAWN_FOUR_BAR.format(ab="1.0000001", angle=90), "ok.yaml")))
    assert ok.returncode == 0, ok.stderr
    bad = mech("velocity", str(yaml_file(DRAWN_FOUR_BAR.format(ab="1.001", angle=90), "bad.yaml")))
    assert bad.returncode == 2 and "0.001" in bad.stderr and "Traceback" not in bad.stderr


GEARS = """\
links: [frame, g1, g2]
joints:
  O1: {{type: revolute, links: [frame, g1], at: [0, 0]}}
  O2: {{type: revolute, links: [frame, g2], at: [{x2}, 0]}}
  M: {{type: gear, links: [g1, g2], {size}}}
drive: {{link: g1, rpm: 600}}
"""


@pytest.mark.parametrize("size", ["teeth: [20, 40], module: 5 mm", "radii: [0.05, 0.1]"])
def test_gear_centre_distance_that_contradicts_pitch_radii_is_refused(yaml_file, size):
    # Audit defect, fixed: pitch radii 50 + 100 mm need centres 150 mm apart; the file puts them 300 mm
    # apart.  mech accepts it (exit 0) and reports the pitch point M twice with different
    # velocities (3.14 m/s on g1, 7.85 m/s on g2): the teeth would slip.  Must be an error.
    f = yaml_file(GEARS.format(x2=0.3, size=size))
    p = mech("velocity", str(f))
    assert_bad_input(p, f)


def test_consistent_gears_pitch_point_moves_alike_on_both(yaml_file):
    # passes today (guard): centres 150 mm apart, z 20/40: w2 = -w1/2; pitch point speed w1 r1.
    f = yaml_file(GEARS.format(x2=0.15, size="teeth: [20, 40], module: 5 mm"))
    p = mech("velocity", "--json", str(f))
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    w1 = 600 * 2 * math.pi / 60
    assert close(d["links"]["g2"]["omega"], -w1 / 2)
    speeds = [math.hypot(*q["velocity"]) for q in d["points"] if q["point"] == "M"]
    assert speeds and all(close(s, w1 * 0.05) for s in speeds)


def test_mechanism_far_from_origin_gives_wrong_velocity(yaml_file):
    # Audit defect, fixed: the same slider crank drawn with O at (1e12, 1e12) m.  The answer is
    # translation-invariant (|vB| = w r = 1 m/s at 90 deg) but mech prints 0.99976 m/s (1e-4 off;
    # 6% off at 1e14).  Solve relative to a local origin, or refuse.
    f = yaml_file(slider_crank(0.1, 0.4, 90, 10, origin=1e12))
    p = mech("velocity", "--json", str(f))
    if p.returncode == 2:
        assert "Traceback" not in p.stderr
        return
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    assert close(abs(d["sliders"][0]["sliding"]), 1.0)


def test_huge_but_finite_mechanism_prints_nan_with_exit_0(yaml_file):
    # Audit defect, fixed: lengths 1e307 m: every velocity is NaN (printed "nan", null in JSON) with
    # exit status 0 and a numpy RuntimeWarning.  The true slider speed w r = 1e308 is finite.
    f = yaml_file(slider_crank(1e307, 4e307, 90, 10, near_x=5e307))
    p = mech("velocity", "--json", str(f))
    if p.returncode == 2:
        assert "Traceback" not in p.stderr
        return
    assert p.returncode == 0
    d = strict_json(p.stdout)
    sliding = d["sliders"][0]["sliding"]
    assert sliding is not None and close(abs(sliding), 1e308)


def test_angle_override_huge_degrees_reduced_exactly(yaml_file):
    # Audit defect, fixed (was low severity): 1e300 deg is an exact multiple of 360 (math.fmod gives 0),
    # so A must be at (r, 0); mech converts to radians first and lands at about 266 deg.
    assert math.fmod(1e300, 360.0) == 0.0
    f = yaml_file(slider_crank(0.1, 0.4, 90, 10))
    p = mech("position", "--json", str(f), "--angle", "1e300")
    if p.returncode == 2:
        assert "Traceback" not in p.stderr
        return
    ax, ay = points(strict_json(p.stdout))["A"]["position"]
    assert close(ax, 0.1) and abs(ay) < 1e-12


def test_velocity_directions_are_in_0_360(yaml_file):
    # Audit defect, fixed (was cosmetic): a velocity along +x with a -1e-15 y component prints direction
    # 360.0 (e.g. mechanisms/slider_crank.yaml, point B); angles are reported in [0, 360).
    f = yaml_file(
        """\
links: [frame, crank, rod, piston]
joints:
  O: {type: revolute, links: [frame, crank], at: [0, 0]}
  A: {type: revolute, links: [crank, rod]}
  B: {type: revolute, links: [rod, piston], near: [-700, 0]}
  P: {type: prismatic, links: [piston, frame], path: {through: [0, 0], angle: 0}}
units: {length: mm}
lengths: {OA: 150, AB: 600}
drive: {link: crank, angle: 135, rpm: 300, direction: cw}
"""
    )
    p = mech("velocity", "--json", str(f))
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    for q in d["points"]:
        if q["direction"] is not None:
            assert 0.0 <= q["direction"] < 360.0, q
    for q in d["relative"]:
        assert q.get("direction") is None or 0.0 <= q["direction"] < 360.0, q


def test_near_toggle_velocity_accuracy_after_continuation(yaml_file):
    # Audit defect, fixed: AB = BC = CD = 1, AD = 2 drawn at 60 deg, asked at 75.5224878 deg (1.4e-8 deg
    # short of the toggle; mech does not call it singular).  Closed form: |w_coupler| = 313962.3;
    # mech prints 313949.0 (4.2e-5 off) with the default --tol 1e-12 (--tol 1e-15 gives 1.7e-7).
    # solve.py promises about 1e-6 below its singular threshold: refuse or be within 1e-6.
    def closed_form(th: float, w: float = 10.0) -> set[float]:
        out = set()
        bx, by = math.cos(th), math.sin(th)
        ex, ey = 2 - bx, -by
        r = math.hypot(ex, ey)
        x = r / 2
        h = math.sqrt(1 - x * x)
        for br in (1, -1):
            cx, cy = bx + x * ex / r - br * h * ey / r, by + x * ey / r + br * h * ex / r
            px, py, qx, qy = cx - bx, cy - by, cx - 2, cy
            vbx, vby = -w * by, w * bx
            det = (-py) * (-qx) - qy * px
            out.add(abs((-vbx * -qx - qy * -vby) / det))
        return out

    f = yaml_file(
        """\
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [1.1, 0.5]}
  D: {type: revolute, links: [rocker, frame], at: [2, 0]}
lengths: {AB: 1, BC: 1, CD: 1}
drive: {link: crank, angle: 60, omega: 10}
"""
    )
    p = mech("velocity", "--json", str(f), "--angle", "75.5224878")
    if p.returncode == 2:
        assert "Traceback" not in p.stderr
        return
    assert p.returncode == 0, p.stderr
    w = abs(strict_json(p.stdout)["links"]["coupler"]["omega"])
    expected = closed_form(math.radians(75.5224878))
    assert any(abs(w - e) <= 1e-6 * e for e in expected), (w, expected)


# =========================================================================================
# 4. Defects: infinities that get in, tracebacks and crashes on bad input
# =========================================================================================
@pytest.mark.parametrize(
    "units, length",
    [("", '"1e308 km"'), ("units: {length: km}\n", "1e306"), ("", '"1e308 ft"')],
)
def test_length_that_overflows_to_infinity_is_refused(yaml_file, units, length):
    # Audit defect, fixed: parse_number refuses inf, but the unit factor is applied afterwards, so
    # "1e308 km" = inf m gets in; `mech velocity` then dies with LinAlgError (a traceback).
    # cli.md: "NaN and infinity are refused."
    text = units + slider_crank(0.1, 0.4, 90, 10).replace("AB: 0.4", f"AB: {length}")
    f = yaml_file(text)
    from mech.errors import InputError
    from mech.loader import loads

    with pytest.raises(InputError):
        loads(text, path="m.yaml")
    assert_bad_input(mech("velocity", str(f)), f)


def test_omega_overflowing_to_infinity_is_refused(yaml_file):
    # Audit defect, fixed: omega "1e308 rps" = 6.3e308 rad/s = inf: accepted, velocities print nan, exit 0.
    f = yaml_file(slider_crank(0.1, 0.4, 90, 10).replace("omega: 10", 'omega: "1e308 rps"'))
    assert_bad_input(mech("velocity", str(f)), f)


@pytest.mark.parametrize("where", ["file", "option"])
def test_velocity_with_an_omega_too_large_to_square_is_refused(yaml_file, where):
    # omega 1e200 (finite) once raised OverflowError in solve._result (omega_ref**2) even at
    # velocity level.  mech refuses it as bad input (exit 2), from the file or the option alike.
    if where == "file":
        f = yaml_file(slider_crank(0.1, 0.4, 90, 10).replace("omega: 10", "omega: 1e200"))
        p = mech("velocity", "--json", str(f))
    else:
        f = yaml_file(slider_crank(0.1, 0.4, 90, 10))
        p = mech("velocity", "--json", str(f), "--omega", "1e200")
    assert "Traceback" not in p.stderr, p.stderr[-800:]
    assert p.returncode == 2, p.stdout[-800:]
    assert p.stderr.strip()


def test_deeply_nested_yaml_is_an_error_not_a_segfault(yaml_file):
    # Audit defect, fixed (was severe): 50 000 nested brackets (100 kB) segfault the C YAML composer:
    # exit -11 / 139, no message at all.
    f = yaml_file(
        "links: [frame, crank]\njoints:\n  A: {type: revolute, links: [frame, crank]}\n"
        "description: " + "[" * 50_000 + "]" * 50_000 + "\n"
    )
    p = mech("dof", str(f), subprocess_=True)  # a crash of the interpreter shows only out of process
    assert p.returncode == 2, (p.returncode, p.stderr[-500:])
    assert "error:" in p.stderr and "Traceback" not in p.stderr


def test_cam_without_contact_point_is_located_error_not_traceback(yaml_file):
    # Audit defect, fixed: a cam joint with no `at` -> KeyError 'T' in constraints.build_system.
    f = yaml_file(
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


# =========================================================================================
# 5. Defects: solver refusals without file:line:column or hint
# =========================================================================================
def test_unreachable_offset_path_error_is_located_with_hint(yaml_file):
    # Audit defect, fixed: "error: cannot assemble m.yaml: B cannot reach its path: ..." has no
    # line:column and no hint (cli.md: every error is file:line:column with a hint).
    f = yaml_file(slider_crank(0.1, 0.4, 90, 10, offset=1.0))
    p = mech("velocity", str(f))
    assert_bad_input(p, f)
    assert "hint:" in p.stderr


def test_length_disagreeing_with_drawing_error_is_located(yaml_file):
    # Audit defect, fixed: "error: length AB = 1.5 m but the drawing gives 1 m (off by 0.5 m)" names
    # neither the file nor the line of `AB` in lengths.
    f = yaml_file(DRAWN_FOUR_BAR.format(ab=1.5, angle=90))
    p = mech("velocity", str(f))
    assert_bad_input(p, f)
    assert "0.5" in p.stderr


def test_drawn_toggle_angle_does_not_make_other_angles_unassemblable(yaml_file):
    # FAILED at commit 9198f9e; PASSES with the uncommitted closed-form dyad path (dyads.py) in the
    # working tree.  The file's drive angle is exactly the toggle (cos = 1/4); --angle 70 (which
    # assembles: |BD|^2 = 5 - 4 cos 70 < 4) failed with "cannot be assembled with crank at 70 deg
    # ... leaves D open by 0.02221 m" -- false: continuation could not leave the singular start.
    # Expected: C at distance 1 from B and from D.
    toggle = math.degrees(math.acos(0.25))
    f = yaml_file(
        f"""\
links: [frame, crank, coupler, rocker]
joints:
  A: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  B: {{type: revolute, links: [crank, coupler]}}
  C: {{type: revolute, links: [coupler, rocker], near: [1.1, 0.5]}}
  D: {{type: revolute, links: [rocker, frame], at: [2, 0]}}
lengths: {{AB: 1, BC: 1, CD: 1}}
drive: {{link: crank, angle: {toggle!r}, omega: 10}}
"""
    )
    assert mech("position", str(f)).returncode == 0  # the toggle itself has a position
    p = mech("position", "--json", str(f), "--angle", "70")
    assert p.returncode == 0, p.stderr
    pts = points(strict_json(p.stdout))
    b, c = pts["B"]["position"], pts["C"]["position"]
    assert math.degrees(math.atan2(b[1], b[0])) == pytest.approx(70, abs=1e-9)
    assert math.dist(b, c) == pytest.approx(1, rel=1e-9)
    assert math.dist(c, (2, 0)) == pytest.approx(1, rel=1e-9)


# =========================================================================================
# 6. YAML edge cases (all pass today: guards)
# =========================================================================================
def test_bom_and_crlf_are_read(yaml_file, tmp_path):
    f = tmp_path / "bom.yaml"
    f.write_bytes(
        b"\xef\xbb\xbflinks: [frame, crank]\r\njoints:\r\n  A: {type: revolute, links: [frame, crank]}\r\n"
    )
    p = mech("dof", "--json", str(f))
    assert p.returncode == 0, p.stderr
    assert strict_json(p.stdout)["dof"] == 1


def test_crlf_error_points_at_right_column(tmp_path):
    f = tmp_path / "crlf.yaml"
    f.write_bytes(b"links: [frame, crank]\r\njoints:\r\n  A: {type: revolute, links: [frame, crankk]}\r\n")
    p = mech("dof", str(f))
    assert_bad_input(p, f)
    assert f"{f}:3:38:" in p.stderr


def test_tab_indentation_is_located(yaml_file):
    f = yaml_file("links: [frame, crank]\njoints:\n\tA: {type: revolute, links: [frame, crank]}\n")
    p = mech("dof", str(f))
    assert_bad_input(p, f)
    assert f"{f}:3:1:" in p.stderr and "hint:" in p.stderr


def test_multi_document_file_is_refused_with_location(yaml_file):
    f = yaml_file(
        "links: [frame, crank]\njoints:\n  A: {type: revolute, links: [frame, crank]}\n---\nlinks: [x]\n"
    )
    p = mech("dof", str(f))
    assert_bad_input(p, f)
    assert f"{f}:4:1:" in p.stderr


def test_merge_key_refused(yaml_file):
    f = yaml_file("links: [frame, crank]\njoints:\n  A: {<<: {type: revolute}, links: [frame, crank]}\n")
    p = mech("dof", str(f))
    assert_bad_input(p, f)
    assert "merge" in p.stderr


def test_alias_bomb_refused_quickly(yaml_file):
    text = "a: &a [x,x,x,x,x,x,x,x,x,x]\n"
    for i in range(1, 9):
        prev = chr(96 + i)
        text += f"{chr(97 + i)}: &{chr(97 + i)} [" + ",".join([f"*{prev}"] * 10) + "]\n"
    p = mech("dof", str(yaml_file(text)), timeout=30)
    assert p.returncode == 2 and "Traceback" not in p.stderr


def test_big_file_is_read(yaml_file):
    f = yaml_file(
        "links: [frame, crank]\njoints:\n  A: {type: revolute, links: [frame, crank]}\n"
        "description: " + "x" * 5_000_000 + "\n"
    )
    p = mech("dof", "--json", str(f), timeout=60)
    assert p.returncode == 0 and strict_json(p.stdout)["dof"] == 1


def test_nulls_everywhere_each_located(yaml_file):
    f = yaml_file("name:\nunits:\nground:\nlinks:\njoints:\nlengths:\ndrive:\npoints:\nanswers:\n")
    p = mech("dof", str(f))
    assert_bad_input(p, f)
    for line in range(2, 10):
        assert f"{f}:{line}:" in p.stderr


@pytest.mark.parametrize("name", ["cr.ank", '"my link"', "a-b", "2.5"])
def test_unusable_link_names_are_located(yaml_file, name):
    f = yaml_file(f"links: [frame, {name}]\njoints:\n  A: {{type: revolute, links: [frame, {name}]}}\n")
    p = mech("dof", str(f))
    assert_bad_input(p, f)
    assert "hint:" in p.stderr


def test_unicode_names_are_fine(yaml_file):
    f = yaml_file(
        "links: [frame, 曲柄, Kurbel_ä]\njoints:\n  Á: {type: revolute, links: [frame, 曲柄]}\n"
        "  B: {type: revolute, links: [曲柄, Kurbel_ä]}\n  C: {type: revolute, links: [Kurbel_ä, frame]}\n"
    )
    p = mech("dof", "--json", str(f))
    assert p.returncode == 0 and strict_json(p.stdout)["dof"] == 0


def test_joint_listing_a_link_twice_and_bad_joint_values(yaml_file):
    f = yaml_file(
        """\
links: [frame, crank]
joints:
  D: {type: revolute, links: [frame, crank, crank]}
  E: {type: revolute, links: [frame, frame]}
  F: {type: revolute, links: [frame, crank], radius: 0}
"""
    )
    p = mech("dof", str(f))
    assert_bad_input(p, f)
    assert f"{f}:3:" in p.stderr and f"{f}:4:" in p.stderr and f"{f}:5:" in p.stderr


def test_two_ground_candidates_and_missing_ground(yaml_file):
    p = mech(
        "dof",
        str(yaml_file("links: [frame, ground]\njoints:\n  A: {type: revolute, links: [frame, ground]}\n")),
    )
    assert p.returncode == 2 and "ground" in p.stderr
    p = mech(
        "dof", str(yaml_file("links: [a, b]\njoints:\n  A: {type: revolute, links: [a, b]}\n", "n.yaml"))
    )
    assert p.returncode == 2 and "ground" in p.stderr


def test_duplicate_length_ab_ba_is_located(yaml_file):
    f = yaml_file(slider_crank().replace("AB: 0.4}", "AB: 0.4, B-A: 0.5}"))
    p = mech("velocity", str(f))
    assert_bad_input(p, f)
    assert "twice" in p.stderr


def test_zero_length_refused(yaml_file):
    f = yaml_file(slider_crank().replace("OA: 0.1", "OA: 0"))
    assert_bad_input(mech("velocity", str(f)), f)


def test_gear_teeth_without_module_located(yaml_file):
    f = yaml_file(GEARS.format(x2=0.15, size="teeth: [20, 40]"))
    p = mech("dof", str(f))
    assert_bad_input(p, f)
    assert "module" in p.stderr


@pytest.mark.parametrize(
    "stdin",
    [b"\x00\x01\x02garbage", b"\xff\xfe not utf8", b"{{{{", b"", b"[1, 2]", b'"just a string"'],
)
def test_stdin_garbage_is_exit_2(stdin):
    p = mech("dof", "-", input=stdin)
    assert p.returncode == 2 and "Traceback" not in p.stderr and "error:" in p.stderr


# =========================================================================================
# 7. Command-line options (pass today)
# =========================================================================================
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
def test_bad_solver_options_exit_2(yaml_file, opts):
    p = mech("velocity", str(yaml_file(slider_crank())), *opts)
    assert p.returncode == 2 and "Traceback" not in p.stderr and p.stdout == ""


def test_acceleration_alpha_nan_exit_2(yaml_file):
    p = mech("acceleration", str(yaml_file(slider_crank())), "--alpha", "nan")
    assert p.returncode == 2 and "Traceback" not in p.stderr


def test_rpm_zero_gives_zero_velocities(yaml_file):
    p = mech("velocity", "--json", str(yaml_file(slider_crank())), "--rpm", "0")
    assert p.returncode == 0
    d = strict_json(p.stdout)
    assert all(v["omega"] == 0 for v in d["links"].values())


# =========================================================================================
# 9. Output hygiene (pass today)
# =========================================================================================
@pytest.mark.parametrize("cmd", [["dof"], ["classify"], ["velocity"], ["acceleration"], ["icentres"]])
def test_no_escape_codes_in_plain_output(cmd):
    p = mech(*cmd, str(EXAMPLES / "four_bar.yaml"))
    assert p.returncode == 0
    assert "\x1b" not in p.stdout and "\x1b" not in p.stderr


def test_no_escape_codes_in_errors(yaml_file):
    p = mech(
        "dof",
        str(yaml_file("links: [frame, crank]\njoints:\n  A: {type: revolute, links: [frame, crankk]}\n")),
    )
    assert "\x1b" not in p.stderr
