"""Run mech as a user does, and read what it left (for tests of the command line in any subject).

In process through click's runner by default (fast); a real ``python -m mech``
process where only that shows the truth: a crash of the interpreter, a process
pool, a memory limit.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

__all__ = ["Run", "assert_bad_input", "close", "mech", "no_traceback", "points", "strict_json"]


class Run:
    """What a run of mech left: ``returncode``, ``stdout``, ``stderr`` (as subprocess gives)."""

    def __init__(self, returncode: int, stdout: str, stderr: str) -> None:
        self.returncode, self.stdout, self.stderr = returncode, stdout, stderr


def mech(
    *args: str,
    input: str | bytes | None = None,
    cwd: Path | None = None,
    timeout: float = 120,
    subprocess_: bool = False,
    preexec_fn=None,
):
    """Run mech ARGS as a user would, with NO_COLOR and a wide terminal.

    In process (click's runner) by default; an exception that escapes is turned into a
    ``Traceback`` on stderr, exactly what a user would see.  With ``subprocess_=True``,
    ``python -m mech`` in a real process (process pools, memory limits, crashes).
    """
    env = dict(os.environ, NO_COLOR="1", COLUMNS="200", PYTHONWARNINGS="ignore")
    if subprocess_:
        data = input.encode() if isinstance(input, str) else input
        proc = subprocess.run(
            [sys.executable, "-m", "mech", *args],
            input=data,
            capture_output=True,
            cwd=cwd,
            env=env,
            timeout=timeout,
            preexec_fn=preexec_fn,
        )
        return Run(
            proc.returncode, proc.stdout.decode("utf-8", "replace"), proc.stderr.decode("utf-8", "replace")
        )
    import traceback

    from click.testing import CliRunner

    from mech.cli import cli

    here = os.getcwd()
    try:
        if cwd is not None:
            os.chdir(cwd)
        result = CliRunner().invoke(cli, list(args), input=input, env=env, prog_name="mech")
    finally:
        os.chdir(here)
    stderr = result.stderr
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        stderr += "Traceback (most recent call last):\n" + "".join(
            traceback.format_exception(result.exception)
        )
        return Run(1, result.stdout, stderr)
    return Run(result.exit_code, result.stdout, stderr)


def strict_json(text: str):
    """json.loads that refuses NaN / Infinity tokens (not valid JSON)."""

    def bad(token: str):
        raise ValueError(f"invalid JSON constant {token}")

    return json.loads(text, parse_constant=bad)


def no_traceback(p: Run) -> None:
    """No Python traceback reached the user."""
    assert "Traceback" not in p.stderr, p.stderr[-2500:]


def assert_bad_input(proc: Run, path: Path | str | None = None, *, located: bool = True) -> None:
    """Exit 2, an ``error:`` on stderr (at ``path:line:col`` when asked), never a traceback."""
    no_traceback(proc)
    assert proc.returncode == 2, (proc.returncode, proc.stdout[-500:], proc.stderr[-1500:])
    assert "error:" in proc.stderr
    if located and path is not None:
        assert re.search(re.escape(str(path)) + r":\d+:\d+: error:", proc.stderr), proc.stderr


def points(data: dict) -> dict[str, dict]:
    """Points of a kinematics JSON (position, velocity, acceleration) by name, first entry per name."""
    out: dict[str, dict] = {}
    for p in data["points"]:
        out.setdefault(p["point"], p)
    return out


def close(a: float, b: float, rel: float = 1e-9, abs_: float = 0.0) -> bool:
    """a and b agree to ``rel`` of the larger (or to ``abs_``): numbers read back from JSON."""
    return abs(a - b) <= max(rel * max(abs(a), abs(b)), abs_)
