"""Text from users' files, made safe to show: on a terminal, in XML, in SVG.

A name, a claim or a message can carry any character a YAML string can: an
escape sequence that would drive the teacher's terminal, or a control character
that XML 1.0 does not allow at all (a JUnit report a CI server cannot parse).
They are shown as visible ``\\x1b``-style escapes instead.
"""

from __future__ import annotations

import re

from mech._text import visible

__all__ = ["printable", "xml_safe"]

# what XML 1.0 forbids anywhere in a document (tab, newline and carriage return are allowed)
_NOT_XML = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\ufffe\uffff]")


def _escape(match: re.Match[str]) -> str:
    code = ord(match.group())
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def printable(text: str) -> str:
    """``text`` with control and direction characters shown as escapes (for terminals and tables).

    The rule is :func:`mech._text.visible`, shared with the loader and the error messages.
    """
    return visible(text)


def xml_safe(document: str) -> str:
    """A serialised XML or SVG document with the characters XML 1.0 forbids shown as ``\\xNN``.

    Safe on a whole document: those characters never occur in markup itself.
    """
    return _NOT_XML.sub(_escape, document)
