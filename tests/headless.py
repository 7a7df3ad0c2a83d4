"""Headless Chromium as the page tests and the page benchmark run it (one set of flags for both).

As root on a machine with no network: no sandbox, no GPU, none of Chromium's own connections.
Debian's package (``apt-get install -y chromium``) is what ``.ci/run`` installs.
"""

from __future__ import annotations

import shutil

#: The flags every run of the browser takes; a caller adds what it asks (``--dump-dom``, a screenshot).
FLAGS = (
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
)


def chromium() -> str | None:
    """The browser's command on this machine, or None."""
    return shutil.which("chromium") or shutil.which("chromium-browser")
