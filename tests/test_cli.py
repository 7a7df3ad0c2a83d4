"""The command line: exit statuses, stderr messages, JSON, plain output, start-up imports."""

from __future__ import annotations

import importlib
import itertools
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest

from cli_runner import mech
from hostile import HOSTILE_NUMBERS, HOSTILE_WORDS, answers_or_refuses, edit
from mech import __version__
from mechanism_texts import FIVE_BAR_ONE_DRIVE

ROOT = Path(__file__).resolve().parent.parent
FOUR_BAR = str(ROOT / "mechanisms" / "four_bar.yaml")
BAD = "links: [frame, crank]\njoints:\n  A: {type: revolute, links: [frame, crankk]}\n"


def test_version(run):
    result = run("--version")
    assert result.exit_code == 0
    assert result.output.strip() == f"mech {__version__}"


def test_every_command_has_help(run):
    from mech.cli import cli

    for name in cli.commands:
        result = run(name, "--help")
        assert result.exit_code == 0, name
        assert "Usage: mech " + name in result.output


def test_dof_prints_the_worked_count(run):
    result = run("dof", FOUR_BAR)
    assert result.exit_code == 0
    assert "n = 3(4 − 1) − 2·4 − 0 = 1" in result.output
    assert "constrained mechanism" in result.output
    assert "Grübler" in result.output


def test_dof_json_structure(run):
    result = run("dof", "--json", FOUR_BAR)
    data = json.loads(result.output)
    assert data["dof"] == 1 and data["links"] == 4 and data["equivalent_binary_joints"] == 4
    assert data["higher_pairs"] == 0 and data["kind"] == "constrained" and data["chain"] == "four-bar"
    assert data["grubler"]["satisfied"] is True
    assert data["icentres"] == 6


def test_bad_file_exits_2_with_location_and_no_traceback(run, write):
    path = write(BAD)
    result = run("dof", str(path))
    assert result.exit_code == 2
    assert f"{path}:3:38: error: joint A names unknown link 'crankk'" in result.stderr
    assert "hint: did you mean 'crank'?" in result.stderr
    assert "Traceback" not in result.stderr
    assert result.stdout == ""


def test_several_files_one_bad_still_counts_the_others(run, write):
    bad = write(BAD, "bad.yaml")
    result = run("dof", FOUR_BAR, str(bad), str(ROOT / "mechanisms" / "five_bar.yaml"))
    assert result.exit_code == 2
    assert "four_bar.yaml" in result.stdout and "five_bar.yaml" in result.stdout
    assert "bad.yaml:3:38" in result.stderr


def test_several_files_json_has_an_error_entry(run, write):
    bad = write(BAD, "bad.yaml")
    result = run("dof", "--json", FOUR_BAR, str(bad))
    data = json.loads(result.stdout)
    assert [d.get("dof") for d in data] == [1, None]
    problem = data[1]["error"]["problems"][0]
    assert (problem["line"], problem["column"]) == (3, 38)


def test_too_few_drives_are_refused_by_the_count_with_the_inputs_needed(run, write):
    # A ring of 7 links and 7 pins: Kutzbach 3·6 − 2·7 = 4 freedoms, one drive: exit 2, the drive located.
    names = ["frame", "l1", "l2", "l3", "l4", "l5", "l6", "frame"]
    joints = "\n".join(
        f"  J{i}: {{type: revolute, links: [{a}, {b}]"
        + (", at: [0, 0]}" if i == 0 else ", at: [1, 0]}" if i == 6 else "}")
        for i, (a, b) in enumerate(itertools.pairwise(names))
    )
    lengths = ", ".join(f"J{i}J{i + 1}: 1" for i in range(6))
    text = f"links: [{', '.join(names[:-1])}]\njoints:\n{joints}\nlengths: {{{lengths}}}\ndrive: {{link: l1, angle: 60, rpm: 60}}\n"
    path = write(text, "ring.yaml")
    for command in ("velocity", "acceleration", "icentres"):
        result = run(command, str(path))
        assert result.exit_code == 2 and result.stdout == ""
        assert "ring.yaml:11:8: error:" in result.stderr and "it needs 4 inputs" in result.stderr, command
    # with no drive at all, the refusal points at the first moving link, where `links:` names it
    result = run("velocity", str(write(text.split("drive:")[0], "ring0.yaml")))
    assert "ring0.yaml:1:16: error:" in result.stderr and "but no drive" in result.stderr, result.stderr


