"""A cam's motion programme as the file gives it: segments of rise, dwell and return.

These are plain frozen records (no numpy), so that :mod:`mech.model` can hold
a programme on its ``cam`` joint without importing anything heavy.  The
follower's motion they describe is evaluated by :func:`follower_motion`.

Angles are in radians, counted from the programme's start in the sense the
cam turns; a lift is in metres for a translating follower and in radians for
an oscillating one (its arm's swing).
"""

from __future__ import annotations

import math
from dataclasses import field
from typing import TYPE_CHECKING, Any

from mech._records import dataclass
from mech.errors import Problem, Where

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from mech.cam.laws import Motion

__all__ = [
    "FOLLOWERS",
    "LAW_NAMES",
    "CamProgram",
    "Segment",
    "follower_motion",
    "program_problems",
    "program_schema",
    "resolve",
]

FOLLOWERS = ("knife", "roller", "flat")
LAW_NAMES = ("uniform", "shm", "parabolic", "cycloidal")
FULL_TURN = 2 * math.pi
_ANGLE_TOL = 1e-9  # rad: the segments' sum is 360° to this


@dataclass(frozen=True, slots=True)
class Segment:
    """One part of the programme.

    ``kind`` is ``rise``, ``dwell`` or ``return``; ``lift`` the height risen
    (or fallen) in SI (0 for a dwell); ``over`` the cam angle it takes (rad);
    ``law`` the motion law of a rise or return (``None`` for a dwell).

    The file's bare ``rise: 30`` is 30 mm for a translating follower and 30°
    for an oscillating one, and which it is follows from the follower's joint
    to the ground, known only once the whole mechanism is read.  So the reader
    keeps both readings (``as_length`` in m, ``as_angle`` in rad; one of them
    ``None`` when the value carries a unit) and :func:`resolve` picks one.
    """

    kind: str
    over: float
    lift: float = 0.0
    law: str | None = None
    where: Where | None = field(default=None, compare=False)
    as_length: float | None = None
    as_angle: float | None = None


@dataclass(frozen=True, slots=True)
class CamProgram:
    """What a ``cam`` joint's ``program`` says.

    ``motion`` is ``translating`` (the follower slides on a prismatic joint)
    or ``oscillating`` (it turns about its pivot); it is not written in the
    file but follows from the follower's joint to the ground: ``None`` until
    :func:`resolve` is told which.  ``offset`` is
    ``None`` when the file does not give it (then the follower's path decides).
    """

    base_radius: float
    follower: str
    segments: tuple[Segment, ...]
    motion: str | None = "translating"
    roller_radius: float | None = None
    offset: float | None = None
    where: Where | None = field(default=None, compare=False)

    @property
    def stroke(self) -> float:
        """The largest lift over the programme (m or rad)."""
        lift = peak = 0.0
        for seg in self.segments:
            lift += seg.lift if seg.kind == "rise" else -seg.lift if seg.kind == "return" else 0.0
            peak = max(peak, lift)
        return peak

    @property
    def starts(self) -> tuple[float, ...]:
        """The cam angle (rad) at which each segment starts."""
        out, at = [], 0.0
        for seg in self.segments:
            out.append(at)
            at += seg.over
        return tuple(out)

    @property
    def breaks(self) -> tuple[float, ...]:
        """Where a derivative of the lift may jump (rad): each segment's start, and inside a segment
        where its law's pieces meet (:data:`mech.cam.laws.KNOTS`: half-way through a parabolic one)."""
        from mech.cam.laws import KNOTS

        out = []
        for start, seg in zip(self.starts, self.segments, strict=True):
            out.append(start)
            out += [start + k * seg.over for k in KNOTS.get(seg.law or "", ())]
        return tuple(out)


def program_schema(number: dict[str, Any]) -> dict[str, Any]:
    """The JSON Schema fragment of a cam joint's ``program`` (``number``: the schema of a number)."""
    law = {"enum": list(LAW_NAMES)}
    segment = {
        "oneOf": [
            {
                "type": "object",
                "required": ["rise", "over", "law"],
                "additionalProperties": False,
                "properties": {"rise": number, "over": number, "law": law},
            },
            {
                "type": "object",
                "required": ["return", "over", "law"],
                "additionalProperties": False,
                "properties": {"return": number, "over": number, "law": law},
            },
            {
                "type": "object",
                "required": ["dwell"],
                "additionalProperties": False,
                "properties": {"dwell": number},
            },
        ]
    }
    return {
        "type": "object",
        "required": ["base_radius", "follower", "segments"],
        "additionalProperties": False,
        "properties": {
            "base_radius": number,
            "follower": {"enum": list(FOLLOWERS)},
            "roller_radius": number,
            "offset": number,
            "segments": {"type": "array", "items": segment, "minItems": 1},
        },
    }


