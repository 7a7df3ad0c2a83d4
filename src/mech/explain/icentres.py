"""Kennedy's circle diagram written out, from located I-centres (``mech icentres --explain``)."""

from __future__ import annotations

import math
import re
from typing import Any

__all__ = ["explain_icentres"]

_KENNEDY = re.compile(r"^Kennedy: I(\S+)–I(\S+) ∩ I(\S+)–I(\S+)$")


def _pair(name: str) -> tuple[int, int]:
    """``13`` → (1, 3); ``1,12`` → (1, 12) (an I-centre's numbers, as its name writes them)."""
    if "," in name:
        a, b = name.split(",")
        return int(a), int(b)
    return int(name[0]), int(name[1:])


def explain_icentres(ics: Any, *, unit: str = "m") -> list[str]:
    """Kennedy's circle diagram written out, from located I-centres (:func:`mech.icentres.locate`).

    The links are numbered round a circle (ground 1); each I-centre known by
    inspection is a side or chord joining two numbers; each one found by the
    Aronhold-Kennedy theorem is a diagonal that closes two triangles whose other
    sides are known: it lies on both lines through their I-centres, in the
    order the construction found them (its rounds).
    """
    from mech.units import to_unit

    def at(c: Any) -> str:
        if c.at_infinity:
            d = c.direction
            return "at infinity" + (
                f", direction {math.degrees(math.atan2(d[1], d[0])) % 180:.1f}°" if d else ""
            )
        if c.point is None:
            return "not located"
        x, y = (v if abs(v) > 1e-9 * ics.size else 0.0 for v in c.point)  # rounding noise shown as 0
        return f"at ({to_unit(x, unit):.4g}, {to_unit(y, unit):.4g}) {unit}"

    names = ", ".join(f"{i + 1} ({link})" for i, link in enumerate(ics.links))
    out = [
        f"Kennedy's circle diagram: mark the links {names} round a circle; {ics.formula} I-centres, one for each "
        "side or diagonal joining two numbers."
    ]
    primary = [c for c in ics.centres if c.primary]
    out.append(
        "By inspection (draw these lines on the circle): "
        + "; ".join(f"{c.numbers[0]}–{c.numbers[1]}: {c.name} {c.method}, {at(c)}" for c in primary)
        + "."
    )
    later = sorted(
        (c for c in ics.centres if not c.primary),
        key=lambda c: (c.step if c.step is not None else 99, c.numbers),
    )
    for k, c in enumerate(later, 1):
        m = _KENNEDY.match(c.method)
        if m is None:
            out.append(f"{k}. {c.name}: {c.method}, {at(c)}.")
            continue
        (a1, b1), (a2, b2), (a3, b3), (a4, b4) = (_pair(g) for g in m.groups())
        i, j = c.numbers
        third1 = ({a1, b1} | {a2, b2}) - {i, j}
        third2 = ({a3, b3} | {a4, b4}) - {i, j}
        t1, t2 = (sorted({i, j} | t) for t in (third1, third2))
        out.append(
            f"{k}. Draw the diagonal {i}–{j}: it closes the triangles {'-'.join(map(str, t1))} and "
            f"{'-'.join(map(str, t2))}, so {c.name} lies on the line I{m.group(1)}–I{m.group(2)} and on the line "
            f"I{m.group(3)}–I{m.group(4)} (Aronhold-Kennedy: three I-centres of three links are in one line); "
            f"they meet {at(c)}."
        )
    return out
