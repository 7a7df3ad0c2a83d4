"""``mech check``: verdicts, tolerances, batches, answer sheets, report formats, exit codes.

Reference values come from closed forms worked here, never from the code under
test.  The main fixture is an in-line slider crank with the crank at 90°:

* crank OA = r = 0.1 m, rod AB = l = 0.3 m, ω = 10 rad/s ccw; A = (0, r),
  B = (√(l² − r²), 0) on the x axis.
* v_A = ω × OA = (−ω r, 0): 1.0 m/s.  B moves along x, and A's velocity is
  along x too, so the rod translates: ω_rod = 0 and v_B = v_A, |v_B| = 1.0 m/s;
  the sliding speed at the piston's joint is 1.0 m/s.
* Every point of the translating rod moves at 1.0 m/s: least_speed.rod = 1.0.
  The crank turns about O, which lies on its line: least_speed.crank = 0.
* I-centre frame–rod: on the line OA (x = 0) and on the normal to the path at
  B (x = x_B): parallel lines, so it is at infinity.
* Kutzbach: l = 4, j = 4 (3 revolute + 1 prismatic), h = 0 → n = 1; every link takes
  two joints (the piston B and P, the frame O and P): four binary links.
"""

from __future__ import annotations

import io
import itertools
import json
import math
import subprocess
import sys
import textwrap
from pathlib import Path
from xml.etree import ElementTree as ET

import pytest

from cli_runner import assert_bad_input, mech
from mech.batch import CheckOptions, Report, run
from mech.check import ERROR, FAIL, PASS, check, check_file
from mech.loader import loads
from mechanism_texts import slider_crank

R, L, W = 0.1, 0.3, 10.0
XB = math.sqrt(L * L - R * R)

SLIDER = """\
name: {name}
units: {{length: m, angle: deg}}
links: [frame, crank, rod, piston]
joints:
  O: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  A: {{type: revolute, links: [crank, rod]}}
  B: {{type: revolute, links: [rod, piston], near: [0.3, 0]}}
  P: {{type: prismatic, links: [piston, frame], path: {{through: [0, 0], angle: 0}}}}
lengths: {{OA: 0.1, AB: 0.3}}
drive: {{link: crank, angle: 90, omega: 10, direction: ccw}}
"""

DOF_ONLY = """\
name: {name}
links: [frame, crank, coupler, rocker]
joints:
  A: {{type: revolute, links: [frame, crank]}}
  B: {{type: revolute, links: [crank, coupler]}}
  C: {{type: revolute, links: [coupler, rocker]}}
  D: {{type: revolute, links: [rocker, frame]}}
"""


def problem(answers: str, *, name: str = "slider crank at 90 deg", body: str = SLIDER) -> str:
    """A problem file: the mechanism plus an ``answers`` block (YAML lines, unindented)."""
    return body.format(name=name) + "answers:\n" + textwrap.indent(textwrap.dedent(answers), "  ")


def verdicts(text: str) -> dict[str, tuple[str, str]]:
    return {v.key: (v.status, v.message) for v in check(loads(text))}


# -- single verdicts ----------------------------------------------------------------------------
def test_right_answers_pass() -> None:
    got = verdicts(
        problem(
            """\
            dof: 1
            links.count: 4
            links.binary: 4
            links.singular: 0
            joints.count: 4
            joints.equivalent_binary: 4
            higher_pairs: 0
            icentres.count: 6
            chain: slider crank
            velocity.A: 1.0 m/s
            velocity.B: 1000 mm/s
            velocity.B.A: 0
            omega.crank: 10 rad/s ccw
            omega.rod: 0 rad/s
            sliding.P: 1.0
            least_speed.rod: 1.0 m/s
            least_speed.crank: 0
            icentre.frame.rod: infinity
            distance.O.B: 0.28284 m
            """
        )
    )
    assert {k: s for k, (s, _) in got.items()} == dict.fromkeys(got, PASS), got