def program_problems(segments: tuple[Segment, ...], where: Where | None) -> list[Problem]:
    """What is wrong with a list of segments, each problem placed at its segment.

    The segments must cover exactly 360°, and the follower must come back to
    where it started: a return can only fall as far as the follower has risen,
    and the rises and returns must balance at the end.
    """
    problems: list[Problem] = []
    if not segments:
        return [Problem("a cam programme needs segments", where, "e.g. [{rise: 30, over: 120, law: shm}, …]")]
    total = sum(seg.over for seg in segments)
    if abs(total - FULL_TURN) > _ANGLE_TOL:
        shown = math.degrees(total)
        problems.append(
            Problem(
                f"the segments cover {shown:.6g}°, not 360°",
                where,
                f"{'add' if shown < 360 else 'take away'} {abs(360 - shown):.6g}° "
                "(a dwell of that much, or longer or shorter segments)",
            )
        )
    lift = 0.0
    scale = max((seg.lift for seg in segments), default=0.0)
    tol = 1e-9 * max(scale, 1e-300)
    for seg in segments:
        if seg.kind == "rise":
            lift += seg.lift
        elif seg.kind == "return":
            if seg.lift > lift + tol:
                problems.append(
                    Problem(
                        f"this return falls {seg.lift:.6g} but the follower has only risen {lift:.6g} (SI units)",
                        seg.where,
                        "a return brings the follower back down: it cannot fall below where it started",
                    )
                )
            lift -= seg.lift
    if abs(lift) > tol and not problems:
        problems.append(
            Problem(
                f"the follower ends the turn {lift:.6g} (SI units) above where it started",
                segments[-1].where or where,
                "the returns must bring it back down by as much as the rises lift it",
            )
        )
    return problems


def resolve(program: CamProgram, motion: str) -> CamProgram:
    """The programme with its lifts read for a ``translating`` or ``oscillating`` follower.

    Raises :class:`~mech.errors.InputError` with every segment whose lift is of
    the wrong kind (a rise in mm for an oscillating follower …), and with the
    programme's problems once the lifts are known.
    """
    from dataclasses import replace

    from mech.errors import InputError

    angular = motion == "oscillating"
    problems: list[Problem] = []
    segments = []
    for seg in program.segments:
        if seg.kind == "dwell":
            segments.append(seg)
            continue
        lift = seg.as_angle if angular else seg.as_length
        if lift is None:
            noun, other = ("an angle", "a length") if angular else ("a length", "an angle")
            problems.append(
                Problem(
                    f"the {seg.kind} is {other}, but this follower {'turns' if angular else 'slides'}: "
                    f"its {seg.kind} is {noun}",
                    seg.where,
                    "an oscillating follower rises by an angle (deg), a translating one by a length",
                )
            )
            continue
        segments.append(replace(seg, lift=lift))
    if not problems:
        problems = program_problems(tuple(segments), program.where)
    if problems:
        raise InputError(problems=problems)
    return replace(program, motion=motion, segments=tuple(segments))


def follower_motion(program: CamProgram, theta: ArrayLike) -> Motion:
    """The follower's lift and its derivatives against cam angle, at cam angles ``theta`` (rad).

    ``theta`` is the cam's rotation from the programme's start, in the sense it
    turns; any value is taken modulo one turn.  Returns a
    :class:`mech.cam.laws.Motion` (``s`` in m or rad, ``ds`` per rad …).  At a
    boundary between segments the later segment's values are given.
    """
    import numpy as np

    from mech.cam.laws import Motion, rise

    th = np.mod(np.asarray(theta, dtype=float), FULL_TURN)
    s = np.zeros_like(th)
    ds = np.zeros_like(th)
    d2s = np.zeros_like(th)
    d3s = np.zeros_like(th)
    base = 0.0  # lift at the segment's start
    for start, seg in zip(program.starts, program.segments, strict=True):
        mask = (th >= start) & (th < start + seg.over)
        if seg is program.segments[-1]:
            mask |= th >= start
        if seg.kind == "dwell" or seg.law is None:
            s[mask] = base
        else:
            m = rise(seg.law, (th[mask] - start) / seg.over, seg.lift, seg.over)
            sign = 1.0 if seg.kind == "rise" else -1.0
            s[mask] = base + sign * m.s
            ds[mask] = sign * m.ds
            d2s[mask] = sign * m.d2s
            d3s[mask] = sign * m.d3s
            base += sign * seg.lift
    return Motion(s, ds, d2s, d3s)
