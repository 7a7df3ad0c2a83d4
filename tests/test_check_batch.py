"""``mech check`` batches: every file a row, time limits, crashes, interrupts, report files.

The slow file is a real one: a chain of 400 four-bars, each rocker the next one's crank
(1,201 joints).  Solving it takes many seconds of CPU, so a time limit of one second
always expires on it, however fast the machine.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path
from xml.etree import ElementTree as ET

import pytest

from mech.batch import CheckOptions, run
from mech.batchpool import run_jobs
from mech.check import ERROR

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
    assert out.read_text().splitlines()[0] == "student,problem,passed,total,score,status"
    assert "old report" not in out.read_text()
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".mech-")] == []


@pytest.mark.parametrize("jobs", ["1", "2"])
def test_cli_interrupted_exits_130_and_leaves_no_report(tmp_path: Path, jobs: str) -> None:
    d = tmp_path / "hw"
    d.mkdir()
    (d / "a.yaml").write_text(GOOD)
    (d / "b_long.yaml").write_text(long_chain())
    junit, grades = tmp_path / "junit.xml", tmp_path / "grades.csv"
    junit.write_text("<old/>")  # an older run's report: it must not pass for this run's
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "mech",
            "check",
            str(d),
            "-j",
            jobs,
            "--junit",
            str(junit),
            "--csv",
            str(grades),
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    first = proc.stdout.readline()  # the fast file's line is streamed before the slow one ends
    assert "a.yaml" in first, first
    os.killpg(proc.pid, signal.SIGINT)  # Ctrl-C reaches the whole foreground group
    _, err = proc.communicate(timeout=60)
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
