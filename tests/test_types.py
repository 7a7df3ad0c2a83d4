"""src/ stays clean under mypy (configured in pyproject.toml, [tool.mypy]).

Why mypy rather than pyright: it installs from PyPI as a Python package (no Node runtime on
the machine or in CI), has a Python API the test calls in-process, reads its settings from
pyproject.toml beside ruff's, and numpy ships its stubs as a mypy-first package.  Its cache
goes to a temporary directory so the run leaves nothing in the tree.
"""

from __future__ import annotations

from pathlib import Path

import pytest

api = pytest.importorskip("mypy.api", reason="mypy comes with the test extra: pip install -e '.[test]'")

ROOT = Path(__file__).resolve().parent.parent


def test_src_is_clean_under_mypy(tmp_path_factory, monkeypatch):
    monkeypatch.chdir(ROOT)  # pyproject.toml's [tool.mypy] names the files and the settings
    cache = tmp_path_factory.mktemp("mypy-cache")
    out, err, status = api.run(["--cache-dir", str(cache), "--no-error-summary"])
    assert status == 0, out[-4000:] + err[-1000:]
