"""The loader: every kind of bad input gets one located message; good input reads exactly."""

from __future__ import annotations

import itertools
import math
import textwrap

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cli_runner import assert_bad_input, mech, strict_json
from mech.errors import InputError
from mech.loader import load, loads
from mech.pairs import KINDS, kind_of
from mechanism_texts import GEARS
from mechanism_texts import slider_crank as slider_crank_text

FOUR_BAR = textwrap.dedent(
    """\
    name: Four-bar chain ABCD
    units: {length: mm, angle: deg}
    ground: frame
    links: [frame, crank, coupler, rocker]
    joints:
      A: {type: revolute, links: [frame, crank], at: [0, 0]}
      B: {type: revolute, links: [crank, coupler]}
      C: {type: revolute, links: [coupler, rocker], near: [100, 80]}
      D: {type: revolute, links: [rocker, frame], at: [150, 0]}
    lengths: {AB: 40, BC: 150, CD: 80}
    drive: {link: crank, angle: 60, rpm: 120, direction: cw}
    points:
      E: {link: coupler, from: B, toward: C, distance: 50}
    answers:
      omega.rocker: 4.8 rad/s
    """
)


def problems(text: str) -> list[tuple[int, int, str]]:
    """(line, column, message) of every problem the loader reports for ``text``."""
    with pytest.raises(InputError) as info:
        loads(text, path="t.yaml")
    return [(p.where.line, p.where.column, p.message) for p in info.value.problems]


def one_problem(text: str) -> tuple[int, int, str]:
    found = problems(text)
    assert len(found) == 1, found
    return found[0]


# -- good input ----------------------------------------------------------------------------
def test_design_example_reads_in_si():
    m = loads(FOUR_BAR, path="fb.yaml")
    assert m.ground == "frame"
    assert [link.name for link in m.links] == ["frame", "crank", "coupler", "rocker"]
    assert m.joint("D").place.at == pytest.approx((0.15, 0.0))
    assert m.joint("C").place.near == pytest.approx((0.1, 0.08))
    assert {(ln.a, ln.b): ln.value for ln in m.lengths} == pytest.approx(
        {("A", "B"): 0.04, ("B", "C"): 0.15, ("C", "D"): 0.08}
    )
    (drive,) = m.drives
    assert drive.angle == pytest.approx(math.radians(60))
    assert drive.omega == pytest.approx(-120 * 2 * math.pi / 60)  # cw is negative
    assert m.point("E").place.distance == pytest.approx(0.05)
    (claim,) = m.answers
    assert (claim.key, claim.value, claim.sense) == ("omega.rocker", pytest.approx(4.8), None)


def test_strings_with_units_override_the_file_units():
    text = FOUR_BAR.replace("AB: 40", 'AB: "4 cm"').replace("angle: 60,", 'angle: "1.0471975511965976 rad",')
    m = loads(text)
    assert next(ln.value for ln in m.lengths if ln.a == "A") == pytest.approx(0.04)
    assert m.drives[0].angle == pytest.approx(math.radians(60))


def test_exponent_numbers_are_numbers_not_strings():
    # PyYAML (YAML 1.1) reads 1e3 as a string; the format means a number.
    m = loads(FOUR_BAR.replace("BC: 150", "BC: 1.5e2"))
    assert next(ln.value for ln in m.lengths if ln.a == "B") == pytest.approx(0.15)


def test_yaml11_booleans_are_names_where_names_are_expected():
    text = "links: [frame, no, on]\njoints:\n  A: {type: revolute, links: [frame, no]}\n  B: {type: revolute, links: [no, on]}\n"
    m = loads(text)
    assert [link.name for link in m.links] == ["frame", "no", "on"]


def test_links_as_mapping_with_kind():
    text = "links:\n  frame:\n  belt: {kind: flexible, description: a flat belt}\njoints:\n  A: {type: revolute, links: [frame, belt]}\n"
    m = loads(text)
    assert m.link("belt").kind == "flexible"
    assert m.link("frame").is_ground


def test_lengths_split_unambiguous_names():
    text = (
        "links: [frame, crank, rod]\njoints:\n"
        "  O2: {type: revolute, links: [frame, crank], at: [0, 0]}\n"
        "  A: {type: revolute, links: [crank, rod]}\n"
        "lengths: {O2A: 12}\n"
    )
    m = loads(text)
    assert (m.lengths[0].a, m.lengths[0].b) == ("O2", "A")


def test_counting_files_need_no_geometry():
    # a path is geometry: a file that only asks for the DOF count may leave it out
    m = loads(
        "links: [frame, slider, rod]\njoints:\n  P: {type: prismatic, links: [slider, frame]}\n  B: {type: revolute, links: [slider, rod]}\n"
    )
    assert m.joint("P").path is None


