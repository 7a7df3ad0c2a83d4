"""YAML text → :class:`~mech.model.Mechanism`: units, names, validation.

The loader walks the node tree PyYAML composes (with libyaml's C parser when
present) instead of the Python objects it would construct, for three reasons:

* every value keeps its line and column, so each message can point at it;
* a duplicate key, which YAML silently lets overwrite, is caught;
* scalars are read from their raw text, so YAML 1.1's surprises do not leak in:
  ``1e3`` is the number 1000 (PyYAML makes it a string), and a link called
  ``no`` or ``on`` is a name, not a boolean.

Nothing is constructed from tags, so the loader is as safe as ``safe_load``.
All problems in a file are gathered and raised together as one
:class:`~mech.errors.InputError`.
"""

from __future__ import annotations

import contextlib
import math
import os
import re
import sys
from collections.abc import Callable, Iterable, Mapping
from typing import Any

import yaml

from mech.answers import KIND_LABELS, AnswerKey, Compare, key_forms, names_by_kind, parse_key
from mech.errors import InputError, Problem, Where
from mech.model import (
    Claim,
    Drive,
    Joint,
    JointType,
    Length,
    Link,
    Load,
    Mechanism,
    Placement,
    Point,
    Tolerance,
    Vec,
)
from mech.pairs.registry import KINDS
from mech.units import (
    MAGNITUDE_RANGE,
    Dimension,
    known_units,
    parse_number,
    parse_quantity,
    unit_factor,
)

__all__ = ["load", "loads", "parse_answer_entries", "parse_answers"]

_YamlLoader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)

_TOP_KEYS = (
    "name",
    "description",
    "source",
    "units",
    "ground",
    "links",
    "joints",
    "lengths",
    "drive",
    "points",
    "answers",
    "asks",
    "loads",
)
_PLACE_KEYS = ("at", "near", "from", "toward", "distance", "offset")
_COMMON_JOINT_KEYS = ("type", "links", "closure", "description", *_PLACE_KEYS)
_NAME = re.compile(r"^[^\s.\-\[\]{},:#]+$")
_MAX_NODES = 200_000  # an alias bomb is refused, not expanded
_MAX_DEPTH = 64  # deeper nesting is refused before libyaml's recursive composer sees it

_PLAIN_NULLS = {"", "~", "null", "Null", "NULL"}
_TRUE = {"true", "True", "TRUE", "yes", "Yes", "YES", "on", "On", "ON"}
_FALSE = {"false", "False", "FALSE", "no", "No", "NO", "off", "Off", "OFF"}


def load(path: str | os.PathLike[str]) -> Mechanism:
    """Read a mechanism file.  ``"-"`` reads standard input.

    Raises
    ------
    InputError
        Naming the file, line and column of every problem, with a hint.
    """
    name = os.fspath(path)
    if name == "-":
        data = sys.stdin.buffer.read()
        return loads(data, path="<stdin>")
    try:
        with open(name, "rb") as f:  # not pathlib: it costs mech dof ~5 ms of start-up (urllib, ipaddress)
            data = f.read()
    except FileNotFoundError:
        raise InputError(
            f"no such file: {name}",
            where=Where(name),
            hint="check the path; with no FILE, mech reads mechanism.yaml in this folder",
        ) from None
    except IsADirectoryError:
        raise InputError(
            f"{name} is a folder, not a mechanism file",
            where=Where(name),
            hint="name a .yaml file (mech check takes folders)",
        ) from None
    except OSError as exc:
        raise InputError(f"cannot read {name}: {exc.strerror}", where=Where(name)) from None
    return loads(data, path=name)


def loads(text: str | bytes, *, path: str = "<string>") -> Mechanism:
    """Read a mechanism from YAML text (``path`` is used only in messages).

    Examples
    --------
    >>> m = loads('''
    ... links: [frame, crank, coupler, rocker]
    ... joints:
    ...   A: {type: revolute, links: [frame, crank]}
    ...   B: {type: revolute, links: [crank, coupler]}
    ...   C: {type: revolute, links: [coupler, rocker]}
    ...   D: {type: revolute, links: [rocker, frame]}
    ... ''')
    >>> m.ground, len(m.joints)
    ('frame', 4)
    """
    if isinstance(text, bytes):
        if b"\x00" in text:
            raise InputError(
                "this is a binary file, not a YAML mechanism file",
                where=Where(path),
                hint="mech reads text files in the format of cli.md (see mechanisms/ for examples)",
            )
        try:
            text = text.decode("utf-8-sig")
        except UnicodeDecodeError as exc:
            raise InputError(
                f"this file is not UTF-8 text (byte {exc.start} cannot be read)",
                where=Where(path),
                hint="save the file as UTF-8",
            ) from None
    return _Reader(text, path).read()


def parse_answers(
    node: yaml.Node, mechanism: Mechanism, *, path: str, source: str | None = None
) -> tuple[tuple[Claim, ...], Tolerance]:
    """Read an ``answers`` mapping written outside the mechanism's own file.

    ``mech check --answers SHEET`` reads a student's sheet (problem → answers)
    and validates each answers mapping exactly as the loader validates a
    file's own ``answers``: the same key grammar, names checked against
    ``mechanism``, units against the quantity.  ``node`` is the mapping node
    PyYAML composed from the sheet; ``path`` and ``source`` are the sheet's,
    so every problem points into the sheet with a caret.

    Returns the claims and the ``tolerance`` the mapping sets (2% if none).

    Raises
    ------
    InputError
        With every problem in the mapping at once.
    """
    reader = _Reader(source or "", path)
    claims, tolerance = reader.guard(
        lambda: reader._answers(node, mechanism.links, list(mechanism.joints), list(mechanism.points)),
        ([], Tolerance(0.02)),
    )
    reader.fail()
    return tuple(claims), tolerance


def parse_answer_entries(
    node: yaml.MappingNode, mechanism: Mechanism, *, path: str, source: str | None = None
) -> list[tuple[str, Where, Claim | InputError]]:
    """Each entry of an answers mapping read on its own: ``(key, where, claim or its error)``.

    For answer sheets, where one bad key must cost only that key: every entry
    is validated as :func:`parse_answers` would (same grammar, names, units),
    but a problem becomes that entry's :class:`InputError` instead of failing
    the mapping.  Keys are returned as written, repeats and ``tolerance``
    included (the caller decides what they mean on a sheet).
    """
    reader = _Reader(source or "", path)
    kinds = names_by_kind(
        (link.name for link in mechanism.links),
        (j.name for j in mechanism.joints),
        (p.name for p in mechanism.points),
        len(mechanism.links),
    )
    out: list[tuple[str, Where, Claim | InputError]] = []
    for knode, vnode in node.value:
        reader.problems = []
        key = str(knode.value) if isinstance(knode, yaml.ScalarNode) else _text(knode)
        claim: Claim | None = None
        try:
            if not isinstance(knode, yaml.ScalarNode):
                raise reader.problem(
                    knode, f"an answer key is text such as omega.rocker, not {node_kind(knode)}"
                )
            claim = reader._claim(key, knode, vnode, kinds)
        except _Skip:
            pass
        if reader.problems or claim is None:
            problems = reader.problems or [Problem("unreadable answer", reader.where(knode))]
            error = InputError(problems=problems, source=source)
            out.append((key, reader.where(knode), error))
        else:
            out.append((key, reader.where(knode), claim))
    return out


