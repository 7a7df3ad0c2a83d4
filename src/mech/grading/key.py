"""A problem's answer key: the reference value of each of its questions, computed (``mech key``).

The teacher's side of ``mech check``: the same compute functions
(:data:`mech.grading.COMPUTE`), the same analysis, each key at the level it needs
(an acceleration that cannot be had costs only itself), and each value as the
checker holds a claim against it — signed for an angular value (counter-clockwise
positive, shown with cw/ccw), a magnitude for a speed, ``[x, y]`` for a point.
``mech variants`` writes every student's key with it.
"""

from __future__ import annotations

import math
from typing import Any

from mech import grading
from mech._records import dataclass
from mech.answers import AnswerKey, AtInfinity, Compare, Undefined, parse_key
from mech.errors import MechError
from mech.grading.lazy import NOISE, Analysis, InternalError
from mech.model import Mechanism
from mech.units import Dimension, format_unit

__all__ = ["KeyRow", "answer_key", "questions", "reference"]


@dataclass(frozen=True, slots=True)
class KeyRow:
    """One question's answer.

    ``value`` is SI and JSON-ready: a float (signed for ω, α, torques and ratios;
    a magnitude for speeds, accelerations and lengths), an int count, a name, a
    point ``[x, y]``, ``"infinity"``, or None when it cannot be computed (``error``
    says why).  ``text`` is the value as a teacher reads it (``4.785 rad/s cw``).
    """

    key: str
    value: Any
    unit: str | None
    text: str
    error: str | None = None
    marks: float = 1.0


def questions(mech: Mechanism) -> tuple[str, ...]:
    """A problem's questions: its ``answers`` keys, else its ``asks`` (DESIGN § 1.1)."""
    return tuple(c.key for c in mech.answers) or tuple(mech.asks)


def reference(akey: AnswerKey, an: Analysis) -> Any:
    """The raw reference value of a key, from a solve of its own level when the whole one failed."""
    try:
        return grading.value(akey, an)
    except MechError:
        lower = an.below(akey.level)
        if lower is None:
            raise
        return grading.value(akey, lower)


def answer_key(mech: Mechanism, analysis: Analysis | None = None) -> tuple[KeyRow, ...]:
    """Every question of ``mech`` with its computed answer, in the file's order."""
    keys = questions(mech)
    an = analysis or Analysis(mech)
    akeys = [parse_key(k) for k in keys]
    an.need(akeys)
    return tuple(_row(akey, an, mech.marks_of(akey.key)) for akey in akeys)


def _row(akey: AnswerKey, an: Analysis, marks: float) -> KeyRow:
    unit = akey.dimension.value if akey.dimension not in (None, Dimension.NUMBER) else None
    if akey.compare in (Compare.COUNT, Compare.LABEL):
        unit = None
    try:
        raw = reference(akey, an)
    except MechError as error:
        p = error.problems[0] if error.problems else None
        why = p.message if p is not None else str(error)
        return KeyRow(akey.key, None, unit, "", f"cannot be computed: {why}", marks)
    except (Undefined, InternalError) as why:
        return KeyRow(akey.key, None, unit, "", str(why), marks)
    if akey.family == "stroke":  # a slider's travel (m) or a pivoted link's swing (rad)
        unit = _stroke_unit(an, akey.names[0], unit)
    value, text = _shown(akey, raw, unit, _floor(akey, an))
    return KeyRow(akey.key, value, unit, text, None, marks)


def _stroke_unit(an: Analysis, joint: str, default: str | None) -> str | None:
    from mech.grading.properties import cycle_of

    stroke = cycle_of(an).strokes.get(joint)
    return stroke.unit if stroke is not None else default


def _floor(akey: AnswerKey, an: Analysis) -> float:
    """Below this a value is rounding (ω of a translating rod: 2e-16 rad/s), shown as 0."""
    if akey.compare in (Compare.COUNT, Compare.LABEL, Compare.POINT):
        return 0.0
    try:
        return NOISE * an.scale(akey.dimension)
    except Exception:  # no scale to be had: nothing is rounded away
        return 0.0


def _shown(akey: AnswerKey, raw: Any, unit: str | None, floor: float = 0.0) -> tuple[Any, str]:
    """(JSON value, text) of a raw reference value, as the checker compares it."""
    if isinstance(raw, AtInfinity) or (isinstance(raw, float) and math.isinf(raw)):
        return "infinity", "infinity"
    if akey.compare is Compare.COUNT:
        return int(raw), str(int(raw))
    if akey.compare is Compare.LABEL:
        return (None, "none") if raw is None else (str(raw), str(raw))
    if akey.compare is Compare.POINT:
        x, y = (float(c) for c in raw)
        return [x, y], f"[{x:.6g}, {y:.6g}] m"
    if isinstance(raw, tuple):  # a vector quantity: graded by its magnitude
        raw = math.hypot(raw[0], raw[1])
        value = raw
    elif akey.compare is Compare.MAGNITUDE:
        value = abs(float(raw))
    else:
        value = float(raw)
    if abs(value) <= floor:
        value = 0.0
    suffix = f" {format_unit(unit)}" if unit else ""
    if akey.compare is Compare.SENSE and value != 0.0:
        return value, f"{abs(value):.6g}{suffix} {'ccw' if value > 0 else 'cw'}"
    return value, f"{value:.6g}{suffix}"