def test_slider_drive_and_drive_list():
    text = (
        "links: [frame, slider, rod, crank]\njoints:\n"
        "  P: {type: prismatic, links: [slider, frame], path: {through: [0, 0], angle: 0}}\n"
        "  B: {type: revolute, links: [slider, rod]}\n"
        "  A: {type: revolute, links: [rod, crank]}\n"
        "  O: {type: revolute, links: [crank, frame], at: [0, 0]}\n"
        "drive: [{joint: P, speed: 2 m/s}]\n"
    )
    m = loads(text)
    assert m.drives[0].joint == "P" and m.drives[0].speed == pytest.approx(2.0)


def test_answers_parse_units_senses_and_tolerances():
    text = FOUR_BAR.replace(
        "  omega.rocker: 4.8 rad/s\n",
        "  tolerance: 5%\n"
        "  omega.rocker: 10 rpm ccw\n"
        "  velocity.C: {value: 385 mm/s, tolerance: 1%}\n"
        "  acceleration.B: {value: 126 m/s², tolerance: 0.5 m/s^2}\n"
        "  icentre.crank.rocker: [0.1, 0.2]\n"
        "  icentre.frame.coupler: infinity\n"
        "  dof: 1\n"
        "  chain: four-bar\n",
    )
    m = loads(text)
    claims = {c.key: c for c in m.answers}
    assert m.tolerance.value == pytest.approx(0.05) and m.tolerance.relative
    assert claims["omega.rocker"].value == pytest.approx(10 * 2 * math.pi / 60)
    assert claims["omega.rocker"].sense == "ccw"
    assert claims["velocity.C"].value == pytest.approx(0.385)
    assert claims["velocity.C"].tolerance.value == pytest.approx(0.01)
    assert claims["acceleration.B"].tolerance.relative is False
    assert claims["icentre.crank.rocker"].value == pytest.approx((0.1, 0.2))
    assert claims["icentre.frame.coupler"].value == "infinity"
    assert claims["dof"].value == 1
    assert claims["chain"].value == "four-bar"


def test_load_reads_a_file_and_reports_missing_ones(tmp_path):
    path = tmp_path / "fb.yaml"
    path.write_text(FOUR_BAR)
    assert load(path).name == "Four-bar chain ABCD"
    with pytest.raises(InputError, match="no such file"):
        load(tmp_path / "missing.yaml")
    with pytest.raises(InputError, match="folder"):
        load(tmp_path)


# -- bad input: one message each, with line and column -------------------------------------
BASE = "links: [frame, crank, rod]\njoints:\n  A: {type: revolute, links: [frame, crank], at: [0, 0]}\n  B: {type: revolute, links: [crank, rod]}\n"


