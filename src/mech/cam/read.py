"""Reading a ``cam`` joint's ``program`` from the file, with every problem located.

The loader hands over the ``program`` nodes once all joints are read, because
a bare ``rise: 30`` means 30 mm for a follower that slides on a prismatic joint
and 30° for one that turns about a pivot, and only the other joints say which.
The reader object is the loader's: it converts numbers with the file's units
and collects problems (each with file:line:col) so that a file is reported
whole.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

from mech.cam.program import FOLLOWERS, LAW_NAMES, CamProgram, Segment, program_problems
from mech.model import Joint, JointType
from mech.units import Dimension

__all__ = ["PROGRAM_KEYS", "follower_motion_kind", "read_programs"]

PROGRAM_KEYS = ("base_radius", "follower", "roller_radius", "offset", "segments")
_SEGMENT_KINDS = ("rise", "dwell", "return")


def follower_motion_kind(joints: list[Joint], follower: str, ground: str | None) -> str | None:
    """``translating`` when the follower slides on the ground, ``oscillating`` when it turns
    about a pivot on the ground, ``None`` when neither (or both)."""
    slides = [
        j
        for j in joints
        if j.type is JointType.PRISMATIC and j.links[:1] == (follower,) and ground in j.links
    ]
    turns = [j for j in joints if j.type is JointType.REVOLUTE and follower in j.links and ground in j.links]
    if len(slides) + len(turns) != 1:
        return None
    return "translating" if slides else "oscillating"


def read_programs(reader: Any, joints: list[Joint], nodes: dict[str, Any], ground: str | None) -> list[Joint]:
    """The joints with each cam's ``program`` read from its node (problems go to ``reader``)."""
    out = []
    for joint in joints:
        node = nodes.get(joint.name)
        if node is None:
            out.append(joint)
            continue
        program = reader.guard(lambda j=joint, n=node: _program(reader, j, n, joints, ground), None)
        out.append(replace(joint, program=program) if program is not None else joint)
    return out


def _program(reader: Any, joint: Joint, node: Any, joints: list[Joint], ground: str | None) -> CamProgram:
    what = f"the program of {joint.name}"
    f = reader.mapping(node, what, allowed=PROGRAM_KEYS)
    follower_link = joint.links[1] if len(joint.links) > 1 else joint.links[0]
    motion = follower_motion_kind(joints, follower_link, ground)
    if motion is None:
        raise reader.problem(
            node,
            f"the follower {follower_link} of {joint.name} must either slide on a prismatic joint "
            f"with {ground} or turn about one revolute joint on {ground}",
            "a programme moves the second link of `links: [cam, follower]`: give it a prismatic "
            "joint (translating) or a pivot (oscillating) on the ground",
        )
    for key in ("base_radius", "follower", "segments"):
        if key not in f:
            raise reader.problem(node, f"{what} has no `{key}`", _EXAMPLE)
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
        if motion == "oscillating" and kind != "flat":
            reader.problem(
                f["offset"][0],
                "`offset` belongs to a translating follower (or an oscillating flat face)",
                "an oscillating follower's place is its pivot and its arm's length",
            )
        else:
            offset = reader.number(f["offset"][1], "the offset", Dimension.LENGTH)
    lift_dim = Dimension.LENGTH if motion == "translating" else Dimension.ANGLE
    segments = tuple(
        seg
        for seg in (
            reader.guard(lambda n=n: _segment(reader, n, lift_dim), None)
            for n in reader.sequence(f["segments"][1], "the segments")
        )
        if seg is not None
    )
    if len(segments) == len(f["segments"][1].value):
        reader.problems.extend(program_problems(segments, reader.where(f["segments"][1])))
    return CamProgram(
        base_radius=base,
        follower=kind,
        segments=segments,
        motion=motion,
        roller_radius=roller,
        offset=offset,
        where=reader.where(node),
    )


_EXAMPLE = (
    "e.g. program: {base_radius: 40, follower: roller, roller_radius: 10, segments: "
    "[{rise: 30, over: 120, law: shm}, {dwell: 30}, {return: 30, over: 150, law: cycloidal}, {dwell: 60}]}"
)


def _segment(reader: Any, node: Any, lift_dim: Dimension) -> Segment:
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
    what = "rise" if kind == "rise" else "return"
    noun = "an angle" if lift_dim is Dimension.ANGLE else "a length"
    lift = reader.number(f[kind][1], f"the {what} ({noun} for this follower)", lift_dim, positive=True)
    if "over" not in f:
        raise reader.problem(node, f"a {what} needs `over`: the cam angle it takes", "e.g. over: 120")
    over = reader.number(f["over"][1], f"`over` of the {what}", Dimension.ANGLE, positive=True)
    if over > 2 * math.pi * (1 + 1e-12):
        raise reader.problem(f["over"][1], f"a {what} cannot take more than 360° of cam angle")
    if "law" not in f:
        raise reader.problem(node, f"a {what} needs a `law`", "laws: " + ", ".join(LAW_NAMES))
    law = reader.scalar(f["law"][1], "the law")
    if law not in LAW_NAMES:
        raise reader.problem(f["law"][1], f"unknown motion law {law!r}", "laws: " + ", ".join(LAW_NAMES))
    return Segment(kind, over, lift, law, where=where)
