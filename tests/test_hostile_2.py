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
import math
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from hostile_runner import Run, mech, strict_json

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


# =========================================================================================
# 2. mech icentres against a velocity field derived here
# =========================================================================================
def own_field(links, ground, constraints, drive):
    """Velocity field of every link from the constraints alone: link -> (u, w).

    u is the velocity of the link's point at the origin, w its angular velocity, so
    v(P) = u + w k x P.  Constraints: ("pin", P, a, b): v_a(P) = v_b(P); ("normal", P, a, b, n):
    n . (v_a(P) - v_b(P)) = 0 (cam, gear, slot); ("prismatic", P, a, b, t): the same across
    the path t, and w_a = w_b.  drive: (link, w) or ("slide", P, slider, t, speed).
    """
    moving = [lk for lk in links if lk != ground]
    idx = {lk: 3 * i for i, lk in enumerate(moving)}
    n = 3 * len(moving)

    def vrow(lk, P):
        M = np.zeros((2, n))
        if lk != ground:
            i = idx[lk]
            M[0, i], M[1, i + 1], M[0, i + 2], M[1, i + 2] = 1, 1, -P[1], P[0]
        return M

    def wrow(lk):
        r = np.zeros(n)
        if lk != ground:
            r[idx[lk] + 2] = 1
        return r

    rows, rhs = [], []
    for c in constraints:
        if c[0] == "pin":
            _, P, a, b = c
            rows += list(vrow(a, P) - vrow(b, P))
            rhs += [0.0, 0.0]
        elif c[0] == "normal":
            _, P, a, b, nn = c
            rows.append(np.asarray(nn, float) @ (vrow(a, P) - vrow(b, P)))
            rhs.append(0.0)
        elif c[0] == "prismatic":
            _, P, a, b, t = c
            rows.append(np.array([-t[1], t[0]], float) @ (vrow(a, P) - vrow(b, P)))
            rows.append(wrow(a) - wrow(b))
            rhs += [0.0, 0.0]
    if drive[0] == "slide":
        _, P, slider, t, speed = drive
        rows.append(np.asarray(t, float) @ vrow(slider, P))
        rhs.append(speed)
    else:
        rows.append(wrow(drive[0]))
        rhs.append(drive[1])
    A, b = np.array(rows), np.array(rhs)
    x = np.linalg.lstsq(A, b, rcond=None)[0]
    assert np.linalg.matrix_rank(A) == n and np.allclose(A @ x, b, atol=1e-10 * np.abs(b).max())
    out = {ground: (np.zeros(2), 0.0)}
    for lk in moving:
        out[lk] = (x[idx[lk] : idx[lk] + 2], float(x[idx[lk] + 2]))
    return out


def own_icentre(field, a, b):
    """The point where v_a = v_b: P = k x (u_a - u_b) / (w_a - w_b); (None, direction) at infinity."""
    (ua, wa), (ub, wb) = field[a], field[b]
    vrel, dw = ua - ub, wa - wb
    wmax = max(abs(w) for _, w in field.values())
    k = np.array([-vrel[1], vrel[0]])
    if abs(dw) <= 1e-12 * wmax:
        norm = np.linalg.norm(k)
        return None, (k / norm if norm > 1e-12 else None)
    return k / dw, None


def _ang(deg):
    return np.array([math.cos(math.radians(deg)), math.sin(math.radians(deg))])


