"""A gear train worked out stage by stage (``--explain``), as the notes write a train's value.

For each mesh, from the driver outward: the driven gear turns, relative to the arm that
carries both centres (the frame, or an epicyclic train's arm), in the ratio of the pitch radii
(teeth): ω_B − ω_c = ∓ (r_A / r_B)(ω_A − ω_c), minus for external gears (they turn opposite
ways), plus for an internal (ring) gear (Khurmi & Gupta ch. 13, "gear trains"; Rattan ch. 10).
Gears on one shaft are one link and share its ω; the train value is ω_out / ω_in.
"""

from __future__ import annotations

import math
from typing import Any

from mech.explain.worked import Line, Worked, g
from mech.model import Mechanism
from mech.pairs import kind_of
from mech.pairs.gearing import common_carrier

__all__ = ["working"]


def _radii(mech: Mechanism, kin: Any, j: Any, pins: tuple[str, str]) -> tuple[float, float, str]:
    """The pitch radii of a mesh (given, teeth × module / 2, or as drawn from its centres ``pins``)
    and how they are named."""
    if j.teeth is not None:
        z1, z2 = j.teeth  # the radii are in the ratio of the teeth: the ratio is written with them
        return float(z1), float(z2), f"z = {z1} and {z2}"
    if j.radii is not None and None not in j.radii:
        return j.radii[0], j.radii[1], f"r = {g(j.radii[0] * 1000)} and {g(j.radii[1] * 1000)} mm"
    p = kin.positions[j.name]
    o1, o2 = kin.positions[pins[0]], kin.positions[pins[1]]
    r1, r2 = math.dist(p, o1), math.dist(p, o2)
    return r1, r2, f"r = {g(r1 * 1000)} and {g(r2 * 1000)} mm (as drawn)"


def _stage(mech: Mechanism, kin: Any, j: Any, known: str, other: str) -> Line | None:
    """One mesh: ``other``'s ω from ``known``'s, relative to the arm both centres are pinned to."""
    held = common_carrier(_view(kin), j, kin.positions)
    if held is None:
        return None
    arm, pin1, pin2 = held
    first = j.links[0] == known
    r_a, r_b, named = _radii(mech, kin, j, (pin1, pin2))
    if not first:
        r_a, r_b = r_b, r_a
    internal = j.internal
    k = (r_a / r_b) * (1.0 if internal else -1.0)
    w_a, w_c = kin.links[known].omega or 0.0, kin.links[arm].omega or 0.0
    w_b = w_c + k * (w_a - w_c)
    kind = "internal: the same way" if internal else "external: opposite ways"
    rel = "" if arm == mech.ground else f" relative to the arm {arm}"
    text = f"Mesh {j.name}: {known} drives {other} ({named}, {kind}{rel}): " + (
        f"ω_{other} = {'+' if internal else '−'}({g(r_a)}/{g(r_b)}) ω_{known} = {g(k)} × {g(w_a)} = {g(w_b)} rad/s"
        if arm == mech.ground
        else f"ω_{other} − ω_{arm} = {g(k)} (ω_{known} − ω_{arm}) = {g(k)} × ({g(w_a)} − {g(w_c)}), "
        f"ω_{other} = {g(w_b)} rad/s"
    )
    inputs = {"r_a": r_a, "r_b": r_b, "omega_a": w_a, "omega_arm": w_c, "internal": float(internal)}
    return Line(text, f"omega.{other}", "omega_arm + (±r_a/r_b)(omega_a - omega_arm)", inputs, w_b, "rad/s")


class _Carriers:
    """The solved instant as :class:`mech.pairs.base.Carriers` (who carries each location)."""

    def __init__(self, kin: Any) -> None:
        self.carriers = kin.carriers
        by_link: dict[str, list[str]] = {}
        for name, links in kin.carriers.items():
            for lk in links:
                by_link.setdefault(lk, []).append(name)
        self.on_link = {k: tuple(v) for k, v in by_link.items()}


def _view(kin: Any) -> _Carriers:
    return _Carriers(kin)


def working(mech: Mechanism, kin: Any) -> Worked:
    """The train of ``mech``'s gear meshes, from the driver outward, and its value."""
    gears = [j for j in mech.joints if kind_of(j).meshes]
    driver = next((d.link for d in mech.drives if d.link), None)
    lines: list[Line] = []
    if driver is None:
        return Worked(mech.label, "gear train", ())
    lines.append(
        Line(
            f"The driver {driver} turns at ω = {g(kin.links[driver].omega or 0.0)} rad/s (ccw +).",
            f"omega.{driver}",
            None,
            {},
            kin.links[driver].omega,
            "rad/s",
        )
    )
    known, last = {driver}, driver
    todo = list(gears)
    while todo:
        step = next(
            ((j, a, b) for j in todo for a, b in (j.links, j.links[::-1]) if a in known and b not in known),
            None,
        )
        if step is None:
            break
        j, a, b = step
        todo.remove(j)
        line = _stage(mech, kin, j, a, b)
        if line is not None:
            lines.append(line)
            known.add(b)
            last = b
    if last != driver:
        w_in, w_out = kin.links[driver].omega or 0.0, kin.links[last].omega or 0.0
        if w_in:
            lines.append(
                Line(
                    f"Train value ω_{last} / ω_{driver} = {g(w_out)} / {g(w_in)} = {g(w_out / w_in)}",
                    "train_value",
                    "omega_out / omega_in",
                    {"omega_out": w_out, "omega_in": w_in},
                    w_out / w_in,
                    "1",
                )
            )
    return Worked(mech.label, "gear train", tuple(lines))
