"""Text from users' files, made safe to show: on a terminal, in XML, in SVG.

A name, a claim or a message can carry any character a YAML string can: an
escape sequence that would drive the teacher's terminal, or a control character
that XML 1.0 does not allow at all (a JUnit report a CI server cannot parse).
They are shown as visible ``\\x1b``-style escapes instead.
"""

from __future__ import annotations

from mech._text import visible, xml_safe

__all__ = ["printable", "xml_safe"]


def printable(text: str) -> str:
    """``text`` with control and direction characters shown as escapes (for terminals and tables).

    The rule is :func:`mech._text.visible`, shared with the loader and the error messages.
    """
    return visible(text)