@pytest.mark.parametrize(
    "command",
    [
        ("sweep",),
        ("properties",),
        ("draw", "-o", "{tmp}/five.svg"),
        ("draw", "--path", "C", "-o", "{tmp}/five.svg"),
        ("position",),
    ],
    ids=["sweep", "properties", "draw", "draw --path", "position"],
)
def test_too_few_drives_are_refused_by_the_count_before_anything_is_assembled(
    command, run, write, monkeypatch
):
    """Issue 11: sweep, properties and draw assembled the chain (and took its rank) before refusing
    it (a 200-link chain: 82 s; 2,000 links: over 100 s). The pipeline now refuses from the count."""

    def assemble(*args, **kwargs):
        raise AssertionError("assembled before the count refused the file")

    monkeypatch.setattr(importlib.import_module("mech.kinematics.compiled"), "assemble", assemble)
    path = write(FIVE_BAR_ONE_DRIVE, "five.yaml")
    result = run(*(a.format(tmp=path.parent) for a in command), str(path))
    assert result.exit_code == 2 and result.stdout == ""
    assert "five.yaml:10:8: error:" in result.stderr and "but 1 drive: it needs 2 inputs" in result.stderr
    assert not (path.parent / "five.svg").exists()


# The same five-bar drawn (B, C, D with at; no lengths, the drive (line 9) without an angle): placed as drawn.
FIVE_BAR_DRAWN = (
    FIVE_BAR_ONE_DRIVE.replace("[a, b]}", "[a, b], at: [6.946, 39.392]}")
    .replace("near: [60, 80]", "at: [60, 85]")
    .replace("[c, d]}", "[c, d], at: [113.054, 39.392]}")
    .replace("lengths: {AB: 40, BC: 70, CD: 70, DE: 40}\n", "")
    .replace("angle: 80, ", "")
)


def test_a_drawn_five_bar_with_one_drive_is_drawn_but_not_swept(run, write, tmp_path):
    """What needs no drive is given (the drawing, the properties' loops); what moves it is refused:
    the sweep once marched the free chain by least squares and reported it (exit 0)."""
    path = write(FIVE_BAR_DRAWN, "five.yaml")
    swept = run("sweep", "--steps", "4", str(path))
    assert swept.exit_code == 2 and "five.yaml:9:8: error:" in swept.stderr
    assert "it needs 2 inputs" in swept.stderr
    drawn = run("draw", "-o", str(tmp_path / "five.svg"), str(path))
    assert drawn.exit_code == 0, drawn.stderr
    assert (tmp_path / "five.svg").exists()
    props = run("properties", str(path))
    assert props.exit_code == 0, props.stderr
    text = " ".join(props.stdout.split())
    assert "over the cycle: not swept" in text and "it needs 2 inputs" in text


def test_properties_that_need_no_drive_are_given_without_one(run, write):
    """Khurmi's four-bar drawn (B and C to two decimals) with no drive: Grashof's criterion needs
    only the lengths (40 + 150 < 80 + 150: crank-rocker), the cycle says why it is not swept."""
    text = (ROOT / "mechanisms" / "four_bar.yaml").read_text()
    text = text.replace("[crank, coupler]}", "[crank, coupler], at: [20.00, 34.64]}")
    text = text.replace("near: [160, 80]", "at: [163.33, 78.88]")
    text = "\n".join(line for line in text.splitlines() if not line.startswith("drive:"))
    result = run("properties", str(write(text, "four_bar.yaml")))
    assert result.exit_code == 0, result.stderr
    out = " ".join(result.stdout.split())
    assert "crank-rocker" in out and "over the cycle: not swept" in out


