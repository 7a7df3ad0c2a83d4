"""One file's trip through mech's rooms in ``mech check``: how often it moves between rooms, and climbs.

Issue 20 item 5: a file checked by ``mech check`` should go down the rooms (batch → the pool →
check → diagnose → grading → analysis → …) and come back by returning, not bounce between
them.  This tool runs :func:`mech.batch.run` on one problem file in this process (``jobs=1``)
under :func:`sys.setprofile` and counts, over every call from a function of mech to another
function of mech (the nearest caller of mech's own, so Python's and numpy's frames in between
are transparent):

* a **move**: the caller and the callee are in different rooms;
* a **climb**: a move whose callee's room is *above* the caller's in the room order of
  /work/notes/ROOMS.md (``ROOMS`` below): a callback or a lazy back-edge;
* **entries** per room: the moves that land in it.

A room is ``mech.X`` (a module or a package: ``mech.loader.nodes`` is in ``loader``), with the
cam programme's package ``mech.pairs.cam`` in ``pairs``.  The counts are given twice: over every
room, and over the checking rooms alone (calls between two of ``CHECKING``; calls into the
rooms below them, kinematics or the loader, are not counted there).  A generator expression pulled
by its consumer (a ``(j.name for j in …)`` handed to another room) is data, not a call, and is
not counted.  A warm-up run comes
first, so that imports (module bodies) and first-use caches are not part of the trip.

Usage::

    python tests/tools/trip.py [FILE]      # default: a four-bar with a wrong answer (diagnosed)

Run it with the interpreter of the tree to measure (``/work/venvs/NAME/bin/python``).
"""

from __future__ import annotations

import argparse
import collections
import shutil
import sys
import tempfile
from pathlib import Path
from types import FrameType
from typing import Any

#: The rooms of ROOMS.md, top to bottom (a room on one line with ``|`` shares its rank).
ROOMS: tuple[tuple[str, ...], ...] = (
    ("__main__",),
    ("entry",),
    ("cli",),
    ("commands",),
    ("view",),
    ("render",),
    ("draw",),
    ("explain",),
    ("batch",),
    ("batchpool",),
    ("check",),
    ("diagnose",),
    ("grading",),
    ("analysis",),
    ("forces",),
    ("properties", "cam"),
    ("icentres",),
    ("kinematics",),
    ("topology", "schema"),
    ("loader",),
    ("answers",),
    ("pairs",),
    ("fields",),
    ("model", "options"),
    ("errors", "units"),
    ("_records", "_memo", "_text"),
)
RANK = {room: -i for i, line in enumerate(ROOMS) for room in line}  # higher rank: higher room

#: The rooms of ``mech check`` itself.
CHECKING = frozenset({"batch", "batchpool", "check", "diagnose", "grading", "analysis", "answers"})

#: A four-bar (crank AB = 40 mm at 60°, 120 rpm cw) with a right count, two right kinematic
#: answers and one wrong sense (ω of the crank claimed ccw): every step of a check is taken,
#: the diagnosis of a failed answer included.
FOUR_BAR = """\
name: four-bar
units: {length: mm, angle: deg}
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [160, 80]}
  D: {type: revolute, links: [rocker, frame], at: [150, 0]}
lengths: {AB: 40, BC: 150, CD: 80}
drive: {link: crank, angle: 60, rpm: 120, direction: cw}
answers:
  chain: four-bar
  velocity.B: 0.50265 m/s
  acceleration.B: 6.3165 m/s^2
  omega.crank: 12.566 rad/s ccw
"""


def room(module: str) -> str | None:
    """The room of a module of mech (None for the package ``mech`` itself)."""
    parts = module.split(".")
    if len(parts) < 2:
        return None
    return parts[1]


def trip(path: str) -> list[tuple[str, str]]:
    """``(caller's room, callee's room)`` for every call between two different rooms, in order."""
    from mech.batch import CheckOptions, run

    options = CheckOptions((path,), jobs=1, timeout=None)
    run(options)  # warm-up: imports and first-use caches are not the trip
    moves: list[tuple[str, str]] = []

    def profile(frame: FrameType, event: str, arg: Any) -> None:
        if event != "call" or frame.f_code.co_name == "<genexpr>":
            return  # a generator expression pulled by its consumer is data, not a call into its room
        callee = room(frame.f_globals.get("__name__", ""))
        if callee is None or not frame.f_globals.get("__name__", "").startswith("mech."):
            return
        caller_frame = frame.f_back
        while caller_frame is not None and not caller_frame.f_globals.get("__name__", "").startswith("mech."):
            caller_frame = caller_frame.f_back
        if caller_frame is None:
            return
        caller = room(caller_frame.f_globals["__name__"])
        if caller is not None and caller != callee:
            moves.append((caller, callee))

    sys.setprofile(profile)
    try:
        run(options)
    finally:
        sys.setprofile(None)
    return moves


def summary(moves: list[tuple[str, str]], label: str) -> None:
    climbs = [(a, b) for a, b in moves if RANK.get(b, -99) > RANK.get(a, -99)]
    entries = collections.Counter(b for _, b in moves)
    print(f"{label}: {len(moves)} moves between rooms, {len(climbs)} climbs back up")
    print("  entries: " + ", ".join(f"{r} {n}" for r, n in entries.most_common()))
    if climbs:
        print("  climbs:  " + ", ".join(f"{a}→{b} ×{n}" for (a, b), n in collections.Counter(climbs).items()))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("file", nargs="?", help="a problem file with answers (default: a four-bar)")
    args = parser.parse_args()
    folder = Path(tempfile.mkdtemp(prefix="mech-trip-"))
    try:
        path = args.file
        if path is None:
            path = str(folder / "four_bar.yaml")
            Path(path).write_text(FOUR_BAR, encoding="utf-8")
        moves = trip(path)
        import mech

        print(
            f"one file's trip in mech check ({path}), mech {mech.__version__} at {Path(mech.__file__).parent}"
        )
        summary(moves, "every room")
        summary([(a, b) for a, b in moves if a in CHECKING and b in CHECKING], "the checking rooms")
    finally:
        shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    main()