BAD_CASES = [
    ("links: [frame, crank\njoints: {}\n", 2, 7, "not valid YAML"),
    ("links: [frame, crank]\nlinks: [a]\njoints: {}\n", 2, 1, "duplicate key 'links'"),
    (BASE.replace("at: [0, 0]", "at: [0, 0], at: [1, 1]"), 3, 58, "duplicate key 'at'"),
    (BASE.replace("[frame, crank], at", "[frame, crankk], at"), 3, 38, "unknown link 'crankk'"),
    (BASE.replace("links: [crank, rod]", "links: [crank]"), 4, 30, "joins 1 link"),
    (
        BASE.replace("type: revolute, links: [crank", "type: revolte, links: [crank"),
        4,
        13,
        "unknown joint type 'revolte'",
    ),
    (BASE + "lengths: {AB: 0}\n", 5, 15, "greater than zero"),
    (BASE + "lengths: {AB: -3}\n", 5, 15, "greater than zero"),
    (BASE + "lengths: {AB: forty}\n", 5, 15, "must be a number"),
    (BASE + "lengths: {AB: .nan}\n", 5, 15, "finite"),
    (BASE + "lengths: {AB: .inf}\n", 5, 15, "finite"),
    (BASE + 'lengths: {AB: "4 furlong"}\n', 5, 15, "unknown unit 'furlong'"),
    (BASE + 'lengths: {AB: "4 rad/s"}\n', 5, 15, "must be a length"),
    (BASE + "units: {length: parsec}\n", 5, 17, "not a unit of length"),
    (BASE + "lengths: {A-X: 3}\n", 5, 11, "unknown point 'X'"),
    (BASE + "links2: []\n", 5, 1, "unknown key 'links2'"),
    (BASE + "drive: {link: crnk, rpm: 60}\n", 5, 15, "unknown link 'crnk'"),
    (BASE + "drive: {link: crank, rpm: 60, omega: 6}\n", 5, 31, "rpm or omega"),
    (BASE + "drive: {link: frame, rpm: 60}\n", 5, 15, "cannot turn the ground"),
    (BASE + "drive: [{link: crank, rpm: 60}, {link: crank, rpm: 30}]\n", 5, 33, "driven twice"),
    (BASE + "answers: {omega.crank: 5 m/s}\n", 5, 24, "angular velocity"),
    (BASE + "answers: {omegas.crank: 5}\n", 5, 11, "unknown answer key"),
    (BASE + "answers: {omega.crunk: 5}\n", 5, 11, "unknown link 'crunk'"),
    (BASE + "answers: {dof: one}\n", 5, 16, "whole number"),
    ("links: [a, b]\njoints:\n  A: {type: revolute, links: [a, b]}\n", 1, 8, "no ground link"),
    (
        "links: [frame, ground]\njoints:\n  A: {type: revolute, links: [frame, ground]}\n",
        1,
        8,
        "two links could be ground",
    ),
    (
        "ground: base\nlinks: [frame, crank]\njoints:\n  A: {type: revolute, links: [frame, crank]}\n",
        1,
        9,
        "not among the links",
    ),
    ("- a\n- b\n", 1, 1, "must be a mapping"),
    ("just a string\n", 1, 1, "must be a mapping"),
    ("links: [frame, crank]\n", 1, 1, "no `joints:`"),
    (BASE.replace("  B: {type: revolute", "  crank: {type: revolute"), 4, 3, "used twice"),
    (
        "links: [frame, crank, rod, block]\njoints:\n  A: {type: revolute, links: [frame, crank]}\n"
        "  B: {type: revolute, links: [crank, rod]}\n  C: {type: revolute, links: [rod, block]}\nlengths: {A-C: 4}\n",
        6,
        11,
        "not on one link",
    ),
    (
        BASE.replace("links: [crank, rod]}", "links: [crank, rod], path: {through: A, angle: 0}}"),
        4,
        44,
        "unknown key 'path' for a revolute",
    ),
    (
        "links: [frame, a, b, c]\njoints:\n  A: {type: cam, links: [frame, a, b]}\n",
        3,
        25,
        "exactly two links",
    ),
]


@pytest.mark.parametrize(("text", "line", "column", "fragment"), BAD_CASES)
def test_bad_input_is_located(text, line, column, fragment):
    found = problems(text)
    assert any(fragment in msg for _, _, msg in found), found
    first = next((ln, col) for ln, col, msg in found if fragment in msg)
    assert first == (line, column), found


@pytest.mark.parametrize(("text", "line", "column", "fragment"), BAD_CASES)
def test_bad_input_on_the_command_line_exits_2_with_the_place(text, line, column, fragment, run, write):
    path = write(text)
    result = run("dof", str(path))
    assert result.exit_code == 2
    assert f"{path}:{line}:{column}: error:" in result.stderr and fragment in result.stderr
    assert "Traceback" not in result.stderr


def test_every_problem_in_a_file_is_reported_at_once():
    text = (
        BASE.replace("[frame, crank], at", "[frame, crankk], at") + "lengths: {AB: -1}\ndrive: {link: rodd}\n"
    )
    found = problems(text)
    assert len(found) == 3
    assert [ln for ln, _, _ in found] == sorted(ln for ln, _, _ in found)


@pytest.mark.parametrize(
    ("data", "fragment"),
    [
        (b"", "empty"),
        (b"# only a comment\n\n", "empty"),
        (b"\x00\x01\x02binary", "binary file"),
        (b"links: [\xff\xfe]\n", "not UTF-8"),
    ],
)
def test_unreadable_files_are_refused(data, fragment):
    with pytest.raises(InputError, match=fragment):
        loads(data, path="x.yaml")


def test_alias_bomb_is_refused_not_expanded():
    bomb = "a: &a [x, x, x, x, x, x, x, x, x, x]\n"
    for i in range(1, 7):
        bomb += f"{'abcdefg'[i]}: &{'abcdefg'[i]} [" + ", ".join([f"*{'abcdefg'[i - 1]}"] * 10) + "]\n"
    with pytest.raises(InputError, match="through its aliases"):
        loads(
            "links: [frame, crank]\njoints: {}\nx:\n" + "".join("  " + ln + "\n" for ln in bomb.splitlines())
        )


_leaf = st.one_of(st.integers(-9, 9), st.sampled_from(["a", "b", "", None]))
_tree = st.recursive(
    _leaf,
    lambda kids: st.lists(kids, max_size=4) | st.dictionaries(st.sampled_from("xyz"), kids, max_size=3),
    max_leaves=30,
)


