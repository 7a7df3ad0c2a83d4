"""Output formats, registered in one place: a command is parse options → analyse → emit.

Each kind of report (``kinematics``, ``icentres``, ``sweep`` …) has an emitter
per format, registered here as ``"module:function"`` so that nothing is
imported until a format is used: the JSON of ``mech dof`` never loads rich,
the table of ``mech velocity`` never loads the I-centres.  A command calls::

    emit("kinematics", choose(as_json), result, echo=click.echo, units=units)

and never branches on ``--json`` itself.  A later format (CSV of a velocity
table, Markdown …) is one function and one :func:`register` call here; the
commands need no change.

Formats
-------
``table``
    For people: rich tables on the console :func:`mech.render.console.stdout`
    gives.  That console is the one place that decides colour: piped or with
    ``NO_COLOR`` it writes plain text.
``plain``
    The same report as plain text, chosen by :func:`choose` when standard
    output is not a terminal or ``NO_COLOR`` is set; it draws through the same
    console (which is plain then), so a ``plain`` emitter defaults to the table's.
``json``
    For machines: the structures documented in cli.md, written by
    :func:`mech.render.jsonout.dumps` (NaN and infinity as null; the JSON
    contract is :mod:`mech.render.jsonout`'s).

An emitter is ``fn(value, *, echo, **context)``: ``value`` is what the
pipeline returned (a :class:`mech.analysis.Result` for the analyses), ``echo``
writes one text block to standard output (the command line passes
``click.echo``), and ``context`` is the report's own settings (units, the
file's name, ``explain`` …), by keyword.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from importlib import import_module
from typing import TYPE_CHECKING, Any

from mech.errors import MechError

if TYPE_CHECKING:  # pragma: no cover
    from mech.analysis import Result
    from mech.explain import Construction
    from mech.icentres.order import TopologyCentres
    from mech.options import OutputUnits
    from mech.render.console import ReportConsole
    from mech.topology import Topology

__all__ = ["FORMATS", "Echo", "choose", "emit", "emitter", "formats", "register"]

#: The formats every report kind can be asked for (a kind may register more).
FORMATS = ("table", "plain", "json")

Echo = Callable[[str], None]

#: kind → format → the emitter, as ``"module:function"`` (imported on first use) or the function.
_REGISTRY: dict[str, dict[str, str | Callable[..., None]]] = {}


def register(kind: str, fmt: str, target: str | Callable[..., None]) -> None:
    """Make ``target`` the emitter of ``kind`` reports in format ``fmt`` (replacing any before)."""
    _REGISTRY.setdefault(kind, {})[fmt] = target


def formats(kind: str) -> tuple[str, ...]:
    """The formats registered for ``kind``."""
    return tuple(_REGISTRY.get(kind, {}))


def choose(as_json: bool) -> str:
    """The format a command's flags ask for: ``json`` with ``--json``, else ``table`` or ``plain``.

    ``plain`` when standard output is not a terminal or ``NO_COLOR`` is set (what
    the console itself decides; the choice is only named here).
    """
    if as_json:
        return "json"
    try:
        terminal = sys.stdout.isatty()
    except (AttributeError, ValueError):
        terminal = False
    return "table" if terminal and not os.environ.get("NO_COLOR") else "plain"


def emitter(kind: str, fmt: str) -> Callable[..., None]:
    """The emitter of ``kind`` in ``fmt``; ``plain`` falls back to ``table`` (same console, plain then)."""
    table = _REGISTRY.get(kind)
    if table is None:
        raise KeyError(f"no report kind {kind!r}")
    target = table.get(fmt) or (table.get("table") if fmt == "plain" else None)
    if target is None:
        raise KeyError(f"no {fmt!r} format for {kind!r} reports (registered: {', '.join(table)})")
    if isinstance(target, str):
        module, _, name = target.partition(":")
        target = getattr(import_module(module), name)
        table[fmt] = target
    return target


def emit(kind: str, fmt: str, value: Any, *, echo: Echo | None = None, **context: Any) -> None:
    """Write ``value`` as a ``kind`` report in format ``fmt`` (see the module's docstring)."""
    emitter(kind, fmt)(value, echo=echo or _print, **context)


def _print(text: str) -> None:
    print(text)


def _console() -> ReportConsole:
    from mech.render.console import stdout

    return stdout()


def _json(echo: Echo, record: Any) -> None:
    """Write a report's JSON; its contract keys were added by :func:`mech.render.jsonout.stamp`."""
    from mech.render.jsonout import dumps

    echo(dumps(record))


COUNT_UNITS = {"length": "m"}  # the counts' reports: loop lengths in metres


def stamp(record: dict[str, Any], **contract: Any) -> dict[str, Any]:
    """The JSON contract's keys on ``record`` (:func:`mech.render.jsonout.stamp`, imported on use)."""
    from mech.render.jsonout import stamp as stamped

    return stamped(record, **contract)


# -- the emitters of mech's own reports -------------------------------------------------------
_HERE = __name__


def classify_json(topology: Topology, *, echo: Echo) -> None:
    """``mech classify --json``."""
    from mech.render.topology import classify_dict

    t = classify_dict(topology)
    _json(echo, stamp(t, command="classify", file=topology.path, name=topology.name, units=COUNT_UNITS))


def classify_table(topology: Topology, *, echo: Echo) -> None:
    """``mech classify``: links, joints and pairs."""
    from mech.render.topology import classify_tables

    classify_tables(topology, _console())


def kinematics_json(
    result: Result, *, echo: Echo, units: OutputUnits, construction: Construction | None = None
) -> None:
    """``mech position|velocity|acceleration --json`` (with ``construction`` under ``--explain``)."""
    from mech.render.kinematics import kinematics_json as record_of

    assert result.kinematics is not None
    record = record_of(result.kinematics, units=units)
    record = stamp(record, command=record["level"], file=result.file, name=record["mechanism"])
    if construction is not None:
        from mech.explain import construction_dict

        record["construction"] = construction_dict(construction)
    _json(echo, record)


def kinematics_table(
    result: Result, *, echo: Echo, units: OutputUnits, construction: Construction | None = None
) -> None:
    """``mech position|velocity|acceleration``: the tables, then the construction written out."""
    from mech.render.kinematics import kinematics_table as tables

    assert result.kinematics is not None
    console = _console()
    tables(result.kinematics, console, units=units)
    if construction is not None:
        from mech.render.table import Text

        console.print()
        console.print(Text(construction.text()), soft_wrap=True)


def icentres_json(
    result: Result, *, echo: Echo, units: OutputUnits, file: str | None = None, explain: bool = False
) -> None:
    """``mech icentres --json`` (the construction's lines under ``--explain``)."""
    from mech.render.icentres import icentres_dict

    assert result.icentres is not None
    record = stamp(
        icentres_dict(result.icentres, units=units, file=file), command="icentres", file=file, name=None
    )
    if explain:
        from mech.explain import explain_icentres

        record["construction"] = explain_icentres(result.icentres)
    _json(echo, record)


def icentres_table(
    result: Result, *, echo: Echo, units: OutputUnits, file: str | None = None, explain: bool = False
) -> None:
    """``mech icentres``: the centres, how each was found, ω by I-centres beside the solver's."""
    from mech.render.icentres import icentres_table as table

    assert result.icentres is not None
    console = _console()
    table(result.icentres, console, units=units)
    if explain:
        from mech.explain import explain_icentres
        from mech.render.table import Text

        console.print()
        for line in explain_icentres(result.icentres, unit=units.length):
            console.print(Text(line), soft_wrap=True)


def icentre_order_json(order: TopologyCentres, *, echo: Echo, file: str | None = None) -> None:
    """``mech icentres --json`` on a file that places nothing: the centres without coordinates."""
    from mech.render.icentres import order_dict

    _json(echo, stamp(order_dict(order), command="icentres", file=file, name=order.name))


def icentre_order_table(order: TopologyCentres, *, echo: Echo, file: str | None = None) -> None:
    """``mech icentres`` on a file that places nothing: primary centres, then Kennedy's order."""
    from mech.render.icentres import order_table

    order_table(order, _console())


def properties_json(result: Result, *, echo: Echo, units: OutputUnits, file: str | None = None) -> None:
    """``mech properties --json``."""
    from mech.render.properties import properties_dict

    assert result.properties is not None
    record = properties_dict(result.properties, units=units, file=file)
    _json(echo, stamp(record, command="properties", file=file, name=record["mechanism"]))


def properties_table(result: Result, *, echo: Echo, units: OutputUnits, file: str | None = None) -> None:
    """``mech properties``: Grashof, transmission angle, limits, strokes, time ratio."""
    from mech.render.properties import properties_table as table

    assert result.properties is not None
    table(result.properties, _console(), units=units)


def sweep_json(
    result: Result, *, echo: Echo, units: OutputUnits, file: str | None = None, series: tuple[str, ...] = ()
) -> None:
    """``mech sweep --json`` (the series of the quantities asked)."""
    from mech.render.sweep import sweep_json as record_of

    assert result.sweep is not None
    record = record_of(result.sweep, units=units, file=file, series=series)
    _json(echo, stamp(record, command="sweep", file=file, name=record["mechanism"]))


def sweep_table(
    result: Result, *, echo: Echo, units: OutputUnits, file: str | None = None, series: tuple[str, ...] = ()
) -> None:
    """``mech sweep``: gaps, toggles, dead centres, time ratio, extremes."""
    from mech.render.sweep import sweep_table as table

    assert result.sweep is not None
    table(result.sweep, _console(), units=units)


def dof_json(counted: list[tuple[str, Result | MechError]], *, echo: Echo, mobility: bool = False) -> None:
    """``mech dof --json``: one record per file (errors last), a lone record not in a list."""
    from mech.render.jsonout import error_record
    from mech.render.topology import topology_dict

    out = []
    errors = [(path, r) for path, r in counted if isinstance(r, MechError)]
    for _path, r in counted:
        if isinstance(r, MechError):
            continue
        assert r.topology is not None
        record = stamp(
            topology_dict(r.topology),
            command="dof",
            file=r.topology.path,
            name=r.topology.name,
            units=COUNT_UNITS,
        )
        if mobility:
            record["mobility"] = mobility_record(r)
        out.append(record)
    out += [error_record("dof", p, e) for p, e in errors]
    _json(echo, out if len(out) != 1 or errors else out[0])


def dof_table(counted: list[tuple[str, Result | MechError]], *, echo: Echo, mobility: bool = False) -> None:
    """``mech dof``: one table for every file counted (the errors were reported as they came)."""
    from mech.render.topology import dof_table as table

    results = [r for _path, r in counted if not isinstance(r, MechError)]
    if not results:
        return
    console = _console()
    table([r.topology for r in results if r.topology is not None], console)
    if mobility:
        for r in results:
            where = "" if len(results) == 1 else f"{r.mechanism.path}: "
            console.print(f"  {where}numeric mobility {mobility_record(r)['text']}", soft_wrap=True)


def mobility_record(result: Result) -> dict[str, Any]:
    """``mech dof --mobility``'s figure: value, text and condition, or why it was not computed."""
    m = result.mobility
    if m is None:
        reason = result.mobility_error.problems[0].message if result.mobility_error else "not asked"
        return {"value": None, "text": f"not computed: {reason}"}
    return {"value": m.numeric, "text": m.describe(), "condition": m.condition}


def cam_json(
    value: tuple[Any, Any], *, echo: Echo, file: str, name: str | None, label: str, step_deg: float
) -> None:
    """``mech cam --json``: the programme, the extremes, the profile's checks."""
    from mech.render.cam import cam_json as record_of

    setup, analysis = value
    _json(
        echo,
        stamp(
            record_of(setup, analysis, path=file, name=name, step_deg=step_deg),
            command="cam",
            file=file,
            name=label,
        ),
    )


def cam_table(
    value: tuple[Any, Any], *, echo: Echo, file: str, name: str | None, label: str, step_deg: float
) -> None:
    """``mech cam``: the motion table and the profile's checks."""
    from mech.render.cam import cam_table as table

    setup, analysis = value
    table(setup, analysis, _console(), name=label, step_deg=step_deg)


def summary_json(summary: dict[str, Any], *, echo: Echo, name: str | None = None) -> None:
    """A summary already made JSON-able (``mech draw --json``: what was drawn, at what scales)."""
    _json(echo, stamp(summary, command="draw", file=summary.get("file"), name=name, units={"length": "mm"}))


def nothing(value: Any, *, echo: Echo, **context: Any) -> None:
    """No report for people: the command's output is the file it wrote (``mech draw``)."""


for _kind in ("dof", "classify", "cam", "kinematics", "icentres", "properties", "sweep"):
    register(_kind, "table", f"{_HERE}:{_kind}_table")
    register(_kind, "json", f"{_HERE}:{_kind}_json")
register("icentre-order", "table", f"{_HERE}:icentre_order_table")
register("icentre-order", "json", f"{_HERE}:icentre_order_json")
register("draw", "table", nothing)
register("draw", "json", summary_json)

# `mech forces` (issue 24): its report lives with its command's body
register("forces", "table", "mech.render.forces:forces_table")
register("forces", "json", "mech.render.forces:forces_json")
register("force-sweep", "table", "mech.render.forces_sweep:cycle_table")
register("force-sweep", "json", "mech.render.forces_sweep:cycle_json")
