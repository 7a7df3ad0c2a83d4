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
    if names and _any_link(an, c, names[0]):
        return float(an.cached(f"time_ratio.{names[0]}", lambda: _link_time_ratio(an, names[0])))
    output = _output(an, c, names[0]) if names else None
    got = c.sweep.time_ratio_of(output)
    if isinstance(got, str):
        raise Undefined(f"cannot be computed: {got}")
    return float(got.ratio)


def _any_link(an: Analysis, c: Any, name: str) -> bool:
    """A moving link that is neither an output the sweep follows nor the driven one (a coupler)."""
    sw = c.sweep
    known = {r.output for r in sw.time_ratios} | {n for n, _w in sw.time_ratio_refused if n}
    drives = {d.link for d in an.mech.drives}
    carried = any(j.name in known and name in j.links and j.name in sw.slides for j in an.mech.joints)
    return name not in known and name not in drives and not carried and name in sw.links


def _link_time_ratio(an: Analysis, name: str) -> float:
    """Slow stroke over fast of any link that swings between two limit angles (a coupler).

    DESIGN § 1.2: "a link … for any output with two limit positions over the input's full
    turn".  Over one turn of the crank the link's ω changes sign exactly twice, at its largest
    and least angles (its limit positions, refined by the sweep); the crank's arcs between
    them are the strokes.
    """
    import math

    import numpy as np

    from mech.kinematics.sweep import sweep

    if len(an.mech.drives) != 1 or an.mech.drives[0].link is None:
        raise Undefined("cannot be computed: a time ratio is over one crank's full turn")
    start = float(an.kin.drives[0].angle or 0.0)
    angles = start + np.linspace(0.0, 2.0 * math.pi, 721)
    key = f"angle.{name}"
    sw = sweep(an.mech, angles, level="velocity", quantities=[key], options=an.options.with_(angle=None))
    if not np.all(sw.assembled):
        raise Undefined(
            "cannot be computed: the crank does not turn fully (a time ratio needs its whole turn)"
        )
    w = sw.series(f"omega.{name}")
    signs = np.sign(w[np.abs(w) > 1e-12 * max(float(np.max(np.abs(w))), 1e-300)])
    reversals = int(np.count_nonzero(signs != np.roll(signs, 1))) if signs.size else 0
    if reversals != 2:
        said = "never reverses" if reversals == 0 else f"reverses {reversals} times"
        raise Undefined(
            f"cannot be computed: {name} {said} over the turn (a time ratio needs two limit positions)"
        )
    from mech.kinematics import solve

    def omega(theta: float) -> float:
        kin = solve(an.mech, "velocity", an.options.with_(angle=theta, method="auto"))
        return float(kin.links[name].omega or 0.0)

    phi = sw.angles
    ends = [
        _root(omega, float(phi[k]), float(phi[k + 1]), float(w[k]), float(w[k + 1]))
        for k in range(phi.size - 1)
        if w[k] * w[k + 1] < 0.0 or (w[k + 1] == 0.0 and k + 1 < phi.size - 1)
    ]
    if len(ends) != 2:
        raise Undefined(f"cannot be computed: {name}'s limit positions could not be told apart over the turn")
    arc = (ends[1] - ends[0]) % (2.0 * math.pi)
    return max(arc, 2.0 * math.pi - arc) / min(arc, 2.0 * math.pi - arc)


def _root(fn: Any, a: float, b: float, fa: float, fb: float) -> float:
    """A root of ``fn`` in [a, b] where it changes sign (regula falsi, Illinois), to rounding."""
    if fb == 0.0:
        return b
    side = 0
    for _ in range(100):
        c = b - fb * (b - a) / (fb - fa)
        if not a < c < b and not b < c < a:
            c = 0.5 * (a + b)
        fc = fn(c)
        if fc == 0.0 or abs(b - a) <= 4e-16 * max(1.0, abs(c)):
            return c
        if fc * fb < 0.0:
            a, fa = b, fb
            side = 0
        else:
            fa = fa / 2 if side == -1 else fa
            side = -1
        b, fb = c, fc
    return b


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
    return effort_value(effort, kind)


def effort_value(effort: Any, kind: str) -> float:
    """An input effort's value when it is of ``kind`` (``torque`` or ``force``), else why not:
    the answer key names the other kind of drive (by the loads alone or with the links' masses)."""
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