@settings(max_examples=60, deadline=None)
@given(_tree, st.booleans())
def test_text_without_anchors_holds_no_more_values_than_characters(tree, flow):
    # the premise on which the loader skips its alias-bomb walk for a short file with no `&`
    # (mech.loader.nodes.compose): written as densely as YAML allows, every node costs a character
    import yaml

    text = yaml.safe_dump(tree, default_flow_style=flow)
    nodes, stack = 0, [yaml.compose(text)]
    while stack:
        node = stack.pop()
        nodes += 1
        if isinstance(node, yaml.MappingNode):
            stack.extend(n for kv in node.value for n in kv)
        elif isinstance(node, yaml.SequenceNode):
            stack.extend(node.value)
    assert "&" not in text and nodes <= len(text)


def test_python_tags_are_never_constructed(tmp_path):
    marker = tmp_path / "pwned"
    # a tagged scalar is read as its raw text; a tagged list is just a list: nothing runs
    m = loads(BASE + f"name: !!python/name:os.system {marker}\n")
    assert m.name == f"{marker}"
    with pytest.raises(InputError, match="single value"):
        loads(BASE + f"name: !!python/object/apply:os.system ['touch {marker}']\n")
    assert not marker.exists()


def test_error_message_has_file_line_caret_and_hint():
    with pytest.raises(InputError) as info:
        loads(BASE.replace("[frame, crank], at", "[frame, crankk], at"), path="hw/p1.yaml")
    text = info.value.format()
    assert text.splitlines()[0] == "hw/p1.yaml:3:38: error: joint A names unknown link 'crankk'"
    assert text.splitlines()[2].index("^") == 4 + 37
    assert "hint: did you mean 'crank'?" in text


def test_joint_types_are_all_accepted():
    for jtype in KINDS:
        extra = ", path: {through: [0, 0], angle: 0}" if kind_of(jtype).role == "path" else ""
        text = f"links: [frame, a, b]\njoints:\n  J: {{type: {jtype}, links: [a, frame]{extra}}}\n  K: {{type: revolute, links: [a, b]}}\n  L: {{type: revolute, links: [b, frame]}}\n"
        m = loads(text)
        assert m.joint("J").type == jtype


def test_a_misspelt_link_is_one_error_not_a_cascade():
    # C's misspelt link would also make "C and D are not on one link" — noise, not news.
    text = FOUR_BAR.replace("links: [coupler, rocker]", "links: [coupler, roker]")
    found = problems(text)
    assert [msg for _, _, msg in found] == ["joint C names unknown link 'roker'"]


def test_an_unknown_joint_type_is_not_echoed_by_the_lengths_that_name_it():
    text = FOUR_BAR.replace(
        "B: {type: revolute, links: [crank, coupler]}", "B: {type: pin, links: [crank, coupler]}"
    )
    found = problems(text)
    assert [msg for _, _, msg in found] == ["unknown joint type 'pin'"]


def test_point_placed_toward_coordinates_says_what_to_write():
    text = FOUR_BAR.replace(
        "E: {link: coupler, from: B, toward: C, distance: 50}",
        "E: {link: coupler, from: B, toward: [1, 0], distance: 50}",
    )
    (line, column, message) = one_problem(text)
    assert "must name a joint or point of the same link, not coordinates" in message
    assert (line, column) == (13, 39)


@pytest.mark.parametrize(
    ("data", "fragment"),
    [(b"", "empty"), (b"\x00\x01binary", "binary file"), (b"links: [\xff]\n", "not UTF-8")],
)
def test_unreadable_files_exit_2_on_the_command_line(data, fragment, run, tmp_path):
    path = tmp_path / "bad.yaml"
    path.write_bytes(data)
    result = run("dof", str(path))
    assert result.exit_code == 2 and fragment in result.stderr and str(path) in result.stderr


PLACED_FROM_ITSELF = """
units: {length: mm, angle: deg}
links: [frame, crank, rod]
joints:
  O: {type: revolute, links: [frame, crank], at: [0, 0]}
  A: {type: revolute, links: [crank, rod], at: [10, 0]}
  B: {type: revolute, links: [rod, frame], at: [30, 0]}
lengths: {OA: 10}
points: %s
drive: {link: crank, angle: 0, rpm: 10}
"""


