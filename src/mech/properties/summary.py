"""Everything ``mech properties`` reports about one mechanism, in one frozen result.

The loops and Grashof's criterion use the solved configuration's lengths (so a
file that places joints relative to others is classified too); the transmission
angle is read at the instant solved; the cycle (extremes, limits, strokes, time
ratio) needs a crank that a sweep can turn, and where it cannot the reason is
kept instead.
"""

from __future__ import annotations

from typing import Any

from mech._records import dataclass
from mech.errors import MechError, UnsupportedError
from mech.model import Mechanism
from mech.options import SolveOptions
from mech.pairs import located_on
from mech.properties.cycle import Cycle, Transmission, cycle, included_angle, transmission_loop
from mech.topology.grashof import linkage_loops

__all__ = ["LinkageProperties", "linkage_properties"]


@dataclass(frozen=True)
class LinkageProperties:
    """Grashof loops, the transmission angle now and over the cycle, limits and strokes.

    ``mu`` is the transmission angle at the instant solved (rad), None when the
    mechanism has no four-bar loop with the driven crank (``transmission`` None);
    ``cycle`` None with ``cycle_error`` saying why it could not be swept.
    ``kin`` is the solution at the instant (velocity level when the drive has a
    speed), kept for the renderers and for mechanical advantage.
    """

    mechanism: str
    loops: tuple[Any, ...]
    transmission: Transmission | None
    mu: float | None
    cycle: Cycle | None
    cycle_error: str | None
    kin: Any
    length_unit: str = "m"
    advantages: tuple[Any, ...] = ()
    effort: Any = None
    advantage_error: str | None = None


def linkage_properties(
    mech: Mechanism, *, options: SolveOptions | None = None, outputs: tuple[str, ...] = ()
) -> LinkageProperties:
    """Solve ``mech`` at its instant and over the crank's cycle, and collect its properties.

    ``outputs`` are the links or points whose mechanical advantage to give
    (default: every moving link but the driver, and every loaded point).
    """
    from mech.kinematics import solve

    options = options or SolveOptions()
    kin = solve(mech, "position", options.with_(omega=None, direction=None, alpha=None))
    loops = linkage_loops(mech, kin.positions)
    try:
        trans: Transmission | None = transmission_loop(mech, kin.positions)
    except UnsupportedError:
        trans = None
    mu = None
    if trans is not None:
        pos = kin.positions
        mu = included_angle(pos[trans.coupler_joint], pos[trans.joint], pos[trans.pivot])
    result: Cycle | None = None
    why = None
    try:
        result = cycle(mech, options=options.with_(angle=None))
    except MechError as error:
        why = error.problems[0].message if error.problems else str(error)
    advantages, effort, ma_why = _advantages(mech, options, outputs)
    return LinkageProperties(
        advantages=advantages,
        effort=effort,
        advantage_error=ma_why,
        mechanism=mech.label,
        loops=loops,
        transmission=trans,
        mu=mu,
        cycle=result,
        cycle_error=why,
        kin=kin,
        length_unit=mech.length_unit,
    )


def _advantages(
    mech: Mechanism, options: SolveOptions, outputs: tuple[str, ...]
) -> tuple[tuple[Any, ...], Any, str | None]:
    """Mechanical advantages of the outputs and the input effort balancing the loads, or why not.

    They are ratios, independent of the drive's speed: a drive with no speed is turned at 1 rad/s.
    """
    from mech.kinematics import solve
    from mech.properties.advantage import input_effort, mechanical_advantage, virtual_displacements

    try:
        if (
            len(mech.drives) == 1
            and mech.drives[0].link
            and options.omega is None
            and mech.drives[0].omega is None
        ):
            options = options.with_(omega=1.0)
        kin = solve(mech, "velocity", options)
        from mech.icentres import locate

        try:
            ics = locate(mech, kin)
        except MechError:
            ics = None
        disp = virtual_displacements(mech, kin, options=options) if kin.drives[0].link else None
        drive = kin.drives[0].link
        names = list(outputs) or [lk.name for lk in mech.moving_links if lk.name != drive]
        if not outputs:  # loaded points that move (a force on a ground pivot does no work)
            names += [
                ld.target
                for ld in mech.loads
                if ld.force is not None
                and ld.target not in names
                and mech.ground not in _carriers(mech, ld.target)
            ]
        out = tuple(
            mechanical_advantage(mech, kin, n, icentres=ics, options=options, displacements=disp)
            if ics is not None
            else mechanical_advantage(mech, kin, n, options=options, displacements=disp)
            for n in names
        )
        effort = input_effort(mech, kin, options=options, displacements=disp) if mech.loads else None
    except MechError as error:
        if outputs:
            raise
        return (), None, error.problems[0].message if error.problems else str(error)
    return out, effort, None


def _carriers(mech: Mechanism, name: str) -> tuple[str, ...]:
    for p in mech.points:
        if p.name == name:
            return (p.link,)
    return located_on(mech.joint(name))