# --------------------------------------------------------------------------------------
class _Skip(Exception):
    """A value could not be read; its problem is already recorded."""


class _Reader:
    """One pass over one file, collecting every problem before raising."""

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
        if node is None or node.start_mark is None:
            return Where(self.path)
        return Where(self.path, node.start_mark.line + 1, node.start_mark.column + 1)

    def problem(self, node: yaml.Node | None, message: str, hint: str | None = None) -> _Skip:
        self.problems.append(Problem(message, self.where(node), hint))
        return _Skip()

    def fail(self) -> None:
        if self.problems:
            ordered = sorted(
                self.problems, key=lambda p: (p.where.line, p.where.column) if p.where else (0, 0)
            )
            raise InputError(problems=ordered, source=self.text)

    # -- the file -----------------------------------------------------------------------
    def read(self) -> Mechanism:
        if not self.text.strip() or all(
            not ln.strip() or ln.lstrip().startswith("#") for ln in self.text.splitlines()
        ):
            raise InputError(
                "the file is empty",
                where=Where(self.path, 1, 1),
                hint="a mechanism needs at least `links:` and `joints:` (see mechanisms/)",
            )
        try:
            self._check_depth()
            root = yaml.compose(self.text, Loader=_YamlLoader)
        except yaml.MarkedYAMLError as exc:
            mark = exc.problem_mark or exc.context_mark
            where = Where(self.path, mark.line + 1, mark.column + 1) if mark else Where(self.path)
            what = exc.problem or exc.context or "malformed YAML"
            if exc.context and exc.problem and exc.context_mark is not None and mark is exc.problem_mark:
                cm = exc.context_mark
                what += f" ({exc.context} at line {cm.line + 1}, column {cm.column + 1})"
            raise InputError(
                f"this is not valid YAML: {what}",
                where=where,
                hint=self._yaml_hint(where),
                source=self.text,
            ) from None
        except yaml.YAMLError as exc:
            raise InputError(f"this is not valid YAML: {exc}", where=Where(self.path)) from None
        if root is None:
            raise InputError("the file is empty", where=Where(self.path, 1, 1))
        self._check_size(root)
        if not isinstance(root, yaml.MappingNode):
            raise InputError(
                f"a mechanism file must be a mapping of keys (links:, joints: …), not {node_kind(root)}",
                where=self.where(root),
                hint="start with `links: [...]` and `joints: {...}`",
                source=self.text,
            )
        top = self.mapping(root, "the file", allowed=_TOP_KEYS)
        return self._mechanism(root, top)

    def _yaml_hint(self, where: Where) -> str:
        """What to look for at a YAML syntax error; tabs get a hint of their own."""
        lines = self.text.splitlines()
        nearby = lines[max(where.line - 2, 0) : where.line] if where.line else lines
        if any("\t" in line for line in nearby):
            return "YAML indents with spaces, never tabs: replace the tabs with spaces"
        return "check indentation, colons and brackets near this place"

    def _check_depth(self) -> None:
        """Refuse absurd nesting before composing: libyaml's composer recurses in C and
        would crash the interpreter (not raise) on tens of thousands of nested brackets.

        The event stream is flat, so counting depth on it is safe; it is only read
        when the text has enough brackets or dashes to nest deeply at all.
        """
        text = self.text
        if text.count("[") + text.count("{") + text.count("- ") < 4 * _MAX_DEPTH:
            return
        depth = 0
        for event in yaml.parse(text, Loader=_YamlLoader):
            if isinstance(event, (yaml.SequenceStartEvent, yaml.MappingStartEvent)):
                depth += 1
                if depth > _MAX_DEPTH:
                    mark = event.start_mark
                    raise InputError(
                        f"the file nests lists or mappings more than {_MAX_DEPTH} deep",
                        where=Where(self.path, mark.line + 1, mark.column + 1) if mark else Where(self.path),
                        hint="a mechanism file nests three or four levels; look for runaway brackets",
                    )
            elif isinstance(event, (yaml.SequenceEndEvent, yaml.MappingEndEvent)):
                depth -= 1

    def _check_size(self, root: yaml.Node) -> None:
        seen = 0
        stack = [root]
        while stack:
            node = stack.pop()
            seen += 1
            if seen > _MAX_NODES:
                raise InputError(
                    "the file expands to too many values (an alias bomb?)",
                    where=self.where(root),
                    hint="a mechanism file needs a few hundred values, not millions",
                )
            if isinstance(node, yaml.MappingNode):
                for k, v in node.value:
                    stack.extend((k, v))
            elif isinstance(node, yaml.SequenceNode):
                stack.extend(node.value)

    def _mechanism(self, root: yaml.MappingNode, top: dict[str, tuple[Any, Any]]) -> Mechanism:
        name = self.optional(top, "name", self.text_value)
        self.optional(top, "description", self.text_value)
        self.optional(top, "source", self.text_value)
        self.optional(top, "units", self._units)

        if "links" not in top:
            self.problem(root, "the file has no `links:`", "list the links: `links: [frame, crank, …]`")
            links_raw: list[tuple[str, yaml.Node, dict[str, Any]]] = []
        else:
            links_raw = self.guard(lambda: self._links(top["links"][1]), [])
        if "joints" not in top:
            self.problem(
                root,
                "the file has no `joints:`",
                "add `joints:` with e.g. `A: {type: revolute, links: [frame, crank]}`",
            )
        link_names = [n for n, _, _ in links_raw]
        ground = self._ground(root, top, link_names)
        links = tuple(
            Link(
                name=n,
                index=i,
                kind=extra.get("kind", "rigid"),
                description=extra.get("description"),
                is_ground=(n == ground),
                where=self.where(node),
            )
            for i, (n, node, extra) in enumerate(links_raw)
        )
        joints: list[Joint] = []
        if "joints" in top:
            joints = self.guard(lambda: self._joints(top["joints"][1], set(link_names)), [])
        points: list[Point] = []
        if "points" in top:
            points = self.guard(lambda: self._points(top["points"][1], set(link_names)), [])

        self._names(links_raw, top, joints, points)
        located = _located_on(joints, points)
        # a joint whose own error is reported counts as on every link, so nothing echoes it
        self._check_refs(joints, points, {**located, **{n: set(link_names) for n in self.tainted}})
        lengths: list[Length] = []
        if "lengths" in top:
            lengths = self.guard(lambda: self._lengths(top["lengths"][1], located), [])
        drives: list[Drive] = []
        if "drive" in top:
            drives = self.guard(lambda: self._drives(top["drive"][1], set(link_names), ground, joints), [])
        answers: list[Claim] = []
        tolerance = Tolerance(0.02)
        if "answers" in top:
            answers, tolerance = self.guard(
                lambda: self._answers(top["answers"][1], links, joints, points),
                ([], tolerance),
            )
        asks: tuple[str, ...] = ()
        if "asks" in top:
            asks = self.guard(lambda: self._asks(top["asks"][1], links, joints, points), ())
        loads: tuple[Load, ...] = ()
        if "loads" in top:
            loads = self.guard(lambda: self._loads(top["loads"][1], link_names, joints, points), ())
        self.fail()
        return Mechanism(
            name=name,
            path=self.path,
            ground=ground or "",
            links=links,
            joints=tuple(joints),
            points=tuple(points),
            lengths=tuple(lengths),
            drives=tuple(drives),
            answers=tuple(answers),
            asks=asks,
            loads=loads,
            tolerance=tolerance,
            length_unit=self.length_unit,
            angle_unit=self.angle_unit,
            source=self.text,
        )

    # -- generic readers ----------------------------------------------------------------
    def guard(self, fn: Callable[[], Any], default: Any) -> Any:
        try:
            return fn()
        except _Skip:
            return default

    def optional(self, mapping: Mapping[str, tuple[Any, Any]], key: str, reader: Callable[..., Any]) -> Any:
        if key not in mapping:
            return None
        try:
            return reader(mapping[key][1])
        except _Skip:
            return None

    def mapping(
        self, node: yaml.Node, what: str, *, allowed: Iterable[str] | None = None
    ) -> dict[str, tuple[yaml.Node, yaml.Node]]:
        """A mapping node as ``{key: (key node, value node)}``; duplicates and unknown keys reported."""
        if not isinstance(node, yaml.MappingNode):
            raise self.problem(node, f"{what} must be a mapping (`key: value` lines), not {node_kind(node)}")
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
                self.problem(knode, f"unknown key {key!r} in {what}", _did_you_mean(key, allowed_set))
                continue
            out[key] = (knode, vnode)
        return out

    def sequence(self, node: yaml.Node, what: str) -> list[yaml.Node]:
        if not isinstance(node, yaml.SequenceNode):
            raise self.problem(node, f"{what} must be a list, not {node_kind(node)}")
        return list(node.value)

    def scalar(self, node: yaml.Node, what: str) -> str:
        if not isinstance(node, yaml.ScalarNode):
            raise self.problem(node, f"{what} must be a single value, not {node_kind(node)}")
        return node.value

    def text_value(self, node: yaml.Node) -> str:
        return self.scalar(node, "this value")

    def name(self, node: yaml.Node, what: str) -> str:
        if is_null(node):
            raise self.problem(node, f"{what} is empty", "write a name")
        value = self.scalar(node, what)
        if not _NAME.match(value):
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
                f"{what} must be {_a(dimension.label)}, but {q.unit!r} is a unit of {q.dimension.label}",
                f"{dimension.label} units: {', '.join(known_units(dimension))}",
            )
        else:
            value = q.value
        if positive and not value > 0:
            raise self.problem(node, f"{what} must be greater than zero, not {raw}")
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

    # -- sections -----------------------------------------------------------------------
    def _units(self, node: yaml.Node) -> None:
        units = self.mapping(node, "units", allowed=("length", "angle"))
        if "length" in units:
            found = self._unit(units["length"][1], Dimension.LENGTH)
            if found:
                self.length_factor, self.length_unit = found
        if "angle" in units:
            found = self._unit(units["angle"][1], Dimension.ANGLE)
            if found:
                self.angle_factor, self.angle_unit = found

    def _unit(self, node: yaml.Node, dimension: Dimension) -> tuple[float, str] | None:
        """A unit name of ``dimension`` → (factor to SI, name); a problem otherwise."""
        name = self.scalar(node, f"the {dimension.label} unit")
        try:
            dim, factor = unit_factor(name)
        except KeyError:
            dim, factor = None, 0.0
        if dim is not dimension:
            self.problem(
                node,
                f"{name!r} is not a unit of {dimension.label}",
                f"use one of {', '.join(known_units(dimension))}",
            )
            return None
        return factor, name

    def _links(self, node: yaml.Node) -> list[tuple[str, yaml.Node, dict[str, Any]]]:
        out: list[tuple[str, yaml.Node, dict[str, Any]]] = []
        if isinstance(node, yaml.SequenceNode):
            for item in node.value:
                with contextlib.suppress(_Skip):
                    out.append((self.name(item, "a link"), item, {}))
        elif isinstance(node, yaml.MappingNode):
            for key, (knode, vnode) in self.mapping(node, "links").items():
                try:
                    name = self.name(knode, "a link")
                except _Skip:
                    continue
                extra: dict[str, Any] = {}
                empty = is_null(vnode)
                if not empty:
                    try:
                        fields = self.mapping(vnode, f"link {key}", allowed=("kind", "description"))
                    except _Skip:
                        fields = {}
                    if "kind" in fields:
                        kind = self.scalar(fields["kind"][1], "kind")
                        if kind not in ("rigid", "flexible", "fluid"):
                            self.problem(
                                fields["kind"][1],
                                f"unknown link kind {kind!r}",
                                "kind is rigid, flexible or fluid",
                            )
                        extra["kind"] = kind
                    if "description" in fields:
                        extra["description"] = self.scalar(fields["description"][1], "description")
                out.append((name, knode, extra))
        else:
            raise self.problem(
                node,
                f"links must be a list of names or a mapping, not {node_kind(node)}",
                "e.g. `links: [frame, crank, coupler, rocker]`",
            )
        if not out and not self.problems:
            raise self.problem(node, "there are no links", "a mechanism has at least two links")
        return out

    def _ground(self, root: yaml.Node, top: dict[str, tuple[Any, Any]], links: list[str]) -> str | None:
        if "ground" in top:
            vnode = top["ground"][1]
            try:
                g = self.name(vnode, "the ground link")
            except _Skip:
                return None
            if links and g not in links:
                self.problem(
                    vnode,
                    f"ground link {g!r} is not among the links",
                    _did_you_mean(g, links) or f"links: {', '.join(links)}",
                )
                return None
            return g
        candidates = [n for n in links if n in ("frame", "ground")]
        if len(candidates) == 1:
            return candidates[0]
        if len(candidates) == 2:
            self.problem(
                top["links"][1],
                "two links could be ground: frame and ground",
                "say which with `ground: frame`",
            )
            return None
        if links:
            self.problem(
                top["links"][1] if "links" in top else root,
                "no ground link: none is named frame or ground",
                "name the fixed link with `ground: <link>`",
            )
        return None

    def _place(self, fields: dict[str, tuple[Any, Any]], what: str) -> Placement:
        at = self.optional(fields, "at", lambda n: self.vec(n, f"`at` of {what}"))
        near = self.optional(fields, "near", lambda n: self.vec(n, f"`near` of {what}"))
        origin = self.optional(fields, "from", lambda n: self._anchor(n, "from", what))
        toward = self.optional(fields, "toward", lambda n: self._anchor(n, "toward", what))
        distance = self.optional(
            fields, "distance", lambda n: self.number(n, f"`distance` of {what}", Dimension.LENGTH)
        )
        offset = self.optional(fields, "offset", lambda n: self.vec(n, f"`offset` of {what}"))
        relative = [k for k in ("from", "toward", "distance", "offset") if k in fields]
        if relative:
            anchor = fields[relative[0]][0]
            if "from" not in fields or "toward" not in fields:
                self.problem(
                    anchor, f"{what} is placed relative to two points: give both `from` and `toward`"
                )
            if ("distance" in fields) == ("offset" in fields):
                self.problem(anchor, f"{what} needs exactly one of `distance` or `offset` with from/toward")
            if "at" in fields:
                self.problem(fields["at"][0], f"{what} has both `at` and from/toward", "place it one way")
        return Placement(at=at, near=near, origin=origin, toward=toward, distance=distance, offset=offset)

    def _anchor(self, node: yaml.Node, key: str, what: str) -> str:
        """``from``/``toward`` of a placement: the name of a point of the same link."""
        if isinstance(node, yaml.SequenceNode):
            raise self.problem(
                node,
                f"`{key}` of {what} must name a joint or point of the same link, not coordinates",
                "coordinates place it with `at: [x, y]`; from/toward keep it rigid on its link as it moves",
            )
        return self.name(node, f"`{key}` of {what}")

    def _joints(self, node: yaml.Node, links: set[str]) -> list[Joint]:
        joints: list[Joint] = []
        entries = self.mapping(node, "joints")
        if not entries:
            raise self.problem(node, "there are no joints")
        for key, (knode, vnode) in entries.items():
            try:
                joints.append(self._joint(knode, vnode, links))
            except _Skip:
                self.tainted.add(key)  # reported already: lengths naming it would only echo it
                continue
        return joints

    def _joint(self, knode: yaml.Node, vnode: yaml.Node, links: set[str]) -> Joint:
        name = self.name(knode, "a joint")
        what = f"joint {name}"
        fields = self.mapping(vnode, what)
        if "type" not in fields:
            raise self.problem(
                vnode,
                f"{what} has no `type`",
                "e.g. `type: revolute` (" + ", ".join(t.value for t in JointType) + ")",
            )
        type_node = fields["type"][1]
        type_text = self.scalar(type_node, "the joint type")
        try:
            jtype = JointType(type_text)
        except ValueError:
            raise self.problem(
                type_node,
                f"unknown joint type {type_text!r}",
                _did_you_mean(type_text, [t.value for t in JointType])
                or "types: " + ", ".join(t.value for t in JointType),
            ) from None
        pair = KINDS[jtype]
        allowed = set(_COMMON_JOINT_KEYS) | set(pair.keys)
        for key, (kn, _) in fields.items():
            if key not in allowed:
                others = [t.value for t, k in KINDS.items() if key in k.keys]
                hint = (
                    f"`{key}` belongs to {', '.join(others)} joints"
                    if others
                    else _did_you_mean(key, allowed)
                )
                self.problem(kn, f"unknown key {key!r} for a {jtype.value} joint", hint)
        if "links" not in fields:
            raise self.problem(vnode, f"{what} has no `links`", "e.g. `links: [frame, crank]`")
        lnode = fields["links"][1]
        names: list[str] = []
        for item in self.sequence(lnode, f"the links of {what}"):
            try:
                ln = self.name(item, "a link")
            except _Skip:
                continue
            if links and ln not in links:
                self.tainted.add(name)  # lengths to this joint would only repeat the error
                self.problem(
                    item,
                    f"{what} names unknown link {ln!r}",
                    _did_you_mean(ln, links) or "add it to `links:`",
                )
            elif ln in names:
                self.problem(item, f"{what} lists link {ln!r} twice")
            else:
                names.append(ln)
        if len(lnode.value) < 2:
            raise self.problem(
                lnode,
                f"{what} joins {len(lnode.value)} link; a joint joins at least two",
                "list both links it connects",
            )
        if pair.max_links is not None and len(lnode.value) > pair.max_links:
            raise self.problem(
                lnode,
                f"a {jtype.value} joint joins exactly two links, not {len(lnode.value)}",
                "only a revolute (pin) joint may join more than two",
            )
        place = self._place(fields, what)
        own = {k: v for k, v in fields.items() if k in pair.keys}
        spec = pair.read(self, own, what, tuple(names))
        closure = self.optional(fields, "closure", lambda n: self.scalar(n, "closure"))
        if closure is not None and closure not in ("form", "force", "self"):
            self.problem(
                fields["closure"][1], f"unknown closure {closure!r}", "closure is form (self-closed) or force"
            )
        if "description" in fields:
            self.scalar(fields["description"][1], "description")
        return Joint(
            name=name,
            type=jtype,
            links=tuple(names),
            place=place,
            spec=spec,
            closure=closure,
            where=self.where(knode),
        )

    def _points(self, node: yaml.Node, links: set[str]) -> list[Point]:
        out: list[Point] = []
        for _key, (knode, vnode) in self.mapping(node, "points").items():
            try:
                name = self.name(knode, "a point")
                what = f"point {name}"
                fields = self.mapping(vnode, what, allowed=("link", "description", *_PLACE_KEYS))
                if "link" not in fields:
                    raise self.problem(vnode, f"{what} has no `link`", "say which link it is fixed on")
                link = self.name(fields["link"][1], f"the link of {what}")
                if links and link not in links:
                    raise self.problem(
                        fields["link"][1], f"{what} is on unknown link {link!r}", _did_you_mean(link, links)
                    )
                place = self._place(fields, what)
                if place.at is None and not place.is_relative:
                    raise self.problem(
                        vnode,
                        f"{what} is not placed",
                        "give `at: [x, y]` or `from`/`toward` with `distance` or `offset`",
                    )
                out.append(Point(name=name, link=link, place=place, where=self.where(knode)))
            except _Skip:
                continue
        return out

    def _names(
        self,
        links: list[tuple[str, yaml.Node, dict[str, Any]]],
        top: dict[str, tuple[Any, Any]],
        joints: list[Joint],
        points: list[Point],
    ) -> None:
        """Links, joints and points share one namespace."""
        seen: dict[str, str] = {}
        entries: list[tuple[str, str, Where | None]] = [(n, "link", self.where(node)) for n, node, _ in links]
        entries += [(j.name, "joint", j.where) for j in joints]
        entries += [(p.name, "point", p.where) for p in points]
        for name, kind, where in entries:
            if name in seen:
                self.problems.append(
                    Problem(
                        f"the name {name!r} is used twice (a {seen[name]} and a {kind})",
                        where,
                        "links, joints and points share one set of names",
                    )
                )
            else:
                seen[name] = kind

    def _check_refs(self, joints: list[Joint], points: list[Point], located: dict[str, set[str]]) -> None:
        """Names used in from/toward, path and point must be on the right link."""
        for j in joints:
            w = j.where
            if j.place.is_relative:
                for ref in (j.place.origin, j.place.toward):
                    if ref is not None and not (located.get(ref, set()) & set(j.links)):
                        self.problems.append(
                            Problem(
                                f"joint {j.name} is placed from {ref!r}, which is not a point of {' or '.join(j.links)}",
                                w,
                            )
                        )
            if j.type in (JointType.PRISMATIC, JointType.SLOT) and len(j.links) == 2:
                mover, guide = j.links
                if j.path is not None:
                    for path_ref in (j.path.through, j.path.toward):
                        if (
                            path_ref is not None
                            and path_ref.name is not None
                            and guide not in located.get(path_ref.name, set())
                        ):
                            self.problems.append(
                                Problem(
                                    f"the path of {j.name} goes through {path_ref.name!r}, which is not a point of the guide {guide}",
                                    w,
                                    "a path is fixed in the guide (the second link): name one of its joints or points, or give coordinates",
                                )
                            )
                if j.point is not None:
                    if j.point != j.name and mover not in located.get(j.point, set()):
                        self.problems.append(
                            Problem(
                                f"`point` of {j.name} is {j.point!r}, which is not a point of {mover}",
                                w,
                                f"name a joint or point of {mover}",
                            )
                        )
                elif j.type is JointType.PRISMATIC and j.path is not None:
                    # a slot's pin is the slot joint itself; a prismatic slider runs on a point of its own
                    others = [
                        o.name
                        for o in joints
                        if o is not j and mover in o.links and o.type is not JointType.PRISMATIC
                    ]
                    others += [p.name for p in points if p.link == mover]
                    if len(others) != 1:
                        self.problems.append(
                            Problem(
                                f"joint {j.name} does not say which point of {mover} runs on its path ({len(others)} candidates)",
                                w,
                                f"add `point: <name>` ({', '.join(others) or 'give the slider a joint or point'})",
                            )
                        )
            for link, prof in j.profiles:
                for ref in (getattr(prof, k, None) for k in ("centre", "through", "toward", "point")):
                    name = getattr(ref, "name", None)
                    if name is not None and link not in located.get(name, set()):
                        self.problems.append(
                            Problem(
                                f"the profile of {link} in joint {j.name} names {name!r}, which is not a point of {link}",
                                w,
                                f"a profile is fixed in its link: name a joint or point of {link}, or give coordinates",
                            )
                        )
        for p in points:
            for ref in (p.place.origin, p.place.toward):
                if ref is not None and p.link not in located.get(ref, set()):
                    self.problems.append(
                        Problem(
                            f"point {p.name} is placed from {ref!r}, which is not a point of {p.link}",
                            p.where,
                        )
                    )
        self.problems.extend(placement_cycles([*joints, *points]))

    def _lengths(self, node: yaml.Node, located: dict[str, set[str]]) -> list[Length]:
        out: list[Length] = []
        seen: dict[frozenset[str], str] = {}
        for key, (knode, vnode) in self.mapping(node, "lengths").items():
            try:
                a, b = self._length_key(knode, key, located)
                if a == b:
                    raise self.problem(knode, f"length {key} joins {a!r} to itself")
                value = self.number(vnode, f"length {key}", Dimension.LENGTH, positive=True)
                if {a, b} & self.tainted:  # its joint's error is reported; more would be echoes
                    continue
                common = located[a] & located[b]
                if not common:
                    raise self.problem(
                        knode,
                        f"{a} and {b} are not on one link ({a}: {', '.join(sorted(located[a]))}; {b}: {', '.join(sorted(located[b]))})",
                        "a length is the distance between two points of the same link",
                    )
                pair = frozenset((a, b))
                if pair in seen:
                    raise self.problem(knode, f"length {key} is given twice (also as {seen[pair]})")
                seen[pair] = key
                out.append(Length(a, b, value, self.where(knode)))
            except _Skip:
                continue
        return out

    def _length_key(self, knode: yaml.Node, key: str, located: dict[str, set[str]]) -> tuple[str, str]:
        if self.tainted:  # a joint whose own error is reported counts as known here, silently
            located = {**{n: set() for n in self.tainted}, **located}
        if "-" in key:
            parts = key.split("-")
            if len(parts) != 2 or not all(parts):
                raise self.problem(knode, f"length {key!r} must name two points as A-B")
            for part in parts:
                if part not in located:
                    raise self.problem(
                        knode,
                        f"length {key} names unknown point {part!r}",
                        _did_you_mean(part, located) or "name joints or points",
                    )
            return parts[0], parts[1]
        splits = [(key[:i], key[i:]) for i in range(1, len(key)) if key[:i] in located and key[i:] in located]
        if len(splits) == 1:
            return splits[0]
        if len(splits) > 1:
            options = " or ".join(f"{a}-{b}" for a, b in splits)
            raise self.problem(knode, f"length {key!r} is ambiguous", f"write {options}")
        raise self.problem(
            knode,
            f"length {key!r} does not name two known points",
            "write it as A-B with the names of two joints or points",
        )

    def _drives(
        self, node: yaml.Node, links: set[str], ground: str | None, joints: list[Joint]
    ) -> list[Drive]:
        items = node.value if isinstance(node, yaml.SequenceNode) else [node]
        out: list[Drive] = []
        for item in items:
            try:
                drive = self._drive(item, links, ground, joints)
            except _Skip:
                continue
            twin = next((d for d in out if (d.link, d.joint) == (drive.link, drive.joint)), None)
            if twin is not None:
                self.problem(
                    item,
                    f"{drive.link or drive.joint} is driven twice (first at line {twin.where.line if twin.where else '?'})",
                    "one drive per input link or slider; a mechanism of n degrees of freedom needs n different inputs",
                )
                continue
            out.append(drive)
        return out

    def _drive(self, node: yaml.Node, links: set[str], ground: str | None, joints: list[Joint]) -> Drive:
        keys = (
            "link",
            "joint",
            "angle",
            "rpm",
            "omega",
            "direction",
            "alpha",
            "about",
            "relative_to",
            "speed",
            "accel",
            "acceleration",
        )
        f = self.mapping(node, "the drive", allowed=keys)
        link = self.optional(f, "link", lambda n: self.name(n, "the driven link"))
        joint = self.optional(f, "joint", lambda n: self.name(n, "the driven joint"))
        if (link is None) == (joint is None):
            raise self.problem(node, "a drive names either a `link` (a crank) or a `joint` (a slider)")
        if link is not None:
            if links and link not in links:
                raise self.problem(
                    f["link"][1], f"the drive turns unknown link {link!r}", _did_you_mean(link, links)
                )
            if link == ground:
                raise self.problem(f["link"][1], "the drive cannot turn the ground link", "drive the crank")
            for key in ("speed", "accel", "acceleration"):
                if key in f:
                    self.problem(
                        f[key][0], f"`{key}` belongs to a slider drive (`joint:`); a crank takes rpm or omega"
                    )
        if joint is not None:
            known = {j.name: j for j in joints}
            if joint not in known:
                raise self.problem(
                    f["joint"][1], f"the drive moves unknown joint {joint!r}", _did_you_mean(joint, known)
                )
            if known[joint].type not in (JointType.PRISMATIC, JointType.SLOT):
                raise self.problem(
                    f["joint"][1],
                    f"a joint drive moves a slider; {joint} is {known[joint].type.value}",
                    "drive a prismatic joint, or use `link:` for a crank",
                )
            for key in ("rpm", "omega", "angle", "alpha", "direction", "about", "relative_to"):
                if key in f:
                    self.problem(
                        f[key][0], f"`{key}` belongs to a crank drive (`link:`); a slider takes speed"
                    )
        if "rpm" in f and "omega" in f:
            self.problem(f["omega"][0], "give rpm or omega, not both")
        direction = self.optional(f, "direction", lambda n: self.scalar(n, "direction"))
        if direction is not None and direction not in ("cw", "ccw"):
            self.problem(f["direction"][1], f"direction must be cw or ccw, not {direction!r}")
            direction = None
        omega = None
        for key, unit_factor_ in (("rpm", 2 * math.pi / 60), ("omega", 1.0)):
            if key in f:
                omega, sense = self._angular(f[key][1], key, unit_factor_)
                if sense and direction and sense != direction:
                    self.problem(f[key][1], f"{key} says {sense} but direction says {direction}")
                direction = direction or sense
        sign = -1.0 if direction == "cw" else 1.0
        alpha = None
        if "alpha" in f:
            alpha = self._signed(f["alpha"][1], "alpha", Dimension.ANGULAR_ACCELERATION)
        angle = self.optional(f, "angle", lambda n: self.number(n, "the drive angle", Dimension.ANGLE))
        about = self.optional(f, "about", lambda n: self.name(n, "`about`"))
        relative_to = self.optional(f, "relative_to", lambda n: self.name(n, "`relative_to`"))
        if relative_to is not None and link is not None:
            if links and relative_to not in links:
                raise self.problem(
                    f["relative_to"][1],
                    f"relative_to names unknown link {relative_to!r}",
                    _did_you_mean(relative_to, links),
                )
            if relative_to == link:
                raise self.problem(
                    f["relative_to"][1], f"{link} cannot be driven relative to itself", "name another link"
                )
            if relative_to == ground:
                relative_to = None  # relative to the ground is what a drive means anyway
        speed = self.optional(f, "speed", lambda n: self.number(n, "the slider speed", Dimension.VELOCITY))
        acc_key = "accel" if "accel" in f else "acceleration"
        accel = self.optional(
            f, acc_key, lambda n: self.number(n, "the slider acceleration", Dimension.ACCELERATION)
        )
        if angle is not None and sign < 0 and link is not None and _turns_a_programme(link, joints):
            # a cam's drive angle is its turn from the programme's start in the sense it turns
            # (DESIGN § 1.1); the model keeps every angle counter-clockwise, so a cw turn is negative
            angle = -angle
        return Drive(
            link=link,
            joint=joint,
            angle=angle,
            omega=None if omega is None else sign * omega,
            alpha=alpha,
            about=about,
            speed=speed,
            accel=accel,
            direction=direction,
            where=self.where(node),
            relative_to=relative_to,
        )

    def _angular(self, node: yaml.Node, key: str, bare_factor: float) -> tuple[float, str | None]:
        raw = self.scalar(node, key)
        try:
            q = parse_quantity(raw)
        except (KeyError, ValueError):
            raise self.problem(
                node, f'{key} must be a speed such as 600 or "62.8 rad/s", not {raw!r}'
            ) from None
        if q.dimension is None:
            value = q.value * bare_factor
        elif q.dimension is Dimension.ANGULAR_VELOCITY:
            value = q.value
        else:
            raise self.problem(
                node, f"{key} must be an angular velocity, but {q.unit!r} is a unit of {q.dimension.label}"
            )
        if value < 0:
            raise self.problem(
                node, f"{key} must not be negative", "give the sense with `direction: cw` or `ccw`"
            )
        return self.in_range(node, key, value, Dimension.ANGULAR_VELOCITY), q.sense

    def _signed(self, node: yaml.Node, key: str, dimension: Dimension) -> float:
        """A signed value, counter-clockwise positive; ``"5 rad/s^2 cw"`` is −5."""
        raw = self.scalar(node, key)
        try:
            q = parse_quantity(raw)
        except (KeyError, ValueError):
            raise self.problem(
                node, f'{key} must be a number such as 5 or "5 {dimension.value} cw", not {raw!r}'
            ) from None
        if q.dimension not in (None, dimension):
            raise self.problem(
                node, f"{key} must be {_a(dimension.label)}, but {q.unit!r} is a unit of {q.dimension.label}"
            )  # type: ignore[union-attr]
        value = self.in_range(node, key, q.value, dimension)
        if q.sense == "cw":
            return -abs(value)
        if q.sense == "ccw":
            return abs(value)
        return value

    def _answers(
        self, node: yaml.Node, links: tuple[Link, ...], joints: list[Joint], points: list[Point]
    ) -> tuple[list[Claim], Tolerance]:
        entries = self.mapping(node, "answers")
        tolerance = Tolerance(0.02)
        if "tolerance" in entries:
            with contextlib.suppress(_Skip):
                tolerance = self._tolerance(entries["tolerance"][1], None, file_level=True)
        kinds = names_by_kind(
            (link.name for link in links), (j.name for j in joints), (p.name for p in points), len(links)
        )
        claims: list[Claim] = []
        for key, (knode, vnode) in entries.items():
            if key == "tolerance":
                continue
            try:
                claims.append(self._claim(key, knode, vnode, kinds))
            except _Skip:
                continue
        return claims, tolerance

    def _answer_key(self, key: str, knode: yaml.Node, kinds: dict[str, set[str]]) -> AnswerKey:
        """A key of ``answers`` or ``asks``: a registered form whose names exist."""
        try:
            akey = parse_key(key)
        except ValueError as exc:
            raise self.problem(
                knode,
                str(exc),
                _did_you_mean(key.split(".")[0], {f.split(".")[0] for f in key_forms()})
                or "see `answers` in cli.md",
            ) from None
        for name, kind in zip(akey.names, akey.kinds, strict=False):
            if name not in kinds[kind]:
                label = KIND_LABELS.get(kind, kind)
                raise self.problem(
                    knode, f"answer {key} names unknown {label} {name!r}", _did_you_mean(name, kinds[kind])
                )
        if akey.kind.distinct and len(set(akey.names)) < len(akey.names):
            raise self.problem(
                knode,
                f"answer {key} names {akey.names[0]!r} twice",
                f"{akey.family} relates two different names",
            )
        return akey

    def _loads(
        self, node: yaml.Node, links: list[str], joints: list[Joint], points: list[Point]
    ) -> tuple[Load, ...]:
        """``loads: {P: {force: [0, -500]}, rocker: {torque: "20 N m"}}`` (DESIGN § 1.1)."""
        located = {j.name for j in joints if j.located_on} | {p.name for p in points}
        out = []
        for name, (knode, vnode) in self.mapping(node, "loads").items():
            fields = self.mapping(vnode, f"the load on {name}", allowed=("force", "torque"))
            if name in links:
                if "torque" not in fields or "force" in fields:
                    self.problem(knode, f"{name} is a link: load it with a torque", 'e.g. {torque: "20 N m"}')
                    continue
                torque = self.number(fields["torque"][1], f"the torque on {name}", Dimension.TORQUE)
                out.append(Load(name, torque=torque, where=self.where(knode)))
            elif name in located:
                if "force" not in fields or "torque" in fields:
                    self.problem(knode, f"{name} is a point: load it with a force", "e.g. {force: [0, -500]}")
                    continue
                items = self.sequence(fields["force"][1], f"the force at {name}")
                if len(items) != 2:
                    self.problem(fields["force"][1], f"the force at {name} must be a pair [Fx, Fy] (N)")
                    continue
                fx, fy = (self.number(n, f"the force at {name}", Dimension.FORCE) for n in items)
                out.append(Load(name, force=(fx, fy), where=self.where(knode)))
            else:
                self.problem(
                    knode,
                    f"loads names {name!r}, which is neither a link nor a point",
                    _did_you_mean(name, set(links) | located),
                )
        return tuple(out)

    def _asks(
        self, node: yaml.Node, links: tuple[Link, ...], joints: list[Joint], points: list[Point]
    ) -> tuple[str, ...]:
        """``asks: [omega.rocker, velocity.C]``: the questions of a problem file without values."""
        kinds = names_by_kind(
            (link.name for link in links), (j.name for j in joints), (p.name for p in points), len(links)
        )
        out: dict[str, yaml.Node] = {}
        for item in self.sequence(node, "asks (a list of answer keys)"):
            try:
                key = self.scalar(item, "an answer key")
                self._answer_key(key, item, kinds)
            except _Skip:
                continue
            if key in out:
                self.problem(item, f"asks lists {key} twice", f"first at line {out[key].start_mark.line + 1}")
                continue
            out[key] = item
        return tuple(out)

    def _claim(self, key: str, knode: yaml.Node, vnode: yaml.Node, kinds: dict[str, set[str]]) -> Claim:
        akey = self._answer_key(key, knode, kinds)
        tolerance = None
        value_node = vnode
        if isinstance(vnode, yaml.MappingNode):
            f = self.mapping(vnode, f"answer {key}", allowed=("value", "tolerance"))
            if "value" not in f:
                raise self.problem(vnode, f"answer {key} has no `value`")
            value_node = f["value"][1]
            if "tolerance" in f:
                tolerance = self._tolerance(f["tolerance"][1], akey.dimension, file_level=False)
        text = _text(value_node)
        if akey.compare is Compare.LABEL:
            return Claim(
                key, self.scalar(value_node, "the chain"), None, None, tolerance, text, self.where(knode)
            )
        if akey.compare is Compare.COUNT:
            raw = self.scalar(value_node, f"answer {key}")
            if not re.fullmatch(r"[+-]?\d+", raw.strip()):
                raise self.problem(value_node, f"answer {key} is a count: a whole number, not {raw!r}")
            return Claim(key, int(raw), Dimension.NUMBER.value, None, tolerance, text, self.where(knode))
        if akey.compare is Compare.POINT:
            if (
                akey.kind.infinity
                and isinstance(value_node, yaml.ScalarNode)
                and value_node.value.strip().lower()
                in (
                    "infinity",
                    "inf",
                    "at infinity",
                )
            ):
                return Claim(
                    key, "infinity", Dimension.LENGTH.value, None, tolerance, text, self.where(knode)
                )
            pt = self._claim_point(value_node, key)
            return Claim(key, pt, Dimension.LENGTH.value, None, tolerance, text, self.where(knode))
        dimension = akey.dimension
        assert dimension is not None
        raw = self.scalar(value_node, f"answer {key}")
        try:
            q = parse_quantity(raw)
        except KeyError as exc:
            raise self.problem(
                value_node,
                f"unknown unit {exc.args[0]!r} in answer {key}",
                f"{dimension.label} units: {', '.join(known_units(dimension))}",
            ) from None
        except ValueError:
            raise self.problem(
                value_node, f"answer {key} must be a number with an optional unit, not {raw!r}"
            ) from None
        if q.dimension is not None and q.dimension not in akey.dimensions:
            raise self.problem(
                value_node,
                f"answer {key} is {_a(dimension.label)}, but {q.unit!r} is a unit of {q.dimension.label}",
                f"{dimension.label} units: {', '.join(known_units(dimension)) or 'none (a plain number)'}",
            )
        self.in_range(value_node, f"answer {key}", q.value, dimension)
        if q.sense is not None and akey.compare not in (Compare.SENSE, Compare.SIGNED):
            raise self.problem(value_node, f"answer {key} is not an angular quantity: cw/ccw does not apply")
        return Claim(key, q.value, dimension.value, q.sense, tolerance, text, self.where(knode))

    def _claim_point(self, node: yaml.Node, key: str) -> Vec:
        shape = "a point [x, y]" + (" or infinity" if parse_key(key).kind.infinity else "")
        items = self.sequence(node, f"answer {key} ({shape})")
        if len(items) != 2:
            raise self.problem(node, f"answer {key} must be {shape}")
        out = []
        for item in items:
            raw = self.scalar(item, "a coordinate")
            try:
                q = parse_quantity(raw)
            except (KeyError, ValueError):
                raise self.problem(
                    item, f"a coordinate of answer {key} must be a length, not {raw!r}"
                ) from None
            if q.dimension not in (None, Dimension.LENGTH):
                raise self.problem(item, f"a coordinate of answer {key} must be a length")
            out.append(q.value)
        return (out[0], out[1])

    def _tolerance(self, node: yaml.Node, dimension: Dimension | None, *, file_level: bool) -> Tolerance:
        raw = self.scalar(node, "tolerance").strip()
        if raw.endswith("%"):
            try:
                value = parse_number(raw[:-1])
            except ValueError:
                raise self.problem(node, f"tolerance {raw!r} is not a percentage") from None
            if value < 0:
                raise self.problem(node, "a tolerance cannot be negative")
            return Tolerance(value / 100.0, relative=True)
        if file_level:
            raise self.problem(
                node,
                f"the file's tolerance must be a percentage such as 2%, not {raw!r}",
                "per answer, `{value: …, tolerance: 0.05 m/s}` may be absolute",
            )
        try:
            q = parse_quantity(raw)
        except (KeyError, ValueError):
            raise self.problem(
                node, f"tolerance {raw!r} must be a percentage or a value with a unit"
            ) from None
        if q.dimension is not None and dimension is not None and q.dimension is not dimension:
            raise self.problem(
                node, f"tolerance {raw!r} is {_a(q.dimension.label)}, but the answer is {_a(dimension.label)}"
            )
        if q.value < 0:
            raise self.problem(node, "a tolerance cannot be negative")
        return Tolerance(q.value, relative=False)


