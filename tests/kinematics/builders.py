"""Build :class:`~mech.model.Mechanism` objects in a few lines (no loader needed).

``build`` takes plain dicts shaped like the YAML file, already in SI (m, rad,
rad/s), so tests state their mechanisms the way the file format does.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

from mech.model import Drive, Joint, Length, Link, Mechanism, Path, Placement, Point, Ref
from mech.pairs import kind_of


def _ref(v: Any) -> Ref:
    return Ref(name=v) if isinstance(v, str) else Ref(xy=(float(v[0]), float(v[1])))


def _place(spec: dict[str, Any]) -> Placement:
    return Placement(
        at=tuple(spec["at"]) if "at" in spec else None,
        near=tuple(spec["near"]) if "near" in spec else None,
        origin=spec.get("from"),
        toward=spec.get("toward"),
        distance=spec.get("distance"),
        offset=tuple(spec["offset"]) if "offset" in spec else None,
    )


def build(
    links: list[str],
    joints: dict[str, dict[str, Any]],
    *,
    lengths: dict[str, float] | None = None,
    drive: dict[str, Any] | list[dict[str, Any]] | None = None,
    points: dict[str, dict[str, Any]] | None = None,
    ground: str = "frame",
    length_unit: str = "m",
    name: str = "test mechanism",
) -> Mechanism:
    """A mechanism from YAML-shaped dicts (SI values; ``lengths`` keys ``"A-B"``)."""
    jts = []
    for jname, spec in joints.items():
        path = None
        if "path" in spec:
            p = spec["path"]
            path = Path(
                through=_ref(p["through"]),
                angle=p.get("angle"),
                toward=_ref(p["toward"]) if "toward" in p else None,
            )
        jtype = spec.get("type", "revolute")
        own: dict[str, Any] = {"path": path, "point": spec.get("point")}
        own |= {k: spec[k] for k in ("radius", "normal", "pressure_angle", "internal") if k in spec}
        if "radii" in spec:
            own["radii"] = tuple(spec["radii"])
        kind_spec = kind_of(jtype).spec
        fields = {k: v for k, v in own.items() if v is not None and hasattr(kind_spec, k)}
        jts.append(
            Joint(
                name=jname,
                type=jtype,
                links=tuple(spec["links"]),
                place=_place(spec),
                spec=replace(kind_spec, **fields),
            )
        )
    lns = [Length(*k.split("-"), float(v)) for k, v in (lengths or {}).items()]
    drives = drive if isinstance(drive, list) else ([drive] if drive else [])
    drvs = [Drive(**d) for d in drives]
    pts = [Point(n, s["link"], _place(s)) for n, s in (points or {}).items()]
    lks = tuple(Link(n, i, is_ground=(n == ground)) for i, n in enumerate(links))
    return Mechanism(
        name=name,
        path="<test>",
        ground=ground,
        links=lks,
        joints=tuple(jts),
        points=tuple(pts),
        lengths=tuple(lns),
        drives=tuple(drvs),
        length_unit=length_unit,
    )


def four_bar(
    a: float = 0.04,
    b: float = 0.15,
    c: float = 0.08,
    d: float = 0.15,
    angle: float = math.radians(60),
    omega: float | None = -4 * math.pi,
    alpha: float | None = None,
    near: tuple[float, float] | None = None,
    origin: tuple[float, float] = (0.0, 0.0),
    unit: str = "m",
) -> Mechanism:
    """Crank AB = a, coupler BC = b, rocker CD = c, frame AD = d along +x from ``origin``."""
    ox, oy = origin
    c_spec: dict[str, Any] = {"links": ["coupler", "rocker"]}
    if near is not None:
        c_spec["near"] = near
    drive = {"link": "crank", "angle": angle, "omega": omega, "alpha": alpha}
    return build(
        ["frame", "crank", "coupler", "rocker"],
        {
            "A": {"links": ["frame", "crank"], "at": (ox, oy)},
            "B": {"links": ["crank", "coupler"]},
            "C": c_spec,
            "D": {"links": ["rocker", "frame"], "at": (ox + d, oy)},
        },
        lengths={"A-B": a, "B-C": b, "C-D": c},
        drive=drive,
        length_unit=unit,
    )


def slider_crank(
    r: float = 0.1,
    rod: float = 0.4,
    e: float = 0.0,
    angle: float = math.radians(45),
    omega: float | None = 20 * math.pi,
    alpha: float | None = None,
    points: dict | None = None,
) -> Mechanism:
    """Crank OA = r about O at the origin, rod AB of length rod, slider B on the line y = e along +x."""
    return build(
        ["frame", "crank", "rod", "slider"],
        {
            "O": {"links": ["frame", "crank"], "at": (0.0, 0.0)},
            "A": {"links": ["crank", "rod"]},
            "B": {"links": ["rod", "slider"]},
            "P": {
                "type": "prismatic",
                "links": ["slider", "frame"],
                "path": {"through": (0.0, e), "angle": 0.0},
            },
        },
        lengths={"O-A": r, "A-B": rod},
        drive={"link": "crank", "angle": angle, "omega": omega, "alpha": alpha},
        points=points,
    )


def slotted_lever(
    r: float = 0.12,
    d: float = 0.3,
    lever: float = 0.6,
    angle: float = math.radians(60),
    omega: float | None = 20 * math.pi,
    alpha: float | None = None,
) -> Mechanism:
    """Crank O2A = r about O2 at the origin; a block at A slides on lever O1B (O1 at (0, −d)).

    The lesson's crank and slotted lever (Example 3.1: 600 rpm, O2A = 12 cm, O1B = 60 cm):
    prismatic joint on a moving guide, path through O1 toward B.
    """
    return build(
        ["frame", "crank", "block", "lever"],
        {
            "O2": {"links": ["frame", "crank"], "at": (0.0, 0.0)},
            "A": {"links": ["crank", "block"]},
            "S": {"type": "prismatic", "links": ["block", "lever"], "path": {"through": "O1", "toward": "B"}},
            "O1": {"links": ["lever", "frame"], "at": (0.0, -d)},
        },
        lengths={"O2-A": r, "O1-B": lever},
        drive={"link": "crank", "angle": angle, "omega": omega, "alpha": alpha},
        points={"B": {"link": "lever"}},
    )
