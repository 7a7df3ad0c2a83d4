"""Start-up: each command imports only what it uses (checked on sys.modules, never on time).

The light commands are run as a user runs them, in a fresh interpreter, and
the modules they leave loaded are compared with the ones they must not need:
numpy and rich where no number is solved or no table drawn, the analyses
another command owns, and standard-library modules that cost milliseconds
(pathlib pulls urllib.parse and ipaddress; difflib is only for misspelt names).
Timings are measured by tests/benchmarks/bench_issue_table.py, not here.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

FOUR_BAR = str(Path(__file__).resolve().parents[1] / "mechanisms" / "four_bar.yaml")

COSTLY_STDLIB = ("pathlib", "urllib.parse", "ipaddress", "difflib", "tempfile", "logging", "asyncio", "email")
# click costs two interpreter start-ups: mech.entry runs the plain forms of the hot commands without it
CLI_PARSER = ("click", "mech.cli")
OTHER_ANALYSES = ("mech.kinematics", "mech.icentres", "mech.draw", "mech.check", "mech.batch", "matplotlib")


def loaded_by(*argv: str) -> set[str]:
    """Modules loaded after ``mech ARGV`` in a fresh interpreter (its output discarded).

    ``mech.entry.main`` is the console script's entry point, as ``pip install`` writes it.
    """
    code = (
        "import json, os, sys\n"
        "from mech.entry import main\n"
        "sys.stdout = open(os.devnull, 'w', encoding='utf-8')  # a UTF-8 stream, as a pipe is\n"
        "try:\n"
        "    main(sys.argv[1:])\n"
        "except SystemExit as exit:\n"
        "    assert not exit.code, exit.code\n"
        "print(json.dumps(sorted(sys.modules)), file=sys.__stdout__)\n"
    )
    env = {k: v for k, v in os.environ.items() if k != "COLUMNS"}  # pytest sets it to its terminal's
    done = subprocess.run(
        [sys.executable, "-c", code, *argv], capture_output=True, text=True, check=False, env=env
    )
    assert done.returncode == 0, done.stderr
    return set(json.loads(done.stdout))


@pytest.mark.parametrize(
    "argv",
    [("dof", "--json", FOUR_BAR), ("classify", "--json", FOUR_BAR)],
    ids=["dof --json", "classify --json"],
)
def test_counting_commands_with_json_import_neither_numpy_nor_rich(argv):
    mods = loaded_by(*argv)
    assert "mech.loader" in mods  # it did run
    unwanted = {"numpy", "rich", *COSTLY_STDLIB, *OTHER_ANALYSES, *CLI_PARSER}
    assert not (mods & unwanted), sorted(mods & unwanted)


@pytest.mark.parametrize("argv", [("dof", FOUR_BAR), ("classify", FOUR_BAR)], ids=["dof", "classify"])
def test_counting_tables_piped_import_neither_numpy_nor_rich(argv):
    # piped tables are written by mech.render.plain, byte for byte as rich writes them
    mods = loaded_by(*argv)
    assert "mech.render.plain" in mods  # it did print a table
    unwanted = {"numpy", "rich", *COSTLY_STDLIB, *OTHER_ANALYSES, *CLI_PARSER}
    assert not (mods & unwanted), sorted(mods & unwanted)


@pytest.mark.parametrize("level", ["position", "velocity", "acceleration"])
def test_kinematics_tables_piped_import_numpy_but_no_rich(level):
    mods = loaded_by(level, FOUR_BAR, "--rpm", "600")
    assert "numpy" in mods and "mech.render.plain" in mods
    unwanted = {"rich", *COSTLY_STDLIB, *CLI_PARSER, "mech.icentres", "mech.draw", "mech.check", "mech.batch"}
    assert not (mods & unwanted), sorted(mods & unwanted)


def test_velocity_json_imports_numpy_but_no_rich_drawing_or_checking():
    mods = loaded_by("velocity", FOUR_BAR, "--rpm", "600", "--json")
    assert "numpy" in mods and "mech.kinematics" in mods
    unwanted = {
        "rich",
        *COSTLY_STDLIB,
        *CLI_PARSER,
        "mech.icentres",
        "mech.draw",
        "mech.check",
        "mech.batch",
        "matplotlib",
    }
    assert not (mods & unwanted), sorted(mods & unwanted)


def test_a_file_of_pins_loads_only_the_revolute_kind():
    # the kinds are registered by where they live and imported when a file names them
    # (mech.pairs.table): a four-bar's count never loads the cam's laws or the gears' geometry
    mods = loaded_by("dof", "--json", FOUR_BAR)
    kinds = {m for m in mods if m.startswith("mech.pairs.") and m.count(".") == 2}
    assert kinds - {"mech.pairs.base", "mech.pairs.table", "mech.pairs.registry"} == {"mech.pairs.revolute"}
    assert not {m for m in mods if m.startswith("mech.cam")}
