"""Reports of ``mech sweep``: a rich summary, the series as CSV, JSON, and the plot wiring.

The summary is what a student reads off a cycle: where the mechanism cannot
be assembled, its toggles, the dead centres of its output, the quick-return
time ratio and the extreme values with the crank angle where each occurs.
The CSV holds the series themselves (one row per crank angle).  All three are
made from the same :class:`~mech.kinematics.sweep.Sweep` and the same unit
conversion, so they cannot disagree.
"""

from __future__ import annotations

import csv
import io
import math
from typing import TYPE_CHECKING, Any

import numpy as np

from mech.kinematics.result import Kinematics
from mech.kinematics.sweep import Sweep, TimeRatio, default_quantities, quantity_unit
from mech.model import Mechanism
from mech.options import OutputUnits

if TYPE_CHECKING:  # pragma: no cover
    from mech.render.console import ReportConsole
from mech.units import format_unit, to_unit

__all__ = ["sweep_animation_file", "sweep_csv", "sweep_json", "sweep_plot_file", "sweep_table"]


def _out_unit(si: str, units: OutputUnits) -> str:
    return {
        "m": units.length,
        "m/s": units.velocity,
        "m/s^2": units.acceleration,
        "rad": units.angle,
        "rad/s": units.angular_velocity,
        "rad/s^2": units.angular_acceleration,
    }[si]


def _conv(value: float | None, si: str, units: OutputUnits) -> float | None:
    if value is None or not math.isfinite(value):
        return None
    return to_unit(value, _out_unit(si, units))


def _deg(a: float) -> float:
    return math.degrees(a)


def _cell(shown: float | None, value: float) -> str:
    """An extreme in the table: its number, or ∞ where a rate grows without bound toward a toggle."""
    if math.isinf(value):
        return "∞ (toggle)" if value > 0 else "−∞ (toggle)"
    return f"{shown:.6g}" if shown is not None else "–"


def _par(sw: Sweep, units: OutputUnits) -> Any:
    """The sweep's parameter in output units: a crank's angle in degrees, a slider's position in --units."""
    if sw.parameter == "angle":
        return _deg
    return lambda x: to_unit(x, units.length)


def _par_text(sw: Sweep, units: OutputUnits, x: float, digits: int) -> str:
    """A parameter value for people: ``12.345678°`` or ``0.125 m`` (a slider's position)."""
    if sw.parameter == "angle":
        return f"{_deg(x):.{digits}f}°"
    return f"{to_unit(x, units.length):.{digits}g} {format_unit(units.length)}"


def _par_unit(sw: Sweep, units: OutputUnits) -> str:
    return "deg" if sw.parameter == "angle" else units.length


def _drives_json(sw: Sweep, units: OutputUnits) -> list[dict[str, Any]]:
    """Each drive's law over the sweep (a slider drive or several drives), the lead first.

    ``per_parameter``: how far the drive moves per unit of the parameter, in its own output
    unit (deg or the length unit) per the parameter's (deg or the length unit).
    """
    par = _deg(1.0) if sw.parameter == "angle" else to_unit(1.0, units.length)
    out = []
    for law in sw.drives:
        own, speed = (
            ("deg", units.angular_velocity) if law.kind == "angle" else (units.length, units.velocity)
        )
        mine = _deg(1.0) if law.kind == "angle" else to_unit(1.0, units.length)
        out.append(
            {
                "drive": law.drive,
                "kind": law.kind,
                "rate": None if law.rate is None else to_unit(law.rate, speed),
                "rate_unit": speed,
                "per_parameter": law.per_parameter * mine / par,
                "per_parameter_unit": f"{own}/{_par_unit(sw, units)}",
                "relative_to": law.relative_to,
            }
        )
    return out


def quantities_of(sw: Sweep, asked: tuple[str, ...] = ()) -> list[str]:
    """The quantities a report shows: those asked, else the sweep's defaults."""
    if asked:
        return list(asked)
    from mech.kinematics.sweep import LEVELS

    return default_quantities(sw.points, sw.links, sw.slides, LEVELS.index(sw.level), sw.drive)


