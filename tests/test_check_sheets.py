"""Grading a class with answer sheets: fair scores, located sheet errors, every row in every format.

The class below is built so that each student's score can be worked by hand:

* ``p1.yaml`` — the slider crank of ``tests/test_check.py`` (crank 0.1 m at 90°,
  ω = 10 rad/s ccw, rod 0.3 m): the rod translates, so |v_B| = ω r = 1.0 m/s
  and ω_rod = 0.  Its ``answers`` keys are the questions (the values in it are
  not used): velocity.B, omega.rod.
* ``p2.yaml`` — a four-bar count with ``asks: [dof, links.binary]``: Kutzbach
  gives n = 3(4 − 1) − 2·4 = 1, and every link carries two joints: 4 binary.
* ``p3.yaml`` — malformed YAML (the teacher's mistake) and ``p4.yaml`` — asks
  nothing: both are left out of every score.

So every student is asked 4 questions; a score is passed/4.
"""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path
from xml.etree import ElementTree as ET

import pytest

from cli_runner import Run, mech, no_traceback, strict_json
from mech.batch import CheckOptions, Report, run
from mech.check import ERROR, FAIL, IGNORED, PASS
from mechanism_texts import FOUR_BAR_NAME, strip_answers

SLIDER = """\
name: Slider crank
links: [frame, crank, rod, piston]
joints:
  O: {type: revolute, links: [frame, crank], at: [0, 0]}
  A: {type: revolute, links: [crank, rod]}
  B: {type: revolute, links: [rod, piston], near: [0.3, 0]}
  P: {type: prismatic, links: [piston, frame], path: {through: [0, 0], angle: 0}}
lengths: {OA: 0.1, AB: 0.3}
drive: {link: crank, angle: 90, omega: 10, direction: ccw}
answers: {velocity.B: 0, omega.rod: 5}
"""

FOUR_BAR = """\
name: Four-bar count
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker]}
  D: {type: revolute, links: [rocker, frame]}
"""

QUESTIONS = {"p1.yaml": ("velocity.B", "omega.rod"), "p2.yaml": ("dof", "links.binary")}

SHEETS = {
    # every answer right; an answer to an excluded problem is ignored, not scored
    "alice": "p1: {velocity.B: 1 m/s, omega.rod: 0}\np2: {dof: 1, links.binary: 4}\np3: {dof: 1}\n",
    # answers only the easy key
    "bob": "p2: {dof: 1}\n",
    # one bad key (a speed given for ω) and keys that are not questions
    "carol": (
        "p1:\n  velocity.B: 1 m/s\n  omega.rod: 4 m/s\n"
        "p2: {dof: 1, links.binary: 4, tolerance: 50%, chain: four-bar}\n"
    ),
    # not YAML
    "dave": "p1: [\n",
    # a wrong value, a misspelt point, a problem that does not exist
    "erin": "p1: {velocity.B: 2 m/s, velocity.Z: 1, omega.rod: 0}\np9: {dof: 1}\n",
}

# which questions each student gets right, worked from the closed forms above
RIGHT = {
    "alice": {"velocity.B", "omega.rod", "dof", "links.binary"},
    "bob": {"dof"},
    "carol": {"velocity.B", "dof", "links.binary"},
    "dave": set(),
    "erin": {"omega.rod"},
}


@pytest.fixture
def classroom(tmp_path: Path) -> Path:
    problems = tmp_path / "problems"
    problems.mkdir()
    (problems / "p1.yaml").write_text(SLIDER)
    (problems / "p2.yaml").write_text(FOUR_BAR + "asks: [dof, links.binary]\n")
    (problems / "p3.yaml").write_text("links: [frame, crank\njoints: {\n")
    (problems / "p4.yaml").write_text(FOUR_BAR.replace("Four-bar count", "No questions"))
    sheets = tmp_path / "sheets"
    sheets.mkdir()
    for student, text in SHEETS.items():
        (sheets / f"{student}.yaml").write_text(text)
    return tmp_path


def grade(classroom: Path, **kw: object) -> Report:
    return run(CheckOptions((str(classroom / "problems"),), answers=str(classroom / "sheets"), jobs=1, **kw))


def test_every_student_is_scored_passed_over_asked(classroom: Path) -> None:
    report = grade(classroom)
    asked = sum(len(q) for q in QUESTIONS.values())
    got = {s.student: (s.passed, s.asked) for s in report.scores()}
    assert got == {st: (len(right), asked) for st, right in RIGHT.items()}
    for s in report.scores():
        assert s.score == pytest.approx(len(RIGHT[s.student]) / asked)


def test_the_denominator_is_the_same_for_every_student(classroom: Path) -> None:
    scores = grade(classroom).scores()
    assert {s.asked for s in scores} == {4}
    assert {s.problems for s in scores} == {2}
    # and each row of a counted problem holds exactly one scored verdict per question
    for r in grade(classroom).results:
        if r.student is not None and not r.sheet and not r.excluded:
            name = Path(r.path).name
            assert tuple(v.key for v in r.verdicts if v.scored) == QUESTIONS[name], r


def test_broken_or_empty_problem_files_are_reported_once_and_excluded(classroom: Path) -> None:
    report = grade(classroom)
    teacher = {Path(r.path).name: r for r in report.teacher}
    assert set(teacher) == {"p3.yaml", "p4.yaml"}
    assert teacher["p3.yaml"].verdicts[0].status == ERROR
    assert teacher["p3.yaml"].problems[0].where.line == 2  # located: where the unclosed list breaks
    assert "asks nothing" in teacher["p4.yaml"].verdicts[0].message
    # no student row for an excluded problem is scored
    for r in report.results:
        if r.student is not None and Path(r.path).name in ("p3.yaml", "p4.yaml"):
            assert r.excluded and r.total == 0, r
    alice_p3 = next(r for r in report.results if r.student == "alice" and r.path.endswith("p3.yaml"))
    assert [v.status for v in alice_p3.verdicts] == [IGNORED]


def test_a_student_answering_only_the_easy_key_scores_a_quarter(classroom: Path) -> None:
    bob = {s.student: s for s in grade(classroom).scores()}["bob"]
    assert (bob.passed, bob.failed, bob.errors, bob.asked) == (1, 3, 0, 4)