def test_missing_file_exits_2(run, tmp_path):
    result = run("dof", str(tmp_path / "nope.yaml"))
    assert result.exit_code == 2
    assert "no such file" in result.stderr


def test_default_file_is_mechanism_yaml(run, tmp_path, monkeypatch):
    (tmp_path / "mechanism.yaml").write_text(Path(FOUR_BAR).read_text())
    monkeypatch.chdir(tmp_path)
    result = run("dof")
    assert result.exit_code == 0 and "= 1" in result.output
    result = run("classify")
    assert result.exit_code == 0


def test_dash_reads_standard_input(run):
    result = run("dof", "-", input=Path(FOUR_BAR).read_text())
    assert result.exit_code == 0 and "n = 3(4 − 1) − 2·4 − 0 = 1" in result.output
    result = run("dof", "-", input=BAD)
    assert result.exit_code == 2 and "<stdin>:3:38" in result.stderr


def test_classify_lists_pairs(run):
    result = run("classify", FOUR_BAR)
    assert result.exit_code == 0
    assert "turning" in result.output and "lower" in result.output and "self-closed" in result.output
    data = json.loads(run("classify", "--json", FOUR_BAR).output)
    assert {p["joint"] for p in data["pairs"]} == {"A", "B", "C", "D"}
    assert all(p["counts_in"] == "j" for p in data["pairs"])


def test_unknown_option_is_a_usage_error(run):
    result = run("dof", "--frobnicate", FOUR_BAR)
    assert result.exit_code == 2


def test_schema_is_draft07_and_accepts_every_example(run):
    jsonschema = pytest.importorskip("jsonschema")
    import yaml

    schema = json.loads(run("schema").output)
    jsonschema.Draft7Validator.check_schema(schema)
    validator = jsonschema.Draft7Validator(schema)
    for path in sorted((ROOT / "mechanisms").glob("*.yaml")):
        errors = list(validator.iter_errors(yaml.safe_load(path.read_text())))
        assert not errors, (path.name, [e.message for e in errors][:3])


def test_schema_rejects_an_unknown_key(run):
    jsonschema = pytest.importorskip("jsonschema")
    schema = json.loads(run("schema").output)
    doc = {
        "links": ["frame", "crank"],
        "joints": {"A": {"type": "revolute", "links": ["frame", "crank"]}},
        "linkz": 1,
    }
    assert not jsonschema.Draft7Validator(schema).is_valid(doc)


def _run_subprocess(*args: str, env: dict[str, str] | None = None, input: str | None = None):
    return subprocess.run(
        [sys.executable, *args],
        capture_output=True,
        text=True,
        env={**os.environ, **(env or {})},
        input=input,
        check=False,
    )


def test_python_dash_m_mech_works_and_is_plain_when_piped():
    result = _run_subprocess("-m", "mech", "dof", FOUR_BAR)
    assert result.returncode == 0, result.stderr
    assert "\x1b[" not in result.stdout  # no colour codes when not a terminal
    assert "n = 3(4 − 1) − 2·4 − 0 = 1" in result.stdout


def test_no_color_gives_plain_text_even_when_forced_terminal():
    result = _run_subprocess(
        "-m", "mech", "dof", FOUR_BAR, env={"NO_COLOR": "1", "FORCE_COLOR": "", "TTY_COMPATIBLE": "1"}
    )
    assert result.returncode == 0
    assert "\x1b[" not in result.stdout


def test_dof_does_not_import_numpy():
    code = (
        "import sys; from mech.cli import main\n"
        "try:\n    main(['dof', sys.argv[1]])\nexcept SystemExit:\n    pass\n"
        "heavy = sorted(m for m in ('numpy', 'scipy') if m in sys.modules)\n"
        "print('HEAVY=' + ','.join(heavy))\n"
    )
    result = _run_subprocess("-c", code, FOUR_BAR)
    assert "HEAVY=\n" in result.stdout or result.stdout.rstrip().endswith("HEAVY="), (
        result.stdout + result.stderr
    )


