"""``mech check`` batches: every file a row, time limits, crashes, interrupts, report files.

The slow file is a real one: a chain of 400 four-bars, each rocker the next one's crank
(1,201 joints).  Solving it takes many seconds of CPU, so a time limit of one second
always expires on it, however fast the machine.
"""

from __future__ import annotations

import csv
import io
import json
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path
from xml.etree import ElementTree as ET

import pytest

from cli_runner import mech, no_traceback, strict_json
from mech.batch import CheckOptions, run
from mech.batchpool import run_jobs
from mech.check import ERROR
from mechanism_texts import TOGGLE_FOUR_BAR, slider_crank, strip_answers

ROOT = Path(__file__).resolve().parent.parent
GOOD = (ROOT / "mechanisms" / "four_bar.yaml").read_text(encoding="utf-8")  # its answers all pass
NO_ANSWERS = GOOD.split("\nanswers:")[0] + "\n"


def long_chain(n: int = 400) -> str:
    """n four-bars in a row, each rocker driving the next: a file that takes seconds to solve."""
    links = ", ".join(f"l{i}" for i in range(1, 2 * n + 2))
    lines = ["name: long chain", f"links: [frame, {links}]", "joints:"]
    lines.append("  J0: {type: revolute, links: [frame, l1], at: [0, 0]}")
    x = 0.0
    for k in range(n):
        crank, coupler, rocker = f"l{2 * k + 1}", f"l{2 * k + 2}", f"l{2 * k + 3}"
        lines.append(f"  B{k}: {{type: revolute, links: [{crank}, {coupler}]}}")
        lines.append(f"  C{k}: {{type: revolute, links: [{coupler}, {rocker}], near: [{x + 1.2:.3f}, 0.9]}}")
        lines.append(f"  D{k}: {{type: revolute, links: [{rocker}, frame], at: [{x + 1.5:.3f}, 0]}}")
        x += 1.5
    lines.append("lengths:")
    for k in range(n):
        lines.append(f"  {'J0' if k == 0 else f'D{k - 1}'}-B{k}: 0.4")
        lines.append(f"  B{k}-C{k}: 1.5")
        lines.append(f"  C{k}-D{k}: 1.0")
    lines.append("drive: {link: l1, angle: 60, omega: 1}")
    lines.append(f"answers: {{omega.l{2 * n + 1}: 1}}")
    return "\n".join(lines) + "\n"


# -- every file a row -------------------------------------------------------------------------
@pytest.fixture
def odd_folder(tmp_path: Path) -> Path:
    d = tmp_path / "hw"
    d.mkdir()
    (d / "good.yaml").write_text(GOOD)
    (d / "notes.yaml").write_text(NO_ANSWERS)
    (d / "dangling.yaml").symlink_to(d / "nowhere.yaml")
    (d / "loop.yaml").symlink_to(d / "loop.yaml")
    (d / "device.yaml").symlink_to("/dev/null")
    os.mkfifo(d / "pipe.yaml")
    return d


ODD = {
    "dangling.yaml": "symbolic link to",
    "loop.yaml": "symbolic link loop",
    "device.yaml": "a device",
    "pipe.yaml": "FIFO",
}


@pytest.mark.parametrize("jobs", [1, 2])
def test_special_files_are_error_rows_and_files_without_answers_are_skipped_rows(
    odd_folder: Path, jobs: int
) -> None:
    report = run(CheckOptions((str(odd_folder),), jobs=jobs))
    rows = {Path(r.path).name: r for r in report.results}
    assert set(rows) == {"good.yaml", "notes.yaml", *ODD}
    assert rows["good.yaml"].ok and rows["good.yaml"].total > 0
    assert rows["notes.yaml"].skipped and rows["notes.yaml"].total == 0
    for name, reason in ODD.items():
        (v,) = rows[name].verdicts
        assert v.status == ERROR and reason in v.message, (name, v.message)
    assert report.exit_status == 1