def _ic_cases():
    cases = {}
    # crank-rocker at its limit position: crank and coupler in line, extended (rocker at rest)
    c = 18.75 / 24
    th = math.acos(c)
    B = np.array([math.cos(th), math.sin(th)])
    C = 4 * B
    cases["crank_rocker_at_limit"] = (
        f"""\
links: [frame, crank, coupler, rocker]
joints:
  A: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  B: {{type: revolute, links: [crank, coupler], at: {pt(B)}}}
  C: {{type: revolute, links: [coupler, rocker], at: {pt(C)}}}
  D: {{type: revolute, links: [rocker, frame], at: [3, 0]}}
drive: {{link: crank, angle: {f(math.degrees(th))}, omega: 10}}
""",
        ["frame", "crank", "coupler", "rocker"],
        [
            ("pin", (0, 0), "frame", "crank"),
            ("pin", B, "crank", "coupler"),
            ("pin", C, "coupler", "rocker"),
            ("pin", (3, 0), "rocker", "frame"),
        ],
        ("crank", 10.0),
    )
    # parallelogram: translating coupler (I13 and I24 at infinity)
    B = _ang(70)
    C = B + np.array([2.0, 0])
    cases["parallelogram_translating_coupler"] = (
        f"""\
links: [frame, crank, coupler, rocker]
joints:
  A: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  B: {{type: revolute, links: [crank, coupler], at: {pt(B)}}}
  C: {{type: revolute, links: [coupler, rocker], at: {pt(C)}}}
  D: {{type: revolute, links: [rocker, frame], at: [2, 0]}}
drive: {{link: crank, angle: 70, omega: 5}}
""",
        ["frame", "crank", "coupler", "rocker"],
        [
            ("pin", (0, 0), "frame", "crank"),
            ("pin", B, "crank", "coupler"),
            ("pin", C, "coupler", "rocker"),
            ("pin", (2, 0), "rocker", "frame"),
        ],
        ("crank", 5.0),
    )
    # crank and slotted lever: slider on a moving guide
    O2 = np.array([0, 0.5])
    A = O2 + 0.12 * _ang(35)
    cases["slotted_lever"] = (
        f"""\
links: [frame, crank, block, lever]
joints:
  O2: {{type: revolute, links: [frame, crank], at: [0, 0.5]}}
  A: {{type: revolute, links: [crank, block]}}
  S: {{type: prismatic, links: [block, lever], path: {{through: O1, toward: B}}}}
  O1: {{type: revolute, links: [lever, frame], at: [0, 0]}}
lengths: {{O2A: 0.12}}
points:
  B: {{link: lever, at: {pt(1.3 * A)}}}
drive: {{link: crank, angle: 35, omega: 20}}
""",
        ["frame", "crank", "block", "lever"],
        [
            ("pin", O2, "frame", "crank"),
            ("pin", A, "crank", "block"),
            ("prismatic", A, "block", "lever", A / np.linalg.norm(A)),
            ("pin", (0, 0), "lever", "frame"),
        ],
        ("crank", 20.0),
    )
    # Scotch yoke: pin in a slot of a yoke that slides on the frame
    P = 0.1 * _ang(60)
    cases["slot_scotch_yoke"] = (
        f"""\
links: [frame, crank, yoke]
joints:
  O: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  P: {{type: slot, links: [crank, yoke], path: {{through: Q, angle: 90}}}}
  Y: {{type: prismatic, links: [yoke, frame], path: {{through: [0, 0], angle: 0}}, point: Q}}
lengths: {{OP: 0.1}}
points:
  Q: {{link: yoke, at: [{f(P[0])}, 0]}}
drive: {{link: crank, angle: 60, omega: 10, direction: ccw}}
""",
        ["frame", "crank", "yoke"],
        [
            ("pin", (0, 0), "frame", "crank"),
            ("normal", P, "crank", "yoke", (1, 0)),
            ("prismatic", (P[0], 0), "yoke", "frame", (1, 0)),
        ],
        ("crank", 10.0),
    )
    n20 = (math.sin(math.radians(20)), math.cos(math.radians(20)))
    cases["gears_external"] = (
        """\
links: [frame, g1, g2]
joints:
  O1: {type: revolute, links: [frame, g1], at: [0, 0]}
  O2: {type: revolute, links: [frame, g2], at: [0.15, 0]}
  M: {type: gear, links: [g1, g2], radii: [0.05, 0.1], pressure_angle: 20}
drive: {link: g1, omega: 30, direction: cw}
""",
        ["frame", "g1", "g2"],
        [
            ("pin", (0, 0), "frame", "g1"),
            ("pin", (0.15, 0), "frame", "g2"),
            ("normal", (0.05, 0), "g1", "g2", n20),
        ],
        ("g1", -30.0),
    )
    cases["gears_internal"] = (
        """\
links: [frame, pinion, ring]
joints:
  O1: {type: revolute, links: [frame, pinion], at: [0, 0]}
  O2: {type: revolute, links: [frame, ring], at: [0.15, 0]}
  M: {type: gear, links: [pinion, ring], radii: [0.05, 0.2], internal: true, pressure_angle: 20}
drive: {link: pinion, omega: 30, direction: ccw}
""",
        ["frame", "pinion", "ring"],
        [
            ("pin", (0, 0), "frame", "pinion"),
            ("pin", (0.15, 0), "frame", "ring"),
            ("normal", (-0.05, 0), "pinion", "ring", n20),
        ],
        ("pinion", 30.0),
    )
    # a wheel rolling on the ground, driven through a crank and rod
    Bc, rw = 0.1 * _ang(60), 0.05
    C = np.array([Bc[0] + math.sqrt(0.3**2 - (rw - Bc[1]) ** 2), rw])
    cases["rolling_wheel"] = (
        f"""\
links: [frame, crank, rod, wheel]
joints:
  O: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  A: {{type: revolute, links: [crank, rod], at: {pt(Bc)}}}
  C: {{type: revolute, links: [rod, wheel], at: {pt(C)}}}
  R: {{type: rolling, links: [wheel, frame], at: [{f(C[0])}, 0]}}
drive: {{link: crank, angle: 60, omega: 10}}
""",
        ["frame", "crank", "rod", "wheel"],
        [
            ("pin", (0, 0), "frame", "crank"),
            ("pin", Bc, "crank", "rod"),
            ("pin", C, "rod", "wheel"),
            ("pin", (C[0], 0), "wheel", "frame"),
        ],
        ("crank", 10.0),
    )
    cases["cam_offset_follower"] = (
        """\
links: [frame, cam, follower]
joints:
  O: {type: revolute, links: [frame, cam], at: [0, 0]}
  G: {type: prismatic, links: [follower, frame], path: {through: [0.01, 0], angle: 90}, point: T}
  K: {type: cam, links: [cam, follower], at: [0.01, 0.04], normal: 120}
points:
  T: {link: follower, at: [0.01, 0.04]}
drive: {link: cam, omega: 10}
""",
        ["frame", "cam", "follower"],
        [
            ("pin", (0, 0), "frame", "cam"),
            ("prismatic", (0.01, 0.04), "follower", "frame", (0, 1)),
            ("normal", (0.01, 0.04), "cam", "follower", _ang(120)),
        ],
        ("cam", 10.0),
    )
    Aq, Bq = np.array([math.cos(math.radians(30)), 0]), np.array([0, 0.5])
    cases["elliptic_trammel"] = (
        f"""\
links: [frame, sx, bar, sy]
joints:
  PA: {{type: prismatic, links: [sx, frame], path: {{through: [0, 0], angle: 0}}, point: A}}
  A: {{type: revolute, links: [sx, bar], at: {pt(Aq)}}}
  B: {{type: revolute, links: [bar, sy], at: {pt(Bq)}}}
  PB: {{type: prismatic, links: [sy, frame], path: {{through: [0, 0], angle: 90}}, point: B}}
drive: {{link: bar, omega: 2, about: A}}
""",
        ["frame", "sx", "bar", "sy"],
        [
            ("prismatic", Aq, "sx", "frame", (1, 0)),
            ("pin", Aq, "sx", "bar"),
            ("pin", Bq, "bar", "sy"),
            ("prismatic", Bq, "sy", "frame", (0, 1)),
        ],
        ("bar", 2.0),
    )
    st = dict(O1=(0, 0), a=(1, 1), b=(1.2, -0.4), d=(2.5, 1.8), e=(2.8, 0.3), c=(3.6, 1.5), O2=(4, 0.2))
    pairs = dict(
        O1=("frame", "T1"),
        a=("T1", "B1"),
        b=("T1", "B2"),
        d=("B1", "T2"),
        e=("B2", "T2"),
        c=("T2", "B4"),
        O2=("B4", "frame"),
    )
    cases["stephenson_six_bar"] = (
        "links: [frame, T1, B1, B2, T2, B4]\njoints:\n"
        + "".join(
            f"  {k}: {{type: revolute, links: [{a}, {b}], at: {pt(st[k])}}}\n" for k, (a, b) in pairs.items()
        )
        + "drive: {link: T1, omega: 10, angle: 45}\n",
        ["frame", "T1", "B1", "B2", "T2", "B4"],
        [("pin", st[k], a, b) for k, (a, b) in pairs.items()],
        ("T1", 10.0),
    )
    t = np.array([0.2, 1.4]) / math.hypot(0.2, 1.4)
    cases["six_bar_slider_on_moving_rocker"] = (
        """\
links: [frame, crank, coupler, rocker, block, link5]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler], at: [0.5, 0.866]}
  C: {type: revolute, links: [coupler, rocker], at: [2.2, 1.4]}
  D: {type: revolute, links: [rocker, frame], at: [2, 0]}
  S: {type: prismatic, links: [block, rocker], path: {through: D, toward: C}, point: F}
  F: {type: revolute, links: [block, link5], at: [2.1, 0.7]}
  G: {type: revolute, links: [link5, frame], at: [3.5, 1.0]}
drive: {link: crank, omega: 10}
""",
        ["frame", "crank", "coupler", "rocker", "block", "link5"],
        [
            ("pin", (0, 0), "frame", "crank"),
            ("pin", (0.5, 0.866), "crank", "coupler"),
            ("pin", (2.2, 1.4), "coupler", "rocker"),
            ("pin", (2, 0), "rocker", "frame"),
            ("prismatic", (2.1, 0.7), "block", "rocker", t),
            ("pin", (2.1, 0.7), "block", "link5"),
            ("pin", (3.5, 1.0), "link5", "frame"),
        ],
        ("crank", 10.0),
    )
    # eight links, some I-centres beyond Kennedy (from tests/icentres; positions in mm)
    j8 = dict(
        P02=((32.383, 15.085), "frame", "crank"),
        P03=((65.093, 7.244), "frame", "L3"),
        P06=((53.588, 36.569), "frame", "L6"),
        P12=((5.800, 50.744), "L1", "crank"),
        P14=((3.750, 43.365), "L1", "L4"),
        P15=((6.986, 9.071), "L1", "L5"),
        P35=((42.452, 82.685), "L3", "L5"),
        P46=((12.380, 22.324), "L4", "L6"),
        P47=((62.743, 94.771), "L4", "L7"),
        P57=((57.710, 39.668), "L5", "L7"),
    )
    cases["eight_links_beyond_kennedy"] = (
        "units: {length: mm, angle: deg}\nlinks: [frame, L1, crank, L3, L4, L5, L6, L7]\njoints:\n"
        + "".join(
            f"  {k}: {{type: revolute, links: [{a}, {b}], at: [{p[0]}, {p[1]}]}}\n"
            for k, (p, a, b) in j8.items()
        )
        + "drive: {link: crank, omega: 6}\n",
        ["frame", "L1", "crank", "L3", "L4", "L5", "L6", "L7"],
        [("pin", (p[0] / 1000, p[1] / 1000), a, b) for p, a, b in j8.values()],
        ("crank", 6.0),
    )
    # slider crank driven by its piston (the driver has w = 0: the I-centre method must still work)
    A = 0.1 * _ang(45)
    Bx = A[0] + math.sqrt(0.4**2 - A[1] ** 2)
    cases["slider_driven_crank"] = (
        f"""\
links: [frame, crank, rod, piston]
joints:
  O: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  A: {{type: revolute, links: [crank, rod], at: {pt(A)}}}
  B: {{type: revolute, links: [rod, piston], near: [0.45, 0]}}
  P: {{type: prismatic, links: [piston, frame], path: {{through: [0, 0], angle: 0}}}}
lengths: {{AB: 0.4}}
drive: {{joint: P, speed: 2}}
""",
        ["frame", "crank", "rod", "piston"],
        [
            ("pin", (0, 0), "frame", "crank"),
            ("pin", A, "crank", "rod"),
            ("pin", (Bx, 0), "rod", "piston"),
            ("prismatic", (Bx, 0), "piston", "frame", (1, 0)),
        ],
        ("slide", (Bx, 0), "piston", (1, 0), 2.0),
    )
    return cases