def test_import_mech_and_cli_is_light():
    code = (
        "import sys, mech, mech.cli; print(sorted(m for m in ('numpy', 'rich', 'yaml') if m in sys.modules))"
    )
    result = _run_subprocess("-c", code)
    assert result.stdout.strip() == "[]", result.stdout + result.stderr


def test_library_use_without_cli():
    import mech

    m = mech.load(FOUR_BAR)
    assert mech.dof(m).n == 1
    assert mech.classify(m).chain == "four-bar"


def test_dof_mobility_sees_what_kutzbach_misses(run):
    # The double parallelogram: Kutzbach counts 0, yet it moves (one redundant constraint).
    path = str(ROOT / "mechanisms" / "double_parallelogram.yaml")
    data = json.loads(run("dof", "--mobility", "--json", path).output)
    assert data["dof"] == 0
    assert data["mobility"]["value"] == 1
    result = run("dof", "--mobility", path)
    assert "numeric mobility 1" in result.output and "it moves" in result.output


def test_dof_mobility_without_geometry_says_why(run):
    result = run("dof", "--mobility", str(ROOT / "mechanisms" / "four_bar_dof.yaml"))
    assert result.exit_code == 0
    assert "not computed" in result.output


def test_rounding_noise_prints_as_zero(run):
    # At dead centre the rod lies along the path: y = 0 and the piston stands still, exactly.
    path = str(ROOT / "mechanisms" / "slider_crank.yaml")
    data = json.loads(run("velocity", path, "--angle", "0", "--json").output)
    points = {p["point"]: p for p in data["points"]}
    assert points["B"]["position"][1] == 0.0
    assert points["B"]["velocity"] == [0.0, 0.0] and points["B"]["direction"] is None
    # the rod's angle is the direction from its origin A = (150, 0) mm to the piston B = (-450, 0) mm
    assert data["links"]["rod"]["origin"] == [0.15, 0.0]
    assert data["links"]["rod"]["angle"] == 180.0


TINY_CRANK = """
name: tiny crank
units: {length: m, angle: deg}
links: [frame, crank, rod, piston]
joints:
  O: {type: revolute, links: [frame, crank], at: [0, 0]}
  A: {type: revolute, links: [crank, rod]}
  B: {type: revolute, links: [rod, piston], near: [1, 0]}
  P: {type: prismatic, links: [piston, frame], path: {through: [0, 0], angle: 0}}
lengths: {OA: 1e-12, AB: 1}
drive: {link: crank, angle: 45, rpm: 60}
"""


def test_tiny_crank_prints_its_true_speeds(run, write):
    # r = 1e-12 m, l = 1 m, θ = 45°, ω = 2π rad/s. Closed form (r/l negligible to 1e-12):
    # v_A = rω = 6.2832e-12 m/s; v_B = −rω(sinθ + r sin2θ/(2l)) = −4.4429e-12 m/s;
    # ω_rod = −rω cosθ/(l cosφ) = −4.4429e-12 rad/s (cw). Formerly all printed as 0.
    r, w, th = 1e-12, 2 * math.pi, math.radians(45)
    data = json.loads(run("velocity", str(write(TINY_CRANK)), "--json").output)
    points = {p["point"]: p for p in data["points"]}
    assert points["A"]["speed"] == pytest.approx(r * w, rel=1e-12)
    assert points["B"]["velocity"][0] == pytest.approx(-r * w * math.sin(th), rel=1e-11)
    assert points["B"]["velocity"][1] == 0.0  # on its guide: noise, shown as the zero it is
    assert data["sliders"][0]["sliding"] == pytest.approx(-r * w * math.sin(th), rel=1e-11)
    assert data["links"]["rod"]["omega"] == pytest.approx(-r * w * math.cos(th), rel=1e-11)
    assert data["links"]["crank"]["angle"] == pytest.approx(45.0, rel=1e-12)


