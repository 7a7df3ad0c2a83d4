"""Gear pair (h = 1): pitch circles that roll, teeth that keep them in step.

``radii`` or ``teeth`` with ``module`` give the pitch circles about each gear's
pivot (then the pitch point follows from the centres and the pair moves);
``pressure_angle`` turns the line of action from the common tangent;
``internal`` marks a ring gear.
"""

from __future__ import annotations

import re
from typing import Any

from mech.model import JointType
from mech.pairs.base import NUMBER, PROFILES, Fields, PairKind, Reader, read_profiles, read_radii
from mech.pairs.specs import GearSpec
from mech.units import Dimension


def _teeth(r: Reader, node: Any) -> tuple[int, int]:
    items = r.sequence(node, "teeth")
    if len(items) != 2:
        raise r.problem(node, "teeth must be a pair [z1, z2]")
    out = []
    for item in items:
        raw = r.scalar(item, "a tooth count")
        if not re.fullmatch(r"\d+", raw.strip()) or int(raw) < 1:
            raise r.problem(item, f"a tooth count must be a whole number above zero, not {raw!r}")
        out.append(int(raw))
    return (out[0], out[1])


def _read(r: Reader, fields: Fields, what: str, links: tuple[str, ...]) -> GearSpec:
    normal = r.optional(fields, "normal", lambda n: r.number(n, "the common normal", Dimension.ANGLE))
    pressure = r.optional(
        fields, "pressure_angle", lambda n: r.number(n, "the pressure angle", Dimension.ANGLE)
    )
    radii = r.optional(fields, "radii", lambda n: read_radii(r, n, what, nulls=False))
    teeth = r.optional(fields, "teeth", lambda n: _teeth(r, n))
    module = r.optional(
        fields, "module", lambda n: r.number(n, "the module", Dimension.LENGTH, positive=True)
    )
    internal = bool(r.optional(fields, "internal", lambda n: r.boolean(n, "internal")))
    profiles = r.optional(fields, "profiles", lambda n: read_profiles(r, n, what, links)) or ()
    if teeth is not None and module is None:
        r.problem(fields["teeth"][0], "gear teeth need a `module` to give the pitch radii")
    if radii is not None and teeth is not None:
        r.problem(fields["radii"][0], "give `radii` or `teeth` with `module`, not both")
    return GearSpec(
        normal=normal,
        pressure_angle=pressure,
        radii=radii,
        teeth=teeth,
        module=module,
        internal=internal,
        profiles=profiles,
    )


GEAR = PairKind(
    type=JointType.GEAR,
    keys={
        "normal": NUMBER,
        "pressure_angle": NUMBER,
        "radii": {"type": "array", "items": NUMBER, "minItems": 2, "maxItems": 2},
        "teeth": {"type": "array", "items": {"type": "integer", "minimum": 1}, "minItems": 2, "maxItems": 2},
        "module": NUMBER,
        "internal": {"type": "boolean"},
        "profiles": PROFILES,
    },
    read=_read,
    spec=GearSpec(),
    higher=True,
    motion="gear (sliding and rolling)",
    line_contact=True,
)
