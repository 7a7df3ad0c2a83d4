"""``mech view``'s pages: how big they are and how soon headless Chromium shows their first instant.

Issue 23 asks that a four-bar's page be at most 1 MB and open in under a second.  For each page
(written once by an installed ``mech``), Chromium loads it ``--runs`` times; the page stamps
``data-ready-ms`` on its body (``performance.now()`` once its first instant is drawn: parsing,
its data, and the drawing, from the start of navigation), read back from ``--dump-dom``.  The
reference, interleaved in the same run, is an empty page that stamps the same attribute from
the same script position: the ratio is the page's own cost over the browser's floor.  The
whole ``chromium --dump-dom`` process (start-up included) is timed beside it, as a user's
wait is larger than the page's.

Usage::

    python tests/benchmarks/bench_view.py [--mech mech] [--chromium chromium] [--runs 7]
"""

from __future__ import annotations

import argparse
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests"))
from headless import FLAGS, chromium  # noqa: E402  (the tests' own flags: one set for both)

EXAMPLES = ("four_bar", "slider_crank", "watt_six_bar")
EMPTY = (
    "<!DOCTYPE html><html><head><meta charset='utf-8'><title>empty</title></head><body>"
    "<script>document.body.setAttribute('data-ready-ms', performance.now().toFixed(1));</script>"
    "</body></html>"
)


def load(chromium: str, page: Path, profile: Path) -> tuple[float, float]:
    """(ms to the first instant as the page stamps it, s of the whole browser process)."""
    start = time.perf_counter()
    done = subprocess.run(
        [chromium, *FLAGS, f"--user-data-dir={profile}", "--dump-dom", page.as_uri() + "#angle=100"],
        capture_output=True,
        text=True,
        check=True,
        timeout=120,
    )
    wall = time.perf_counter() - start
    found = re.search(r'data-ready-ms="([0-9.]+)"', done.stdout)
    if found is None:
        raise SystemExit(f"{page.name}: no data-ready-ms in the DOM (did its script fail?)")
    return float(found.group(1)), wall


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--mech", default=shutil.which("mech") or "mech")
    parser.add_argument("--chromium", default=chromium() or "chromium")
    parser.add_argument("--runs", type=int, default=7)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        empty = folder / "empty.html"
        empty.write_text(EMPTY, encoding="utf-8")
        print(f"{'page':<14} {'bytes':>9} {'ready ms':>9} {'empty ms':>9} {'ratio':>6} {'process s':>10}")
        for name in EXAMPLES:
            page = folder / f"{name}.html"
            subprocess.run(
                [args.mech, "view", str(ROOT / "mechanisms" / f"{name}.yaml"), "-o", str(page)],
                check=True,
                stdout=subprocess.DEVNULL,
            )
            mine, ref, walls = [], [], []
            for k in range(args.runs):  # interleaved: the same load on the machine for both
                ms, wall = load(args.chromium, page, folder / f"p-{name}-{k}")
                mine.append(ms)
                walls.append(wall)
                ref.append(load(args.chromium, empty, folder / f"e-{name}-{k}")[0])
            a, b = statistics.median(mine), statistics.median(ref)
            print(
                f"{name:<14} {page.stat().st_size:>9,} {a:>9.1f} {b:>9.1f} {a / b:>6.2f} "
                f"{statistics.median(walls):>10.2f}"
            )


if __name__ == "__main__":
    main()
