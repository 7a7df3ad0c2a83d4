"""README's ``check_file``-over-Dask example, really run: a LocalCluster of worker processes.

The snippet is taken from README.md as written (only the scheduler's address is swapped
for a local cluster), run in a folder holding a small homework set — right, wrong,
malformed and answer-free files — and its JUnit report must equal a local run's.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text(encoding="utf-8")
GOOD = (ROOT / "mechanisms" / "four_bar.yaml").read_text(encoding="utf-8")


def readme_snippet() -> str:
    block = re.search(r"```python\n(from dask\.distributed import Client.*?)```", README, flags=re.S)
    assert block is not None, "README.md lost its Dask example"
    code = block.group(1)
    assert 'Client("scheduler:8786")' in code
    return code.replace('Client("scheduler:8786")', "Client(cluster)")


def test_readme_dask_example_gives_the_same_report_as_a_local_run(tmp_path: Path, monkeypatch) -> None:
    distributed = pytest.importorskip(
        "distributed", reason="dask[distributed] is not installed (pip install 'planar-mech[dask]')"
    )
    from mech.batch import CheckOptions, run
    from mech.render.check import junit_xml

    hw = tmp_path / "homework"
    hw.mkdir()
    (hw / "good.yaml").write_text(GOOD)
    (hw / "wrong.yaml").write_text(GOOD.replace("omega.rocker: 4.8 rad/s cw", "omega.rocker: 4.8 rad/s ccw"))
    (hw / "broken.yaml").write_text("links: [frame, crank\n")
    (hw / "notes.yaml").write_text(GOOD.split("\nanswers:")[0] + "\n")
    monkeypatch.chdir(tmp_path)
    local = junit_xml(run(CheckOptions(("homework/",), jobs=1)))

    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster:
        namespace: dict[str, object] = {"cluster": cluster}
        try:
            exec(compile(readme_snippet(), "README.md", "exec"), namespace)
        finally:
            client = namespace.get("client")
            if client is not None:
                client.close()  # type: ignore[attr-defined]
    assert (tmp_path / "results.xml").read_text(encoding="utf-8") == local
    assert "wrong.yaml" in local and "<skipped" in local and "FileError" in local
