"""Text from users' files shown to people: control and direction characters become escapes."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys

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


HOSTILE_TITLE = "\u202eABCD \x1b[31m red"


def _four_bar_titled(tmp_path, title: str):
    text = (EXAMPLES / "four_bar.yaml").read_text(encoding="utf-8")
    text = re.sub(r"(?m)^name: .*$", lambda _: "name: " + json.dumps(title), text)
    m = tmp_path / "m.yaml"
    m.write_text(text, encoding="utf-8")
    return m


@pytest.mark.parametrize("command", ["dof", "classify", "icentres", "velocity", "properties"])
def test_json_carries_a_title_whole_as_json_escapes(tmp_path, command):
    """JSON is for machines: the title decodes to the very characters written, and the text of
    the JSON holds none of them raw (``\\u202e`` / ``\\u001b`` escapes), so it is safe on a terminal."""
    p = mech(command, "--json", str(_four_bar_titled(tmp_path, HOSTILE_TITLE)))
    assert p.returncode == 0, p.stderr
    assert json.loads(p.stdout)["name"] == HOSTILE_TITLE
    assert "\u202e" not in p.stdout and "\x1b" not in p.stdout
    assert "\\u202e" in p.stdout


def test_a_terminal_shows_a_title_escaped_and_keeps_its_own_colours(tmp_path):
    """On a colour terminal rich writes its own escape codes; the title's are shown as text."""
    m = _four_bar_titled(tmp_path, HOSTILE_TITLE)
    p = subprocess.run(
        [sys.executable, "-m", "mech", "dof", str(m)],
        capture_output=True,
        text=True,
        env={**os.environ, "FORCE_COLOR": "1", "TTY_COMPATIBLE": "1", "NO_COLOR": "", "COLUMNS": "120"},
        check=False,
    )
    assert p.returncode == 0, p.stderr
    assert "\u202e" not in p.stdout and "\x1b[31m" not in p.stdout
    assert "\\u202eABCD \\x1b[31m red" in p.stdout
    assert "\x1b[1m" in p.stdout  # the title's bold is rich's own code, still written