IC_CASES = _ic_cases()


@pytest.mark.parametrize("case", sorted(IC_CASES))
def test_every_icentre_and_omega_agrees_with_an_independent_velocity_field(tmp_path, case):
    # guard: every I-centre (finite: to 1e-9 of its distance; at infinity: its direction) and
    # every w by the I-centre method agree with the field solved here from the constraints.
    text, links, constraints, drive = IC_CASES[case]
    m = write(tmp_path / f"{case}.yaml", text)
    p = mech("icentres", "--json", str(m))
    no_traceback(p)
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    n = len(links)
    assert d["count"] == n * (n - 1) // 2 == len(d["icentres"])
    field = own_field(links, "frame", constraints, drive)
    size = max(np.linalg.norm(np.subtract(c[1], e[1])) for c in constraints for e in constraints)
    for ic in d["icentres"]:
        a, b = ic["links"]
        P, direction = own_icentre(field, a, b)
        if P is None and direction is None:  # no relative motion (a link at rest on ground): any point
            continue
        if P is None:
            assert ic["at_infinity"] and ic["point"] is None, ic
            assert abs(abs(float(np.dot(direction, ic["direction"]))) - 1) < 1e-9, ic
        else:
            assert ic["point"] is not None, ic
            assert np.linalg.norm(np.array(ic["point"]) - P) <= 1e-9 * max(size, np.linalg.norm(P)), (ic, P)
    for row in d["omega"]:
        w = field[row["link"]][1]
        wmax = max(abs(x) for _, x in field.values())
        assert row["by_icentres"] is not None and abs(row["by_icentres"] - w) <= 1e-9 * wmax, (row, w)


