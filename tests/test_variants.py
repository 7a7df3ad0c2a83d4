"""``mech variants`` and grading a class of variants (issue 22, "Done when").

A class of 40 from two ``vary:`` problems; every reference value is worked here:

* **Four-bar** A(0, 0) – B – C – D(150 mm, 0), BC = 150, CD = 80 mm, AB and the crank angle θ₂
  varied, the crank turning at n rpm clockwise (ω₂ = −2πn/60).  B = AB(cos θ₂, sin θ₂); C is the
  intersection of the circles (B, BC) and (D, CD) nearest the file's hint (160, 80) mm; then the
  vector loop v_B + ω₃ k × BC = ω₄ k × DC (a 2×2 solve) gives ω₄ and v_C = ω₄ k × DC.
  Grashof: s + l ≤ p + q with the crank shortest is a crank-rocker.  The least transmission
  angle of a crank-rocker is at θ₂ = 0 (C B D folded over AD): cos μ = (BC² + CD² − (AD − AB)²) /
  (2 BC CD) (Norton, *Design of Machinery*, § 4.10, eq. 4.32).
* **In-line slider crank** O(0, 0), crank r, rod L, θ varied, ω = 120 rpm ccw: the rod's angle
  sin φ = r sin θ / L; |v_B| = r ω |sin θ + r sin θ cos θ / √(L² − r² sin² θ)| and
  |ω_rod| = r ω |cos θ| / (L cos φ) (Hibbeler, *Engineering Mechanics: Dynamics*, § 16.5).
"""

from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from cli_runner import mech

MM = 1e-3

FOUR_BAR = """\
name: Four-bar for each student
units: {length: mm, angle: deg}
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [160, 80]}
  D: {type: revolute, links: [rocker, frame], at: [150, 0]}
lengths: {AB: 40, BC: 150, CD: 80}
drive: {link: crank, angle: 60, rpm: 120, direction: cw}
vary:
  lengths.AB: {from: 30, to: 60, step: 0.5}
  drive.angle: {from: 30, to: 150, step: 1}
  drive.rpm: [100, 120, 150, 200]
keep:
  grashof: crank-rocker
  transmission_angle.min: {at_least: 35 deg}
asks: {omega.rocker: 2, velocity.C: 3}
"""

SLIDER = """\
name: Slider crank for each student
units: {length: mm, angle: deg}
links: [frame, crank, rod, piston]
joints:
  O: {type: revolute, links: [frame, crank], at: [0, 0]}
  A: {type: revolute, links: [crank, rod]}
  B: {type: revolute, links: [rod, piston], near: [150, 0]}
  P: {type: prismatic, links: [piston, frame], path: {through: [0, 0], angle: 0}}
lengths: {OA: 30, AB: 120}
drive: {link: crank, angle: 45, rpm: 120, direction: ccw}
vary:
  lengths.OA: {from: 20, to: 40, step: 1}
  lengths.AB: {from: 100, to: 160, step: 2}
  drive.angle: {from: 10, to: 170, step: 1}
answers: {velocity.B: {value: 0, marks: 1}, omega.rod: {value: 0, marks: 4}}
"""

STUDENTS = [f"s{i:02d}" for i in range(1, 41)]


def _roster(path: Path, students: list[str]) -> Path:
    path.write_text("name,student\n" + "".join(f"Student {s},{s}\n" for s in students), encoding="utf-8")
    return path


def _variants(tmp: Path, problem: str, text: str, students: list[str], out: str, seed: int = 7):
    (tmp / problem).write_text(text, encoding="utf-8")
    roster = _roster(tmp / f"{out}.csv", students)
    return mech(
        "variants", str(tmp / problem), "--roster", str(roster), "--seed", str(seed), "-o", str(tmp / out)
    )


