"""``mech forces``, ``mech sweep --level forces`` and ``mech draw --forces`` as a user runs them.

The numbers are checked against independent derivations in test_instant.py, test_force_cycle.py and
test_freebody.py; here: what each command prints and writes, the JSON structure cli.md
documents, the exit statuses of bad input, and hostile files through every force command
(exit 0 or 2, never a traceback).
"""

from __future__ import annotations

import copy
import csv
import io
import json
import math
import re
from pathlib import Path

import pytest
from tests.mechanism_texts import EXAMPLES

from cli_runner import assert_bad_input, mech, no_traceback, strict_json
from hostile import HOSTILE_NUMBERS, HOSTILE_WORDS, answers_or_refuses, edit

FOUR_BAR = str(EXAMPLES / "four_bar_inertia_forces.yaml")
ENGINE = str(EXAMPLES / "engine_turning_moment.yaml")
KHURMI = str(EXAMPLES / "khurmi_gas_engine_flywheel.yaml")
ROOT = Path(__file__).resolve().parents[2]
CLI_MD = (ROOT / "cli.md").read_text(encoding="utf-8")


def test_forces_prints_each_pair_lettered_the_input_torque_and_the_shaking():
    out = mech("forces", FOUR_BAR)
    assert out.returncode == 0, out.stderr
    for text in (
        "F₁₂",
        "F₂₃",
        "F₃₄",
        "F₄₁",
        "input torque on crank: 0.664023 N·m ccw",
        "shaking force on the frame",
    ):
        assert text in out.stdout
    assert "137.408" in out.stdout  # |F₁₂|, the Newton–Euler value to six figures


def test_forces_json_has_the_keys_cli_md_documents():
    out = mech("forces", FOUR_BAR, "--json", "--explain", "--units", "mm")
    data = strict_json(out.stdout)
    assert list(data)[:4] == ["command", "file", "name", "mechanism"]
    assert data["command"] == "forces" and data["determinate"] is True and data["units"]["length"] == "mm"
    section = CLI_MD[CLI_MD.index("## mech forces") : CLI_MD.index("## mech sweep")]
    for key in [*data, *data["pairs"][0], *data["input"], *data["inertia"][0], *data["shaking"]]:
        assert f'"{key}"' in section, key
    for key in [*data["free_bodies"][0], *data["free_bodies"][0]["actions"][0]]:
        assert f'"{key}"' in section, key
    b = next(p for p in data["pairs"] if p["joint"] == "B")
    assert b["label"] == "F23" and b["text"] == "F₂₃, on link 3 (coupler) from link 2 (crank)"
    assert b["at"] == pytest.approx([20.0, 40 * math.sin(math.radians(60))])  # mm


def test_forces_says_when_the_pairs_are_indeterminate_and_still_gives_the_torque(tmp_path):
    text = (EXAMPLES / "double_parallelogram.yaml").read_text()
    path = tmp_path / "dp.yaml"
    path.write_text(text[: text.index("\nanswers:")] + "\nloads: {coupler: {torque: 5}}\n")
    out = mech("forces", str(path), "--json")
    data = strict_json(out.stdout)
    assert data["determinate"] is False and data["pairs"] == [] and "indeterminate" in data["note"]
    assert data["input"]["value"] == pytest.approx(0.0, abs=1e-9)
    table = mech("forces", str(path), "--explain")
    assert table.returncode == 0 and "indeterminate" in table.stdout


def test_forces_of_a_bad_file_is_located_bad_input(tmp_path):
    path = tmp_path / "bad.yaml"
    path.write_text(
        (EXAMPLES / "four_bar_inertia_forces.yaml").read_text().replace("centre: G3", "centre: G9")
    )
    assert_bad_input(mech("forces", str(path)), path)
    err = mech("forces", str(path), "--json")
    assert err.returncode == 2 and json.loads(err.stderr)["command"] == "forces"


def test_force_sweep_reports_the_turning_moment_energy_and_flywheel():
    out = mech("sweep", KHURMI, "--level", "forces")
    assert out.returncode == 0, out.stderr
    assert "mean input torque: -636.62 N·m" in out.stdout
    assert "ΔE = 10083.3 J" in out.stdout and "I = ΔE / (ω² C_s) = 255.414 kg·m²" in out.stdout
    assert "greatest at 532.5000° and least at 367.5000°" in out.stdout


def test_force_sweep_json_has_the_keys_cli_md_documents():
    data = strict_json(mech("sweep", ENGINE, "--level", "forces", "--steps", "36", "--json").stdout)
    assert data["command"] == "sweep" and data["level"] == "forces" and data["cycle"] == pytest.approx(720.0)
    section = CLI_MD[CLI_MD.index("### Forces over the cycle") : CLI_MD.index("## mech draw")]
    for key in [*data, *data["flywheel"], *data["effort"], *data["pairs"][0], *data["energy_max"]]:
        assert f'"{key}"' in section, key
    assert data["flywheel"]["inertia"] == pytest.approx(4.0, rel=1e-5)


