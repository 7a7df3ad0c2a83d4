"""YAML text → located nodes: the one place mech turns text into YAML nodes.

The loader walks the node tree PyYAML composes (with libyaml's C parser when
present) instead of the Python objects it would construct, for three reasons:

* every value keeps its line and column, so each message can point at it;
* a duplicate key, which YAML silently lets overwrite, is caught;
* scalars are read from their raw text, so YAML 1.1's surprises do not leak in:
  ``1e3`` is the number 1000 (PyYAML makes it a string), and a link called
  ``no`` or ``on`` is a name, not a boolean.

Nothing is constructed from tags, so reading is as safe as ``safe_load``.
Mechanism files and answer sheets are both read here (:func:`decode`,
:func:`compose`), so both get the same encodings, limits and ``file:line:col``
messages.  The small helpers that describe nodes in messages live here too.
"""

from __future__ import annotations

import gc
import re
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from typing import Any

import yaml

from mech.errors import InputError, Where, source_lines
from mech.fields import is_null

__all__ = [
    "compose",
    "decode",
    "did_you_mean",
    "is_null",
    "no_cycle_collection",
    "node_kind",
    "text_of",
    "where_of",
]

_NULL = "tag:yaml.org,2002:null"
_NULLS = frozenset(("", "~", "null", "Null", "NULL"))  # YAML 1.1's plain nulls, as PyYAML resolves them
_DEFAULT_TAGS = {
    yaml.ScalarNode: "tag:yaml.org,2002:str",
    yaml.SequenceNode: "tag:yaml.org,2002:seq",
    yaml.MappingNode: "tag:yaml.org,2002:map",
}


class _YamlLoader(getattr(yaml, "CSafeLoader", yaml.SafeLoader)):  # type: ignore[misc]
    """PyYAML's safe loader (libyaml's C parser when present), resolving only the tag mech reads.

    Scalars are read from their text, so of a tag only "is it null" is ever
    asked (:func:`is_null`).  PyYAML's resolver tries a dozen regular
    expressions on every plain scalar (bool, int, float, timestamp …) and walks
    its path resolvers at every node: a third of composing a file, for tags
    nobody reads.  Here a plain null (empty, ``~``, ``null``, ``Null``,
    ``NULL``) is tagged null exactly as PyYAML tags it, every other scalar
    ``str``, a list ``seq``, a mapping ``map``; explicit tags are kept as written.
    """

    def resolve(self, kind: type[yaml.Node], value: str | None, implicit: tuple[bool, bool]) -> str:
        if kind is yaml.ScalarNode and implicit[0] and value in _NULLS:
            return _NULL
        return _DEFAULT_TAGS[kind]

    def descend_resolver(self, current_node: yaml.Node | None, current_index: object) -> None:
        return None  # no path resolvers

    def ascend_resolver(self) -> None:
        return None


MAX_NODES = 200_000  # an alias bomb is refused, not expanded
ANCHOR = "&"  # every alias repeats an anchor, and an anchor is written with this
MAX_DEPTH = 64  # deeper nesting is refused (before composing, where the composer could crash on it)


@contextmanager
def no_cycle_collection() -> Iterator[None]:
    """Reading a file without the cyclic garbage collector running meanwhile.

    Composing and reading a file allocate a node, two marks and a tag per value,
    then the model: objects that live until the file is read and form no cycles
    (reference counting frees them).  The collector cannot know that: it runs
    every 700 allocations, and each full collection walks every object alive,
    so on a large file (10,000 joints: 500,000 objects) it cost more than the
    reading itself (0.4 s of 0.8 s) while finding nothing to free.  It resumes
    when the file is read (and stays off if it was off).
    """
    if not gc.isenabled():
        yield
        return
    gc.disable()
    try:
        yield
    finally:
        gc.enable()


# UTF-32 before UTF-16: the UTF-32-LE mark begins with the UTF-16-LE one
_BOMS = (
    (b"\xff\xfe\x00\x00", "utf-32-le"),
    (b"\x00\x00\xfe\xff", "utf-32-be"),
    (b"\xff\xfe", "utf-16-le"),
    (b"\xfe\xff", "utf-16-be"),
)


def decode(data: bytes, path: str, *, what: str = "mechanism file") -> str:
    """The text of a file's bytes: UTF-8 (a BOM allowed), or UTF-16/32 when a byte-order mark
    says so (Windows editors save "Unicode" that way); binary or other encodings refused.

    ``what`` names what the file should have been (``"answer sheet"``).

    Raises
    ------
    InputError
        Naming the file and the first byte that cannot be read.
    """
    for bom, codec in _BOMS:
        if data.startswith(bom):
            try:
                return data[len(bom) :].decode(codec)
            except UnicodeDecodeError as exc:
                raise InputError(
                    f"this file starts with a {codec.upper()} byte-order mark but byte {exc.start + len(bom)} "
                    "cannot be read as it",
                    where=Where(path),
                    hint="save the file as UTF-8",
                ) from None
    if b"\x00" in data:
        raise InputError(
            f"this is a binary file, not a YAML {what}",
            where=Where(path),
            hint="mech reads text files in the format of cli.md (see mechanisms/ for examples)",
        )
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(
            f"this file is not UTF-8 text (byte {exc.start} cannot be read)",
            where=Where(path),
            hint="save the file as UTF-8",
        ) from None


