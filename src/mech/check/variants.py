"""A problem for each student: ``vary:`` and ``keep:`` (DESIGN § 1.3), drawn deterministically.

A problem file may say how its given values vary from student to student::

    vary:
      lengths.AB: {from: 30, to: 50, step: 1}    # any scalar of the file, by its dotted path
      drive.rpm: [100, 120, 150, 200]            # a list: one of these
    keep:
      grashof: crank-rocker                      # an answer key and the label it must have
      transmission_angle.min: {at_least: 35 deg} # or bounds on its value (with units)

**A student's variant depends only on the seed, the file and the student's id**: each
value is chosen by a hash (SHA-256) of the seed, the file's text, the id, the attempt
and the value's path — never by a random generator's order — so adding, removing or
reordering students changes no one's variant, and the same seed gives the same class.
A variant that breaks a ``keep`` condition, does not assemble, or leaves a question
of the problem uncomputable is redrawn (the next attempt), at most
:data:`MAX_ATTEMPTS` times.

Each variant is the problem with that student's numbers, its drawn positions
recomputed (every ``near`` hint, and every ``at`` of a joint not on the frame, moved
to where that variant's solution puts it), its ``asks`` kept, and no ``vary``,
``keep`` or ``answers`` (answers' keys become ``asks``, with their marks).
"""

from __future__ import annotations

import copy
import hashlib
import math
import re
from collections.abc import Mapping, Sequence
from itertools import pairwise
from typing import Any

import yaml

from mech import loader
from mech._records import dataclass
from mech.answers import AnswerKey, Compare, parse_key
from mech.errors import InputError, MechError, Problem, Where
from mech.grading.key import KeyRow, answer_key
from mech.grading.lazy import Analysis
from mech.model import Mechanism
from mech.units import parse_quantity, to_unit

__all__ = ["MAX_ATTEMPTS", "Plan", "Variant", "plan", "variant_for"]

#: Redraws of one student's variant before giving up (the keep conditions may be too strict).
MAX_ATTEMPTS = 200

_BOOL = "tag:yaml.org,2002:bool"


class _TextLoader(yaml.SafeLoader):
    """PyYAML's safe loader with YAML 1.2's booleans (``true``, ``false``) only.

    mech reads ``on``, ``no``, ``yes``, ``off`` as text (a load's ``on: piston``, a link named
    ``no``), where YAML 1.1 would make them booleans: a variant must keep them text, and the
    dumper quotes them on the way out (``'on': piston``), so every variant reads as its problem.
    """


_TextLoader.yaml_implicit_resolvers = {
    first: [(tag, rx) for tag, rx in resolvers if tag != _BOOL]
    for first, resolvers in yaml.SafeLoader.yaml_implicit_resolvers.items()
}
_TextLoader.add_implicit_resolver(_BOOL, re.compile(r"^(?:true|True|TRUE|false|False|FALSE)$"), list("tTfF"))


@dataclass(frozen=True, slots=True)
class Plan:
    """What a problem file varies and keeps, read and checked once."""

    path: str
    text: str
    data: dict[str, Any]
    vary: tuple[tuple[str, tuple[Any, ...]], ...]
    keep: tuple[tuple[str, Any], ...]
    digest: str


@dataclass(frozen=True, slots=True)
class Variant:
    """One student's problem: its values, its text (YAML), the mechanism and its key."""

    student: str
    values: tuple[tuple[str, Any], ...]
    text: str
    mech: Mechanism
    key: tuple[KeyRow, ...]
    attempt: int