def test_wrong_answers_fail_with_the_computed_value() -> None:
    got = verdicts(
        problem(
            """\
            dof: 2
            chain: four-bar
            velocity.B: 1.1 m/s
            omega.crank: 10 rad/s cw
            icentre.frame.rod: [0.1, 0.2]
            """
        )
    )
    assert all(s == FAIL for s, _ in got.values()), got
    assert got["dof"][1] == "dof is 1, not 2"
    assert "slider-crank" in got["chain"][1]
    assert "1 m/s" in got["velocity.B"][1] and "off by 10.0%" in got["velocity.B"][1]
    assert "wrong sense" in got["omega.crank"][1]
    assert "at infinity" in got["icentre.frame.rod"][1]


def test_a_point_claimed_where_the_icentre_is_finite_and_infinity_claimed_for_a_point() -> None:
    # I-centre frame-crank is the pin O = (0, 0); crank-rod is the pin A = (0, r)
    got = verdicts(
        problem(
            """\
            icentre.frame.crank: infinity
            icentre.crank.rod: ["0 mm", "100 mm"]
            """
        )
    )
    assert got["icentre.frame.crank"][0] == FAIL and "not at infinity" in got["icentre.frame.crank"][1]
    assert got["icentre.crank.rod"][0] == PASS


def test_a_bare_length_in_mm_gets_a_hint() -> None:
    status, message = verdicts(problem("distance.O.A: 100\n"))["distance.O.A"]
    assert status == FAIL and "looks like mm" in message


def test_sense_is_checked_only_when_claimed() -> None:
    got = verdicts(problem("omega.crank: 10\nalpha.crank: 0\n"))
    assert got["omega.crank"][0] == PASS
    got = verdicts(problem("omega.crank: 10 rad/s ccw\n"))
    assert got["omega.crank"][0] == PASS


@pytest.mark.parametrize(
    ("claimed", "tolerance", "status"),
    [
        (1.019, None, PASS),  # 1.9% of the computed 1.0 m/s, default 2%
        (1.021, None, FAIL),
        (0.981, None, PASS),
        (1.04, "5%", PASS),
        (1.06, "5%", FAIL),
        (1.04, "0.05 m/s", PASS),
        (1.06, "0.05 m/s", FAIL),
    ],
)
def test_tolerance_is_relative_to_the_computed_value_or_absolute(
    claimed: float, tolerance: str | None, status: str
) -> None:
    value = f"{{value: {claimed} m/s, tolerance: {tolerance}}}" if tolerance else f"{claimed} m/s"
    assert verdicts(problem(f"velocity.A: {value}\n"))["velocity.A"][0] == status


def test_file_tolerance_applies_to_every_answer() -> None:
    got = verdicts(problem("tolerance: 10%\nvelocity.A: 1.08\nvelocity.B: 1.12\n"))
    assert got["velocity.A"][0] == PASS and got["velocity.B"][0] == FAIL


def test_icentre_tolerance_is_a_fraction_of_the_size() -> None:
    # size = largest joint distance = |OB| = 0.2828 m; 2% of it is 5.7 mm; I(crank, rod) = A = (0, 0.1)
    got = verdicts(problem('icentre.crank.rod: [0.004, 0.1]\nicentre.frame.crank: ["8 mm", 0]\n'))
    assert got["icentre.crank.rod"][0] == PASS
    assert got["icentre.frame.crank"][0] == FAIL


def test_omega_ratio_of_a_link_at_rest_is_an_error() -> None:
    status, message = verdicts(problem("omega_ratio.crank.rod: 1\n"))["omega_ratio.crank.rod"]
    assert status == ERROR and "zero" in message


def test_a_quantity_that_cannot_be_computed_is_an_error_with_the_reason() -> None:
    # no drive speed: velocities cannot be had, counts still can
    text = problem("dof: 1\nvelocity.A: 1\n").replace(", omega: 10, direction: ccw", "")
    got = verdicts(text)
    assert got["dof"][0] == PASS
    assert got["velocity.A"][0] == ERROR and got["velocity.A"][1].startswith("cannot be computed")


def test_least_speed_matches_a_brute_force_search_along_the_line() -> None:
    """A turning coupler: sample the line densely with v = v_O + ω × r, no closed form used."""
    from mech import load
    from mech.grading.keys import least_speed
    from mech.kinematics import solve

    root = Path(__file__).resolve().parent.parent
    mech = load(root / "mechanisms" / "four_bar.yaml")
    kin = solve(mech, level="velocity")
    state = kin.links["coupler"]
    b, c = kin.positions["B"], kin.positions["C"]
    speeds = []
    for i in range(-40001, 40002):
        s = i / 4000.0  # from −10 to +10 link lengths
        p = (b[0] + s * (c[0] - b[0]), b[1] + s * (c[1] - b[1]))
        speeds.append(math.hypot(*state.velocity_at(p)))
    assert least_speed(mech, kin, "coupler") == pytest.approx(min(speeds), rel=1e-6, abs=1e-9)


