"""``mech forces``: what each pair carries, the input effort and its parts, the shaking on the frame.

:func:`forces_dict` makes the JSON record (cli.md, "mech forces") from a
:class:`~mech.forces.result.ForceAnalysis`; the table for people is printed
from the same record, so ``--json`` and the table cannot disagree.  Forces are
in newtons and torques in N·m whatever ``--units`` says; lengths (where a force
acts) and accelerations follow ``--units``.  ``--explain`` adds each link's free
body (:mod:`mech.forces.freebody`): what acts on it and Newton–Euler's
equations with the numbers.

:func:`run` is the command's body (the click command in :mod:`mech.cli` only
declares its options): load, solve, emit.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Protocol

from mech.options import OutputUnits, SolveOptions
from mech.units import format_unit, to_unit

if TYPE_CHECKING:  # pragma: no cover
    from mech.forces.freebody import FreeBody
    from mech.forces.result import ForceAnalysis, PairForce
    from mech.model import Mechanism
    from mech.render.console import ReportConsole

__all__ = ["Asking", "draw_forces", "forces_dict", "forces_json", "forces_table", "free_body_dict", "run"]

Echo = Callable[[str], None]


class Asking(Protocol):
    """What a force command was asked, as the command line folds it (a :class:`mech.commands.Request`)."""

    @property
    def file(self) -> str: ...

    @property
    def options(self) -> SolveOptions: ...

    @property
    def units(self) -> OutputUnits: ...

    @property
    def as_json(self) -> bool: ...


def run(request: Asking, *, explain: bool, echo: Echo) -> None:
    """``mech forces FILE``: the forces at the drive's instant, as tables or JSON."""
    from mech.analysis import load_mechanism
    from mech.forces import analyse
    from mech.render.emit import choose, emit

    mech = load_mechanism(request.file)
    fa = analyse(mech, request.options)
    emit(
        "forces",
        choose(request.as_json),
        (mech, fa),
        echo=echo,
        units=request.units,
        file=request.file,
        explain=explain,
    )


def draw_forces(
    request: Asking, output: str, *, free_bodies: tuple[str, ...] = (), refused: dict[str, Any] | None = None
) -> dict[str, Any]:
    """``mech draw --forces`` / ``--free-body LINK``: the forces on the configuration, and each named
    link's free-body diagram beside it; returns the summary ``--json`` prints."""
    from mech.analysis import load_mechanism
    from mech.draw import save
    from mech.draw.forces import forces_drawing
    from mech.errors import InputError
    from mech.forces import analyse
    from mech.render.draw import check_output
    from mech.shapes import Text

    for name, value in (refused or {}).items():
        if value:
            raise InputError(
                f"{name} does not apply to a drawing of forces", hint="draw it in a drawing of its own"
            )
    check_output(output)
    mech = load_mechanism(request.file)
    links = [link.name for link in mech.links]
    for link in free_bodies:
        if link not in links:
            raise InputError(f"--free-body names unknown link {link!r}", hint="one of " + ", ".join(links))
    fa = analyse(mech, request.options)
    if free_bodies and not fa.determinate:
        raise InputError(f"no free body of {mech.label}: {fa.note}")
    figure = forces_drawing(mech, fa, free_body=free_bodies)
    save(figure, output)
    return {
        "file": request.file,
        "name": mech.label,
        "output": output,
        "size_mm": [round(figure.width, 1), round(figure.height, 1)],
        "scales": [t.text for t in figure.items if isinstance(t, Text) and t.cls == "scale"],
        "free_bodies": list(free_bodies),
        "notes": [fa.note] if fa.note else [],
    }


def _vec(v: tuple[float, float] | None, unit: str) -> list[float] | None:
    return None if v is None else [to_unit(float(v[0]), unit), to_unit(float(v[1]), unit)]


def _dir(v: tuple[float, float]) -> float | None:
    return math.degrees(math.atan2(v[1], v[0])) % 360.0 if (v[0] or v[1]) else None


