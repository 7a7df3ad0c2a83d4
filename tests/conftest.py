"""Shared fixtures: the example library and a way to run the CLI in-process."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

ROOT = Path(__file__).resolve().parent.parent
MECHANISMS = ROOT / "mechanisms"


def example_files() -> list[Path]:
    """Every shipped example mechanism."""
    return sorted(MECHANISMS.glob("*.yaml"))


@pytest.fixture
def run():
    """Run ``mech ARGS`` in-process; returns click's Result (exit_code, stdout, stderr)."""
    from mech.cli import cli

    runner = CliRunner()

    def _run(*args: str, input: str | None = None):
        return runner.invoke(cli, list(args), input=input, catch_exceptions=False, prog_name="mech")

    return _run


@pytest.fixture
def write(tmp_path: Path):
    """Write a YAML text to a file in a temporary folder and return its path."""

    def _write(text: str, name: str = "m.yaml") -> Path:
        path = tmp_path / name
        path.write_text(text, encoding="utf-8")
        return path

    return _write
