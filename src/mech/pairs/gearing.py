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

__all__ = [
    "carrier_of",
    "common_carrier",
    "gear_centre",
    "gear_centres",
    "gear_normal",
    "gear_row",
    "line_of_action",
    "pulls",
    "rack_link",
]

Vec = tuple[float, float]


def gear_centre(view: Carriers, link: str, positions: Mapping[str, Vec]) -> Vec | None:
    """A gear link's centre: its only revolute joint (None when it has none or several)."""
    pins = [n for n in view.on_link.get(link, ()) if n in positions and len(view.carriers.get(n, ())) >= 2]
    return positions[pins[0]] if len(pins) == 1 else None


def gear_centres(view: Carriers, j: Joint, positions: Mapping[str, Vec]) -> tuple[Vec, Vec] | None:
    """Both gears' centres: each gear's only pin, or, for a gear pinned more than once (a fixed ring
    that is the frame), its pin on the carrier both centres are fixed in (:func:`carrier_of`: the
    arm of an epicyclic train); None when a centre is not known.  The one reading of a gear's centre
    for its pitch point, its drawing's check, its line of action and its rows; a rack has none
    (:func:`rack_link`: a pin on it, to a rod, is no centre)."""
    if rack_link(j) is not None:
        return None
    held = common_carrier(view, j, positions)
    out: list[Vec] = []
    for k, link in enumerate(j.links):
        only = gear_centre(view, link, positions)
        if only is not None:
            out.append(only)
        elif held is not None:
            out.append(positions[held[1 + k]])
        else:
            return None
    return out[0], out[1]


def common_carrier(view: Carriers, j: Joint, positions: Mapping[str, Vec]) -> tuple[str, str, str] | None:
    """The link both gears' centres are fixed in (the frame, an arm, coaxial pins included:
    :func:`carrier_of`) and each gear's pin on it; None when there is none."""
    g1, g2 = j.links
    c1, c2 = carrier_of(view, g1, positions), carrier_of(view, g2, positions)
    common = [c for c in c1 if c in c2 and c not in (g1, g2)]
    return (common[0], c1[common[0]], c2[common[0]]) if common else None


def rack_link(j: Joint) -> str | None:
    """The pair's rack: the link whose pitch curve is a straight line (``radii: [r, null]``, or a
    ``line`` profile against the other's circle); None for two gears.  The one reading of a rack for
    its rows, its line of action and its tooth load."""
    from mech.specs import Circle, Line

    if j.radii is not None and None in j.radii:
        return j.links[j.radii.index(None)]
    profiles = dict(j.profiles)
    for link, other in (j.links, reversed(j.links)):
        if isinstance(profiles.get(link), Line) and isinstance(profiles.get(other), Circle):
            return link
    return None


def _rack(view: Carriers, j: Joint, positions: Mapping[str, Vec]) -> tuple[Vec, Vec] | None:
    """A rack and pinion's "centres": the pinion's, and the pitch point for the rack's (the line of
    centres is then the perpendicular from the pinion's centre to the pitch line)."""
    rack = rack_link(j)
    if rack is None or j.name not in positions:
        return None
    pinion = next(lk for lk in j.links if lk != rack)
    c = gear_centre(view, pinion, positions)
    if c is None:
        return None
    p = positions[j.name]
    return (c, p) if j.links[0] == pinion else (p, c)


class _Pins:
    """Who carries each pin, read off the file (where no layout is at hand: a solved instant)."""

    def __init__(self, mech: Mechanism) -> None:
        self.carriers = {k.name: tuple(k.links) for k in mech.joints if kind_of(k).role == "pin"}
        self.on_link = {
            lk.name: tuple(n for n, links in self.carriers.items() if lk.name in links) for lk in mech.links
        }


