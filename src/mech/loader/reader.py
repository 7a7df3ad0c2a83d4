"""The located-node reader: typed values out of YAML nodes, every problem collected.

A :class:`NodeReader` is one pass over one file.  Its readers (``mapping``,
``name``, ``number`` …) either return a value or record a located
:class:`~mech.errors.Problem` and raise :class:`Skip`, which the caller catches
at the level where reading can go on (the next joint, the next length).  At the
end :meth:`NodeReader.fail` raises every problem of the file at once.

The section readers (:mod:`mech.loader.links`, :mod:`~mech.loader.joints` …)
and the pair kinds' readers (:class:`mech.pairs.base.Reader`) all read through
one of these, so every value gets the same units, ranges and messages.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Iterable, Mapping
from typing import Any

import yaml

from mech._text import INVISIBLE, visible
from mech.errors import InputError, Problem, Where
from mech.loader.nodes import article, did_you_mean, is_null, node_kind, where_of
from mech.model import Vec
from mech.units import MAGNITUDE_RANGE, Dimension, known_units, parse_quantity

__all__ = ["NAME_PATTERN", "NodeReader", "Skip"]

NAME_PATTERN = re.compile(r"^[^\s.\-\[\]{},:#]+$")

_TRUE = {"true", "True", "TRUE", "yes", "Yes", "YES", "on", "On", "ON"}
_FALSE = {"false", "False", "FALSE", "no", "No", "NO", "off", "Off", "OFF"}


class Skip(Exception):
    """A value could not be read; its problem is already recorded."""


class NodeReader:
    """One pass over one file, collecting every problem before raising.

    Besides the problems it holds what one section tells the others: the
    file's units (``length_factor`` …, set by ``units:``) and ``tainted``, the
    names whose own errors are reported already (so that nothing echoes them).
    """

    def __init__(self, text: str, path: str) -> None:
        self.text = text
        self.path = path
        self.problems: list[Problem] = []
        self.length_factor = 1.0
        self.angle_factor = math.pi / 180.0
        self.length_unit = "m"
        self.angle_unit = "deg"
        self.tainted: set[str] = set()  # names whose own errors are reported already

    # -- problems -----------------------------------------------------------------------
    def where(self, node: yaml.Node | None) -> Where:
        return where_of(node, self.path)

    def problem(self, node: yaml.Node | None, message: str, hint: str | None = None) -> Skip:
        """Record a problem at ``node``; returns the :class:`Skip` to raise where reading stops."""
        self.problems.append(Problem(message, self.where(node), hint))
        return Skip()

    def fail(self) -> None:
        """Raise every recorded problem at once, in file order."""
        if self.problems:
            ordered = sorted(
                self.problems, key=lambda p: (p.where.line, p.where.column) if p.where else (0, 0)
            )
            raise InputError(problems=ordered, source=self.text)

    # -- generic readers ----------------------------------------------------------------
    def guard(self, fn: Callable[[], Any], default: Any) -> Any:
        try:
            return fn()
        except Skip:
            return default

    def optional(self, mapping: Mapping[str, tuple[Any, Any]], key: str, reader: Callable[..., Any]) -> Any:
        if key not in mapping:
            return None
        try:
            return reader(mapping[key][1])
        except Skip:
            return None

    def mapping(
        self, node: yaml.Node, what: str, *, allowed: Iterable[str] | None = None
    ) -> dict[str, tuple[yaml.Node, yaml.Node]]:
        """A mapping node as ``{key: (key node, value node)}``; duplicates and unknown keys reported."""
        if not isinstance(node, yaml.MappingNode):
            raise self.problem(
                node,
                f"{what} must be a mapping (`key: value` lines), not {node_kind(node)}",
                f"write {what} as `key: value` pairs, in braces ({{a: 1, b: 2}}) or one per indented line",
            )
        out: dict[str, tuple[yaml.Node, yaml.Node]] = {}
        allowed_set = set(allowed) if allowed is not None else None
        for knode, vnode in node.value:
            if not isinstance(knode, yaml.ScalarNode):
                self.problem(knode, f"a key in {what} must be a plain name, not {node_kind(knode)}")
                continue
            key = knode.value
            if key == "<<":
                self.problem(knode, "YAML merge keys (<<) are not supported", "write the keys out")
                continue
            if key in out:
                first = self.where(out[key][0])
                self.problem(
                    knode,
                    f"duplicate key {key!r} in {what} (first at line {first.line})",
                    "YAML would silently keep only the last one; remove or rename one",
                )
                continue
            if allowed_set is not None and key not in allowed_set:
                self.problem(
                    knode,
                    f"unknown key {key!r} in {what}",
                    did_you_mean(key, allowed_set, f"the keys of {what}"),
                )
                continue
            out[key] = (knode, vnode)
        return out

    def sequence(self, node: yaml.Node, what: str) -> list[yaml.Node]:
        if not isinstance(node, yaml.SequenceNode):
            raise self.problem(
                node,
                f"{what} must be a list, not {node_kind(node)}",
                "write it in brackets: [x, y] or [a, b, …]",
            )
        return list(node.value)

    def scalar(self, node: yaml.Node, what: str) -> str:
        if not isinstance(node, yaml.ScalarNode):
            raise self.problem(
                node,
                f"{what} must be a single value, not {node_kind(node)}",
                "write one value (a number, a name, or text in quotes), not a list or a mapping",
            )
        value: str = node.value  # a scalar node holds its text
        return value

    def text_value(self, node: yaml.Node) -> str:
        return self.scalar(node, "this value")

    def name(self, node: yaml.Node, what: str) -> str:
        if is_null(node):
            raise self.problem(node, f"{what} is empty", "write a name")
        value = self.scalar(node, what)
        hidden = INVISIBLE.search(value)
        if hidden is not None:
            raise self.problem(
                node,
                f"the name '{visible(value)}' for {what} holds an invisible character (U+{ord(hidden.group()):04X})",
                "names are shown in tables and typed in other keys: retype it without control "
                "or direction characters",
            )
        if not NAME_PATTERN.match(value):
            raise self.problem(
                node,
                f"{value!r} is not a usable name for {what}",
                "names are one word without spaces, dots or dashes (e.g. O2, crank, B1)",
            )
        return value

    def boolean(self, node: yaml.Node, what: str) -> bool:
        value = self.scalar(node, what)
        if value in _TRUE:
            return True
        if value in _FALSE:
            return False
        raise self.problem(node, f"{what} must be true or false, not {value!r}")

    def number(self, node: yaml.Node, what: str, dimension: Dimension, *, positive: bool = False) -> float:
        """A number in SI: a bare number is in the file's units, a string may carry its unit."""
        if is_null(node):
            raise self.problem(node, f"{what} is empty", "write a number")
        raw = self.scalar(node, what)
        try:
            q = parse_quantity(raw)
        except KeyError as exc:
            raise self.problem(
                node,
                f"unknown unit {exc.args[0]!r} in {what}",
                f"{dimension.label} units: {', '.join(known_units(dimension))}",
            ) from None
        except ValueError as exc:
            nonfinite = raw.strip().lower().lstrip("+-") in (".nan", "nan", ".inf", "inf", "infinity")
            if nonfinite:
                message = f"{what} must be a finite number, not {raw!r}"
            elif "overflows" in str(exc):
                message = f"{what} is too large: {raw} overflows in SI units"
            else:
                message = f"{what} must be a number, not {raw!r}"
            raise self.problem(node, message, f'e.g. 40 or "40 mm" ({dimension.label})') from None
        if q.sense is not None:
            raise self.problem(node, f"{what} cannot carry a sense ({q.sense})")
        if q.dimension is None:
            value = q.value * self._default_factor(dimension)
        elif q.dimension is not dimension:
            raise self.problem(
                node,
                f"{what} must be {article(dimension.label)}, but {q.unit!r} is a unit of {q.dimension.label}",
                f"{dimension.label} units: {', '.join(known_units(dimension))}",
            )
        else:
            value = q.value
        if positive and not value > 0:
            raise self.problem(
                node,
                f"{what} must be greater than zero, not {raw}",
                f"give {what} as a positive {dimension.label}",
            )
        return self.in_range(node, what, value, dimension)

    def in_range(self, node: yaml.Node, what: str, value: float, dimension: Dimension | None) -> float:
        """Refuse magnitudes no mechanism has, before they overflow or underflow the solvers."""
        low, high = MAGNITUDE_RANGE
        if value != 0.0 and not (low <= abs(value) <= high):
            unit = f" {dimension.value}" if dimension not in (None, Dimension.NUMBER) else ""
            raise self.problem(
                node,
                f"{what} is {value:g}{unit} in SI units, outside the range mech works in "
                f"({low:g} to {high:g})",
                "check the number and its unit",
            )
        return value

    def _default_factor(self, dimension: Dimension) -> float:
        """What a bare number of ``dimension`` is multiplied by (the file's ``units:``)."""
        if dimension is Dimension.LENGTH:
            return self.length_factor
        if dimension is Dimension.ANGLE:
            return self.angle_factor
        return 1.0

    def vec(self, node: yaml.Node, what: str) -> Vec:
        items = self.sequence(node, what)
        if len(items) != 2:
            raise self.problem(node, f"{what} must be a pair [x, y], not {len(items)} values")
        x = self.number(items[0], f"x of {what}", Dimension.LENGTH)
        y = self.number(items[1], f"y of {what}", Dimension.LENGTH)
        return (x, y)