def forces_dict(
    mech: Mechanism, fa: ForceAnalysis, *, units: OutputUnits, explain: bool = False
) -> dict[str, Any]:
    """The JSON record of one force analysis (cli.md, "mech forces", documents every key)."""
    from mech.forces.freebody import numbers

    num = numbers(mech)
    record: dict[str, Any] = {
        "mechanism": mech.label,
        "units": {
            "length": units.length,
            "angle": "deg",
            "force": "N",
            "torque": "N m",
            "mass": "kg",
            "acceleration": units.acceleration,
            "angular_acceleration": "rad/s^2",
            "moment_of_inertia": "kg m^2",
        },
        "drive_angle": None if fa.drive_angle is None else math.degrees(fa.drive_angle),
        "static": fa.static,
        "determinate": fa.determinate,
        "note": fa.note or None,
        "notes": list(fa.notes),
        "pairs": [_pair_dict(p, num, units) for p in fa.pairs],
        "input": _effort_dict(fa),
        "inertia": [
            {
                "link": r.link,
                "mass": r.mass,
                "centre": next((m.centre for m in mech.masses if m.link == r.link), None),
                "at": _vec(r.centre, units.length),
                "acceleration": _vec(r.acceleration, units.acceleration),
                "alpha": r.alpha,
                "force": list(r.force),
                "couple": r.couple,
                "weight": list(r.weight),
            }
            for r in fa.inertia
        ],
        "shaking": {
            "force": list(fa.shaking_force),
            "magnitude": math.hypot(*fa.shaking_force),
            "direction": _dir(fa.shaking_force),
            "moment": fa.shaking_moment,
            "about": _vec(fa.about, units.length),
        },
    }
    if explain:
        record["free_bodies"] = [free_body_dict(b, units) for b in _bodies(mech, fa)]
    return record


def _bodies(mech: Mechanism, fa: ForceAnalysis) -> tuple[FreeBody, ...]:
    from mech.forces.freebody import free_bodies

    return free_bodies(mech, fa.kinematics, fa) if fa.kinematics is not None else ()


def _pair_dict(p: PairForce, num: dict[str, int], units: OutputUnits) -> dict[str, Any]:
    from mech.forces.freebody import subscript

    label = f"F{num[p.by]}{num[p.on]}" if max(num[p.by], num[p.on]) < 10 else f"F{num[p.by]},{num[p.on]}"
    return {
        "joint": p.joint,
        "label": label,
        "on": p.on,
        "by": p.by,
        "text": f"{subscript(label)}, on link {num[p.on]} ({p.on}) from link {num[p.by]} ({p.by})",
        "force": list(p.force),
        "magnitude": p.magnitude,
        "direction": _dir(p.force),
        "at": _vec(p.at, units.length),
        "normal": p.normal,
        "offset": None if p.offset is None else to_unit(p.offset, units.length),
        "couple": p.couple,
    }


def _effort_dict(fa: ForceAnalysis) -> dict[str, Any] | None:
    e = fa.effort
    if e is None:
        return None
    return {
        "kind": e.kind,
        "driver": e.driver,
        "value": e.value,
        "unit": "N m" if e.kind == "torque" else "N",
        "sense": (None if e.value == 0 else "ccw" if e.value > 0 else "cw") if e.kind == "torque" else None,
        "loads": e.loads,
        "inertia": e.inertia,
        "gravity": e.gravity,
    }


def free_body_dict(b: FreeBody, units: OutputUnits) -> dict[str, Any]:
    """One free body as JSON: its actions with their moments, the sums and the kinetic side."""
    return {
        "link": b.link,
        "number": b.number,
        "about": b.about,
        "about_at": _vec(b.about_at, units.length),
        "mass": b.mass,
        "inertia": b.inertia,
        "acceleration": _vec(b.acceleration, units.acceleration),
        "alpha": b.alpha,
        "actions": [
            {
                "label": a.label,
                "what": a.what,
                "force": None if a.force is None else list(a.force),
                "at": _vec(a.at, units.length),
                "point": a.point,
                "couple": a.couple,
                "moment": a.moment,
            }
            for a in b.actions
        ],
        "sum_force": list(b.sum_force),
        "sum_moment": b.sum_moment,
        "m_a": list(b.m_a),
        "i_alpha": b.i_alpha,
        "equations": list(b.equations()),
    }


# -- emitters (mech.render.emit) ------------------------------------------------------------
def forces_json(
    value: tuple[Mechanism, ForceAnalysis],
    *,
    echo: Echo,
    units: OutputUnits,
    file: str,
    explain: bool = False,
) -> None:
    """``mech forces --json``."""
    from mech.render.jsonout import dumps, stamp

    mech, fa = value
    record = forces_dict(mech, fa, units=units, explain=explain)
    echo(dumps(stamp(record, command="forces", file=file, name=mech.label)))


def forces_table(
    value: tuple[Mechanism, ForceAnalysis],
    *,
    echo: Echo,
    units: OutputUnits,
    file: str,
    explain: bool = False,
) -> None:
    """``mech forces``: the pairs' forces, the input effort, the inertia loads, the shaking."""
    from mech.render.console import stdout

    mech, fa = value
    console = stdout()
    data = forces_dict(mech, fa, units=units, explain=explain)
    _tables(data, console, units)
    if explain:
        from mech.forces.freebody import free_bodies

        console.print()
        if fa.kinematics is None or not fa.determinate:
            console.print("free bodies: not written, the pairs' forces being indeterminate", soft_wrap=True)
        for body in free_bodies(mech, fa.kinematics, fa) if fa.kinematics is not None else ():
            for line in body.text():
                console.print(line, soft_wrap=True)


