"""Tables and JSON for ``mech dof`` and ``mech classify``.

No rich here: the tables are :mod:`mech.render.table`'s, printed by whichever console stands
on stdout (piped, :mod:`mech.render.plain` lays them out without rich).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from mech.render.console import table_box
from mech.render.properties import loop_dict, loop_lines
from mech.render.table import Table, Text
from mech.topology import Topology

if TYPE_CHECKING:  # pragma: no cover
    from mech.render.console import ReportConsole


def topology_dict(t: Topology) -> dict[str, Any]:
    """The JSON of one file for ``mech dof --json`` (see cli.md)."""
    c = t.count
    return {
        "file": t.path,
        "name": t.name,
        "ground": t.ground,
        "links": c.l,
        "joints": c.joints,
        "equivalent_binary_joints": c.j,
        "higher_pairs": c.h,
        "dof": c.n,
        "formula": c.formula,
        "grubler": {
            "value": c.grubler_value,
            "satisfied": c.grubler_value == 0 and c.h == 0,
            "text": c.grubler,
        },
        "kind": c.kind,
        "verdict": c.verdict,
        "chain": t.chain,
        "link_classes": {k: list(v) for k, v in t.link_classes().items()},
        "joint_classes": {k: list(v) for k, v in t.joint_classes().items()},
        "icentres": t.icentres,
        "loops": [loop_dict(loop) for loop in t.loops],
    }


def classify_dict(t: Topology) -> dict[str, Any]:
    """The JSON of ``mech classify --json``: the dof record plus every link and pair."""
    out = topology_dict(t)
    out["link_table"] = [
        {
            "link": k.name,
            "class": k.class_name,
            "joints": list(k.joints),
            "kind": k.kind,
            "ground": k.is_ground,
        }
        for k in t.links
    ]
    out["pairs"] = [
        {
            "joint": p.joint,
            "type": p.type,
            "links": list(p.links),
            "joint_class": p.joint_class,
            "equivalent_binary": p.equivalent_binary,
            "relative_motion": p.relative_motion,
            "contact": p.contact,
            "closure": p.closure,
            "counts_in": p.kutzbach,
        }
        for p in t.pairs
    ]
    return out


def _classes(classes: dict[str, tuple[str, ...]]) -> str:
    return "; ".join(f"{len(v)} {k} ({', '.join(v)})" for k, v in classes.items())


def dof_table(results: Sequence[Topology], console: ReportConsole) -> None:
    """One table for one or many files: l, j, h, n worked, Grübler, verdict."""
    box = table_box(console)

    table = Table(box=box, title="Degrees of freedom (Kutzbach)" if len(results) > 1 else None)
    if len(results) > 1:
        table.add_column("file", overflow="fold")
    table.add_column("l", justify="right")
    table.add_column("j", justify="right")
    table.add_column("h", justify="right")
    table.add_column("Kutzbach: n = 3(l − 1) − 2j − h")
    table.add_column("verdict")
    for t in results:
        c = t.count
        row = [str(c.l), str(c.j), str(c.h), c.formula, c.verdict]
        if len(results) > 1:
            row = [t.path, *row[:-1], c.kind if c.n <= 1 else f"{c.n} inputs"]
        table.add_row(*row)
    if len(results) == 1:
        t = results[0]
        c = t.count
        console.print(Text(f"{t.name}", style="bold"))
        console.print(f"  links l = {c.l}: {_classes(t.link_classes())}")
        jc = t.joint_classes()
        console.print(f"  joints: {c.joints} as written: {_classes(jc)}")
        console.print(
            f"  equivalent binary joints j = {c.j}"
            + (f", higher pairs h = {c.h} ({', '.join(c.higher_pairs)})" if c.h else ", higher pairs h = 0")
        )
        console.print(table)
        console.print(f"  Grübler: {c.grubler}")
        if t.chain:
            console.print(f"  chain: {t.chain}")
        console.print(f"  instantaneous centres: N = l(l − 1)/2 = {c.l}·{c.l - 1}/2 = {t.icentres}")
        _print_loops(t, console)
    else:
        console.print(table)


def classify_tables(t: Topology, console: ReportConsole) -> None:
    """``mech classify``: links by class, pairs three ways, then the count."""
    box = table_box(console)

    console.print(Text(t.name, style="bold"))
    links = Table(box=box, title="Links")
    for col in ("link", "class", "joints", "kind"):
        links.add_column(col)
    for k in t.links:
        links.add_row(
            k.name + (" (ground)" if k.is_ground else ""), k.class_name, ", ".join(k.joints), k.kind
        )
    console.print(links)
    pairs = Table(box=box, title="Kinematic pairs")
    for col in (
        "joint",
        "type",
        "links",
        "joint class",
        "relative motion",
        "contact",
        "closure",
        "counts in",
    ):
        pairs.add_column(col)
    for p in t.pairs:
        joint_class = p.joint_class + (f" (= {p.equivalent_binary} binary)" if p.order > 2 else "")
        pairs.add_row(
            p.joint,
            p.type,
            "–".join(p.links),
            joint_class,
            p.relative_motion,
            p.contact,
            p.closure,
            "h (higher)" if p.kutzbach == "h" else f"j (+{p.equivalent_binary})",
        )
    console.print(pairs)
    console.print(f"Kutzbach: {t.count.formula} — {t.count.verdict}")
    _print_loops(t, console, indent="")


def _print_loops(t: Topology, console: ReportConsole, indent: str = "  ") -> None:
    """Grashof's criterion for each four-bar loop, the inversion of each slider-crank loop."""
    for loop in t.loops:
        for line in loop_lines(loop, t.length_unit):
            console.print(Text(indent + line), soft_wrap=True)
