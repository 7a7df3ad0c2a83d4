"""The ``answers:`` and ``asks:`` sections: claimed results and the questions a problem asks.

A key is one of the registered answer forms (:mod:`mech.answers`) whose names
exist in this mechanism; a value is a number with an optional unit of the
right quantity, a point, a count or a label, optionally with its own
``tolerance``.  Answer sheets (:mod:`mech.batch`) are read with the same code.
"""

from __future__ import annotations

import contextlib
import math
import re
import sys
from collections.abc import Set as AbstractSet
from dataclasses import replace

import yaml

from mech.answers import KIND_LABELS, AnswerKey, Compare, ICentreNames, key_forms, parse_key
from mech.errors import Where
from mech.loader.nodes import article, did_you_mean, text_of
from mech.loader.reader import NodeReader, Skip
from mech.model import Claim, Tolerance, Vec
from mech.units import Dimension, known_units, parse_number, parse_quantity

__all__ = ["ANSWER_KEYS", "DEFAULT_TOLERANCE", "read_answers", "read_asks", "read_claim", "read_marks"]

#: The keys of an answer written as a mapping (``{value: …, tolerance: …, marks: …}``).
ANSWER_KEYS = ("value", "tolerance", "marks")
#: The file's tolerance when ``answers`` sets none.
DEFAULT_TOLERANCE = Tolerance(0.02)

Kinds = dict[str, AbstractSet[str]]


def read_answers(r: NodeReader, node: yaml.Node, kinds: Kinds) -> tuple[list[Claim], Tolerance]:
    """Every claim of an ``answers`` mapping and the file's ``tolerance`` (2% if none)."""
    entries = r.mapping(node, "answers")
    tolerance = DEFAULT_TOLERANCE
    if "tolerance" in entries:
        with contextlib.suppress(Skip):
            tolerance = _tolerance(r, entries["tolerance"][1], None, file_level=True)
    claims: list[Claim] = []
    for key, (knode, vnode) in entries.items():
        if key == "tolerance":
            continue
        try:
            claims.append(read_claim(r, key, knode, vnode, kinds))
        except Skip:
            continue
    return claims, tolerance


def read_asks(r: NodeReader, node: yaml.Node, kinds: Kinds) -> tuple[tuple[str, ...], dict[str, float]]:
    """The questions of a problem file without values, and their marks.

    ``asks: [omega.rocker, velocity.C]`` (1 mark each), or a mapping of key to
    marks ``asks: {omega.rocker: 2, velocity.C: 3}`` (DESIGN § 1.3).
    """
    if isinstance(node, yaml.MappingNode):
        marks: dict[str, float] = {}
        for key, (knode, vnode) in r.mapping(node, "asks (answer keys and their marks)").items():
            try:
                _answer_key(r, key, knode, kinds)
                marks[key] = read_marks(r, vnode, key)
            except Skip:
                continue
        return tuple(marks), marks
    out: dict[str, yaml.Node] = {}
    for item in r.sequence(node, "asks (a list of answer keys, or a mapping of key to marks)"):
        try:
            key = r.scalar(item, "an answer key")
            _answer_key(r, key, item, kinds)
        except Skip:
            continue
        if key in out:
            r.problem(item, f"asks lists {key} twice", f"first at line {out[key].start_mark.line + 1}")
            continue
        out[key] = item
    return tuple(out), {}


def read_marks(r: NodeReader, node: yaml.Node, key: str) -> float:
    """A question's marks: a number above zero (whole or not: 0.5 marks is a mark scheme too)."""
    raw = r.scalar(node, f"the marks of {key}")
    try:
        value = parse_number(raw)
    except ValueError:
        raise r.problem(node, f"the marks of {key} must be a number, not {_shown(raw)}") from None
    if not math.isfinite(value) or value <= 0:
        raise r.problem(
            node,
            f"the marks of {key} must be above 0, not {_shown(raw)}",
            "leave the key out to ask nothing of it",
        )
    return value