def test_every_file_is_a_row_in_junit_csv_and_gradescope(odd_folder: Path) -> None:
    from mech.render.check import csv_text, gradescope_dict, junit_xml

    report = run(CheckOptions((str(odd_folder),), jobs=1))
    names = {"good.yaml", "notes.yaml", *ODD}
    root = ET.fromstring(junit_xml(report))
    suites = {Path(s.get("name")).name: s for s in root.findall("testsuite")}
    assert set(suites) == names
    assert suites["notes.yaml"].find("testcase/skipped") is not None
    assert suites["notes.yaml"].get("skipped") == "1" and root.get("skipped") == "1"
    assert all(suites[n].find("testcase/error") is not None for n in ODD)
    csv_rows = csv_text(report).splitlines()[1:]
    assert {Path(r.split(",")[1]).name for r in csv_rows} == names
    assert any(r.endswith("nothing to check") and "notes.yaml" in r for r in csv_rows)
    tests = gradescope_dict(report)["tests"]
    assert {Path(t["name"].split(" (")[0].split(": ")[0]).name for t in tests} == names


def test_check_file_gives_the_same_row_as_the_batch(odd_folder: Path) -> None:
    from mech.batch import find_problem_files
    from mech.check import check_file

    paths = find_problem_files([str(odd_folder)])
    batch = run(CheckOptions((str(odd_folder),), jobs=1))
    assert tuple(check_file(p) for p in paths) == batch.results


# -- time limits and crashes --------------------------------------------------------------------
@pytest.mark.parametrize("jobs", [1, 2])
def test_a_file_past_the_time_limit_is_an_error_row_and_the_others_finish(tmp_path: Path, jobs: int) -> None:
    d = tmp_path / "hw"
    d.mkdir()
    (d / "a.yaml").write_text(GOOD)
    (d / "b_long.yaml").write_text(long_chain())
    (d / "c.yaml").write_text(GOOD)
    report = run(CheckOptions((str(d),), jobs=jobs, timeout=1.0))
    rows = {Path(r.path).name: r for r in report.results}
    assert rows["a.yaml"].ok and rows["c.yaml"].ok
    (v,) = rows["b_long.yaml"].verdicts
    assert v.status == ERROR and "time limit" in v.message


def _sleep_without_alarm(seconds: float) -> str:
    """A job stuck where SIGALRM cannot reach it (as in C code): only a kill stops it."""
    signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGALRM})
    time.sleep(seconds)
    return "slept"


def _job(spec: tuple[str, float]) -> str:
    kind, arg = spec
    if kind == "stuck":
        return _sleep_without_alarm(arg)
    if kind == "crash":
        os._exit(3)
    if kind == "slow":
        time.sleep(arg)
    return f"done {arg:g}"


def _lost(spec: tuple[str, float], why: str) -> str:
    return f"lost {spec[0]}: {why}"


def test_the_pool_kills_a_job_the_alarm_cannot_stop_and_finishes_the_rest() -> None:
    jobs = [("ok", 1.0), ("stuck", 60.0), ("ok", 2.0), ("ok", 3.0)]
    got = list(run_jobs(jobs, _job, _lost, workers=2, timeout=0.2, chunk=2))
    assert got == ["done 1", "lost stuck: timeout", "done 2", "done 3"]


def test_the_pool_reports_a_crashed_job_and_reruns_the_jobs_its_worker_held() -> None:
    jobs = [("ok", 1.0), ("crash", 0.0), ("ok", 2.0), ("ok", 3.0), ("ok", 4.0)]
    got = list(run_jobs(jobs, _job, _lost, workers=2, timeout=None, chunk=3))
    assert got == ["done 1", "lost crash: crash", "done 2", "done 3", "done 4"]


