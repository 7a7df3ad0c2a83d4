"""Text from users' files shown to people: control and direction characters become escapes."""

from __future__ import annotations

import re

import pytest

from cli_runner import mech, no_traceback
from mech._text import visible
from mechanism_texts import EXAMPLES


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


@pytest.mark.parametrize("command", ["position", "velocity", "acceleration", "sweep", "icentres", "dof"])
def test_a_mechanism_name_with_square_brackets_is_printed_literally(tmp_path, command):
    """`name:` is free text: "x [/b] [red]y" once ended in rich's MarkupError (a traceback)."""
    text = (EXAMPLES / "four_bar.yaml").read_text(encoding="utf-8")
    text = re.sub(r"(?m)^name: .*$", 'name: "x [/b] [red]y"', text)
    m = tmp_path / "m.yaml"
    m.write_text(text, encoding="utf-8")
    p = mech(command, str(m), *(["--steps", "12"] if command == "sweep" else []))
    no_traceback(p)
    assert p.returncode == 0
    assert "x [/b] [red]y" in p.stdout