@pytest.mark.parametrize(
    "command", ["dof", "position", "velocity", "acceleration", "icentres", "sweep", "draw"]
)
@pytest.mark.parametrize(
    ("points", "message"),
    [
        (
            "{PS: {link: crank, from: PS, toward: PS, distance: 5}}",
            "PS is placed from itself: the placements form a cycle (PS → PS)",
        ),
        (
            "{P1: {link: crank, from: P2, toward: O, distance: 5}, P2: {link: crank, from: P1, toward: A, distance: 3}}",
            "the placements form a cycle (P1 → P2 → P1)",
        ),
    ],
    ids=["itself", "ring"],
)
def test_points_placed_in_a_cycle_are_located_errors_for_every_command(command, points, message, run, write):
    path = write(PLACED_FROM_ITSELF % points)
    extra = ["-o", str(path.with_suffix(".svg"))] if command == "draw" else []
    result = run(command, str(path), *extra)
    assert result.exit_code == 2
    assert message in result.stderr
    assert f"{path.name}:9:" in result.stderr
    assert "Traceback" not in result.stderr


def test_a_point_placed_from_and_toward_one_point_is_refused():
    with pytest.raises(InputError, match="placed from O toward O: one point gives no direction"):
        loads(PLACED_FROM_ITSELF % "{P: {link: crank, from: O, toward: O, distance: 5}}")


@pytest.mark.parametrize(
    ("text", "line", "column", "code"),
    [
        ("name: x\nlinks: [a\x01]\n", 2, 10, 0x01),
        # after two-byte characters: libyaml counts bytes, the column counts characters
        ("name: ééé\nlinks: [a\x1b]\n", 2, 10, 0x1B),
        # a form feed is a control character, not a line break, for YAML and for the count
        ("name: x\n\nlinks: [ab, c\x0c]\n", 3, 14, 0x0C),
        ("name: x\r\nlinks: [a, b\x7f]\r\n", 2, 13, 0x7F),
    ],
)
def test_a_control_character_is_located_by_line_and_column(text, line, column, code):
    ((ln, col, message),) = problems(text)
    assert (ln, col) == (line, column)
    assert f"U+{code:04X}" in message


def test_a_control_character_message_shows_it_escaped_under_a_caret(run, write):
    result = run("dof", str(write("name: x\nlinks: [ab\x1b, c]\n")))
    assert result.exit_code == 2
    assert "\x1b" not in result.stderr
    lines = result.stderr.splitlines()
    assert lines[0].endswith(
        "m.yaml:2:11: error: this file holds a control character (U+001B) that YAML does not allow"
    )
    assert lines[1] == "    links: [ab\\x1b, c]"
    assert lines[2].index("^") == 4 + len("links: [ab")


@pytest.mark.parametrize("codec", ["utf-16", "utf-16-le", "utf-16-be", "utf-32", "utf-8-sig"])
def test_a_file_with_a_byte_order_mark_reads_as_its_encoding(codec):
    bom = {"utf-16-le": "\ufeff", "utf-16-be": "\ufeff"}.get(codec, "")
    data = (bom + FOUR_BAR).encode(codec)
    assert loads(data, path="w.yaml") == loads(FOUR_BAR, path="w.yaml")


def test_utf16_without_a_byte_order_mark_is_refused_as_binary():
    with pytest.raises(InputError, match="binary file"):
        loads(FOUR_BAR.encode("utf-16-le"), path="w.yaml")


@pytest.mark.parametrize(
    ("written", "code"),
    [("\u202e", 0x202E), ("\u2066", 0x2066), ("\u200f", 0x200F), ("\\e", 0x1B), ("\\N", 0x85)],
)
def test_a_name_with_an_invisible_character_is_refused_where_it_is_written(written, code):
    """Written as a YAML escape or as the character itself, inside double quotes."""
    text = FOUR_BAR.replace("links: [frame, crank,", f'links: [frame, "cr{written}ank",', 1)
    found = problems(text)
    assert (found[0][0], found[0][1]) == (4, 16)
    assert f"U+{code:04X}" in found[0][2] and chr(code) not in found[0][2]


def test_a_title_with_control_and_direction_characters_is_shown_escaped(run, write):
    path = write(FOUR_BAR.replace("name: Four-bar chain ABCD", 'name: "\u202eABCD \\e[31m red"'))
    result = run("velocity", str(path))
    assert result.exit_code == 0
    assert "\x1b" not in result.stdout and "\u202e" not in result.stdout
    assert result.stdout.splitlines()[0].startswith("\\u202eABCD \\x1b[31m red")


def test_a_file_name_with_control_characters_is_shown_escaped_in_messages(run, tmp_path):
    path = tmp_path / "hw\x1b[2J.yaml"
    path.write_text("links: [a, b\n", encoding="utf-8")
    result = run("dof", str(path))
    assert result.exit_code == 2
    assert "\x1b" not in result.stderr and "hw\\x1b[2J.yaml" in result.stderr