def test_force_sweep_csv_has_the_torque_its_parts_the_energy_and_every_pair(tmp_path):
    path = tmp_path / "tm.csv"
    out = mech("sweep", ENGINE, "--level", "forces", "--steps", "72", "--csv", str(path))
    assert out.returncode == 0, out.stderr
    rows = list(csv.reader(io.StringIO(path.read_text())))
    head = rows[0]
    assert head[:6] == [
        "angle [deg]",
        "input_torque [N m]",
        "input_torque.loads [N m]",
        "input_torque.inertia [N m]",
        "input_torque.gravity [N m]",
        "energy [J]",
    ]
    assert "force.B [N]" in head and "force.P.y [N]" in head and head[-1] == "shaking_moment [N m]"
    assert len(rows) == 74 and float(rows[-1][0]) == pytest.approx(720.0)
    parts = [[float(x) for x in r[1:5]] for r in rows[1:]]
    assert all(t == pytest.approx(a + b + c, abs=1e-9 * 724) for t, a, b, c in parts)
    piped = mech("sweep", ENGINE, "--level", "forces", "--steps", "4", "--csv", "-", "--quantity", "energy")
    assert piped.stdout.splitlines()[0] == "angle [deg],energy [J]" and len(piped.stdout.splitlines()) == 6


def test_force_sweep_plots_the_turning_moment_diagram(tmp_path):
    pytest.importorskip("matplotlib")
    path = tmp_path / "tm.png"
    out = mech("sweep", ENGINE, "--level", "forces", "--steps", "72", "--plot", str(path))
    assert out.returncode == 0, out.stderr
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize(
    ("extra", "says"),
    [
        (["--animate", "x.gif"], "--animate does not apply"),
        (["--quantity", "velocity.B"], "no quantity 'velocity.B'"),
        (["--drive", "rod"], "first drive"),
    ],
)
def test_force_sweep_refuses_what_it_cannot_do(extra, says):
    out = mech("sweep", ENGINE, "--level", "forces", *extra)
    assert_bad_input(out, located=False)
    assert says in out.stderr


def test_draw_forces_letters_every_force_and_draws_the_free_bodies(tmp_path):
    path = tmp_path / "f.svg"
    out = mech("draw", str(EXAMPLES / "khurmi_engine_forces.yaml"), "-o", str(path), "--forces",
               "--free-body", "rod", "--free-body", "piston", "--json")  # fmt: skip
    assert out.returncode == 0, out.stderr
    svg = path.read_text()
    for name in ("F₁₂", "F₂₃", "F₃₄", "F₄₁", "P at B", "−m₄a_G₄", "T = 6799 N·m"):
        assert name in svg, name
    assert "Free body of link 3 (rod)" in svg and "Free body of link 4 (piston)" in svg
    assert re.search(r"forces: 1 cm = \d+ N", svg)
    summary = json.loads(out.stdout)
    assert summary["free_bodies"] == ["rod", "piston"] and any("forces" in s for s in summary["scales"])


@pytest.mark.parametrize(
    ("extra", "says"),
    [
        (["--free-body", "coupler"], "unknown link 'coupler'"),
        (["--forces", "--velocity"], "--velocity does not apply"),
    ],
)
def test_draw_forces_refuses_what_it_cannot_draw(tmp_path, extra, says):
    out = mech("draw", FOUR_BAR.replace("four_bar_inertia_forces", "khurmi_engine_forces"), "-o",
               str(tmp_path / "f.svg"), *extra)  # fmt: skip
    assert_bad_input(out, located=False)
    assert says in out.stderr


@pytest.mark.parametrize("command", [["forces"], ["sweep", "--level", "forces", "--steps", "12"]])
def test_every_example_answers_in_strict_json_or_refuses_it_as_bad_input(command):
    # the DOF-only files have no geometry or no drive, a slider drive wants its stroke: exit 2, said
    for path in sorted(EXAMPLES.glob("*.yaml")):
        out = mech(*command, str(path), "--json")
        no_traceback(out)
        assert out.returncode in (0, 2), (path.name, out.stderr[-400:])
        if out.returncode == 0:
            strict_json(out.stdout)
        else:
            assert out.stdout == "" and json.loads(out.stderr)["error"]["problems"], path.name


# -- hostile files ---------------------------------------------------------------------------
_COMMANDS = [
    ["forces"],
    ["forces", "--explain", "--json"],
    ["sweep", "--level", "forces", "--steps", "6"],
    ["draw", "-o", "{tmp}/forces.svg", "--forces", "--free-body", "rod"],
]