def sweep_json(
    sw: Sweep, *, units: OutputUnits, file: str | None = None, series: tuple[str, ...] = ()
) -> dict[str, Any]:
    """The sweep as a JSON-able dict (angles in degrees, values in ``units``).

    Structure::

        {"file", "mechanism", "level", "method", "drive", "steps",
         "range": [from°, to°], "omega": rad/s | null, "alpha",
         "units": {...},
         "gaps": [{"from", "to", "kind": "cannot close" | "not reached", "miss" [length], "what"}],
         "toggles": [{"angle", "what"}],
         "change_points": [{"angle", "what", "continued"}],   # only when one is passed
         "dead_centres": [{"angle", "output", "position" [length or angle]}],
         "dwells": [{"output", "from", "to", "position" [length or angle], "reverses"}],
         "time_ratio": {"output", "slow", "fast", "ratio"} | null,   # the bare one (DESIGN § 1.2)
         "time_ratios": [{"output", "slow", "fast", "ratio"}],        # every output's
         "time_ratio_refused": {output or "": why},
         "extremes": [{"quantity", "unit", "max", "max_angle", "min", "min_angle", "max_jump", "min_jump"}],
         "max_condition": float, "notes": [str],
         "series": {"angle": [...], key: [...]}   # only the keys asked with --quantity
        }
    """
    at = _par(sw, units)
    out: dict[str, Any] = {
        "file": file,
        "mechanism": sw.mechanism,
        "level": sw.level,
        "method": sw.method,
        "drive": sw.drive,
        "parameter": {"drive": sw.drive, "kind": sw.parameter, "unit": _par_unit(sw, units)},
        "drives": _drives_json(sw, units),
        "steps": int(sw.angles.size),
        "range": [at(float(sw.angles[0])), at(float(sw.angles[-1]))],
        "omega": sw.omega,
        "alpha": sw.alpha,
        "units": {
            "angle": "deg",
            "length": units.length,
            "velocity": units.velocity,
            "acceleration": units.acceleration,
            "angular_velocity": units.angular_velocity,
            "angular_acceleration": units.angular_acceleration,
        },
        "gaps": [
            {
                "from": at(g.start),
                "to": at(g.end),
                "kind": g.kind,
                "miss": _conv(g.miss, "m", units),
                "what": g.what,
            }
            for g in sw.gaps
        ],
        "toggles": [{"angle": at(t.angle), "what": t.subject} for t in sw.toggles],
        "dead_centres": [
            {
                "angle": at(e.angle),
                "output": e.subject,
                "position": _conv(e.value, "m" if e.subject in sw.slides else "rad", units),
            }
            for e in sw.dead_centres
        ],
        "dwells": _dwells_json(sw, units),
        "time_ratio": None if sw.time_ratio is None else _ratio_json(sw.time_ratio),
        "time_ratios": [_ratio_json(r) for r in sw.time_ratios],
        "time_ratio_refused": dict(sw.time_ratio_refused),
        "extremes": [
            {
                "quantity": e.quantity,
                "unit": _out_unit(e.unit, units),
                "max": _conv(e.max_value, e.unit, units),
                "max_angle": at(e.max_angle),
                "min": _conv(e.min_value, e.unit, units),
                "min_angle": at(e.min_angle),
                # reached at a jump: the values just before and after it (a law's segment end)
                "max_jump": None if e.max_jump is None else [_conv(v, e.unit, units) for v in e.max_jump],
                "min_jump": None if e.min_jump is None else [_conv(v, e.unit, units) for v in e.min_jump],
            }
            for e in sw.extremes
        ],
        "max_condition": sw.max_condition,
        "notes": list(sw.notes),
    }
    if sw.change_points:  # only when one is passed: the JSON of every other sweep is unchanged
        out["change_points"] = [
            {"angle": at(e.angle), "what": e.subject, "continued": "the branch with a continuous tangent"}
            for e in sw.change_points
        ]
    if series:
        out["series"] = {sw.parameter: [at(a) for a in sw.angles.tolist()]}
        for key in series:
            si = quantity_unit(key)
            out["series"][key] = [_conv(v, si, units) for v in sw.series(key).tolist()]
    return out


