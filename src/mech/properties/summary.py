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
from mech.properties.cycle import Cycle, Transmission, cycle, included_angle, transmission_loop
from mech.properties.grashof import linkage_loops

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


def linkage_properties(mech: Mechanism, *, options: SolveOptions | None = None) -> LinkageProperties:
    """Solve ``mech`` at its instant and over the crank's cycle, and collect its properties."""
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
    return LinkageProperties(
        mechanism=mech.label,
        loops=loops,
        transmission=trans,
        mu=mu,
        cycle=result,
        cycle_error=why,
        kin=kin,
        length_unit=mech.length_unit,
    )
