"""The geometry of a gear mesh: its gears' centres and carrier, the rolling row, the line of action.

Below the kinds that use it (:mod:`mech.pairs.gear`; :mod:`mech.pairs.profiles`
for a rack's pitch circle; :mod:`mech.explain.train`), so none of them needs the
gear kind's module (issue 20: profiles ↔ gear was an import circle).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING

from mech.pairs.table import kind_of

if TYPE_CHECKING:
    from mech.model import Joint, Mechanism
    from mech.pairs.base import Carriers
    from mech.pairs.rows import RowBuilder

__all__ = ["carrier_of", "gear_centre", "gear_normal", "gear_row", "line_of_action"]

Vec = tuple[float, float]


def gear_centre(view: Carriers, link: str, positions: Mapping[str, Vec]) -> Vec | None:
    """A gear link's centre: its only revolute joint (None when it has none or several)."""
    pins = [n for n in view.on_link.get(link, ()) if n in positions and len(view.carriers.get(n, ())) >= 2]
    return positions[pins[0]] if len(pins) == 1 else None


def carrier_of(view: Carriers, link: str, positions: Mapping[str, Vec]) -> dict[str, str]:
    """Pins of ``link`` with the other link each joins it to: ``{other_link: joint}``."""
    out: dict[str, str] = {}
    for name in view.on_link.get(link, ()):
        carriers = view.carriers.get(name, ())
        if len(carriers) >= 2 and name in positions:
            for c in carriers:
                if c != link:
                    out.setdefault(c, name)
    return out


def gear_row(b: RowBuilder, j: Joint) -> tuple[dict[int, float], float] | None:
    """A gear pair with both centres pinned to one carrier: ``r₁(θ₁−θc) ± r₂(θ₂−θc) = const``.

    The pitch circles roll on each other relative to the carrier (ground for a
    fixed-axis pair, the arm of an epicyclic train), which is holonomic: the
    pair then moves, and accelerates, like any lower pair.  External pairs
    turn opposite ways (+), internal pairs the same way (−).  Returns None
    when there is no common carrier or no radii.
    """
    pos = b.pos
    g1, g2 = j.links
    c1, c2 = carrier_of(b, g1, pos), carrier_of(b, g2, pos)
    common = [c for c in c1 if c in c2 and c not in (g1, g2)]
    if not common:
        return None
    carrier = common[0]
    o1, o2 = pos[c1[carrier]], pos[c2[carrier]]
    given = getattr(j.spec, "pitch_radii", None) or j.radii  # a gear's (teeth × module / 2), or circles
    internal = j.internal
    radii: tuple[float, float]
    if given is not None and given[0] is not None and given[1] is not None:
        radii = (given[0], given[1])
    else:
        if j.name not in pos:
            return None
        p = pos[j.name]
        r1 = math.hypot(p[0] - o1[0], p[1] - o1[1])
        r2 = math.hypot(p[0] - o2[0], p[1] - o2[1])
        d = math.hypot(o2[0] - o1[0], o2[1] - o1[1])
        internal = internal or abs(abs(r1 - r2) - d) < abs(r1 + r2 - d)
        radii = (r1, r2)
    sign = -1.0 if internal else 1.0
    i1, i2, ic = b.index[g1], b.index[g2], b.index[carrier]
    coef: dict[int, float] = {}
    for col, v in ((i1, radii[0]), (i2, sign * radii[1]), (ic, -radii[0] - sign * radii[1])):
        coef[col] = coef.get(col, 0.0) + v / (max(radii) or 1.0)  # O(1) coefficients
    theta = {i: (0.0 if i == b.n else float(b.q0[3 * i + 2])) for i in coef}
    return coef, sum(v * theta[i] for i, v in coef.items())


def gear_normal(view: Carriers, j: Joint, positions: Mapping[str, Vec]) -> float | None:
    """Line of action of a gear pair: the common tangent turned by the pressure angle."""
    centres = [gear_centre(view, lk, positions) for lk in j.links]
    if centres[0] is None or centres[1] is None:
        return None
    return _action_angle(j, centres[0], centres[1])


def _action_angle(j: Joint, c1: Vec, c2: Vec) -> float:
    """The line of action's direction (rad): the line of centres turned by a right angle less the pressure angle."""
    return math.atan2(c2[1] - c1[1], c2[0] - c1[0]) + math.pi / 2.0 - (j.pressure_angle or 0.0)


def line_of_action(mech: Mechanism, j: Joint, positions: Mapping[str, Vec]) -> Vec | None:
    """A gear pair's common normal: the common tangent of the pitch circles turned by the pressure angle.

    Each gear's centre is its only pin; without both centres there is no line
    of action to draw (the pitch point is then taken as a rolling contact).
    """
    centres = []
    for lk in j.links:
        pins = [k.name for k in mech.joints_of(lk) if kind_of(k).role == "pin" and k.name in positions]
        if len(pins) != 1:
            return None
        centres.append(positions[pins[0]])
    if centres[0] == centres[1]:
        return None
    a = _action_angle(j, centres[0], centres[1])
    return (math.cos(a), math.sin(a))