@pytest.mark.parametrize("name", ["four_bar", "slider_crank", "whitworth_quick_return", "watt_six_bar"])
def test_fixed_pivots_print_exactly_zero_velocity(run, name):
    # Rounding noise on ordinary mechanisms still prints as 0: a ground pivot's velocity and
    # acceleration are zero by the constraints, whatever the solve's round-off.
    from mech.loader import load

    path = ROOT / "mechanisms" / f"{name}.yaml"
    mech = load(path)
    pivots = {j.name for j in mech.joints if mech.ground in j.links and j.type == "revolute"}
    data = json.loads(run("acceleration", str(path), "--json").output)
    rows = [p for p in data["points"] if p["point"] in pivots]
    assert rows
    for p in rows:
        assert p["velocity"] == [0.0, 0.0] and p["direction"] is None, p
        assert p["acceleration"] == [0.0, 0.0], p


# -- as a user runs it (cli_runner: tracebacks shown) -------------------------------------
@pytest.mark.parametrize(
    "stdin",
    [b"\x00\x01\x02garbage", b"\xff\xfe not utf8", b"{{{{", b"", b"[1, 2]", b'"just a string"'],
)
def test_garbage_on_stdin_is_exit_2_with_an_error(stdin):
    p = mech("dof", "-", input=stdin)
    assert p.returncode == 2 and "Traceback" not in p.stderr and "error:" in p.stderr


@pytest.mark.parametrize("cmd", [["dof"], ["classify"], ["velocity"], ["acceleration"], ["icentres"]])
def test_plain_output_has_no_escape_codes(cmd):
    p = mech(*cmd, str(ROOT / "mechanisms" / "four_bar.yaml"))
    assert p.returncode == 0
    assert "\x1b" not in p.stdout and "\x1b" not in p.stderr


def test_plain_errors_have_no_escape_codes(write):
    p = mech(
        "dof", str(write("links: [frame, crank]\njoints:\n  A: {type: revolute, links: [frame, crankk]}\n"))
    )
    assert "\x1b" not in p.stderr


def _main_exit(argv: list[str], *, via_click: bool = False) -> int:
    """Run the console script's entry point (or click's half of it) in-process; its exit status."""
    from mech.cli import main as click_main
    from mech.entry import main

    with pytest.raises(SystemExit) as info:
        (click_main if via_click else main)(argv)
    return int(info.value.code or 0)


def test_a_bug_exits_70_with_one_line_on_how_to_report_it(monkeypatch, capsys):
    import mech.loader

    def broken(*args, **kwargs):
        raise ZeroDivisionError("float division by zero")

    monkeypatch.setattr(mech.loader, "load", broken)
    monkeypatch.delenv("MECH_DEBUG", raising=False)
    for args, via_click in (
        (["dof", FOUR_BAR], False),
        (["dof", FOUR_BAR], True),
        (["sweep", FOUR_BAR], False),
    ):
        assert _main_exit(args, via_click=via_click) == 70
        err = capsys.readouterr().err
        assert err.startswith("mech: internal error at ")
        assert "ZeroDivisionError: float division by zero" in err
        assert "bug in mech" in err and "MECH_DEBUG=1" in err and "--debug" in err
        assert "Traceback" not in err
        assert len(err.strip().splitlines()) == 2  # the line, and how to report it
        # no invented address: README's section on reporting, which exists, and the version
        assert "http" not in err and f"mech {__version__}" in err
        assert 'README.md, "Reporting a bug"' in err
        assert "\n## Reporting a bug\n" in (ROOT / "README.md").read_text(encoding="utf-8")


def test_exit_statuses_of_the_entry_point_are_the_documented_ones():
    from mech.commands import ExitStatus

    doc = (ROOT / "cli.md").read_text(encoding="utf-8")
    section = doc.split("### Exit statuses", 1)[1].split("\n### ", 1)[0]
    for status in ExitStatus:
        assert f"| {int(status)} |" in section, status


