"""``mech sweep`` on the command line: exit statuses, JSON, CSV, refusals."""

from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path

import numpy as np
import pytest

from cli_runner import mech, no_traceback, strict_json
from mechanism_texts import CRANK_ROCKER, CRANK_ROCKER_LENGTHS, slider_crank
from oracles.four_bar import crank_rocker_limits, crank_rocker_sweep, four_bar
from oracles.slider_crank import slider_dead_centres

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


# -- numbers through mech sweep --json, against tests/oracles (cli_runner: tracebacks shown) --
CR = CRANK_ROCKER_LENGTHS


def _file(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def sweep_json(path, *args):
    p = mech("sweep", "--json", str(path), *args)
    no_traceback(p)
    assert p.returncode == 0, p.stderr
    return strict_json(p.stdout)


def _crank_rocker_limits() -> tuple[float, float, float]:
    return crank_rocker_limits(CR["a"], CR["b"], CR["c"], CR["d"])


@pytest.mark.parametrize("rng", [("0", "360"), ("-180", "180"), ("720", "1080"), ("0", "720")])
def test_crank_rocker_dead_centres_and_time_ratio_match_the_law_of_cosines(tmp_path, rng):
    """Dead centres where crank and coupler are in line, ratio (180 + a)/(180 - a), any full range."""
    t_ext, t_fold, ratio = _crank_rocker_limits()
    m = _file(tmp_path, "cr.yaml", CRANK_ROCKER)
    d = sweep_json(m, "--from", rng[0], "--to", rng[1], "--steps", "36")
    assert d["time_ratio"]["ratio"] == pytest.approx(ratio, rel=1e-10)
    lo, hi = float(rng[0]), float(rng[1])
    want = sorted(t + 360 * k for t in (t_ext, t_fold) for k in range(-2, 4) if lo <= t + 360 * k <= hi)
    assert [e["angle"] for e in d["dead_centres"]] == pytest.approx(want, abs=1e-8)


@pytest.mark.parametrize(
    "rng, steps, full_turn",
    [(("90", "-90"), "360", False), (("90", "-90"), "12", False), (("360", "0"), "360", True)],
)
def test_descending_sweep_refines_dead_centres_and_time_ratio_as_an_ascending_one(
    tmp_path, rng, steps, full_turn
):
    """--from above --to: dead centres to 1e-8 deg (once 0.05 deg off); a time ratio needs a full turn."""
    t_ext, t_fold, ratio = _crank_rocker_limits()
    m = _file(tmp_path, "cr.yaml", CRANK_ROCKER)
    d = sweep_json(m, "--from", rng[0], "--to", rng[1], "--steps", steps)
    got = sorted(e["angle"] for e in d["dead_centres"])
    lo, hi = sorted(map(float, rng))
    want = sorted(t + 360 * k for t in (t_ext, t_fold) for k in (-1, 0, 1) if lo <= t + 360 * k <= hi)
    assert got == pytest.approx(want, abs=1e-8)
    if full_turn:
        assert d["time_ratio"]["ratio"] == pytest.approx(ratio, rel=1e-10)
    else:  # half a turn holds one stroke only: no ratio of two strokes
        assert d["time_ratio"] is None


@pytest.mark.parametrize("offset", [0.0, 0.05])
def test_slider_crank_dead_centres_and_time_ratio_match_the_closed_form(tmp_path, offset):
    """In line: exactly 0 and 180 deg, ratio 1; offset e: asin(e/(L+r)) and 180 + asin(e/(L-r))."""
    r, L = 0.1, 0.4
    m = _file(tmp_path, "sc.yaml", slider_crank(r, L, 90, 10, offset=offset))
    d = sweep_json(m, "--steps", "7")
    outer, inner, x_out, x_in = slider_dead_centres(r, L, offset)
    t1, t2 = math.degrees(outer), math.degrees(inner)
    alpha = t2 - t1 - 180
    got = [(e["angle"], e["position"]) for e in d["dead_centres"]]
    assert [g[0] for g in got] == pytest.approx([t1, t2], abs=1e-9)
    assert [g[1] for g in got] == pytest.approx([x_out, x_in], rel=1e-12)
    if offset == 0:
        assert d["dead_centres"][0]["angle"] == 0.0
    assert d["time_ratio"]["ratio"] == pytest.approx((180 + alpha) / (180 - alpha), rel=1e-10)


def _dense_extremes(lo, hi, n=400_001):
    th = np.linspace(lo, hi, n)
    psi, w4, w3, vc = crank_rocker_sweep(CR["a"], CR["b"], CR["c"], CR["d"], th, 10.0)
    return th, {"angle.rocker": psi, "omega.rocker": w4, "omega.coupler": w3, "velocity.C": vc}


@pytest.mark.parametrize("rng", [("300", "420"), ("0", "360"), ("10", "100")])
def test_twelve_step_extremes_match_a_dense_evaluation_of_the_closed_form(tmp_path, rng):
    """12 steps give the extremes of 400 001 points of the oracle, and their angles."""
    m = _file(tmp_path, "cr.yaml", CRANK_ROCKER)
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


def test_newton_sweep_extremes_are_refined_not_read_off_a_parabola(tmp_path):
    """--method newton: the rocker's largest angle within its limit, least |v_C| = 0 where it stops."""
    m = _file(tmp_path, "cr.yaml", CRANK_ROCKER)
    d = sweep_json(m, "--steps", "36", "--method", "newton")
    _, dense = _dense_extremes(0.0, 360.0)
    got = {e["quantity"]: e for e in d["extremes"]}
    for key, v in dense.items():
        scale = float(np.max(np.abs(v)))
        assert got[key]["max"] == pytest.approx(float(v.max()), abs=1e-6 * scale), (key, got[key])
        least = 0.0 if key == "velocity.C" else float(v.min())  # the rocker stops: |v_C| = 0
        assert got[key]["min"] == pytest.approx(least, abs=1e-6 * scale), (key, got[key])


def test_gear_sweep_extremes_are_values_the_wheel_takes(tmp_path):
    """A 2:1 wheel does not repeat each pinion turn: angle.wheel runs 0 to -180 deg, no wrap."""
    d = sweep_json(ROOT / "mechanisms" / "gear_pair.yaml", "--steps", "8", "--quantity", "angle.wheel")
    assert d["series"]["angle.wheel"] == pytest.approx([-th / 2 for th in d["series"]["angle"]], abs=1e-9)
    (e,) = d["extremes"]
    assert e["max"] == pytest.approx(0.0, abs=1e-9) and e["max_angle"] == pytest.approx(0.0, abs=1e-6)
    assert e["min"] == pytest.approx(-180.0, abs=1e-9) and e["min_angle"] == pytest.approx(360.0, abs=1e-6)


def test_one_step_over_a_full_turn_locates_what_a_fine_sweep_does(tmp_path):
    """Both ends of 0..360 are one crank position, but the sweep looks between its steps (1° grid):
    the dead centres and time ratio of the law of cosines, as with 36 steps."""
    t_ext, t_fold, ratio = _crank_rocker_limits()
    m = _file(tmp_path, "cr.yaml", CRANK_ROCKER)
    d = sweep_json(m, "--steps", "1")
    assert [e["angle"] for e in d["dead_centres"]] == pytest.approx(sorted([t_ext, t_fold]), abs=1e-8)
    assert d["time_ratio"]["ratio"] == pytest.approx(ratio, rel=1e-10)
    assert d["steps"] == 2


def test_sweep_steps_beyond_the_memory_budget_are_refused(tmp_path):
    """Under a 1.5 GB address-space limit, --steps 10,000,000 is exit 2 saying how many fit."""
    import resource

    m = _file(tmp_path, "cr.yaml", CRANK_ROCKER)

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
def test_sweep_unknown_quantity_is_a_usage_error(tmp_path, quantity):
    """A quantity that does not exist (or needs a higher --level) is exit 2 with a message."""
    m = _file(tmp_path, "sc.yaml", slider_crank(0.1, 0.4, 90, 10))
    p = mech("sweep", str(m), "--steps", "4", "--quantity", quantity)
    no_traceback(p)
    assert p.returncode == 2 and "error:" in p.stderr


def test_sweep_csv_has_units_in_its_header_and_empty_cells_in_a_gap(tmp_path):
    """AB = BC = CD = 1, AD = 2.5 assembles only while cos(th) >= 0.65: toggles at +-acos(0.65)."""
    m = _file(
        tmp_path,
        "g.yaml",
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
    # v_C at 0 deg from the four-bar oracle (C above BD), in mm/s
    _C, _w3, w4, _, _ = four_bar(1.0, 1.0, 1.0, 2.5, 0.0, 10.0)
    assert float(rows[1][1]) == pytest.approx(1000 * abs(w4) * 1.0, rel=1e-10)


def test_sweep_json_units_mm_scale_lengths_and_speeds_not_angles(tmp_path):
    """--units mm: dead centres, extremes and series of lengths and speeds x 1000; ω unchanged."""
    m = _file(tmp_path, "sc.yaml", slider_crank(0.1, 0.4, 90, 10, offset=0.05))
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


def test_sweep_to_1e308_degrees_is_refused_with_what_to_do(run):
    # It printed seven dead centres at 1e307-sized angles, exit 0.
    result = run("sweep", FOUR_BAR, "--from", "0", "--to", "1e308", "--steps", "10")
    assert result.exit_code == 2
    assert "floating point" in result.output and "subtract whole turns" in result.output


def test_sweep_of_two_turns_in_three_steps_reports_four_dead_centres(run):
    # It reported 2 of the 4 (23.68°, 211.29°, 383.68°, 571.29°: tests/kinematics/test_sweep.py).
    result = run("sweep", FOUR_BAR, "--to", "720", "--steps", "3", "--json")
    assert result.exit_code == 0, result.output
    angles = [d["angle"] for d in json.loads(result.output)["dead_centres"]]
    assert [round(a, 2) for a in angles] == [23.68, 211.29, 383.68, 571.29]


def test_csv_dash_writes_the_series_to_standard_output_and_no_file(run, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    args = ("sweep", FOUR_BAR, "--steps", "12", "--quantity", "omega.rocker", "--units", "mm")
    result = run(*args, "--csv", "-")
    assert result.exit_code == 0, result.output
    assert not (tmp_path / "-").exists()
    # the CSV is the whole of standard output: the same text --csv FILE writes, no report
    run(*args, "--csv", "s.csv")
    assert result.stdout == (tmp_path / "s.csv").read_text(encoding="utf-8")
    rows = list(csv.reader(io.StringIO(result.stdout)))
    assert rows[0] == ["angle [deg]", "omega.rocker [rad/s]"] and len(rows) == 14


def test_csv_dash_with_json_is_refused_as_two_documents_on_one_stream(run, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = run("sweep", FOUR_BAR, "--csv", "-", "--json")
    assert result.exit_code == 2
    assert not (tmp_path / "-").exists()


TRAMMEL = str(ROOT / "mechanisms" / "elliptic_trammel.yaml")
FIVE_BAR_TWO = str(ROOT / "mechanisms" / "five_bar_two_cranks.yaml")


def test_slider_drive_sweeps_its_stroke_in_the_files_length_unit(run):
    # --from/--to are A's positions along its path in mm (the file's unit); B rises to L = 200 mm
    # where A crosses the other guide: y_B = sqrt(L² − s²) (closed form)
    args = ("sweep", TRAMMEL, "--from", "-150", "--to", "150", "--steps", "6", "--units", "mm")
    result = run(*args, "--json", "--quantity", "position.B.y")
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert data["parameter"] == {"drive": "PA", "kind": "position", "unit": "mm"}
    assert data["range"] == [-150.0, 150.0] and data["time_ratio"] is None
    assert data["series"]["position"] == pytest.approx([-150, -100, -50, 0, 50, 100, 150])
    want = [math.sqrt(200**2 - s**2) for s in (-150, -100, -50, 0, 50, 100, 150)]
    assert data["series"]["position.B.y"] == pytest.approx(want, rel=1e-12)
    (dead,) = data["dead_centres"]
    assert dead["output"] == "PB" and abs(dead["angle"]) < 1e-9 and dead["position"] == pytest.approx(200)
    table = run(*args)
    assert table.exit_code == 0 and "sweep of PA along its path from -150 to 150 mm" in table.output
    rows = list(csv.reader(io.StringIO(run(*args, "--csv", "-").stdout)))
    assert rows[0][0] == "position [mm]" and float(rows[1][0]) == -150.0


@pytest.mark.parametrize("far", ["1e308", "1e30"])
def test_a_stroke_beyond_float_precision_is_refused_with_what_to_do(run, far):
    # It ended in an internal error (exit 70): the analysis grid's part count overflowed int64.
    # 1e30 mm is held only to spacing(1e30) = 1.4e14 mm, on a trammel 200 mm long.
    result = run("sweep", TRAMMEL, "--from", "0", "--to", far)
    assert result.exit_code == 2, result.output
    assert "floating point" in result.stderr and "within the slider's reach" in result.stderr


@pytest.mark.parametrize(("far", "steps"), [("1e6", "4"), ("1e9", "24")])
def test_a_stroke_past_the_reach_is_swept_to_the_limit_it_cannot_pass(run, far, steps):
    # B leaves its guide where A reaches the rod's length L = 200 mm (y_B = sqrt(L² − s²) = 0): the
    # toggle.  In steps of 4.2e7 mm (too wide for the analysis grid's memory) the limit was put at
    # 79 mm: one Newton solve failing across a wide step was read as the limit (bisection).
    result = run("sweep", TRAMMEL, "--from", "0", "--to", far, "--steps", steps, "--json", "--units", "mm")
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert [t["angle"] for t in data["toggles"]] == [pytest.approx(200, rel=1e-9)]
    assert data["gaps"][0]["from"] == pytest.approx(200, rel=1e-9)


def test_slider_drive_without_a_stroke_is_refused(run):
    result = run("sweep", TRAMMEL)
    assert result.exit_code == 2 and "needs its stroke" in result.stderr


def test_several_drives_sweep_each_in_proportion_and_name_the_lead(run):
    result = run("sweep", FIVE_BAR_TWO, "--json", "--steps", "36")
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert data["parameter"]["drive"] == "link_2" and data["parameter"]["kind"] == "angle"
    assert [(d["drive"], d["per_parameter"]) for d in data["drives"]] == [("link_2", 1.0), ("link_5", -2.0)]
    led = json.loads(
        run("sweep", FIVE_BAR_TWO, "--json", "--drive", "link_5", "--from", "90", "--to", "0").output
    )
    assert led["parameter"]["drive"] == "link_5" and led["drives"][1]["per_parameter"] == -0.5
    refused = run("sweep", FIVE_BAR_TWO, "--rpm", "100")
    assert refused.exit_code == 2 and "set a single drive" in refused.stderr
    unknown = run("sweep", FIVE_BAR_TWO, "--drive", "link_3")
    assert unknown.exit_code == 2 and "no drive of 'link_3'" in unknown.stderr


def test_no_range_ends_a_sweep_in_an_exception_or_a_warning():
    """Property: whatever --from/--to/--steps (huge, tiny, negative, equal, reversed), a sweep of a
    crank, a slider's stroke or several drives answers (0) or refuses (2) — never an exception that
    would exit 70, never a RuntimeWarning on stderr."""
    import warnings

    from click.testing import CliRunner
    from hypothesis import HealthCheck, given, settings
    from hypothesis import strategies as st

    from mech.cli import cli

    runner = CliRunner()
    ends = st.one_of(
        st.sampled_from([0.0, -0.0, 1e-300, 5e-324, 1e308, -1e308, 1e30, 1e9, 360.0, -150.0, 199.999, 200.0]),
        st.floats(-1e12, 1e12, allow_nan=False),
    )

    @settings(max_examples=40, deadline=None, suppress_health_check=list(HealthCheck), derandomize=True)
    @given(
        path=st.sampled_from([TRAMMEL, FIVE_BAR_TWO, FOUR_BAR]),
        lo=ends,
        hi=ends,
        steps=st.sampled_from(["1", "3", "24"]),
    )
    def one(path: str, lo: float, hi: float, steps: str) -> None:
        args = ["sweep", path, "--from", repr(lo), "--to", repr(hi), "--steps", steps, "--json"]
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            result = runner.invoke(cli, args, catch_exceptions=True)
        if result.exception is not None and not isinstance(result.exception, SystemExit):
            raise AssertionError(f"mech {' '.join(args)} raised {result.exception!r}")
        assert result.exit_code in (0, 2), (args, result.exit_code, result.output[-800:])
        runtime = [str(w.message) for w in caught if issubclass(w.category, RuntimeWarning)]
        assert not runtime, (args, runtime)

    one()


def test_two_drive_sweep_says_not_reached_never_cannot_close(run):
    # mechanisms/five_bar_two_cranks.yaml (θ2 = φ, θ5 = 270° − 2φ): the loop closes while |BD| ≤ 160 mm,
    # φ in [0, 123.596°] and [169.513°, 360°] (the closed form's roots, test_sweep.py); a Newton sweep
    # reaches both stretches from the drawing, and what lies between it did not reach (issue 25, item 3)
    result = run("sweep", str(ROOT / "mechanisms" / "five_bar_two_cranks.yaml"), "--steps", "72")
    assert result.exit_code == 0, result.output
    said = " ".join(result.output.split())
    assert "not reached from 123.595740° to 169.513163°" in said
    assert "cannot be assembled" not in said and "cannot close" not in said
    gaps = json.loads(
        run("sweep", str(ROOT / "mechanisms" / "five_bar_two_cranks.yaml"), "--steps", "72", "--json").output
    )["gaps"]
    assert [(round(g["from"], 6), round(g["to"], 6), g["kind"]) for g in gaps] == [
        (123.59574, 169.513163, "not reached")
    ]


def test_a_high_gear_ratio_is_not_called_a_toggle(run, write):
    # a 1e12 mm pinion driving a 1 mm wheel: ω_wheel = −1e12 ω_pinion at every angle, and the
    # constraint equations' condition number is 2e12 everywhere; no links come into line (issue 25,
    # item 13).  The sweep says why the rates are left out, not that a toggle is near.
    text = """
units: {length: mm, angle: deg}
links: [frame, pinion, wheel]
joints:
  O1: {type: revolute, links: [frame, pinion], at: [0, 0]}
  O2: {type: revolute, links: [frame, wheel], at: [1000000000001, 0]}
  mesh: {type: gear, links: [pinion, wheel], radii: [1000000000000, 1]}
drive: {link: pinion, rpm: 1200, direction: cw}
"""
    result = run("sweep", str(write(text)), "--steps", "36")
    assert result.exit_code == 0, result.output
    said = " ".join(result.output.split())  # as printed, lines wrapped at the terminal's width
    assert "toggle" not in said.replace("no toggle or change point", "")
    assert (
        "at every angle, with no toggle or change point (links or gear ratios of very different scales)"
        in said
    )


def test_a_sweep_follows_each_links_point_at_a_cam_contact(run):
    # mechanisms/eccentric_cam.yaml (R = 40, e = 15 mm, 300 rpm): the face touches straight above E,
    # so the cam's point there is e sin θ + R from the shaft: ω(R + e) = 1.7279 m/s at θ = 90°,
    # ω(R − e) = 0.7854 at 270°; the face's point rises at eω cos θ, at most eω = 0.4712 m/s
    w = 10 * math.pi
    result = run(
        "sweep",
        str(ROOT / "mechanisms" / "eccentric_cam.yaml"),
        "--json",
        "--quantity",
        "velocity.K@cam",
        "--quantity",
        "velocity.K@follower",
        "--quantity",
        "velocity.K",
    )
    assert result.exit_code == 0, result.output
    ext = {e["quantity"]: e for e in json.loads(result.output)["extremes"]}
    cam = ext["velocity.K@cam"]
    assert cam["max"] == pytest.approx(w * 0.055, rel=1e-6) and cam["max_angle"] == pytest.approx(
        90, abs=1e-3
    )
    assert cam["min"] == pytest.approx(w * 0.025, rel=1e-6) and cam["min_angle"] == pytest.approx(
        270, abs=1e-3
    )
    assert ext["velocity.K@follower"]["max"] == pytest.approx(w * 0.015, rel=1e-6)
    assert ext["velocity.K"]["max"] == pytest.approx(w * 0.015, rel=1e-6)
    wrong = run("sweep", str(ROOT / "mechanisms" / "eccentric_cam.yaml"), "--quantity", "velocity.K@frame")
    assert wrong.exit_code == 2 and "K@cam or K@follower" in wrong.stderr


def test_a_swept_rolling_wheels_point_at_the_ground_accelerates_at_omega_squared_r():
    # mechanisms/rolling_wheel.yaml: a wheel of r = 30 mm rolling without slip on straight ground.
    # Its point at the contact is the instant centre (at rest) and accelerates toward the wheel's
    # centre at ω² r, whatever α (rolling kinematics); the ground's point there is at rest. W alone
    # is asked for its velocity: its acceleration, two-valued, is not given (NaN), not an error.
    from mech.kinematics import sweep
    from mech.loader import load

    m = load(ROOT / "mechanisms" / "rolling_wheel.yaml")
    keys = ["acceleration.W@wheel", "acceleration.W@frame", "velocity.W"]
    s = sweep(m, np.radians(np.arange(0.0, 360.0, 10.0)), level="acceleration", quantities=keys)
    w = s.series("omega.wheel")
    assert s.series("acceleration.W@wheel") == pytest.approx(w * w * 0.030, rel=1e-9, abs=1e-12)
    assert s.series("acceleration.W@frame") == pytest.approx(np.zeros(w.size), abs=1e-12)
    assert s.series("velocity.W") == pytest.approx(np.zeros(w.size), abs=1e-12)


@pytest.mark.parametrize(
    "name", ["cam_roller_program", "cam_valve_khurmi", "cam_oscillating_roller", "cam_flat_follower"]
)
def test_shipped_cam_examples_sweep_one_line_per_dwell_and_no_dead_centre_inside_one(run, name):
    # Each programme has two dwells (their segments, in the files); a follower at rest over one has
    # no dead centre inside it (the roller cam listed 92, one at every degree of both dwells).
    path = str(ROOT / "mechanisms" / f"{name}.yaml")
    text = run("sweep", path, "--rpm", "100")
    assert text.exit_code == 0, text.output
    assert text.output.count("  dwell of ") == 2 and "dead centre" not in text.output
    d = json.loads(run("sweep", path, "--rpm", "100", "--json").output)
    assert len(d["dwells"]) == 2 and all(dw["reverses"] for dw in d["dwells"])  # lowest and highest
    assert d["dead_centres"] == []
