"""Text and JSON for linkage properties: Grashof, transmission angle, strokes, mechanical advantage.

No rich at import: the table functions import it inside.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from mech.units import to_unit

if TYPE_CHECKING:  # pragma: no cover
    from mech.options import OutputUnits
    from mech.properties.cycle import Cycle
    from mech.properties.summary import LinkageProperties
    from mech.render.console import ReportConsole
    from mech.topology.grashof import FourBarLoop, SliderCrankLoop


def _len(value: float, unit: str) -> str:
    return f"{to_unit(value, unit):.4g}"


def loop_dict(loop: FourBarLoop | SliderCrankLoop) -> dict[str, Any]:
    """One loop for ``--json`` (lengths in m)."""
    from mech.topology.grashof import FourBarLoop

    if isinstance(loop, FourBarLoop):
        sl, pq = loop.sums
        return {
            "type": "four-bar",
            "links": list(loop.links),
            "joints": list(loop.joints),
            "lengths": dict(zip(loop.links, loop.lengths, strict=True)),
            "frame": loop.frame,
            "shortest": loop.shortest,
            "longest": loop.longest,
            "s_plus_l": sl,
            "p_plus_q": pq,
            "condition": loop.condition,
            "class": loop.kind,
            "turns_fully": list(loop.turns_fully),
        }
    return {
        "type": "slider-crank",
        "links": list(loop.links),
        "joints": list(loop.joints),
        "slider": loop.slider,
        "guide": loop.guide,
        "crank": loop.crank,
        "rod": loop.rod,
        "lengths": dict(loop.lengths),
        "fixed": loop.fixed,
        "inversion": loop.inversion,
        "offset": loop.offset,
        "crank_turns_fully": loop.crank_turns_fully,
    }


def loop_lines(
    loop: FourBarLoop | SliderCrankLoop, unit: str, motion: Mapping[str, str] | None = None
) -> list[str]:
    """Grashof's criterion worked for one loop, as a student writes it (lengths in ``unit``).

    ``motion`` (``mech properties``): what each link on the frame does in the whole mechanism
    over the crank's turn ("turns fully", "swings 69.09°"), written beside what the loop alone
    would do: a loop driven through another one (a Watt six-bar's second loop) is a
    crank-rocker alone, while its "crank" only swings as far as the first loop moves it.
    """
    from mech.topology.grashof import FourBarLoop

    if isinstance(loop, FourBarLoop):
        ring = "–".join(loop.links)
        order = sorted(range(4), key=lambda i: loop.lengths[i])
        s, p, q, lg = (loop.lengths[i] for i in order)
        sl, pq = loop.sums
        rel = {"grashof": "<", "change-point": "=", "non-grashof": ">"}[loop.condition]
        worked = (
            f"s + l = {_len(s, unit)} + {_len(lg, unit)} = {_len(sl, unit)} {rel} "
            f"p + q = {_len(p, unit)} + {_len(q, unit)} = {_len(pq, unit)} {unit}"
        )
        names = f"s = {loop.shortest}, l = {loop.longest}"
        if loop.kind is None:
            verdict = (
                f"Grashof (no fixed link in this loop; {loop.shortest} turns fully relative to the others)"
            )
        else:
            verdict = loop.kind + (" as a loop alone" if motion is not None else "")
            if loop.kind != "non-grashof":
                turning = ", ".join(loop.turns_fully) or "none"
                verdict += f"; turns fully: {turning}"
            else:
                verdict += " (triple rocker): no link turns fully"
        lines = [f"Grashof, loop {ring} ({' '.join(loop.joints)}): {worked} ({names})", f"  {verdict}"]
        done = [f"{lk} {motion[lk]}" for lk in loop.links if motion is not None and lk in motion]
        if done:
            lines.append(f"  in this mechanism: {'; '.join(done)}")
        return lines
    ring = "–".join(loop.links)
    lines = [f"slider-crank loop {ring}: slider {loop.slider} on guide {loop.guide}, crank {loop.crank}"]
    if loop.inversion:
        lines.append(f"  {loop.inversion}")
    turns = loop.crank_turns_fully
    if turns is not None:
        r, rod, e = loop.lengths[loop.crank], loop.lengths[loop.rod], abs(loop.offset or 0.0)
        rel = "≤" if turns else ">"
        lines.append(
            f"  r + |e| = {_len(r, unit)} + {_len(e, unit)} {rel} l = {_len(rod, unit)} {unit}: "
            + ("the crank turns fully" if turns else "the crank cannot turn fully")
        )
    return lines


def degrees(rad: float) -> float:
    return math.degrees(rad)


# -- mech properties ----------------------------------------------------------------------------
def _deg(rad: float | None) -> float | None:
    return None if rad is None else math.degrees(rad)


#: A crank angle within this (deg) below 360° is 0°: the seam's extremes are refined to about 1e-6°.
SEAM_DEG = 1e-5


def _crank_deg(rad: float) -> float:
    """A drive angle in [0°, 360°): one convention for every crank angle and output angle shown."""
    d = math.degrees(rad) % 360.0
    return 0.0 if d >= 360.0 - SEAM_DEG else d


def _deg_text(deg: float) -> str:
    """A crank angle in [0°, 360°) to 4 decimals: one just below 360° rounds to 0.0000, not 360.0000."""
    text = f"{deg:.4f}"
    return "0.0000" if text == "360.0000" else text


def motion_of(props: LinkageProperties) -> dict[str, str] | None:
    """What each link on the frame does over the crank's turn in the whole mechanism (None: not swept)."""
    c = props.cycle
    if c is None:
        return None
    out: dict[str, str] = {}
    drive = props.kin.drives[0].link if props.kin.drives else None
    if drive and not c.gaps:
        out[drive] = "turns fully (driven)"
    for s in c.strokes.values():
        if s.unit == "rad":
            out[s.subject] = f"swings {math.degrees(s.value):.5g}°"
    for loop in props.loops:
        joints, links = getattr(loop, "joints", ()), getattr(loop, "links", ())
        for i, j in enumerate(joints):
            if j in c.turning and len(links) == len(joints):
                pair = (links[i], links[(i + 1) % len(links)])
                out.update({lk: "turns fully" for lk in pair if lk != getattr(loop, "frame", None)})
    return out


def properties_dict(
    props: LinkageProperties, *, units: OutputUnits, file: str | None = None
) -> dict[str, Any]:
    """``mech properties --json``: keys named as the answer keys (angles in degrees, lengths in ``units``)."""
    from mech.topology.grashof import FourBarLoop, main_loop

    length = units.length
    out: dict[str, Any] = {
        "file": file,
        "mechanism": props.mechanism,
        "units": {"length": length, "angle": "deg"},
    }
    out["loops"] = [loop_dict(loop) for loop in props.loops]
    drive = props.transmission.driver if props.transmission else None
    main = main_loop(props.loops, drive)
    out["grashof"] = main.kind if isinstance(main, FourBarLoop) else None
    out["transmission_angle"] = _transmission_dict(props)
    if props.cycle is not None:
        out.update(_cycle_dict(props.cycle, length))
    out["cycle_error"] = props.cycle_error
    out.update(_advantage_dict(props))
    out["advantage_error"] = props.advantage_error
    return out


def _transmission_dict(props: LinkageProperties) -> dict[str, Any] | None:
    """The transmission angle now, and its least and greatest over the cycle with their crank angles."""
    t, c = props.transmission, props.cycle
    if t is None:
        return None
    return {
        "value": _deg(props.mu),
        "at": t.joint,
        "between": [t.coupler, t.output],
        "angle": [t.coupler_joint, t.joint, t.pivot],
        "min": _deg(c.mu_min) if c else None,
        "min_crank_angle": _crank_deg(c.mu_min_angle) if c and c.mu_min_angle is not None else None,
        "max": _deg(c.mu_max) if c else None,
        "max_crank_angle": _crank_deg(c.mu_max_angle) if c and c.mu_max_angle is not None else None,
    }


def _cycle_dict(c: Cycle, length: str) -> dict[str, Any]:
    """What the cycle gives: strokes, time ratio, limit positions, the links that turn fully."""

    def value(v: float, unit: str) -> float:
        return to_unit(v, length) if unit == "m" else math.degrees(v)

    def place(v: float, unit: str) -> float:  # an output's angle in [0°, 360°), as in every table
        return to_unit(v, length) if unit == "m" else _crank_deg(v)

    return {
        "stroke": {
            j: {
                "subject": s.subject,
                "link": s.link or s.subject,
                "value": value(s.value, s.unit),
                "unit": length if s.unit == "m" else "deg",
                "low": place(s.low, s.unit),
                "low_crank_angle": _crank_deg(s.low_angle),
                "high": place(s.high, s.unit),
                "high_crank_angle": _crank_deg(s.high_angle),
            }
            for j, s in c.strokes.items()
        },
        "time_ratio": c.time_ratio,
        "time_ratio_output": c.time_ratio_output,
        "time_ratios": dict(c.time_ratios),
        "time_ratio_refused": dict(c.time_ratio_why),
        "limit_positions": [
            {
                "output": lp.output,
                "crank_angle": _crank_deg(lp.crank_angle),
                "position": place(lp.value, lp.unit),
                "unit": length if lp.unit == "m" else "deg",
                "dwell_to_crank_angle": None if lp.until is None else _crank_deg(lp.until),
            }
            for lp in c.limits
        ],
        "dwells": [
            {
                "output": d.subject,
                "from_crank_angle": _crank_deg(d.start),
                "to_crank_angle": _crank_deg(d.end),
                "position": place(d.value, "m" if d.subject in c.sweep.slides else "rad"),
                "reverses": d.reverses,
            }
            for d in c.sweep.dwells
        ],
        "turns_fully_at": list(c.turning),
    }


def _advantage_dict(props: LinkageProperties) -> dict[str, Any]:
    """Mechanical advantage of each output, and the input torque or force the loads ask for."""
    e = props.effort
    return {
        "mechanical_advantage": {
            a.output: {
                "value": a.value,
                "unit": a.unit,
                "kind": a.kind,
                "driver": a.driver,
                "velocity_ratio": a.velocity_ratio,
                "by_icentres": a.by_icentres,
                "by_virtual_work": a.by_virtual_work,
                "construction": a.construction,
                "dead_centre": a.dead_centre,  # the output at rest: every value ∞, written null
                "notes": list(a.notes),
            }
            for a in props.advantages
        },
        "input_torque": e.value if e is not None and e.kind == "torque" else None,
        "input_force": e.value if e is not None and e.kind == "force" else None,
        "input_effort": None
        if e is None
        else {
            "driver": e.driver,
            "kind": e.kind,
            "value": e.value,
            "by_virtual_work": e.by_virtual_work,
            "terms": {name: -t for name, t in e.terms},
        },
    }


def properties_table(props: LinkageProperties, console: ReportConsole, *, units: OutputUnits) -> None:
    """``mech properties``: Grashof worked, transmission angle, limit positions, strokes, time ratio."""
    from mech.render.console import table_box
    from mech.render.table import Table, Text

    d = properties_dict(props, units=units)
    console.print(Text(props.mechanism, style="bold"))
    for loop in props.loops:
        for line in loop_lines(loop, units.length, motion_of(props)):
            console.print(Text("  " + line), soft_wrap=True)
    if not props.loops:
        console.print("  no four-bar or slider-crank loop")
    t = d["transmission_angle"]
    if t is not None:
        console.print(
            Text(
                f"  transmission angle μ = ∠{''.join(t['angle'])} between {t['between'][0]} and {t['between'][1]} "
                f"at {t['at']}: {t['value']:.4f}° now"
            ),
            soft_wrap=True,
        )
        if t["min"] is not None:
            console.print(
                Text(
                    f"    least {t['min']:.4f}° at crank {t['min_crank_angle']:.4f}°, "
                    f"greatest {t['max']:.4f}° at crank {t['max_crank_angle']:.4f}°"
                ),
                soft_wrap=True,
            )
    _advantage_tables(props, d, console)
    if props.cycle is None:
        console.print(Text(f"  over the cycle: not swept ({props.cycle_error})"), soft_wrap=True)
        return
    if d["limit_positions"]:
        table = Table(box=table_box(console), title="Limit positions (dead centres of the outputs)")
        for col, just in (("output", "left"), ("crank angle (deg)", "right"), ("position", "right")):
            table.add_column(col, justify=just)  # type: ignore[arg-type]
        for lp in d["limit_positions"]:
            crank = _deg_text(lp["crank_angle"])
            if lp["dwell_to_crank_angle"] is not None:
                crank = f"dwell from {crank} to {_deg_text(lp['dwell_to_crank_angle'])}"
            table.add_row(lp["output"], crank, f"{lp['position']:.5g} {lp['unit']}")
        console.print(table)
    for dw in d["dwells"]:
        if not dw["reverses"]:  # a pause on the way (a limit position's dwell is in the table)
            console.print(
                f"  dwell of {dw['output']} from {_deg_text(dw['from_crank_angle'])}° to "
                f"{_deg_text(dw['to_crank_angle'])}° of crank"
            )
    if d["stroke"]:
        table = Table(box=table_box(console), title="Strokes (stroke.<joint>)")
        for col in ("joint", "of", "stroke", "from", "at crank (deg)", "to", "at crank (deg)"):
            table.add_column(col, justify="left" if col in ("joint", "of") else "right")
        for j, s in d["stroke"].items():
            table.add_row(
                j,
                s["link"],
                f"{s['value']:.5g} {s['unit']}",
                f"{s['low']:.5g}",
                _deg_text(s["low_crank_angle"]),
                f"{s['high']:.5g}",
                _deg_text(s["high_crank_angle"]),
            )
        console.print(table)
    for joint in d["turns_fully_at"]:
        console.print(f"  no stroke at {joint}: its output never reverses over the turn (it turns on)")
    for out, ratio in d["time_ratios"].items():
        console.print(f"  time ratio (slow / fast stroke of {out}, time_ratio.{out}): {ratio:.6g}")
    if d["time_ratio"] is None and d["time_ratio_refused"].get("") and d["limit_positions"]:
        console.print(Text(f"  time ratio: none ({d['time_ratio_refused']['']})"), soft_wrap=True)


def _advantage_tables(props: LinkageProperties, d: dict[str, Any], console: ReportConsole) -> None:
    """Mechanical advantage three ways, the I-centre ratio written out, and the input effort."""
    from mech.render.console import table_box
    from mech.render.table import Table, Text

    if props.advantage_error:
        console.print(Text(f"  mechanical advantage: not computed ({props.advantage_error})"), soft_wrap=True)
    if props.advantages:
        table = Table(
            box=table_box(console), title="Mechanical advantage (output load / input effort, no friction)"
        )
        for col in ("output", "by I-centres", "virtual work", "velocity solution", "unit"):
            table.add_column(col, justify="left" if col in ("output", "unit") else "right")

        def fmt(v: float | None) -> str:
            return "—" if v is None else "∞ (dead centre)" if v == math.inf else f"{v:.6g}"

        for a in props.advantages:
            table.add_row(a.output, fmt(a.by_icentres), fmt(a.by_virtual_work), fmt(a.value), a.unit)
        console.print(table)
        for a in props.advantages:
            console.print(Text(f"  {a.output}: {a.construction}"), soft_wrap=True)
            for note in a.notes:
                console.print(Text(f"    {note}"), soft_wrap=True)
    e = props.effort
    if e is not None:
        unit = "N·m, ccw +" if e.kind == "torque" else "N, along the drive's path"
        vw = "" if e.by_virtual_work is None else f" (virtual work: {e.by_virtual_work:.6g})"
        console.print(
            Text(f"  input {e.kind} on {e.driver} balancing the loads: {e.value:.6g} {unit}{vw}"),
            soft_wrap=True,
        )
