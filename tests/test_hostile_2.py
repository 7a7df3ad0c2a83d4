"""Hostile-input and hand-solved-number tests, second audit (check, icentres, sweep, draw, JSON).

The first audit (tests/test_hostile.py) covered the loader's YAML edge cases and the basic
solver; this one goes after what it did not reach: answer sheets and the report files of
``mech check``, I-centres of every pair type against a velocity field derived here, sweeps
(ranges, dead centres, time ratios, extremes, CSV), drawings with hostile names, and JSON.

Promises tested (cli.md): bad input -> ``file:line:column: error:`` + hint, exit 2, never a
traceback; a failed check -> exit 1; in a batch one bad file never stops the others and every
file gets its row; numbers are right or refused, never silently wrong; JSON is valid JSON.

Expected numbers are derived here (closed forms, or an independent linear velocity solve from
the pin/slider/contact constraints written out below), never taken from mech.

Every test is either a guard (passes today, marked ``# guard``) or pins a defect found by this
audit (marked ``# DEFECT:``, with what happens and what should happen); defects fail today.
"""

from __future__ import annotations

import csv
import io
import json
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from cli_runner import Run, mech, strict_json

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "mechanisms"


# -- helpers (mech() copied from tests/test_hostile.py) -----------------------------------
def no_traceback(p: Run) -> None:
    assert "Traceback" not in p.stderr, p.stderr[-2500:]


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


def f(x: float) -> str:
    return repr(float(x))


def pt(p) -> str:
    return f"[{f(p[0])}, {f(p[1])}]"


# The shipped four-bar (Khurmi 7.1) and slider crank without their answers: problems for sheets.
def _strip_answers(name: str) -> str:
    return (EXAMPLES / name).read_text(encoding="utf-8").split("\nanswers:")[0] + "\n"


FOUR_BAR_NAME = "Four-bar chain ABCD (Khurmi Ex. 7.1)"


@pytest.fixture
def problems(tmp_path: Path) -> Path:
    """problems/four_bar.yaml (teacher's questions dof, omega.rocker) and slider_crank.yaml (none)."""
    d = tmp_path / "problems"
    write(
        d / "four_bar.yaml",
        _strip_answers("four_bar.yaml") + "answers:\n  dof: 1\n  omega.rocker: 4.785 rad/s cw\n",
    )
    # a problem without values lists its questions (issue 10: a problem asking nothing is excluded)
    write(d / "slider_crank.yaml", _strip_answers("slider_crank.yaml") + "asks: [dof]\n")
    return d


def check_json(*args: str) -> tuple[Run, dict]:
    p = mech("check", *args, "-j", "1", "--json")
    no_traceback(p)
    return p, strict_json(p.stdout)


def rows_of(report: dict, student: str) -> list[dict]:
    return [r for r in report["results"] if r["student"] == student]


# =========================================================================================
# 1. mech check: answer sheets
# =========================================================================================
def test_markup_in_a_students_claim_crashes_the_whole_class_report(problems, tmp_path):
    # DEFECT: (high) a sheet with `chain: "[/b]"` kills `mech check` with a rich MarkupError
    # traceback: no table, no closing line, for every student of the class.  Claims, keys,
    # messages and names are printed as rich markup: `[bold red]x[/bold red]` is shown as `x`
    # ("the chain is four-bar, not x"), misreporting what the student wrote.
    # Should: print text literally (rich.text.Text / markup escaping), exit 1.
    sheet = write(tmp_path / "s.yaml", 'four_bar: {chain: "[/b]", dof: 1}\n')
    p = mech("check", str(problems), "--answers", str(sheet), "-j", "1", "-v")
    no_traceback(p)
    assert p.returncode == 1
    assert "[/b]" in p.stdout and "failed" in p.stdout
    sheet2 = write(tmp_path / "s2.yaml", 'four_bar: {chain: "[bold red]x[/bold red]", dof: 1}\n')
    p2 = mech("check", str(problems), "--answers", str(sheet2), "-j", "1", "-v")
    no_traceback(p2)
    assert "[bold red]x[/bold red]" in p2.stdout


