"""cli.md and README.md cannot drift from the commands they describe."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import click
import pytest

from mech.cli import cli

ROOT = Path(__file__).resolve().parent.parent
CLI_MD = (ROOT / "cli.md").read_text(encoding="utf-8")
README = (ROOT / "README.md").read_text(encoding="utf-8")


def section(name: str) -> str:
    """The text of cli.md from the heading that names ``mech <name>`` to the next heading."""
    for match in re.finditer(r"^## (.+)$", CLI_MD, flags=re.M):
        if re.search(rf"\b{name}\b", match.group(1)):
            rest = CLI_MD[match.end() :]
            end = re.search(r"^## ", rest, flags=re.M)
            return rest[: end.start()] if end else rest
    raise AssertionError(f"cli.md has no section for mech {name}")


@pytest.mark.parametrize("name", sorted(cli.commands))
def test_every_command_and_option_is_documented(name):
    # each spelling of each option, as a whole word: `--to` is not documented by `--tol`, nor `-o` by `-oo`
    text = section(name)
    command = cli.commands[name]
    for param in command.params:
        if isinstance(param, click.Option):
            for opt in (*param.opts, *param.secondary_opts):
                assert re.search(rf"(?<![\w-]){re.escape(opt)}(?![\w-])", text), (
                    f"cli.md, mech {name}: {opt} missing"
                )
    assert f"`mech {name}`" in CLI_MD or f"mech {name}" in CLI_MD


def _schema_keys(node: object) -> set[str]:
    """Every key the file format has (mech schema's properties, at every depth)."""
    keys: set[str] = set()
    if isinstance(node, dict):
        keys |= set(node.get("properties") or {})
        for child in node.values():
            keys |= _schema_keys(child)
    elif isinstance(node, list):
        for child in node:
            keys |= _schema_keys(child)
    return keys


def test_every_key_of_the_file_format_is_documented():
    # issue 22: cli.md documents the file as mech schema reads it (DESIGN §§ 1.2-1.5's keys among them)
    from mech.schema import schema

    for key in sorted(_schema_keys(schema())):
        quoted = rf"`[^`\n]*(?<![\w.-]){re.escape(key)}(?![\w-])[^`\n]*`"
        assert re.search(quoted, CLI_MD) or re.search(rf"^\s*{re.escape(key)}:", CLI_MD, re.M), key


def test_readme_starts_with_the_two_commands_ci_runs():
    block = re.search(r"```sh\n(.*?)\n```", README, flags=re.S)
    assert block is not None and README.index(block.group(0)) < 200
    lines = [ln for ln in block.group(1).splitlines() if ln.strip()]
    assert len(lines) == 2
    assert "pip install ." in lines[0] and "mech " in lines[0]
    assert "pytest" in lines[1]
    ci = (ROOT / ".ci" / "run").read_text()
    assert "README.md" in ci


def test_readme_commands_mention_shipped_examples():
    for path in re.findall(r"mechanisms/[\w.]+\.yaml", README + CLI_MD):
        assert (ROOT / path).exists(), path


def test_ci_script_is_valid_bash():
    subprocess.run(["bash", "-n", str(ROOT / ".ci" / "run")], check=True)


def test_readme_python_example_runs(monkeypatch):
    code = re.search(r"## From Python.*?```python\n(.*?)```", README, flags=re.S)
    assert code is not None
    monkeypatch.chdir(ROOT)
    exec(compile(code.group(1), "README.md", "exec"), {})


def test_readme_s_first_sample_is_what_its_command_prints():
    # the console block after the two commands: `$ mech dof mechanisms/four_bar.yaml` and its output,
    # compared line by line with the command's plain output (trailing blanks aside: rich pads tables)
    block = re.search(r"```console\n\$ (mech dof mechanisms/four_bar\.yaml)\n(.*?)```", README, flags=re.S)
    assert block is not None, "README.md: the console sample of mech dof mechanisms/four_bar.yaml is gone"
    from cli_runner import mech

    run = mech(*block.group(1).split()[1:], cwd=ROOT)
    assert run.returncode == 0, run.stderr
    got = [line.rstrip() for line in run.stdout.rstrip("\n").splitlines()]
    assert got == [line.rstrip() for line in block.group(2).rstrip("\n").splitlines()]