def test_icentres_closed_forms_for_slot_gears_and_cam(tmp_path):
    # guard: textbook closed forms, independent of the field above.
    def ic(case, name):
        m = write(tmp_path / f"{case}.yaml", IC_CASES[case][0])
        p = mech("icentres", "--json", str(m))
        assert p.returncode == 0, p.stderr
        return {i["name"]: i for i in strict_json(p.stdout)["icentres"]}[name]

    # Scotch yoke: I23 on the normal to the slot through the pin (y = r sin th) and on x = 0.
    assert ic("slot_scotch_yoke", "I23")["point"] == pytest.approx(
        [0, 0.1 * math.sin(math.radians(60))], abs=1e-12
    )
    # gears: the pitch point divides the centre line in the ratio of the radii
    assert ic("gears_external", "I23")["point"] == pytest.approx([0.05, 0], abs=1e-12)
    assert ic("gears_internal", "I23")["point"] == pytest.approx([-0.05, 0], abs=1e-12)  # outside O1O2
    # cam: the common normal through T meets the line of I12-I13 (y = 0): x = 0.01 - 0.04 cot(120 deg)
    x = 0.01 - 0.04 / math.tan(math.radians(120))
    assert ic("cam_offset_follower", "I23")["point"] == pytest.approx([x, 0], abs=1e-12)


def test_icentres_units_mm_scale_points_not_directions(tmp_path):
    # guard: --units mm multiplies every finite point by 1000 and leaves directions and w alone.
    m = write(tmp_path / "m.yaml", IC_CASES["slotted_lever"][0])
    si = strict_json(mech("icentres", "--json", str(m)).stdout)
    mm = strict_json(mech("icentres", "--json", "--units", "mm", str(m)).stdout)
    assert mm["units"]["length"] == "mm"
    for a, b in zip(si["icentres"], mm["icentres"], strict=True):
        if a["point"] is None:
            assert b["point"] is None and b["direction"] == pytest.approx(a["direction"])
        else:
            assert b["point"] == pytest.approx([1000 * v for v in a["point"]], rel=1e-12, abs=1e-9)
    assert [o["by_icentres"] for o in mm["omega"]] == pytest.approx([o["by_icentres"] for o in si["omega"]])


def test_icentres_coincident_pivots_and_toggle_do_not_crash(tmp_path):
    # guard: two ground pivots at one point (crank, coupler, rocker then turn as one body): an
    # undetermined centre is said so, exit 0; a four-bar at its toggle is refused, exit 2.
    m = write(
        tmp_path / "c.yaml",
        """\
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler], at: [1, 0]}
  C: {type: revolute, links: [coupler, rocker], at: [0.5, 1]}
  D: {type: revolute, links: [rocker, frame], at: [0, 0]}
drive: {link: crank, omega: 10}
""",
    )
    p = mech("icentres", "--json", str(m))
    no_traceback(p)
    assert p.returncode == 0
    d = strict_json(p.stdout)
    by = {i["name"]: i for i in d["icentres"]}
    assert by["I13"]["point"] == pytest.approx([0, 0], abs=1e-12)  # the body turns about A = D
    assert all(o["by_icentres"] == pytest.approx(10.0) for o in d["omega"])
    t = write(tmp_path / "t.yaml", FAILURES["toggle"].split("answers:")[0])
    p = mech("icentres", str(t))
    no_traceback(p)
    assert p.returncode == 2 and "error:" in p.stderr


# =========================================================================================
# 3. mech sweep
# =========================================================================================
CR = dict(a=1.0, b=3.0, c=2.5, d=3.0)  # crank-rocker: Grashof, crank the shortest
CRANK_ROCKER = """\
name: crank rocker
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [3, 2]}
  D: {type: revolute, links: [rocker, frame], at: [3, 0]}
lengths: {AB: 1, BC: 3, CD: 2.5}
drive: {link: crank, angle: 90, omega: 10, direction: ccw}
"""


