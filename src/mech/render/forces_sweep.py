"""``mech sweep --level forces``: the turning-moment diagram, the fluctuation of energy, the flywheel.

:func:`run` is the body the sweep command hands a force sweep to: it reads the
range (a crank's angles in degrees, by default one cycle of the loads; a slider
drive's positions in the file's length unit), runs
:func:`mech.forces.cycle.force_cycle` and writes what was asked: the report
(table or ``--json``), the CSV of the series (``--csv``) and the diagram
(``--plot``).  :func:`cycle_dict` is the JSON record (cli.md, "mech sweep",
"Forces over the cycle"); the table is printed from it.
"""

from __future__ import annotations

import csv
import io
import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from mech._records import dataclass
from mech.errors import InputError
from mech.options import OutputUnits
from mech.units import to_unit

if TYPE_CHECKING:  # pragma: no cover
    from mech.forces.cycle import ForceCycle, Peak
    from mech.render.console import ReportConsole
    from mech.render.forces import Asking

__all__ = ["Asked", "columns", "cycle_csv", "cycle_dict", "cycle_json", "cycle_table", "run"]

Echo = Callable[[str], None]


@dataclass(frozen=True, slots=True)
class Asked:
    """What ``mech sweep --level forces`` was asked: the range (``start``, ``stop`` as the command
    line gives them: degrees, or a slider's positions in the file's unit), the steps, the drive,
    the kinematic method, the CSV's columns and the files to write."""

    start: float | None
    stop: float | None
    steps: int
    drive: str | None
    method: str
    quantities: tuple[str, ...]
    csv_path: str | None
    plot_path: str | None


def run(
    request: Asking,
    asked: Asked,
    *,
    echo: Echo,
    write: Callable[[str, str], None],
    refused: Sequence[tuple[str, object]] = (),
) -> None:
    """The force sweep: solve, then the CSV, the plot and the report, as asked.

    ``echo`` prints a block of text, ``write`` writes a file (the command line's own, which
    writes atomically and makes a failure bad input); ``refused`` are options of the sweep
    that draw positions (``--animate``, ``--path``, ``--svg``): an error with ``--level forces``.
    """
    from mech.analysis import load_mechanism
    from mech.forces.cycle import force_cycle
    from mech.render.emit import choose, emit

    for name, value in refused:
        if value:
            raise InputError(f"{name} does not apply to --level forces", hint="sweep the kinematics for it")
    mech = load_mechanism(request.file)
    lead = mech.drives[0].link or mech.drives[0].joint if mech.drives else None
    if asked.drive is not None and asked.drive != lead:
        raise InputError(f"--level forces sweeps the first drive ({lead}), not {asked.drive!r}")
    lo, hi = _range(mech, asked.start, asked.stop)
    if asked.plot_path:
        from mech.draw.raster import use_matplotlib

        use_matplotlib()  # before solving: fail fast when the plot extra is missing
    options = request.options.with_(method=asked.method)
    try:
        cycle = force_cycle(mech, options, start=lo, stop=hi, steps=asked.steps)
    except MemoryError:
        raise InputError(
            f"out of memory sweeping the forces of {mech.label} at {asked.steps + 1:,} angles",
            hint="give fewer --steps: the integrals and peaks are refined between steps anyway",
        ) from None
    keys = columns(cycle, asked.quantities)
    if asked.csv_path == "-":
        echo(cycle_csv(cycle, keys, units=request.units).rstrip("\n"))
        return
    if asked.csv_path:
        write(asked.csv_path, cycle_csv(cycle, keys, units=request.units))
    if asked.plot_path:
        from mech.draw.forces import turning_moment_plot

        turning_moment_plot(asked.plot_path, cycle)
    context = {"units": request.units, "file": request.file, "series": asked.quantities}
    emit("force-sweep", choose(request.as_json), cycle, echo=echo, **context)


def _range(mech: Any, start: float | None, stop: float | None) -> tuple[float | None, float | None]:
    """--from/--to in SI: a crank's degrees as rad, a slider's positions (the file's unit) as m."""
    from mech.units import unit_factor

    if not mech.drives or mech.drives[0].link is not None:
        return tuple(None if x is None else math.radians(x) for x in (start, stop))  # type: ignore[return-value]
    factor = unit_factor(mech.length_unit)[1]
    return tuple(None if x is None else x * factor for x in (start, stop))  # type: ignore[return-value]


# -- the series ---------------------------------------------------------------------------------
def _effort_key(cycle: ForceCycle) -> str:
    return "input_torque" if cycle.kind == "torque" else "input_force"


