"""Table and JSON for ``mech icentres``, made from one :class:`~mech.icentres.ICentres`."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from mech.units import format_unit, to_unit

if TYPE_CHECKING:  # pragma: no cover
    from mech.icentres import ICentre, ICentres
    from mech.icentres.order import TopologyCentres
    from mech.options import OutputUnits
    from mech.render.console import ReportConsole

__all__ = ["icentres_dict", "icentres_table", "order_dict", "order_table"]


def _angle(direction: tuple[float, float]) -> float:
    """Direction of a centre at infinity in degrees, in [0, 180).

    To 1e-9°: a direction along x found from rounded velocities is 1e-14° off it, which is
    rounding, not a direction (it printed as ``∞ at 9.925e-15°``).
    """
    a = round(math.degrees(math.atan2(direction[1], direction[0])), 9) % 180.0
    return 0.0 if a >= 180.0 - 1e-9 else a + 0.0


def _length_unit(units: OutputUnits | None) -> str:
    return units.length if units is not None else "m"


def _centre_dict(c: ICentre, unit: str) -> dict[str, Any]:
    return {
        "name": c.name,
        "links": list(c.links),
        "numbers": list(c.numbers),
        "point": None if c.point is None else [to_unit(c.point[0], unit), to_unit(c.point[1], unit)],
        "at_infinity": c.at_infinity,
        "direction": None if c.direction is None else list(c.direction),
        "angle": None if c.direction is None else _angle(c.direction),
        "method": c.method,
        "primary": c.primary,
        "step": c.step,
        "check": c.check,
    }


def icentres_dict(
    ic: ICentres, *, units: OutputUnits | None = None, file: str | None = None
) -> dict[str, Any]:
    """The JSON of ``mech icentres --json`` (structure in cli.md)."""
    unit = _length_unit(units)
    checks = [c.check for c in ic.centres if c.check is not None]
    return {
        "file": file,
        "name": ic.mechanism,
        "units": {"length": unit, "angle": "deg", "angular_velocity": "rad/s"},
        "links": [{"number": k + 1, "name": lk} for k, lk in enumerate(ic.links)],
        "count": ic.count,
        "formula": ic.formula,
        "kennedy_rounds": ic.rounds,
        "icentres": [_centre_dict(c, unit) for c in ic.centres],
        "max_check": max(checks) if checks else None,
        "omega": [
            {"link": o.link, "by_icentres": o.omega, "via": o.via, "solver": o.solver} for o in ic.omegas
        ],
        "notes": list(ic.notes),
    }


def _num(v: float, tiny: float) -> str:
    """A coordinate for people: rounding noise (below 1e-9 of the size) shows as 0."""
    return f"{v:.6g}" if abs(v) > tiny else "0"


def _ordinal(k: int) -> str:
    return f"{k}{'st' if k == 1 else 'nd' if k == 2 else 'rd' if k == 3 else 'th'}"


def _omega(w: float | None) -> str:
    if w is None:
        return "—"
    if abs(w) < 1e-12:
        return "0"
    return f"{abs(w):.6g} {'ccw' if w > 0 else 'cw'}"


def icentres_table(ic: ICentres, console: ReportConsole, *, units: OutputUnits | None = None) -> None:
    """``mech icentres``: the count worked, every centre with how it was found, ω by I-centres."""
    from mech.render.console import table_box
    from mech.render.table import Table, Text

    unit = _length_unit(units)
    shown = format_unit(unit)
    console.print(Text(ic.mechanism, style="bold"))
    numbering = ", ".join(f"{k + 1} {lk}" for k, lk in enumerate(ic.links))
    console.print(f"  links, numbered (ground = 1): {numbering}")
    console.print(f"  instantaneous centres: {ic.formula}")
    table = Table(box=table_box(console))
    table.add_column("I-centre")
    table.add_column("links")
    table.add_column(f"x ({shown})", justify="right")
    table.add_column(f"y ({shown})", justify="right")
    table.add_column("how found", overflow="fold")
    table.add_column("kind")
    for c in ic.centres:
        if c.point is not None:
            tiny = 1e-9 * to_unit(ic.size, unit)
            x, y = _num(to_unit(c.point[0], unit), tiny), _num(to_unit(c.point[1], unit), tiny)
        elif c.direction is not None:
            x, y = f"∞ at {_angle(c.direction):.4g}°", ""
        else:
            x, y = "?", "?"
        if c.primary:
            kind = "primary"
        elif c.step is None:
            kind = "secondary (field)" if c.found else "—"
        else:
            kind = f"secondary ({_ordinal(c.step)} round)"
        table.add_row(c.name, f"{c.links[0]}–{c.links[1]}", x, y, c.method, kind)
    console.print(table)
    checks = [c.check for c in ic.centres if c.check is not None]
    if checks:
        console.print(
            f"  checked against the velocity field: {len(checks)} of {ic.count} agree "
            f"(largest separation {max(checks):.1e} of the size {ic.size:.6g} m)"
        )
    field = [c.name for c in ic.centres if c.found and c.step is None]
    if field:
        console.print(f"  from the velocity field (Kennedy cannot reach them): {', '.join(field)}")
    if ic.rounds:
        console.print(f"  Kennedy's construction: {ic.rounds} round{'s' if ic.rounds > 1 else ''}")
    for note in ic.notes:
        console.print(f"  note: {note}")
    if ic.omegas:
        om = Table(box=table_box(console), title="Angular velocities by the I-centre method")
        om.add_column("link")
        om.add_column("ω by I-centres (rad/s)", justify="right")
        om.add_column("via")
        om.add_column("ω relative-velocity solution (rad/s)", justify="right")
        for o in ic.omegas:
            om.add_row(o.link, _omega(o.omega), o.via, _omega(o.solver))
        console.print(om)
        console.print("  ω_j/ω_i = I1i·Iij / I1j·Iij: the point Iij moves alike on links i and j")


def order_dict(order: TopologyCentres) -> dict[str, Any]:
    """``mech icentres --json`` without coordinates: each centre, how and in which step it is found."""
    return {
        "file": order.path,
        "name": order.name,
        "links": list(order.numbered),
        "count": order.count,
        "located": False,
        "centres": [
            {
                "name": c.name,
                "links": list(c.links),
                "numbers": list(c.numbers),
                "primary": c.step == 0,
                "step": c.step,
                "lines": [[a, b] if b else [a] for a, b in c.lines],
                "how": c.how,
            }
            for c in order.centres
        ],
    }


def order_table(order: TopologyCentres, console: ReportConsole) -> None:
    """``mech icentres`` on a file that places nothing: the count, the primary centres, Kennedy's order."""
    from mech.render.console import table_box
    from mech.render.table import Table, Text

    box = table_box(console)
    n = len(order.numbered)
    console.print(Text(order.name, style="bold"))
    numbering = ", ".join(f"{k + 1} {name}" for k, name in enumerate(order.numbered))
    console.print(f"  links, numbered (ground = 1): {numbering}")
    console.print(f"  instantaneous centres: N = n(n − 1)/2 = {n}·{n - 1}/2 = {order.count}")
    table = Table(box=box)
    table.add_column("I-centre")
    table.add_column("links")
    table.add_column("found", justify="right")
    table.add_column("how found", overflow="fold")
    for c in order.centres:
        found = "primary" if c.step == 0 else ("—" if c.step is None else f"step {c.step}")
        table.add_row(c.name, f"{c.links[0]}–{c.links[1]}", found, c.how)
    console.print(table)
    console.print(
        f"  {len(order.primary)} primary by inspection, {order.count - len(order.primary) - len(order.unreached)} "
        f"by Kennedy's theorem, {len(order.unreached)} not reached; no coordinates: the file places nothing "
        "(give positions and lengths to locate them)",
        soft_wrap=True,
    )
