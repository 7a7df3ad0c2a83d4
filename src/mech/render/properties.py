"""Text and JSON for linkage properties: Grashof, transmission angle, strokes, mechanical advantage.

No rich at import: the table functions import it inside.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from mech.units import to_unit

if TYPE_CHECKING:  # pragma: no cover
    from mech.properties.grashof import FourBarLoop, SliderCrankLoop


def _len(value: float, unit: str) -> str:
    return f"{to_unit(value, unit):.4g}"


def loop_dict(loop: FourBarLoop | SliderCrankLoop) -> dict[str, Any]:
    """One loop for ``--json`` (lengths in m)."""
    from mech.properties.grashof import FourBarLoop

    if isinstance(loop, FourBarLoop):
        sl, pq = loop.sums
        return {
            "type": "four-bar",
            "links": list(loop.links),
            "joints": list(loop.joints),
            "lengths": dict(zip(loop.links, loop.lengths, strict=True)),
            "frame": loop.frame,
            "shortest": loop.shortest,
            "longest": loop.longest,
            "s_plus_l": sl,
            "p_plus_q": pq,
            "condition": loop.condition,
            "class": loop.kind,
            "turns_fully": list(loop.turns_fully),
        }
    return {
        "type": "slider-crank",
        "links": list(loop.links),
        "joints": list(loop.joints),
        "slider": loop.slider,
        "guide": loop.guide,
        "crank": loop.crank,
        "rod": loop.rod,
        "lengths": dict(loop.lengths),
        "fixed": loop.fixed,
        "inversion": loop.inversion,
        "offset": loop.offset,
        "crank_turns_fully": loop.crank_turns_fully,
    }


def loop_lines(loop: FourBarLoop | SliderCrankLoop, unit: str) -> list[str]:
    """Grashof's criterion worked for one loop, as a student writes it (lengths in ``unit``)."""
    from mech.properties.grashof import FourBarLoop

    if isinstance(loop, FourBarLoop):
        ring = "–".join(loop.links)
        order = sorted(range(4), key=lambda i: loop.lengths[i])
        s, p, q, lg = (loop.lengths[i] for i in order)
        sl, pq = loop.sums
        rel = {"grashof": "<", "change-point": "=", "non-grashof": ">"}[loop.condition]
        worked = (
            f"s + l = {_len(s, unit)} + {_len(lg, unit)} = {_len(sl, unit)} {rel} "
            f"p + q = {_len(p, unit)} + {_len(q, unit)} = {_len(pq, unit)} {unit}"
        )
        names = f"s = {loop.shortest}, l = {loop.longest}"
        if loop.kind is None:
            verdict = (
                f"Grashof (no fixed link in this loop; {loop.shortest} turns fully relative to the others)"
            )
        else:
            verdict = loop.kind
            if loop.kind != "non-grashof":
                turning = ", ".join(loop.turns_fully) or "none"
                verdict += f"; turns fully: {turning}"
            else:
                verdict += " (triple rocker): no link turns fully"
        return [f"Grashof, loop {ring} ({' '.join(loop.joints)}): {worked} ({names})", f"  {verdict}"]
    ring = "–".join(loop.links)
    lines = [f"slider-crank loop {ring}: slider {loop.slider} on guide {loop.guide}, crank {loop.crank}"]
    if loop.inversion:
        lines.append(f"  {loop.inversion}")
    turns = loop.crank_turns_fully
    if turns is not None:
        r, rod, e = loop.lengths[loop.crank], loop.lengths[loop.rod], abs(loop.offset or 0.0)
        rel = "≤" if turns else ">"
        lines.append(
            f"  r + |e| = {_len(r, unit)} + {_len(e, unit)} {rel} l = {_len(rod, unit)} {unit}: "
            + ("the crank turns fully" if turns else "the crank cannot turn fully")
        )
    return lines


def degrees(rad: float) -> float:
    return math.degrees(rad)