def _dwells_json(sw: Sweep, units: OutputUnits) -> list[dict[str, Any]]:
    at = _par(sw, units)
    return [
        {
            "output": d.subject,
            "from": at(d.start),
            "to": at(d.end),
            "position": _conv(d.value, "m" if d.subject in sw.slides else "rad", units),
            "reverses": d.reverses,
        }
        for d in sw.dwells
    ]


def _ratio_json(r: TimeRatio) -> dict[str, Any]:
    return {"output": r.output, "slow": _deg(r.slow), "fast": _deg(r.fast), "ratio": r.ratio}


def sweep_csv(sw: Sweep, *, units: OutputUnits, quantities: tuple[str, ...] = ()) -> str:
    """The series: ``angle`` (deg) then one column per quantity, named ``key [unit]``; empty cells where unassembled."""
    keys = quantities_of(sw, quantities)
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    first = "angle [deg]" if sw.parameter == "angle" else f"position [{units.length}]"
    at = _par(sw, units)
    w.writerow([first] + [f"{k} [{_out_unit(quantity_unit(k), units)}]" for k in keys])
    cols = []
    for k in keys:
        si = quantity_unit(k)
        factor = to_unit(1.0, _out_unit(si, units))
        cols.append(np.asarray(sw.series(k)) * factor)
    for i, a in enumerate(sw.angles.tolist()):
        w.writerow(
            [repr(round(at(a), 12))] + ["" if not np.isfinite(c[i]) else repr(float(c[i])) for c in cols]
        )
    return buf.getvalue()


def sweep_table(sw: Sweep, console: ReportConsole, *, units: OutputUnits) -> None:
    """The summary for people: gaps, toggles, dead centres, time ratio, extremes, notes."""
    from mech.render.console import table_box
    from mech.render.table import Table, Text

    console.print(Text(sw.mechanism, style="bold"))
    speed = "" if sw.omega is None else f", ω = {sw.omega:.6g} rad/s"
    if sw.parameter == "angle":
        lo, hi = _deg(float(sw.angles[0])), _deg(float(sw.angles[-1]))
        span = f"from {lo:g}° to {hi:g}°"
    else:
        lo, hi = (to_unit(float(x), units.length) for x in (sw.angles[0], sw.angles[-1]))
        span = f"along its path from {lo:g} to {hi:g} {format_unit(units.length)}"
    others = [law.drive for law in sw.drives[1:]]
    with_ = f" (with {', '.join(others)} in proportion)" if others else ""
    console.print(
        f"  sweep of {sw.drive}{with_} {span} in {sw.angles.size - 1} steps ({sw.level}{speed}); {sw.method}"
    )
    if sw.gaps:
        for g in sw.gaps:
            miss = _conv(g.miss, "m", units)
            gap = f", misses by {miss:.4g} {format_unit(units.length)}" if miss is not None else ""
            said = "cannot be assembled" if g.cannot_close else "not reached"
            console.print(
                f"  {said} from {_par_text(sw, units, g.start, 6)} to {_par_text(sw, units, g.end, 6)}: {g.what}{gap}"
            )
    else:
        console.print("  assembled at every step")
    for t in sw.toggles:
        console.print(f"  toggle at {_par_text(sw, units, t.angle, 9)}: {t.subject}")
    for c in sw.change_points:
        console.print(
            f"  change point at {_par_text(sw, units, c.angle, 6)}: {c.subject}; "
            "continued on the branch with a continuous tangent"
        )
    _output_lines(sw, console, units)
    cond = sw.max_condition
    if math.isfinite(cond) and cond > 1e3:
        console.print(
            Text(f"  largest condition number {cond:.3g}: results near it lose digits", style="yellow")
        )
    if sw.extremes:
        table = Table(box=table_box(console), show_edge=False, pad_edge=False)
        for name, justify in (
            ("quantity", "left"),
            ("max", "right"),
            ("at", "right"),
            ("min", "right"),
            ("at", "right"),
            ("unit", "left"),
        ):
            table.add_column(name, justify=justify)  # type: ignore[arg-type]
        for ex in sw.extremes:
            unit = _out_unit(ex.unit, units)
            mx, mn = _conv(ex.max_value, ex.unit, units), _conv(ex.min_value, ex.unit, units)
            table.add_row(
                ex.quantity,
                _cell(mx, ex.max_value),
                _par_text(sw, units, ex.max_angle, 4) + (" (jump)" if ex.max_jump else ""),
                _cell(mn, ex.min_value),
                _par_text(sw, units, ex.min_angle, 4) + (" (jump)" if ex.min_jump else ""),
                format_unit(unit),
            )
        console.print()
        console.print(table)
    for note in sw.notes:
        console.print(f"  note: {note}")