def _hostile_files():
    """YAML files grown from the engine example (masses, a load table, gravity, a flywheel) by
    hostile edits, as tests/test_cli.py grows them from the four-bar."""
    import yaml
    from hypothesis import strategies as st

    base = yaml.safe_load(Path(ENGINE).read_text(encoding="utf-8"))
    scalars = st.one_of(
        st.none(),
        st.booleans(),
        st.sampled_from(HOSTILE_NUMBERS),
        st.floats(),
        st.text(max_size=8),
        st.sampled_from([*HOSTILE_WORDS, "on", "table", "kg", "5 kg", "2%", "-1 kg m^2", "piston", "rod"]),
    )
    keys = st.one_of(st.sampled_from([*base, "masses", "gravity", "flywheel", "loads", "friction"]), scalars)
    values = st.recursive(
        scalars,
        lambda inner: st.one_of(st.lists(inner, max_size=4), st.dictionaries(keys, inner, max_size=4)),
        max_leaves=8,
    )

    @st.composite
    def files(draw):
        doc = copy.deepcopy(base)
        edit(draw, doc, keys, values, draw(st.integers(1, 3)))
        return yaml.safe_dump(doc, allow_unicode=True, sort_keys=False)

    return files()


def test_no_hostile_file_gives_a_traceback_from_a_force_command(tmp_path_factory):
    from click.testing import CliRunner
    from hypothesis import HealthCheck, given, settings
    from hypothesis import strategies as st

    runner = CliRunner()
    folder = tmp_path_factory.mktemp("hostile-forces")

    @settings(max_examples=60, deadline=None, suppress_health_check=list(HealthCheck), derandomize=True)
    @given(text=_hostile_files(), command=st.sampled_from(_COMMANDS))
    def one(text: str, command: list[str]) -> None:
        answers_or_refuses(runner, folder, text, command)

    one()


def test_a_force_command_in_a_real_process_leaves_no_traceback():
    out = mech("forces", ENGINE, "--angle", "375", subprocess_=True)
    no_traceback(out)
    assert out.returncode == 0 and "input torque on crank" in out.stdout


def test_a_slider_drives_input_force_is_signed_along_its_path():
    # a torque of 15 N·m ccw on the crank held by a force on the slider: the power balance
    # F v + M ω = 0 gives F = −M ω / v, ω the crank's for the slider's v (law of cosines)
    from tests.mechanism_texts import SLIDER_DRIVEN
    from tests.oracles.slider_crank import slider_driven_crank

    _, w = slider_driven_crank(0.1, 0.3, 0.3, 1.0)
    run = mech("forces", "-", input=SLIDER_DRIVEN)
    assert run.returncode == 0, run.stderr
    (line,) = [x for x in run.stdout.splitlines() if x.startswith("input force along")]
    assert "(signed, + along the path)" in line and "ccw" not in line
    assert f"{-15 * w:.6g} N" in line


@pytest.mark.parametrize(
    "name",
    ["eccentric_cam_roller.yaml", "four_bar_inertia_forces.yaml", "rolling_wheel.yaml", "gear_pair.yaml"],
)
def test_every_pin_force_is_drawn_from_its_pin(name):
    # a drawing whose sheet grows to hold a pitch circle or a cam's profile moves its items: the
    # force arrows must move with them (they floated 18 and 29 mm off on the cam's and rack's)
    from tests.mechanism_texts import epicyclic

    from mech.draw.forces import forces_drawing
    from mech.forces import analyse
    from mech.loader import loads
    from mech.shapes import Circle, Line

    text = (EXAMPLES / name).read_text(encoding="utf-8").split("\nanswers:")[0]
    if "loads:" not in text:
        driven = text.split("links: [")[1].split(",")[1].strip()
        text += f"\nloads: {{{driven}: {{torque: 1}}}}\n"
    for m in (loads(text, path=name), loads(epicyclic(extra="loads: {arm: {torque: -10}}\n"), path="e.yaml")):
        fa = analyse(m)
        fig = forces_drawing(m, fa)
        pins = {i.name: i.centre for i in fig.items if isinstance(i, Circle) and i.cls == "pin"}
        tails = {i.name: i.p0 for i in fig.items if isinstance(i, Line) and i.cls == "force"}
        num = {lk.name: k + 1 for k, lk in enumerate(m.links)}
        for p in fa.pairs:
            label = f"F{num[p.by]}{num[p.on]}".translate(str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉"))
            if p.joint in pins and label in tails:
                assert tails[label] == pytest.approx(pins[p.joint], abs=1e-9), (name, p.joint)


def test_a_force_drawing_states_the_drive_angle_as_mech_forces_does(tmp_path):
    # a programme cam turning cw, 60° into its programme: −60° from +x in both (the drawing said 300°)
    cam = str(EXAMPLES / "cam_roller_program.yaml")
    out = tmp_path / "cam.svg"
    drawn = mech("draw", cam, "-o", str(out), "--forces")
    assert drawn.returncode == 0, drawn.stderr
    said = mech("forces", cam)
    assert "at drive angle -60°" in said.stdout
    assert "forces at the drive's angle -60°" in out.read_text(encoding="utf-8")
