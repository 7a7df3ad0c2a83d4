"""``mech sweep`` on the command line: exit statuses, JSON, CSV, refusals."""

from __future__ import annotations

import csv
import json
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SHAPER = str(ROOT / "mechanisms" / "crank_slotted_lever_quick_return.yaml")
FOUR_BAR = str(ROOT / "mechanisms" / "four_bar.yaml")


def test_sweep_prints_dead_centres_and_time_ratio(run):
    result = run("sweep", SHAPER)
    assert result.exit_code == 0, result.output
    assert "dead centre of stroke at 210.000000°" in result.output
    assert "time ratio (stroke)" in result.output and "= 2" in result.output


def test_sweep_json_and_csv_agree(run, tmp_path):
    out = tmp_path / "s.csv"
    result = run(
        "sweep",
        FOUR_BAR,
        "--json",
        "--steps",
        "72",
        "--quantity",
        "omega.rocker",
        "--csv",
        str(out),
        "--units",
        "mm",
    )
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert data["steps"] == 73 and data["method"] == "closed form"
    assert [e["quantity"] for e in data["extremes"]] == ["omega.rocker"]
    rows = list(csv.reader(out.open()))
    assert rows[0] == ["angle [deg]", "omega.rocker [rad/s]"]
    assert len(rows) == 74
    assert float(rows[1][1]) == data["series"]["omega.rocker"][0]


def test_sweep_refuses_angle_and_bad_quantity(run):
    result = run("sweep", FOUR_BAR, "--angle", "30")
    assert result.exit_code == 2
    assert "--from and --to" in result.stderr
    result = run("sweep", FOUR_BAR, "--quantity", "omega.nothing")
    assert result.exit_code == 2
    assert "no link named nothing" in result.stderr


def test_sweep_reports_a_gap(run):
    result = run("sweep", str(ROOT / "mechanisms" / "khurmi_six_link_slider.yaml"))
    assert result.exit_code == 0
    assert "cannot be assembled from 27.58" in result.output
    assert "toggle at" in result.output


def test_plot_without_matplotlib_is_exit_2_before_solving(run, monkeypatch, tmp_path):
    import sys

    monkeypatch.setitem(sys.modules, "matplotlib", None)  # as if the plot extra were not installed
    result = run("sweep", FOUR_BAR, "--plot", str(tmp_path / "p.png"))
    assert result.exit_code == 2
    assert "matplotlib" in result.stderr
    assert not (tmp_path / "p.png").exists()


def test_plot_and_animation_are_written(run, tmp_path):
    import pytest

    pytest.importorskip("matplotlib")
    png, gif = tmp_path / "p.png", tmp_path / "a.gif"
    result = run(
        "sweep",
        FOUR_BAR,
        "--steps",
        "24",
        "--quantity",
        "omega.rocker",
        "--plot",
        str(png),
        "--animate",
        str(gif),
    )
    assert result.exit_code == 0, result.output
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert gif.read_bytes()[:6] in (b"GIF89a", b"GIF87a")
