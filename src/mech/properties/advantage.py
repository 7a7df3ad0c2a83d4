"""Velocity ratio, mechanical advantage and the input torque that balances the loads (no friction).

Three routes to the same numbers, each independent of the others:

* **I-centres** (the notes' method): the I-centre I_ik of the input i and the
  output k moves alike on both links, so ω_k/ω_i = I_1i·I_ik / I_1k·I_ik (signed
  by which side of I_ik the two ground centres lie), and a point P of k moves at
  |ω_k|·I_1k·P.  Only the I-centres' positions are used.
* **The velocity solution**: ω and v from the solver's velocity analysis.
* **Virtual work**: the virtual displacements δφ_k/δθ, δr_P/δθ are central
  differences of *position* solves at θ ± h (Richardson-extrapolated, error
  O(h⁶)), so they owe nothing to the velocity analysis.  With loads F_P at
  points and T_k on links, the input torque that balances them is
  T_in = −(Σ F_P·δr_P/δθ + Σ T_k·δφ_k/δθ) — the principle of virtual work
  (Shigley & Uicker, *Theory of Machines and Mechanisms*, § 11.9).

Mechanical advantage (DESIGN § 1.1) is output load over input effort, a positive
magnitude: for a link output T_out/T_in = |ω_in/ω_out|; for a point output its
force (along its velocity) over the input torque, ω_in/|v_P| in 1/m — or over
the input force, v_in/|v_P|, for a slider drive.

**At a dead centre the advantage is infinite, and said so.**  Where the output is at
rest while the input moves (a rocker at its limit, a piston at the end of its stroke)
the rate it is divided by is zero, and a solve gives rounding instead: 1e-17 m per rad,
printed as an advantage of 4e16.  The velocity solution decides: a link's ω is zero
where the solver set it so (within its own error bound) and a point's speed below
1e-12 of the terms it is summed from (as ``mech velocity`` prints them), each widened
for a mechanism far from the origin (:func:`placement`).  The advantage is then
``math.inf`` and the result says ``dead_centre``; the I-centre and virtual-work routes
agree where their own distance or displacement is zero to their own rounding.  A slow
wheel of a 1e12:1 gear train is not at rest: its advantage is 1e12.  The virtual-work
route's rounding is the largest, since it divides differences of positions by the step
(:func:`_vw_noise`): where a displacement is less than a million times it, the six
figures shown would not be known, and that route gives None with a note rather than a
number 8 % off (1e-9° from the slider crank's dead centre).
"""

from __future__ import annotations

import math
import sys
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from mech.errors import InputError, UnsupportedError
from mech.model import Mechanism
from mech.options import SolveOptions
from mech.pairs import higher_pairs, point_link, points_of

__all__ = ["Advantage", "InputEffort", "input_effort", "mechanical_advantage"]

Vec = tuple[float, float]

#: Richardson-extrapolated central differences: steps h, h/2, h/4 of the drive angle (rad).
STEP = 1e-3
#: A point's speed below this fraction of the terms it is summed from is zero (the output is
#: at rest: a dead centre), the rule ``mech velocity`` prints by; far from the origin, the
#: float spacing of its coordinates widens it (:func:`placement`).
ZERO = 1e-12
#: Ulps of a coordinate that a position solve may be off by (the virtual-work route's floor).
POSITION_ULPS = 4.0
#: The virtual-work route shows a value only when its rounding is below this fraction of it:
#: the six figures the table prints.
RESOLVED = 1e-6