def crank_rocker_closed_form(theta_deg, omega=10.0):
    """Own closed form (C above AD, left of B->D): rocker angle (deg), w_rocker, w_coupler, |v_C|."""
    a, b, c, d = CR["a"], CR["b"], CR["c"], CR["d"]
    th = np.radians(np.asarray(theta_deg, float))
    B = np.stack([a * np.cos(th), a * np.sin(th)], -1)
    D = np.array([d, 0.0])
    BD = D - B
    r = np.linalg.norm(BD, axis=-1)
    x = (b * b - c * c + r * r) / (2 * r)
    h = np.sqrt(b * b - x * x)
    u = BD / r[..., None]
    nrm = np.stack([-u[..., 1], u[..., 0]], -1)  # left of B->D
    C = B + x[..., None] * u + h[..., None] * nrm
    vB = omega * np.stack([-B[..., 1], B[..., 0]], -1)
    BC, DC = C - B, C - D
    # vB + w3 k x BC = w4 k x DC  ->  [ -BCy  DCy ; BCx  -DCx ] [w3 w4]^T = -vB
    det = (-BC[..., 1]) * (-DC[..., 0]) - DC[..., 1] * BC[..., 0]
    w3 = ((-vB[..., 0]) * (-DC[..., 0]) - DC[..., 1] * (-vB[..., 1])) / det
    w4 = ((-BC[..., 1]) * (-vB[..., 1]) - (-vB[..., 0]) * BC[..., 0]) / det
    psi = np.degrees(np.arctan2(DC[..., 1], DC[..., 0]))
    return psi, w4, w3, np.abs(w4) * c


def crank_rocker_limits():
    """Crank angles of the rocker's limit positions and the time ratio (180 + a)/(180 - a)."""
    a, b, c, d = CR["a"], CR["b"], CR["c"], CR["d"]

    def psi(AC):  # angle DAC of triangle A, D, C
        return math.degrees(math.acos((AC * AC + d * d - c * c) / (2 * AC * d)))

    t_ext, t_fold = psi(a + b), psi(b - a) + 180.0  # crank along AC; crank opposite to AC
    alpha = t_fold - t_ext - 180.0
    return t_ext, t_fold, (180 + alpha) / (180 - alpha)


def sweep_json(path, *args):
    p = mech("sweep", "--json", str(path), *args)
    no_traceback(p)
    assert p.returncode == 0, p.stderr
    return strict_json(p.stdout)


@pytest.mark.parametrize("rng", [("0", "360"), ("-180", "180"), ("720", "1080"), ("0", "720")])
def test_crank_rocker_time_ratio_and_dead_centres_closed_form(tmp_path, rng):
    # guard: dead centres where crank and coupler are in line, ratio (180 + a)/(180 - a).
    t_ext, t_fold, ratio = crank_rocker_limits()
    m = write(tmp_path / "cr.yaml", CRANK_ROCKER)
    d = sweep_json(m, "--from", rng[0], "--to", rng[1], "--steps", "36")
    assert d["time_ratio"]["ratio"] == pytest.approx(ratio, rel=1e-10)
    lo, hi = float(rng[0]), float(rng[1])
    want = sorted(t + 360 * k for t in (t_ext, t_fold) for k in range(-2, 4) if lo <= t + 360 * k <= hi)
    assert [e["angle"] for e in d["dead_centres"]] == pytest.approx(want, abs=1e-8)


@pytest.mark.parametrize("rng, steps", [(("90", "-90"), "360"), (("90", "-90"), "12"), (("360", "0"), "360")])
def test_descending_sweep_dead_centres_and_time_ratio_are_not_refined(tmp_path, rng, steps):
    # DEFECT: (numbers silently wrong) the same crank-rocker swept downwards (--from 90 --to -90, or
    # 360 -> 0): the dead centre is printed at 38.617188 deg (12 steps: 38.671875, 0.05 deg off)
    # instead of 38.624833 deg, and the time ratio 1.210708 instead of 1.210573; the rocker's
    # angle there is off too.  Ascending sweeps are right to 1e-12; cli.md promises a dead
    # centre's angle to about 1e-15 rad.  (The bracket is used as (lo, hi) although lo > hi.)
    t_ext, t_fold, ratio = crank_rocker_limits()
    m = write(tmp_path / "cr.yaml", CRANK_ROCKER)
    d = sweep_json(m, "--from", rng[0], "--to", rng[1], "--steps", steps)
    got = sorted(e["angle"] for e in d["dead_centres"])
    lo, hi = sorted(map(float, rng))
    want = sorted(t + 360 * k for t in (t_ext, t_fold) for k in (-1, 0, 1) if lo <= t + 360 * k <= hi)
    assert got == pytest.approx(want, abs=1e-8)
    if d["time_ratio"] is not None:
        assert d["time_ratio"]["ratio"] == pytest.approx(ratio, rel=1e-10)


@pytest.mark.parametrize("offset", [0.0, 0.05])
def test_slider_crank_dead_centres_closed_form(tmp_path, offset):
    # guard: in line, dead centres at exactly 0 and 180 deg (x = L + r, L - r), ratio 1;
    # offset e: crank along OB at asin(e/(L+r)), opposite OB at 180 + asin(e/(L-r)).
    r, L = 0.1, 0.4
    m = write(tmp_path / "sc.yaml", _slider(r, L, 90, 10, offset=offset))
    d = sweep_json(m, "--steps", "7")
    t1 = math.degrees(math.asin(offset / (L + r)))
    t2 = 180 + math.degrees(math.asin(offset / (L - r)))
    alpha = t2 - t1 - 180
    got = [(e["angle"], e["position"]) for e in d["dead_centres"]]
    assert [g[0] for g in got] == pytest.approx([t1, t2], abs=1e-9)
    assert [g[1] for g in got] == pytest.approx(
        [math.sqrt((L + r) ** 2 - offset**2), math.sqrt((L - r) ** 2 - offset**2)], rel=1e-12
    )
    if offset == 0:
        assert d["dead_centres"][0]["angle"] == 0.0
    assert d["time_ratio"]["ratio"] == pytest.approx((180 + alpha) / (180 - alpha), rel=1e-10)


def _dense_extremes(lo, hi, n=400_001):
    th = np.linspace(lo, hi, n)
    psi, w4, w3, vc = crank_rocker_closed_form(th)
    return th, {"angle.rocker": psi, "omega.rocker": w4, "omega.coupler": w3, "velocity.C": vc}


