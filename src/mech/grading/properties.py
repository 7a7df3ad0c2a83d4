"""Reference values of the linkage-property answer keys, for ``mech check`` (DESIGN § 1.1).

Each function is ``compute(an, names)`` (:mod:`mech.grading`): ``an`` is the
problem's :class:`~mech.grading.lazy.Analysis`, ``names`` the names the key's
placeholders matched.  The analyses of :mod:`mech.properties` are imported
inside the functions that use them, so counting DOF never loads them.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from mech.answers import Undefined
from mech.topology.grashof import linkage_loops, main_loop

if TYPE_CHECKING:  # pragma: no cover
    from mech.grading.lazy import Analysis

__all__ = [
    "grashof",
    "input_force",
    "input_torque",
    "mechanical_advantage",
    "stroke",
    "time_ratio",
    "transmission_angle",
    "transmission_angle_max",
    "transmission_angle_min",
]


def grashof(an: Analysis, names: tuple[str, ...]) -> str:
    """The Grashof class of the driven four-bar loop (lengths from the file, else from the solve)."""
    drive = next((d.link for d in an.mech.drives if d.link is not None), None)
    loop = main_loop(an.topology.loops, drive)
    if loop is None:
        loop = main_loop(linkage_loops(an.mech, an.kin.positions), drive)
    if loop is None:
        raise Undefined(
            "cannot be computed: the mechanism has no four-bar loop of turning pairs with a fixed link"
        )
    return str(loop.kind)


def _cycle(an: Analysis) -> Any:
    from mech.properties.cycle import cycle

    return an.cached("properties.cycle", lambda: cycle(an.mech, options=an.options.with_(angle=None)))


def cycle_of(an: Analysis) -> Any:
    """The cycle's properties (made once per analysis): ``mech key`` reads a stroke's unit from it."""
    return _cycle(an)


def transmission_angle(an: Analysis, names: tuple[str, ...]) -> float:
    """∠(crank pin, coupler–output joint, output pivot) at the instant, rad (0 to π)."""
    from mech.properties.cycle import transmission_angle as at_instant

    return at_instant(an.mech, an.kin)[1]


def _mu(an: Analysis, which: str) -> float:
    c = _cycle(an)
    if c.transmission is None:
        from mech.properties.cycle import transmission_loop

        transmission_loop(an.mech, an.kin.positions)  # raises the reason
    value = c.mu_min if which == "min" else c.mu_max
    if value is None:
        raise Undefined("cannot be computed: the transmission angle was not found over the cycle")
    return float(value)


def transmission_angle_min(an: Analysis, names: tuple[str, ...]) -> float:
    """Least transmission angle over the crank's cycle, rad."""
    return _mu(an, "min")


def transmission_angle_max(an: Analysis, names: tuple[str, ...]) -> float:
    """Greatest transmission angle over the crank's cycle, rad."""
    return _mu(an, "max")


def time_ratio(an: Analysis, names: tuple[str, ...]) -> float:
    """Slow stroke over fast stroke (≥ 1) of the mechanism's one output with two dead centres.

    ``time_ratio.<output>`` names the output (a link, or a slider's joint; a slider's own link
    stands for its joint); bare ``time_ratio`` is refused with the candidates named when
    several outputs have different ones (DESIGN § 1.2).  Every refusal says what is true of
    this mechanism's turn (:func:`mech.kinematics.sweep_rest.find_time_ratios`).
    """
    c = _cycle(an)
    output = _output(an, c, names[0]) if names else None
    got = c.sweep.time_ratio_of(output)
    if isinstance(got, str):
        raise Undefined(f"cannot be computed: {got}")
    return float(got.ratio)


def _output(an: Analysis, c: Any, name: str) -> str:
    """The output a key names: a link, a slider's joint, or a slider's own link (its one joint)."""
    sw = c.sweep
    known = {r.output for r in sw.time_ratios} | {n for n, _w in sw.time_ratio_refused if n}
    if name in known:
        return name
    carried = [j.name for j in an.mech.joints if j.name in known and name in j.links]
    if any(lk.name == name for lk in an.mech.links) and len(carried) == 1 and carried[0] in sw.slides:
        return carried[0]
    drive = next((d.link for d in an.mech.drives if d.link is not None), None)
    if name == drive:
        raise Undefined(f"cannot be computed: {name} is the driven link, not an output")
    raise Undefined(
        f"cannot be computed: {name} is not an output whose dead centres a sweep finds "
        f"(a link pivoted on the frame or a slider on it: {', '.join(sorted(known)) or 'none here'})"
    )


def stroke(an: Analysis, names: tuple[str, ...]) -> float:
    """A prismatic joint's travel (m), or the swing of the link a frame pivot carries (rad)."""
    c = _cycle(an)
    joint = names[0]
    if joint in c.strokes:
        return float(c.strokes[joint].value)
    if joint in c.turning:
        raise Undefined(
            f"cannot be computed: the output at {joint} never reverses over the turn "
            "(it turns right round, or turns on as a gear): no stroke"
        )
    raise Undefined(
        f"cannot be computed: {joint} is neither a prismatic joint nor a revolute joint on the frame "
        "carrying a link other than the crank"
    )


def mechanical_advantage(an: Analysis, names: tuple[str, ...]) -> float:
    """Output load over input effort (velocity solution; the I-centre route agrees to rounding)."""
    from mech.properties.advantage import mechanical_advantage as ma

    out = names[0]
    return float(
        an.cached(
            f"properties.ma.{out}",
            lambda: ma(an.mech, an.kin, out, icentres=an.icentres, options=an.options, virtual_work=False),
        ).value
    )


def _effort(an: Analysis, kind: str) -> float:
    from mech.properties.advantage import input_effort

    effort = an.cached("properties.effort", lambda: input_effort(an.mech, an.kin, virtual_work=False))
    if effort.kind != kind:
        other = "input_force" if kind == "torque" else "input_torque"
        raise Undefined(
            f"cannot be computed: the drive is {'a slider' if kind == 'torque' else 'a turning link'}; "
            f"answer {other} instead"
        )
    return float(effort.value)


def input_torque(an: Analysis, names: tuple[str, ...]) -> float:
    """The torque on the input link that balances the file's loads (N·m, ccw +), no friction."""
    return _effort(an, "torque")


def input_force(an: Analysis, names: tuple[str, ...]) -> float:
    """The force along a slider drive's path that balances the file's loads (N), no friction."""
    return _effort(an, "force")
