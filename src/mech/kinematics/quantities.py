"""The quantities a sweep reports: their keys, SI units, which level they need, and how each is read.

A key is ``kind.name[.component]``: ``angle.LINK``, ``omega.LINK``,
``alpha.LINK``, ``velocity.POINT[.x|.y]``, ``acceleration.POINT[.x|.y]``,
``position.POINT.x|y``, ``displacement.JOINT``, ``sliding.JOINT``,
``included.P.Q.R``.  :func:`pick` reads one from the arrays of either
back-end, at any shape of angles.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from mech.errors import InputError

__all__ = ["LEVELS", "check_quantity", "contact_points_asked", "default_quantities", "pick", "quantity_unit"]

LEVELS = ("position", "velocity", "acceleration")


_UNITS = {
    "angle": "rad",
    "omega": "rad/s",
    "alpha": "rad/s^2",
    "velocity": "m/s",
    "acceleration": "m/s^2",
    "position": "m",
    "displacement": "m",
    "sliding": "m/s",
    "included": "rad",
}
_NEEDS = {"omega": 1, "velocity": 1, "sliding": 1, "alpha": 2, "acceleration": 2}


def quantity_unit(quantity: str) -> str:
    """SI unit of a quantity key.

    Keys: ``angle.<link>``, ``omega.<link>``, ``alpha.<link>`` (signed, ccw +);
    ``velocity.<point>``, ``acceleration.<point>`` (magnitudes) or with
    ``.x``/``.y`` (components); ``position.<point>.x|y``;
    ``displacement.<joint>`` and ``sliding.<joint>`` (a slider along its path);
    ``included.<p>.<q>.<r>``: the angle p–q–r at q, 0 to π (a transmission angle).
    """
    return _UNITS[quantity.split(".", 1)[0]]


def check_quantity(
    sw_points: Sequence[str], links: Sequence[str], slides: Sequence[str], key: str, lvl: int
) -> None:
    parts = key.split(".")
    kind = parts[0]
    if kind not in _UNITS or len(parts) < 2:
        raise InputError(
            f"unknown quantity {key!r}",
            hint="angle.LINK, omega.LINK, alpha.LINK, velocity.POINT[.x|.y], acceleration.POINT[.x|.y], "
            "position.POINT.x|y, displacement.JOINT, sliding.JOINT, included.P.Q.R",
        )
    if kind == "included":
        if len(parts) != 4:
            raise InputError(f"{key}: an included angle names three points, included.P.Q.R (the angle at Q)")
        for name in parts[1:]:
            if name not in sw_points:
                raise InputError(f"{key}: no point named {name}", hint=f"choose from {', '.join(sw_points)}")
        return
    if _NEEDS.get(kind, 0) > lvl:
        raise InputError(f"{key} needs level {LEVELS[_NEEDS[kind]]} (give --level {LEVELS[_NEEDS[kind]]})")
    name = parts[1]
    pool = {"angle": links, "omega": links, "alpha": links, "displacement": slides, "sliding": slides}.get(
        kind, sw_points
    )
    if name not in pool and kind in ("displacement", "sliding"):
        raise InputError(
            _slide_message(key, kind, name, slides, sw_points),
            hint=_slide_hint(kind, name, slides, sw_points),
        )
    if name not in pool and "@" in name:
        raise InputError(
            f"{key}: {name} is a link's point at a contact (DESIGN § 1.2); a sweep does not follow "
            "such points yet",
            hint=f"mech {kind if kind != 'position' else 'position'} FILE --angle A gives {name} at one "
            f"angle; a sweep follows {name.split('@')[0]} where it is a follower's own point, and the "
            f"links' named points: {', '.join(pool)}",
        )
    if name not in pool:
        raise InputError(
            f"{key}: no {'link' if kind in ('angle', 'omega', 'alpha') else 'joint' if kind in ('displacement', 'sliding') else 'point'} named {name}",
            hint=f"choose from {', '.join(pool)}",
        )
    comp = parts[2] if len(parts) > 2 else None
    if comp not in (None, "x", "y") or (kind == "position" and comp is None) or (len(parts) > 3):
        raise InputError(
            f"{key}: a component is .x or .y" + (" (position needs one)" if kind == "position" else "")
        )


def _slide_message(key: str, kind: str, name: str, slides: Sequence[str], points: Sequence[str]) -> str:
    """Why a displacement or sliding key names nothing: it is a slider's, along its path."""
    what = "travel along its path" if kind == "displacement" else "speed along its path"
    where = f"{name} is not one" if name in points or not slides else f"there is no slider joint named {name}"
    if not slides:
        where = "the mechanism has no slider (prismatic or slot joint)"
    return f"{key}: {kind} is a slider's {what} (a prismatic or slot joint); {where}"