def _g(x: float | None, digits: int = 6) -> str:
    """A number for the table (−0 printed as 0), or a dash."""
    return "–" if x is None or not math.isfinite(x) else f"{x + 0.0:.{digits}g}"


def _tables(data: dict[str, Any], console: ReportConsole, units: OutputUnits) -> None:
    """The report for people, from the JSON record: pairs, input effort, inertia, shaking."""
    from mech.render.console import table_box
    from mech.render.table import Table, Text

    box = table_box(console)
    console.print(Text(data["mechanism"], style="bold") + Text(" — forces"))
    if data["drive_angle"] is not None:
        static = "; static (no drive speed: no inertia)" if data["static"] else ""
        console.print(f"  at drive angle {data['drive_angle']:.6g}°{static}")
    for note in ([data["note"]] if data["note"] else []) + data["notes"]:
        console.print(f"  note: {note}", soft_wrap=True)
    if data["pairs"]:
        console.print(_pairs_table(Table, box, data["pairs"], format_unit(units.length)))
        for p in data["pairs"]:
            if p["offset"] is not None and abs(p["offset"]) > 1e-9 * max(1.0, *map(abs, p["at"] or [0.0])):
                console.print(
                    f"  {p['joint']}: the normal force acts {p['offset']:.6g} {format_unit(units.length)} "
                    "along the path from the slider's point",
                    soft_wrap=True,
                )
            elif p["offset"] is None and p["couple"]:
                console.print(
                    f"  {p['joint']}: no normal force; a couple of {p['couple']:.6g} N·m (ccw +) on the guide, "
                    "which holds the slider from turning",
                    soft_wrap=True,
                )
    e = data["input"]
    if e is not None:
        unit = "N·m" if e["kind"] == "torque" else "N"
        sense = f" {e['sense']}" if e["sense"] else ""
        what = "input torque on" if e["kind"] == "torque" else "input force along"
        signs = "ccw +" if e["kind"] == "torque" else "+ along the path"
        console.print(
            f"{what} {e['driver']}: {_g(abs(e['value']) if e['sense'] else e['value'])} {unit}{sense} "
            f"= loads {_g(e['loads'])} + inertia {_g(e['inertia'])} + gravity {_g(e['gravity'])} (signed, {signs})",
            soft_wrap=True,
        )
    if data["inertia"]:
        console.print(_inertia_table(Table, box, data["inertia"], format_unit(units.acceleration)))
    s = data["shaking"]
    about = f"({_g(s['about'][0])}, {_g(s['about'][1])}) {format_unit(units.length)}"
    console.print(
        f"shaking force on the frame: {_g(s['magnitude'])} N"
        + (f" at {s['direction']:.4g}°" if s["direction"] is not None else "")
        + f"; shaking moment about {about}: {_g(s['moment'])} N·m (ccw +)",
        soft_wrap=True,
    )


def _pairs_table(Table: Any, box: Any, pairs: list[dict[str, Any]], length: str) -> Any:
    t = Table(
        title="Pair forces (F₂₃: the force on link 3 from link 2; links numbered from the frame, 1)",
        box=box,
        title_justify="left",
    )
    for name in (
        "force",
        "joint",
        "on",
        "from",
        "Fx (N)",
        "Fy (N)",
        "|F| (N)",
        "dir (deg)",
        f"at ({length})",
    ):
        t.add_column(name, justify="left" if name in ("force", "joint", "on", "from") else "right")
    t.add_column("normal (N)", justify="right")
    for p in pairs:
        at = "–" if p["at"] is None else f"{_g(p['at'][0], 4)}, {_g(p['at'][1], 4)}"
        values = (p["force"][0], p["force"][1], p["magnitude"], p["direction"])
        t.add_row(
            p["text"].split(",")[0], p["joint"], p["on"], p["by"], *map(_g, values), at, _g(p["normal"])
        )
    return t


def _inertia_table(Table: Any, box: Any, records: list[dict[str, Any]], acc: str) -> Any:
    t = Table(title="Inertia (d'Alembert: −m a_G at G, −I_G α)", box=box, title_justify="left")
    for name in ("link", "m (kg)", "centre", f"a_G ({acc})", "α (rad/s²)", "−m a_G (N)", "−I_G α (N·m)"):
        t.add_column(name, justify="left" if name in ("link", "centre") else "right")
    for r in records:
        t.add_row(
            r["link"],
            _g(r["mass"]),
            r["centre"] or "",
            f"{_g(r['acceleration'][0], 5)}, {_g(r['acceleration'][1], 5)}",
            _g(r["alpha"]),
            f"{_g(r['force'][0], 5)}, {_g(r['force'][1], 5)}",
            _g(r["couple"]),
        )
    return t
