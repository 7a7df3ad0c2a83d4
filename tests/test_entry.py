"""The console script's fast forms (mech.entry) answer exactly as click does.

mech.entry runs the plainest command lines of dof, classify, position,
velocity, acceleration and check without importing click; every other command line
goes to click.  Each case is run both ways in a fresh interpreter and the exit
status, stdout and stderr compared byte for byte, and the forms meant to be
fast are checked to be taken without click.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

from mech.entry import _fast

ROOT = Path(__file__).resolve().parents[1]
FOUR_BAR = str(ROOT / "mechanisms" / "four_bar.yaml")
SLIDER = str(ROOT / "mechanisms" / "slider_crank.yaml")
MECHANISMS = str(ROOT / "mechanisms")
REPORT = str(Path(tempfile.gettempdir()) / "mech-test-entry-report.xml")

FAST = [
    ("dof", FOUR_BAR),
    ("dof", "--json", FOUR_BAR),
    ("dof", FOUR_BAR, SLIDER, "--json"),
    ("dof", "--mobility", FOUR_BAR),
    ("dof", FOUR_BAR, "no_such_file.yaml"),
    ("dof", "--json", FOUR_BAR, "no_such_file.yaml"),
    ("classify", FOUR_BAR),
    ("classify", "--json", FOUR_BAR),
    ("velocity", FOUR_BAR, "--rpm", "600"),
    ("velocity", FOUR_BAR, "--rpm=600", "--json", "--units", "mm"),
    ("velocity", FOUR_BAR, "--rpm", "600", "--rpm", "300", "--direction", "ccw"),
    ("velocity", FOUR_BAR, "--rpm", "-5"),
    ("velocity", FOUR_BAR, "--rpm", "600", "--omega", "3"),
    ("velocity", FOUR_BAR, "--angle", "-30", "--omega", "2", "--explain"),
    ("velocity", FOUR_BAR, "--rpm", "nan"),
    ("position", FOUR_BAR, "--angle", "1e300", "--tol", "1e-10"),
    ("acceleration", SLIDER, "--rpm", "600", "--alpha", "5", "--json"),
    ("velocity", "no_such_file.yaml"),
    ("check", MECHANISMS, "-q"),
    ("check", FOUR_BAR, SLIDER, "--json", "-j", "1"),
    ("check", MECHANISMS, "--jobs=2", "--timeout", "10", "-v"),
    ("check", FOUR_BAR, "--junit", REPORT, "--quiet"),
]
SLOW = [
    ("dof", "--help"),
    ("dof", MECHANISMS),
    ("dof", "--jsn", FOUR_BAR),
    ("dof", "--json=1", FOUR_BAR),
    ("dof", "--", FOUR_BAR),
    ("classify", FOUR_BAR, SLIDER),
    ("velocity", FOUR_BAR, "--rpm", "fast"),
    ("velocity", FOUR_BAR, "--rpm"),
    ("velocity", FOUR_BAR, "--direction", "CW"),
    ("velocity", FOUR_BAR, "--alpha", "3"),
    ("position", FOUR_BAR, "--explain"),
    ("--version",),
    ("sweep", FOUR_BAR),
    ("check",),
    ("check", "no_such_folder"),
    ("check", FOUR_BAR, "-j", "0"),
    ("check", FOUR_BAR, "-j2"),
    ("check", FOUR_BAR, "-qv"),
    ("check", FOUR_BAR, "--timeout", "0"),
    ("check", FOUR_BAR, "--junit", REPORT, "--csv", REPORT),
    ("check", FOUR_BAR, "--junit", MECHANISMS),
    ("check", FOUR_BAR, "--", SLIDER),
    (),
]


def run(module: str, argv: tuple[str, ...]) -> tuple[int, str, str]:
    code = f"import sys; from {module} import main; main(sys.argv[1:])"
    done = subprocess.run(
        [sys.executable, "-c", code, *argv], capture_output=True, text=True, check=False, cwd=ROOT
    )
    return done.returncode, done.stdout, done.stderr


@pytest.mark.parametrize("argv", FAST + SLOW, ids=lambda a: " ".join(Path(x).name for x in a) or "none")
def test_command_line_answers_as_click_answers(argv):
    assert run("mech.entry", argv) == run("mech.cli", argv)


@pytest.mark.parametrize("argv", FAST, ids=lambda a: " ".join(Path(x).name for x in a))
def test_plain_forms_are_taken_without_click(argv):
    assert _fast(list(argv)) is not None


@pytest.mark.parametrize("argv", SLOW, ids=lambda a: " ".join(Path(x).name for x in a) or "none")
def test_other_forms_are_left_to_click(argv):
    assert _fast(list(argv)) is None


def test_every_option_is_declared_once_and_click_reads_the_declaration():
    """click's commands are built from mech.commands.params (issue 20, item 6): each option's
    names, help, default and type come from one declaration, which the fast path reads too."""
    import click

    from mech.cli import cli
    from mech.commands.params import COMMANDS

    assert set(cli.commands) == set(COMMANDS)
    for name, command in cli.commands.items():
        declared = {p.dest: p for p in COMMANDS[name]}
        built = {p.name: p for p in command.params if p.name != "help"}
        assert set(built) == set(declared), name
        for dest, param in built.items():
            p = declared[dest]
            if isinstance(param, click.Option):
                assert tuple(param.opts + param.secondary_opts) == p.names, (name, dest)
                assert param.help == p.help and param.multiple == p.multiple, (name, dest)
                if p.kind != "flag" and not p.multiple and p.default is not None:
                    assert param.default == p.default, (name, dest)
                elif p.kind != "flag" and not p.multiple:
                    # no default is handed to click (an explicit None lets a required option go
                    # missing in click 8.5): click's own "not given", which reaches the command as None
                    assert param.default is None or type(param.default).__name__ == "Sentinel", (name, dest)
            else:
                assert param.nargs == p.nargs and param.required == p.required, (name, dest)


def test_the_fast_path_has_no_parser_of_its_own():
    """No option is spelt in mech.entry: it reads mech.commands.params like click."""
    import re

    source = (ROOT / "src" / "mech" / "entry.py").read_text(encoding="utf-8")
    code = re.sub(r'"""(.|\n)*?"""', "", source)  # the docstrings may name options
    assert not re.findall(r"""["']--?[a-z]""", code)