def _four_bar(ab: float, theta: float, rpm: float) -> tuple[float, float]:
    """(ω₄ signed, |v_C|) by the vector loop (module docstring)."""
    w2 = -rpm * 2 * math.pi / 60
    b = ab * np.array([math.cos(theta), math.sin(theta)])
    d = np.array([150 * MM, 0.0])
    c = _coupler_pin(ab, 150 * MM, theta)

    def k(w: float, r: np.ndarray) -> np.ndarray:
        return np.array([-w * r[1], w * r[0]])

    m = np.column_stack([k(1.0, c - b), -k(1.0, c - d)])
    _w3, w4 = np.linalg.solve(m, -k(w2, b))
    return float(w4), float(np.hypot(*k(w4, c - d)))


def _slider(r: float, rod: float, theta: float) -> tuple[float, float]:
    """(|v_B|, |ω_rod|) of the in-line slider crank (module docstring)."""
    w = 120 * 2 * math.pi / 60
    root = math.sqrt(rod**2 - (r * math.sin(theta)) ** 2)
    vb = r * w * abs(math.sin(theta) + r * math.sin(theta) * math.cos(theta) / root)
    return vb, r * w * abs(math.cos(theta)) / root


def _key(out: Path) -> dict[tuple[str, str], dict]:
    doc = json.loads((out / "key.json").read_text(encoding="utf-8"))
    return {(r["student"], r["key"]): r for r in doc["answers"]}


def _given(out: Path, student: str, name: str) -> dict:
    return yaml.safe_load((out / student / name).read_text(encoding="utf-8"))