@pytest.mark.parametrize("command", ["position", "velocity", "acceleration", "sweep", "icentres", "dof"])
def test_mechanism_name_with_square_brackets_crashes_tables(tmp_path, command):
    # DEFECT: (high for position/velocity/acceleration/sweep) `name:` is free text, but a name such
    # as "x [/b] [red]y" ends in `rich.errors.MarkupError` (a traceback, exit 1) because the
    # header is printed as markup.  Should: print the name literally, exit 0.
    # (dof and icentres hold today: guards.)
    text = (EXAMPLES / "four_bar.yaml").read_text(encoding="utf-8")
    text = re.sub(r"(?m)^name: .*$", 'name: "x [/b] [red]y"', text)
    m = write(tmp_path / "m.yaml", text)
    p = mech(command, str(m), *(["--steps", "12"] if command == "sweep" else []))
    no_traceback(p)
    assert p.returncode == 0
    assert "x [/b] [red]y" in p.stdout


def test_empty_answers_for_a_problem_score_better_than_leaving_it_out(problems, tmp_path):
    # DEFECT: (grading) cli.md: "A problem the sheet does not answer at all is one failed row".
    # ann writes `slider_crank: {}` and gets 0 rows for it -> 100%; ben leaves slider_crank out
    # and gets a failed row -> 50%, for the same work.  Should: `{}` is "not answered" (a failed
    # row) like a missing entry (or an error row), never a free pass.
    sheets = tmp_path / "sheets"
    write(sheets / "ann.yaml", "four_bar: {dof: 1, omega.rocker: 4.785 rad/s cw}\nslider_crank: {}\n")
    write(sheets / "ben.yaml", "four_bar: {dof: 1, omega.rocker: 4.785 rad/s cw}\n")
    p, report = check_json(str(problems), "--answers", str(sheets))
    assert p.returncode == 1
    scores = {s["student"]: s for s in report["students"]}
    assert scores["ben"]["failed"] == 1  # guard: the documented rule for a missing problem
    assert scores["ann"]["score"] == scores["ben"]["score"], scores
    ann_sc = [r for r in rows_of(report, "ann") if r["file"].endswith("slider_crank.yaml")]
    assert ann_sc and sum(r["failed"] + r["errors"] for r in ann_sc) >= 1