def _located_on(joints: list[Joint], points: list[Point]) -> dict[str, set[str]]:
    """Name → links it is a point of (see :attr:`Joint.located_on`)."""
    out: dict[str, set[str]] = {}
    for j in joints:
        if j.located_on:
            out[j.name] = set(j.located_on)
    for p in points:
        out[p.name] = {p.link}
    return out


def _turns_a_programme(link: str, joints: list[Joint]) -> bool:
    """True when ``link`` is the cam of a cam joint that gives its follower's programme."""
    return any(
        j.type is JointType.CAM and j.links[:1] == (link,) and getattr(j.spec, "program", None) is not None
        for j in joints
    )


def is_null(node: yaml.Node | None) -> bool:
    """An empty value (``key:``, ``~``, ``null``): YAML's resolver tagged it null.

    Public because :mod:`mech.batch` reads answer sheets' nodes with it too.
    """
    return isinstance(node, yaml.ScalarNode) and node.tag == "tag:yaml.org,2002:null"


def node_kind(node: yaml.Node | None) -> str:
    """What a node is, with its article, for messages: ``a list``, ``an empty value``."""
    if isinstance(node, yaml.MappingNode):
        return "a mapping"
    if isinstance(node, yaml.SequenceNode):
        return "a list"
    if isinstance(node, yaml.ScalarNode):
        if is_null(node):
            return "an empty value"
        return f"a single value ({node.value!r})" if len(node.value) < 40 else "a single value"
    return "nothing"