# -- through the command line as a user runs it (cli_runner: crashes and tracebacks shown) --
@pytest.mark.parametrize(
    "units, length",
    [("", '"1e308 km"'), ("units: {length: km}\n", "1e306"), ("", '"1e308 ft"')],
)
def test_a_length_that_overflows_to_infinity_in_si_is_refused(write, units, length):
    """ "1e308 km" is finite as written but inf m: refused (once LinAlgError); cli.md refuses infinity."""
    text = units + slider_crank_text(0.1, 0.4, 90, 10).replace("AB: 0.4", f"AB: {length}")
    f = write(text)
    with pytest.raises(InputError):
        loads(text, path="m.yaml")
    assert_bad_input(mech("velocity", str(f)), f)


def test_an_omega_overflowing_to_infinity_is_refused(write):
    """ω "1e308 rps" = 6.3e308 rad/s = inf: once accepted with nan velocities and exit 0."""
    f = write(slider_crank_text(0.1, 0.4, 90, 10).replace("omega: 10", 'omega: "1e308 rps"'))
    assert_bad_input(mech("velocity", str(f)), f)


def test_deeply_nested_yaml_is_an_error_not_a_segfault(write):
    """50,000 nested brackets once crashed the C YAML composer (exit -11, no message at all)."""
    f = write(
        "links: [frame, crank]\njoints:\n  A: {type: revolute, links: [frame, crank]}\n"
        "description: " + "[" * 50_000 + "]" * 50_000 + "\n"
    )
    p = mech("dof", str(f), subprocess_=True)  # a crash of the interpreter shows only out of process
    assert p.returncode == 2, (p.returncode, p.stderr[-500:])
    assert "error:" in p.stderr and "Traceback" not in p.stderr


def test_a_file_with_a_bom_and_crlf_line_ends_is_read(tmp_path):
    f = tmp_path / "bom.yaml"
    f.write_bytes(
        b"\xef\xbb\xbflinks: [frame, crank]\r\njoints:\r\n  A: {type: revolute, links: [frame, crank]}\r\n"
    )
    p = mech("dof", "--json", str(f))
    assert p.returncode == 0, p.stderr
    assert strict_json(p.stdout)["dof"] == 1


def test_an_error_in_a_crlf_file_points_at_the_right_column(tmp_path):
    f = tmp_path / "crlf.yaml"
    f.write_bytes(b"links: [frame, crank]\r\njoints:\r\n  A: {type: revolute, links: [frame, crankk]}\r\n")
    p = mech("dof", str(f))
    assert_bad_input(p, f)
    assert f"{f}:3:38:" in p.stderr


def test_tab_indentation_is_located_with_a_hint(write):
    f = write("links: [frame, crank]\njoints:\n\tA: {type: revolute, links: [frame, crank]}\n")
    p = mech("dof", str(f))
    assert_bad_input(p, f)
    assert f"{f}:3:1:" in p.stderr and "hint:" in p.stderr


def test_a_second_yaml_document_is_refused_where_it_starts(write):
    f = write(
        "links: [frame, crank]\njoints:\n  A: {type: revolute, links: [frame, crank]}\n---\nlinks: [x]\n"
    )
    p = mech("dof", str(f))
    assert_bad_input(p, f)
    assert f"{f}:4:1:" in p.stderr


def test_a_merge_key_is_refused(write):
    f = write("links: [frame, crank]\njoints:\n  A: {<<: {type: revolute}, links: [frame, crank]}\n")
    p = mech("dof", str(f))
    assert_bad_input(p, f)
    assert "merge" in p.stderr


def test_an_alias_bomb_is_refused(write):
    """Nine levels of ten aliases (10^9 nodes) are refused, exit 2, not expanded."""
    text = "a: &a [x,x,x,x,x,x,x,x,x,x]\n"
    for i in range(1, 9):
        prev = chr(96 + i)
        text += f"{chr(97 + i)}: &{chr(97 + i)} [" + ",".join([f"*{prev}"] * 10) + "]\n"
    p = mech("dof", str(write(text)), timeout=30)
    assert p.returncode == 2 and "Traceback" not in p.stderr


def test_a_five_megabyte_file_is_read(write):
    f = write(
        "links: [frame, crank]\njoints:\n  A: {type: revolute, links: [frame, crank]}\n"
        "description: " + "x" * 5_000_000 + "\n"
    )
    p = mech("dof", "--json", str(f), timeout=60)
    assert p.returncode == 0 and strict_json(p.stdout)["dof"] == 1