def _slide_hint(kind: str, name: str, slides: Sequence[str], points: Sequence[str]) -> str:
    """What to ask instead: a slider joint, or the point's path, position or speed."""
    instead = (
        f"--path {name} (its x and y over the sweep), position.{name}.x|y"
        if kind == "displacement"
        else f"velocity.{name} (its speed), velocity.{name}.x|y"
    )
    if name not in points:
        instead = "--path POINT, position.POINT.x|y" if kind == "displacement" else "velocity.POINT"
    sliders = f"; sliders: {', '.join(slides)}" if slides else ""
    return f"for a point use {instead}{sliders}"


def pick(arrays: dict[str, Any], names: dict[str, tuple[str, ...]], key: str) -> np.ndarray:
    """A quantity from arrays shaped (..., P, 2) / (..., L) / (..., S)."""
    parts = key.split(".")
    kind, name = parts[0], parts[1]
    comp = parts[2] if len(parts) > 2 else None
    if kind in ("angle", "omega", "alpha"):
        arr = arrays[{"angle": "link_angles", "omega": "omegas", "alpha": "alphas"}[kind]]
        return arr[..., names["links"].index(name)]
    if kind in ("displacement", "sliding"):
        return arrays[kind][..., names["slides"].index(name)]
    if kind == "included":  # the angle p–q–r at q, 0 to π
        pos = arrays["positions"]
        p, q, r = (pos[..., names["points"].index(n), :] for n in parts[1:4])
        u, w = p - q, r - q
        cross = u[..., 0] * w[..., 1] - u[..., 1] * w[..., 0]
        dot = u[..., 0] * w[..., 0] + u[..., 1] * w[..., 1]
        return np.abs(np.arctan2(cross, dot))
    arr = arrays[{"position": "positions", "velocity": "velocities", "acceleration": "accelerations"}[kind]]
    v = arr[..., names["points"].index(name), :]
    if comp == "x":
        return v[..., 0]
    if comp == "y":
        return v[..., 1]
    return np.hypot(v[..., 0], v[..., 1])


def default_quantities(
    points: Sequence[str], links: Sequence[str], slides: Sequence[str], lvl: int, drive: str
) -> list[str]:
    """What a sweep reports extremes of when none are asked: per level, the textbook quantities."""
    out = [f"displacement.{s}" for s in slides]
    out += [f"angle.{lk}" for lk in links if lk != drive]
    if lvl >= 1:
        out += [f"omega.{lk}" for lk in links if lk != drive]
        out += [f"velocity.{p}" for p in points]
        out += [f"sliding.{s}" for s in slides]
    if lvl >= 2:
        out += [f"alpha.{lk}" for lk in links if lk != drive]
        out += [f"acceleration.{p}" for p in points]
    return out


def contact_points_asked(mech: Any, quantities: Sequence[str] | None) -> tuple[str, ...]:
    """The points of higher pairs the quantities name, checked: ``<joint>@<link>`` (DESIGN § 1.2), a
    link's point at the contact, and a pair's own name (the follower's own point, which a programme
    cam already has among its located points)."""
    from mech.pairs import higher_pairs

    pairs = dict(higher_pairs(mech.joints))
    out: list[str] = []
    for key in quantities or ():
        parts = key.split(".")
        if len(parts) < 2 or parts[0] not in ("position", "velocity", "acceleration"):
            continue
        if parts[1] in pairs and parts[1] not in out:  # a profile cam's K: its follower's own point
            out.append(parts[1])
        if "@" not in parts[1]:
            continue
        joint, _, link = parts[1].partition("@")
        if joint not in pairs:
            raise InputError(
                f"{key}: {joint} is no higher pair (cam, contact, rolling or gear joint)",
                hint=f"higher pairs: {', '.join(pairs) or 'none'}",
            )
        if link not in pairs[joint]:
            raise InputError(
                f"{key}: {link} is not a link of {joint}",
                hint=" or ".join(f"{joint}@{lk}" for lk in pairs[joint]),
            )
        if parts[1] not in out:
            out.append(parts[1])
    return tuple(out)
