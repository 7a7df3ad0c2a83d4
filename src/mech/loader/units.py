"""The ``units:`` section: what a bare number of a length or an angle means in this file."""

from __future__ import annotations

import yaml

from mech.loader.reader import NodeReader
from mech.units import Dimension, known_units, unit_factor

__all__ = ["UNITS_KEYS", "read_units"]

#: The keys of ``units:`` and the dimension each sets.
UNITS_KEYS: dict[str, Dimension] = {"length": Dimension.LENGTH, "angle": Dimension.ANGLE}


def read_units(r: NodeReader, node: yaml.Node) -> None:
    """``units: {length: mm, angle: deg}``: sets the reader's factors for bare numbers."""
    units = r.mapping(node, "units", allowed=UNITS_KEYS)
    if "length" in units:
        found = _unit(r, units["length"][1], Dimension.LENGTH)
        if found:
            r.length_factor, r.length_unit = found
    if "angle" in units:
        found = _unit(r, units["angle"][1], Dimension.ANGLE)
        if found:
            r.angle_factor, r.angle_unit = found


def _unit(r: NodeReader, node: yaml.Node, dimension: Dimension) -> tuple[float, str] | None:
    """A unit name of ``dimension`` → (factor to SI, name); a problem otherwise."""
    name = r.scalar(node, f"the {dimension.label} unit")
    try:
        dim, factor = unit_factor(name)
    except KeyError:
        dim, factor = None, 0.0
    if dim is not dimension:
        r.problem(
            node,
            f"{name!r} is not a unit of {dimension.label}",
            f"use one of {', '.join(known_units(dimension))}",
        )
        return None
    return factor, name