def test_a_pool_started_before_its_jobs_exist_runs_them_and_replaces_a_crashed_worker() -> None:
    # mech check starts its workers before it reads a class's sheets: the jobs travel with
    # their chunks, made after the workers were forked
    from mech.batchpool import Pool

    pool = Pool(_job, _lost, workers=2, timeout=None).start()
    jobs = [("ok", 1.0), ("crash", 0.0), ("ok", 2.0), ("ok", 3.0)]
    assert list(pool.map(jobs, chunk=1)) == ["done 1", "lost crash: crash", "done 2", "done 3"]
    assert pool.slots == [None, None]  # closed at the end of its map


def test_the_soft_limit_stops_a_slow_job_in_this_process() -> None:
    got = list(run_jobs([("slow", 60.0), ("ok", 1.0)], _job, _lost, workers=1, timeout=0.2))
    assert got == ["lost slow: timeout", "done 1"]


# -- report files and the command line ----------------------------------------------------------
def test_cli_two_reports_on_one_path_is_a_usage_error(run, tmp_path: Path) -> None:
    (tmp_path / "a.yaml").write_text(GOOD)
    out = tmp_path / "r.xml"
    result = run("check", str(tmp_path / "a.yaml"), "--junit", str(out), "--csv", str(out))
    assert result.exit_code == 2 and "--junit and --csv both write" in result.stderr
    assert not out.exists()


def test_cli_reports_replace_an_old_report_whole(run, tmp_path: Path) -> None:
    (tmp_path / "a.yaml").write_text(GOOD)
    out = tmp_path / "r.csv"
    out.write_text("old report\n" * 1000)
    result = run("check", str(tmp_path / "a.yaml"), "--csv", str(out))
    assert result.exit_code == 0
    assert out.read_text().splitlines()[0] == "student,problem,passed,total,score,status,earned,out_of"
    assert "old report" not in out.read_text()
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".mech-")] == []


#: ``mech`` as a user runs it, with one hook: loading a file named ``*blocks.yaml`` says so (a
#: marker file) and waits for the interrupt, however long (a worker forked from this process
#: inherits the hook, and is killed by the parent).  Under load a slow file could finish before
#: the interrupt arrived; this one cannot.
BLOCKING_MECH = """\
import pathlib, sys, time
import mech.loader
marker = pathlib.Path(sys.argv.pop(1))
real = mech.loader.load
def load(path, *args, **kwargs):
    if str(path).endswith("blocks.yaml"):
        marker.write_text("loading")
        while True:
            time.sleep(3600)
    return real(path, *args, **kwargs)
mech.loader.load = load
from mech.entry import main
main()
"""


@pytest.mark.parametrize("jobs", ["1", "2"])
def test_cli_interrupted_exits_130_and_leaves_no_report(tmp_path: Path, jobs: str) -> None:
    d = tmp_path / "hw"
    d.mkdir()
    (d / "a.yaml").write_text(GOOD)
    (d / "b_blocks.yaml").write_text(GOOD)
    marker = tmp_path / "loading"
    junit, grades = tmp_path / "junit.xml", tmp_path / "grades.csv"
    junit.write_text("<old/>")  # an older run's report: it must not pass for this run's
    command = ["check", str(d), "-j", jobs, "--timeout", "600", "--junit", str(junit), "--csv", str(grades)]
    proc = subprocess.Popen(
        [sys.executable, "-c", BLOCKING_MECH, str(marker), *command],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    try:
        first = proc.stdout.readline()  # the fast file's line is streamed while the other one loads
        assert "a.yaml" in first, first
        deadline = time.monotonic() + 120
        while not marker.exists():  # the batch is running, and cannot end: the interrupt lands in it
            assert proc.poll() is None and time.monotonic() < deadline, proc.stderr.read()
            time.sleep(0.01)
        os.killpg(proc.pid, signal.SIGINT)  # Ctrl-C reaches the whole foreground group
        _, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert proc.returncode == 130, err
    assert "interrupted" in err and "Traceback" not in err
    assert not junit.exists() and not grades.exists()
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".mech-")] == []


