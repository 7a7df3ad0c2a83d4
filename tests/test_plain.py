"""Piped output written without rich (mech.render.plain) is byte for byte what rich writes.

Every shipped example's dof, classify and position/velocity/acceleration
tables are printed twice — through PlainConsole with mech's plain Table and
Text, and through the rich console piped output used before (120 columns,
no colour) with rich's — and the two texts compared.  Cases the plain
writer hands to rich (too wide, odd characters) are compared too: they must
come out the same, whichever way they go.
"""

from __future__ import annotations

import contextlib
import io
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
from rich.console import Console

from mech.errors import MechError
from mech.kinematics import solve
from mech.loader import load
from mech.options import OutputUnits
from mech.render.kinematics import kinematics_table
from mech.render.plain import PlainConsole
from mech.render.table import SIMPLE, Table, Text
from mech.render.topology import classify_tables, dof_table
from mech.topology import classify
from mechanism_texts import expected_refusal

EXAMPLES = sorted((Path(__file__).resolve().parents[1] / "mechanisms").glob("*.yaml"))


def printed(render: Callable[[Any], None], console: Any) -> str:
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        render(console)
    return out.getvalue()


def both(render: Callable[[Any], None], width: int = 120) -> tuple[str, str]:
    rich_console = Console(highlight=False, markup=False, width=width, color_system=None, file=None)
    return printed(render, PlainConsole(width)), printed(render, rich_console)


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_counting_tables_print_as_rich_prints_them(path):
    t = classify(load(path))
    plain, rich = both(lambda c: (dof_table([t], c), classify_tables(t, c)))
    assert plain == rich


def test_several_files_table_prints_as_rich_prints_it():
    results = [classify(load(p)) for p in EXAMPLES]
    for width in (120, 60):  # at 60 columns the file names fold: rich draws it
        plain, rich = both(lambda c: dof_table(results, c), width)
        assert plain == rich


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
@pytest.mark.parametrize("level", ["position", "velocity", "acceleration"])
def test_kinematics_tables_print_as_rich_prints_them(path, level):
    refusal = expected_refusal(path.read_text(encoding="utf-8"), level)
    if refusal is not None:  # the file itself says it cannot be solved at this level
        with pytest.raises(MechError, match=refusal):
            solve(load(path), level=level)
        return
    kin = solve(load(path), level=level)
    for units in ("si", "mm"):
        plain, rich = both(lambda c, u=units: kinematics_table(kin, c, units=OutputUnits.named(u)))
        assert plain == rich


@pytest.mark.parametrize(
    "cell",
    [
        "plain",
        "θ ω α — ²",
        ":smile: emoji",
        "tab\there",
        "wide 漢字",
        "e\u0301 combining",
        "  padded ",
        "x" * 150,
    ],
    ids=["ascii", "greek", "emoji", "tab", "wide", "combining", "padded", "too-wide"],
)
@pytest.mark.parametrize("justify", ["left", "center"])
def test_odd_cells_and_titles_come_out_as_rich_prints_them(cell, justify):
    def render(console: Any) -> None:
        plain = isinstance(console, PlainConsole)
        table = (Table if plain else __import__("rich.table").table.Table)(
            title=cell, box=SIMPLE if plain else __import__("rich.box").box.SIMPLE, title_justify=justify
        )
        table.add_column("name")
        table.add_column("value", justify="right")
        table.add_row(cell, "1.5")
        table.add_row("b", cell)
        console.print(table)
        console.print(cell)
        console.print((Text if plain else __import__("rich.text").text.Text)(cell, style="bold"))
        console.print()

    plain, rich = both(render)
    assert plain == rich


RENDER = Path(__file__).resolve().parents[1] / "src" / "mech" / "render"


@pytest.mark.parametrize("path", sorted(RENDER.glob("*.py")), ids=lambda p: p.stem)
def test_every_table_is_built_once_with_mechs_table(path):
    """Renderers build mech.render.table's Table and Text, printed by whichever console stands on
    stdout; none builds rich's (which would be a second, rich-only copy of the table)."""
    import ast

    if path.stem in ("table", "richconsole"):
        return  # the one place that turns a table into rich's, and rich's console itself
    tree = ast.parse(path.read_text(encoding="utf-8"))
    imported = {
        node.module for node in ast.walk(tree) if isinstance(node, ast.ImportFrom) and node.module is not None
    }
    assert not imported & {"rich.table", "rich.text", "rich.box"}, sorted(
        imported & {"rich.table", "rich.text"}
    )


@pytest.mark.parametrize(
    "package", ["mech.render", "mech.commands"], ids=["render: console, plain", "commands"]
)
def test_no_import_circle_in_the_cli_and_report_layers(package):
    """console and plain (and cli and entry, through mech.commands) import one way (issue 20, item 5)."""
    grimp = pytest.importorskip("grimp")

    graph = grimp.build_graph("mech")
    modules = sorted(m for m in graph.modules if m.startswith(package) or m in ("mech.cli", "mech.entry"))
    for a in modules:
        for b in modules:
            if a < b and graph.chain_exists(a, b) and graph.chain_exists(b, a):
                pytest.fail(f"{a} and {b} import each other (through {graph.find_shortest_chain(b, a)})")


def test_joined_text_prints_on_a_terminal_as_riches_own_joined_text():
    """``Text(name, style="bold") + Text(" — velocities")`` is bold throughout, as rich's own is
    (the kinematics report's heading: a terminal's bytes unchanged by building it once)."""
    from rich.text import Text as RichText

    def coloured(obj: Any) -> str:
        out = io.StringIO()
        Console(file=out, force_terminal=True, color_system="truecolor", width=80).print(obj)
        return out.getvalue()

    ours = Text("Four-bar", style="bold") + Text(" — velocities") + " !"
    rich = RichText("Four-bar", style="bold") + RichText(" — velocities") + " !"
    assert coloured(ours) == coloured(rich)
