"""Everything the live page shows, as one JSON-able dict made from one sweep.

The page's script only draws: it never solves.  What it draws at step ``i`` is here:
the points' positions, the links' outlines, the sliders' blocks and slots, the velocity
and acceleration polygons (images and vectors, built by :mod:`mech.draw.polygon` at every
step), the I-centres, the transmission angle's joints, and the numbers of the table under
their answer keys (``omega.rocker``, ``velocity.C``…) in SI as ``mech velocity --json``
gives them.  Numbers are kept to 7 significant figures: a four-bar page is about 0.3 MB.
"""

from __future__ import annotations

import contextlib
import math
from typing import TYPE_CHECKING, Any

import numpy as np

from mech.draw.config import display_name, link_colours
from mech.draw.polygon import PolygonData, acceleration_polygon, velocity_polygon
from mech.errors import MechError
from mech.pairs import kind_of
from mech.units import unit_factor
from mech.view.frames import Vec, as_list, icentres, instant, link_members, own_step, round_sig

if TYPE_CHECKING:  # pragma: no cover
    from mech.kinematics.result import Kinematics
    from mech.kinematics.sweep import Sweep
    from mech.model import Mechanism

__all__ = ["contact_points", "page_data"]


def page_data(mech: Mechanism, drawn: Kinematics, sw: Sweep) -> dict[str, Any]:
    """The page's data: the sweep ``sw`` (its first step is the file's own instant) and its pictures.

    ``drawn`` is the solve at the file's own instant (carriers, joints, drives).
    """
    own = own_step(sw, drawn)
    ats = contact_points(mech, sw)
    kins = [instant(mech, drawn, sw, i, own, ats[i] if ats else None) for i in range(sw.angles.shape[0])]
    factor = unit_factor(mech.length_unit)[1]
    data: dict[str, Any] = {
        "title": mech.label,
        "unit": mech.length_unit,
        "factor": factor,
        "level": sw.level,
        "param": _parameter(mech, sw, factor),
        "own": own,
        "ok": [bool(x) for x in sw.assembled],
        "marks": _marks(sw, factor),
        "notes": list(sw.notes),
    }
    data.update(_configuration(mech, drawn, sw))
    data["polygons"] = [
        p for p in (_polygon(mech, kins, sw, "velocity"), _polygon(mech, kins, sw, "acceleration")) if p
    ]
    data["table"] = _table(mech, drawn, sw) + _contact_rows(mech, kins, sw)
    names, ic = icentres(mech, drawn, sw)
    data["icentres"] = {"names": names, "rows": as_list(ic, 6), "from": _first_pivot(mech, drawn, sw)}
    data["transmission"] = _transmission(mech, drawn, sw)
    return data


def _parameter(mech: Mechanism, sw: Sweep, factor: float) -> dict[str, Any]:
    """What the slider moves: a crank's angle (shown in degrees) or a slider's position (file unit)."""
    if sw.parameter == "angle":
        shown = [round_sig(_degrees_shown(a), 9) for a in sw.angles]
        turn = np.mod(sw.angles, 2 * math.pi)  # radians in [0, 2π), as the file's angle is read
        return {"kind": "angle", "si": as_list(turn, 10), "shown": shown, "drive": sw.drive, "unit": "°"}
    shown = [round_sig(a / factor, 9) for a in sw.angles]
    return {
        "kind": "position",
        "si": as_list(sw.angles, 10),
        "shown": shown,
        "drive": sw.drive,
        "unit": mech.length_unit,
    }


def _degrees_shown(a: float) -> float:
    """A crank angle in [0°, 360°) as the page shows it: a turn's end 1e-15° from 0° is 0°, not 7e-15°."""
    d = math.degrees(a) % 360.0
    return 0.0 if d < 1e-9 or d > 360.0 - 1e-9 else d


def _marks(sw: Sweep, factor: float) -> list[dict[str, Any]]:
    """Dead centres, toggles, change points and gaps, at the sweep parameter's values (SI)."""
    out: list[dict[str, Any]] = []
    for e in (*sw.dead_centres, *sw.toggles, *sw.change_points):
        out.append({"kind": e.kind, "at": e.angle, "text": f"{e.kind}: {e.subject}"})
    for g in sw.gaps:
        out.append({"kind": "gap", "at": g.start, "to": g.end, "text": f"not assembled: {g.what}"})
    return out