@dataclass(frozen=True, slots=True)
class Advantage:
    """Mechanical advantage of ``output`` (a link or a point) over the driver, three ways.

    ``value`` (velocity solution), ``by_icentres`` and ``by_virtual_work`` are
    positive magnitudes (dimensionless for a link output; 1/m for a point output
    of a turning driver; dimensionless for a point output of a slider drive; m
    for a link output of a slider drive); ``velocity_ratio`` is the output's
    rate over the input's, signed for a link (ω_out/ω_in).  ``construction``
    writes the I-centre ratio out with the distances (m).  A route that does not
    apply is None (no I-centres for a slider drive's chain, a slider drive for
    virtual displacements, a virtual displacement too small to resolve).

    ``dead_centre`` is True when the velocity solution finds the output at rest
    (its rate zero to rounding) while the input moves: ``value`` is then
    ``math.inf``, as is every route that agrees.  ``notes`` say why a route
    gives no number.
    """

    output: str
    kind: str  # "link" or "point"
    driver: str
    unit: str
    value: float
    velocity_ratio: float
    by_icentres: float | None
    by_virtual_work: float | None
    construction: str
    dead_centre: bool = False
    notes: tuple[str, ...] = ()


@dataclass(frozen=True, slots=True)
class InputEffort:
    """The input torque (N·m, ccw +) or force (N, along the drive's path) balancing the loads.

    ``value`` from the velocity solution, ``by_virtual_work`` from virtual
    displacements of position solves; ``terms`` each load's virtual power per
    unit input rate (N·m per rad, or N), whose negated sum is the effort.
    """

    driver: str
    kind: str  # "torque" or "force"
    value: float
    by_virtual_work: float | None
    terms: tuple[tuple[str, float], ...]


# -- the driver ----------------------------------------------------------------------------
def _driver(mech: Mechanism, kin: Any) -> tuple[str, str, float]:
    """(name, "link" | "slider", input rate): the single drive's link and ω, or slider joint and speed."""
    if len(kin.drives) != 1:
        raise UnsupportedError(
            f"mechanical advantage is for one input; {mech.label} has {len(kin.drives)} drives"
        )
    d = kin.drives[0]
    if d.link is not None:
        w = kin.links[d.link].omega
        if w is None or w == 0.0:
            raise InputError(
                f"the drive of {d.link} has no speed here: give rpm or omega (or --rpm)", where=d.where
            )
        return d.link, "link", float(w)
    speed = d.speed
    if speed is None or speed == 0.0:
        raise InputError(
            f"the slider drive at {d.joint} has no speed: give speed (or --speed)", where=d.where
        )
    return str(d.joint), "slider", float(speed)


def _carrier(mech: Mechanism, point: str) -> str:
    """The link a point output moves with (:func:`mech.pairs.point_link`: a higher pair's follower)."""
    link = point_link(mech, point)
    if link is None:
        raise InputError(f"{point} is fixed to the ground: it has no mechanical advantage")
    return link


def _output(mech: Mechanism, kin: Any, output: str) -> tuple[str, str]:
    """("link" | "point", carrier link) for an output name; a translating link counts as a point."""
    names = {link.name for link in mech.links}
    if output in names:
        if output == mech.ground:
            raise InputError("the ground does not move: choose a moving link or a point as the output")
        return "link", output
    if output not in kin.positions:
        raise InputError(f"{output} is neither a link nor a point with a position")
    return "point", _carrier(mech, output)


# -- rounding: when a rate is zero ------------------------------------------------------------
def placement(kin: Any) -> float:
    """How finely this solve's points are held, relative to its size: 64 ulps of the farthest.

    Coordinates are floats in global metres: a mechanism 1 mm across drawn 1e6 m from the
    origin has its points only to about 1e-10 m, 1e-7 of its size, and every distance and
    rate computed from them inherits that.  About 3e-14 for a mechanism at the origin.
    """
    size = kin.size or 1.0
    return 64.0 * sys.float_info.epsilon * (_far(kin) + size) / size


def _offset(kin: Any) -> float:
    """The part of :func:`placement` a solve's own error bound does not see: that of the
    mechanism's distance from the origin beyond its size (0 for a mechanism at the origin)."""
    size = kin.size or 1.0
    return 64.0 * sys.float_info.epsilon * max(_far(kin) - size, 0.0) / size