def test_every_empty_section_is_located_on_its_own_line(write):
    """`links:` with nothing after it and the rest: one located error per line 2 to 9."""
    f = write("name:\nunits:\nground:\nlinks:\njoints:\nlengths:\ndrive:\npoints:\nanswers:\n")
    p = mech("dof", str(f))
    assert_bad_input(p, f)
    for line in range(2, 10):
        assert f"{f}:{line}:" in p.stderr


@pytest.mark.parametrize("name", ["cr.ank", '"my link"', "a-b", "2.5"])
def test_an_unusable_link_name_is_located_with_a_hint(write, name):
    f = write(f"links: [frame, {name}]\njoints:\n  A: {{type: revolute, links: [frame, {name}]}}\n")
    p = mech("dof", str(f))
    assert_bad_input(p, f)
    assert "hint:" in p.stderr


def test_unicode_names_are_read(write):
    f = write(
        "links: [frame, 曲柄, Kurbel_ä]\njoints:\n  Á: {type: revolute, links: [frame, 曲柄]}\n"
        "  B: {type: revolute, links: [曲柄, Kurbel_ä]}\n  C: {type: revolute, links: [Kurbel_ä, frame]}\n"
    )
    p = mech("dof", "--json", str(f))
    assert p.returncode == 0 and strict_json(p.stdout)["dof"] == 0


def test_a_joint_listing_a_link_twice_and_a_zero_radius_are_each_located(write):
    """Three bad joints, three located errors (lines 3, 4 and 5) in one run."""
    f = write(
        """\
links: [frame, crank]
joints:
  D: {type: revolute, links: [frame, crank, crank]}
  E: {type: revolute, links: [frame, frame]}
  F: {type: revolute, links: [frame, crank], radius: 0}
"""
    )
    p = mech("dof", str(f))
    assert_bad_input(p, f)
    assert f"{f}:3:" in p.stderr and f"{f}:4:" in p.stderr and f"{f}:5:" in p.stderr


def test_two_ground_candidates_and_no_ground_are_refused_naming_ground(write):
    p = mech(
        "dof",
        str(write("links: [frame, ground]\njoints:\n  A: {type: revolute, links: [frame, ground]}\n")),
    )
    assert p.returncode == 2 and "ground" in p.stderr
    p = mech("dof", str(write("links: [a, b]\njoints:\n  A: {type: revolute, links: [a, b]}\n", "n.yaml")))
    assert p.returncode == 2 and "ground" in p.stderr


def test_a_length_given_as_ab_and_b_a_is_located_as_given_twice(write):
    f = write(slider_crank_text().replace("AB: 0.4}", "AB: 0.4, B-A: 0.5}"))
    p = mech("velocity", str(f))
    assert_bad_input(p, f)
    assert "twice" in p.stderr


def test_a_zero_length_is_refused_where_written(write):
    f = write(slider_crank_text().replace("OA: 0.1", "OA: 0"))
    assert_bad_input(mech("velocity", str(f)), f)


def test_gear_teeth_without_a_module_are_located_naming_module(write):
    f = write(GEARS.format(x2=0.15, size="teeth: [20, 40]"))
    p = mech("dof", str(f))
    assert_bad_input(p, f)
    assert "module" in p.stderr


# -- nesting, nulls and the collector on large files ------------------------------------------
_MANY_BRACKETS = "x: [" + ", ".join(["[a]"] * 300) + "]\n"  # enough brackets that nesting is measured


@pytest.mark.parametrize("composer_stops_itself", [True, False], ids=["libyaml>=0.2.5", "older-libyaml"])
def test_nesting_past_64_is_located_at_the_first_list_too_deep(monkeypatch, composer_stops_itself):
    """Measured on the composed nodes (libyaml refuses crashing depths itself) or, where composing
    could crash, on the event stream first: the same message at the same place either way."""
    from mech.loader import nodes

    monkeypatch.setattr(nodes, "_COMPOSER_STOPS_ITSELF", composer_stops_itself)
    with pytest.raises(InputError) as info:
        nodes.compose(_MANY_BRACKETS + "d: " + "[" * 64 + "]" * 64 + "\n", "t.yaml")
    (p,) = info.value.problems
    assert (p.where.line, p.where.column) == (2, 4 + 63) and "more than 64 deep" in p.message
    nodes.compose(_MANY_BRACKETS + "d: " + "[" * 63 + "]" * 63 + "\n", "t.yaml")  # 64 levels: read


def test_an_alias_counts_for_nesting_where_its_anchor_is_written():
    from mech.loader import nodes

    anchored = "a: &a " + "[" * 40 + "]" * 40 + "\nb: " + "[" * 40 + "*a" + "]" * 40 + "\n"
    assert nodes.compose(anchored + _MANY_BRACKETS, "t.yaml") is not None  # 41 + 41 through the alias