@pytest.mark.parametrize("rng", [("300", "420"), ("0", "360"), ("10", "100")])
def test_extremes_match_a_dense_evaluation_of_the_closed_form(tmp_path, rng):
    # guard: 12 steps give the extremes of 400 001 points of our own closed form, and the angles.
    m = write(tmp_path / "cr.yaml", CRANK_ROCKER)
    d = sweep_json(m, "--from", rng[0], "--to", rng[1], "--steps", "12")
    th, dense = _dense_extremes(float(rng[0]), float(rng[1]))
    got = {e["quantity"]: e for e in d["extremes"]}
    for key, v in dense.items():
        e = got[key]
        scale = float(np.max(np.abs(v)))
        assert e["max"] == pytest.approx(float(v.max()), abs=1e-9 * scale), key
        assert abs(e["max_angle"] - th[v.argmax()]) < 1e-2, (key, e)
        if key == "velocity.C" and float(v.min()) < 1e-3 * scale:
            # |v_C| has a V-shaped minimum, zero where the rocker stops (a dead centre in range):
            # the dense grid only brackets it, the exact least value is 0
            assert 0 <= e["min"] <= 1e-9 * scale, e
        else:
            assert e["min"] == pytest.approx(float(v.min()), abs=1e-9 * scale), key
        assert abs(e["min_angle"] - th[v.argmin()]) < 1e-2, (key, e)


def test_newton_sweep_extremes_are_read_off_a_parabola_and_wrong(tmp_path):
    # DEFECT: (numbers silently wrong) the same crank-rocker with --method newton (what `auto`
    # uses for every chain that does not decompose into dyads): the extremes are the vertex of
    # a parabola through three grid values, not refined.  With 36 steps the rocker's largest
    # angle is 138.5911 deg, beyond its limit position 138.5904 deg (impossible), and the least
    # |v_C| is 0.419 m/s at 39.65 deg -- the rocker actually stops (v_C = 0) at 38.62 deg.
    # cli.md: "12 steps give the same extreme value as 3,600 (to about 1e-15 relative)".
    m = write(tmp_path / "cr.yaml", CRANK_ROCKER)
    d = sweep_json(m, "--steps", "36", "--method", "newton")
    _, dense = _dense_extremes(0.0, 360.0)
    got = {e["quantity"]: e for e in d["extremes"]}
    for key, v in dense.items():
        scale = float(np.max(np.abs(v)))
        assert got[key]["max"] == pytest.approx(float(v.max()), abs=1e-6 * scale), (key, got[key])
        least = 0.0 if key == "velocity.C" else float(v.min())  # the rocker stops: |v_C| = 0
        assert got[key]["min"] == pytest.approx(least, abs=1e-6 * scale), (key, got[key])


def test_gear_sweep_extremes_lie_outside_the_values_swept(tmp_path):
    # DEFECT: (numbers silently wrong) the shipped gear pair (20/40 teeth, pinion 0..360 deg): the
    # wheel turns -theta/2, so angle.wheel runs from 0 to -180 deg (the series says so), but the
    # extremes say max 12.656 deg at 16.875 deg and min -192.656 deg at 343.125 deg -- values the
    # wheel never takes, at angles where it is elsewhere.  The full-turn "wrap" assumes every
    # quantity repeats each crank turn; a 2:1 wheel does not.
    d = sweep_json(EXAMPLES / "gear_pair.yaml", "--steps", "8", "--quantity", "angle.wheel")
    assert d["series"]["angle.wheel"] == pytest.approx([-th / 2 for th in d["series"]["angle"]], abs=1e-9)
    (e,) = d["extremes"]
    assert e["max"] == pytest.approx(0.0, abs=1e-9) and e["max_angle"] == pytest.approx(0.0, abs=1e-6)
    assert e["min"] == pytest.approx(-180.0, abs=1e-9) and e["min_angle"] == pytest.approx(360.0, abs=1e-6)


def test_one_step_over_a_full_turn_reports_no_extremes_and_says_nothing(tmp_path):
    # DEFECT: (low) --steps 1 from 0 to 360: both angles are the same position, and the sweep
    # silently reports no extremes, no dead centres and no time ratio ("extremes": []), while
    # --steps 2 finds all of them (refined) and --steps 1 over 0..90 finds its dead centre.
    # Should: refine from the range as for --steps 2, or a note that one step cannot show them.
    m = write(tmp_path / "cr.yaml", CRANK_ROCKER)
    d = sweep_json(m, "--steps", "1")
    assert d["extremes"] or any("step" in n for n in d["notes"][1:]), d


def test_sweep_steps_beyond_the_memory_budget_are_refused(tmp_path):
    # --steps 10,000,000 needs several GB; under a 1.5 GB address-space limit it once died with
    # numpy's _ArrayMemoryError traceback.  It is refused (exit 2), saying how many steps fit.
    import resource

    m = write(tmp_path / "cr.yaml", CRANK_ROCKER)

    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (1_500_000_000, 1_500_000_000))

    p = mech("sweep", str(m), "--steps", "10000000", subprocess_=True, preexec_fn=limit, timeout=60)
    assert "Traceback" not in p.stderr, p.stderr[-600:]
    assert p.returncode == 2, p.stdout[-600:]
    assert "give at most" in p.stderr


@pytest.mark.parametrize(
    "quantity",
    [
        "omega.nolink",
        "velocity.Z",
        "displacement.O",
        "sliding.A",
        "angle.frame",
        "omega",
        "velocity.B.z",
        "position.B",
        "acceleration.B",
        "alpha.rod",
        "",
        "omega.rod.x.y",
        "velocity.<&>",
    ],
)
def test_sweep_unknown_quantities_are_usage_errors(tmp_path, quantity):
    # guard: a quantity that does not exist (or needs a higher --level) is exit 2 with a message.
    m = write(tmp_path / "sc.yaml", _slider(0.1, 0.4, 90, 10))
    p = mech("sweep", str(m), "--steps", "4", "--quantity", quantity)
    no_traceback(p)
    assert p.returncode == 2 and "error:" in p.stderr