def _configuration(mech: Mechanism, drawn: Kinematics, sw: Sweep) -> dict[str, Any]:
    """Points and their positions at every step, links' outlines, pins, pivots, sliders, colours."""
    points = list(sw.points)
    index = {n: k for k, n in enumerate(points)}
    colours = link_colours(mech)
    members = link_members(mech, drawn)
    links = []
    for link in mech.moving_links:
        idx = [index[n] for n in members[link.name] if n in index]
        if len(idx) >= 2:
            links.append({"name": link.name, "colour": colours[link.name], "points": idx})
    pins, pivots, sliders = [], [], []
    for j in mech.joints:
        kind = kind_of(j)
        g = drawn.joints.get(j.name)
        if kind.role == "pin" and j.name in index:
            pins.append(index[j.name])
            if mech.ground in j.links:
                pivots.append(index[j.name])
        elif kind.role == "path" and g is not None and g.point in index and g.direction is not None:
            guide = j.links[1]
            if not kind.keeps_angle:
                pins.append(index[g.point])  # a pin in a slot
            sliders.append(
                {
                    "joint": j.name,
                    "point": index[g.point],
                    "dir": list(g.direction),
                    "guide": None if guide == mech.ground else sw.links.index(guide),
                    "block": kind.keeps_angle,
                    "colour": colours.get(j.links[0 if kind.keeps_angle else 1], "#1a1a1a"),
                }
            )
    named = {p.name for p in mech.points}
    return {
        "points": points,
        "labels": [display_name(n) for n in points],
        "named": [index[n] for n in points if n in named and index[n] not in pins],
        "xy": as_list(sw.positions),
        "links": links,
        "pins": pins,
        "pivots": pivots,
        "sliders": sliders,
        "angles": as_list(sw.link_angles, 8),
        "moving": list(sw.links),
        "origins": [_origin_index(drawn, sw, name) for name in sw.links],
    }


def _origin_index(drawn: Kinematics, sw: Sweep, link: str) -> int | None:
    for k, name in enumerate(sw.points):
        if link in drawn.carriers.get(name, ()):
            return k
    return None


def _polygon(mech: Mechanism, kins: list[Kinematics], sw: Sweep, kind: str) -> dict[str, Any] | None:
    """One polygon's structure (from the file's own instant) and its points at every step."""
    from mech.kinematics.quantities import LEVELS

    if LEVELS.index(sw.level) < LEVELS.index(kind):
        return None
    build = velocity_polygon if kind == "velocity" else acceleration_polygon
    first: PolygonData | None = None
    frames: list[PolygonData | None] = []
    for kin in kins:
        try:
            frames.append(build(mech, kin))
        except (MechError, ValueError, TypeError, KeyError):
            frames.append(None)  # a step not assembled
    first = next((f for f in frames if f is not None), None)
    if first is None:
        return None
    keys = ["o"] + [im.key for im in first.images] + sorted(first.construction)
    values = np.full((len(frames), len(keys), 2), np.nan)
    for i, f in enumerate(frames):
        if f is None:
            continue
        for k, key in enumerate(keys):
            with contextlib.suppress(KeyError):
                values[i, k] = f.at(key)
    colours = link_colours(mech)
    return {
        "kind": kind,
        "keys": keys,
        "labels": [first.pole] + [im.label for im in first.images] + [""] * len(first.construction),
        "values": as_list(values),
        "vectors": [
            {
                "name": v.name,
                "s": keys.index(v.start),
                "e": keys.index(v.end),
                "kind": v.kind,
                "colour": colours.get(v.link, "#444444") if v.link else "#444444",
            }
            for v in first.vectors
            if v.start in keys and v.end in keys
        ],
        "unit": "m/s" if kind == "velocity" else "m/s²",
    }


