"""mech.cam is a library: usable without the command line's rich and click."""

from __future__ import annotations

import math
import subprocess
import sys

import pytest


def test_cam_analysis_imports_neither_rich_nor_click():
    code = (
        "import sys, mech.cam.analysis, mech.cam.profile, mech.cam.read;"
        "bad = [m for m in ('rich', 'click') if m in sys.modules];"
        "print(bad); sys.exit(1 if bad else 0)"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr


def test_reading_a_file_with_a_programme_does_not_import_numpy():
    """The loader reads a programme with plain records: numpy waits for the analysis."""
    code = (
        "import sys; from mech.loader import load;"
        "m = load('mechanisms/cam_roller_program.yaml');"
        "sys.exit(1 if 'numpy' in sys.modules else 0)"
    )
    from tests.conftest import ROOT

    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert result.returncode == 0, result.stdout + result.stderr


def test_readme_cam_example_runs():
    """The README's cam-from-Python block runs and says what the file example says."""
    import re

    from tests.conftest import ROOT

    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    block = re.search(
        r"A cam from its programme, without a mechanism file:\n\n```python\n(.*?)```", readme, re.S
    )
    assert block is not None
    scope: dict[str, object] = {}
    exec(block.group(1), scope)
    a = scope["a"]
    # the cycloidal return's peak, 2hω/β = 2 · 0.03 · 10π / (150°) = 0.72 m/s
    assert abs(a.velocity.value) == pytest.approx(2 * 0.03 * 10 * math.pi / math.radians(150), rel=1e-9)
    assert not a.undercut