# -- reading vary and keep --------------------------------------------------------------------
def plan(path: str, text: str | None = None) -> Plan:
    """Read a problem file's ``vary`` and ``keep``; a located InputError (exit 2) if they are wrong."""
    if text is None:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    loader.loads(text, path=path)  # the problem itself must be a valid file first
    root = yaml.compose(text)
    data = yaml.load(text, Loader=_TextLoader)  # a SafeLoader: nothing is constructed from tags
    nodes = {k.value: v for k, v in root.value} if isinstance(root, yaml.MappingNode) else {}
    problems: list[Problem] = []
    where = lambda node: Where(path, node.start_mark.line + 1, node.start_mark.column + 1)  # noqa: E731
    if "vary" not in nodes:
        raise InputError(
            f"{path} has no `vary:`: every student would get the same numbers",
            where=Where(path),
            hint="add e.g. `vary: {lengths.AB: {from: 30, to: 50, step: 1}}` (DESIGN § 1.3)",
        )
    vary = []
    vnode = nodes["vary"]
    if not isinstance(vnode, yaml.MappingNode) or not vnode.value:
        raise InputError("`vary` must map dotted paths to ranges or lists", where=where(vnode))
    for knode, spec_node in vnode.value:
        dotted = str(knode.value)
        spec = data["vary"][dotted]
        try:
            _get(data, dotted)
        except (KeyError, IndexError, TypeError):
            problems.append(
                Problem(
                    f"vary: {dotted} names no value of this file",
                    where(knode),
                    "a dotted path to a scalar, e.g. lengths.AB, drive.angle, joints.D.at.0",
                )
            )
            continue
        choices = _choices(spec)
        if isinstance(choices, str):
            problems.append(Problem(f"vary: {dotted}: {choices}", where(spec_node)))
            continue
        vary.append((dotted, choices))
    keep = []
    if "keep" in nodes:
        knodes = nodes["keep"]
        if not isinstance(knodes, yaml.MappingNode):
            raise InputError(
                "`keep` must map answer keys to a label or to {at_least, at_most}", where=where(knodes)
            )
        for knode, cnode in knodes.value:
            key = str(knode.value)
            try:
                akey = parse_key(key)
            except ValueError as exc:
                problems.append(
                    Problem(
                        f"keep: {exc}", where(knode), "a condition is an answer key (see cli.md § answers)"
                    )
                )
                continue
            why = _unholdable(akey, data["keep"][key])
            if why is not None:
                problems.append(
                    Problem(
                        f"keep: {key}: {why}",
                        where(cnode),
                        "a label, or {at_least: …, at_most: …} with units (e.g. {at_least: 35 deg})",
                    )
                )
                continue
            keep.append((key, data["keep"][key]))
    if problems:
        raise InputError(problems=problems, source=text)
    digest = hashlib.sha256(text.encode("utf-8")).hexdigest()
    return Plan(path, text, data, tuple(vary), tuple(keep), digest)


def _unholdable(akey: AnswerKey, want: Any) -> str | None:
    """Why a ``keep`` condition could hold nothing (a misspelt bound, a bound not of the key's
    quantity), or None: each variant must satisfy it (DESIGN § 1.3), never pass it by a typo."""
    if not isinstance(want, dict):
        return (
            None
            if isinstance(want, (str, int, float)) and not isinstance(want, bool)
            else "a label or bounds"
        )
    if not want or set(want) - {"at_least", "at_most"}:
        wrong = ", ".join(str(k) for k in want if k not in ("at_least", "at_most"))
        return "bounds are at_least and at_most" + (f", not {wrong}" if wrong else "")
    for bound, raw in want.items():
        try:
            q = parse_quantity(str(raw)) if not isinstance(raw, bool) else None
        except (ValueError, KeyError):
            q = None
        if q is None:
            return f"{bound}: {raw!r} is not a number with a unit"
        if q.dimension is not None and akey.dimensions and q.dimension not in akey.dimensions:
            return f"{bound}: {raw} measures {q.dimension.value}, not {akey.dimensions[0].value}"
    return None


def _choices(spec: Any) -> tuple[Any, ...] | str:
    """The values a ``vary`` entry allows, in order; a string says what is wrong."""
    if isinstance(spec, list):
        return tuple(spec) if spec else "an empty list"
    if not isinstance(spec, dict) or set(spec) - {"from", "to", "step"} or not {"from", "to"} <= set(spec):
        return "a range {from, to, step} or a list of values"
    lo, hi, step = spec["from"], spec["to"], spec.get("step", 1)
    if not all(isinstance(x, (int, float)) for x in (lo, hi, step)) or step <= 0 or hi < lo:
        return "from ≤ to, and a step above 0 (numbers, in the file's units)"
    n = math.floor((hi - lo) / step + 1e-9) + 1
    whole = all(float(x).is_integer() for x in (lo, step))
    return tuple((int(lo + i * step) if whole else round(lo + i * step, 12)) for i in range(n))