def _table(mech: Mechanism, drawn: Kinematics, sw: Sweep) -> list[dict[str, Any]]:
    """The numbers shown for each instant, keyed as answers are: ω, α of links, speeds of points."""
    rows: list[dict[str, Any]] = []
    for li, name in enumerate(sw.links):
        if sw.omegas is not None:
            rows.append(_row(f"omega.{name}", f"ω {name}", "rad/s", sw.omegas[:, li]))
        if sw.alphas is not None and sw.level == "acceleration":
            rows.append(_row(f"alpha.{name}", f"α {name}", "rad/s²", sw.alphas[:, li]))
    moving = [(k, n) for k, n in enumerate(sw.points) if mech.ground not in drawn.carriers.get(n, ())]
    own = _own_points(mech, drawn, sw)  # a cam's own point first, then the points the sweep carries
    speeds = [(name, vel) for name, (vel, _acc) in own.items() if vel is not None]
    accelerations = [(name, acc) for name, (_vel, acc) in own.items() if acc is not None]
    if sw.velocities is not None:
        speeds += [(name, (sw.velocities[:, k, 0], sw.velocities[:, k, 1])) for k, name in moving]
    if sw.accelerations is not None:
        accelerations += [
            (name, (sw.accelerations[:, k, 0], sw.accelerations[:, k, 1])) for k, name in moving
        ]
    rows += [_row(f"velocity.{n}", f"v {display_name(n)}", "m/s", np.hypot(*v)) for n, v in speeds]
    rows += [
        _row(f"acceleration.{n}", f"a {display_name(n)}", "m/s²", np.hypot(*a)) for n, a in accelerations
    ]
    return rows


def contact_points(mech: Mechanism, sw: Sweep) -> list[dict[str, Vec | None]] | None:
    """Where each higher pair's joint is at every step of ``sw``: the cam's contact, a gear's pitch point.

    The sweep carries the located points and each link's angle; from them each step's
    configuration is read back as the solver holds it (:func:`~mech.kinematics.result_fields.configuration`)
    and its joints' points found by the code every solve uses (:func:`~mech.kinematics.result_fields.joint_points`),
    so the page's ``velocity.K@cam`` is the one ``mech velocity --json`` gives at that instant.
    None when the mechanism has no higher pair, or its configuration cannot be read back.
    """
    names = [j.name for j in mech.joints if kind_of(j).higher or kind_of(j).rolls]
    if not names:
        return None
    from mech.kinematics.compiled import compiled
    from mech.kinematics.result_fields import configuration, joint_points

    try:
        comp = compiled(mech, None)
    except MechError:
        return None
    out: list[dict[str, Vec | None]] = []
    for i in range(sw.angles.shape[0]):
        q = None
        if sw.assembled[i]:
            positions = {
                n: (float(x), float(y)) for n, (x, y) in zip(sw.points, sw.positions[i], strict=True)
            }
            q = configuration(comp, positions, dict(zip(sw.links, sw.link_angles[i].tolist(), strict=True)))
        if q is None and sw.assembled[i]:
            return None  # a link without a point of its own in the sweep: its frame cannot be read back
        points = joint_points(comp, q) if q is not None else {}
        out.append({n: points.get(n) for n in names})
    return out


def _contact_rows(mech: Mechanism, kins: list[Kinematics], sw: Sweep) -> list[dict[str, Any]]:
    """Speed and acceleration of the moving links' points at each higher pair's joint, keyed as answers are.

    A rolling pair's points move alike (no slip): one ``velocity.<joint>``; otherwise, and for
    accelerations always, ``<joint>@<link>`` for each moving link of the pair (DESIGN § 1.2),
    as ``mech velocity --json`` and ``mech acceleration --json`` list them.
    """
    rows: list[dict[str, Any]] = []
    if sw.velocities is None:
        return rows
    for j in mech.joints:
        kind = kind_of(j)
        if not (kind.higher or kind.rolls):
            continue
        own = [f"{j.name}@{lk}" for lk in j.links if lk != mech.ground]
        # (key, the point asked of each step): a rolling pair's points agree, so either link's will do
        asks = [(f"velocity.{name}", name) for name in own]
        if kind.rolls:
            asks = [(f"velocity.{j.name}", own[0])] if own and j.name not in sw.points else []
        if sw.level == "acceleration" and sw.accelerations is not None:
            asks += [(f"acceleration.{name}", name) for name in own]
        for key, name in asks:
            what = key.partition(".")[0]
            values = np.array(
                [_magnitude(k, what, name, ok) for k, ok in zip(kins, sw.assembled, strict=True)]
            )
            if np.all(np.isnan(values)):
                continue
            symbol, unit = ("v", "m/s") if what == "velocity" else ("a", "m/s²")
            rows.append(_row(key, f"{symbol} {display_name(key.partition('.')[2])}", unit, values))
    return rows