def compose(text: str, path: str, *, what: str = "this") -> yaml.Node | None:
    """The root node of YAML ``text`` (None when it holds no document).

    ``what`` names the text in a syntax error (``"this answer sheet"`` → "this
    answer sheet is not valid YAML: …").  Absurd nesting and alias bombs are
    refused before they can crash or exhaust the interpreter.

    Raises
    ------
    InputError
        At the line and column of a syntax error, with a hint.
    """
    deep = _could_nest_deeply(text)
    try:
        if deep and not _COMPOSER_STOPS_ITSELF:
            _check_depth(text, path)
        root = yaml.compose(text, Loader=_YamlLoader)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        where = Where(path, mark.line + 1, mark.column + 1) if mark else Where(path)
        problem = exc.problem or exc.context or "malformed YAML"
        if exc.context and exc.problem and exc.context_mark is not None and mark is exc.problem_mark:
            cm = exc.context_mark
            problem += f" ({exc.context} at line {cm.line + 1}, column {cm.column + 1})"
        raise InputError(
            f"{what} is not valid YAML: {problem}",
            where=where,
            hint=_yaml_hint(text, where),
            source=text,
        ) from None
    except yaml.reader.ReaderError as exc:
        raise _unreadable_character(text, path, what, exc) from None
    except yaml.YAMLError as exc:
        raise InputError(f"{what} is not valid YAML: {exc}", where=Where(path)) from None
    if root is not None:
        if ANCHOR in text or 2 * len(text) >= MAX_NODES:
            # without an anchor nothing repeats, and a node takes at least a character of text: a
            # short file cannot hold MAX_NODES values, so only a long one or one with aliases is walked
            _check_size(root, path, what)
        if deep:
            _check_tree_depth(root, path)
    return root


# what YAML 1.1 allows in a stream (PyYAML's reader refuses anything else)
_NOT_YAML = re.compile("[^\x09\x0a\x0d\x20-\x7e\x85\xa0-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")


def _unreadable_character(text: str, path: str, what: str, exc: yaml.reader.ReaderError) -> InputError:
    """A character YAML does not allow, located at its line and column.

    PyYAML reports it by offset into the text (libyaml counts UTF-8 bytes, the pure
    Python reader characters), so the character is found again here and placed by
    YAML's own line breaks.
    """
    found = _NOT_YAML.search(text)
    if found is None:  # the reader refused something else (it never should): say what it said
        return InputError(f"{what} is not valid YAML: {exc.reason}", where=Where(path))
    before = source_lines(text[: found.start()])
    where = Where(path, len(before), len(before[-1]) + 1)
    subject = "this file" if what == "this" else what
    return InputError(
        f"{subject} holds a control character (U+{ord(found.group()):04X}) that YAML does not allow",
        where=where,
        hint="delete it (most editors do not show it: retype the line if in doubt)",
        source=text,
    )


def _yaml_hint(text: str, where: Where) -> str:
    """What to look for at a YAML syntax error; tabs get a hint of their own."""
    lines = text.splitlines()
    nearby = lines[max(where.line - 2, 0) : where.line] if where.line else lines
    if any("\t" in line for line in nearby):
        return "YAML indents with spaces, never tabs: replace the tabs with spaces"
    return "check indentation, colons and brackets near this place"


def _libyaml_stops_deep_nesting() -> bool:
    """True when composing cannot crash however deep the text nests.

    libyaml's composer recurses in C, and before 0.2.5 it crashed the
    interpreter (not raised) on tens of thousands of nested brackets; since
    0.2.5 its scanner refuses more than 1,000 levels with a located error.
    PyYAML's own (pure Python) composer would recurse past Python's limit.
    """
    if not issubclass(_YamlLoader, getattr(yaml, "CSafeLoader", ())):
        return False
    try:
        from yaml import _yaml  # type: ignore[attr-defined]

        return tuple(_yaml.get_version()) >= (0, 2, 5)  # type: ignore[no-any-return]
    except (ImportError, AttributeError):  # pragma: no cover - a libyaml binding without a version
        return False


_COMPOSER_STOPS_ITSELF = _libyaml_stops_deep_nesting()


def _could_nest_deeply(text: str) -> bool:
    """Whether the text has enough brackets or dashes to nest more than MAX_DEPTH at all."""
    return text.count("[") + text.count("{") + text.count("- ") >= 4 * MAX_DEPTH