@pytest.mark.parametrize(
    ("argv", "values"),
    [
        (("--rpm=600", "--units", "mm", "f.yaml"), {"rpm": 600.0, "unit_system": "mm", "file": "f.yaml"}),
        (
            ("--angle", "-30", "--rpm", "1", "--rpm", "2"),
            {"angle": -30.0, "rpm": 2.0, "file": "mechanism.yaml"},
        ),
        (("--tol", "1e-9", "-"), {"tol": 1e-9, "file": "-", "as_json": False, "direction": None}),
    ],
)
def test_the_fast_path_reads_values_as_click_converts_them(argv, values):
    from mech.commands.params import read

    read_values = read("velocity", list(argv))
    assert read_values is not None
    assert {k: read_values[k] for k in values} == values


@pytest.mark.parametrize("given, seen", [(None, "1"), ("4", "4")])
def test_a_command_asks_numpy_s_blas_for_one_thread_unless_the_user_said(given, seen):
    # read by OpenBLAS when numpy is first imported: set by the console script before any command runs
    import os

    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    if given is not None:
        env["OPENBLAS_NUM_THREADS"] = given
    probe = (
        "import os, sys\n"
        "from mech.entry import main\n"
        "try:\n"
        f"    main(['velocity', {FOUR_BAR!r}, '--json'])\n"
        "except SystemExit:\n"
        "    pass\n"
        "print(os.environ['OPENBLAS_NUM_THREADS'], 'numpy' in sys.modules, file=sys.stderr)\n"
    )
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, env=env, check=False)
    assert done.stderr.split()[-2:] == [seen, "True"], done.stderr