def _magnitude(kin: Kinematics, what: str, name: str, ok: bool) -> float:
    """|v| or |a| of ``name`` in ``kin`` (NaN where the step is not assembled or has no such point)."""
    if not ok:
        return math.nan
    try:
        return math.hypot(*(kin.velocity(name) if what == "velocity" else kin.acceleration(name)))
    except MechError:
        return math.nan


def _row(key: str, label: str, unit: str, values: np.ndarray) -> dict[str, Any]:
    return {"key": key, "label": label, "unit": unit, "values": as_list(values)}


Pair = tuple[np.ndarray, np.ndarray]  # x and y components, one value per step


def _own_points(mech: Mechanism, drawn: Kinematics, sw: Sweep) -> dict[str, tuple[Pair | None, Pair | None]]:
    """A cam's (or contact's) own point that the sweep does not carry: its velocity and acceleration.

    DESIGN § 1.2: the joint's name is the follower's own point (the knife edge, the roller's
    centre), fixed in the follower, so it moves with the follower as a rigid body does:
    v_K = v_P + ω k×(K − P) and a_K = a_P + α k×(K − P) − ω²(K − P), from a point P of the
    follower that the sweep carries, K − P turned with the follower from the file's instant.
    """
    out: dict[str, tuple[Pair | None, Pair | None]] = {}
    if sw.velocities is None or sw.omegas is None:
        return out
    own = own_step(sw, drawn)
    for j in mech.joints:
        kind = kind_of(j)
        if not kind.higher or kind.rolls or j.name in sw.points or j.name not in drawn.positions:
            continue
        carriers = drawn.carriers.get(j.name, ())
        if len(carriers) != 1 or carriers[0] not in sw.links:
            continue
        link = carriers[0]
        anchor = next((k for k, n in enumerate(sw.points) if link in drawn.carriers.get(n, ())), None)
        if anchor is None:
            continue
        li = sw.links.index(link)
        turn = sw.link_angles[:, li] - sw.link_angles[own, li]
        dx0 = drawn.positions[j.name][0] - sw.positions[own, anchor, 0]
        dy0 = drawn.positions[j.name][1] - sw.positions[own, anchor, 1]
        c, s = np.cos(turn), np.sin(turn)
        rx, ry = c * dx0 - s * dy0, s * dx0 + c * dy0
        w = sw.omegas[:, li]
        vel = (sw.velocities[:, anchor, 0] - w * ry, sw.velocities[:, anchor, 1] + w * rx)
        acc = None
        if sw.accelerations is not None and sw.alphas is not None and sw.level == "acceleration":
            al = sw.alphas[:, li]
            acc = (
                sw.accelerations[:, anchor, 0] - al * ry - w * w * rx,
                sw.accelerations[:, anchor, 1] + al * rx - w * w * ry,
            )
        out[j.name] = (vel, acc)
    return out


def _first_pivot(mech: Mechanism, drawn: Kinematics, sw: Sweep) -> int | None:
    """The frame's first pivot (where far I-centres' distances are measured from)."""
    for j in mech.joints:
        if mech.ground in j.links and kind_of(j).role == "pin" and j.name in sw.points:
            return sw.points.index(j.name)
    return None


def _transmission(mech: Mechanism, drawn: Kinematics, sw: Sweep) -> list[int] | None:
    """The three joints of the transmission angle (coupler joint, joint, output pivot), or None."""
    from mech.errors import UnsupportedError
    from mech.properties.cycle import transmission_loop

    try:
        t = transmission_loop(mech, drawn.positions)
    except (UnsupportedError, MechError):
        return None
    names = (t.coupler_joint, t.joint, t.pivot)
    if not all(n in sw.points for n in names):
        return None
    return [sw.points.index(n) for n in names]
