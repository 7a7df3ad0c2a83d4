"""A worker that dies (the interpreter itself crashed on a file) costs that file only."""

from __future__ import annotations

import multiprocessing
import os
import shutil
from pathlib import Path

import pytest

import mech.check.problem as problem
from mech.batch import CheckOptions, run

EXAMPLES = Path(__file__).resolve().parent.parent / "mechanisms"
NAMES = ["four_bar_dof.yaml", "five_bar.yaml", "structure_three_bar.yaml", "seven_link_chain.yaml"]


@pytest.mark.skipif(multiprocessing.get_start_method() != "fork", reason="the crash is injected by fork")
def test_a_crashing_file_is_one_error_row_and_the_others_are_checked(tmp_path, monkeypatch):
    for name in NAMES:
        shutil.copy(EXAMPLES / name, tmp_path / name)
    real = problem._check_task

    def crash_on_five_bar(task):
        if task.path.endswith("five_bar.yaml"):
            os._exit(139)  # what a segfault in a C extension looks like to the pool
        return real(task)

    monkeypatch.setattr(problem, "_check_task", crash_on_five_bar)
    report = run(CheckOptions(paths=(str(tmp_path),), jobs=2))
    rows = {Path(r.path).name: r for r in report.results}
    assert set(rows) == set(NAMES)
    crashed = rows["five_bar.yaml"]
    assert [v.status for v in crashed.verdicts] == ["error"]
    assert "crashed" in crashed.verdicts[0].message
    for name in set(NAMES) - {"five_bar.yaml"}:
        assert rows[name].verdicts and all(v.status == "pass" for v in rows[name].verdicts), name
    assert report.exit_status == 1