def _series(cycle: ForceCycle) -> dict[str, tuple[str, np.ndarray]]:
    """Every column a force sweep can give: key → (SI unit, values at the grid)."""
    from mech.forces.cycle import pair_quantity

    s = cycle.series
    unit = "N m" if cycle.kind == "torque" else "N"
    key = _effort_key(cycle)
    out: dict[str, tuple[str, np.ndarray]] = {key: (unit, s.effort)}
    for i, part in enumerate(("loads", "inertia", "gravity")):
        out[f"{key}.{part}"] = (unit, s.parts[:, i])
    out["energy"] = ("J", cycle.energy)
    for i, pair in enumerate(s.pairs):
        name = pair_quantity(pair, s.pairs)
        out[name] = ("N", s.magnitude(i))
        out[f"{name}.x"] = ("N", s.forces[:, i, 0])
        out[f"{name}.y"] = ("N", s.forces[:, i, 1])
    out["shaking_force"] = ("N", np.hypot(s.shaking[:, 0], s.shaking[:, 1]))
    out["shaking_force.x"] = ("N", s.shaking[:, 0])
    out["shaking_force.y"] = ("N", s.shaking[:, 1])
    out["shaking_moment"] = ("N m", s.moment)
    return out


def columns(cycle: ForceCycle, asked: Sequence[str]) -> list[str]:
    """The series' keys to write: those asked (checked), else every one."""
    known = _series(cycle)
    for key in asked:
        if key not in known:
            raise InputError(
                f"no quantity {key!r} in a force sweep",
                hint="one of " + ", ".join(known),
            )
    return list(asked) or list(known)


def _parameter(cycle: ForceCycle, units: OutputUnits) -> tuple[str, Callable[[float], float]]:
    if cycle.kind == "torque":
        return "angle [deg]", math.degrees
    return f"position [{units.length}]", lambda x: to_unit(x, units.length)


def cycle_csv(cycle: ForceCycle, keys: Sequence[str], *, units: OutputUnits) -> str:
    """The series: the drive's angle (deg) then one column per key, named ``key [unit]``; empty
    cells where the mechanism could not be solved."""
    series = _series(cycle)
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    first, at = _parameter(cycle, units)
    w.writerow([first] + [f"{k} [{series[k][0]}]" for k in keys])
    cols = [series[k][1] for k in keys]
    for i, a in enumerate(cycle.series.angles.tolist()):
        w.writerow(
            [repr(round(at(a), 12))] + ["" if not np.isfinite(c[i]) else repr(float(c[i])) for c in cols]
        )
    return buf.getvalue()


# -- the report ---------------------------------------------------------------------------------
def _peak(p: Peak | None, at: Callable[[float], float]) -> dict[str, float] | None:
    return None if p is None else {"value": p.value, "angle": at(p.angle)}


def cycle_dict(cycle: ForceCycle, *, units: OutputUnits, series: Sequence[str] = ()) -> dict[str, Any]:
    """The force sweep as a JSON-able dict (cli.md, "mech sweep", "Forces over the cycle")."""
    _, at = _parameter(cycle, units)
    unit = "N m" if cycle.kind == "torque" else "N"
    power = None
    if cycle.mean is not None and cycle.omega is not None:
        power = cycle.mean * cycle.omega
    out: dict[str, Any] = {
        "mechanism": cycle.mechanism,
        "level": "forces",
        "drive": cycle.drive,
        "kind": cycle.kind,
        "units": {
            "angle": "deg",
            "length": units.length,
            "torque": "N m",
            "force": "N",
            "energy": "J",
            "power": "W",
            "moment_of_inertia": "kg m^2",
            "effort": unit,
        },
        "steps": int(cycle.series.angles.size),
        "range": [at(cycle.start), at(cycle.stop)],
        "cycle": at(cycle.period),
        "whole_cycle": cycle.whole,
        "omega": cycle.omega,
        "static": cycle.static,
        "mean": cycle.mean,
        "work": cycle.work,
        "power": power,
        "fluctuation": cycle.fluctuation,
        "energy_max": None
        if cycle.greatest is None
        else {"angle": at(cycle.greatest[0]), "value": cycle.greatest[1]},
        "energy_min": None if cycle.least is None else {"angle": at(cycle.least[0]), "value": cycle.least[1]},
        "flywheel": None
        if cycle.coefficient is None
        else {"fluctuation": cycle.coefficient, "inertia": cycle.flywheel},
        "effort": {"max": _peak(cycle.effort_max, at), "min": _peak(cycle.effort_min, at)},
        "pairs": [{"quantity": p.quantity, "max": p.value, "angle": at(p.angle)} for p in cycle.peaks],
        "shaking_force": _peak(cycle.shaking, at),
        "notes": list(cycle.notes),
    }
    if series:
        known = _series(cycle)
        name = "angle" if cycle.kind == "torque" else "position"
        out["series"] = {name: [at(a) for a in cycle.series.angles.tolist()]}
        for key in series:
            out["series"][key] = [None if not math.isfinite(v) else v for v in known[key][1].tolist()]
    return out