# -- files and batches -------------------------------------------------------------------------
def test_a_malformed_file_is_one_error_row(tmp_path: Path) -> None:
    bad_yaml = tmp_path / "bad.yaml"
    bad_yaml.write_text("links: [frame, crank\n")
    unknown_key = tmp_path / "key.yaml"
    unknown_key.write_text(problem("omega.rodd: 1\nvelocity.Q: 2\n"))
    wrong_unit = tmp_path / "unit.yaml"
    wrong_unit.write_text(problem("omega.rod: 4 m/s\n"))
    for path in (bad_yaml, unknown_key, wrong_unit):
        result = check_file(str(path))
        assert [v.status for v in result.verdicts] == [ERROR], result
        assert result.verdicts[0].key == "file"
    assert len(check_file(str(unknown_key)).problems) == 2  # both problems kept for JSON


def make_homework(folder: Path, n: int, corrupt: int | None = None) -> dict[str, dict[str, str]]:
    """n problem files with right, wrong and uncomputable answers; the expected verdicts by file."""
    folder.mkdir(parents=True, exist_ok=True)
    expected: dict[str, dict[str, str]] = {}
    for i in range(n):
        path = folder / f"p{i:03d}.yaml"
        if i == corrupt:
            path.write_text("links: [frame\njoints: {\n")
            expected[str(path)] = {"file": ERROR}
        elif i % 3 == 0:
            path.write_text(problem("dof: 1\njoints.count: 5\n", body=DOF_ONLY, name=f"dof {i}"))
            expected[str(path)] = {"dof": PASS, "joints.count": FAIL}
        elif i % 3 == 1:
            path.write_text(problem("velocity.B: 1.0 m/s\nomega.rod: 1 rad/s\n", name=f"slider {i}"))
            expected[str(path)] = {"velocity.B": PASS, "omega.rod": FAIL}
        else:
            path.write_text(problem("icentres.count: 6\nvelocity.A: 1\n", body=DOF_ONLY, name=f"dof {i}"))
            expected[str(path)] = {"icentres.count": PASS, "velocity.A": ERROR}
    return expected


def observed(report: Report) -> dict[str, dict[str, str]]:
    return {r.path: {v.key: v.status for v in r.verdicts} for r in report.results}


def test_a_homework_set_gives_exactly_the_expected_verdicts(tmp_path: Path) -> None:
    expected = make_homework(tmp_path / "hw", 12, corrupt=5)
    report = run(CheckOptions((str(tmp_path / "hw"),), jobs=1))
    assert observed(report) == expected
    # 4 + 4 + 3 passes; 4 + 4 fails; 3 uncomputable + 1 corrupt file
    assert (report.passed, report.failed, report.errors) == (11, 8, 4)
    assert report.exit_status == 1


def test_one_corrupt_file_in_a_hundred_leaves_99_verdicts_and_one_error_row(tmp_path: Path) -> None:
    expected = make_homework(tmp_path / "hw", 100, corrupt=42)
    report = run(CheckOptions((str(tmp_path / "hw"),), jobs=2))
    assert len(report.results) == 100
    file_rows = [r for r in report.results if r.verdicts[0].key == "file"]
    assert [r.path for r in file_rows] == [str(tmp_path / "hw" / "p042.yaml")]
    assert sum(1 for r in report.results if r.verdicts[0].key != "file") == 99
    assert observed(report) == expected


def test_two_jobs_give_the_same_report_as_one(tmp_path: Path) -> None:
    make_homework(tmp_path / "hw", 30, corrupt=7)
    one = run(CheckOptions((str(tmp_path / "hw"),), jobs=1))
    two = run(CheckOptions((str(tmp_path / "hw"),), jobs=2))
    assert one == two
    assert [r.path for r in two.results] == sorted(r.path for r in two.results)


