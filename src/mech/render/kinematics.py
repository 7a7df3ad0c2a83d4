"""Tables and JSON for ``mech position``, ``mech velocity`` and ``mech acceleration``.

Grouped as a student works the problem: links (θ, ω, α), points (position,
velocity, acceleration), relative motion along each link (the velocity
polygon's **ab**, the acceleration polygon's normal and tangential parts),
sliders and slots (sliding velocity, Coriolis), rubbing at pins, then notes.
Both the table and the JSON are made from the same rows, so they cannot
disagree.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

from mech.errors import InputError
from mech.kinematics import Kinematics
from mech.options import OutputUnits
from mech.units import format_unit, to_unit, unit_factor

if TYPE_CHECKING:  # pragma: no cover
    from mech.render.console import ReportConsole

__all__ = ["kinematics_json", "kinematics_table"]

_LEVELS = ("position", "velocity", "acceleration")


def _at_least(kin: Kinematics, level: str) -> bool:
    return _LEVELS.index(kin.level) >= _LEVELS.index(level)


def _sense(w: float | None) -> str | None:
    if w is None:
        return None
    return "ccw" if w > 0 else "cw" if w < 0 else None


def _dir(v: tuple[float, float]) -> float | None:
    """Direction in degrees [0, 360), or None for a zero vector."""
    if v[0] == 0.0 and v[1] == 0.0:
        return None
    d = math.degrees(math.atan2(v[1], v[0])) % 360.0
    return 0.0 if d >= 360.0 else d  # -1e-15° would round to 360.0


def _point_rows(kin: Kinematics) -> Iterator[tuple[str, str | None]]:
    """(point, link) for every reported point; a higher pair's points at the contact as ``K@link``.

    A contact point whose links' points move differently there is listed once per link,
    ``K@cam`` and ``K@follower`` (DESIGN § 1.2); a higher pair whose name is the follower's
    own point (a programme cam's roller centre) lists it, then each link's point at the contact.
    """
    moving = _at_least(kin, "velocity")
    for name in kin.positions:
        joint = kin.joints.get(name)
        if not moving:
            yield name, None
            yield from _contact_rows(kin, name)
            continue
        try:
            kin.velocity(name)
            if _at_least(kin, "acceleration"):
                kin.acceleration(name)  # a rolling contact: one velocity, two accelerations
            yield name, None
        except InputError:
            for link in joint.links if joint else ():
                yield f"{name}@{link}", link
            continue
        yield from _contact_rows(kin, name)


def _contact_rows(kin: Kinematics, name: str) -> Iterator[tuple[str, str | None]]:
    """``K@cam``, ``K@follower`` after a higher pair's own point ``K`` when it is not where they touch."""
    from mech.pairs import kind_of

    joint = kin.joints.get(name)
    if joint is None or not kin.carriers.get(name) or joint.at is None or not kind_of(joint.type).higher:
        return
    if math.dist(joint.at, kin.positions[name]) > 1e-12 * max(kin.size, 1e-300):
        for link in joint.links:  # the follower's own point (a roller's centre) is not where it touches
            yield f"{name}@{link}", link


def _higher(kin: Kinematics, name: str) -> bool:
    """Whether ``name`` is a higher pair's joint (its name a follower's own point)."""
    from mech.pairs import kind_of

    joint = kin.joints.get(name)
    return joint is not None and kind_of(joint.type).higher


def _link_pairs(kin: Kinematics) -> Iterator[tuple[str, str, str]]:
    """(link, from point, to point): each moving link's first point to each of its others."""
    on_link: dict[str, list[str]] = {}
    for name, carriers in kin.carriers.items():
        if name in kin.positions:
            for lk in carriers:
                on_link.setdefault(lk, []).append(name)
    tol = 1e-12 * max(kin.size, 1e-300)
    for lk, state in kin.links.items():
        if lk == kin.ground:
            continue
        names = on_link.get(lk, [])
        # a cam joint standing for the follower's own point where a named point already is
        # (a roller's centre C): the same point twice, no vector between them
        names = [
            n
            for n in names
            if not _higher(kin, n)
            or not any(m != n and math.dist(kin.positions[m], kin.positions[n]) <= tol for m in names)
        ]
        # start from the link's origin point (its ground pivot where it has one)
        names.sort(key=lambda n: math.dist(kin.positions[n], state.origin) > 1e-12 * max(kin.size, 1e-300))
        for other in names[1:]:
            yield lk, names[0], other


class _Noise:
    """Rounding noise shown as the zero it is, each quantity judged against its own scale.

    A rod exactly along +x comes out at 3e-15° or 359.99999999999997°, a pivot's
    velocity at 4e-18 m/s with a direction of 249°; a student reads those as
    numbers.  But a 1e-12 m crank on 1 m links really moves its pin at
    6.3e-12 m/s, and that must print.  So:

    - ω and α come from the solver already judged, each against its own error
      bound (``solve._snap_to_error``): they are shown as they are;
    - a point's velocity is v_o + ω × r of its link, and is noise below 1e-12 of
      |v_o| + |ω|·|r| (the terms it is summed from); an acceleration likewise
      against |a_o| + (|α| + ω²)·|r|; a relative or sliding velocity against the
      scales of the two points it is the difference of;
    - positions and angles against the mechanism's size: the position solve's
      stated accuracy is 1e-12 of the size (Newton's tolerance), so a
      coordinate nearer zero than that is zero to the accuracy it is known to.
    """

    RELATIVE = 1e-12

    def __init__(self, kin: Kinematics, has_v: bool, has_a: bool) -> None:
        self.kin, self.has_v, self.has_a = kin, has_v, has_a
        self.size = kin.size

    def _links_at(self, name: str, link: str | None) -> tuple[str, ...]:
        if link is not None:
            return (link,)
        carriers = tuple(self.kin.carriers.get(name, ()))
        joint = self.kin.joints.get(name)
        return carriers or (joint.links if joint is not None else ())

    def v_scale(self, links: tuple[str, ...], p: tuple[float, float]) -> float:
        """|v_o| + |ω|·|r| over ``links``: the sizes of the terms a velocity at ``p`` is summed from."""
        out = 0.0
        for lk in links:
            s = self.kin.links[lk]
            r = math.dist(p, s.origin)
            out = max(out, math.hypot(*(s.velocity or (0.0, 0.0))) + abs(s.omega or 0.0) * r)
        return out

    def a_scale(self, links: tuple[str, ...], p: tuple[float, float]) -> float:
        """|a_o| + (|α| + ω²)·|r| over ``links``."""
        out = 0.0
        for lk in links:
            s = self.kin.links[lk]
            r = math.dist(p, s.origin)
            w, al = s.omega or 0.0, s.alpha or 0.0
            out = max(out, math.hypot(*(s.acceleration or (0.0, 0.0))) + (abs(al) + w * w) * r)
        return out

    def point_v_scale(self, name: str, link: str | None) -> float:
        return self.v_scale(self._links_at(name, link), self.kin.position(name))

    def point_a_scale(self, name: str, link: str | None) -> float:
        return self.a_scale(self._links_at(name, link), self.kin.position(name))

    def angle(self, theta: float) -> float:
        return 0.0 if abs(math.remainder(theta, 2 * math.pi)) < self.RELATIVE else theta

    @staticmethod
    def omega(w: float | None) -> float | None:
        return w

    @staticmethod
    def alpha(a: float | None) -> float | None:
        return a

    def scalar(self, v: float, scale: float) -> float:
        return 0.0 if abs(v) <= self.RELATIVE * scale else v

    @classmethod
    def vector(cls, v: tuple[float, float], scale: float) -> tuple[float, float]:
        floor = cls.RELATIVE * scale
        return (0.0 if abs(v[0]) <= floor else v[0], 0.0 if abs(v[1]) <= floor else v[1])

    def position(self, p: tuple[float, float]) -> tuple[float, float]:
        return self.vector(p, self.size)

    def joint_scales(self, name: str) -> tuple[float, float]:
        """(velocity, acceleration) scales at a sliding joint's point, over its two links."""
        j = self.kin.joints[name]
        p = j.at if j.at is not None else (0.0, 0.0)
        v = sum(self.v_scale((lk,), p) for lk in j.links)
        a = sum(self.a_scale((lk,), p) for lk in j.links) if self.has_a else 0.0
        w = abs(self.kin.links[j.links[-1]].omega or 0.0)
        return v, a + 2.0 * w * v


def _vec(v: tuple[float, float] | None, unit: str) -> list[float] | None:
    """A vector in ``unit`` as a JSON list, or None."""
    return None if v is None else [to_unit(v[0], unit), to_unit(v[1], unit)]


def _num(x: float | None, unit: str) -> float | None:
    """A number in ``unit``, or None."""
    return None if x is None else to_unit(x, unit)


def _as_read(value: float | None, unit: str) -> float | None:
    """``value`` (SI) in ``unit`` as a file would write it: the shortest decimal that the loader's
    conversion (× the unit's factor) turns back into exactly ``value``.

    Dividing by the factor does not always undo the loader's product: ``angle: 60`` is read as
    60·(π/180) = 1.0471975511965976 rad, which divided by π/180 is 59.99999999999999.  The number
    returned here is the same angle to the last bit (read again, it gives ``value``), so a drive
    reports the angle its file gave.

    >>> _as_read(60 * (math.pi / 180), "deg"), to_unit(60 * (math.pi / 180), "deg")
    (60.0, 59.99999999999999)
    """
    if value is None:
        return None
    plain = to_unit(value, unit)
    factor = unit_factor(unit)[1]
    for digits in range(1, 18):
        shortest = float(f"{plain:.{digits}g}")
        if shortest * factor == value:
            return shortest
    return plain


def _drive_frames(kin: Kinematics, d: Any, units: OutputUnits) -> dict[str, Any]:
    """A turning drive both ways: ``absolute`` (from the ground) and ``relative`` (to a moving link).

    The drive's own values are in its convention (absolute unless it says
    ``relative_to``, DESIGN § 1.1), and the frame of that convention repeats them
    as given (the inputs, known at every level: α is the file's, 0 by default,
    where the solve stopped at velocities); the other convention is derived from
    the solved links: θ_b = φ + θ_a, ω_b from the solve, ω_b − ω_a … (null at a
    level not solved).  The reference link is ``relative_to``, else the moving link
    the ``about`` pivot joins the driven link to (the pair a student measures at a
    joint), else there is none (``relative`` is null).
    """
    W, AL, ANG = units.angular_velocity, units.angular_acceleration, units.angle
    ref = d.relative_to
    if ref is None and d.about is not None and d.about in kin.joints:
        others = [lk for lk in kin.joints[d.about].links if lk != d.link]
        ref = others[0] if len(others) == 1 and others[0] != kin.ground else None
    mine = kin.links.get(d.link)
    other = kin.links.get(ref) if ref is not None else None

    def diff(x: float | None, y: float | None) -> float | None:
        return None if x is None or y is None else x - y

    def frame(angle: float | None, omega: float | None, alpha: float | None) -> dict[str, Any]:
        return {"angle": _as_read(angle, ANG), "omega": _num(omega, W), "alpha": _num(alpha, AL)}

    theta_a = other.angle if other is not None else 0.0
    own = frame(d.angle, d.omega, d.alpha)
    relative: dict[str, Any] | None = None
    if d.relative_to is not None:  # the drive gives θ_b − θ_a …: θ_b, ω_b, α_b are the solve's
        angle_abs = None if d.angle is None else math.remainder(d.angle + theta_a, 2 * math.pi)
        absolute = frame(angle_abs, mine.omega if mine else None, mine.alpha if mine else None)
        relative = {"to": ref, **own}
    else:
        absolute = own
        if other is not None:
            angle_rel = None if d.angle is None else math.remainder(d.angle - theta_a, 2 * math.pi)
            relative = {"to": ref, **frame(angle_rel, diff(d.omega, other.omega), diff(d.alpha, other.alpha))}
    return {"absolute": absolute, "relative": relative}


def kinematics_json(kin: Kinematics, *, units: OutputUnits) -> dict[str, Any]:
    """The solve as a plain JSON-able dict, numbers in ``units``.

    Structure (keys present at every level; values of levels not solved are null)::

        {
          "mechanism": str, "level": "position" | "velocity" | "acceleration",
          "units": {"length", "velocity", "acceleration", "angle",
                    "angular_velocity", "angular_acceleration"},   # unit names used below
          "size": float,                                  # largest joint distance [length]
          "drives": [{"link" | "joint": str, "angle": float [angle] | null,
                      "omega": float [angular_velocity, ccw +] | null, "sense": "cw" | "ccw" | null,
                      "alpha": float | null, "speed": float [velocity] | null,
                      # turning drives only: the values above are in the drive's own convention
                      "relative_to": str | null,
                      "absolute": {"angle", "omega", "alpha"},               # from the ground
                      "relative": {"to": str, "angle", "omega", "alpha"} | null}],
          "links": {name: {"origin": [x, y], "angle": float, "omega": float | null,
                           "sense": "cw" | "ccw" | null, "alpha": float | null}},
          "points": [{"point": str, "link": str | null,   # link: the contact point's link
                      "position": [x, y], "velocity": [vx, vy] | null, "speed": float | null,
                      "direction": float [angle] | null,
                      "acceleration": [ax, ay] | null, "acceleration_magnitude": float | null}],
          "relative": [{"link": str, "from": A, "to": B, "label": "ab",   # v_B − v_A
                        "velocity": [vx, vy], "speed": float,
                        "normal": float | null, "tangential": float | null}],  # ω²·AB, α·AB
          "sliders": [{"joint": str, "type": str, "slider": str, "guide": str,
                       "sliding": float [velocity, signed along the path],
                       "sliding_acceleration": float [acceleration, along the path] | null,
                       "coriolis": [ax, ay] | null, "coriolis_magnitude": float | null}],
          "rubbing": [{"joint": str, "radius": float [length], "rubbing": float [velocity]}],
          "mobility": {"kutzbach": int, "numeric": int | null, "redundant": int,
                       "condition": float, "free": [str], "locked": [str]},
          "notes": [str]
        }
    """
    L, V, A = units.length, units.velocity, units.acceleration
    has_v, has_a = _at_least(kin, "velocity"), _at_least(kin, "acceleration")
    quiet = _Noise(kin, has_v, has_a)
    sliders, rubbing = _joints_json(kin, quiet, units) if has_v else ([], [])
    m = kin.mobility
    return {
        "mechanism": kin.mechanism,
        "level": kin.level,
        "units": {
            "length": L,
            "velocity": V,
            "acceleration": A,
            "angle": units.angle,
            "angular_velocity": units.angular_velocity,
            "angular_acceleration": units.angular_acceleration,
        },
        "size": to_unit(kin.size, L),
        "drives": _drives_json(kin, units),
        "links": _links_json(kin, quiet, units),
        "points": _points_json(kin, quiet, units),
        "relative": _relative_json(kin, quiet, units) if has_v else [],
        "sliders": sliders,
        "rubbing": rubbing,
        "mobility": {
            "kutzbach": m.kutzbach,
            "numeric": m.numeric,
            "redundant": m.redundant,
            "condition": m.condition,
            "free": list(m.free),
            "locked": list(m.locked),
        },
        "notes": list(kin.notes),
    }


def _drives_json(kin: Kinematics, units: OutputUnits) -> list[dict[str, Any]]:
    """Each drive in its own convention; a turning drive also absolute and relative (:func:`_drive_frames`)."""
    drives = []
    for d in kin.drives:
        entry: dict[str, Any] = {"link": d.link} if d.link is not None else {"joint": d.joint}
        entry.update(
            angle=_as_read(d.angle, units.angle) if d.link is not None else None,
            omega=_num(d.omega, units.angular_velocity),
            sense=_sense(d.omega),
            alpha=_num(d.alpha, units.angular_acceleration),
            speed=_num(d.speed, units.velocity),
        )
        if d.link is not None:
            entry["relative_to"] = d.relative_to
            entry.update(_drive_frames(kin, d, units))
        drives.append(entry)
    return drives


def _links_json(kin: Kinematics, quiet: _Noise, units: OutputUnits) -> dict[str, dict[str, Any]]:
    """Every link (ground too): its origin, angle, ω and sense, α."""
    return {
        name: {
            "origin": _vec(quiet.position(s.origin), units.length),
            "angle": to_unit(quiet.angle(s.angle), units.angle),
            "omega": _num(quiet.omega(s.omega), units.angular_velocity),
            "sense": _sense(quiet.omega(s.omega)),
            "alpha": _num(quiet.alpha(s.alpha), units.angular_acceleration),
        }
        for name, s in kin.links.items()
    }


def _points_json(kin: Kinematics, quiet: _Noise, units: OutputUnits) -> list[dict[str, Any]]:
    """Every point (a contact point once per link where they differ): position, velocity, acceleration."""
    V, A = units.velocity, units.acceleration
    has_v, has_a = quiet.has_v, quiet.has_a
    points = []
    for name, link in _point_rows(kin):
        v = quiet.vector(kin.velocity(name, link), quiet.point_v_scale(name, link)) if has_v else None
        a = quiet.vector(kin.acceleration(name, link), quiet.point_a_scale(name, link)) if has_a else None
        points.append(
            {
                "point": name,
                "link": link,
                "position": _vec(quiet.position(kin.position(name)), units.length),
                "velocity": _vec(v, V),
                "speed": _num(math.hypot(*v), V) if v is not None else None,
                "direction": _dir(v) if v is not None else None,
                "acceleration": _vec(a, A),
                "acceleration_magnitude": _num(math.hypot(*a), A) if a is not None else None,
            }
        )
    return points


def _relative_json(kin: Kinematics, quiet: _Noise, units: OutputUnits) -> list[dict[str, Any]]:
    """Relative velocity along each moving link (the polygon's ab), with ω²·AB and α·AB."""
    V, A = units.velocity, units.acceleration
    has_a = quiet.has_a
    relative = []
    for lk, p, q in _link_pairs(kin):
        state = kin.links[lk]
        v = quiet.vector(
            kin.relative_velocity(q, p, link_a=lk, link_b=lk),
            quiet.point_v_scale(p, lk) + quiet.point_v_scale(q, lk),
        )
        r = math.dist(kin.positions[p], kin.positions[q])
        relative.append(
            {
                "link": lk,
                "from": p,
                "to": q,
                "label": f"{p}{q}".lower(),
                "velocity": _vec(v, V),
                "speed": to_unit(math.hypot(*v), V),
                "normal": to_unit((quiet.omega(state.omega) or 0.0) ** 2 * r, A) if has_a else None,
                "tangential": to_unit(abs(quiet.alpha(state.alpha) or 0.0) * r, A) if has_a else None,
            }
        )
    return relative


def _joints_json(
    kin: Kinematics, quiet: _Noise, units: OutputUnits
) -> tuple[list[dict[str, Any]], list[dict[str, Any]]]:
    """(sliders, rubbing): sliding velocity, acceleration and Coriolis at each slider and slot; rubbing at pins."""
    V, A = units.velocity, units.acceleration
    has_a = quiet.has_a
    sliders, rubbing = [], []
    from mech.pairs import kind_of

    for name, j in kin.joints.items():
        role = kind_of(j.type).role
        if role == "path":
            v_sc, a_sc = quiet.joint_scales(name)
            cor = quiet.vector(kin.coriolis(name), a_sc) if has_a else None
            sliders.append(
                {
                    "joint": name,
                    "type": j.type,
                    "slider": j.links[0],
                    "guide": j.links[1],
                    "sliding": to_unit(quiet.scalar(kin.sliding(name), v_sc), V),
                    "sliding_acceleration": _num(
                        quiet.scalar(kin.sliding_acceleration(name), a_sc) if has_a else None, A
                    ),
                    "coriolis": _vec(cor, A),
                    "coriolis_magnitude": _num(math.hypot(*cor), A) if cor is not None else None,
                }
            )
        elif role == "pin" and j.radius is not None:
            rubbing.append(
                {
                    "joint": name,
                    "radius": to_unit(j.radius, units.length),
                    "rubbing": to_unit(kin.rubbing(name), V),
                }
            )
    return sliders, rubbing


def _g(x: float | None, digits: int = 5) -> str:
    """A number for a table: ``digits`` significant figures, ``—`` for none, no ``-0``."""
    if x is None:
        return "—"
    if x == 0 or abs(x) < 1e-300:
        return "0"
    mag = abs(x)
    if 1e-3 <= mag < 1e7:  # fixed notation: 473740, 0.0452, 9.2042
        decimals = max(0, digits - 1 - math.floor(math.log10(mag)))
        s = f"{x:.{decimals}f}"
    else:
        s = f"{x:.{digits}g}"
    return "0" if s.lstrip("-").strip("0.") == "" else s


def _col(table: Any, header: str, justify: str = "left") -> None:
    """A column whose numbers fold onto a second line rather than being cut to ``…``."""
    table.add_column(header, justify=justify, overflow="fold")


def _point_label(p: dict[str, Any]) -> str:
    """``C``, ``K@cam`` (a link's point at a contact), or ``C (on coupler)`` for a coincident point."""
    return p["point"] if p["link"] is None or "@" in p["point"] else f"{p['point']} (on {p['link']})"


_LEVEL_TITLES = {"position": "positions", "velocity": "velocities", "acceleration": "accelerations"}


def kinematics_table(kin: Kinematics, console: ReportConsole, *, units: OutputUnits) -> None:
    """Print the solve as rich tables on ``console`` (numbers in ``units``)."""
    from mech.render.console import table_box
    from mech.render.table import Table, Text

    box = table_box(console)
    data = kinematics_json(kin, units=units)
    u = {k: format_unit(v) for k, v in data["units"].items()}

    def titled(title: str) -> Any:
        return Table(title=title, box=box, title_justify="left")

    console.print(Text(kin.mechanism, style="bold") + Text(f" — {_LEVEL_TITLES[kin.level]}"))
    for d in data["drives"]:
        console.print(_drive_line(d, u))
    has_v, has_a = _at_least(kin, "velocity"), _at_least(kin, "acceleration")
    console.print(_links_table(titled("Links"), data, u, kin.ground, has_v, has_a))
    # Positions with velocities, then accelerations in a table of their own: one table with
    # both is wider than a terminal.
    console.print(_points_table(titled("Points"), data, u, has_v))
    if has_a:
        console.print(_accelerations_table(titled("Point accelerations"), data, u))
    if data["relative"]:
        title = "Relative motion along links (velocity polygon)"
        console.print(_relative_table(titled(title), data, u, has_a))
    if data["sliders"]:
        console.print(_sliders_table(titled("Sliders and slots"), data, u, has_a))
    if data["rubbing"]:
        t = titled("Rubbing at pins")
        _col(t, "joint")
        _col(t, f"radius ({u['length']})", justify="right")
        _col(t, f"rubbing ({u['velocity']})", justify="right")
        for r in data["rubbing"]:
            t.add_row(r["joint"], _g(r["radius"]), _g(r["rubbing"]))
        console.print(t)
    for note in data["notes"]:
        console.print(f"note: {note}", highlight=False)


def _drive_line(d: dict[str, Any], u: dict[str, str]) -> str:
    """``drive crank, at 60 deg, ω = 12.566 rad/s cw``, with the other convention in brackets."""
    if "link" not in d:
        parts = [f"drive {d['joint']}"]
        if d["speed"] is not None:
            parts.append(f"v = {_g(d['speed'])} {u['velocity']}")
        return ", ".join(parts)
    parts = [f"drive {d['link']}"]
    if d["angle"] is not None:
        parts.append(f"at {_g(d['angle'])} {u['angle']}")
    if d["omega"] is not None:
        parts.append(f"ω = {_g(abs(d['omega']))} {u['angular_velocity']} {d['sense'] or ''}".rstrip())
    if d["alpha"]:
        parts.append(f"α = {_g(d['alpha'])} {u['angular_acceleration']}")
    other = d["relative"] if d["relative_to"] is None else d["absolute"]
    if other is not None:
        what = f"relative to {other['to']}" if d["relative_to"] is None else "absolute"
        if d["relative_to"] is not None:
            parts[0] += f" relative to {d['relative_to']}"
        extra = [f"{_g(other['angle'])} {u['angle']}"] if other["angle"] is not None else []
        if other["omega"] is not None:
            w = other["omega"]
            extra.append(f"ω = {_g(abs(w))} {u['angular_velocity']} {_sense(w) or ''}".rstrip())
        if other["alpha"] is not None and d["alpha"]:
            extra.append(f"α = {_g(other['alpha'])} {u['angular_acceleration']}")
        parts[-1] += f" ({what}: {', '.join(extra)})"
    return ", ".join(parts)


def _links_table(
    t: Any, data: dict[str, Any], u: dict[str, str], ground: str, has_v: bool, has_a: bool
) -> Any:
    """θ of each moving link, with ω and its sense, α, as far as solved."""
    _col(t, "link")
    _col(t, f"θ ({u['angle']})", justify="right")
    if has_v:
        _col(t, f"ω ({u['angular_velocity']})", justify="right")
        _col(t, "sense")
    if has_a:
        _col(t, f"α ({u['angular_acceleration']})", justify="right")
    for name, s in data["links"].items():
        if name == ground:
            continue
        row = [name, _g(s["angle"])]
        if has_v:
            row += [_g(abs(s["omega"])), s["sense"] or "—"]
        if has_a:
            row += [_g(s["alpha"])]
        t.add_row(*row)
    return t


def _points_table(t: Any, data: dict[str, Any], u: dict[str, str], has_v: bool) -> Any:
    """Each point's position, with its velocity (magnitude, direction, components) once solved."""
    _col(t, "point")
    _col(t, f"x ({u['length']})", justify="right")
    _col(t, f"y ({u['length']})", justify="right")
    if has_v:
        _vector_columns(t, "v", u["velocity"], u["angle"])
    for p in data["points"]:
        row = [_point_label(p), _g(p["position"][0]), _g(p["position"][1])]
        if has_v:
            row += _vector_cells(p["speed"], p["direction"], p["velocity"])
        t.add_row(*row)
    return t


def _accelerations_table(t: Any, data: dict[str, Any], u: dict[str, str]) -> Any:
    """Each point's acceleration: magnitude, direction, components."""
    _col(t, "point")
    _vector_columns(t, "a", u["acceleration"], u["angle"])
    for p in data["points"]:
        a = p["acceleration"]
        t.add_row(_point_label(p), *_vector_cells(p["acceleration_magnitude"], _dir(tuple(a)), a))
    return t


def _vector_columns(t: Any, symbol: str, unit: str, angle: str) -> None:
    """A vector's four columns: ``|v|``, its direction, ``vx`` and ``vy``."""
    for col in (f"|{symbol}| ({unit})", f"dir ({angle})", f"{symbol}x ({unit})", f"{symbol}y ({unit})"):
        _col(t, col, justify="right")


def _vector_cells(magnitude: float | None, direction: float | None, xy: list[float]) -> list[str]:
    """The cells under :func:`_vector_columns` (the direction to four figures)."""
    return [_g(magnitude), _g(direction, 4), _g(xy[0]), _g(xy[1])]


def _relative_table(t: Any, data: dict[str, Any], u: dict[str, str], has_a: bool) -> Any:
    """The velocity polygon's vectors along each link, with the normal and tangential parts."""
    for col in ("link", "vector", f"|v| ({u['velocity']})", f"dir ({u['angle']})"):
        _col(t, col, justify="left" if col in ("link", "vector") else "right")
    if has_a:
        _col(t, f"normal ω²r ({u['acceleration']})", justify="right")
        _col(t, f"tangential αr ({u['acceleration']})", justify="right")
    for r in data["relative"]:
        row = [
            r["link"],
            f"{r['label']} (v{r['to']}{r['from']})",
            _g(r["speed"]),
            _g(_dir(tuple(r["velocity"])), 4),
        ]
        if has_a:
            row += [_g(r["normal"]), _g(r["tangential"])]
        t.add_row(*row)
    return t


def _sliders_table(t: Any, data: dict[str, Any], u: dict[str, str], has_a: bool) -> Any:
    """Sliding velocity at each slider and slot; its acceleration and the Coriolis term once solved."""
    for col in ("joint", "slider on guide", f"sliding ({u['velocity']})"):
        _col(t, col, justify="right" if "sliding" in col else "left")
    if has_a:
        _col(t, f"sliding acc. ({u['acceleration']})", justify="right")
        _col(t, f"Coriolis 2ωv ({u['acceleration']})", justify="right")
        _col(t, f"dir ({u['angle']})", justify="right")
    for s in data["sliders"]:
        row = [s["joint"], f"{s['slider']} on {s['guide']}", _g(s["sliding"])]
        if has_a:
            row += [
                _g(s["sliding_acceleration"]),
                _g(s["coriolis_magnitude"]),
                _g(_dir(tuple(s["coriolis"])), 4),
            ]
        t.add_row(*row)
    return t
