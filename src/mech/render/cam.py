"""Tables and JSON for ``mech cam``: the programme, the follower's motion, the profile's checks.

Both are made from the same :class:`~mech.cam.analysis.CamAnalysis`, so they
cannot disagree.  JSON numbers are SI (m, m/s, m/s², m/s³; rad, rad/s … for an
oscillating follower), angles in degrees.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from mech.cam.analysis import CamAnalysis, Extreme
from mech.cam.profile import evaluate
from mech.cam.program import follower_motion
from mech.pairs.cam.setup import CamSetup

if TYPE_CHECKING:  # pragma: no cover
    from mech.render.console import ReportConsole

__all__ = ["cam_json", "cam_table", "motion_rows", "segment_rows"]


def _units(a: CamAnalysis) -> dict[str, str]:
    if a.follower_angular:
        return {"s": "rad", "v": "rad/s", "a": "rad/s^2", "j": "rad/s^3"}
    return {"s": "m", "v": "m/s", "a": "m/s^2", "j": "m/s^3"}


def segment_rows(a: CamAnalysis) -> list[dict[str, Any]]:
    """One row per segment: its span, lift, law and its largest |v|, |a| (by dense sampling)."""
    prog = a.layout.program
    rows = []
    w = a.omega
    for start, seg in zip(prog.starts, prog.segments, strict=True):
        row: dict[str, Any] = {
            "kind": seg.kind,
            "from": math.degrees(start),
            "to": math.degrees(start + seg.over),
            "lift": seg.lift,
            "law": seg.law,
            "v_max": None,
            "a_max": None,
        }
        if w is not None and seg.kind != "dwell":
            t = np.linspace(start, start + seg.over, 2001)[:-1]
            m = follower_motion(prog, t)
            row["v_max"] = float(np.max(np.abs(m.ds))) * w
            row["a_max"] = float(np.max(np.abs(m.d2s))) * w**2
        rows.append(row)
    return rows


def motion_rows(a: CamAnalysis, step_deg: float) -> list[dict[str, float | None]]:
    """s, v, a, j, pressure angle and radius of curvature every ``step_deg`` of cam angle."""
    n = max(1, round(360.0 / step_deg))
    theta = np.radians(np.arange(n) * 360.0 / n)
    st = evaluate(a.layout, theta)
    w = a.omega

    def clean(x: np.ndarray) -> np.ndarray:
        # rounding noise (1e-15 m/s² where a law's acceleration is zero) shown as the zero it is
        scale = float(np.max(np.abs(x[np.isfinite(x)]), initial=0.0))
        return np.where(np.abs(x) <= 1e-9 * scale, 0.0, x)

    s, ds, d2s, d3s = clean(st.s), clean(st.ds), clean(st.d2s), clean(st.d3s)
    pressure = clean(st.pressure)
    rows = []
    for k in range(n):
        rows.append(
            {
                "theta": float(math.degrees(theta[k])),
                "s": float(s[k]),
                "v": None if w is None else float(ds[k] * w),
                "a": None if w is None else float(d2s[k] * w**2),
                "j": None if w is None else float(d3s[k] * w**3),
                "pressure_angle": float(math.degrees(pressure[k])),
                "rho": float(st.rho[k]),
            }
        )
    return rows


def _denoise(x: float, over: np.ndarray) -> float:
    """Rounding noise (below 1e-9 of the quantity's largest value over the turn) as the zero it is."""
    return 0.0 if abs(x) <= 1e-9 * float(np.max(np.abs(over))) else x


def _ext(e: Extreme | None, *, degrees: bool = False) -> dict[str, float] | None:
    if e is None:
        return None
    return {"value": math.degrees(e.value) if degrees else e.value, "theta": math.degrees(e.theta)}


def cam_json(
    setup: CamSetup, a: CamAnalysis, *, path: str, name: str | None, step_deg: float
) -> dict[str, Any]:
    """The JSON record of ``mech cam`` (structure in cli.md § mech cam)."""
    lay = a.layout
    prog = lay.program
    now = evaluate(lay, [setup.angle])
    w = a.omega
    flat = prog.follower == "flat"
    out: dict[str, Any] = {
        "file": path,
        "name": name,
        "joint": setup.joint.name,
        "cam": setup.cam,
        "follower": setup.follower,
        "follower_kind": prog.follower,
        "motion": prog.motion,
        "units": {"length": "m", "angle": "deg", **_units(a)},
        "centre": list(setup.centre),
        "sense": "ccw" if lay.sense > 0 else "cw",
        "omega": w,
        "base_radius": prog.base_radius,
        "prime_radius": lay.prime_radius,
        "roller_radius": prog.roller_radius,
        "offset": None if lay.oscillating else lay.offset,
        "pivot": None
        if lay.pivot is None
        else [lay.pivot[0] + setup.centre[0], lay.pivot[1] + setup.centre[1]],
        "arm": lay.arm,
        "stroke": a.stroke,
        "segments": segment_rows(a),
        "velocity_max": _ext(a.velocity),
        "acceleration_max": _ext(a.acceleration),
        "jerk_max": _ext(a.jerk),
        "infinite_acceleration_at": [math.degrees(t) for t in a.velocity_jumps],
        "infinite_jerk_at": [math.degrees(t) for t in a.acceleration_jumps],
        "pressure_angle_max": _ext(a.pressure, degrees=True),
        "least_radius": _ext(a.least_radius_any if flat else a.least_radius),
        "undercut": a.undercut,
        "cusp": a.cusp,
        "face_width": None if a.face is None else {"min": a.face[0], "max": a.face[1]},
        "at": {
            "theta": math.degrees(setup.angle),
            "s": float(now.s[0]),
            "v": None if w is None else _denoise(float(now.ds[0]), a.state.ds) * w,
            "a": None if w is None else _denoise(float(now.d2s[0]), a.state.d2s) * w**2,
            "pressure_angle": float(math.degrees(now.pressure[0])),
            "point": [float(now.point[0][0] + setup.centre[0]), float(now.point[0][1] + setup.centre[1])],
        },
        "motion_table": motion_rows(a, step_deg),
    }
    return out


def _fmt(x: float | None, digits: int = 5) -> str:
    if x is None:
        return "–"
    if not math.isfinite(x):
        return "∞" if x > 0 else "−∞"
    if x == 0:
        return "0"
    return f"{x:.{digits}g}"


def cam_table(setup: CamSetup, a: CamAnalysis, console: ReportConsole, *, name: str, step_deg: float) -> None:
    """The human report: set-up, segments, follower motion every ``step_deg``, the profile's checks."""
    from mech.render.console import table_box
    from mech.render.table import Text

    box = table_box(console)
    console.print(Text(name, style="bold"))
    for line in _setup_lines(setup, a):
        console.print(line)
    console.print(_programme_table(a, box))
    console.print(_motion_table(a, box, step_deg))
    console.print(_results_table(a, box))
    console.print(_drawn_line(setup, a))
    if a.omega is None:
        console.print("  (no speed given: the drive has no rpm/omega; use --rpm for velocities)")


_MM = 1000.0  # mm per m


def _lift(a: CamAnalysis, x: float) -> str:
    """A lift as the table shows it: degrees for an oscillating follower, mm for a translating one."""
    return f"{math.degrees(x):.4g}°" if a.follower_angular else f"{x * _MM:.5g} mm"


def _setup_lines(setup: CamSetup, a: CamAnalysis) -> list[str]:
    """The set-up in words: how the cam turns, the follower and where it runs, the circles and stroke."""
    lay = a.layout
    prog = lay.program
    mm = _MM
    speed = "" if a.omega is None else f" at {a.omega * 60 / (2 * math.pi):.5g} rpm ({a.omega:.5g} rad/s)"
    turns = (
        f"  {setup.cam} (the cam) turns {'counter-clockwise' if lay.sense > 0 else 'clockwise'}{speed} "
        f"about ({setup.centre[0] * mm:.5g}, {setup.centre[1] * mm:.5g}) mm"
    )
    kind = {"knife": "knife-edge", "roller": "roller", "flat": "flat-faced"}[prog.follower]
    if lay.oscillating:
        assert lay.pivot is not None and lay.arm is not None
        where = (
            f"oscillating about ({(lay.pivot[0] + setup.centre[0]) * mm:.5g}, "
            f"{(lay.pivot[1] + setup.centre[1]) * mm:.5g}) mm, "
            + (
                f"face {lay.arm * mm:.5g} mm from the pivot"
                if prog.follower == "flat"
                else f"arm {lay.arm * mm:.5g} mm"
            )
        )
    else:
        where = f"translating along {math.degrees(lay.axis) % 360:.4g}°, " + (
            "in-line" if lay.offset == 0 else f"offset {lay.offset * mm:.5g} mm"
        )
    roller = f" (roller radius {prog.roller_radius * mm:.5g} mm)" if prog.roller_radius else ""
    circles = (
        f"  base circle {prog.base_radius * mm:.5g} mm"
        + (f", prime circle {lay.prime_radius * mm:.5g} mm" if lay.roller else "")
        + f", stroke {_lift(a, a.stroke)}"
    )
    return [turns, f"  {setup.follower} (the follower): {kind}{roller}, {where}", circles]


def _programme_table(a: CamAnalysis, box: Any) -> Any:
    """One row per segment of the programme: span, lift, law, largest |v| and |a|."""
    from mech.render.table import Table

    units = _units(a)
    seg = Table(box=box, title="Programme")
    for col, just in (
        ("segment", "left"),
        ("from (°)", "right"),
        ("to (°)", "right"),
        ("lift", "right"),
        ("law", "left"),
        (f"|v| max ({units['v']})", "right"),
        (f"|a| max ({units['a']})", "right"),
    ):
        seg.add_column(col, justify=just)  # type: ignore[arg-type]
    for row in segment_rows(a):
        seg.add_row(
            row["kind"],
            f"{row['from']:.4g}",
            f"{row['to']:.4g}",
            "–" if row["kind"] == "dwell" else _lift(a, row["lift"]),
            row["law"] or "–",
            _fmt(row["v_max"]),
            _fmt(row["a_max"]),
        )
    return seg


def _motion_table(a: CamAnalysis, box: Any, step_deg: float) -> Any:
    """The follower's motion every ``step_deg``: s (v, a, j with a speed), pressure angle, ρ."""
    from mech.render.table import Table

    units = _units(a)
    ang = a.follower_angular
    mot = Table(box=box, title="Follower motion over the turn")
    s_unit = "°" if ang else "mm"
    cols = [("θ (°)", "right"), (f"s ({s_unit})", "right")]
    if a.omega is not None:
        cols += [
            (f"v ({units['v']})", "right"),
            (f"a ({units['a']})", "right"),
            (f"j ({units['j']})", "right"),
        ]
    cols += [("pressure angle (°)", "right"), ("ρ (mm)", "right")]
    for col, just in cols:
        mot.add_column(col, justify=just)  # type: ignore[arg-type]
    for r in motion_rows(a, step_deg):
        lift_now = float(r["s"] or 0.0)
        cells = [f"{r['theta']:.4g}", f"{(math.degrees(lift_now) if ang else lift_now * _MM):.5g}"]
        if a.omega is not None:
            cells += [_fmt(r["v"]), _fmt(r["a"]), _fmt(r["j"])]
        rho = r["rho"]
        cells += [f"{r['pressure_angle']:.4g}", _fmt(None if rho is None else rho * _MM)]
        mot.add_row(*cells)
    return mot


def _results_table(a: CamAnalysis, box: Any) -> Any:
    """The extremes and where they fall, the jumps, and the profile's verdict (cusp or undercut)."""
    from mech.render.table import Table

    units = _units(a)
    res = Table(box=box, title="Results")
    res.add_column("quantity")
    res.add_column("value", justify="right")
    res.add_column("at θ (°)", justify="right")

    def add(label: str, e: Extreme | None, unit: str, scale: float = 1.0) -> None:
        if e is not None:
            res.add_row(label, f"{_fmt(e.value * scale)} {unit}", f"{math.degrees(e.theta):.4g}")

    def infinite(label: str, jumps: tuple[float, ...], what: str) -> None:
        if jumps:
            res.add_row(label, f"∞ ({what} jumps)", ", ".join(f"{math.degrees(t):.4g}" for t in jumps))

    add("largest velocity", a.velocity, units["v"])
    infinite("acceleration", a.velocity_jumps, "velocity")
    add("largest acceleration", a.acceleration, units["a"])
    infinite("jerk", a.acceleration_jumps, "acceleration")
    add("largest jerk", a.jerk, units["j"])
    add("largest pressure angle", a.pressure, "°", 180 / math.pi)
    if a.layout.program.follower == "flat":
        add("least radius of curvature of the profile", a.least_radius_any, "mm", _MM)
        for row in _flat_verdict(a):
            res.add_row(*row)
    else:
        add("least radius of curvature of the pitch curve (convex)", a.least_radius, "mm", _MM)
        for row in _roller_verdict(a):
            res.add_row(*row)
    return res


def _flat_verdict(a: CamAnalysis) -> list[tuple[str, str, str]]:
    """A flat face's rows: cusp or none, and how far from its axis the contact runs."""
    corner = a.least_radius_any.value == -math.inf
    verdict = (
        "cusp: a corner where the velocity falls at once; use a law without velocity jumps"
        if corner
        else "cusp: the profile folds back (ρ < 0), raise the base circle"
        if a.cusp
        else "no cusp (ρ > 0 everywhere)"
    )
    rows = [("profile", verdict, "")]
    if a.face is not None:
        rows.append(("face contact from its axis", f"{a.face[0] * _MM:.4g} to {a.face[1] * _MM:.4g} mm", ""))
    return rows


def _roller_verdict(a: CamAnalysis) -> list[tuple[str, str, str]]:
    """A roller's row: undercut or not, against the roller's radius (none for a knife edge)."""
    prog = a.layout.program
    if prog.follower != "roller":
        return []
    assert prog.roller_radius is not None
    corner = a.least_radius is not None and a.least_radius.value == 0.0
    verdict = (
        "undercut: a corner where the velocity falls at once (the roller rounds it); "
        "use a law without velocity jumps"
        if a.undercut and corner
        else f"undercut: ρ_min < roller radius {prog.roller_radius * _MM:.4g} mm (the profile loops; "
        "use a smaller roller or a larger base circle)"
        if a.undercut
        else f"no undercut: ρ_min ≥ roller radius {prog.roller_radius * _MM:.4g} mm"
    )
    return [("roller", verdict, "")]


def _drawn_line(setup: CamSetup, a: CamAnalysis) -> str:
    """The follower where the drawing shows it: s (v, a with a speed) and the pressure angle."""
    units = _units(a)
    now = evaluate(a.layout, [setup.angle])
    drawn = f"  at θ = {math.degrees(setup.angle):.4g}°: s = {_lift(a, float(now.s[0]))}"
    if a.omega is not None:
        # rounding noise (1e-14 where a law's acceleration is zero) is the zero it is
        v_now = _denoise(float(now.ds[0]), a.state.ds)
        a_now = _denoise(float(now.d2s[0]), a.state.d2s)
        drawn += f", v = {_fmt(v_now * a.omega)} {units['v']}, a = {_fmt(a_now * a.omega**2)} {units['a']}"
    drawn += f", pressure angle {math.degrees(float(now.pressure[0])):.4g}°"
    return drawn