def _far(kin: Any) -> float:
    return max((math.hypot(*p) for p in kin.positions.values()), default=0.0)


def _fastest(kin: Any, rate: float, dkind: str) -> float:
    """The fastest |ω| of the solve (rad/s): the scale its rates are solved to."""
    w = max((abs(s.omega or 0.0) for s in kin.links.values()), default=0.0)
    return max(w, abs(rate)) if dkind == "link" else max(w, abs(rate) / (kin.size or 1.0))


def _link_at_rest(kin: Any, w_out: float, fastest: float) -> bool:
    """The solver sets an ω within its own error bound of zero to zero (Skeel's bound); far from
    the origin, the placement of the points widens that bound (:func:`_offset`).  A slow wheel
    of a 1e12:1 train turns at 1e-12 of its pinion's ω, and that is not zero."""
    return w_out == 0.0 or abs(w_out) <= _offset(kin) * fastest


def _point_at_rest(mech: Mechanism, kin: Any, name: str | None, link: str, speed: float) -> bool:
    """A point's velocity v_o + ω × r is zero below :data:`ZERO` of the terms it is summed from
    (|v_o| + |ω|·r over its links, as ``mech velocity`` prints it), widened far from the origin."""
    p = kin.positions.get(name) if name is not None else None
    carriers = [link] + [lk for lk in (kin.carriers.get(name, ()) if name is not None else ()) if lk != link]
    scale = 0.0
    for lk in carriers:
        st = kin.links[lk]
        r = math.dist(p, st.origin) if p is not None else 0.0
        scale = max(scale, math.hypot(*(st.velocity or (0.0, 0.0))) + abs(st.omega or 0.0) * r)
    return speed <= max(ZERO, _offset(kin)) * scale


def _translates(mech: Mechanism, link: str, at_rest: bool, icentres: Any) -> bool:
    """A translating link (a piston, a parallelogram's coupler: its force counts, as a point's)
    is one whose I-centre with the ground is at infinity; a rocker at its limit, at rest but
    turning about its pivot, is a link at a dead centre.  Without I-centres: ω zero to rounding."""
    if icentres is not None:
        c = icentres.get(mech.ground, link)
        if c.found:
            return bool(c.at_infinity)
    return at_rest


# -- I-centres -----------------------------------------------------------------------------------
def _dist(p: Vec, q: Vec) -> float:
    return math.hypot(p[0] - q[0], p[1] - q[1])


