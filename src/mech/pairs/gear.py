"""Gear pair (h = 1): pitch circles that roll, teeth that keep them in step.

``radii`` or ``teeth`` with ``module`` give the pitch circles about each gear's
pivot (then the pitch point follows from the centres and the pair moves);
``pressure_angle`` turns the line of action from the common tangent;
``internal`` marks a ring gear.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

from mech.errors import Problem
from mech.fields import NUMBER, PROFILES, RADII, Fields, Reader, is_null, read_profiles, read_radii
from mech.pairs.base import Carriers, PairKind, contact_forces, push_row
from mech.pairs.gearing import (
    gear_centre,
    gear_centres,
    gear_normal,
    gear_row,
    line_of_action,
    pulls,
    rack_link,
)
from mech.pairs.higher import see_contact
from mech.specs import GearSpec
from mech.units import Dimension, to_unit

if TYPE_CHECKING:
    from mech.model import Joint, Mechanism
    from mech.pairs.base import InstantView, PairForce, Wrench
    from mech.pairs.glyph import GlyphView, Shape
    from mech.pairs.rows import RowBuilder

__all__ = ["Gear"]

Vec = tuple[float, float]
#: Pitch radii and centre distance agree to this, relative (exact data that must close together).
_AGREE = 1e-6


def _teeth(r: Reader, node: Any) -> tuple[int, int]:
    items = r.sequence(node, "teeth")
    if len(items) != 2:
        raise r.problem(node, "teeth must be a pair [z1, z2]")
    out = []
    for item in items:
        if is_null(item):  # a rack has no count of teeth round a circle
            raise r.problem(
                item,
                "a rack has no tooth count",
                "write a rack and pinion with radii: [r, null] (the pinion's pitch radius r = teeth × module / 2)",
            )
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
    radii = r.optional(fields, "radii", lambda n: read_radii(r, n, what, nulls=True))  # null: a rack
    teeth = r.optional(fields, "teeth", lambda n: _teeth(r, n))
    module = r.optional(
        fields, "module", lambda n: r.number(n, "the module", Dimension.LENGTH, positive=True)
    )
    internal = bool(r.optional(fields, "internal", lambda n: r.boolean(n, "internal")))
    profiles = r.optional(fields, "profiles", lambda n: read_profiles(r, n, what, links)) or ()
    if pressure is not None and not 0.0 <= pressure < math.pi / 2:
        r.problem(  # at 90° the tooth load along the normal carries no torque: nothing is determined
            fields["pressure_angle"][1],
            f"a pressure angle must lie from 0° up to, not including, 90°, not {math.degrees(pressure):g}°",
            "typical values are 14.5°, 20° and 25°",
        )
    if teeth is not None and module is None and "module" not in fields:  # a bad module is said already
        r.problem(fields["teeth"][0], "gear teeth need a `module` to give the pitch radii")
    if radii is not None and teeth is not None:
        r.problem(
            fields["radii"][0],
            "give `radii` or `teeth` with `module`, not both",
            "the pitch radii are teeth × module / 2: keep one of the two",
        )
    if radii is not None and None in radii and internal:
        r.problem(
            fields["internal"][0],
            "a rack (a null radius) has no inside: it cannot be internal",
            "leave internal out for a rack and pinion",
        )
    return GearSpec(
        normal=normal,
        pressure_angle=pressure,
        radii=radii,
        teeth=teeth,
        module=module,
        internal=internal,
        profiles=profiles,
    )


class Gear(PairKind):
    """Two pitch circles that roll, kept in step by teeth (h = 1)."""

    name = "gear"
    keys = MappingProxyType(
        {
            "normal": NUMBER,
            "pressure_angle": NUMBER,
            "radii": RADII,
            "teeth": {
                "type": "array",
                "items": {"type": "integer", "minimum": 1},
                "minItems": 2,
                "maxItems": 2,
            },
            "module": NUMBER,
            "internal": {"type": "boolean"},
            "profiles": PROFILES,
        }
    )
    spec = GearSpec()
    higher = True
    motion = "gear (sliding and rolling)"
    line_contact = True
    rolls = True
    meshes = True
    icentre = ("line", "gears {joint}: on the common normal at the mesh (the line of action)")
    contact_hint = " or `radii` (or `teeth` with `module`)"

    def read(self, r: Reader, fields: Fields, what: str, links: tuple[str, ...]) -> GearSpec:
        return _read(r, fields, what, links)

    def glyph(self, view: GlyphView, j: Joint) -> list[Shape]:
        """The profiles as they are now (pitch circles about the pivots where no profile is drawn), the common normal and tangent, the contact."""
        from mech.pairs.glyph import contact

        return contact(view, j, self.drawn_profiles(view.mech, j, view.positions.get(j.name)), pitch=True)

    def contact_problem(self, j: Joint) -> Problem | None:
        """Pitch radii (or teeth and module) put the pitch point between the centres, and a rack's
        (``radii: [r, null]``) on its pinion's pitch circle, along the rack's slide: no ``at`` needed."""
        if getattr(j.spec, "pitch_radii", None) is not None or j.radii is not None:
            return None
        return super().contact_problem(j)

    def complete(self, view: Carriers, j: Joint, positions: dict[str, Vec]) -> None:
        """A gear pair without ``at``: its pitch point from the centres and radii (or teeth·module/2)."""
        if j.name in positions:
            return
        radii = getattr(j.spec, "pitch_radii", None)
        centres = gear_centres(view, j, positions)
        if radii is None or centres is None:
            return
        c1, c2 = centres
        d = math.hypot(c2[0] - c1[0], c2[1] - c1[1]) or 1.0
        e = ((c2[0] - c1[0]) / d, (c2[1] - c1[1]) / d)
        if j.internal and radii[0] > radii[1]:  # the ring is the first gear: pitch point beyond the second
            positions[j.name] = (c1[0] + radii[0] * e[0], c1[1] + radii[0] * e[1])
        elif j.internal:
            positions[j.name] = (c2[0] - radii[1] * e[0], c2[1] - radii[1] * e[1])
        else:
            positions[j.name] = (c1[0] + radii[0] * e[0], c1[1] + radii[0] * e[1])

    def drawing_problem(
        self, view: Carriers, j: Joint, positions: Mapping[str, Vec], fmt: Callable[[float], str]
    ) -> Problem | None:
        """Gears whose pitch radii are given must have their centres that far apart.

        External gears: centre distance r1 + r2; internal (a ring): |r1 − r2|.  A file
        that says otherwise describes gears that cannot mesh, and every velocity
        computed from it would be wrong.
        """
        radii = getattr(j.spec, "pitch_radii", None)
        centres = gear_centres(view, j, positions)
        if radii is None or centres is None:
            return None
        c1, c2 = centres
        d = math.hypot(c2[0] - c1[0], c2[1] - c1[1])
        want = abs(radii[0] - radii[1]) if j.internal else radii[0] + radii[1]
        if abs(d - want) <= _AGREE * max(want, d):
            return None
        kind = "internal (|r1 − r2|)" if j.internal else "external (r1 + r2)"
        return Problem(
            f"gear {j.name}: pitch radii {fmt(radii[0])} and {fmt(radii[1])} need centres "
            f"{fmt(want)} apart ({kind}), but they are {fmt(d)} apart",
            j.where,
            "correct the radii, the teeth and module, or the positions of the gear centres",
        )

    def inspect(self, seen: InstantView, j: Joint) -> None:
        """On the common normal at the mesh: the line of action."""
        see_contact(seen, j, line_of_action(seen.mech, j, seen.positions))

    def reaction_rows(self, j: Joint, view: Any) -> list[list[float]] | None:
        """Gears on one carrier keep their speed ratio by an angle row, but push each other along
        the line of action at the pitch point: that force's row, [n, (P − R₁) × n] on the first
        gear and its opposite on the second (the same constraint, given the pins)."""
        kin = view.kin
        if j.name not in kin.positions or not any(r == j.name for r in view.sys.row_names):
            return None
        n = line_of_action(view.mech, j, kin.positions, view.flanks.get(j.name, 1.0))
        if n is None or j.name in view.sys.path_dirs:
            return None
        if j.name in view.sys.normals and rack_link(j) is None:
            return None  # pitch curves that roll: their own rows push along the contact's normal
        return [push_row(view, j, kin.positions[j.name], n)]

    def other_flank(self, j: Joint, mech: Mechanism, positions: Mapping[str, Vec], force: Vec) -> bool:
        """Whether the tooth load ``force`` solved on the line of action pulls: the other flanks push."""
        return pulls(mech, j, positions, force)

    def forces(
        self, j: Joint, wrenches: Mapping[str, Wrench], at: Vec | None, direction: Vec | None
    ) -> list[PairForce]:
        """The tooth load on the second gear, along the line of action at the pitch point (teeth push:
        its normal component is its magnitude where the line of action was not solved for)."""
        from dataclasses import replace

        out = contact_forces(j, wrenches, at, direction)
        # a rack's pitch line is its profiles' tangent, but its teeth push along the line of action
        rack = rack_link(j) is not None
        return [replace(f, normal=f.magnitude) if f.normal is None or rack else f for f in out]

    def rows(self, b: RowBuilder, j: Joint) -> None:
        """Pitch circles on one carrier roll (holonomic); pitch curves given roll; else the instant."""
        from mech.pairs.profiles import instant_normal, moving_contact
        from mech.pairs.rows import Angle

        holo = gear_row(b, j)
        if holo is not None:
            b.angle.append(Angle(holo[0], holo[1], j.name))
            return
        rack = j.radii is not None and None in j.radii  # radii: [r, null], a pitch circle on a pitch line
        if rack and j.radii is not None:
            pinion, radius = next((lk, r) for lk, r in zip(j.links, j.radii, strict=True) if r is not None)
            if gear_centre(b, pinion, b.pos) is None:
                swapped = [
                    f"{to_unit(radius, b.mech.length_unit):g}" if r is None else "null" for r in j.radii
                ]
                b.problems.append(
                    Problem(
                        f"gear {j.name}: the pitch circle is given to {pinion}, which turns on no single pin "
                        "(it slides: it is the rack)",
                        j.where,
                        f"radii follow links ({', '.join(j.links)}): write radii: [{', '.join(swapped)}]",
                    )
                )
                return
        if (j.profiles or rack) and moving_contact(
            b, j, rolls=True, held=True, radii=j.radii if rack else None
        ):
            return  # a rack and pinion, or pitch curves that roll
        normal = j.normal if j.normal is not None else gear_normal(b, j, b.pos)
        instant_normal(b, j, normal)
