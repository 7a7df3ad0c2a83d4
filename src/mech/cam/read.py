"""Reading a ``cam`` joint's ``program`` from the file, with every problem located.

The pair-kind registry (:mod:`mech.pairs.contact`) calls :func:`read_program`
for a cam joint's ``program`` with the loader's node reader, which converts
numbers in the file's units and collects problems (each with file:line:col)
so that a file is reported whole.

A bare ``rise: 30`` means 30 mm for a follower that slides on a prismatic joint
and 30° for one that turns about a pivot, and only the other joints say which:
both readings are kept (:class:`mech.cam.program.Segment`) and the right one
is taken when the cam is placed (:func:`mech.cam.program.resolve`).
"""

from __future__ import annotations

import math
from typing import Any

from mech.cam.program import FOLLOWERS, LAW_NAMES, CamProgram, Segment, program_problems
from mech.units import Dimension, parse_quantity

__all__ = ["PROGRAM_KEYS", "read_program"]

PROGRAM_KEYS = ("base_radius", "follower", "roller_radius", "offset", "segments")
_SEGMENT_KINDS = ("rise", "dwell", "return")
_EXAMPLE = (
    "e.g. program: {base_radius: 40, follower: roller, roller_radius: 10, segments: "
    "[{rise: 30, over: 120, law: shm}, {dwell: 30}, {return: 30, over: 150, law: cycloidal}, {dwell: 60}]}"
)


def read_program(reader: Any, node: Any, what: str) -> CamProgram:
    """A cam joint's ``program`` mapping as a :class:`~mech.cam.program.CamProgram`.

    ``reader`` is the loader's node reader (``mapping``, ``number``,
    ``problem`` … as :class:`mech.pairs.base.Reader` lists them); a problem is
    recorded through it and, where nothing sensible can be returned, raised
    as the exception ``reader.problem`` gives.
    """
    f = reader.mapping(node, f"the program of {what}", allowed=PROGRAM_KEYS)
    for key in ("base_radius", "follower", "segments"):
        if key not in f:
            raise reader.problem(node, f"the program of {what} has no `{key}`", _EXAMPLE)
    base = reader.number(f["base_radius"][1], "the base circle's radius", Dimension.LENGTH, positive=True)
    kind = reader.scalar(f["follower"][1], "the follower")
    if kind not in FOLLOWERS:
        raise reader.problem(f["follower"][1], f"unknown follower {kind!r}", "followers: knife, roller, flat")
    roller = None
    if "roller_radius" in f:
        if kind != "roller":
            reader.problem(f["roller_radius"][0], f"`roller_radius` belongs to a roller follower, not {kind}")
        else:
            roller = reader.number(
                f["roller_radius"][1], "the roller radius", Dimension.LENGTH, positive=True
            )
    elif kind == "roller":
        reader.problem(f["follower"][1], "a roller follower needs `roller_radius`", "e.g. roller_radius: 10")
    offset = None
    if "offset" in f:
        offset = reader.number(f["offset"][1], "the offset", Dimension.LENGTH)
    items = reader.sequence(f["segments"][1], "the segments")
    segments = tuple(
        seg for seg in (reader.guard(lambda n=n: _segment(reader, n), None) for n in items) if seg is not None
    )
    provisional = _provisional(segments) if len(segments) == len(items) else None
    if provisional is not None:
        # bare lifts read either way keep their proportions: coverage and balance are checked now
        for p in program_problems(provisional, reader.where(f["segments"][1])):
            recorded = getattr(reader, "problems", None)
            if isinstance(recorded, list):
                recorded.append(p)  # the loader's list: the problem keeps its segment's place
            else:
                reader.problem(f["segments"][1], p.message, p.hint)
    return CamProgram(
        base_radius=base,
        follower=kind,
        segments=segments,
        motion=None,
        roller_radius=roller,
        offset=offset,
        where=reader.where(node),
    )


def _provisional(segments: tuple[Segment, ...]) -> tuple[Segment, ...] | None:
    """The segments with one consistent reading of their lifts, or ``None`` when they mix kinds."""
    from dataclasses import replace

    moving = [s for s in segments if s.kind != "dwell"]
    for reading in ("as_length", "as_angle"):
        lifts = [getattr(s, reading) for s in moving]
        if all(lift is not None for lift in lifts):
            it = iter(lifts)
            return tuple(s if s.kind == "dwell" else replace(s, lift=float(next(it))) for s in segments)
    return None  # a rise in mm and a return in degrees: reported when the follower is known


def _lift(reader: Any, node: Any, what: str) -> tuple[float | None, float | None]:
    """(as a length in m, as an angle in rad): a bare number both, a number with a unit one."""
    raw = reader.scalar(node, what)
    try:
        q = parse_quantity(raw)
    except (KeyError, ValueError):
        q = None
    if q is not None and q.dimension is Dimension.ANGLE:
        return None, reader.number(node, what, Dimension.ANGLE, positive=True)
    length = reader.number(node, what, Dimension.LENGTH, positive=True)
    if q is not None and q.dimension is None:
        return length, reader.number(node, what, Dimension.ANGLE, positive=True)
    return length, None


def _segment(reader: Any, node: Any) -> Segment:
    f = reader.mapping(node, "a segment", allowed=(*_SEGMENT_KINDS, "over", "law"))
    kinds = [k for k in _SEGMENT_KINDS if k in f]
    if len(kinds) != 1:
        raise reader.problem(
            node,
            "a segment is one of rise, dwell or return"
            + (f", not {' and '.join(kinds)} together" if kinds else ""),
            "e.g. {rise: 30, over: 120, law: shm}, {dwell: 30}",
        )
    kind = kinds[0]
    where = reader.where(node)
    if kind == "dwell":
        for key in ("over", "law"):
            if key in f:
                reader.problem(f[key][0], f"a dwell takes its angle as `dwell: 30`; `{key}` is not used")
        over = reader.number(f["dwell"][1], "the dwell", Dimension.ANGLE, positive=True)
        return Segment("dwell", over, where=where)
    as_length, as_angle = _lift(reader, f[kind][1], f"the {kind}")
    if "over" not in f:
        raise reader.problem(node, f"a {kind} needs `over`: the cam angle it takes", "e.g. over: 120")
    over = reader.number(f["over"][1], f"`over` of the {kind}", Dimension.ANGLE, positive=True)
    if over > 2 * math.pi * (1 + 1e-12):
        raise reader.problem(f["over"][1], f"a {kind} cannot take more than 360° of cam angle")
    if "law" not in f:
        raise reader.problem(node, f"a {kind} needs a `law`", "laws: " + ", ".join(LAW_NAMES))
    law = reader.scalar(f["law"][1], "the law")
    if law not in LAW_NAMES:
        raise reader.problem(f["law"][1], f"unknown motion law {law!r}", "laws: " + ", ".join(LAW_NAMES))
    lift = as_length if as_length is not None else as_angle
    assert lift is not None
    return Segment(kind, over, lift, law, where=where, as_length=as_length, as_angle=as_angle)