def _a(noun: str) -> str:
    """``an angular velocity``, ``a length``."""
    return ("an " if noun[:1] in "aeiou" else "a ") + noun


def _text(node: yaml.Node) -> str:
    if isinstance(node, yaml.ScalarNode):
        return node.value
    if isinstance(node, yaml.SequenceNode):
        return "[" + ", ".join(_text(n) for n in node.value) + "]"
    return "…"


def placement_cycles(placed: Iterable[Joint | Point]) -> list[Problem]:
    """Relative placements (``from``/``toward``) that lead back to themselves.

    A point placed from itself, or points placed from each other in a ring,
    have no position to start from: assembly would chase its own tail.  One
    problem per cycle, at its first member's line, naming the whole ring.
    """
    items = list(placed)
    refs = {
        it.name: [r for r in (it.place.origin, it.place.toward) if r is not None]
        for it in items
        if it.place.is_relative
    }
    where = {it.name: it.where for it in items}
    problems: list[Problem] = [
        Problem(
            f"{name} is placed from {r[0]} toward {r[1]}: one point gives no direction",
            where[name],
            "`toward` names a second point of the link, other than `from`",
        )
        for name, r in refs.items()
        if len(r) == 2 and r[0] == r[1] and r[0] != name
    ]
    rings: set[frozenset[str]] = set()
    state: dict[str, int] = {}  # 1: on the current path, 2: done
    for start in refs:
        if start in state:
            continue
        path: list[str] = []
        stack = [(start, iter(refs[start]))]
        state[start] = 1
        path.append(start)
        while stack:
            name, todo = stack[-1]
            nxt = next(todo, None)
            if nxt is None:
                stack.pop()
                path.pop()
                state[name] = 2
                continue
            if state.get(nxt) == 1 and frozenset(path[path.index(nxt) :]) not in rings:
                rings.add(frozenset(path[path.index(nxt) :]))
                ring = [*path[path.index(nxt) :], nxt]
                what = (
                    f"{nxt} is placed from itself"
                    if len(ring) == 2
                    else f"{nxt} is placed from {ring[1]}, which leads back to it"
                )
                problems.append(
                    Problem(
                        f"{what}: the placements form a cycle ({' → '.join(ring)})",
                        where.get(nxt),
                        "place one of them with `at`, or from/toward joints placed otherwise",
                    )
                )
            elif nxt in refs and nxt not in state:
                state[nxt] = 1
                path.append(nxt)
                stack.append((nxt, iter(refs[nxt])))
    return problems


def _did_you_mean(word: str, choices: Iterable[str]) -> str | None:
    import difflib  # only for a misspelt name: not paid at start-up

    match = difflib.get_close_matches(word, list(choices), n=1, cutoff=0.6)
    return f"did you mean {match[0]!r}?" if match else None