def _by_icentres(
    mech: Mechanism,
    kin: Any,
    ics: Any,
    driver: str,
    out: tuple[str, str, str],
    at_rest: bool,
) -> tuple[float | None, float | None, str]:
    """(signed ω_k/ω_i or None, MA or None, the construction written out) for a turning driver.

    ``out`` is (kind, link, point) of the output.  Where the velocity solution finds the
    output at rest (``at_rest``), a distance within the rounding of the points of zero is
    zero: I_ik on I_1i, a dead centre, MA ∞.  I_ik on I_1k as well leaves the ratio 0/0,
    undetermined by this construction (a coaxial internal gear pair): None.
    """
    ground = mech.ground
    out_kind, k, output = out
    i = driver
    tiny = placement(kin) * (kin.size or 1.0)
    rest = tiny if at_rest else 0.0
    # six figures of a distance need it a million times the rounding of the points it is measured
    # between (an ulp of the farthest): 1e-9° from a slider crank's dead centre, I12·I24 = 3.3e-12 m
    # is 160 × tiny, yet carries the points' rounding at 2e-5 of itself
    six = 1e6 * sys.float_info.epsilon * (_far(kin) + (kin.size or 1.0))
    c1i = ics.get(ground, i)
    if c1i.at_infinity or c1i.point is None:
        return None, None, "the driver translates: its I-centre with the ground is at infinity"
    if k == i:
        ratio: float | None = 1.0
        text = "the output link is the driver: ω_out/ω_in = 1"
        c1k = c1i
    else:
        c1k, cik = ics.get(ground, k), ics.get(i, k)
        if not (c1k.found and cik.found):
            return None, None, f"{c1k.name if not c1k.found else cik.name} is not located: no I-centre ratio"
        n1i, n1k, nik = c1i.name, c1k.name, cik.name
        if cik.at_infinity:
            ratio, text = 1.0, f"{nik} at infinity: {k} turns with {i}, ω_out/ω_in = 1"
        elif c1k.at_infinity:
            ratio = 0.0
            text = f"{n1k} at infinity: {k} translates"
        else:
            a, b = _dist(c1i.point, cik.point), _dist(c1k.point, cik.point)
            if b <= tiny:
                why = "0/0, undetermined" if a <= tiny else f"infinite: {i} cannot turn (a toggle)"
                return (
                    None,
                    None,
                    f"{n1k} and {nik} coincide: ω_{k}/ω_{i} = {n1i}·{nik} / {n1k}·{nik} is {why}",
                )
            if a <= six and not at_rest:
                return None, None, _unresolved(f"{n1i}·{nik}", a, six)
            a = 0.0 if a <= rest else a
            same = (
                (c1i.point[0] - cik.point[0]) * (c1k.point[0] - cik.point[0])
                + (c1i.point[1] - cik.point[1]) * (c1k.point[1] - cik.point[1])
            ) > 0
            ratio = (a / b) * (1.0 if same or a == 0.0 else -1.0)
            text = f"ω_{k}/ω_{i} = {n1i}·{nik} / {n1k}·{nik} = {a:.6g} m / {b:.6g} m = {abs(ratio):.6g}"
            text += (
                f": {k} at rest (dead centre)"
                if a == 0.0
                else " (same sense)"
                if same
                else " (opposite senses)"
            )
    if out_kind == "link" and not (c1k.at_infinity and k != i):
        return ratio, (1.0 / abs(ratio) if ratio else math.inf), text
    # a point: its speed per unit ω_in
    p = kin.positions[output]
    if k != i and c1k.at_infinity:
        cik = ics.get(i, k)
        speed = _dist(c1i.point, cik.point)
        if speed <= six and not at_rest:
            return None, None, _unresolved(f"{c1i.name}·{cik.name}", speed, six)
        speed = 0.0 if speed <= rest else speed
        text += f"; v_{output}/ω_in = {c1i.name}·{cik.name} = {speed:.6g} m"
    else:
        r = _dist(c1k.point, p)
        speed = abs(ratio or 0.0) * r
        if speed <= six and not at_rest:
            return None, None, _unresolved(f"v_{output}/ω_in", speed, six)
        speed = 0.0 if speed <= rest else speed
        text += f"; v_{output}/ω_in = |ω_{k}/ω_{i}|·{c1k.name}{output} = {abs(ratio or 0.0):.6g} × {r:.6g} m = {speed:.6g} m"
    if speed == 0.0:
        text += f": {output} at rest (dead centre)"
    return ratio, (1.0 / speed if speed else math.inf), text


def _unresolved(what: str, value: float, six: float) -> str:
    return (
        f"the I-centre ratio is not resolved to six figures: {what} = {value:.3g} m is less than "
        f"{six:.2g} m, a million times the rounding of the points, and the velocity solution finds the "
        "output moving"
    )