def test_only_plain_nulls_are_read_as_empty():
    """The loader's resolver tags nulls exactly as YAML 1.1 does and nothing else."""
    from mech.loader.nodes import compose, is_null

    root = compose("a:\nb: ~\nc: null\nd: NULL\ne: ''\nf: 'null'\ng: no\nh: 0\ni: !!str\n", "t.yaml")
    assert root is not None
    assert {k.value: is_null(v) for k, v in root.value} == {
        "a": True,
        "b": True,
        "c": True,
        "d": True,
        "e": False,
        "f": False,
        "g": False,
        "h": False,
        "i": False,
    }


def test_reading_leaves_the_cyclic_collector_as_it_was():
    import gc

    loads(FOUR_BAR)
    assert gc.isenabled()
    gc.disable()
    try:
        loads(FOUR_BAR)
        assert not gc.isenabled()
    finally:
        gc.enable()


def test_a_ten_thousand_joint_chain_is_read_with_every_joint_located():
    n = 10_000
    links = ["frame"] + [f"l{i}" for i in range(1, n)]
    ring = [*links, "frame"]
    joints = "".join(
        f"  J{i}: {{type: revolute, links: [{a}, {b}]}}\n"
        for i, (a, b) in enumerate(itertools.pairwise(ring))
    )
    m = loads(f"links: [{', '.join(links)}]\njoints:\n{joints}")
    assert len(m.joints) == n and (m.joints[-1].where.line, m.joints[-1].where.column) == (n + 2, 3)
    bad = joints.replace("links: [l4999, l5000]", "links: [l4999, l5000x]")
    line, column, message = one_problem(f"links: [{', '.join(links)}]\njoints:\n{bad}")
    assert (line, column) == (4999 + 3, 42) and "l5000x" in message  # J4999, its second link


@pytest.mark.parametrize("value", ['"120 rad/s"', '"2 rev/s"', '"30 deg/s"'])
def test_rpm_in_another_unit_is_refused_not_read_silently(value):
    text = FOUR_BAR.replace(
        "drive: {link: crank, angle: 60, rpm: 120, direction: cw}", f"drive: {{link: crank, rpm: {value}}}"
    )
    with pytest.raises(InputError) as err:
        loads(text, path="d.yaml")
    text = err.value.format()
    assert "d.yaml:11:" in text and "rpm is in revolutions per minute" in text and "omega:" in text


def test_rpm_with_its_own_unit_and_omega_in_any_unit_are_read():
    base = FOUR_BAR.replace(
        "drive: {link: crank, angle: 60, rpm: 120, direction: cw}", "drive: {link: crank, KEY}"
    )
    assert loads(base.replace("KEY", 'rpm: "120 rpm"')).drives[0].omega == pytest.approx(4 * math.pi)
    assert loads(base.replace("KEY", 'omega: "120 rpm"')).drives[0].omega == pytest.approx(4 * math.pi)


def test_an_unknown_key_near_a_known_one_still_gets_a_hint():
    with pytest.raises(InputError) as info:
        loads(BASE + "answer: {dof: 1}\n")
    assert info.value.problems[0].hint == "did you mean 'answers'?"


@pytest.mark.parametrize(
    ("old", "new", "hint"),
    [
        ("rpm: 120,", 'rpm: "120 m/s",', "rev/min"),
        ("CD: 80", "CD: -80", "positive length"),
        ("{link: crank, angle: 60", "{link: wheel, angle: 60", "links: "),
        ("direction: cw", "direction: clockwise", "direction: ccw"),
        ("lengths: {AB: 40, BC: 150, CD: 80}", "lengths: [40, 150, 80]", "key: value"),
        ("from: B, toward: C", "from: B, toward: Z", "place it from a joint or point of coupler: B, C"),
        ("omega.rocker: 4.8 rad/s", "omega.rocker: {value: 4.8 rad/s, tolerance: -2%}", "give its size"),
        ("name: Four-bar chain ABCD", "name: [1, 2]", "one value"),
        ("lengths: {AB: 40,", "lengths: {AB: 40, BA: 40,", "give each distance once"),
        ("omega.rocker: 4.8 rad/s", "omega.wheel: 4.8 rad/s", "links: "),
    ],
)
def test_a_refusal_says_what_to_do(old: str, new: str, hint: str) -> None:
    # each from a new user's tries: the message located, and a hint naming the way out
    assert old in FOUR_BAR
    with pytest.raises(InputError) as caught:
        loads(FOUR_BAR.replace(old, new, 1), path="fb.yaml")
    problem = caught.value.problems[0]
    assert problem.where is not None and problem.where.line is not None
    assert problem.hint and hint in problem.hint, (problem.message, problem.hint)