def _nested_too_deep(path: str, mark: Any) -> InputError:
    return InputError(
        f"the file nests lists or mappings more than {MAX_DEPTH} deep",
        where=Where(path, mark.line + 1, mark.column + 1) if mark else Where(path),
        hint="a mechanism file nests three or four levels; look for runaway brackets",
    )


def _check_tree_depth(root: yaml.Node, path: str) -> None:
    """Refuse nesting deeper than MAX_DEPTH, found on the composed nodes.

    The nodes are walked in the order they are written, so the first list or
    mapping too deep is the one named; an alias is counted where its anchor is
    written (as on the event stream), not again where it is used.
    """
    scalar = yaml.ScalarNode
    seen: set[yaml.Node] = set()
    stack: list[tuple[yaml.Node, int]] = [(root, 1)]
    while stack:
        node, depth = stack.pop()
        if node in seen:
            continue
        if depth > MAX_DEPTH:
            raise _nested_too_deep(path, node.start_mark)
        seen.add(node)
        children = _children(node)
        children.reverse()
        stack.extend([(n, depth + 1) for n in children if n.__class__ is not scalar])


def _children(node: yaml.Node) -> list[yaml.Node]:
    """A collection's nodes in the order written (a mapping's keys and values alternating)."""
    if isinstance(node, yaml.MappingNode):
        return [n for kv in node.value for n in kv]
    if isinstance(node, yaml.SequenceNode):
        return list(node.value)
    return []


def _check_depth(text: str, path: str) -> None:
    """Refuse absurd nesting before composing, on the event stream, which is flat
    (so counting depth on it is safe).

    Only where composing could crash (:func:`_libyaml_stops_deep_nesting`);
    elsewhere the composed nodes are measured (:func:`_check_tree_depth`).
    """
    depth = 0
    for event in yaml.parse(text, Loader=_YamlLoader):
        if isinstance(event, (yaml.SequenceStartEvent, yaml.MappingStartEvent)):
            depth += 1
            if depth > MAX_DEPTH:
                raise _nested_too_deep(path, event.start_mark)
        elif isinstance(event, (yaml.SequenceEndEvent, yaml.MappingEndEvent)):
            depth -= 1


def _check_size(root: yaml.Node, path: str, what: str = "this") -> None:
    """Refuse a file that expands to more than MAX_NODES values (aliases counted each time used).

    The message says which it is: a file that expands through its aliases (an alias bomb), or
    one that simply holds that many values (a large answer sheet is not a bomb).
    """
    scalar = yaml.ScalarNode
    seen = 1
    stack = [root]
    collections: set[yaml.Node] = set()
    aliased = False
    while stack:
        node = stack.pop()
        if node in collections:
            aliased = True  # a collection met twice: an alias repeats it
        collections.add(node)
        children = _children(node)
        seen += len(children)
        if seen > MAX_NODES:
            subject = "the file" if what == "this" else what.replace("this ", "the ", 1)
            if aliased:
                message = f"{subject} expands to more than {MAX_NODES:,} values through its aliases (an alias bomb?)"
                hint = "write the values out, or alias fewer of them"
            else:
                message = f"{subject} holds more than {MAX_NODES:,} values: more than mech reads in one file"
                hint = (
                    "an answer sheet needs a few values per problem"
                    if "sheet" in what
                    else "a mechanism file needs a few hundred values, not millions"
                )
            raise InputError(message, where=where_of(root, path), hint=hint)
        stack.extend([n for n in children if n.__class__ is not scalar])


def where_of(node: yaml.Node | None, path: str) -> Where:
    """``path:line:col`` of a node (1-based), or the file alone when the node has no mark."""
    if node is None or node.start_mark is None:
        return Where(path)
    return Where(path, node.start_mark.line + 1, node.start_mark.column + 1)


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


def text_of(node: yaml.Node) -> str:
    """A value as written, for echoing in results (``[1, 2]`` for a list, ``…`` for a mapping)."""
    if isinstance(node, yaml.ScalarNode):
        return node.value
    if isinstance(node, yaml.SequenceNode):
        return "[" + ", ".join(text_of(n) for n in node.value) + "]"
    return "…"


def article(noun: str) -> str:
    """``an angular velocity``, ``a length``."""
    return ("an " if noun[:1] in "aeiou" else "a ") + noun


def did_you_mean(word: str, choices: Iterable[str], kind: str | None = None) -> str | None:
    """``did you mean 'crank'?`` for a near miss among ``choices``; with no near miss, the choices
    themselves when ``kind`` names them (``links: frame, crank, …``, the first 12), else None."""
    import difflib  # only for a misspelt name: not paid at start-up

    names = list(choices)
    match = difflib.get_close_matches(word, names, n=1, cutoff=0.6)
    if match:
        return f"did you mean {match[0]!r}?"
    if kind is None or not names:
        return None
    shown = sorted(names)
    return f"{kind}: {', '.join(shown[:12])}" + (f" and {len(shown) - 12:,} more" if len(shown) > 12 else "")