def cycle_json(
    cycle: ForceCycle, *, echo: Echo, units: OutputUnits, file: str, series: tuple[str, ...] = ()
) -> None:
    """``mech sweep --level forces --json``."""
    from mech.render.jsonout import dumps, stamp

    record = cycle_dict(cycle, units=units, series=series)
    echo(dumps(stamp(record, command="sweep", file=file, name=cycle.mechanism)))


def cycle_table(
    cycle: ForceCycle, *, echo: Echo, units: OutputUnits, file: str, series: tuple[str, ...] = ()
) -> None:
    """``mech sweep --level forces``: the turning moment, the energy, the flywheel, the peaks."""
    from mech.render.console import stdout

    _table(cycle_dict(cycle, units=units), stdout())


def _g(x: float | None) -> str:
    return "–" if x is None or not math.isfinite(x) else f"{x + 0.0:.6g}"


def _table(d: dict[str, Any], console: ReportConsole) -> None:
    from mech.render.console import table_box
    from mech.render.table import Table, Text

    box = table_box(console)
    deg = d["kind"] == "torque"
    unit = "N·m" if deg else "N"

    def at(x: float) -> str:
        return f"{x:.4f}°" if deg else f"{x:.6g} {d['units']['length']}"

    console.print(Text(d["mechanism"], style="bold") + Text(" — forces over the cycle"))
    speed = f", ω = {d['omega']:.6g} rad/s" if deg and d["omega"] is not None else ""
    span = f"from {at(d['range'][0])} to {at(d['range'][1])}"
    whole = f"; the loads' cycle is {at(d['cycle'])}" if deg else ""
    console.print(
        f"  sweep of {d['drive']} {span} in {d['steps'] - 1} steps (forces{speed}){whole}", soft_wrap=True
    )
    effort = "input torque" if deg else "input force"
    if d["mean"] is not None:
        power = f"; power {_g(d['power'])} W" if d["power"] is not None else ""
        console.print(
            f"  mean {effort}: {_g(d['mean'])} {unit} (work {_g(d['work'])} J over the range{power})",
            soft_wrap=True,
        )
        console.print(
            f"  fluctuation of energy ΔE = {_g(d['fluctuation'])} J: the energy (and the speed) is greatest at "
            f"{at(d['energy_max']['angle'])} and least at {at(d['energy_min']['angle'])}"
            if d["energy_max"] is not None and d["energy_min"] is not None
            else "  fluctuation of energy ΔE = 0 J: the effort is steady, the speed does not vary",
            soft_wrap=True,
        )
    fw = d["flywheel"]
    if fw is not None and fw["inertia"] is not None:
        console.print(
            f"  flywheel: I = ΔE / (ω² C_s) = {_g(fw['inertia'])} kg·m² (C_s = {fw['fluctuation']:.4g}, "
            f"(ω_max − ω_min)/ω_mean)",
            soft_wrap=True,
        )
    t = Table(box=box)
    for name, justify in (
        ("quantity", "left"),
        ("greatest", "right"),
        ("at", "right"),
        ("least", "right"),
        ("at", "right"),
        ("unit", "left"),
    ):
        t.add_column(name, justify=justify)
    e = d["effort"]
    if e["max"] is not None:
        low = e["min"]
        t.add_row(
            effort,
            _g(e["max"]["value"]),
            at(e["max"]["angle"]),
            _g(low["value"]) if low else "–",
            at(low["angle"]) if low else "–",
            unit,
        )
    for p in d["pairs"]:
        t.add_row(p["quantity"], _g(p["max"]), at(p["angle"]), "", "", "N")
    if d["shaking_force"] is not None:
        t.add_row(
            "shaking force", _g(d["shaking_force"]["value"]), at(d["shaking_force"]["angle"]), "", "", "N"
        )
    console.print()
    console.print(t)
    for note in d["notes"]:
        console.print(f"  note: {note}", soft_wrap=True)