def test_a_bad_key_costs_only_that_question_and_is_located(classroom: Path) -> None:
    report = grade(classroom)
    p1 = next(r for r in report.results if r.student == "carol" and r.path.endswith("p1.yaml"))
    statuses = {v.key: v.status for v in p1.verdicts}
    assert statuses == {"velocity.B": PASS, "omega.rod": ERROR}
    bad = next(v for v in p1.verdicts if v.key == "omega.rod")
    assert bad.where.path.endswith("carol.yaml") and (bad.where.line, bad.where.column) == (3, 14)
    assert "m/s" in bad.message


def test_sheet_keys_that_are_not_questions_are_ignored_and_reported(classroom: Path) -> None:
    report = grade(classroom)
    carol_p2 = next(r for r in report.results if r.student == "carol" and r.path.endswith("p2.yaml"))
    ignored = {v.key: v for v in carol_p2.verdicts if v.status == IGNORED}
    assert set(ignored) == {"tolerance", "chain"}
    assert "cannot set a tolerance" in ignored["tolerance"].message
    assert "not a question" in ignored["chain"].message
    erin_p1 = next(r for r in report.results if r.student == "erin" and r.path.endswith("p1.yaml"))
    z = next(v for v in erin_p1.verdicts if v.key == "velocity.Z")
    assert z.status == IGNORED and "unknown point 'Z'" in z.message and z.where.line == 1
    sheet_rows = [r for r in report.results if r.sheet and r.student == "erin"]
    assert [(v.key, v.status, v.where.line) for r in sheet_rows for v in r.verdicts] == [("p9", IGNORED, 2)]


def test_every_problem_in_every_sheet_is_reported_in_one_run(classroom: Path) -> None:
    report = grade(classroom)
    located = {
        (Path(v.where.path).stem, v.key)
        for r in report.results
        for v in r.verdicts
        if v.status in (ERROR, IGNORED) and v.where is not None and v.where.line
    }
    assert {
        ("carol", "omega.rod"),
        ("carol", "tolerance"),
        ("carol", "chain"),
        ("erin", "velocity.Z"),
        ("erin", "p9"),
        ("alice", "dof"),
    } <= located
    dave = next(r for r in report.results if r.sheet and r.student == "dave")
    assert dave.problems[0].where.line == 2 and dave.verdicts[0].status == ERROR


def test_an_unreadable_sheet_scores_zero_over_the_same_questions(classroom: Path) -> None:
    dave = {s.student: s for s in grade(classroom).scores()}["dave"]
    assert (dave.passed, dave.errors, dave.asked) == (0, 4, 4)


def test_the_teachers_tolerance_is_used(classroom: Path) -> None:
    (classroom / "problems" / "p1.yaml").write_text(
        SLIDER.replace("velocity.B: 0", "velocity.B: {value: 0, tolerance: 20%}")
    )
    (classroom / "sheets" / "bob.yaml").write_text("p1: {velocity.B: 1.15 m/s}\n")  # 15% off 1.0 m/s
    bob = next(r for r in grade(classroom).results if r.student == "bob" and r.path.endswith("p1.yaml"))
    assert [v.status for v in bob.verdicts] == [PASS, FAIL]  # velocity.B within 20%; omega.rod not answered


def test_a_problem_answered_twice_on_a_sheet_is_an_error_for_its_questions(classroom: Path) -> None:
    (classroom / "sheets" / "bob.yaml").write_text("p2: {dof: 1}\np2.yaml: {dof: 1}\n")
    bob = next(r for r in grade(classroom).results if r.student == "bob" and r.path.endswith("p2.yaml"))
    assert [v.status for v in bob.verdicts] == [ERROR, ERROR]
    assert "answered twice" in bob.verdicts[0].message


def test_one_key_answered_twice_in_an_entry_costs_that_question(classroom: Path) -> None:
    (classroom / "sheets" / "bob.yaml").write_text("p2:\n  dof: 1\n  links.binary: 4\n  dof: 1\n")
    bob = next(r for r in grade(classroom).results if r.student == "bob" and r.path.endswith("p2.yaml"))
    assert {v.key: v.status for v in bob.verdicts} == {"dof": ERROR, "links.binary": PASS}


# -- formats --------------------------------------------------------------------------------------
def test_csv_has_a_row_per_student_and_problem_and_says_excluded(classroom: Path) -> None:
    from mech.render.check import csv_text

    rows = list(csv.DictReader(io.StringIO(csv_text(grade(classroom)))))
    assert list(rows[0]) == ["student", "problem", "passed", "total", "score", "status", "earned", "out_of"]
    alice = {Path(r["problem"]).name: r for r in rows if r["student"] == "alice"}
    assert (alice["p1.yaml"]["passed"], alice["p1.yaml"]["total"], alice["p1.yaml"]["score"]) == (
        "2",
        "2",
        "100.0",
    )
    for name in ("p3.yaml", "p4.yaml"):
        assert alice[name]["score"] == "" and alice[name]["status"].startswith("excluded")
    teacher = [r for r in rows if r["student"] == "" and r["status"].startswith("excluded")]
    assert sorted(Path(r["problem"]).name for r in teacher) == ["p3.yaml", "p4.yaml"]
    for student in SHEETS:
        assert {Path(r["problem"]).name for r in rows if r["student"] == student} >= {
            "p1.yaml",
            "p2.yaml",
            "p3.yaml",
            "p4.yaml",
        }


def test_junit_has_a_suite_for_every_row(classroom: Path) -> None:
    from mech.render.check import junit_xml

    report = grade(classroom)
    root = ET.fromstring(junit_xml(report))
    suites = root.findall("testsuite")
    assert len(suites) == len(report.results)
    assert int(root.get("failures")) == report.failed and int(root.get("errors")) == report.errors
    excluded = [s for s in suites if s.get("name").endswith("p4.yaml") and ":" in s.get("name")]
    assert excluded and all(s.find("testcase/skipped") is not None for s in excluded)