def test_mech_debug_shows_a_bugs_traceback(monkeypatch, capsys):
    import mech.loader

    monkeypatch.setattr(mech.loader, "load", lambda *a, **k: 1 / 0)
    monkeypatch.setenv("MECH_DEBUG", "1")
    assert _main_exit(["dof", FOUR_BAR]) == 70
    assert "Traceback" in capsys.readouterr().err


@pytest.mark.parametrize("via_click", [False, True])
def test_debug_option_shows_a_bugs_traceback(monkeypatch, capsys, via_click):
    import mech.loader

    monkeypatch.setattr(mech.loader, "load", lambda *a, **k: 1 / 0)
    monkeypatch.delenv("MECH_DEBUG", raising=False)
    assert _main_exit(["--debug", "velocity", FOUR_BAR], via_click=via_click) == 70
    err = capsys.readouterr().err
    assert "Traceback" in err and "ZeroDivisionError" in err


def test_an_interrupt_exits_130_with_one_line(monkeypatch, capsys):
    import mech.loader

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(mech.loader, "load", interrupted)
    for args in (["dof", FOUR_BAR], ["velocity", FOUR_BAR], ["sweep", FOUR_BAR], ["icentres", FOUR_BAR]):
        assert _main_exit(args) == 130
        err = capsys.readouterr().err
        assert err == "mech: interrupted\n"


INTERRUPT_ON_IMPORT = """
import os, signal, sys

class Interrupt:
    def find_spec(self, name, path=None, target=None):
        if name == sys.argv[1]:
            sys.meta_path.remove(self)
            os.kill(os.getpid(), signal.SIGINT)  # Ctrl-C, while mech is still starting
        return None

sys.meta_path.insert(0, Interrupt())
from mech.entry import main
main(sys.argv[2:])
"""