def _answer_key(r: NodeReader, key: str, knode: yaml.Node, kinds: Kinds) -> AnswerKey:
    """A key of ``answers`` or ``asks``: a registered form whose names exist."""
    try:
        akey = parse_key(key)
    except ValueError as exc:
        raise r.problem(
            knode,
            str(exc),
            did_you_mean(key.split(".")[0], {f.split(".")[0] for f in key_forms()})
            or "see `answers` in cli.md",
        ) from None
    for name, kind in zip(akey.names, akey.kinds, strict=False):
        if name not in kinds[kind]:
            label = KIND_LABELS.get(kind, kind)
            choices = kinds[kind]
            near = choices.suggestions() if isinstance(choices, ICentreNames) else choices
            raise r.problem(
                knode, f"answer {key} names unknown {label} {name!r}", did_you_mean(name, near, f"{label}s")
            )
    if akey.kind.distinct and len(set(akey.names)) < len(akey.names):
        raise r.problem(
            knode,
            f"answer {key} names {akey.names[0]!r} twice",
            f"{akey.family} relates two different names",
        )
    return akey


def read_claim(r: NodeReader, key: str, knode: yaml.Node, vnode: yaml.Node, kinds: Kinds) -> Claim:
    """One answer: its key checked, its value read as the key's quantity compares."""
    akey = _answer_key(r, key, knode, kinds)
    tolerance = None
    marks: float | None = None
    value_node = vnode
    if isinstance(vnode, yaml.MappingNode):
        f = r.mapping(vnode, f"answer {key}", allowed=ANSWER_KEYS)
        if "value" not in f:
            raise r.problem(vnode, f"answer {key} has no `value`")
        value_node = f["value"][1]
        if "tolerance" in f:
            tolerance = _tolerance(r, f["tolerance"][1], akey.dimension, file_level=False)
        if "marks" in f:
            marks = read_marks(r, f["marks"][1], key)
    text = text_of(value_node)
    where = r.where(knode)
    claim = _read_value(r, key, akey, value_node, tolerance, text, where)
    return claim if marks is None else replace(claim, marks=marks)


def _read_value(
    r: NodeReader,
    key: str,
    akey: AnswerKey,
    value_node: yaml.Node,
    tolerance: Tolerance | None,
    text: str,
    where: Where,
) -> Claim:
    """A claim's value read as its key's quantity compares."""
    if akey.compare is Compare.LABEL:
        return Claim(key, r.scalar(value_node, "the chain"), None, None, tolerance, text, where)
    if akey.compare is Compare.COUNT:
        raw = r.scalar(value_node, f"answer {key}")
        if not re.fullmatch(r"[+-]?\d+", raw.strip()):
            raise r.problem(value_node, f"answer {key} is a count: a whole number, not {_shown(raw)}")
        digits = len(raw.strip().lstrip("+-"))
        if digits > _MAX_DIGITS:
            raise r.problem(
                value_node,
                f"answer {key} is a whole number of {digits:,} digits: mech reads counts of at most "
                f"{_MAX_DIGITS:,} digits",
                "a count of links, joints or freedoms is a small whole number",
            )
        return Claim(key, int(raw), Dimension.NUMBER.value, None, tolerance, text, where)
    if (
        akey.kind.infinity
        and isinstance(value_node, yaml.ScalarNode)
        and value_node.value.strip().lower() in ("infinity", "inf", "at infinity", "∞")
    ):
        unit = (akey.dimension or Dimension.LENGTH).value
        return Claim(key, "infinity", unit, None, tolerance, text, where)
    if akey.compare is Compare.POINT:
        pt = _claim_point(r, value_node, key)
        return Claim(key, pt, Dimension.LENGTH.value, None, tolerance, text, where)
    value, sense = _claim_quantity(r, key, akey, value_node)
    assert akey.dimension is not None
    return Claim(key, value, akey.dimension.value, sense, tolerance, text, where)


