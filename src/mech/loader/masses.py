"""``masses:``, ``gravity:`` and ``flywheel:`` (DESIGN § 1.4): what a force analysis needs.

Only what a question needs is modelled: a file without ``masses`` is massless,
and nothing here is read unless the file gives it.  Masses are in kg and
moments of inertia in kg·m² when bare, whatever the file's length unit; a
``radius_of_gyration`` (a length, in the file's unit) may stand for the inertia
(I = m k²).  Friction is the next step of the course, not this one: a
``friction:`` key is refused with a message that says so.
"""

from __future__ import annotations

import math
from functools import partial

import yaml

from mech.loader.nodes import did_you_mean
from mech.loader.reader import NodeReader
from mech.model import Flywheel, Mass, Vec
from mech.units import Dimension

__all__ = ["FLYWHEEL_KEYS", "MASS_KEYS", "read_flywheel", "read_gravity", "read_masses"]

#: The keys of one link's mass.
MASS_KEYS = ("mass", "centre", "inertia", "radius_of_gyration")
#: The keys of ``flywheel``.
FLYWHEEL_KEYS = ("fluctuation",)


def read_masses(
    r: NodeReader, node: yaml.Node, links: list[str], ground: str | None, located: dict[str, set[str]]
) -> tuple[Mass, ...]:
    """``masses: {coupler: {mass: 5, centre: G3, inertia: 0.08}, …}``, each checked against the names."""
    out = []
    for link, (knode, vnode) in r.mapping(node, "masses").items():
        if link not in links:
            r.problem(
                knode, f"masses names {link!r}, which is not a link", did_you_mean(link, links, "links")
            )
        elif link == ground:
            r.problem(knode, f"{link} is the ground: it does not move, so its mass does nothing here")
        else:
            mass = r.guard(partial(_mass, r, link, knode, vnode, located), None)
            if mass is not None:
                out.append(mass)
    return tuple(out)


def _mass(r: NodeReader, link: str, knode: yaml.Node, vnode: yaml.Node, located: dict[str, set[str]]) -> Mass:
    """One link's mass, centre and inertia (or radius of gyration)."""
    what = f"the mass of {link}"
    fields = r.mapping(vnode, what, allowed=MASS_KEYS)
    missing = [k for k in ("mass", "centre") if k not in fields]
    if missing:
        raise r.problem(vnode, f"{what} has no `{missing[0]}`", "e.g. {mass: 5, centre: G3, inertia: 0.08}")
    mass = r.number(fields["mass"][1], what, Dimension.MASS, positive=True)
    centre = r.name(fields["centre"][1], f"the centre of mass of {link}")
    if link not in located.get(centre, set()):
        raise r.problem(
            fields["centre"][1],
            f"the centre of mass of {link} is {centre!r}, which is not a point of {link}",
            f"add a point of {link} (e.g. points: {{G: {{link: {link}, from: A, toward: B, distance: …}}}})",
        )
    if "inertia" in fields and "radius_of_gyration" in fields:
        raise r.problem(
            fields["radius_of_gyration"][0], f"{what} gives both `inertia` and `radius_of_gyration`"
        )
    inertia = 0.0
    if "inertia" in fields:
        inertia = r.number(fields["inertia"][1], f"the inertia of {link}", Dimension.MOMENT_OF_INERTIA)
        if inertia < 0:
            raise r.problem(fields["inertia"][1], f"the inertia of {link} cannot be negative")
    elif "radius_of_gyration" in fields:
        k_node = fields["radius_of_gyration"][1]
        k = r.number(k_node, f"the radius of gyration of {link}", Dimension.LENGTH, positive=True)
        inertia = mass * k * k
    return Mass(link, mass, centre, inertia, where=r.where(knode))


def read_gravity(r: NodeReader, node: yaml.Node) -> Vec:
    """``gravity: [0, -9.81]`` (m/s², or with a unit: ``["0", "-1 g"]``)."""
    items = r.sequence(node, "gravity")
    if len(items) != 2:
        raise r.problem(node, "gravity must be a pair [gx, gy] (m/s²)", "e.g. gravity: [0, -9.81]")
    gx, gy = (r.number(n, "gravity", Dimension.ACCELERATION) for n in items)
    return (gx, gy)


def read_flywheel(r: NodeReader, node: yaml.Node) -> Flywheel:
    """``flywheel: {fluctuation: 2%}``: the total coefficient of fluctuation of speed."""
    fields = r.mapping(node, "the flywheel", allowed=FLYWHEEL_KEYS)
    if "fluctuation" not in fields:
        raise r.problem(node, "the flywheel has no `fluctuation`", "e.g. flywheel: {fluctuation: 2%}")
    vnode = fields["fluctuation"][1]
    raw = r.scalar(vnode, "the coefficient of fluctuation of speed").strip()
    try:
        value = float(raw[:-1]) / 100.0 if raw.endswith("%") else float(raw)
    except ValueError:
        raise r.problem(
            vnode,
            f"the coefficient of fluctuation must be a fraction or a percentage, not {raw!r}",
            "e.g. 2% or 0.02",
        ) from None
    if 1.0 <= value < math.inf and not raw.endswith("%"):
        raise r.problem(  # a bare number is a fraction: 2 is 200 %, not the 2 % meant
            vnode,
            f"the coefficient of fluctuation must lie between 0 and 100 %: {raw} is read as a fraction, "
            f"{value * 100:g} %: write {raw} % or {value / 100:g}",
            "it is (ω_max − ω_min)/ω_mean: ±1 % of speed is 2%",
        )
    if not 0.0 < value < 1.0:
        raise r.problem(
            vnode,
            f"the coefficient of fluctuation must lie between 0 and 100 %, not {raw}",
            "it is (ω_max − ω_min)/ω_mean: ±1 % of speed is 2%",
        )
    return Flywheel(value, where=r.where(vnode))