def test_files_without_answers_are_skipped_and_counted(tmp_path: Path) -> None:
    (tmp_path / "a.yaml").write_text(DOF_ONLY.format(name="no answers"))
    (tmp_path / "b.yml").write_text(problem("dof: 1\n", body=DOF_ONLY, name="b"))
    report = run(CheckOptions((str(tmp_path),), jobs=1))
    assert report.skipped == (str(tmp_path / "a.yaml"),)
    assert report.passed == 1 and report.exit_status == 0


def test_count_only_checks_never_import_numpy(tmp_path: Path) -> None:
    make_homework(tmp_path / "hw", 3)
    for p in (tmp_path / "hw").glob("*.yaml"):
        if "velocity" in p.read_text():
            p.unlink()
    code = (
        "import sys\n"
        "from mech.batch import CheckOptions, run\n"
        "from mech.render.check import report_dict\n"
        f"r = run(CheckOptions(({str(tmp_path / 'hw')!r},), jobs=1))\n"
        "report_dict(r)\n"
        "assert r.total > 0, r\n"
        "print('numpy' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


# -- report formats ---------------------------------------------------------------------------
@pytest.fixture
def report(tmp_path: Path) -> Report:
    make_homework(tmp_path / "hw", 6, corrupt=4)
    return run(CheckOptions((str(tmp_path / "hw"),), jobs=1))


def test_junit_xml_has_the_junit_structure(report: Report) -> None:
    from mech.render.check import junit_xml

    root = ET.fromstring(junit_xml(report))
    assert root.tag == "testsuites"
    assert int(root.get("tests")) == report.total
    assert int(root.get("failures")) == report.failed and int(root.get("errors")) == report.errors
    suites = root.findall("testsuite")
    assert len(suites) == len(report.results)
    for suite, result in zip(suites, report.results, strict=True):
        assert suite.get("name") == result.path
        cases = suite.findall("testcase")
        assert int(suite.get("tests")) == len(cases) == result.total
        assert int(suite.get("failures")) == sum(len(c.findall("failure")) for c in cases) == result.failed
        assert int(suite.get("errors")) == sum(len(c.findall("error")) for c in cases) == result.errors
        for case, v in zip(cases, result.verdicts, strict=True):
            assert case.get("name") == v.key and case.get("classname")
            for child in case:
                assert child.tag in ("failure", "error") and child.get("message") and child.get("type")
    corrupt = next(s for s in suites if s.get("name").endswith("p004.yaml"))
    assert corrupt.find("testcase/error").get("type") == "FileError"


def test_gradescope_results_follow_the_autograder_spec(report: Report) -> None:
    from mech.render.check import gradescope_dict

    data = json.loads(json.dumps(gradescope_dict(report)))
    assert data["score"] == report.passed
    assert len(data["tests"]) == report.total
    for t in data["tests"]:
        assert set(t) >= {"name", "score", "max_score", "status", "output"}
        assert t["status"] in ("passed", "failed")
        assert t["max_score"] == 1.0 and t["score"] == (1.0 if t["status"] == "passed" else 0.0)
    assert sum(t["score"] for t in data["tests"]) == data["score"]


def test_json_report_counts_and_answers(report: Report) -> None:
    from mech.render.check import report_dict

    data = json.loads(json.dumps(report_dict(report)))
    assert data["summary"]["passed"] == report.passed and data["summary"]["exit_status"] == 1
    bad = next(r for r in data["results"] if r["file"].endswith("p004.yaml"))
    assert bad["answers"][0]["status"] == "error" and bad["error"]["problems"][0]["line"] >= 1


# -- the command line -------------------------------------------------------------------------
def test_cli_exit_0_when_all_pass(run, tmp_path: Path) -> None:
    (tmp_path / "a.yaml").write_text(problem("dof: 1\nvelocity.A: 1 m/s\n"))
    result = run("check", str(tmp_path))
    assert result.exit_code == 0, result.output
    assert "2 passed, 0 failed, 0 errors in 1 file" in result.output


def test_cli_exit_1_on_a_failure_or_error(run, tmp_path: Path) -> None:
    make_homework(tmp_path / "hw", 4, corrupt=3)
    result = run("check", "-j", "1", str(tmp_path / "hw"))
    assert result.exit_code == 1
    assert "failed" in result.output and "error" in result.output


@pytest.mark.parametrize(
    "args",
    [
        ("check",),
        ("check", "no/such/folder"),
        ("check", "--jobs", "0", "."),
    ],
)
def test_cli_exit_2_on_usage_errors(run, args: tuple[str, ...]) -> None:
    assert run(*args).exit_code == 2


def test_cli_exit_2_when_there_is_nothing_to_check(run, tmp_path: Path) -> None:
    (tmp_path / "a.yaml").write_text(DOF_ONLY.format(name="x"))
    result = run("check", str(tmp_path))
    assert result.exit_code == 2 and "no answers to check" in result.stderr


def test_mech_check_in_a_subprocess(tmp_path: Path) -> None:
    make_homework(tmp_path / "hw", 3)
    proc = subprocess.run(
        [sys.executable, "-m", "mech", "check", "--jobs", "2", str(tmp_path / "hw")],
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 1, proc.stderr
    assert proc.stdout.rstrip().endswith("3 passed, 2 failed, 1 error in 3 files")
    assert proc.stderr == ""  # no progress bar when stderr is not a terminal


def test_cli_quiet_lists_only_what_went_wrong(run, tmp_path: Path) -> None:
    (tmp_path / "a.yaml").write_text(problem("dof: 1\nvelocity.A: 2 m/s\n"))
    result = run("check", "-q", str(tmp_path))
    assert "velocity.A" in result.output and "dof" not in result.output.replace("dof = ", "")
    assert "1 passed, 1 failed" in result.output


def test_progress_bar_only_on_a_terminal_for_large_sets() -> None:
    from rich.console import Console

    from mech.render.check import progress

    for terminal, total, shown in ((True, 50, True), (True, 5, False), (False, 50, False)):
        buffer = io.StringIO()
        console = Console(file=buffer, force_terminal=terminal, width=80)
        with progress(console) as (start, advance):
            start(total)
            for _ in range(total):
                advance(None)
        assert bool(buffer.getvalue()) is shown, (terminal, total)


def test_terminal_table_has_one_row_per_file_and_every_answer_with_verbose(report: Report) -> None:
    from rich.console import Console

    from mech.render.check import check_table

    def shown(verbose: bool) -> str:
        buffer = io.StringIO()
        console = Console(file=buffer, force_terminal=True, width=200, color_system=None, markup=False)
        check_table(report, console, verbose=verbose)
        return buffer.getvalue()

    short, long = shown(False), shown(True)
    for r in report.results:
        assert sum(Path(r.path).name in ln for ln in short.splitlines()) == 1
    assert "dof = 1" not in short and "dof = 1" in long  # a passing answer: shown only with verbose


# -- through the command line as a user runs it (cli_runner: tracebacks shown) -----------
EXAMPLE_FOUR_BAR = Path(__file__).resolve().parent.parent / "mechanisms" / "four_bar.yaml"


@pytest.mark.parametrize(
    "answer, line_col",
    [
        ("omega.rocker: 4.8 m/s", "26:17"),
        ("velocity.C: 0.385 rad/s", "26:15"),
        ("velocity.C: 0.385 m/s cw", "26:15"),
        ("tolerance: -5%", "26:14"),
        ("tolerance: abc%", "26:14"),
        ("omega.rockr: 4.8", "26:3"),
        ("dof: 1.0", "26:8"),
        ("omega.rocker: .nan", "26:17"),
    ],
)
def test_a_bad_answer_is_one_error_row_located_at_its_value(tmp_path, answer, line_col):
    """Wrong unit, a sense on a speed, a bad tolerance, an unknown key, 1.0 for dof, NaN."""
    text = EXAMPLE_FOUR_BAR.read_text(encoding="utf-8").split("answers:")[0]
    assert text.count("\n") == 24  # the answer lands on line 26
    f = tmp_path / "a.yaml"
    f.write_text(text + "answers:\n  " + answer + "\n", encoding="utf-8")
    p = mech("check", str(f), "-j", "1")
    assert p.returncode == 1 and "Traceback" not in p.stderr
    assert line_col in p.stdout


def test_a_wrong_sense_fails_and_a_bare_mm_number_gets_a_hint(tmp_path):
    text = EXAMPLE_FOUR_BAR.read_text(encoding="utf-8").split("answers:")[0]
    f = tmp_path / "a.yaml"
    f.write_text(text + 'answers:\n  omega.rocker: 4.785 rad/s ccw\n  velocity.C: "383"\n', encoding="utf-8")
    p = mech("check", str(f), "-j", "1", "-v")
    assert p.returncode == 1
    assert "wrong sense" in p.stdout and "mm" in p.stdout


def test_an_icentre_of_a_link_with_itself_is_a_located_input_error(write):
    """`icentre.crank.crank` once passed the loader and made check report "internal error"."""
    f = write(slider_crank(extra="answers:\n  icentre.crank.crank: [0, 0]\n"))
    assert_bad_input(mech("dof", str(f)), f)
    c = mech("check", str(f), "-j", "1")
    assert c.returncode == 1
    assert "internal error" not in c.stdout


@pytest.mark.parametrize(
    "answer, words",
    [
        # 5,000 digits: Python refuses to read more than 4,300 (issue 25: an internal error, exit 70)
        ("dof: " + "9" * 5000, "5,000 digits"),
        ("dof: -" + "9" * 5000, "5,000 digits"),
        # a float beyond 1.8e308 is read as infinity: the message says so, not "must be a number"
        ("velocity.C: " + "9" * 5000 + " m/s", "too large"),
        ("position.C: [" + "9" * 5000 + ", 0]", "too large"),
    ],
)
def test_an_answer_of_5000_digits_is_a_located_input_error(write, answer, words):
    text = EXAMPLE_FOUR_BAR.read_text(encoding="utf-8").split("answers:")[0]
    f = write(text + "answers:\n  " + answer + "\n")
    assert_bad_input(mech("dof", str(f)), f)
    c = mech("check", str(f), "-j", "1")
    assert c.returncode == 1 and "Traceback" not in c.stderr
    assert "internal error" not in c.stdout and words in c.stdout
    assert "26:" in c.stdout  # located at the answer (line 26)


def test_a_count_claim_of_4000_digits_is_read_and_fails(write):
    # within Python's limit a long whole number is a (wrong) count like any other: dof is 1
    text = EXAMPLE_FOUR_BAR.read_text(encoding="utf-8").split("answers:")[0]
    (v,) = check(loads(text + "answers:\n  dof: " + "9" * 4000 + "\n"))
    assert v.status == FAIL and v.computed == 1 and v.message.startswith("dof is 1, not 999")


# A wheel rolling on the ground, the contact given only as the instant's point (no profile, so no
# curvature: its accelerations cannot be had, its velocities can).  The axle B is the piston of an
# in-line slider crank (crank a = 20 mm, rod l = 80 mm, θ = 60°, ω = 120 rpm ccw):
# x_B = a cos θ + √(l² − a² sin² θ); v_B = −a ω sin θ (1 + a cos θ / √(l² − a² sin² θ)).
_A, _L, _TH, _W = 0.020, 0.080, math.radians(60), 120 * 2 * math.pi / 60
_ROOT = math.sqrt(_L**2 - (_A * math.sin(_TH)) ** 2)
_XB = _A * math.cos(_TH) + _ROOT
_VB = abs(-_A * _W * math.sin(_TH) * (1 + _A * math.cos(_TH) / _ROOT))
ROLLING_AT_AN_INSTANT = f"""\
units: {{length: mm, angle: deg}}
links: [frame, crank, rod, wheel]
joints:
  O: {{type: revolute, links: [frame, crank], at: [0, 30]}}
  A: {{type: revolute, links: [crank, rod]}}
  B: {{type: revolute, links: [rod, wheel], at: [{_XB * 1000:.9f}, 30]}}
  W: {{type: rolling, links: [wheel, frame], at: [{_XB * 1000:.9f}, 0]}}
lengths: {{OA: 20, AB: 80}}
drive: {{link: crank, angle: 60, rpm: 120, direction: ccw}}
answers:
  dof: 1
  velocity.B: {_VB:.6f} m/s
  omega.wheel: {_VB / 0.030:.6f} rad/s ccw
  acceleration.B: 1.1847 m/s^2
"""


def test_an_uncomputable_acceleration_errors_only_itself_and_the_velocities_pass() -> None:
    got = {v.key: v for v in check(loads(ROLLING_AT_AN_INSTANT))}
    assert got["acceleration.B"].status == ERROR and "curvature" in got["acceleration.B"].message
    # ω_wheel = v_B / r rolling without slip (r = 30 mm), turning ccw as the axle moves left
    assert [got[k].status for k in ("dof", "velocity.B", "omega.wheel")] == [PASS, PASS, PASS]


@pytest.mark.parametrize(
    ("key", "si", "unit"),
    [
        ("velocity.B", _VB, "mm/s"),  # the axle's speed, worked above
        ("distance.O.B", math.hypot(_XB, 0.0), "mm"),  # O and B on one horizontal line
    ],
)
def test_a_unit_slip_hint_names_a_unit_of_the_claims_quantity_and_following_it_passes(
    key: str, si: float, unit: str
) -> None:
    text = ROLLING_AT_AN_INSTANT.split("answers:")[0] + "answers:\n"
    bare = f"{si * 1000:g}"  # the value in mm (or mm/s), written bare: SI says metres
    (v,) = check(loads(text + f"  {key}: {bare}\n"))
    assert v.status == FAIL and f'"{bare} {unit}"' in v.message, v.message
    (followed,) = check(loads(text + f'  {key}: "{bare} {unit}"\n'))
    assert followed.status == PASS, followed.message


# -- time_ratio.<output> (DESIGN § 1.2, issue 21 item 3) -----------------------------------------
#: One crank drives two crank-rockers through a shared pin B: rocker1 (coupler 110, rocker 70 about
#: O4 100 mm right) and rocker2 (coupler 120, rocker 60 about O6 100 mm left).
TWO_ROCKERS = """
units: {length: mm, angle: deg}
ground: frame
links: [frame, crank, coupler1, rocker1, coupler2, rocker2]
joints:
  O2: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler1, coupler2]}
  C: {type: revolute, links: [coupler1, rocker1], near: [117, 68]}
  O4: {type: revolute, links: [rocker1, frame], at: [100, 0]}
  E: {type: revolute, links: [coupler2, rocker2], near: [-80, 60]}
  O6: {type: revolute, links: [rocker2, frame], at: [-100, 0]}
lengths: {O2B: 30, BC: 110, O4C: 70, BE: 120, O6E: 60}
drive: {link: crank, angle: 60, rpm: 100, direction: ccw}
"""


def test_time_ratio_of_each_output_is_its_own_and_bare_time_ratio_names_the_candidates() -> None:
    # Each rocker's ratio (180 + α)/(180 − α), α from its loop's limit positions by the law of
    # cosines (oracles.four_bar; the mirror image of a loop has the same ratio).  Two outputs with
    # different ratios: the bare key is refused with both named, never one picked silently.
    sys.path.insert(0, str(Path(__file__).parent))
    from oracles.four_bar import crank_rocker_limits

    r1 = crank_rocker_limits(30.0, 110.0, 70.0, 100.0)[2]
    r2 = crank_rocker_limits(30.0, 120.0, 60.0, 100.0)[2]
    claims = f"answers:\n  time_ratio.rocker1: {r1!r}\n  time_ratio.rocker2: {r2!r}\n  time_ratio: {r1!r}\n"
    one, two, bare = check(loads(TWO_ROCKERS + claims))
    assert (one.status, two.status) == (PASS, PASS)
    assert one.computed == pytest.approx(r1, rel=1e-10) and two.computed == pytest.approx(r2, rel=1e-10)
    assert bare.status == ERROR and "rocker1" in bare.message and "rocker2" in bare.message


def test_bare_time_ratio_is_refused_when_several_outputs_share_one_ratio() -> None:
    # Khurmi Ex. 5.1's shaper: the return stroke takes the crank angle 2·acos(120/240) = 120°, the
    # cutting stroke 240°, for the slotted lever and the ram it drives alike: ratio 2 for both.
    # DESIGN § 1.2 refuses the bare key with the candidates named: which stroke is for the file to say.
    text = (Path(__file__).parents[1] / "mechanisms" / "crank_slotted_lever_quick_return.yaml").read_text(
        encoding="utf-8"
    )
    ratio = (360 - 2 * math.degrees(math.acos(120 / 240))) / (2 * math.degrees(math.acos(120 / 240)))
    text = (
        text[: text.index("answers:")]
        + f"answers:\n  time_ratio.lever: {ratio!r}\n  time_ratio.ram: {ratio!r}\n  time_ratio: {ratio!r}\n"
    )
    lever, ram, bare = check(loads(text))
    assert (lever.status, ram.status) == (PASS, PASS)
    assert lever.computed == pytest.approx(2.0, rel=1e-9) and ram.computed == pytest.approx(2.0, rel=1e-9)
    assert bare.status == ERROR and "lever 2" in bare.message and "stroke 2" in bare.message, (
        bare.message
    )  # the ram by its joint


def test_time_ratio_of_a_slider_by_its_joint_or_link_and_a_refusal_that_says_why() -> None:
    # Offset slider crank r = 50, l = 200, e = 20 mm: dead centres at ψ = asin(e/(l + r)) and
    # π + asin(e/(l − r)); ratio (π + β)/(π − β) with β the difference less π.  The slider is named
    # by its joint (guide) or its link (slider); the crank is the driven link.  The rod swings
    # between its limit angles where its ω = r ω₂ cos θ / (l cos φ) is 0, at θ = 90° and 270°: two
    # half turns, a ratio of exactly 1 (DESIGN § 1.2: any link with two limit positions).
    sys.path.insert(0, str(Path(__file__).parent))
    from oracles.slider_crank import slider_dead_centres

    outer, inner, _x1, _x2 = slider_dead_centres(50.0, 200.0, 20.0)
    beta = inner - outer - math.pi
    ratio = (math.pi + beta) / (math.pi - beta)
    text = (Path(__file__).parents[1] / "mechanisms" / "offset_slider_crank.yaml").read_text(encoding="utf-8")
    text = text[: text.index("answers:")]
    claims = f"answers:\n  time_ratio.guide: {ratio!r}\n  time_ratio.slider: {ratio!r}\n  time_ratio.crank: 1\n  time_ratio.rod: 1\n"
    guide, slider, crank, rod = check(loads(text + claims))
    assert (guide.status, slider.status) == (PASS, PASS)
    assert guide.computed == pytest.approx(ratio, rel=1e-10)
    assert crank.status == ERROR and "driven link" in crank.message
    assert rod.status == PASS and rod.computed == pytest.approx(1.0, rel=1e-9)


def test_time_ratio_of_a_coupler_is_between_its_limit_angles_where_crank_and_rocker_are_parallel() -> None:
    # The coupler BC of four_bar.yaml (AB 40, BC 150, CD 80, AD 150 mm) stops turning where
    # v_B = v_C, both perpendicular to their links: AB ∥ DC.  The crank angles of those two
    # positions, found here by mpmath on the loop's closed form (C on the side of (160, 80)),
    # split the turn into the slow and the fast stroke.
    import mpmath

    def cross(theta):
        b = (40 * mpmath.cos(theta), 40 * mpmath.sin(theta))
        dx, dy = 150 - b[0], -b[1]
        dist = mpmath.sqrt(dx * dx + dy * dy)
        x = (150**2 - 80**2 + dist**2) / (2 * dist)
        h = mpmath.sqrt(150**2 - x**2)
        ex, ey = dx / dist, dy / dist
        c = (b[0] + x * ex - h * ey, b[1] + x * ey + h * ex)  # the branch above AD, as drawn
        return b[0] * c[1] - b[1] * (c[0] - 150)  # AB × DC

    grid = [2 * math.pi * k / 720 for k in range(721)]
    roots = [
        float(mpmath.findroot(cross, (a, b), solver="anderson"))
        for a, b in itertools.pairwise(grid)
        if cross(a) * cross(b) < 0
    ]
    assert len(roots) == 2
    arc = roots[1] - roots[0]
    ratio = max(arc, 2 * math.pi - arc) / min(arc, 2 * math.pi - arc)
    text = (Path(__file__).parents[1] / "mechanisms" / "four_bar.yaml").read_text(encoding="utf-8")
    (coupler,) = check(loads(text[: text.index("answers:")] + f"answers:\n  time_ratio.coupler: {ratio!r}\n"))
    assert coupler.status == PASS
    assert coupler.computed == pytest.approx(ratio, rel=1e-9)