def _output_lines(sw: Sweep, console: ReportConsole, units: OutputUnits) -> None:
    """The outputs' dead centres, dwells (once each, DESIGN § 1.2) and time ratios."""
    for e in sw.dead_centres:
        si = "m" if e.subject in sw.slides else "rad"
        v = _conv(e.value, si, units)
        unit = format_unit(_out_unit(si, units))
        word = "at" if e.subject in sw.slides else "angle"
        at = f" ({word} {v:.6g} {unit})" if v is not None else ""
        console.print(f"  dead centre of {e.subject} at {_par_text(sw, units, e.angle, 6)}{at}")
    for d in sw.dwells:
        si = "m" if d.subject in sw.slides else "rad"
        v = _conv(d.value, si, units)
        word, unit = ("at" if d.subject in sw.slides else "angle"), format_unit(_out_unit(si, units))
        turn = ", a limit position" if d.reverses else ""
        console.print(
            f"  dwell of {d.subject} from {_par_text(sw, units, d.start, 4)} to "
            f"{_par_text(sw, units, d.end, 4)} ({word} {v:.6g} {unit}{turn})"
        )
    for tr in sw.time_ratios:
        console.print(
            f"  time ratio ({tr.output}): slow stroke {_deg(tr.slow):.4f}° / fast stroke {_deg(tr.fast):.4f}° "
            f"of crank = {tr.ratio:.6g}"
        )


def sweep_plot_file(path: str, sw: Sweep, *, units: OutputUnits, quantities: tuple[str, ...] = ()) -> None:
    """A PNG of the asked quantities (default: ω's and speeds, else angles) against crank angle."""
    from mech.draw.plot import Series, sweep_plot

    keys = list(quantities) or [
        k for k in quantities_of(sw) if k.split(".")[0] in ("omega", "velocity", "sliding")
    ]
    keys = keys or quantities_of(sw)
    series = []
    for k in keys:
        unit = _out_unit(quantity_unit(k), units)
        factor = to_unit(1.0, unit)
        ext = next((e for e in sw.extremes if e.quantity == k), None)
        refined = None
        if ext is not None:  # the refined extremes, as the report's table gives them
            par = _par(sw, units)
            refined = (
                (par(ext.max_angle), ext.max_value * factor),
                (par(ext.min_angle), ext.min_value * factor),
            )
        series.append(Series(k, format_unit(unit), (np.asarray(sw.series(k)) * factor).tolist(), refined))
    sweep_plot(
        path,
        [_par(sw, units)(a) for a in sw.angles.tolist()],
        series,
        dead_centres=[_par(sw, units)(e.angle) for e in sw.dead_centres],
        title=sw.mechanism,
    )


def sweep_animation_file(
    path: str,
    mech: Mechanism,
    kin: Kinematics,
    sw: Sweep,
    *,
    frames: int = 72,
    paths: tuple[str, ...] = (),
) -> None:
    """An animated GIF of the positions, about ``frames`` assembled steps of the sweep.

    ``kin``: the positions at the file's own instant (:func:`mech.analysis.drawn_positions`),
    which give what the frames do not move (pivots, guides).
    ``paths``: points whose whole path (from every step) is traced in each frame.
    """
    from mech.draw.plot import animate

    ok = np.flatnonzero(sw.assembled)
    pick = ok[:: max(1, ok.size // frames)] if ok.size else ok
    shots = [
        {
            name: (float(sw.positions[i, k, 0]), float(sw.positions[i, k, 1]))
            for k, name in enumerate(sw.points)
        }
        for i in pick
    ]
    curves = [
        (f"path of {p}", [(float(x), float(y)) for x, y in sw.positions[:, sw.points.index(p), :]], "path")
        for p in paths
    ]
    animate(path, mech, kin, shots, curves=curves)
