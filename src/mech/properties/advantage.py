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
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from mech.errors import InputError, UnsupportedError
from mech.model import Mechanism
from mech.options import SolveOptions
from mech.pairs import located_on, points_of

__all__ = ["Advantage", "InputEffort", "input_effort", "mechanical_advantage"]

Vec = tuple[float, float]

#: Richardson-extrapolated central differences: steps h, h/2, h/4 of the drive angle (rad).
STEP = 1e-3


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
    virtual displacements).
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
    """The link a point output moves with (a named point's link; a joint's first moving link)."""
    for p in mech.points:
        if p.name == point:
            return p.link
    joint = mech.joint(point)
    moving = [lk for lk in located_on(joint) if lk != mech.ground]
    if not moving:
        raise InputError(f"{point} is fixed to the ground: it has no mechanical advantage")
    return moving[0]


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


# -- I-centres -----------------------------------------------------------------------------------
def _dist(p: Vec, q: Vec) -> float:
    return math.hypot(p[0] - q[0], p[1] - q[1])


def _by_icentres(
    mech: Mechanism, kin: Any, ics: Any, driver: str, out_kind: str, out_link: str, output: str
) -> tuple[float | None, float | None, str]:
    """(signed ω_k/ω_i or None, MA or None, the construction written out) for a turning driver."""
    ground = mech.ground
    i, k = driver, out_link
    c1i = ics.get(ground, i)
    if c1i.at_infinity or c1i.point is None:
        return None, None, "the driver translates: its I-centre with the ground is at infinity"
    if k == i:
        ratio: float | None = 1.0
        text = "the output link is the driver: ω_out/ω_in = 1"
        c1k = c1i
    else:
        c1k, cik = ics.get(ground, k), ics.get(i, k)
        n1i, n1k, nik = c1i.name, c1k.name, cik.name
        if cik.at_infinity:
            ratio, text = 1.0, f"{nik} at infinity: {k} turns with {i}, ω_out/ω_in = 1"
        elif c1k.at_infinity:
            ratio = 0.0
            text = f"{n1k} at infinity: {k} translates"
        else:
            a, b = _dist(c1i.point, cik.point), _dist(c1k.point, cik.point)
            same = (
                (c1i.point[0] - cik.point[0]) * (c1k.point[0] - cik.point[0])
                + (c1i.point[1] - cik.point[1]) * (c1k.point[1] - cik.point[1])
            ) > 0
            ratio = (a / b) * (1.0 if same else -1.0)
            text = f"ω_{k}/ω_{i} = {n1i}·{nik} / {n1k}·{nik} = {a:.6g} m / {b:.6g} m = {abs(ratio):.6g}"
            text += " (same sense)" if same else " (opposite senses)"
    if out_kind == "link" and not (c1k.at_infinity and k != i):
        return ratio, (1.0 / abs(ratio) if ratio else None), text
    # a point: its speed per unit ω_in
    p = kin.positions[output]
    if k != i and c1k.at_infinity:
        cik = ics.get(i, k)
        speed = _dist(c1i.point, cik.point)
        text += f"; v_{output}/ω_in = {c1i.name}·{cik.name} = {speed:.6g} m"
    else:
        r = _dist(c1k.point, p)
        speed = abs(ratio or 0.0) * r
        text += f"; v_{output}/ω_in = |ω_{k}/ω_{i}|·{c1k.name}{output} = {abs(ratio or 0.0):.6g} × {r:.6g} m = {speed:.6g} m"
    return ratio, (1.0 / speed if speed else None), text


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
    return pts, lks


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

    Raises
    ------
    InputError
        The output is the ground or unknown; the driver has no speed.
    """
    options = options or SolveOptions()
    driver, dkind, rate = _driver(mech, kin)
    out_kind, out_link = _output(mech, kin, output)
    w_out = kin.links[out_link].omega or 0.0
    scale = abs(rate) if dkind == "link" else abs(rate) / kin.size
    translating = out_kind == "link" and abs(w_out) <= 1e-12 * scale
    if translating:  # a slider as the output: its force over the input effort
        out_kind = "point"
    # the output's rate
    if out_kind == "link":
        out_rate = w_out
        ratio = out_rate / rate
    else:
        v = kin.velocity(output) if output in kin.positions else kin.links[out_link].velocity
        out_rate = math.hypot(v[0], v[1])
        ratio = out_rate / abs(rate)
    value = 1.0 / abs(ratio) if ratio else math.inf
    unit = {
        ("link", "link"): "1",
        ("link", "point"): "1/m",
        ("slider", "point"): "1",
        ("slider", "link"): "m",
    }[(dkind, out_kind)]
    by_ic, text = None, ""
    if dkind == "link":
        if icentres is None:
            from mech.icentres import locate

            icentres = locate(mech, kin)
        point_name = output if output in kin.positions else None
        if out_kind == "point" and point_name is None:
            point_name = next(n for n in points_of(mech, out_link) if n in kin.positions)
        _r, by_ic, text = _by_icentres(mech, kin, icentres, driver, out_kind, out_link, point_name or output)
    else:
        text = "slider drive: the I-centre ratio is not formed (its I-centre with the ground is at infinity)"
    by_vw = None
    if dkind == "link" and virtual_work:
        disp = displacements if displacements is not None else _displacements(mech, kin, options)
        pts, lks = disp
        if out_kind == "link":
            d = lks[out_link]
        else:
            name = output if output in pts else next(n for n in points_of(mech, out_link) if n in pts)
            d = math.hypot(*pts[name])
        by_vw = 1.0 / abs(d) if d else math.inf
    return Advantage(
        output=output,
        kind=out_kind,
        driver=driver,
        unit=unit,
        value=value,
        velocity_ratio=ratio,
        by_icentres=by_ic,
        by_virtual_work=by_vw,
        construction=text,
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
    terms = []
    for load in mech.loads:
        if load.torque is not None:
            terms.append((load.target, load.torque * (kin.links[load.target].omega or 0.0) / rate))
        else:
            v = kin.velocity(load.target)
            f = load.force or (0.0, 0.0)
            terms.append((load.target, (f[0] * v[0] + f[1] * v[1]) / rate))
    value = -sum(t for _n, t in terms)
    by_vw = None
    if dkind == "link" and virtual_work:
        pts, lks = displacements if displacements is not None else _displacements(mech, kin, options)
        total = 0.0
        for load in mech.loads:
            if load.torque is not None:
                total += load.torque * lks[load.target]
            else:
                f = load.force or (0.0, 0.0)
                total += f[0] * pts[load.target][0] + f[1] * pts[load.target][1]
        by_vw = -total
    return InputEffort(
        driver=driver,
        kind="torque" if dkind == "link" else "force",
        value=value,
        by_virtual_work=by_vw,
        terms=tuple(terms),
    )


def virtual_displacements(mech: Mechanism, kin: Any, *, options: SolveOptions | None = None) -> Any:
    """Shared virtual displacements for several outputs (None for a slider drive)."""
    return _displacements(mech, kin, options or SolveOptions())


def outputs_of(mech: Mechanism) -> Mapping[str, str]:
    """Candidate outputs: every moving link other than the driver → "link"."""
    drive = next((d.link for d in mech.drives if d.link), None)
    return {lk.name: "link" for lk in mech.moving_links if lk.name != drive}