def carrier_of(view: Carriers, link: str, positions: Mapping[str, Vec]) -> dict[str, str]:
    """The links ``link``'s centre is fixed in, each with the pin at that centre: ``{other_link: joint}``.

    The links it is pinned to, and the links pinned on one of those at the same point (coaxial: an
    epicyclic train's sun pinned to the frame where its arm turns, the sun's centre fixed in the
    arm too), so that a gear pair finds the carrier both its centres are fixed in.
    """
    out: dict[str, str] = {}
    for name in view.on_link.get(link, ()):
        carriers = view.carriers.get(name, ())
        if len(carriers) >= 2 and name in positions:
            for c in carriers:
                if c != link:
                    out.setdefault(c, name)
    for other, pin in list(out.items()):
        here = positions[pin]
        for name in view.on_link.get(other, ()):
            if name == pin or name not in positions or not _same_point(positions[name], here):
                continue
            for c in view.carriers.get(name, ()):
                if c not in (link, other):
                    out.setdefault(c, pin)
    return out


def _same_point(a: Vec, b: Vec) -> bool:
    """Two drawn pins at one point (to rounding of their coordinates)."""
    return math.dist(a, b) <= 1e-12 * max(1.0, abs(a[0]), abs(a[1]), abs(b[0]), abs(b[1]))


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
    held = common_carrier(b, j, pos)
    if held is None:
        return None
    carrier, pin1, pin2 = held
    o1, o2 = pos[pin1], pos[pin2]
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
    centres = gear_centres(view, j, positions)
    return None if centres is None else _action_angle(j, *centres)


def _action_angle(j: Joint, c1: Vec, c2: Vec, flank: float = 1.0) -> float:
    """The line of action's direction (rad): the line of centres turned by a right angle less the
    pressure angle (``flank`` −1: more, the teeth's other flanks in contact)."""
    return math.atan2(c2[1] - c1[1], c2[0] - c1[0]) + math.pi / 2.0 - flank * (j.pressure_angle or 0.0)


def pulls(mech: Mechanism, j: Joint, positions: Mapping[str, Vec], force: Vec) -> bool:
    """Whether ``force`` on the pair's second gear at the pitch point would pull the teeth apart.

    Teeth only push: on a gear with teeth outside (a pinion, a wheel) the tooth load's radial part
    points from the pitch point toward its centre, on a ring (teeth inside) away from it, on a rack
    into its body, away from the pinion.  A load the other way means the other flanks are in
    contact, and the line of action is the mirror one (:func:`line_of_action`, ``flank`` −1).
    """
    pins = _Pins(mech)
    centres = gear_centres(pins, j, positions) or _rack(pins, j, positions)
    if centres is None or j.name not in positions or not j.pressure_angle:
        return False
    p = positions[j.name]
    d = [math.dist(p, c) for c in centres]
    ring = 1 if j.internal and d[1] > d[0] else 0 if j.internal else None
    # judge on a gear with teeth outside: the first unless it is the ring (the force on it is −force)
    k = 0 if ring != 0 else 1
    if d[k] == 0.0:  # the rack's own "centre" is the pitch point: judge on the pinion
        k = 1 - k
    on = force if k == 1 else (-force[0], -force[1])
    c = centres[k]
    inward = (c[0] - p[0]) * on[0] + (c[1] - p[1]) * on[1]
    return inward < 0.0


def line_of_action(mech: Mechanism, j: Joint, positions: Mapping[str, Vec], flank: float = 1.0) -> Vec | None:
    """A gear pair's common normal: the common tangent of the pitch circles turned by the pressure angle.

    Each gear's centre as :func:`gear_centres` reads it; without both there is no line of
    action to draw (the pitch point is then taken as a rolling contact).
    """
    pins = _Pins(mech)
    centres = gear_centres(pins, j, positions) or _rack(pins, j, positions)
    if centres is None:
        return None
    if centres[0] == centres[1]:
        return None
    a = _action_angle(j, centres[0], centres[1], flank)
    return (math.cos(a), math.sin(a))