def _get(data: Any, dotted: str) -> Any:
    for part in dotted.split("."):
        data = data[int(part)] if isinstance(data, list) else data[part]
    if isinstance(data, (dict, list)):
        raise TypeError(dotted)
    return data


def _set(data: Any, dotted: str, value: Any) -> None:
    parts = dotted.split(".")
    for part in parts[:-1]:
        data = data[int(part)] if isinstance(data, list) else data[part]
    last = parts[-1]
    if isinstance(data, list):
        data[int(last)] = value
    else:
        data[last] = value


# -- one student's variant ----------------------------------------------------------------------
def draw(p: Plan, seed: int, student: str, attempt: int) -> tuple[tuple[str, Any], ...]:
    """The values of one attempt: each chosen by a hash of seed, file, student, attempt and path."""
    base = f"{seed}\x1f{p.digest}\x1f{student}\x1f{attempt}".encode()
    out = []
    for dotted, choices in p.vary:
        h = hashlib.sha256(base + b"\x1f" + dotted.encode("utf-8")).digest()
        out.append((dotted, choices[int.from_bytes(h[:8], "big") % len(choices)]))
    return tuple(out)


def variant_for(p: Plan, seed: int, student: str) -> Variant:
    """``student``'s variant: the first attempt that assembles, answers every question, keeps ``keep``."""
    last = "no attempt"
    for attempt in range(MAX_ATTEMPTS):
        values = draw(p, seed, student, attempt)
        try:
            text, mech, rows = _build(p, values)
        except MechError as error:
            last = error.problems[0].message if error.problems else str(error)
            continue
        broken = next((r for r in rows if r.error is not None), None)
        if broken is not None:
            last = f"{broken.key}: {broken.error}"
            continue
        why = _broken_keep(p, mech)
        if why is None:
            return Variant(student, values, text, mech, rows, attempt)
        last = why
    raise InputError(
        f"no variant for {student} in {MAX_ATTEMPTS} attempts keeps every condition (last: {last})",
        where=Where(p.path),
        hint="widen the `vary` ranges or loosen `keep`",
    )


def _build(p: Plan, values: Sequence[tuple[str, Any]]) -> tuple[str, Mechanism, tuple[KeyRow, ...]]:
    data = copy.deepcopy(p.data)
    for dotted, value in values:
        _set(data, dotted, value)
    for k in ("vary", "keep"):
        data.pop(k, None)
    answers = data.pop("answers", None)
    if answers:  # the answers' keys are the questions (their values were the teacher's drawing's)
        asks = {
            k: (v.get("marks", 1) if isinstance(v, dict) else 1)
            for k, v in answers.items()
            if k != "tolerance"
        }
        data["asks"] = asks if any(m != 1 for m in asks.values()) else list(asks)
    first = loader.loads(_dump(data), path=p.path)
    _redraw(data, first, _teacher_positions(p))
    text = _dump(data)
    mech = loader.loads(text, path=p.path)
    return text, mech, answer_key(mech)


def _redraw(data: dict[str, Any], mech: Mechanism, teacher: Mapping[str, tuple[float, float]]) -> None:
    """Move the drawn positions to this variant's solution: ``near`` hints, ``at`` of moving joints,
    and the ``at`` of each point drawn on a moving link, kept at its place on that link."""
    joints = data.get("joints") or {}
    drawn = [n for n, j in joints.items() if isinstance(j, dict) and ("near" in j or "at" in j)]
    points = data.get("points") or {}
    placed = [
        n
        for n, pt in points.items()
        if isinstance(pt, dict)
        and isinstance(pt.get("at"), list)
        and pt.get("link") not in (None, mech.ground)
    ]
    if not drawn and not placed:
        return
    an = Analysis(mech)
    positions = an.kin.positions
    unit = mech.length_unit
    for name in placed:
        where = _kept_on_link(mech, points[name]["link"], name, teacher, positions)
        if where is not None:
            points[name]["at"] = [_round(to_unit(where[0], unit)), _round(to_unit(where[1], unit))]
    for name in drawn:
        j = joints[name]
        moving = mech.ground not in (j.get("links") or ())
        field = "near" if "near" in j else ("at" if moving else None)
        if field is None or name not in positions or not isinstance(j[field], list):
            continue
        x, y = positions[name]
        j[field] = [_round(to_unit(x, unit)), _round(to_unit(y, unit))]


