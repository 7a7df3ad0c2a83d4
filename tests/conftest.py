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


# -- the suite's cost, test by test (MECH_TEST_CPU=report.tsv python -m pytest) ------------------
# Wall time on a shared machine measures the neighbours; the CPU a test spends (its own process and
# the children it waited for) does not, and it is what the budget of issue 20 item 8 is about:
# the default run at most 90 s of CPU.  Tests above a few seconds of CPU are marked `slow`.
_CPU: list[tuple[float, str]] = []


def _cpu_now() -> float:
    import resource

    own, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


@pytest.hookimpl(wrapper=True)
def pytest_runtest_protocol(item, nextitem):
    import os

    if not os.environ.get("MECH_TEST_CPU"):
        return (yield)
    start = _cpu_now()
    try:
        return (yield)
    finally:
        _CPU.append((_cpu_now() - start, item.nodeid))


def pytest_sessionfinish(session, exitstatus):
    import os

    target = os.environ.get("MECH_TEST_CPU")
    if target and _CPU:
        lines = [f"{cpu:.3f}\t{node}" for cpu, node in sorted(_CPU, reverse=True)]
        Path(target).write_text(f"{sum(c for c, _ in _CPU):.1f}\ttotal\n" + "\n".join(lines) + "\n")