def test_the_pool_works_from_a_process_with_threads() -> None:
    # a library caller with threads of its own (Dask, a GUI) gets workers that are not forked
    import threading

    stop = threading.Event()
    helper = threading.Thread(target=stop.wait, daemon=True)
    helper.start()
    try:
        jobs = [("ok", 1.0), ("crash", 0.0), ("ok", 2.0)]
        assert list(run_jobs(jobs, _job, _lost, workers=2, timeout=None)) == [
            "done 1",
            "lost crash: crash",
            "done 2",
        ]
    finally:
        stop.set()
        helper.join()


# -- through the command line as a user runs it (cli_runner: crashes and tracebacks shown) --
def _put(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


HOSTILE_NAME = "Bad <&\"'> \nline2 ]]> é"


def test_reports_escape_hostile_names_and_their_counts_agree_with_the_summary(tmp_path):
    """A file é <&'q'>.yaml named <&"'>, newline, ]]>: JUnit parses, Gradescope and CSV carry it."""
    body = strip_answers("slider_crank.yaml")
    body = re.sub(r"(?m)^name: .*$", lambda _: "name: " + json.dumps(HOSTILE_NAME), body)
    body += "answers:\n  dof: 1\n  omega.rod: 5.642 rad/s ccw\n  chain: \"four <bar> & 'x'\"\n  velocity.B: 9 m/s\n"
    folder = tmp_path / "hw"
    _put(folder / "é <&'q'>.yaml", body)
    _put(folder / "good.yaml", strip_answers("four_bar.yaml") + "answers: {dof: 1}\n")
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


# One file per distinct way the solver can fail to give an answer (each must be one error row).
FAILURES = {
    "no_assembly": slider_crank(0.1, 0.4, 90, 10, offset=1.0, extra="answers: {velocity.B: 1 m/s}\n"),
    "toggle": TOGGLE_FOUR_BAR + "answers: {omega.rocker: 1}\n",
    "structure": """\
links: [frame, a, b]
joints:
  A: {type: revolute, links: [frame, a], at: [0, 0]}
  B: {type: revolute, links: [a, b], at: [1, 1]}
  C: {type: revolute, links: [b, frame], at: [2, 0]}
drive: {link: a, angle: 45, omega: 1}
answers: {velocity.B: 0}
""",
    "no_speed": slider_crank(
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
    "ratio_over_rest": slider_crank(0.1, 0.4, 90, 10, extra="answers: {omega_ratio.crank.rod: 1}\n"),
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
    "out_of_range": slider_crank(1e307, 4e307, 90, 10, extra="answers: {velocity.B: 1e308}\n"),
    "malformed": "links: [frame, crank\nanswers: {dof: 1}\n",
}


def test_each_way_the_solver_fails_is_one_error_row_among_200_files_with_one_or_two_jobs(tmp_path):
    """188 good slider cranks pass (v_B = w r = 1 m/s at 90 deg, rod at rest), each failure is one
    error row, exit 1; -j 2 (a process pool) gives the same JSON as -j 1."""
    folder = tmp_path / "hw"
    good = slider_crank(0.1, 0.4, 90, 10, extra="answers: {velocity.B: 1 m/s, omega.rod: 0}\n")
    for i in range(200 - len(FAILURES)):
        _put(folder / f"ok_{i:03d}.yaml", good)
    for name, text in FAILURES.items():
        _put(folder / f"zz_{name}.yaml", text)
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


@pytest.mark.parametrize("jobs", ["1", "2"])
def test_a_deeply_nested_file_is_one_error_row_and_the_batch_goes_on(tmp_path, jobs):
    """50,000 nested brackets once segfaulted -j 1 (exit 139, no report) and broke the -j 2 pool."""
    _put(tmp_path / "a.yaml", GOOD)
    _put(
        tmp_path / "b.yaml",
        "links: [frame, crank]\njoints:\n  A: {type: revolute, links: [frame, crank]}\n"
        "description: " + "[" * 50_000 + "]" * 50_000 + "\nanswers: {dof: 1}\n",
    )
    p = mech("check", str(tmp_path), "-j", jobs, "--json", subprocess_=True)
    assert p.returncode == 1, (p.returncode, p.stderr[-500:])
    report = strict_json(p.stdout)
    by_file = {Path(r["file"]).name: r for r in report["results"]}
    assert by_file["a.yaml"]["passed"] > 0
    assert by_file["b.yaml"]["errors"] == 1


def test_binary_empty_non_utf8_files_and_link_loops_in_a_folder_are_error_rows(tmp_path):
    """Each unreadable *.yaml is one error row; notes.txt, a folder named sub.yaml and loops are not files."""
    _put(tmp_path / "good.yaml", GOOD)
    (tmp_path / "bin.yaml").write_bytes(b"\x7fELF\x00\x01\x02" * 100)
    (tmp_path / "empty.yaml").write_text("")
    (tmp_path / "latin.yaml").write_bytes(b"\xff\xfe garbage")
    (tmp_path / "notes.txt").write_text("answers: {dof: 1}\n")
    (tmp_path / "sub.yaml").mkdir()
    os.symlink(".", tmp_path / "loop")
    os.symlink("self.yaml", tmp_path / "self.yaml")  # a symlink loop named like a mechanism
    p = mech("check", str(tmp_path), "-j", "1", "--json", timeout=120)
    assert p.returncode == 1, p.stderr[-500:]
    no_traceback(p)
    report = strict_json(p.stdout)
    by_file = {Path(r["file"]).name: r for r in report["results"]}
    assert by_file["good.yaml"]["failed"] == 0 and by_file["good.yaml"]["passed"] > 0
    for bad in ("bin.yaml", "empty.yaml", "latin.yaml"):
        assert by_file[bad]["errors"] == 1, by_file[bad]


@pytest.mark.parametrize("jobs", ["0", "-1"])
def test_check_jobs_below_one_is_a_usage_error(jobs):
    p = mech("check", str(ROOT / "mechanisms" / "four_bar.yaml"), "--jobs", jobs)
    assert p.returncode == 2 and "Traceback" not in p.stderr


def test_check_with_a_thousand_jobs_for_one_file_passes():
    p = mech("check", str(ROOT / "mechanisms" / "four_bar.yaml"), "--jobs", "1000")
    assert p.returncode == 0, p.stderr


def test_pool_chunks_cover_every_job_once_and_shrink_to_single_jobs_at_the_end():
    """Guided scheduling: no worker idles at the end while another finishes a full chunk."""
    from mech.batchpool import _chunks

    for n, largest, workers in ((1000, 32, 2), (7, 3, 2), (1, 32, 4), (100, 1, 2)):
        chunks = list(_chunks(n, largest, workers))
        assert [i for c in chunks for i in c] == list(range(n))
        assert all(1 <= len(c) <= largest for c in chunks)
        assert len(chunks[-1]) == 1
    assert len(next(iter(_chunks(1000, 32, 2)))) == 32


def test_a_worker_dying_with_a_chunk_waiting_in_its_pipe_loses_only_its_current_job() -> None:
    """Each worker is sent its next chunk ahead; a crash hands that chunk to a fresh worker."""
    jobs = [("ok", float(i)) for i in range(12)]
    jobs[1] = ("crash", 0.0)
    got = list(run_jobs(jobs, _job, _lost, workers=2, timeout=None, chunk=3))
    assert got == [f"done {i}" if i != 1 else "lost crash: crash" for i in range(12)]


def _blas_threads(_: int) -> str:
    return os.environ.get("OPENBLAS_NUM_THREADS", "unset")


def test_workers_run_blas_on_one_thread_unless_told_otherwise(monkeypatch: pytest.MonkeyPatch) -> None:
    """One worker per core already: a BLAS thread pool per worker would only oversubscribe them."""
    monkeypatch.delenv("OPENBLAS_NUM_THREADS", raising=False)
    assert list(run_jobs([0, 1], _blas_threads, _lost, workers=2)) == ["1", "1"]
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "3")
    assert list(run_jobs([0, 1], _blas_threads, _lost, workers=2)) == ["3", "3"]
