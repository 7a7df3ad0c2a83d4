"""Text from users' files shown to people: control and direction characters become escapes."""

from __future__ import annotations

import pytest

from mech._text import visible


@pytest.mark.parametrize(
    ("text", "shown"),
    [
        ("\x1b[2Jclear", "\\x1b[2Jclear"),
        ("cr\u202eank", "cr\\u202eank"),  # right-to-left override: would print "crknaa"-like
        ("a\u2066b\u2069", "a\\u2066b\\u2069"),  # isolates
        ("zero\u200bwidth", "zero\\u200bwidth"),
        ("bell\x07 del\x7f csi\x9b", "bell\\x07 del\\x7f csi\\x9b"),
    ],
)
def test_control_and_direction_characters_are_shown_as_escapes(text, shown):
    assert visible(text) == shown


@pytest.mark.parametrize("text", ["Kolbenstange ß", "θ ω α — μm", "מנגנון", "آلية", "tab\tand\nnewline"])
def test_letters_of_every_script_tabs_and_newlines_are_kept(text):
    assert visible(text) == text
