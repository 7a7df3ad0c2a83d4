"""Higher pairs that move: the contact rows of two profiles, and where they touch.

Each link of a ``cam``, ``contact`` or ``rolling`` joint may carry a curve
(:mod:`mech.pairs.specs`): a circle, a straight line, a point (knife edge).
Two such curves in contact give holonomic rows in the shapes of
:mod:`mech.pairs.rows`, so the pair moves, sweeps and accelerates like
any lower pair, and the curvature terms come with the row shape:

==================  =========================================================  ===========
profiles            contact condition                                          row
==================  =========================================================  ===========
circle – line       the centre stays ±r from the line (a flat face, the        OnLine, c = ±r
                    ground under a wheel)
point – line        the knife edge stays on the line                           OnLine, c = 0
circle – circle     centres r₁ + r₂ apart (|r₁ − r₂| inside): an eccentric     Distance
                    cam and a roller
point – circle      the knife edge stays r from the centre                     Distance
==================  =========================================================  ===========

A circle–line pair gives exactly the curvature term of a point on a line (the
centre of curvature moves rigidly with the circle), and a circle–circle pair
that of two points at a fixed distance: these are the classical equivalent
linkages (Uicker, Pennock & Shigley, *Theory of Machines and Mechanisms*,
§ 3.10), exact for all positions because the radii of curvature are constant.

``rolling`` adds no slip (a ``gear`` with profiles only that: its teeth, not a second
contact row, keep a rack's pitch line on the pinion's pitch circle, h = 1): for a circle on a line, ``u·(r_c − r_T) + s·r·(θ_c − θ_line)
= const`` (the arc rolled equals the distance travelled; ``s`` the side of the
line the circle is on).  Two rolling circles whose centres are pinned to one
carrier give the gear-pair row instead (their centre distance is already fixed).

``radii: [r1, r2]`` is shorthand for circles about each link's pivot; ``null`` is
a straight line tangent to the other circle where the pair is drawn (at ``at``,
or under the circle's centre when the joint has no ``at``).

A closed ``curve`` (a periodic cubic spline through its points, see
:mod:`mech.pairs.curves`) moves against a point, a circle or a line.

Without profiles a higher pair describes the drawn instant only: its contact
point (``at``) and common normal give one velocity-level row
(:func:`instant_normal`), or two for rolling (:func:`instant_rolling`).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from mech._records import dataclass
from mech.errors import Problem
from mech.model import Joint, Ref
from mech.pairs.rows import Angle, Coincide, Distance, OnLine, RowBuilder
from mech.specs import Circle, Curve, Knife, Line, Profile

__all__ = ["drawn_profiles", "instant_normal", "instant_point", "instant_rolling", "moving_contact"]

#: Largest gap (relative to the mechanism's size) between profiles drawn in contact.
TOUCH = 1e-6


@dataclass(frozen=True, slots=True)
class _Geo:
    """A profile as drawn, scaled: ``p`` the centre, point or line's through-point; ``u`` a line's direction."""

    link: str
    kind: str  # circle | line | point
    p: np.ndarray
    r: float = 0.0
    u: np.ndarray | None = None
    pts: np.ndarray | None = None  # a curve's points, scaled global


def drawn_profiles(
    b: RowBuilder, j: Joint, radii: tuple[float | None, float | None] | None = None
) -> dict[str, Profile]:
    """The profiles of ``j`` keyed by link: given, or ``radii`` about each link's pivot.

    ``radii`` (a rolling pair's shorthand) are circles about each link's only pin;
    ``None`` for one of them is a straight line tangent to the other circle where
    the pair is drawn (at ``at``, or under the circle's centre when it has no ``at``).
    """
    if j.profiles:
        return dict(j.profiles)
    if radii is None:
        return {}
    from mech.pairs.gearing import gear_centre

    out: dict[str, Profile] = {}
    for link, r in zip(j.links, radii, strict=True):
        if r is None:
            continue
        c = gear_centre(b, link, b.pos)
        if c is None:
            return {}
        out[link] = Circle(Ref(xy=c), r)
    for link, r in zip(j.links, radii, strict=True):
        if r is not None:
            continue
        other = next(lk for lk in j.links if lk != link)
        circle = out[other]
        assert isinstance(circle, Circle) and circle.centre.xy is not None
        cx, cy = circle.centre.xy
        at = j.place.at if j.place.at is not None else _beside(b, link, (cx, cy), circle.radius)
        # the line is tangent to the circle at the contact point: perpendicular to centre → contact
        angle = math.atan2(at[1] - cy, at[0] - cx) + math.pi / 2.0
        out[link] = Line(Ref(xy=at), angle=angle)
    return out


def _beside(b: RowBuilder, link: str, centre: tuple[float, float], radius: float) -> tuple[float, float]:
    """Where a straight pitch line on ``link`` touches the circle about ``centre`` when nothing is drawn.

    A rack slides on a path: its pitch line runs along the path (a rack's teeth are cut along the
    way it slides), on the path's side of the pinion (above it, below it, tilted), or, where the
    path passes through the pinion's centre, on its right-hand side (under a path to +x).  A link
    that slides on nothing (the ground a wheel rolls on) is under the circle, as DESIGN § 1.1
    draws it.
    """
    slides = (b.path(j.name) for j in b.mech.joints if link in j.links)
    slide = next((ps for ps in slides if ps is not None and ps.slider == link), None)
    if slide is not None and slide.point in b.pos:
        a = b.path_angle(slide)
        n = (-math.sin(a), math.cos(a))
        px, py = b.pos[slide.point]
        side = n[0] * (px - centre[0]) + n[1] * (py - centre[1])
        k = math.copysign(radius, side) if side != 0.0 else -radius
        return (centre[0] + k * n[0], centre[1] + k * n[1])
    return (centre[0], centre[1] - radius)


def _geo(b: RowBuilder, j: Joint, link: str, prof: Profile) -> _Geo | None:
    def where(ref: Ref, what: str) -> np.ndarray | None:
        if ref.name is not None:
            name = b.resolve(ref.name)
            if link not in b.carriers.get(name, ()) or name not in b.pos:
                b.problems.append(
                    Problem(
                        f"the {what} of the profile of {link} in joint {j.name} is {ref.name!r}, "
                        f"which is not a drawn point of {link}",
                        j.where,
                        f"name a joint or point of {link}, or give coordinates [x, y]",
                    )
                )
                return None
        return b.where(ref)

    if isinstance(prof, Circle):
        p = where(prof.centre, "centre")
        return None if p is None else _Geo(link, "circle", p, prof.radius / b.scale)
    if isinstance(prof, Knife):
        p = where(prof.point, "point")
        return None if p is None else _Geo(link, "point", p)
    if isinstance(prof, Line):
        p = where(prof.through, "through-point")
        if p is None:
            return None
        if prof.toward is not None:
            q = where(prof.toward, "toward-point")
            if q is None:
                return None
            u = q - p
            u = u / (math.hypot(*u) or 1.0)
        else:
            a = prof.angle or 0.0
            u = np.array([math.cos(a), math.sin(a)])
        return _Geo(link, "line", p, u=u)
    assert isinstance(prof, Curve)
    pts = np.array([b.sc(xy) for xy in prof.points])
    return _Geo(link, "curve", pts.mean(axis=0), pts=pts)


def _at(b: RowBuilder, link: str, s: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
    """Global scaled position of local point ``s`` of ``link`` as a function of q."""
    i = b.index[link]
    if i == b.n:
        return lambda q: s

    def f(q: np.ndarray) -> np.ndarray:
        x, y, th = q[3 * i : 3 * i + 3]
        c, sn = math.cos(th), math.sin(th)
        return np.array([x + c * s[0] - sn * s[1], y + sn * s[0] + c * s[1]])

    return f


def _dir(b: RowBuilder, link: str, u: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
    i = b.index[link]
    if i == b.n:
        return lambda q: u

    def f(q: np.ndarray) -> np.ndarray:
        th = q[3 * i + 2]
        c, sn = math.cos(th), math.sin(th)
        return np.array([c * u[0] - sn * u[1], sn * u[0] + c * u[1]])

    return f


@dataclass(frozen=True, slots=True)
class _How:
    """How a pair's profiles touch: ``rolls`` without slip; ``held`` in contact by teeth (no contact row)."""

    rolls: bool = False
    held: bool = False


def moving_contact(
    b: RowBuilder,
    j: Joint,
    *,
    rolls: bool = False,
    held: bool = False,
    radii: tuple[float | None, float | None] | None = None,
    profiles: dict[str, Profile] | None = None,
) -> bool:
    """Add the rows of ``j``'s profiles to ``b``; False when ``j`` has none (the instant rows apply).

    ``rolls``: the profiles roll without slip (rolling, gears); ``held``: the pair's
    teeth keep them in contact, so only no slip is a row (a rack on its pinion, h = 1);
    ``radii``: a rolling pair's circles about each link's pivot; ``profiles``: curves
    the kind made itself (else the joint's own).  A contact point drawn with ``at`` as
    well must be where the profiles touch.
    """
    if profiles is None:
        profiles = drawn_profiles(b, j, radii)
    if not _moving_contact(b, j, profiles, _How(rolls, held)):
        return False
    locate = b.locators.get(j.name)
    if locate is not None and j.place.at is not None and j.name in b.pos:
        gap = float(math.hypot(*(locate(b.q0) - b.scn(j.name))))
        if gap > TOUCH:
            from mech.units import to_unit

            unit = b.mech.length_unit
            b.problems.append(
                Problem(
                    f"joint {j.name} is drawn at a point {to_unit(gap * b.scale, unit):.4g} {unit} from "
                    "where its profiles touch",
                    j.where,
                    "leave `at` out (the profiles give the contact point) or correct it",
                )
            )
    return True


def _moving_contact(b: RowBuilder, j: Joint, profiles: dict[str, Profile], how: _How) -> bool:
    if not profiles:
        return False
    missing = [lk for lk in j.links if lk not in profiles]
    if missing:
        b.problems.append(
            Problem(
                f"joint {j.name} gives a profile for {', '.join(lk for lk in j.links if lk in profiles)} "
                f"but not for {', '.join(missing)}",
                j.where,
                "a pair moves when each of its links has a curve: add the other profile",
            )
        )
        return True
    geos = [_geo(b, j, lk, profiles[lk]) for lk in j.links]
    if None in geos:
        return True
    ga, gb = geos
    assert ga is not None and gb is not None
    kinds = {ga.kind, gb.kind}
    unit = b.mech.length_unit
    from mech.units import to_unit

    def gap_problem(gap: float, how: str) -> None:
        b.problems.append(
            Problem(
                f"the profiles of joint {j.name} are drawn {to_unit(gap * b.scale, unit):.4g} {unit} "
                f"apart ({how}); they must touch",
                j.where,
                "place the links so that the curves touch in the drawing",
            )
        )

    if "curve" in kinds:
        return _curve_contact(b, j, ga, gb, gap_problem, how)
    if "line" in kinds and len(kinds) == 2:
        other, line = (ga, gb) if gb.kind == "line" else (gb, ga)
        return _line_contact(b, j, other, line, gap_problem, how)
    if kinds <= {"circle", "point"} and "circle" in kinds:
        return _circle_contact(b, j, ga, gb, gap_problem, how)
    b.problems.append(
        Problem(
            f"joint {j.name}: a {ga.kind} and a {gb.kind} do not touch at one point",
            j.where,
            "give a circle or point against a line or circle",
        )
    )
    return True


def _line_contact(
    b: RowBuilder, j: Joint, other: _Geo, line: _Geo, gap_problem: Callable[[float, str], None], how: _How
) -> bool:
    """A circle or point against a line: the distance row (none for a gear's pitch line), the
    rolling row when it rolls, and the contact point and normal as functions of q."""
    assert line.u is not None
    n = np.array([-line.u[1], line.u[0]])
    dist = float(n @ (other.p - line.p))
    side = 1.0 if dist >= 0 else -1.0
    want = side * other.r
    if abs(dist - want) > TOUCH:
        gap_problem(abs(dist - want), f"{other.kind} and line")
        return True
    s_loc = b.to_local(other.link, other.p)
    t_loc = b.to_local(line.link, line.p)
    n_loc = _rotate_into(b, line.link, n)
    u_loc = np.array([n_loc[1], -n_loc[0]])
    io, il = b.index[other.link], b.index[line.link]
    # a gear's teeth keep its pitch line tangent: it adds only no slip (h = 1)
    if not how.held:
        b.online.append(OnLine(io, s_loc, il, t_loc, n_loc, want, j.name))
    if how.rolls:
        if other.kind != "circle":
            b.problems.append(Problem(f"{j.type} joint {j.name}: a point cannot roll", j.where))
            return True
        k = side * other.r
        c0 = float(line.u @ (other.p - line.p)) + k * (b.theta(other.link) - b.theta(line.link))
        b.online.append(OnLine(io, s_loc, il, t_loc, u_loc, c0, j.name, k=k))
    centre, normal = _at(b, other.link, s_loc), _dir(b, line.link, n_loc)
    b.locators[j.name] = lambda q: centre(q) - want * normal(q)
    b.normals[j.name] = normal
    return True


def _circle_contact(
    b: RowBuilder, j: Joint, ga: _Geo, gb: _Geo, gap_problem: Callable[[float, str], None], how: _How
) -> bool:
    """Two circles (or a circle and a point): the centre-distance row, or the rolling row of
    two circles pinned to one carrier, and the contact point and normal as functions of q."""
    dist = float(math.hypot(*(gb.p - ga.p)))
    outer = ga.r + gb.r
    inner = abs(ga.r - gb.r)
    d = outer if abs(dist - outer) <= abs(dist - inner) else inner
    if abs(dist - d) > TOUCH:
        gap_problem(abs(dist - d), "centres")
        return True
    sa, sb = b.to_local(ga.link, ga.p), b.to_local(gb.link, gb.p)
    ca, cb = _at(b, ga.link, sa), _at(b, gb.link, sb)
    if how.rolls:
        from mech.pairs.gearing import gear_row

        holo = gear_row(b, j)
        if holo is None:
            b.problems.append(
                Problem(
                    f"{j.type} joint {j.name}: two circles roll here only with both centres pinned "
                    "to one link (a carrier or the frame)",
                    j.where,
                )
            )
            return True
        b.angle.append(Angle(holo[0], holo[1], j.name))
    else:
        b.distance.append(Distance(b.index[ga.link], sa, b.index[gb.link], sb, d, j.name))
    ra, rb = ga.r, gb.r

    def contact(q: np.ndarray) -> np.ndarray:
        pa, pb = ca(q), cb(q)
        w = pb - pa
        e = w / (math.hypot(*w) or 1.0)
        if d == outer or ra >= rb:
            return pa + ra * e  # outside each other, or b inside a: on a toward b
        return pb - rb * e  # a inside b: on b, beyond a

    b.locators[j.name] = contact

    def normal(q: np.ndarray) -> np.ndarray:
        w = cb(q) - ca(q)
        return w / (math.hypot(*w) or 1.0)

    b.normals[j.name] = normal
    return True


def _rotate_into(b: RowBuilder, link: str, v: np.ndarray) -> np.ndarray:
    """A global direction as drawn, in ``link``'s frame (no translation)."""
    th = b.theta(link)
    c, s = math.cos(th), math.sin(th)
    return np.array([c * v[0] + s * v[1], -s * v[0] + c * v[1]])


def _curve_contact(
    b: RowBuilder, j: Joint, ga: _Geo, gb: _Geo, gap_problem: Callable[[float, str], None], how: _How
) -> bool:
    """A closed curve against a point, a circle (its centre kept ±r off the curve) or a line."""
    from mech.pairs.curves import CurveRow, Spline, curve_rows

    curve, other = (ga, gb) if ga.kind == "curve" else (gb, ga)
    if other.kind == "curve" or how.rolls:
        b.problems.append(
            Problem(
                f"joint {j.name}: a curve moves against a point, a circle or a line "
                + ("(not rolling)" if how.rolls else "(not another curve)"),
                j.where,
            )
        )
        return True
    assert curve.pts is not None
    spline = Spline(np.array([b.to_local(curve.link, p) for p in curve.pts]))
    ic, io = b.index[curve.link], b.index[other.link]
    qf0 = np.append(b.q0, (0.0, 0.0, 0.0))[None]
    if other.kind == "line":
        assert other.u is not None
        n = np.array([-other.u[1], other.u[0]])
        reach = curve.pts @ n - float(n @ other.p)
        if abs(reach.max()) < abs(reach.min()):  # the curve lies on the other side: face it
            n = -n
        row = CurveRow(
            ic,
            spline,
            io,
            "line",
            b.to_local(other.link, other.p),
            _rotate_into(b, other.link, n),
            0.0,
            j.name,
        )
        gap = abs(float(curve_rows(row, qf0)[0][0]))
    else:
        probe = CurveRow(ic, spline, io, "point", b.to_local(other.link, other.p), None, 0.0, j.name)
        f0 = float(curve_rows(probe, qf0)[0][0])
        want = math.copysign(other.r, f0) if other.r else 0.0
        row = CurveRow(ic, spline, io, "point", probe.s, None, want, j.name)
        gap = abs(f0 - want)
    if gap > TOUCH:
        gap_problem(gap, f"curve and {other.kind}")
        return True
    b.curves.append(row)
    from mech.units import to_unit

    unit = b.mech.length_unit
    b.notes.append(
        f"the profile of joint {j.name} on {curve.link} is the periodic cubic spline through its "
        f"{spline.n} points: within about {to_unit(spline.departure() * b.scale, unit):.2g} {unit} "
        "of the smooth curve through them (more points, closer: as the fourth power of their spacing)"
    )

    def full(q: np.ndarray) -> np.ndarray:
        return np.append(q, (0.0, 0.0, 0.0))[None]

    b.locators[j.name] = lambda q: curve_rows(row, full(q))[3][0]
    b.normals[j.name] = lambda q: curve_rows(row, full(q))[4][0]
    return True


# -- a higher pair at the drawn instant only ---------------------------------------------------
def instant_point(b: RowBuilder, j: Joint) -> np.ndarray | None:
    """The contact point as drawn (scaled), or None with the problem recorded."""
    if j.name not in b.pos:
        b.problems.append(
            Problem(
                f"{j.type} joint {j.name} needs at (the contact point of the instant) for velocities",
                j.where,
                "or give each link's curve under `profiles` (then the pair moves)",
            )
        )
        return None
    return b.scn(j.name)


def instant_normal(b: RowBuilder, j: Joint, normal: float | None) -> None:
    """The velocity-level row of a higher pair at the drawn instant: no relative motion along the normal."""
    xy = instant_point(b, j)
    if xy is None:
        return
    if normal is None:
        b.problems.append(
            Problem(
                f"{j.type} joint {j.name} needs normal (the common normal's angle) for velocities", j.where
            )
        )
        return
    a_link, b_link = j.links
    u = b.dir_local(b_link, normal)
    local_a, local_b = b.to_local(a_link, xy), b.to_local(b_link, xy)
    b.online.append(
        OnLine(b.index[a_link], local_a, b.index[b_link], local_b, u, 0.0, j.name, holonomic=False)
    )


def instant_rolling(b: RowBuilder, j: Joint) -> None:
    """Rolling at the drawn instant: the contact point has one velocity on both links (2 rows)."""
    xy = instant_point(b, j)
    if xy is None:
        return
    a_link, b_link = j.links
    local_a, local_b = b.to_local(a_link, xy), b.to_local(b_link, xy)
    b.coincide.append(Coincide(b.index[a_link], local_a, b.index[b_link], local_b, j.name, holonomic=False))