def _claim_quantity(
    r: NodeReader, key: str, akey: AnswerKey, value_node: yaml.Node
) -> tuple[float, str | None]:
    """A claimed number with an optional unit of the key's quantity (and a sense where it turns)."""
    dimension = akey.dimension
    assert dimension is not None
    raw = r.scalar(value_node, f"answer {key}")
    try:
        q = parse_quantity(raw)
    except KeyError as exc:
        raise r.problem(
            value_node,
            f"unknown unit {exc.args[0]!r} in answer {key}",
            f"{dimension.label} units: {', '.join(known_units(dimension))}",
        ) from None
    except ValueError:
        raise r.problem(
            value_node,
            _too_large(raw, f"answer {key}")
            or f"answer {key} must be a number with an optional unit, not {_shown(raw)}",
        ) from None
    if q.dimension is not None and q.dimension not in akey.dimensions:
        raise r.problem(
            value_node,
            f"answer {key} is {article(dimension.label)}, but {q.unit!r} is a unit of {q.dimension.label}",
            f"{dimension.label} units: {', '.join(known_units(dimension)) or 'none (a plain number)'}",
        )
    r.in_range(value_node, f"answer {key}", q.value, dimension)
    if q.sense is not None and akey.compare not in (Compare.SENSE, Compare.SIGNED):
        raise r.problem(value_node, f"answer {key} is not an angular quantity: cw/ccw does not apply")
    return q.value, q.sense


def _claim_point(r: NodeReader, node: yaml.Node, key: str) -> Vec:
    shape = "a point [x, y]" + (" or infinity" if parse_key(key).kind.infinity else "")
    items = r.sequence(node, f"answer {key} ({shape})")
    if len(items) != 2:
        raise r.problem(node, f"answer {key} must be {shape}")
    out = []
    for item in items:
        raw = r.scalar(item, "a coordinate")
        try:
            q = parse_quantity(raw)
        except (KeyError, ValueError):
            raise r.problem(
                item,
                _too_large(raw, f"a coordinate of answer {key}")
                or f"a coordinate of answer {key} must be a length, not {_shown(raw)}",
            ) from None
        if q.dimension not in (None, Dimension.LENGTH):
            raise r.problem(item, f"a coordinate of answer {key} must be a length")
        out.append(q.value)
    return (out[0], out[1])


#: The longest whole number Python reads (``sys.get_int_max_str_digits``; 4,300 by default, 0 for
#: no limit, and no limit before Python 3.11 and its patch releases of 3.10).
_MAX_DIGITS = getattr(sys, "get_int_max_str_digits", lambda: 0)() or 10**9

_DIGITS = re.compile(r"[+-]?(?=[\d_]*\d)[\d_]*\.?[\d_]*(?:[eE][+-]?\d+)?")


def _too_large(raw: str, what: str) -> str | None:
    """Why a number is refused when it is one, but beyond the largest float (1.8e308), else None."""
    number = raw.strip().split(" ", 1)[0]
    if not _DIGITS.fullmatch(number):
        return None
    try:
        value = float(number.replace("_", ""))
    except ValueError:
        return None
    if math.isfinite(value):
        return None
    digits = sum(c.isdigit() for c in number)
    return f"{what} is too large ({digits:,} digits): mech reads numbers up to about 1.8e308"


def _shown(raw: str) -> str:
    """A value as written, for a message: quoted, and cut short past 60 characters."""
    return repr(raw) if len(raw) <= 60 else repr(raw[:57]) + f"… ({len(raw):,} characters)"


def _tolerance(r: NodeReader, node: yaml.Node, dimension: Dimension | None, *, file_level: bool) -> Tolerance:
    """``2%`` (relative), or per answer a value with a unit of the answer's quantity (absolute)."""
    raw = r.scalar(node, "tolerance").strip()
    if raw.endswith("%"):
        try:
            value = parse_number(raw[:-1])
        except ValueError:
            raise r.problem(node, f"tolerance {raw!r} is not a percentage") from None
        if value < 0:
            raise r.problem(node, "a tolerance cannot be negative", "give its size, e.g. 2% or 0.05 m/s")
        return Tolerance(value / 100.0, relative=True)
    if file_level:
        raise r.problem(
            node,
            f"the file's tolerance must be a percentage such as 2%, not {raw!r}",
            "per answer, `{value: …, tolerance: 0.05 m/s}` may be absolute",
        )
    try:
        q = parse_quantity(raw)
    except (KeyError, ValueError):
        raise r.problem(node, f"tolerance {raw!r} must be a percentage or a value with a unit") from None
    if q.dimension is not None and dimension is not None and q.dimension is not dimension:
        raise r.problem(
            node,
            f"tolerance {raw!r} is {article(q.dimension.label)}, but the answer is {article(dimension.label)}",
        )
    if q.value < 0:
        raise r.problem(node, "a tolerance cannot be negative", "give its size, e.g. 2% or 0.05 m/s")
    return Tolerance(q.value, relative=False)