def test_sweep_csv_units_and_empty_cells_in_a_gap(tmp_path):
    # guard: AB = BC = CD = 1, AD = 2.5 assembles only while |BD| <= 2, i.e. cos(th) >= 0.65:
    # toggles at +-acos(0.65); the CSV header carries units (mm, mm/s with --units mm), the
    # cells in the gap are empty, and the rest equals the JSON series in the same units.
    m = write(
        tmp_path / "g.yaml",
        """\
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [1.8, 1]}
  D: {type: revolute, links: [rocker, frame], at: [2.5, 0]}
lengths: {AB: 1, BC: 1, CD: 1}
drive: {link: crank, angle: 30, omega: 10}
""",
    )
    out = tmp_path / "s.csv"
    q = ("--quantity", "velocity.C", "--quantity", "angle.rocker", "--quantity", "position.C.x")
    d = sweep_json(m, "--steps", "36", "--units", "mm", "--csv", str(out), *q)
    t = math.degrees(math.acos(0.65))
    assert [x["angle"] for x in d["toggles"]] == pytest.approx([t, 360 - t], abs=1e-7)
    rows = list(csv.reader(io.StringIO(out.read_text(encoding="utf-8"))))
    assert rows[0] == ["angle [deg]", "velocity.C [mm/s]", "angle.rocker [deg]", "position.C.x [mm]"]
    assert len(rows) == 38
    for row, a in zip(rows[1:], d["series"]["angle"], strict=True):
        assert float(row[0]) == pytest.approx(a)
        inside = math.cos(math.radians(a)) >= 0.65 - 1e-12
        assert (row[1] != "") == inside, row
    for k, key in enumerate(("velocity.C", "angle.rocker", "position.C.x"), 1):
        col = [float(r[k]) if r[k] else None for r in rows[1:]]
        series = d["series"][key]
        # empty cells exactly where the JSON has null; numbers equal where both have one
        # (compared apart: pytest.approx does not take None in every version)
        assert [c is None for c in col] == [v is None for v in series]
        both = [(c, v) for c, v in zip(col, series, strict=True) if c is not None]
        assert [c for c, _ in both] == pytest.approx([v for _, v in both], rel=1e-12)
    # v_C at 0 deg from our own velocity loop, in mm/s: the crank's w r = 10 m/s = 10000 mm/s
    B, D = np.array([1.0, 0]), np.array([2.5, 0])
    x = (1 - 1 + 1.5**2) / (2 * 1.5)  # C on circles of radius 1 about B and D, above BD
    C = B + np.array([x, math.sqrt(1 - x * x)])
    vB = np.array([0, 10.0])
    M = np.array([[-(C - B)[1], (C - D)[1]], [(C - B)[0], -(C - D)[0]]])
    _w3, w4 = np.linalg.solve(M, -vB)
    assert float(rows[1][1]) == pytest.approx(1000 * abs(w4) * 1.0, rel=1e-10)


def test_sweep_json_units_mm_are_si_times_1000(tmp_path):
    # guard: --units mm: dead centre positions, extremes and series of lengths and speeds x 1000;
    # angles and angular velocities unchanged; strict JSON.
    m = write(tmp_path / "sc.yaml", _slider(0.1, 0.4, 90, 10, offset=0.05))
    q = ("--quantity", "sliding.P", "--quantity", "omega.rod", "--quantity", "displacement.P")
    si, mm = sweep_json(m, "--steps", "24", *q), sweep_json(m, "--steps", "24", "--units", "mm", *q)
    assert [e["position"] * 1000 for e in si["dead_centres"]] == pytest.approx(
        [e["position"] for e in mm["dead_centres"]]
    )
    for a, b in zip(si["extremes"], mm["extremes"], strict=True):
        k = 1.0 if a["quantity"].startswith("omega") else 1000.0
        assert (b["max"], b["min"]) == pytest.approx((k * a["max"], k * a["min"]))
        assert b["unit"] == {"sliding.P": "mm/s", "omega.rod": "rad/s", "displacement.P": "mm"}[a["quantity"]]
    assert mm["series"]["sliding.P"] == pytest.approx([1000 * v for v in si["series"]["sliding.P"]])


# =========================================================================================
# 4. mech draw
# =========================================================================================
HOSTILE_DRAW = """\
name: "Crank <&\\"'> \\u00e9 ]]> </svg> <!-- x"
links: ["fr<am>e&", "cr'a\\"nk", rod, "pist\\u00f6n"]
ground: "fr<am>e&"
joints:
  "O<1>": {type: revolute, links: ["fr<am>e&", "cr'a\\"nk"], at: [0, 0]}
  "A&": {type: revolute, links: ["cr'a\\"nk", rod]}
  B: {type: revolute, links: [rod, "pist\\u00f6n"], near: [0.5, 0]}
  P: {type: prismatic, links: ["pist\\u00f6n", "fr<am>e&"], path: {through: [0, 0], angle: 0}}
lengths: {"O<1>-A&": 0.1, "A&-B": 0.4}
drive: {link: "cr'a\\"nk", angle: 60, omega: 10}
"""