# -- virtual displacements -----------------------------------------------------------------------
def _displacements(mech: Mechanism, kin: Any, options: SolveOptions) -> Any:
    """d/dθ of every position and link angle by central differences, Richardson-extrapolated to O(h⁶).

    Returns (points: name → (dx/dθ, dy/dθ), links: name → dφ/dθ), or None for a slider drive.
    """
    from mech.kinematics import solve

    d = kin.drives[0]
    if d.link is None:
        return None
    theta = float(d.angle)
    base = options.with_(omega=None, direction=None, alpha=None)

    def at(angle: float) -> Any:
        return solve(mech, "position", base.with_(angle=angle))

    def central(h: float) -> tuple[dict[str, Vec], dict[str, float]]:
        plus, minus = at(theta + h), at(theta - h)
        pts = {
            n: (
                (plus.positions[n][0] - minus.positions[n][0]) / (2 * h),
                (plus.positions[n][1] - minus.positions[n][1]) / (2 * h),
            )
            for n in kin.positions
            if n in plus.positions and n in minus.positions
        }
        lks = {}
        for n in kin.links:
            da = plus.links[n].angle - minus.links[n].angle
            da = math.atan2(math.sin(da), math.cos(da))
            lks[n] = da / (2 * h)
            o1, o0 = plus.links[n].origin, minus.links[n].origin
            pts[f"#origin {n}"] = ((o1[0] - o0[0]) / (2 * h), (o1[1] - o0[1]) / (2 * h))
        return pts, lks

    # Richardson's table on h, h/2, h/4: the central difference's error series is in h², h⁴ …
    (p1, l1), (p2, l2), (p4, l4) = central(STEP), central(STEP / 2), central(STEP / 4)

    def extrapolate(f1: float, f2: float, f4: float) -> float:
        g1, g2 = (4 * f2 - f1) / 3, (4 * f4 - f2) / 3  # O(h⁴)
        return (16 * g2 - g1) / 15  # O(h⁶)

    pts = {
        n: (extrapolate(p1[n][0], p2[n][0], p4[n][0]), extrapolate(p1[n][1], p2[n][1], p4[n][1])) for n in p4
    }
    lks = {n: extrapolate(l1[n], l2[n], l4[n]) for n in l4}
    # A contact's name (a pitch point, where profiles touch) is no point of a link: it runs along
    # the profiles.  What a load there works through is its follower's own point at that place
    # (DESIGN § 1.2, mech.pairs.load_link): the link's rigid motion, δr = δr_O + δφ × (r − r_O).
    for name, _ in higher_pairs(mech.joints):
        link = point_link(mech, name)
        if name in pts and link is not None:
            (ox, oy), (dx, dy), dphi = kin.links[link].origin, pts[f"#origin {link}"], lks[link]
            px, py = kin.positions[name]
            pts[name] = (dx - dphi * (py - oy), dy + dphi * (px - ox))
    return {n: v for n, v in pts.items() if not n.startswith("#origin ")}, lks