def _tree(root: Path) -> dict[str, bytes]:
    return {p.relative_to(root).as_posix(): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def klass(tmp_path_factory: pytest.TempPathFactory) -> Path:
    tmp = tmp_path_factory.mktemp("class")
    for name, text in (("four_bar.yaml", FOUR_BAR), ("slider.yaml", SLIDER)):
        p = _variants(tmp, name, text, STUDENTS, f"class_{name[:-5]}")
        assert p.returncode == 0, p.stderr
        assert "40 students, 40 distinct variants" in p.stdout and not p.stderr
    return tmp


def test_every_variant_keeps_its_keep_and_its_key_is_the_closed_form(klass: Path) -> None:
    out = klass / "class_four_bar"
    key = _key(out)
    for s in STUDENTS:
        data = _given(out, s, "four_bar.yaml")
        assert not {"vary", "keep", "answers"} & set(data) and data["asks"] == {
            "omega.rocker": 2,
            "velocity.C": 3,
        }
        ab, bc, cd, ad = data["lengths"]["AB"], 150, 80, 150
        assert ab + max(bc, ad) <= cd + min(bc, ad) and ab < cd  # Grashof, crank shortest: crank-rocker
        mu_min = math.degrees(math.acos((bc**2 + cd**2 - (ad - ab) ** 2) / (2 * bc * cd)))
        assert mu_min >= 35
        w4, vc = _four_bar(ab * MM, math.radians(data["drive"]["angle"]), data["drive"]["rpm"])
        assert key[s, "omega.rocker"]["value"] == pytest.approx(w4, rel=1e-7)
        assert key[s, "velocity.C"]["value"] == pytest.approx(vc, rel=1e-7)
        assert (out / s / "four_bar.svg").read_text(encoding="utf-8").lstrip().startswith(("<?xml", "<svg"))
    out = klass / "class_slider"
    key = _key(out)
    for s in STUDENTS:
        data = _given(out, s, "slider.yaml")
        assert data["asks"] == {"velocity.B": 1, "omega.rod": 4}  # answers' keys become asks, with marks
        vb, wr = _slider(
            data["lengths"]["OA"] * MM, data["lengths"]["AB"] * MM, math.radians(data["drive"]["angle"])
        )
        assert key[s, "velocity.B"]["value"] == pytest.approx(vb, rel=1e-7)
        assert abs(key[s, "omega.rod"]["value"]) == pytest.approx(wr, rel=1e-7)
        # the drawn position of B is this variant's: the piston's x by the closed form
        r, rod, th = data["lengths"]["OA"], data["lengths"]["AB"], math.radians(data["drive"]["angle"])
        assert data["joints"]["B"]["near"][0] == pytest.approx(
            r * math.cos(th) + math.sqrt(rod**2 - (r * math.sin(th)) ** 2)
        )


def test_the_same_seed_writes_the_same_bytes_and_the_roster_order_changes_no_variant(klass: Path) -> None:
    again = _variants(klass, "slider.yaml", SLIDER, STUDENTS, "again")
    assert again.returncode == 0
    first = _tree(klass / "class_slider")
    assert _tree(klass / "again") == first
    shuffled = [*reversed(STUDENTS[::2]), "t99", *STUDENTS[1::2], "t01"]
    other = _variants(klass, "slider.yaml", SLIDER, shuffled, "shuffled")
    assert other.returncode == 0
    moved = _tree(klass / "shuffled")
    for s in STUDENTS:
        for f in ("slider.yaml", "slider.svg"):
            assert moved[f"{s}/{f}"] == first[f"{s}/{f}"], (s, f)
    assert _variants(klass, "slider.yaml", SLIDER, STUDENTS, "seed8", seed=8).returncode == 0
    assert (
        _tree(klass / "seed8")["s01/slider.yaml"] != first["s01/slider.yaml"]
    )  # another seed, other numbers


def test_a_class_is_graded_against_its_own_variants_a_copy_is_diagnosed_and_marks_add_up(klass: Path) -> None:
    out = klass / "class_four_bar"
    key = _key(out)
    sheets = klass / "sheets"
    sheets.mkdir()

    def sheet(of: str) -> str:
        w = key[of, "omega.rocker"]["value"]
        v = key[of, "velocity.C"]["value"]
        return f"four_bar:\n  omega.rocker: {abs(w):.6g} rad/s {'ccw' if w > 0 else 'cw'}\n  velocity.C: {v:.6g} m/s\n"

    (sheets / "s01.yaml").write_text(sheet("s01"))  # right
    (sheets / "s02.yaml").write_text(sheet("s17"))  # copied from s17
    (sheets / "s03.yaml").write_text(sheet("s03").split("  velocity")[0] + "\n")  # ω only: 2 of 5 marks
    p = mech(
        "check", str(out), "--answers", str(sheets), "--gradebook", str(klass / "g.csv"), "--json", "-j", "1"
    )
    assert p.returncode == 1
    report = json.loads(p.stdout)
    rows = {(r["student"], a["key"]): a for r in report["results"] if r["student"] for a in r["answers"]}
    assert rows["s01", "omega.rocker"]["status"] == "pass" and rows["s01", "velocity.C"]["status"] == "pass"
    for k in ("omega.rocker", "velocity.C"):
        assert rows["s02", k]["status"] == "fail"
        assert rows["s02", k]["diagnosis"] == "the variant of s17", rows["s02", k]
    book = list(csv.reader(io.StringIO((klass / "g.csv").read_text(encoding="utf-8"))))
    assert book[0] == ["student", "four_bar.yaml", "total", "out_of", "percent"]
    got = {r[0]: r[1:] for r in book[1:]}
    # every student the class was made for has a line: one who handed in no sheet answered nothing
    nothing = {s: ["0", "0", "5", "0.0"] for s in STUDENTS if s not in ("s01", "s02", "s03")}
    assert got == {
        "s01": ["5", "5", "5", "100.0"],
        "s02": ["0", "0", "5", "0.0"],
        "s03": ["2", "2", "5", "40.0"],
        **nothing,
    }
    assert rows["s04", "omega.rocker"]["status"] == "fail"
    assert rows["s04", "omega.rocker"]["message"] == "not answered: no sheet was handed in"


def test_a_sheet_of_a_student_the_class_was_not_made_for_is_graded_for_no_one(tmp_path: Path) -> None:
    # "zed" is on no roster: their sheet names the class's problem, which is only others' variants.
    # It is an error row, shown apart; zed has no gradebook line (not a 0 out of 0 at 0 %).
    klass, roster = tmp_path, STUDENTS[:3]
    assert _variants(klass, "four_bar.yaml", FOUR_BAR, roster, "class_four_bar").returncode == 0
    sheets = klass / "outsider"
    sheets.mkdir()
    (sheets / "s01.yaml").write_text("four_bar: {}\n")
    (sheets / "zed.yaml").write_text("four_bar:\n  omega.rocker: 1 rad/s cw\n")
    out = klass / "class_four_bar"
    g2 = klass / "g2.csv"
    p = mech("check", str(out), "--answers", str(sheets), "--gradebook", str(g2), "--json", "-j", "1")
    assert p.returncode == 1
    book = list(csv.reader(io.StringIO(g2.read_text(encoding="utf-8"))))
    assert [r[0] for r in book[1:]] == sorted(roster)
    report = json.loads(p.stdout)
    assert "zed" not in [s["student"] for s in report["students"]]
    (zed,) = [r for r in report["results"] if r["student"] == "zed"]
    assert [a["status"] for a in zed["answers"]] == ["error"]
    # zed's sheet alone: the same row, shown apart (no student of the class answered)
    alone = mech("check", str(out), "--answers", str(sheets / "zed.yaml"), "-j", "1")
    assert alone.returncode == 1 and "sheets scored for no one" in alone.stdout, alone.stdout
    assert "none of them is zed's" in alone.stdout
    # beside a problem the class shares (one outside the class folder), zed is still scored for no one
    shared = klass / "shared"
    shared.mkdir()
    (shared / "count.yaml").write_text(
        "links: [frame, a, b, c]\njoints:\n  A: {type: revolute, links: [frame, a]}\n"
        "  B: {type: revolute, links: [a, b]}\n  C: {type: revolute, links: [b, c]}\n"
        "  D: {type: revolute, links: [c, frame]}\nasks: [dof]\n"
    )
    (sheets / "zed.yaml").write_text("four_bar:\n  omega.rocker: 1 rad/s cw\ncount:\n  dof: 1\n")
    both = json.loads(
        mech("check", str(out), str(shared), "--answers", str(sheets), "--json", "-j", "1").stdout
    )
    assert "zed" not in [s["student"] for s in both["students"]]
    assert sorted(s["student"] for s in both["students"]) == sorted(roster)


def test_fewer_distinct_variants_than_students_is_said(tmp_path: Path) -> None:
    text = SLIDER.replace(
        "  lengths.AB: {from: 100, to: 160, step: 2}\n  drive.angle: {from: 10, to: 170, step: 1}\n", ""
    ).replace("{from: 20, to: 40, step: 1}", "[20, 30]")
    p = _variants(tmp_path, "slider.yaml", text, STUDENTS[:5], "few")
    assert p.returncode == 0 and "only 2 distinct variants for 5 students" in p.stderr


@pytest.mark.parametrize(
    ("vary", "words"),
    [
        ("vary: {lengths.XY: [1, 2]}\n", "vary: lengths.XY names no value of this file"),
        ("vary: {lengths.OA: {from: 40, to: 20}}\n", "from ≤ to"),
    ],
)
def test_a_wrong_vary_is_a_located_input_error(tmp_path: Path, vary: str, words: str) -> None:
    text = SLIDER.split("vary:")[0] + vary
    p = _variants(tmp_path, "slider.yaml", text, STUDENTS[:2], "bad")
    assert (
        p.returncode == 2 and words in p.stderr and "slider.yaml:" in p.stderr and "Traceback" not in p.stderr
    )


@pytest.mark.parametrize(
    ("keep", "words"),
    [
        ("{at_lest: 35 deg}", "bounds are at_least and at_most, not at_lest"),
        ("{at_least: banana}", "at_least: 'banana' is not a number with a unit"),
        ("{at_least: 35 mm}", "at_least: 35 mm measures m, not rad"),
        ("{}", "bounds are at_least and at_most"),
    ],
)
def test_a_keep_bound_that_cannot_be_held_is_a_located_input_error(
    tmp_path: Path, keep: str, words: str
) -> None:
    # DESIGN § 1.3: "each variant must satisfy these": a misspelt bound would hold nothing, silently
    text = FOUR_BAR.replace("{at_least: 35 deg}", keep)
    p = _variants(tmp_path, "four_bar.yaml", text, STUDENTS[:2], "bad")
    assert p.returncode == 2, p.stderr
    assert f"keep: transmission_angle.min: {words}" in p.stderr and "four_bar.yaml:" in p.stderr
    assert "Traceback" not in p.stderr and not (tmp_path / "bad").exists()


@pytest.mark.parametrize(
    ("roster", "words"),
    [
        ("name\nann\n", "has no `student` column"),
        ("student\ns01\ns02\ns01\n", "student s01 is listed twice (first on line 2)"),
        ("student\n../up\n", "cannot name a folder"),
    ],
)
def test_a_bad_roster_is_a_located_input_error(tmp_path: Path, roster: str, words: str) -> None:
    (tmp_path / "slider.yaml").write_text(SLIDER, encoding="utf-8")
    (tmp_path / "roster.csv").write_text(roster, encoding="utf-8")
    p = mech(
        "variants",
        str(tmp_path / "slider.yaml"),
        "--roster",
        str(tmp_path / "roster.csv"),
        "-o",
        str(tmp_path / "c"),
    )
    assert (
        p.returncode == 2 and words in p.stderr and "roster.csv" in p.stderr and not (tmp_path / "c").exists()
    )


# A load at the pin B of rod and piston, written as DESIGN § 1.4 spells it (`on: piston`), on a
# chain whose ground is named `no`: YAML 1.1 reads both `on` and `no` as booleans; mech reads them
# as text, and so must every variant.  Statics of the in-line slider crank with the force P along
# the line of stroke on the piston: the rod is a two-force member, so the pin B carries
# |P| / cos φ, sin φ = r sin θ / L (Hibbeler, *Engineering Mechanics: Statics*, § 6.6).
NAMES_AS_TEXT = """\
name: Slider crank, a load on the piston at its pin
units: {length: mm, angle: deg}
ground: "no"
links: ["no", crank, rod, piston]
joints:
  O: {type: revolute, links: ["no", crank], at: [0, 0]}
  A: {type: revolute, links: [crank, rod]}
  B: {type: revolute, links: [rod, piston], near: [150, 0]}
  P: {type: prismatic, links: [piston, "no"], path: {through: [0, 0], angle: 0}}
lengths: {OA: 30, AB: 120}
drive: {link: crank, angle: 45, rpm: 120, direction: ccw}
loads:
  B: {force: [-1000, 0], on: piston}
vary:
  lengths.OA: [20, 25, 30]
  drive.angle: {from: 10, to: 80, step: 10}
asks: [force.B]
"""


def test_keys_and_names_yaml_1_1_reads_as_booleans_stay_text_in_every_variant(tmp_path: Path) -> None:
    p = _variants(tmp_path, "pin.yaml", NAMES_AS_TEXT.replace('"no"', "no"), STUDENTS[:4], "c")
    assert p.returncode == 0, p.stderr
    key = _key(tmp_path / "c")
    for s in STUDENTS[:4]:
        text = (tmp_path / "c" / s / "pin.yaml").read_text(encoding="utf-8")
        data = yaml.safe_load(text)
        assert data["ground"] == "no" and data["loads"]["B"] == {"force": [-1000, 0], "on": "piston"}
        r, rod, th = data["lengths"]["OA"], data["lengths"]["AB"], math.radians(data["drive"]["angle"])
        cos_phi = math.sqrt(1 - (r * math.sin(th) / rod) ** 2)
        assert key[s, "force.B"]["value"] == pytest.approx(1000 / cos_phi, rel=1e-9)


def _failed(claimed: str, computed: float, diagnosis: str | None, miss: float | None):
    from mech.check.verdicts import FAIL, Verdict

    return Verdict(
        "omega.rocker",
        FAIL,
        claimed=claimed,
        computed=computed,
        unit="rad/s",
        allowed=0.02 * abs(computed),
        tolerance="2%",
        diagnosis=diagnosis,
        diagnosis_miss=miss,
    )


def test_a_copy_matched_more_closely_than_the_diagnosed_mistake_is_named_a_copy():
    from mech.check.classes import copied
    from mech.check.verdicts import FileResult

    # s02's own ω is 0.7374 rad/s; 6.97482 rad/s is s17's right answer, copied to the digit, and also
    # within 0.95 % of s02's value read in rpm as rad/s (0.7374 × 60/2π = 7.0416): a unit slip
    slip = 0.7374 * 60 / (2 * math.pi)
    miss = abs(6.97482 - slip) / slip
    copy = _failed("6.97482 rad/s", 0.7374, "a unit slip (the value in rpm, given as rad/s)", miss)
    # s03 slipped honestly (the slip to the digit); s17's value lies 0.95 % away from it by chance
    honest = _failed(f"{slip:.6g} rad/s", 0.7374, "a unit slip (the value in rpm, given as rad/s)", 1e-7)
    table = {("p.yaml", "omega.rocker"): [("s02", 0.7374), ("s03", 0.7374), ("s17", 6.97482)]}
    rows = [
        FileResult("class/s02/p.yaml", student="s02", verdicts=(copy,)),
        FileResult("class/s03/p.yaml", student="s03", verdicts=(honest,)),
    ]
    out = copied(rows, table)
    assert out[0].verdicts[0].diagnosis == "the variant of s17"
    assert out[1].verdicts[0].diagnosis == "a unit slip (the value in rpm, given as rad/s)"


def test_a_point_drawn_on_a_coupler_keeps_its_place_on_the_link_in_every_variant(tmp_path):
    # the teacher draws E at the middle of BC (crank 40 mm at 60°: B and C by the vector loop);
    # each student's BC differs, and E must stay the middle of that student's B and C
    ab, theta = 40 * MM, math.radians(60)
    b = ab * np.array([math.cos(theta), math.sin(theta)])
    c = _coupler_pin(ab, 150 * MM, theta)
    e = (b + c) / 2 / MM
    text = FOUR_BAR.replace(
        "lengths: {AB: 40, BC: 150, CD: 80}",
        f"lengths: {{AB: 40, BC: 150, CD: 80}}\npoints:\n  E: {{link: coupler, at: [{e[0]:.10g}, {e[1]:.10g}]}}",
    ).replace(
        "  lengths.AB: {from: 30, to: 60, step: 0.5}\n", "  lengths.BC: {from: 140, to: 160, step: 1}\n"
    )
    done = _variants(tmp_path, "fb.yaml", text, STUDENTS[:8], "class")
    assert done.returncode == 0, done.stderr
    for s in STUDENTS[:8]:
        data = yaml.safe_load((tmp_path / "class" / s / "fb.yaml").read_text(encoding="utf-8"))
        bc, th = data["lengths"]["BC"] * MM, math.radians(data["drive"]["angle"])
        b_s = ab * np.array([math.cos(th), math.sin(th)])
        c_s = _coupler_pin(ab, bc, th)
        assert np.allclose(np.array(data["points"]["E"]["at"]) * MM, (b_s + c_s) / 2, rtol=0, atol=1e-9)


def _coupler_pin(ab: float, bc: float, theta: float) -> np.ndarray:
    """C of the four-bar (CD 80 mm, AD 150 mm) by the circles about B and D, on the side of (160, 80) mm."""
    cd, ad = 80 * MM, 150 * MM
    b = ab * np.array([math.cos(theta), math.sin(theta)])
    d = np.array([ad, 0.0])
    dist = float(np.hypot(*(d - b)))
    x = (bc**2 - cd**2 + dist**2) / (2 * dist)
    h = math.sqrt(bc**2 - x**2)
    ex = (d - b) / dist
    ey = np.array([-ex[1], ex[0]])
    hint = np.array([160 * MM, 80 * MM])
    return min((b + x * ex + h * ey, b + x * ex - h * ey), key=lambda p: float(np.hypot(*(p - hint))))