def test_draw_hostile_names_give_well_formed_svg(tmp_path):
    # guard: <, &, quotes, unicode and "]]>" / "<!--" in link, joint and mechanism names: the SVG
    # parses and carries the names as text.
    m = write(tmp_path / "h.yaml", HOSTILE_DRAW)
    out = tmp_path / "h.svg"
    p = mech("draw", str(m), "-o", str(out), "--velocity", "--acceleration", "--icentres", "--json")
    no_traceback(p)
    assert p.returncode == 0, p.stderr
    strict_json(p.stdout)
    root = ET.parse(out).getroot()
    texts = ["".join(t.itertext()) for t in root.iter("{http://www.w3.org/2000/svg}text")]
    assert "Crank <&\"'> é ]]> </svg> <!-- x" in texts
    assert "O<1>" in texts and "A&" in texts


def test_draw_control_character_in_name_gives_malformed_svg(tmp_path):
    # DEFECT: (low) a mechanism name with a control character (YAML "\\x01", e.g. pasted text) is
    # written raw into <title> and the heading: the SVG is not well-formed XML and browsers
    # refuse to show it.  Should: drop or replace characters XML 1.0 cannot hold.
    m = write(tmp_path / "h.yaml", HOSTILE_DRAW.replace("\\u00e9 ]]>", "\\x01 ]]>", 1))
    out = tmp_path / "h.svg"
    p = mech("draw", str(m), "-o", str(out))
    no_traceback(p)
    assert p.returncode == 0
    ET.parse(out)


def test_draw_at_rest_states_an_absurd_scale(tmp_path):
    # DEFECT: (low) omega 0: the velocity and acceleration polygons shrink to the pole, and the
    # drawing states "1 cm = 2×10^-301 m/s" (and m/s²) as their scale.  Should: say the
    # mechanism is at rest (no scale), or use a nominal round scale.
    m = write(tmp_path / "r.yaml", HOSTILE_DRAW.replace("omega: 10", "omega: 0"))
    out = tmp_path / "r.svg"
    p = mech("draw", str(m), "-o", str(out), "--velocity", "--acceleration", "--json")
    no_traceback(p)
    assert p.returncode == 0
    ET.parse(out)
    scales = strict_json(p.stdout)["scales"]
    exps = [int(x) for s in scales for x in re.findall(r"10\^(-?\d+)", s)]
    assert all(abs(e) < 30 for e in exps), scales


@pytest.mark.parametrize(
    "size, scale", [(1e-7, "1 cm = 1×10^-7 m"), (1.0, "1 cm = 1 m"), (1e9, "1 cm = 1×10^9 m")]
)
def test_draw_tiny_and_huge_mechanisms(tmp_path, size, scale):
    # guard: a slider crank of crank 0.1 um and of 1e9 m: same sheet size, round stated scales,
    # well-formed SVG without nan/inf in any attribute.
    m = write(tmp_path / "s.yaml", _slider(size, 4 * size, 60, 10))
    out = tmp_path / "s.svg"
    p = mech("draw", str(m), "-o", str(out), "--velocity", "--acceleration", "--icentres", "--json")
    no_traceback(p)
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    assert d["scales"][0] == scale
    assert 100 < d["size_mm"][0] < 500 and 50 < d["size_mm"][1] < 500
    text = out.read_text(encoding="utf-8")
    assert not re.search(r'="[^"]*(nan|inf)[^"]*"', text, re.I)
    ET.fromstring(text.encode("utf-8"))


def test_draw_png_without_matplotlib_and_bad_suffix_are_exit_2(tmp_path):
    # guard: matplotlib blocked in a fresh interpreter (it is installed here): .png -> exit 2
    # with the pip hint, nothing written; an unknown suffix -> exit 2 before drawing.
    m = write(tmp_path / "s.yaml", _slider(0.1, 0.4, 60, 10))
    png = tmp_path / "s.png"
    code = (
        "import sys; sys.modules['matplotlib'] = None\n"
        "from mech.cli import main\n"
        f"main(['draw', {str(m)!r}, '-o', {str(png)!r}])\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr, proc.stderr[-800:]
    assert "planar-mech[plot]" in proc.stderr and not png.exists()
    p = mech("draw", str(m), "-o", str(tmp_path / "s.pdf"))
    no_traceback(p)
    assert p.returncode == 2


# =========================================================================================
# 5. JSON of every command
# =========================================================================================
@pytest.mark.parametrize(
    "case", ["parallelogram_translating_coupler", "gears_internal", "cam_offset_follower"]
)
def test_json_strict_and_keys_stable_for_every_command(tmp_path, case):
    # guard: every command's JSON is strict (no NaN/Infinity) with the same top-level keys for
    # different mechanisms, including centres at infinity and links at rest.
    m = write(tmp_path / "m.yaml", IC_CASES[case][0])
    keys = {
        "position": {
            "mechanism",
            "level",
            "units",
            "size",
            "drives",
            "links",
            "points",
            "relative",
            "sliders",
            "rubbing",
            "mobility",
            "notes",
        },
        "icentres": {
            "file",
            "name",
            "units",
            "links",
            "count",
            "formula",
            "kennedy_rounds",
            "icentres",
            "max_check",
            "omega",
            "notes",
        },
    }
    for cmd in ("dof", "classify", "position", "velocity", "acceleration", "icentres"):
        p = mech(cmd, "--json", str(m))
        no_traceback(p)
        if p.returncode == 2:  # acceleration of a cam is refused (no curvature): fine
            assert cmd == "acceleration" and "error:" in p.stderr
            continue
        assert p.returncode == 0, (cmd, p.stderr)
        d = strict_json(p.stdout)
        if cmd in keys:
            assert keys[cmd] <= set(d), (cmd, set(d))
    out = tmp_path / "m.svg"
    p = mech("draw", "--json", str(m), "-o", str(out), "--velocity", "--icentres")
    assert p.returncode == 0
    assert set(strict_json(p.stdout)) == {"file", "output", "size_mm", "scales", "icentres", "notes"}