@pytest.mark.parametrize(
    ("module", "argv"),
    [
        ("mech.commands", ("dof", FOUR_BAR)),
        ("mech.commands.params", ("velocity", FOUR_BAR)),
        ("mech.cli", ("sweep", FOUR_BAR)),
        ("click", ("dof", "--", FOUR_BAR)),
        ("mech.analysis", ("velocity", FOUR_BAR)),
    ],
    ids=["fast path", "reading options", "click's commands", "click", "the analysis"],
)
def test_an_interrupt_while_starting_exits_130_without_a_traceback(module, argv):
    done = subprocess.run(
        [sys.executable, "-c", INTERRUPT_ON_IMPORT, module, *argv],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert (done.returncode, done.stderr) == (130, "mech: interrupted\n")


def test_the_entry_point_keeps_each_commands_own_status(capsys, tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(BAD, encoding="utf-8")
    assert _main_exit(["dof", FOUR_BAR]) == 0
    assert _main_exit(["dof", str(bad)]) == 2
    assert _main_exit(["dof", "--no-such-option"]) == 2
    assert "No such option" in capsys.readouterr().err


@pytest.mark.parametrize(
    "args",
    [
        ["dof", FOUR_BAR],
        ["velocity", FOUR_BAR],
        ["velocity", FOUR_BAR, "--json"],
        ["sweep", FOUR_BAR],
        ["icentres", FOUR_BAR, "--units", "mm"],
        ["check", FOUR_BAR],
    ],
)
def test_a_reader_that_has_closed_the_pipe_gives_141_and_no_message(args):
    """As for ``seq 1000000 | head -1``: 141, not 1 (which means a check failed).

    The pipe's reading end is closed before mech starts, so its first write finds
    the reader gone, whatever the machine's speed.
    """
    read, write = os.pipe()
    os.close(read)
    try:
        result = subprocess.run(
            [sys.executable, "-m", "mech", *args],
            stdout=write,
            stderr=subprocess.PIPE,
            env={**os.environ, "NO_COLOR": "1"},
            check=False,
        )
    finally:
        os.close(write)
    assert result.returncode == 141
    assert result.stderr == b""


def test_output_to_an_ascii_only_stream_spells_the_symbols_out():
    """A Windows console or a C-locale redirect: omega and deg, never UnicodeEncodeError."""
    result = _run_subprocess("-m", "mech", "velocity", FOUR_BAR, env={"PYTHONIOENCODING": "ascii"})
    assert result.returncode == 0, result.stderr
    assert "omega = 12.566 rad/s" in result.stdout
    assert "60.000 deg" in result.stdout
    result.stdout.encode("ascii")


# -- the JSON contract (cli.md, "The JSON contract") --------------------------------------------
_CONTRACT_COMMANDS = [
    ("dof", []),
    ("classify", []),
    ("icentres", []),
    ("position", []),
    ("velocity", []),
    ("acceleration", []),
    ("sweep", ["--steps", "12"]),
    ("properties", []),
    ("draw", ["-o", "{tmp}/drawing.svg"]),
]


@pytest.mark.parametrize(("command", "extra"), _CONTRACT_COMMANDS)
def test_json_reports_share_command_file_name_and_units(run, tmp_path, command, extra):
    args = [a.replace("{tmp}", str(tmp_path)) for a in extra]
    result = run(command, FOUR_BAR, "--json", *args)
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert list(data)[:3] == ["command", "file", "name"]
    assert data["command"] == command
    assert data["file"] == FOUR_BAR
    assert data["name"] == "Four-bar chain ABCD (Khurmi Ex. 7.1)"
    assert isinstance(data["units"], dict) and data["units"]["length"] in ("m", "mm")
    if "mechanism" in data:  # the older key, kept as an alias
        assert data["mechanism"] == data["name"]


def test_check_json_names_its_command_and_units_and_each_file(run):
    data = json.loads(run("check", FOUR_BAR, "--json").stdout)
    assert data["command"] == "check" and data["units"]["velocity"] == "m/s"
    assert data["results"][0]["file"] == FOUR_BAR
    assert data["results"][0]["name"] == "Four-bar chain ABCD (Khurmi Ex. 7.1)"


@pytest.mark.parametrize(("command", "extra"), [*_CONTRACT_COMMANDS, ("cam", [])])
def test_an_error_under_json_is_json_with_its_location(run, write, tmp_path, command, extra):
    """On stderr (stdout is for results), mech dof's one file too (only a list of several files
    holds its errors in the list: test_several_files_json_has_an_error_entry)."""
    bad = write("name: x\nlinks: [a\x01]\n")
    args = [a.replace("{tmp}", str(tmp_path)) for a in extra]
    result = run(command, str(bad), "--json", *args)
    assert result.exit_code == 2
    assert result.stdout == ""
    data = json.loads(result.stderr)
    assert data["text"].startswith(f"{bad}:2:10: error: ")
    assert (data["command"], data["file"], data["name"]) == (command, str(bad), None)
    problem = data["error"]["problems"][0]
    assert (problem["file"], problem["line"], problem["column"]) == (str(bad), 2, 10)
    assert "control character" in problem["message"] and problem["hint"]


# -- no input gives a traceback (cli.md, "Exit statuses") ----------------------------------------
_COMMANDS = [
    ["dof"],
    ["dof", "--mobility"],
    ["classify"],
    ["icentres"],
    ["position"],
    ["velocity"],
    ["acceleration"],
    ["sweep", "--steps", "24"],
    ["properties"],
    ["check", "--jobs", "1"],
    ["draw", "-o", "{tmp}/drawing.svg", "--velocity", "--acceleration", "--icentres"],
]


def _hostile_files():
    """YAML files grown from the four-bar example by hostile edits, or made up whole."""
    import copy

    import yaml
    from hypothesis import strategies as st

    base = yaml.safe_load(Path(FOUR_BAR).read_text(encoding="utf-8"))
    scalars = st.one_of(
        st.none(),
        st.booleans(),
        st.integers(min_value=-(10**30), max_value=10**30),
        st.sampled_from(HOSTILE_NUMBERS),
        st.floats(),
        st.text(max_size=10),
        st.sampled_from(HOSTILE_WORDS),
    )
    keys = st.one_of(
        st.sampled_from([*base, "answers", "points", "loads", "name"]), st.text(max_size=8), scalars
    )
    values = st.recursive(
        scalars,
        lambda inner: st.one_of(st.lists(inner, max_size=4), st.dictionaries(keys, inner, max_size=4)),
        max_leaves=8,
    )

    @st.composite
    def files(draw):
        kind = draw(st.sampled_from(["edited", "edited", "edited", "made up", "text"]))
        if kind == "text":
            return draw(st.text(max_size=200))
        if kind == "made up":
            return yaml.safe_dump(draw(st.dictionaries(keys, values, max_size=6)), allow_unicode=True)
        doc = copy.deepcopy(base)
        edit(draw, doc, keys, values, draw(st.integers(1, 4)))
        return yaml.safe_dump(doc, allow_unicode=True, sort_keys=False)

    return files()


def test_no_file_gives_a_traceback_or_an_undocumented_status(tmp_path_factory):
    """Generated hostile files through every command: exit 0, 1 (a check) or 2, never a bug.

    The commands run in-process through click's CliRunner, not in a subprocess: a subprocess
    costs an interpreter start-up and the imports (~0.3 s) per example, the CliRunner a few
    milliseconds, so a few hundred examples fit in seconds. What a subprocess adds — the
    console script's exits for a bug, ^C and a closed pipe — has its own tests above; here an
    exception that escapes a command is the bug that would have exited 70.
    """

    from click.testing import CliRunner
    from hypothesis import HealthCheck, given, settings
    from hypothesis import strategies as st

    runner = CliRunner()
    folder = tmp_path_factory.mktemp("hostile")

    @settings(max_examples=120, deadline=None, suppress_health_check=list(HealthCheck), derandomize=True)
    @given(text=_hostile_files(), command=st.sampled_from(_COMMANDS))
    def one(text: str, command: list[str]) -> None:
        answers_or_refuses(runner, folder, text, command)

    one()


@pytest.mark.parametrize("command", ["position", "velocity", "acceleration", "icentres", "properties"])
def test_an_angle_beyond_float_precision_is_refused_as_a_sweep_refuses_it(run, command):
    # 1e308° is held only to ~1e292° in floating point: no crank position is known there
    result = run(command, FOUR_BAR, "--angle", "1e308")
    assert result.exit_code == 2
    assert "held only to" in result.stderr and "nearer 0" in result.stderr


def test_a_large_angle_within_float_precision_is_its_turn_modulo_360(run):
    # 1e8° = 277,777 turns + 280°, exactly representable: the crank is at 280°
    result = run("position", FOUR_BAR, "--angle", "1e8", "--json")
    assert result.exit_code == 0
    assert json.loads(result.stdout)["links"]["crank"]["angle"] == pytest.approx(280.0)


def test_every_required_option_left_out_is_a_usage_error_naming_it():
    # walks every command's declarations: a command with a required option (mech draw -o, mech
    # view -o, mech variants --roster …) run without its options must stop before it runs (exit 2,
    # a required option named), never reach the command with None
    from mech.commands.params import COMMANDS

    example = str(Path(__file__).resolve().parent.parent / "mechanisms" / "four_bar.yaml")
    required = {
        command: [p.names[0] for p in params if p.is_option and p.required]
        for command, params in COMMANDS.items()
    }
    required = {command: names for command, names in required.items() if names}
    assert {"draw", "view"} <= required.keys()  # the walk has something to walk
    for command, names in required.items():
        args = [example] if any(not q.is_option for q in COMMANDS[command]) else []
        run = mech(command, *args)
        assert run.returncode == 2, (command, run.stdout, run.stderr)
        assert "Traceback" not in run.stderr
        assert any(f"Missing option '{name}'" in run.stderr for name in names), (command, run.stderr)