def test_json_lists_scores_and_excluded_files(classroom: Path) -> None:
    from mech.render.check import report_dict

    data = json.loads(json.dumps(report_dict(grade(classroom))))
    assert [Path(p).name for p in data["summary"]["excluded"]] == ["p3.yaml", "p4.yaml"]
    students = {s["student"]: s for s in data["students"]}
    assert students["carol"]["score"] == pytest.approx(0.75) and students["carol"]["ignored"] == 2


def test_cli_class_lists_excluded_files_first_then_one_line_per_student(run, classroom: Path) -> None:
    result = run("check", str(classroom / "problems"), "--answers", str(classroom / "sheets"))
    assert result.exit_code == 1
    lines = result.output.splitlines()
    assert lines[0].startswith("excluded from every score")
    assert sum("p3.yaml" in ln for ln in lines) == 1  # reported once
    students = [ln for ln in lines if ln.split(" ")[0] in SHEETS]
    assert [ln.split()[:3] for ln in students] == [
        ["alice", "4/4", "100%"],
        ["bob", "1/4", "25%"],
        ["carol", "3/4", "75%"],
        ["dave", "0/4", "0%"],
        ["erin", "1/4", "25%"],
    ]


def test_cli_refuses_gradescope_for_a_class(run, classroom: Path) -> None:
    result = run(
        "check", str(classroom / "problems"), "--answers", str(classroom / "sheets"), "--gradescope", "r.json"
    )
    assert result.exit_code == 2


def test_cli_writes_every_format(run, classroom: Path, tmp_path: Path) -> None:
    out = tmp_path / "out"
    out.mkdir()
    result = run(
        "check",
        str(classroom / "problems"),
        "--answers",
        str(classroom / "sheets"),
        "--junit",
        str(out / "junit.xml"),
        "--csv",
        str(out / "grades.csv"),
        "--json",
    )
    assert result.exit_code == 1
    data = json.loads(result.stdout)
    assert [s["student"] for s in data["students"]] == sorted(SHEETS)
    assert ET.parse(out / "junit.xml").getroot().tag == "testsuites"
    assert (out / "grades.csv").read_text().startswith("student,problem,passed,total,score,status")
    assert not [p for p in out.iterdir() if p.name.startswith(".mech-")]  # no temporary file left


def test_cli_gradescope_for_one_sheet_names_tests_by_file(run, classroom: Path, tmp_path: Path) -> None:
    out = tmp_path / "results.json"
    sheet = classroom / "sheets" / "carol.yaml"
    result = run("check", str(classroom / "problems"), "--answers", str(sheet), "--gradescope", str(out))
    assert result.exit_code == 1
    data = json.loads(out.read_text())
    assert data["score"] == 3.0
    assert sum(t["max_score"] for t in data["tests"]) == 4.0  # the questions; ignored keys are worth 0
    names = [t["name"] for t in data["tests"]]
    assert any(n.startswith(str(classroom / "problems" / "p1.yaml")) for n in names)
    assert any("p4.yaml" in n for n in names)  # excluded, but a row


def test_terminal_table_lists_excluded_files_then_students(classroom: Path) -> None:
    from rich.console import Console

    from mech.render.check import check_table

    buffer = io.StringIO()
    console = Console(file=buffer, force_terminal=True, width=200, color_system=None, markup=False)
    check_table(grade(classroom), console, verbose=True)
    text = buffer.getvalue()
    assert text.index("excluded from every score") < text.index("alice")
    assert "p3.yaml" in text and "p4.yaml" in text
    alice = next(ln for ln in text.splitlines() if "alice" in ln and "%" in ln)
    assert "100%" in alice
    assert "ignored" in text  # carol's tolerance and chain keys, in the answers table


def test_a_sheet_in_another_encoding_is_one_located_error_row(tmp_path: Path) -> None:
    from mech.batch import read_sheets

    before = "p1: {velocity.B: 1 m/s}  # "
    (tmp_path / "zoe.yaml").write_bytes((before + "é\n").encode("latin-1"))
    (sheet,) = read_sheets(str(tmp_path / "zoe.yaml"))
    assert sheet.error is not None
    # read as mechanism files are: the byte that cannot be read is named (é, one byte in Latin-1)
    assert (
        sheet.error.verdicts[0].message == f"this file is not UTF-8 text (byte {len(before)} cannot be read)"
    )


def test_a_sheet_that_is_not_yaml_points_at_the_line_and_column(tmp_path: Path) -> None:
    from mech.batch import read_sheets

    (tmp_path / "zoe.yaml").write_text("p1: {dof: 1}\np2: [\n")
    (sheet,) = read_sheets(str(tmp_path / "zoe.yaml"))
    assert sheet.error is not None
    problem = sheet.error.problems[0]
    assert problem.message.startswith("this answer sheet is not valid YAML")
    assert (problem.where.line, problem.where.column) == (3, 1)  # the end of the text, where `[` is unclosed