def _kept_on_link(
    mech: Mechanism,
    link: str,
    name: str,
    teacher: Mapping[str, tuple[float, float]],
    now: Mapping[str, tuple[float, float]],
) -> tuple[float, float] | None:
    """Where a point of ``link`` drawn by the teacher is in this variant: at the same place on the link.

    Its place is read from the teacher's drawing against the first two of the link's joints
    (as a fraction along the line from one to the other and across it), so a coupler point
    drawn at the middle of BC stays the middle of this variant's BC, however long BC is.
    None when the link has fewer than two joints drawn apart (the point then keeps its
    coordinates, as before).
    """
    if name not in teacher:
        return None
    ends = [j.name for j in mech.joints if link in j.links and j.name in teacher and j.name in now]
    for a, b in pairwise(ends):
        (ax, ay), (bx, by) = teacher[a], teacher[b]
        dx, dy = bx - ax, by - ay
        span = dx * dx + dy * dy
        if span == 0.0:
            continue
        ex, ey = teacher[name][0] - ax, teacher[name][1] - ay
        along, across = (ex * dx + ey * dy) / span, (dx * ey - dy * ex) / span
        (ax, ay), (bx, by) = now[a], now[b]
        dx, dy = bx - ax, by - ay
        return ax + along * dx - across * dy, ay + along * dy + across * dx
    return None


_TEACHER: dict[str, Mapping[str, tuple[float, float]]] = {}


def _teacher_positions(p: Plan) -> Mapping[str, tuple[float, float]]:
    """Every located point of the teacher's own drawing (SI), solved once per problem file."""
    found = _TEACHER.get(p.digest)
    if found is None:
        try:
            found = Analysis(loader.loads(p.text, path=p.path)).kin.positions
        except Exception:  # the teacher's numbers do not assemble: the points keep their coordinates
            found = {}
        _TEACHER[p.digest] = found
    return found


def _round(v: float) -> float:
    return float(f"{v:.10g}") + 0.0


def _dump(data: dict[str, Any]) -> str:
    return yaml.safe_dump(data, sort_keys=False, allow_unicode=True, default_flow_style=None, width=100)


# -- keep conditions ---------------------------------------------------------------------------
def _broken_keep(p: Plan, mech: Mechanism) -> str | None:
    """Why ``mech`` breaks a ``keep`` condition, or None when it keeps them all."""
    if not p.keep:
        return None
    an = Analysis(mech)
    rows = {r.key: r for r in answer_key(_asking(mech, [k for k, _ in p.keep]), an)}
    for key, want in p.keep:
        row = rows[key]
        if row.error is not None:
            return f"{key}: {row.error}"
        akey = parse_key(key)
        if isinstance(want, dict):
            value = row.value
            if not isinstance(value, (int, float)):
                return f"{key} has no number to bound"
            for bound, ok in (("at_least", lambda v, b: v >= b), ("at_most", lambda v, b: v <= b)):
                if bound in want and not ok(
                    abs(value) if akey.compare is not Compare.SIGNED else value, _si(want[bound])
                ):
                    return f"{key} = {row.text} is not {bound.replace('_', ' ')} {want[bound]}"
        else:
            normal = akey.kind.normalise or (lambda s: s.strip().lower())
            if row.value is None or normal(str(row.value)) != normal(str(want)):
                return f"{key} is {row.text}, not {want}"
    return None


def _si(raw: Any) -> float:
    if isinstance(raw, (int, float)):
        return float(raw)
    return parse_quantity(str(raw)).value


def _asking(mech: Mechanism, keys: Sequence[str]) -> Mechanism:
    from dataclasses import replace

    return replace(mech, answers=(), asks=tuple(keys), marks=())