# -- public ---------------------------------------------------------------------------------------
def mechanical_advantage(
    mech: Mechanism,
    kin: Any,
    output: str,
    *,
    icentres: Any | None = None,
    options: SolveOptions | None = None,
    displacements: Any | None = None,
    virtual_work: bool = True,
) -> Advantage:
    """The mechanical advantage of ``output`` (a link or a point) over the driver.

    Parameters
    ----------
    mech, kin
        The mechanism and its velocity solution (``solve(mech, "velocity")``).
    output
        A moving link (torque ratio) or a point or joint (force over input effort).
    icentres
        Its I-centres (:func:`mech.icentres.locate`); located here when None.
    options
        The solve's options (for the virtual displacements' position solves).
    displacements
        Precomputed virtual displacements (several outputs share one set).
    virtual_work
        False: skip the virtual-work route (four position solves).

    Returns
    -------
    Advantage
        ``value`` is ``math.inf`` with ``dead_centre`` True where the output is at rest.

    Raises
    ------
    InputError
        The output is the ground or unknown; the driver has no speed.
    """
    options = options or SolveOptions()
    driver, dkind, rate = _driver(mech, kin)
    out_kind, out_link = _output(mech, kin, output)
    fastest = _fastest(kin, rate, dkind)
    w_out = kin.links[out_link].omega or 0.0
    turning_rest = _link_at_rest(kin, w_out, fastest)
    if icentres is None and (dkind == "link" or turning_rest):
        icentres = _located(mech, kin)
    if out_kind == "link" and _translates(mech, out_link, turning_rest, icentres):
        out_kind = "point"  # a slider as the output: its force over the input effort
    point_name = output if output in kin.positions else None
    if out_kind == "point" and point_name is None:
        point_name = next((n for n in points_of(mech, out_link) if n in kin.positions), None)
    # the velocity solution: the output's rate, zero to rounding at a dead centre
    if out_kind == "link":
        at_rest = turning_rest
        ratio = 0.0 if at_rest else w_out / rate
    else:
        # the output link's own point there (a cam follower's contact point is a point of both links)
        v = kin.velocity(point_name, out_link) if point_name is not None else kin.links[out_link].velocity
        speed = math.hypot(v[0], v[1])
        at_rest = _point_at_rest(mech, kin, point_name, out_link, speed)
        ratio = 0.0 if at_rest else speed / abs(rate)
    unit = {
        ("link", "link"): "1",
        ("link", "point"): "1/m",
        ("slider", "point"): "1",
        ("slider", "link"): "m",
    }[(dkind, out_kind)]
    by_ic, text, notes = None, "", []
    if dkind == "link" and icentres is not None:
        _r, by_ic, text = _by_icentres(
            mech, kin, icentres, driver, (out_kind, out_link, point_name or output), at_rest
        )
    elif dkind == "link":
        text = "the I-centres could not be located: no I-centre ratio"
    else:
        text = "slider drive: the I-centre ratio is not formed (its I-centre with the ground is at infinity)"
    by_vw = None
    if dkind == "link" and virtual_work:
        disp = displacements if displacements is not None else _displacements(mech, kin, options)
        by_vw, note = _by_virtual_work(kin, disp, out_kind, out_link, point_name, at_rest)
        notes += [note] if note else []
    return Advantage(
        output=output,
        kind=out_kind,
        driver=driver,
        unit=unit,
        value=math.inf if at_rest else 1.0 / abs(ratio),
        velocity_ratio=ratio,
        by_icentres=by_ic,
        by_virtual_work=by_vw,
        construction=text,
        dead_centre=at_rest,
        notes=tuple(notes),
    )


def _located(mech: Mechanism, kin: Any) -> Any:
    """The I-centres of the instant, or None where they cannot be located."""
    from mech.errors import MechError
    from mech.icentres import locate

    try:
        return locate(mech, kin)
    except MechError:
        return None


def _vw_noise(kin: Any, out_kind: str) -> float:
    """How far a virtual displacement may be off from rounding alone: m per rad, or rad per rad.

    Each position is good to :data:`POSITION_ULPS` ulps of the farthest coordinate X; the
    Richardson combination (64 f₄ − 20 f₂ + f₁)/45 of central differences at h, h/2, h/4
    turns an error e in positions into at most (256 + 40 + 1)/45 · e/h ≈ 6.6 e/h; a link's
    angle, from points about the size L apart, into twice that over L.
    """
    size = kin.size or 1.0
    far = max((math.hypot(*p) for p in kin.positions.values()), default=0.0)
    e = POSITION_ULPS * sys.float_info.epsilon * (far + size)
    per = 6.6 * e / STEP
    return per if out_kind == "point" else 2.0 * per / size


def _by_virtual_work(
    kin: Any, disp: Any, out_kind: str, out_link: str, point: str | None, at_rest: bool
) -> tuple[float | None, str | None]:
    """MA by virtual displacements, ∞ at a dead centre, or None (and why) where rounding hides it."""
    pts, lks = disp
    if out_kind == "link":
        d, per = lks[out_link], "rad/rad"
    else:
        name = point if point in pts else next((n for n in kin.positions if n in pts), None)
        d, per = (math.hypot(*pts[name]) if name is not None else 0.0), "m/rad"
    noise = _vw_noise(kin, out_kind)
    if abs(d) <= noise and at_rest:
        return math.inf, None
    if abs(d) * RESOLVED > noise:
        return 1.0 / abs(d), None
    return None, (
        f"virtual work: not resolved to six figures: the virtual displacement {abs(d):.3g} {per} is less "
        f"than a million times the rounding of the position solves ({noise:.2g} {per})"
    )