def test_a_problem_answered_twice_by_stem_and_file_name_silently_keeps_one(problems, tmp_path):
    # DEFECT: (grading) `four_bar:` and `four_bar.yaml:` on one sheet name the same problem; the
    # sheet reader refuses a key written twice, but these two are different keys: the first is
    # graded and the second ({dof: 5}, a wrong answer) is silently dropped -- swap the order and
    # the wrong one is graded instead.  Should: an error row "answered twice" (as for a repeated key).
    sheet = write(
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


def test_a_problem_answered_by_stem_and_by_name_is_reported_as_unknown(problems, tmp_path):
    # DEFECT: (misleading) the same problem named by stem and by its `name:`: the second entry
    # becomes an error row saying "no problem file is named 'Four-bar chain ABCD (Khurmi
    # Ex. 7.1)'" -- but one is.  Should: say it answers four_bar a second time.
    sheet = write(tmp_path / "bob.yaml", f'four_bar: {{dof: 1}}\n"{FOUR_BAR_NAME}": {{dof: 7}}\n')
    _, report = check_json(str(problems), "--answers", str(sheet))
    text = json.dumps(report, ensure_ascii=False)
    assert "no problem file is named" not in text, text[:2000]
    assert "twice" in text


def test_alice_yaml_and_alice_yml_make_one_student_counted_twice(problems, tmp_path):
    # DEFECT: (grading) a class folder with carol.yaml and carol.yml: both sheets become student
    # "carol"; the class table has two identical "carol" rows, each counting the rows of BOTH
    # sheets (16 answers instead of 8) and a score mixing both.  Should: one student per name
    # (an error row for the clash), or distinct students (carol.yaml / carol.yml).
    sheets = tmp_path / "sheets"
    write(sheets / "carol.yaml", "four_bar: {dof: 2}\n")
    write(sheets / "carol.yml", "four_bar: {dof: 1, omega.rocker: 4.785 rad/s cw}\n")
    _, report = check_json(str(problems), "--answers", str(sheets))
    names = [s["student"] for s in report["students"]]
    assert len(names) == len(set(names)), names
    for s in report["students"]:  # a student's totals are the rows with that student's name
        rows = [
            r for r in rows_of(report, s["student"]) if not r["sheet"]
        ]  # a sheet's own row is no question
        assert s["total"] == sum(r["passed"] + r["failed"] + r["errors"] for r in rows)


def test_uppercase_yaml_sheet_is_silently_dropped(problems, tmp_path):
    # DEFECT: (low) a class folder with erin.YAML (a Windows or macOS student's upload): erin gets
    # no row at all -- not in the class table, the CSV or the JSON, and nothing says so.  The
    # same for a problem file named .YAML.  Should: read .YAML/.YML (suffix case-insensitive), or
    # at least an error row naming the file it skipped.
    sheets = tmp_path / "sheets"
    write(sheets / "dave.yaml", "four_bar: {dof: 1}\n")
    write(sheets / "erin.YAML", "four_bar: {dof: 1}\n")
    _, report = check_json(str(problems), "--answers", str(sheets))
    assert "erin" in json.dumps(report), [s["student"] for s in report["students"]]


def test_a_stem_shared_by_two_problem_files_grades_one_answer_against_both(tmp_path):
    # DEFECT: (grading) problems a/hw.yaml (a four-bar) and b/hw.yaml (a slider crank); a sheet
    # `hw: {chain: four-bar}` is silently checked against both: pass on one, fail on the other.
    # Should: an error row saying `hw` is ambiguous (names 2 files: use the path or the name).
    write(tmp_path / "p" / "a" / "hw.yaml", _strip_answers("four_bar.yaml"))
    write(tmp_path / "p" / "b" / "hw.yaml", _strip_answers("slider_crank.yaml"))
    sheet = write(tmp_path / "s.yaml", "hw: {chain: four-bar}\n")
    _, report = check_json(str(tmp_path / "p"), "--answers", str(sheet))
    statuses = [v["status"] for r in report["results"] for v in r["answers"]]
    assert "error" in statuses, statuses


def test_closing_line_counts_a_sheet_as_a_problem_file(problems, tmp_path):
    # DEFECT: (low) 2 problem files, a sheet with one unknown entry: the closing line says
    # "in 3 files" (the sheet's error row is counted as a file) and the class table says the
    # student did 3 "problems".  Should: "in 2 files".
    sheet = write(tmp_path / "s.yaml", "four_bar: {dof: 1}\nno_such_problem: {dof: 1}\n")
    _, report = check_json(str(problems), "--answers", str(sheet))
    assert report["summary"]["files"] == 2, report["summary"]


def test_complex_yaml_key_on_a_sheet_leaks_parser_internals(problems, tmp_path):
    # DEFECT: (cosmetic) a sheet key `? [a, b]` is reported as "no problem file is named
    # \"[ScalarNode(tag='tag:yaml.org,2002:str', value='a'), ...]\"".  Should: a located error
    # saying a problem key is a file name, stem or name (text).
    sheet = write(tmp_path / "w.yaml", "? [a, b]\n: {dof: 1}\nfour_bar: {dof: 1}\n")
    _, report = check_json(str(problems), "--answers", str(sheet))
    assert "ScalarNode" not in json.dumps(report)


@pytest.mark.parametrize(
    "text",
    [
        "- four_bar\n- {dof: 1}\n",  # a list
        "",  # empty
        "four_bar: 1\n",  # a scalar where answers go
        "four_bar: {velocity.Z: 1 m/s, dof: 1}\n",  # a key the problem lacks
        "four_bar: {dof: 1, tolerance: 50%}\n",  # a student setting a tolerance
        "1: {dof: 1}\nnull: {dof: 1}\n",  # non-text keys
        "four_bar: [1, 2]\n",
    ],
)
def test_hostile_sheets_are_error_rows_and_the_class_goes_on(problems, tmp_path, text):
    # guard: each hostile sheet is error rows for that student only; a good sheet beside it is
    # graded normally; exit 1, no traceback.
    sheets = tmp_path / "sheets"
    write(sheets / "bad.yaml", text)
    write(sheets / "good.yaml", "four_bar: {dof: 1, omega.rocker: 4.785 rad/s cw}\n")
    p, report = check_json(str(problems), "--answers", str(sheets))
    assert p.returncode == 1
    good = {s["student"]: s for s in report["students"]}["good"]
    assert good["passed"] == 2 and good["errors"] == 0
    bad = rows_of(report, "bad")
    assert bad and sum(r["errors"] + r["ignored"] for r in bad) >= 1  # ignored: keys that are no question


def test_junit_with_control_characters_from_a_sheet_is_not_xml(problems, tmp_path):
    # DEFECT: (medium) a student's sheet can make the CI's JUnit file unparseable: a claim
    # "four\x01bar" (a YAML escape) or a sheet key "four_bar\x01" is copied raw into XML
    # attributes and text, where XML 1.0 forbids it ("not well-formed (invalid token)"); the
    # whole class's CI report is lost.  Should: drop or replace characters XML cannot hold.
    sheet = write(
        tmp_path / "ctrl.yaml", '"four_bar\\x01": {dof: 1}\nfour_bar: {chain: "four\\x01bar", dof: 1}\n'
    )
    out = tmp_path / "j.xml"
    p = mech("check", str(problems), "--answers", str(sheet), "-j", "1", "--junit", str(out))
    no_traceback(p)
    ET.parse(out)


def test_terminal_escape_codes_from_a_sheet_reach_the_teachers_terminal(problems, tmp_path):
    # DEFECT: (low, terminal injection) a claim "\x1b[2J..." from a student's sheet is printed raw
    # in the plain (NO_COLOR) table, so it clears/recolours the teacher's terminal.  cli.md:
    # plain output has no escape codes.  Should: show control characters escaped.
    sheet = write(tmp_path / "esc.yaml", 'four_bar: {chain: "\\e[2J\\e[31mfour-bar", dof: 1}\n')
    p = mech("check", str(problems), "--answers", str(sheet), "-j", "1")
    no_traceback(p)
    assert "\x1b" not in p.stdout


HOSTILE_NAME = "Bad <&\"'> \nline2 ]]> é"


def test_reports_escape_hostile_names_and_counts_agree(tmp_path):
    # guard: a problem file named é <&'q'>.yaml whose `name` holds <&"'>, a newline and ]]>:
    # JUnit parses and its counts equal the JSON summary; Gradescope is JSON whose test names
    # carry the name exactly; the CSV parses with one row per file; exit 1 for the failures.
    body = _strip_answers("slider_crank.yaml")
    body = re.sub(r"(?m)^name: .*$", lambda _: "name: " + json.dumps(HOSTILE_NAME), body)
    body += "answers:\n  dof: 1\n  omega.rod: 5.642 rad/s ccw\n  chain: \"four <bar> & 'x'\"\n  velocity.B: 9 m/s\n"
    folder = tmp_path / "hw"
    write(folder / "é <&'q'>.yaml", body)
    write(folder / "good.yaml", _strip_answers("four_bar.yaml") + "answers: {dof: 1}\n")
    junit, gs, gb = tmp_path / "r.xml", tmp_path / "gs.json", tmp_path / "g.csv"
    p = mech(
        "check",
        str(folder),
        "-j",
        "1",
        "--json",
        "--junit",
        str(junit),
        "--gradescope",
        str(gs),
        "--csv",
        str(gb),
    )
    no_traceback(p)
    assert p.returncode == 1
    summary = strict_json(p.stdout)["summary"]
    assert (summary["passed"], summary["failed"], summary["errors"]) == (3, 2, 0)
    root = ET.parse(junit).getroot()
    assert root.get("tests") == str(summary["total"]) and root.get("failures") == str(summary["failed"])
    cases = root.findall(".//testcase")
    assert len(cases) == summary["total"]
    assert len(root.findall(".//failure")) == summary["failed"]
    assert sum(int(s.get("tests")) for s in root.findall("testsuite")) == summary["total"]
    messages = [fl.get("message") for fl in root.findall(".//failure")]
    assert any("four <bar> & 'x'" in m for m in messages), messages
    grade = strict_json(gs.read_text(encoding="utf-8"))
    assert grade["score"] == summary["passed"] and len(grade["tests"]) == summary["total"]
    assert any(f"({HOSTILE_NAME}): " in t["name"] for t in grade["tests"])  # named by file and name
    assert all(t["status"] in ("passed", "failed") and t["max_score"] == 1 for t in grade["tests"])
    rows = list(csv.DictReader(io.StringIO(gb.read_text(encoding="utf-8"))))
    assert len(rows) == 2 and {Path(r["problem"]).name for r in rows} == {"é <&'q'>.yaml", "good.yaml"}
    hostile = next(r for r in rows if "q" in r["problem"])
    assert (hostile["passed"], hostile["total"], hostile["score"]) == ("2", "4", "50.0")


def test_gradescope_refuses_a_class_and_unwritable_reports_are_exit_2(problems, tmp_path):
    # guard: cli.md exit status 2 for --gradescope with a folder of sheets and for report files
    # that cannot be written.
    sheets = tmp_path / "sheets"
    write(sheets / "a.yaml", "four_bar: {dof: 1}\n")
    p = mech(
        "check", str(problems), "--answers", str(sheets), "--gradescope", str(tmp_path / "g.json"), "-j", "1"
    )
    no_traceback(p)
    assert p.returncode == 2
    for opt in ("--junit", "--csv", "--gradescope"):
        p = mech("check", str(problems / "four_bar.yaml"), opt, str(tmp_path / "no" / "dir" / "x"), "-j", "1")
        no_traceback(p)
        assert p.returncode == 2 and "cannot write" in p.stderr


def _slider(r, L, angle, omega, offset=0.0, extra="", drive=None):
    drive = drive or f"{{link: crank, angle: {angle}, omega: {omega}, direction: ccw}}"
    return f"""\
links: [frame, crank, rod, piston]
joints:
  O: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  A: {{type: revolute, links: [crank, rod]}}
  B: {{type: revolute, links: [rod, piston], near: [{f(5 * r)}, {f(offset)}]}}
  P: {{type: prismatic, links: [piston, frame], path: {{through: [0, {f(offset)}], angle: 0}}}}
lengths: {{OA: {f(r)}, AB: {f(L)}}}
drive: {drive}
{extra}"""


# One file per distinct way the solver can fail to give an answer (each must be one error row).
FAILURES = {
    "no_assembly": _slider(0.1, 0.4, 90, 10, offset=1.0, extra="answers: {velocity.B: 1 m/s}\n"),
    "toggle": """\
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [1, 1]}
  D: {type: revolute, links: [rocker, frame], at: [2, 0]}
lengths: {AB: 1, BC: 2, CD: 1}
drive: {link: crank, angle: 180, omega: 10}
answers: {omega.rocker: 1}
""",
    "structure": """\
links: [frame, a, b]
joints:
  A: {type: revolute, links: [frame, a], at: [0, 0]}
  B: {type: revolute, links: [a, b], at: [1, 1]}
  C: {type: revolute, links: [b, frame], at: [2, 0]}
drive: {link: a, angle: 45, omega: 1}
answers: {velocity.B: 0}
""",
    "no_speed": _slider(
        0.1, 0.4, 90, 10, drive="{link: crank, angle: 90}", extra="answers: {velocity.B: 1 m/s}\n"
    ),
    "two_dof_one_drive": """\
links: [frame, a, b, c, d]
joints:
  A: {type: revolute, links: [frame, a], at: [0, 0]}
  B: {type: revolute, links: [a, b]}
  C: {type: revolute, links: [b, c], near: [1, 1.5]}
  D: {type: revolute, links: [c, d]}
  E: {type: revolute, links: [d, frame], at: [2, 0]}
lengths: {AB: 1, BC: 1, CD: 1, DE: 1}
drive: {link: a, angle: 90, omega: 1}
answers: {omega.b: 1}
""",
    "ratio_over_rest": _slider(0.1, 0.4, 90, 10, extra="answers: {omega_ratio.crank.rod: 1}\n"),
    "cam_acceleration": """\
links: [frame, cam, follower]
joints:
  O: {type: revolute, links: [frame, cam], at: [0, 0]}
  F: {type: prismatic, links: [follower, frame], path: {through: [0, 0], angle: 90}, point: T}
  T: {type: cam, links: [cam, follower], at: [0, 0.05], normal: 80}
drive: {link: cam, angle: 0, rpm: 60}
answers: {acceleration.T: 1}
""",
    "gear_contradiction": """\
links: [frame, g1, g2]
joints:
  O1: {type: revolute, links: [frame, g1], at: [0, 0]}
  O2: {type: revolute, links: [frame, g2], at: [0.3, 0]}
  M: {type: gear, links: [g1, g2], radii: [0.05, 0.1]}
drive: {link: g1, rpm: 600}
answers: {icentre.g1.g2: [0.1, 0]}
""",
    "mobility_without_geometry": """\
links: [frame, a, b, c]
joints:
  A: {type: revolute, links: [frame, a]}
  B: {type: revolute, links: [a, b]}
  C: {type: revolute, links: [b, c]}
  D: {type: revolute, links: [c, frame]}
answers: {mobility: 1}
""",
    "spherical": """\
links: [frame, a, b]
joints:
  A: {type: spherical, links: [frame, a], at: [0, 0]}
  B: {type: revolute, links: [a, b], at: [1, 0]}
drive: {link: a, angle: 0, omega: 1}
answers: {omega.a: 1}
""",
    "out_of_range": _slider(1e307, 4e307, 90, 10, extra="answers: {velocity.B: 1e308}\n"),
    "malformed": "links: [frame, crank\nanswers: {dof: 1}\n",
}


def test_200_files_each_failure_one_error_row_and_jobs_agree(tmp_path):
    # guard: 188 good slider cranks and one file per distinct solver failure: every failure is
    # one error row, every good file passes, exit 1; -j 2 (a process pool) gives the same JSON
    # byte for byte as -j 1.  v_B = w r at 90 deg for an in-line slider crank: 10 * 0.1 = 1 m/s.
    folder = tmp_path / "hw"
    good = _slider(0.1, 0.4, 90, 10, extra="answers: {velocity.B: 1 m/s, omega.rod: 0}\n")
    for i in range(200 - len(FAILURES)):
        write(folder / f"ok_{i:03d}.yaml", good)
    for name, text in FAILURES.items():
        write(folder / f"zz_{name}.yaml", text)
    one = mech("check", str(folder), "-j", "1", "--json")
    no_traceback(one)
    assert one.returncode == 1
    report = strict_json(one.stdout)
    assert len(report["results"]) == 200 and report["summary"]["files"] == 200
    for r in report["results"]:
        stem = Path(r["file"]).stem
        if stem.startswith("zz_"):
            assert r["errors"] == 1 and r["passed"] == 0, r
        else:
            assert (r["passed"], r["failed"], r["errors"]) == (2, 0, 0), r
    two = mech("check", str(folder), "-j", "2", "--json", subprocess_=True)
    assert two.returncode == 1 and "Traceback" not in two.stderr
    assert strict_json(two.stdout) == report


def test_class_reports_identical_with_one_and_two_jobs(problems, tmp_path):
    # guard: --jobs 2 and --jobs 1 give identical JSON, CSV and JUnit for a class of sheets.
    sheets = tmp_path / "sheets"
    write(sheets / "zoë <&>.yaml", "four_bar: {dof: 1, omega.rocker: 4.785 rad/s cw}\n")
    write(
        sheets / "a.yaml",
        'four_bar: {dof: 2}\n"Slider crank, Khurmi Ex. 7.2 / 8.1": {velocity.D: 3.995 m/s}\n',
    )
    write(sheets / "sub" / "b.yml", "slider_crank.yaml: {omega.rod: 5.642 rad/s ccw}\n")
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