# -- through the command line as a user runs it (cli_runner: tracebacks shown) -----------
# Problems: the shipped four-bar (Khurmi Ex. 7.1, asking dof = 1 and omega.rocker = 4.785 rad/s
# cw) and slider crank (asking dof) without their answers.  Sheets answer them by stem, file
# name or the problem's ``name:``.
def _put(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


@pytest.fixture
def problems(tmp_path: Path) -> Path:
    """problems/four_bar.yaml (questions dof, omega.rocker) and slider_crank.yaml (asks dof)."""
    d = tmp_path / "problems"
    _put(
        d / "four_bar.yaml",
        strip_answers("four_bar.yaml") + "answers:\n  dof: 1\n  omega.rocker: 4.785 rad/s cw\n",
    )
    # a problem without values lists its questions (issue 10: a problem asking nothing is excluded)
    _put(d / "slider_crank.yaml", strip_answers("slider_crank.yaml") + "asks: [dof]\n")
    return d


def check_json(*args: str) -> tuple[Run, dict]:
    p = mech("check", *args, "-j", "1", "--json")
    no_traceback(p)
    return p, strict_json(p.stdout)


def rows_of(report: dict, student: str) -> list[dict]:
    return [r for r in report["results"] if r["student"] == student]


def test_markup_in_a_students_claim_is_printed_literally(problems, tmp_path):
    """`chain: "[/b]"` once killed the class report with rich's MarkupError; `[bold red]` vanished."""
    sheet = _put(tmp_path / "s.yaml", 'four_bar: {chain: "[/b]", dof: 1}\n')
    p = mech("check", str(problems), "--answers", str(sheet), "-j", "1", "-v")
    no_traceback(p)
    assert p.returncode == 1
    assert "[/b]" in p.stdout and "failed" in p.stdout
    sheet2 = _put(tmp_path / "s2.yaml", 'four_bar: {chain: "[bold red]x[/bold red]", dof: 1}\n')
    p2 = mech("check", str(problems), "--answers", str(sheet2), "-j", "1", "-v")
    no_traceback(p2)
    assert "[bold red]x[/bold red]" in p2.stdout


def test_an_empty_entry_for_a_problem_scores_as_leaving_it_out(problems, tmp_path):
    """`slider_crank: {}` is "not answered" (a failed row), never a free pass (cli.md)."""
    sheets = tmp_path / "sheets"
    _put(sheets / "ann.yaml", "four_bar: {dof: 1, omega.rocker: 4.785 rad/s cw}\nslider_crank: {}\n")
    _put(sheets / "ben.yaml", "four_bar: {dof: 1, omega.rocker: 4.785 rad/s cw}\n")
    p, report = check_json(str(problems), "--answers", str(sheets))
    assert p.returncode == 1
    scores = {s["student"]: s for s in report["students"]}
    assert scores["ben"]["failed"] == 1  # the documented rule for a missing problem
    assert scores["ann"]["score"] == scores["ben"]["score"], scores
    ann_sc = [r for r in rows_of(report, "ann") if r["file"].endswith("slider_crank.yaml")]
    assert ann_sc and sum(r["failed"] + r["errors"] for r in ann_sc) >= 1


def test_a_problem_answered_by_stem_and_by_file_name_is_answered_twice(problems, tmp_path):
    """`four_bar:` and `four_bar.yaml:` name one problem: an error, not one silently dropped."""
    sheet = _put(
        tmp_path / "alice.yaml",
        "four_bar: {dof: 1, omega.rocker: 4.785 rad/s cw}\nfour_bar.yaml: {dof: 5}\n",
    )
    _, report = check_json(str(problems), "--answers", str(sheet))
    four = [
        v
        for r in rows_of(report, "alice")
        for v in r["answers"]
        if "four_bar" in r["file"] or "four_bar" in v["key"]
    ]
    assert any(v["status"] != "pass" for v in four), four
    assert "twice" in json.dumps(report)


def test_a_problem_answered_by_stem_and_by_name_is_answered_twice_not_unknown(problems, tmp_path):
    """The second entry names the same problem by its `name:`; "no problem file is named" is false."""
    sheet = _put(tmp_path / "bob.yaml", f'four_bar: {{dof: 1}}\n"{FOUR_BAR_NAME}": {{dof: 7}}\n')
    _, report = check_json(str(problems), "--answers", str(sheet))
    text = json.dumps(report, ensure_ascii=False)
    assert "no problem file is named" not in text, text[:2000]
    assert "twice" in text


def test_sheets_carol_yaml_and_carol_yml_are_not_one_student_counted_twice(problems, tmp_path):
    """One row per student name, and a student's totals are the rows with that name."""
    sheets = tmp_path / "sheets"
    _put(sheets / "carol.yaml", "four_bar: {dof: 2}\n")
    _put(sheets / "carol.yml", "four_bar: {dof: 1, omega.rocker: 4.785 rad/s cw}\n")
    _, report = check_json(str(problems), "--answers", str(sheets))
    names = [s["student"] for s in report["students"]]
    assert len(names) == len(set(names)), names
    for s in report["students"]:
        rows = [
            r for r in rows_of(report, s["student"]) if not r["sheet"]
        ]  # a sheet's own row is no question
        assert s["total"] == sum(r["passed"] + r["failed"] + r["errors"] for r in rows)


def test_an_uppercase_yaml_sheet_is_read(problems, tmp_path):
    """erin.YAML (a Windows or macOS upload) is a student, not silently dropped."""
    sheets = tmp_path / "sheets"
    _put(sheets / "dave.yaml", "four_bar: {dof: 1}\n")
    _put(sheets / "erin.YAML", "four_bar: {dof: 1}\n")
    _, report = check_json(str(problems), "--answers", str(sheets))
    assert "erin" in json.dumps(report), [s["student"] for s in report["students"]]


def test_a_stem_shared_by_two_problem_files_is_an_ambiguous_error(tmp_path):
    """a/hw.yaml and b/hw.yaml: `hw:` is an error row, not graded against both."""
    _put(tmp_path / "p" / "a" / "hw.yaml", strip_answers("four_bar.yaml"))
    _put(tmp_path / "p" / "b" / "hw.yaml", strip_answers("slider_crank.yaml"))
    sheet = _put(tmp_path / "s.yaml", "hw: {chain: four-bar}\n")
    _, report = check_json(str(tmp_path / "p"), "--answers", str(sheet))
    statuses = [v["status"] for r in report["results"] for v in r["answers"]]
    assert "error" in statuses, statuses


def test_the_summary_counts_problem_files_not_the_sheets_error_row(problems, tmp_path):
    """2 problem files and a sheet with an unknown entry: "in 2 files", not 3."""
    sheet = _put(tmp_path / "s.yaml", "four_bar: {dof: 1}\nno_such_problem: {dof: 1}\n")
    _, report = check_json(str(problems), "--answers", str(sheet))
    assert report["summary"]["files"] == 2, report["summary"]


def test_a_complex_yaml_key_on_a_sheet_is_reported_without_parser_internals(problems, tmp_path):
    """`? [a, b]` once printed "[ScalarNode(tag='tag:yaml.org,2002:str', …)]"."""
    sheet = _put(tmp_path / "w.yaml", "? [a, b]\n: {dof: 1}\nfour_bar: {dof: 1}\n")
    _, report = check_json(str(problems), "--answers", str(sheet))
    assert "ScalarNode" not in json.dumps(report)


# (sheet text, the bad student's (passed, failed, errors, ignored)) of 3 questions: four_bar's
# dof and omega.rocker, slider_crank's dof.  An unreadable sheet makes every question an error;
# an unreadable entry its problem's questions; a problem left out is failed; a key that is no
# question (velocity.Z, a student's tolerance, a non-text problem key) is ignored.
HOSTILE_SHEETS = [
    pytest.param("- four_bar\n- {dof: 1}\n", (0, 0, 3, 0), id="a-list"),
    pytest.param("", (0, 0, 3, 0), id="empty"),
    pytest.param("four_bar: 1\n", (0, 1, 2, 0), id="scalar-entry"),
    pytest.param("four_bar: {velocity.Z: 1 m/s, dof: 1}\n", (1, 2, 0, 1), id="key-the-problem-lacks"),
    pytest.param("four_bar: {dof: 1, tolerance: 50%}\n", (1, 2, 0, 1), id="student-tolerance"),
    pytest.param("1: {dof: 1}\nnull: {dof: 1}\n", (0, 3, 0, 2), id="non-text-keys"),
    pytest.param("four_bar: [1, 2]\n", (0, 1, 2, 0), id="list-entry"),
]


@pytest.mark.parametrize("text, counts", HOSTILE_SHEETS)
def test_a_hostile_sheet_costs_only_its_student_and_the_class_goes_on(problems, tmp_path, text, counts):
    """Each hostile sheet is rows for that student only; a good sheet beside it is graded normally."""
    sheets = tmp_path / "sheets"
    _put(sheets / "bad.yaml", text)
    _put(sheets / "good.yaml", "four_bar: {dof: 1, omega.rocker: 4.785 rad/s cw}\n")
    p, report = check_json(str(problems), "--answers", str(sheets))
    assert p.returncode == 1
    students = {s["student"]: s for s in report["students"]}
    good = students["good"]
    assert good["passed"] == 2 and good["errors"] == 0
    bad = students["bad"]
    assert (bad["passed"], bad["failed"], bad["errors"], bad["ignored"]) == counts, bad
    assert rows_of(report, "bad")


def test_gradescope_for_a_class_and_unwritable_reports_are_exit_2(problems, tmp_path):
    """cli.md: --gradescope takes one sheet, and a report file that cannot be written is exit 2."""
    sheets = tmp_path / "sheets"
    _put(sheets / "a.yaml", "four_bar: {dof: 1}\n")
    p = mech(
        "check", str(problems), "--answers", str(sheets), "--gradescope", str(tmp_path / "g.json"), "-j", "1"
    )
    no_traceback(p)
    assert p.returncode == 2
    for opt in ("--junit", "--csv", "--gradescope"):
        p = mech("check", str(problems / "four_bar.yaml"), opt, str(tmp_path / "no" / "dir" / "x"), "-j", "1")
        no_traceback(p)
        assert p.returncode == 2 and "cannot write" in p.stderr


def test_class_reports_are_identical_with_one_and_two_jobs(problems, tmp_path):
    """--jobs 2 (a process pool) and --jobs 1 give the same JSON, CSV and JUnit byte for byte."""
    sheets = tmp_path / "sheets"
    _put(sheets / "zoë <&>.yaml", "four_bar: {dof: 1, omega.rocker: 4.785 rad/s cw}\n")
    _put(
        sheets / "a.yaml",
        'four_bar: {dof: 2}\n"Slider crank, Khurmi Ex. 7.2 / 8.1": {velocity.D: 3.995 m/s}\n',
    )
    _put(sheets / "sub" / "b.yml", "slider_crank.yaml: {omega.rod: 5.642 rad/s ccw}\n")
    outs = []
    for jobs in ("1", "2"):
        x, c = tmp_path / f"{jobs}.xml", tmp_path / f"{jobs}.csv"
        p = mech(
            "check",
            str(problems),
            "--answers",
            str(sheets),
            "-j",
            jobs,
            "--json",
            "--junit",
            str(x),
            "--csv",
            str(c),
            subprocess_=True,
        )
        assert p.returncode == 1 and "Traceback" not in p.stderr, p.stderr[-1000:]
        outs.append((p.stdout, x.read_text(encoding="utf-8"), c.read_text(encoding="utf-8")))
        ET.fromstring(outs[-1][1].encode("utf-8"))
    assert outs[0] == outs[1]
    report = strict_json(outs[0][0])
    assert [s["student"] for s in report["students"]] == ["a", "sub/b", "zoë <&>"]


def test_control_characters_from_a_sheet_leave_the_junit_file_well_formed(problems, tmp_path):
    """A claim "four\\x01bar" or a key "four_bar\\x01" is not copied raw into XML 1.0."""
    sheet = _put(
        tmp_path / "ctrl.yaml", '"four_bar\\x01": {dof: 1}\nfour_bar: {chain: "four\\x01bar", dof: 1}\n'
    )
    out = tmp_path / "j.xml"
    p = mech("check", str(problems), "--answers", str(sheet), "-j", "1", "--junit", str(out))
    no_traceback(p)
    ET.parse(out)


def test_escape_codes_from_a_sheet_never_reach_the_teachers_terminal(problems, tmp_path):
    """A claim "\\x1b[2J…" is shown escaped in the plain table: cli.md, no escape codes when plain."""
    sheet = _put(tmp_path / "esc.yaml", 'four_bar: {chain: "\\e[2J\\e[31mfour-bar", dof: 1}\n')
    p = mech("check", str(problems), "--answers", str(sheet), "-j", "1")
    no_traceback(p)
    assert "\x1b" not in p.stdout


# -- untrusted sheets: bounded memory, messages that say what is true (issue 25 items 10, 13) ----
def test_keys_beyond_twenty_that_are_not_questions_are_counted_in_one_row(problems, tmp_path):
    """A sheet entry with 500 junk keys: 20 listed, one row counting the other 480, none scored."""
    junk = "\n".join(f"  junk_{k}: {k}" for k in range(500))
    sheet = _put(tmp_path / "s.yaml", f"four_bar:\n  dof: 1\n{junk}\n")
    p, report = check_json(str(problems), "--answers", str(sheet))
    assert p.returncode == 1
    (row,) = [r for r in rows_of(report, "s") if r["file"].endswith("four_bar.yaml")]
    ignored = [a for a in row["answers"] if a["status"] == IGNORED]
    assert [a["key"] for a in ignored[:20]] == [f"junk_{k}" for k in range(20)]
    assert len(ignored) == 21 and "480 more keys" in ignored[20]["message"]
    assert [(a["key"], a["status"]) for a in row["answers"] if a["status"] != IGNORED] == [
        ("dof", PASS),
        ("omega.rocker", FAIL),
    ]


def test_entries_beyond_twenty_naming_no_problem_are_counted_in_one_row(problems, tmp_path):
    sheet = _put(tmp_path / "s.yaml", "".join(f"nothing_{k}: {{dof: 1}}\n" for k in range(100)))
    _, report = check_json(str(problems), "--answers", str(sheet))
    rows = [r for r in rows_of(report, "s") if r["file"].endswith("s.yaml")]
    keys = [r["answers"][0]["key"] for r in rows]
    assert keys[:20] == [f"nothing_{k}" for k in range(20)] and len(keys) == 21
    assert "80 more entries" in rows[20]["answers"][0]["message"]


@pytest.mark.slow
def test_a_class_of_junk_keys_is_checked_in_memory_that_does_not_grow_with_it(problems, tmp_path):
    """10 sheets of 1,500 keys that are not questions (30,000 YAML values).

    The sheets' nodes used to be kept for the whole run (~365 bytes a value, 11 MB here) and
    every key was a row (15,000 rows, ~7 MB); now a sheet is its text, one entry is composed at
    a time, and an entry is 21 rows. The bound (8 MB, tracemalloc's peak) is under half of what
    it took.
    """
    import tracemalloc

    def sheets(name: str, count: int, keys: int) -> str:
        junk = "\n".join(f"  junk_key_number_{k}: {k}" for k in range(keys))
        for s in range(count):
            _put(tmp_path / name / f"student{s:02d}.yaml", f"four_bar:\n  dof: 1\n{junk}\n")
        return str(tmp_path / name)

    warm = CheckOptions((str(problems),), answers=sheets("warm", 1, 30), jobs=1, timeout=None)
    run(warm)  # imports and first-use caches are not what is measured
    options = CheckOptions((str(problems),), answers=sheets("class", 10, 1500), jobs=1, timeout=None)
    tracemalloc.start()
    try:
        report = run(options)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert report.ignored == 10 * 21
    assert peak < 8e6, f"{peak / 1e6:.1f} MB"


def test_an_answer_sheet_that_is_a_link_to_a_fifo_is_named_as_such_not_missing(problems, tmp_path):
    """A sheet that exists but is not a file (issue 25: a link to /dev/zero was "no such sheet")."""
    import os

    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    link = tmp_path / "sheet.yaml"
    link.symlink_to(fifo)
    p = mech("check", str(problems), "--answers", str(link))
    no_traceback(p)
    assert p.returncode == 2
    assert "no such" not in p.stderr
    assert f"a symbolic link to {fifo}" in p.stderr and "a FIFO (named pipe), not a file" in p.stderr


@pytest.mark.slow
def test_a_sheet_with_too_many_values_says_so_not_alias_bomb(problems, tmp_path):
    """100,001 plain keys are more than the 200,000 values a file may hold: said as that, located."""
    junk = "\n".join(f"  k{k}: {k}" for k in range(100_001))
    sheet = _put(tmp_path / "s.yaml", f"four_bar:\n{junk}\n")
    _, report = check_json(str(problems), "--answers", str(sheet))
    (row,) = [r for r in rows_of(report, "s") if r["file"].endswith("s.yaml")]
    message = row["answers"][0]["message"]
    assert "alias" not in message
    assert "more than 200,000 values" in message and "answer sheet" in message


def test_an_alias_bomb_sheet_is_still_called_one(problems, tmp_path):
    bomb = "a: &a [x, x, x, x, x, x, x, x, x, x]\n" + "".join(
        f"{c}: &{c} [*{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}]\n"
        for p, c in zip("abcde", "bcdef", strict=True)
    )
    sheet = _put(tmp_path / "s.yaml", bomb)
    _, report = check_json(str(problems), "--answers", str(sheet))
    (row,) = [r for r in rows_of(report, "s") if r["file"].endswith("s.yaml")]
    assert "alias" in row["answers"][0]["message"]


@pytest.mark.parametrize("jobs", [1, 2])
def test_a_class_graded_in_parts_gives_the_report_of_one_part(classroom, monkeypatch, jobs):
    """A class's problem is graded STUDENTS sheets at a time (a worker holds one part): the
    rows, scores and streamed files are those of grading everyone at once."""
    import mech.batch as batch

    whole = run(CheckOptions((str(classroom / "problems"),), answers=str(classroom / "sheets"), jobs=jobs))
    monkeypatch.setattr(batch, "STUDENTS", 2)  # five students: parts of 2, 2 and 1
    streamed: list[tuple[str, ...]] = []
    parts = run(
        CheckOptions((str(classroom / "problems"),), answers=str(classroom / "sheets"), jobs=jobs),
        on_file=lambda rows: streamed.append(tuple(sorted({Path(r.path).name for r in rows}))),
    )
    assert parts.results == whole.results and parts.scores() == whole.scores()
    assert streamed == [("p1.yaml",), ("p2.yaml",), ("p3.yaml",), ("p4.yaml",)]  # once a file, all students


def test_a_part_of_a_class_past_the_time_limit_excludes_the_problem_for_everyone(classroom, monkeypatch):
    """Scores mean the same for everyone: the students of the parts that finished are not
    graded on a problem the others could not be graded on."""
    import mech.batch as batch
    import mech.check.problem as problem
    from mech.batchpool import JobTimeout

    real = problem._check_sheets

    def slow_for_erin(task, mech, questions):
        if task.path.endswith("p1.yaml") and any(s.student == "erin" for s in task.submissions):
            raise JobTimeout  # what the time limit raises inside a job
        return real(task, mech, questions)

    monkeypatch.setattr(batch, "STUDENTS", 2)  # erin is in the last part, alone
    monkeypatch.setattr(problem, "_check_sheets", slow_for_erin)
    report = grade(classroom)
    teacher = {Path(r.path).name: r for r in report.teacher}
    assert set(teacher) == {"p1.yaml", "p3.yaml", "p4.yaml"}
    assert "time limit" in teacher["p1.yaml"].verdicts[0].message
    for r in report.results:
        if r.student is not None and r.path.endswith("p1.yaml"):
            assert r.excluded and r.total == 0, r
    assert {s.asked for s in report.scores()} == {2}  # p2's two questions, for every student


def test_an_entry_using_an_anchor_written_in_another_entry_is_graded(problems, tmp_path):
    """An entry is composed again from its own text; one aliasing an anchor written elsewhere
    on the sheet is taken from the whole sheet instead (same value, same locations)."""
    sheet = _put(
        tmp_path / "s.yaml",
        "notes: {n: &one 1}\nfour_bar:\n  dof: *one\n  omega.rocker: [1, 2]\nslider_crank: {dof: *one}\n",
    )
    _, report = check_json(str(problems), "--answers", str(sheet))
    rows = {Path(r["file"]).name: r for r in rows_of(report, "s")}
    four = {a["key"]: a for a in rows["four_bar.yaml"]["answers"]}
    assert four["dof"]["status"] == PASS
    assert four["omega.rocker"]["status"] == ERROR and four["omega.rocker"]["line"] == 4
    assert rows["slider_crank.yaml"]["answers"][0]["status"] == PASS


@pytest.mark.parametrize("table", [False, True], ids=["plain", "table"])
def test_quiet_lists_each_students_failing_answers_and_not_the_passing_ones(
    classroom: Path, table: bool
) -> None:
    if table:
        from rich.console import Console

        from mech.render.check import check_table

        buffer = io.StringIO()
        console = Console(file=buffer, force_terminal=True, width=200, color_system=None, markup=False)
        check_table(grade(classroom), console, quiet=True)
        out = buffer.getvalue()
    else:
        p = mech(
            "check", str(classroom / "problems"), "--answers", str(classroom / "sheets"), "-q", "-j", "1"
        )
        assert p.returncode == 1
        out = p.stdout
    # erin's wrong speed (2 m/s for the 1.0 m/s of ω r) and bob's unanswered p1 are listed with their keys
    erin = out[out.index("erin") :]
    assert "velocity.B" in erin and "2 m/s" in erin
    assert "not answered" in out[out.index("bob") :]
    assert "alice" not in out  # every answer right: not listed


# -- marks and the gradebook (DESIGN § 1.3) ------------------------------------------------------
MARKED = {
    # the slider crank above: |v_B| = ω r = 1.0 m/s (4 marks), ω_rod = 0 (1 mark)
    "slider.yaml": SLIDER.replace(
        "answers: {velocity.B: 0, omega.rod: 5}", "answers: {velocity.B: {value: 0, marks: 4}, omega.rod: 5}"
    ),
    # Kutzbach n = 1 (2 marks), four binary links (3 marks)
    "count.yaml": FOUR_BAR + "asks: {dof: 2, links.binary: 3}\n",
}
MARKED_SHEETS = {
    "ann": "slider: {velocity.B: 1 m/s, omega.rod: 1}\ncount: {dof: 1, links.binary: 4}\n",  # 4 + 2 + 3 = 9
    "ben": "slider: {velocity.B: 2 m/s, omega.rod: 0}\ncount: {dof: 2}\n",  # 1
    'cy,"the" third': "slider: {omega.rod: 0}\n",  # 1 (a name a CSV must quote)
}
MARKED_EARNED = {
    "ann": {"count.yaml": 5, "slider.yaml": 4},
    "ben": {"count.yaml": 0, "slider.yaml": 1},
    'cy,"the" third': {"count.yaml": 0, "slider.yaml": 1},
}


@pytest.fixture
def marked_class(tmp_path: Path) -> Path:
    (tmp_path / "problems").mkdir()
    (tmp_path / "sheets").mkdir()
    for name, text in MARKED.items():
        (tmp_path / "problems" / name).write_text(text)
    for student, text in MARKED_SHEETS.items():
        (tmp_path / "sheets" / f"{student}.yaml").write_text(text)
    return tmp_path


def test_a_score_is_marks_earned_over_marks_asked_in_every_report(marked_class: Path) -> None:
    out = marked_class
    p = mech(
        "check", str(out / "problems"), "--answers", str(out / "sheets"), "-j", "1",
        "--junit", str(out / "r.xml"), "--csv", str(out / "r.csv"), "--json",
    )  # fmt: skip
    report = strict_json(p.stdout)
    scores = {s["student"]: (s["earned"], s["out_of"], s["score"]) for s in report["students"]}
    for student, per_problem in MARKED_EARNED.items():
        earned = sum(per_problem.values())
        assert scores[student] == (earned, 10, pytest.approx(earned / 10))
    rows = list(csv.DictReader(io.StringIO((out / "r.csv").read_text())))
    for row in rows:
        want = MARKED_EARNED[row["student"]][Path(row["problem"]).name]
        assert (float(row["earned"]), float(row["out_of"])) == (want, 5)
        assert float(row["score"]) == pytest.approx(100 * want / 5, abs=0.05)
    for suite in ET.parse(out / "r.xml").getroot():
        props = {p.get("name"): float(p.get("value")) for p in suite.iter("property")}
        student, _, path = suite.get("name").partition(": ")
        assert props == {"earned": MARKED_EARNED[student][Path(path).name], "out_of": 5}


def test_gradescope_scores_each_answer_by_its_marks(marked_class: Path) -> None:
    out = marked_class
    p = mech(
        "check", str(out / "problems"), "--answers", str(out / "sheets" / "ann.yaml"), "-j", "1",
        "--gradescope", str(out / "gs.json"),
    )  # fmt: skip
    assert p.returncode == 1
    gs = json.loads((out / "gs.json").read_text())
    worth = {t["name"].rsplit(": ", 1)[1]: (t["score"], t["max_score"]) for t in gs["tests"]}
    assert worth == {"dof": (2, 2), "links.binary": (3, 3), "velocity.B": (4, 4), "omega.rod": (0, 1)}
    assert gs["score"] == 9


def test_the_gradebook_has_one_row_per_student_and_follows_the_import_rules(marked_class: Path) -> None:
    """The rules of the two gradebooks' CSV grade imports that a file can break, as documented:

    * Moodle, "Grade import" (docs.moodle.org/311/en/Grade_import, "CSV grade import"): a header
      row names the columns; one column identifies the user ("Map from" a column "Map to" a user
      field such as the ID number or email), every other column is mapped to one grade item, so
      the column names must be told apart; grades are plain numbers (no "%").
    * Canvas, "How do I import grades in the Gradebook?" (community.canvaslms.com, Instructor
      Guide; its CSV rules are those of the SIS CSV format page, canvas.instructure.com/doc/api/
      file.sis_csv.html): "the first row will be interpreted as a header … mandatory", fields with
      a comma or a double quote are quoted with inner quotes doubled, UTF-8; one row per student
      identified by a student column; a score is a number of points, an unknown column header
      becomes a new assignment.  (Canvas's own export adds `ID`, `SIS Login ID` and `Section`;
      they are matched on the student column when merged, and are not ours to invent.)
    Checked here: those, and that the marks add up (problems → total; total / out_of → percent).
    """
    out = marked_class
    p = mech(
        "check",
        str(out / "problems"),
        "--answers",
        str(out / "sheets"),
        "-j",
        "1",
        "--gradebook",
        str(out / "g.csv"),
    )
    assert p.returncode == 1
    raw = (out / "g.csv").read_bytes()
    raw.decode("utf-8")  # UTF-8 (it raises if not)
    rows = list(csv.reader(io.StringIO(raw.decode("utf-8")), strict=True))
    header, body = rows[0], rows[1:]
    problems = [str(out / "problems" / "count.yaml"), str(out / "problems" / "slider.yaml")]
    assert header == ["student", *problems, "total", "out_of", "percent"]
    assert len({h.strip().lower() for h in header}) == len(header)  # every column told apart
    assert all(len(r) == len(header) for r in body)  # a rectangle: every row has every field
    students = [r[0] for r in body]
    assert sorted(students) == sorted(MARKED_EARNED) and len(set(students)) == len(students)
    assert all(s.strip() for s in students)  # the identifying column is never empty
    for r in body:
        cells = [float(c) for c in r[1:]]  # numbers only: no "%", no thousands separator
        assert all("%" not in c and "," not in c for c in r[1:])
        *problems, total, out_of, percent = cells
        want = MARKED_EARNED[r[0]]
        assert problems == [want["count.yaml"], want["slider.yaml"]]
        assert total == sum(problems) and out_of == 10
        assert percent == pytest.approx(100 * total / out_of, abs=0.05)
    assert b'"cy,""the"" third"' in raw  # a comma and quotes in a name: quoted, quotes doubled


def test_gradebook_without_answer_sheets_is_a_usage_error(tmp_path: Path) -> None:
    (tmp_path / "p.yaml").write_text(SLIDER)
    p = mech("check", str(tmp_path / "p.yaml"), "--gradebook", str(tmp_path / "g.csv"))
    assert p.returncode == 2 and "--answers" in p.stderr and not (tmp_path / "g.csv").exists()


def test_class_statistics_give_each_question_its_right_count_and_commonest_mistake(tmp_path: Path) -> None:
    from test_check_diagnose import FB
    from test_check_diagnose import FOUR_BAR as DRAWN

    (tmp_path / "problems").mkdir()
    (tmp_path / "sheets").mkdir()
    (tmp_path / "problems" / "fb.yaml").write_text(DRAWN.replace("answers:\n", "asks: [omega.rocker]\n"))
    w4, w3 = FB["w4"], FB["w3"]  # the rocker's and the coupler's ω by the vector loop
    sense = "cw" if w4 < 0 else "ccw"
    flipped = "ccw" if w4 < 0 else "cw"
    claims = {
        "a": f"{abs(w4):.6f} rad/s {sense}", "b": f"{abs(w4):.6f} rad/s {sense}", "c": f"{abs(w4):.6f}",
        "d": f"{abs(w4):.6f} rad/s {flipped}", "e": f"{abs(w4):.6f} rad/s {flipped}", "f": f"{abs(w3):.6f}",
    }  # fmt: skip
    for student, claim in claims.items():
        (tmp_path / "sheets" / f"{student}.yaml").write_text(f"fb: {{omega.rocker: {claim}}}\n")
    p = mech("check", str(tmp_path / "problems"), "--answers", str(tmp_path / "sheets"), "--json", "-j", "1",
             "--gradebook", str(tmp_path / "g.csv"))  # fmt: skip
    (stat,) = strict_json(p.stdout)["statistics"]
    assert (stat["key"], stat["asked"], stat["right"], stat["wrong"]) == ("omega.rocker", 6, 3, 3)
    assert stat["commonest_mistake"].startswith("the opposite sense") and stat["mistaken"] == 2
    svg = (tmp_path / "g.svg").read_text(encoding="utf-8")  # the histogram beside the gradebook
    ET.fromstring(svg)  # well-formed
    assert "6 students" in svg and ">3<" in svg  # three at 0 % and three at 100 %
    listing = mech(
        "check", str(tmp_path / "problems"), "--answers", str(tmp_path / "sheets"), "-j", "1"
    ).stdout
    assert "omega.rocker: 3/6 right; 2 × the opposite sense" in listing


def test_a_sheet_cannot_give_itself_marks(marked_class: Path) -> None:
    (marked_class / "sheets" / "ann.yaml").write_text(
        "slider: {velocity.B: {value: 1 m/s, marks: 100}, omega.rod: 0}\ncount: {dof: 1, links.binary: 4}\n"
    )
    report = run(
        CheckOptions((str(marked_class / "problems"),), answers=str(marked_class / "sheets"), jobs=1)
    )
    (ann,) = [s for s in report.scores() if s.student == "ann"]
    assert (ann.earned, ann.out_of) == (6, 10)  # the 4 marks of velocity.B are not earned: not graded
    (row,) = [v for r in report.results if r.student == "ann" for v in r.verdicts if v.key == "velocity.B"]
    assert row.status == ERROR and "cannot set a tolerance or marks" in row.message