def input_effort(
    mech: Mechanism,
    kin: Any,
    *,
    options: SolveOptions | None = None,
    displacements: Any | None = None,
    virtual_work: bool = True,
) -> InputEffort:
    """The input torque (or force) that balances the file's loads, without friction.

    Virtual power: T_in·ω_in + Σ F_P·v_P + Σ T_k·ω_k = 0 (velocity solution), and
    the same with virtual displacements of position solves in place of the rates.
    Where the loaded points and links are at rest (a piston at its dead centre), the
    effort is zero: a sum below the rounding of the terms it is made of is written 0.

    Raises
    ------
    InputError
        The file has no ``loads``, or the driver has no speed.
    """
    if not mech.loads:
        raise InputError(
            f"{mech.label} has no loads: give `loads:` (a force at a point, a torque on a link)",
            hint='e.g. loads: {C: {force: [0, -500]}, rocker: {torque: "20 N m"}}',
        )
    options = options or SolveOptions()
    driver, dkind, rate = _driver(mech, kin)
    fastest = _fastest(kin, rate, dkind)
    now = _loads_now(mech, kin)
    terms = []  # a load on a point or link at rest (a piston at its dead centre) does no work: 0
    for load, f in zip(mech.loads, now, strict=True):
        if not load.is_force:
            w = kin.links[load.target].omega or 0.0
            w = 0.0 if _link_at_rest(kin, w, fastest) else w
            terms.append((load.target, f[0] * w / rate))
        else:
            v = kin.velocity(load.target)
            carrier = _carrier(mech, load.target)
            if _point_at_rest(mech, kin, load.target, carrier, math.hypot(*v)):
                v = (0.0, 0.0)
            terms.append((load.target, (f[0] * v[0] + f[1] * v[1]) / rate + 0.0))
    value = -sum(t for _n, t in terms) + 0.0  # never -0
    by_vw = None
    if dkind == "link" and virtual_work:
        pts, lks = displacements if displacements is not None else _displacements(mech, kin, options)
        total, noise = 0.0, 0.0
        for load, f in zip(mech.loads, now, strict=True):
            if not load.is_force:
                total += f[0] * lks[load.target]
                noise += abs(f[0]) * _vw_noise(kin, "link")
            else:
                total += f[0] * pts[load.target][0] + f[1] * pts[load.target][1]
                noise += math.hypot(*f) * _vw_noise(kin, "point")
        by_vw = 0.0 if abs(total) <= noise else -total
    return InputEffort(
        driver=driver,
        kind="torque" if dkind == "link" else "force",
        value=value,
        by_virtual_work=by_vw,
        terms=tuple(terms),
    )


def _loads_now(mech: Mechanism, kin: Any) -> list[tuple[float, ...]]:
    """Each load at the instant solved, in the file's order (two may act at one point): (Fx, Fy) of
    a force, (T,) of a torque, a table read at the drive's angle (DESIGN § 1.4) as the force solve
    reads it (:meth:`mech.model.Load.values`)."""
    import numpy as np

    angle = np.array([kin.drives[0].angle if kin.drives and kin.drives[0].angle is not None else 0.0])
    return [tuple(float(x) for x in np.atleast_1d(ld.values(angle)[0])) for ld in mech.loads]


def virtual_displacements(mech: Mechanism, kin: Any, *, options: SolveOptions | None = None) -> Any:
    """Shared virtual displacements for several outputs (None for a slider drive)."""
    return _displacements(mech, kin, options or SolveOptions())


def outputs_of(mech: Mechanism) -> Mapping[str, str]:
    """Candidate outputs: every moving link other than the driver → "link"."""
    drive = next((d.link for d in mech.drives if d.link), None)
    return {lk.name: "link" for lk in mech.moving_links if lk.name != drive}
