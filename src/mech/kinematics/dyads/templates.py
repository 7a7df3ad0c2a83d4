"""The generated code of each closed-form primitive, with its formula.

Primitives (Norton, *Design of Machinery*, ch. 4, 6, 7; Haug ch. 3 for the
derivative rows).  P, Q, A, O are points already known, with their velocity
and acceleration; the branch is an explicit sign taken from the drawn
configuration, so the closed form stays on the assembly the file drew:

``crank``
    a link turned by the drive about a ground pivot: ``θ = φ + const``.
``rrr``
    the apex J of two links of lengths ``lP``, ``lQ`` pinned at P and Q
    (a four-bar's coupler and rocker): circle–circle, J to the left of
    P → Q when ``sign`` is +1.  Velocity: ``(J − P)·v_J = (J − P)·v_P`` and the
    same for Q; acceleration adds ``−|v_J − v_P|²`` (the centripetal term).
``rrp``
    the point B of a link of length ``l`` from A that runs on a line of a
    known guide (a slider crank's piston): circle–line, B ahead of A along
    the path when ``sign`` is +1.  The path row ``n·(B − T) = 0`` brings the
    guide's ω and the Coriolis term ``2ω u·(v_B − v_T)``.
``rpr``
    a guide link pivoted at a known point O whose straight path must pass
    through a known point P (a crank and slotted lever): the guide's angle
    from ``n·(P − O) = e`` (e the path's offset from O), with ``ω = n·(v_P −
    v_O)/(u·(P − O))``.
``pose2`` / ``pose_angle``
    a link from two known points of it, or from one point and an angle fixed
    to another link (a slider block on its guide).

"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from typing import Any

__all__ = ["constants", "fmt", "rpr", "rrp", "rrr"]


#: The constants of the program being generated, when one is (see :func:`constants`).
_COLLECTED: ContextVar[list[float] | None] = ContextVar("dyad_constants", default=None)


def fmt(x: float) -> str:
    """A number of the generated code: a named constant while a program is generated, else its literal.

    Named, the source depends on the mechanism's structure only (which dyads, in which order),
    not on its lengths: mechanisms of one structure — a class's four-bars — share one compiled
    function (:meth:`mech.kinematics.dyads.program.DyadProgram.function`), each with its own values.
    """
    collected = _COLLECTED.get()
    if collected is None:
        return repr(float(x))
    collected.append(float(x))
    return f"_k{len(collected) - 1}"


@contextmanager
def constants() -> Iterator[list[float]]:
    """Collect the numbers :func:`fmt` writes while generating one program, in order (``_k0``, ``_k1`` …)."""
    values: list[float] = []
    token = _COLLECTED.set(values)
    try:
        yield values
    finally:
        _COLLECTED.reset(token)


def rrr(k: int, j: str, p: str, q: str, lp: float, lq: float, sign: float, pv: Any) -> list[str]:
    """Circle–circle apex J: 16·area² = ((lP+lQ)² − d²)(d² − (lP−lQ)²), J = P + a·d̂ + sign·h·d̂⊥.

    The product form keeps the discriminant accurate next to a toggle, where
    one factor goes to zero (no cancellation of two large numbers).
    """
    P = {w: pv(p, w) for w in ("x", "y", "vx", "vy", "ax", "ay")}
    Q = {w: pv(q, w) for w in ("x", "y", "vx", "vy", "ax", "ay")}
    J = {w: pv(j, w) for w in ("x", "y", "vx", "vy", "ax", "ay")}
    s2, m2 = (lp + lq) ** 2, (lp - lq) ** 2
    return [
        f"    dx = {Q['x']} - {P['x']}; dy = {Q['y']} - {P['y']}; dd = dx * dx + dy * dy",
        f"    f1 = {fmt(s2)} - dd; f2 = dd - {fmt(m2)}",
        # base points that coincide leave the apex undetermined: no closure there (and no 1/0)
        f"    d{k} = f1 * f2 * {fmt(1.0 / (s2 * s2))} - (dd == 0.0); dd = dd + (dd == 0.0)",
        f"    ms{k} = ({fmt(abs(lp - lq) - (lp + lq))} + abs(2.0 * sqrt(dd) - {fmt(abs(lp - lq) + lp + lq)})) * 0.5",
        f"    a = ({fmt(lp * lp - lq * lq)} + dd) / (2.0 * dd); h = {fmt(sign)} * b{k} * sqrt(clip(f1 * f2)) / (2.0 * dd)",
        f"    {J['x']} = {P['x']} + a * dx - h * dy; {J['y']} = {P['y']} + a * dy + h * dx",
        f"    epx = {J['x']} - {P['x']}; epy = {J['y']} - {P['y']}; eqx = {J['x']} - {Q['x']}; eqy = {J['y']} - {Q['y']}",
        "    det = epx * eqy - epy * eqx",
        f"    sn{k} = det * {fmt(1.0 / (lp * lq))}; det = det + (det == 0.0)",
        f"    #V r1 = epx * {P['vx']} + epy * {P['vy']}; r2 = eqx * {Q['vx']} + eqy * {Q['vy']}",
        f"    #V {J['vx']} = (r1 * eqy - epy * r2) / det; {J['vy']} = (epx * r2 - r1 * eqx) / det",
        f"    #A ux = {J['vx']} - {P['vx']}; uy = {J['vy']} - {P['vy']}; wx = {J['vx']} - {Q['vx']}; wy = {J['vy']} - {Q['vy']}",
        f"    #A r1 = epx * {P['ax']} + epy * {P['ay']} - ux * ux - uy * uy",
        f"    #A r2 = eqx * {Q['ax']} + eqy * {Q['ay']} - wx * wx - wy * wy",
        f"    #A {J['ax']} = (r1 * eqy - epy * r2) / det; {J['ay']} = (epx * r2 - r1 * eqx) / det",
    ]


def rrp(
    k: int,
    b: str,
    a: str,
    g: int,
    tx: float,
    ty: float,
    ux: float,
    uy: float,
    length: float,
    sign: float,
    pv: Any,
) -> list[str]:
    """Circle–line: B = T + s·u with |B − A| = l, s = −(T−A)·u + sign·√(l² − ((T−A)·n)²).

    Rows for the derivatives: ``n·v_B = n·v_T + ω_g s`` (the path turns with
    its guide) and ``(B − A)·v_B = (B − A)·v_A``; differentiated again, the
    path row gains ``α_g s + 2ω_g u·(v_B − v_T)``, the Coriolis term.
    """
    A = {w: pv(a, w) for w in ("x", "y", "vx", "vy", "ax", "ay")}
    B = {w: pv(b, w) for w in ("x", "y", "vx", "vy", "ax", "ay")}
    gl = f"l{g}"
    return [
        f"    gux = {gl}_c * {fmt(ux)} - {gl}_s * {fmt(uy)}; guy = {gl}_s * {fmt(ux)} + {gl}_c * {fmt(uy)}",
        f"    rtx = {gl}_c * {fmt(tx)} - {gl}_s * {fmt(ty)}; rty = {gl}_s * {fmt(tx)} + {gl}_c * {fmt(ty)}",
        f"    tx = {gl}_x + rtx; ty = {gl}_y + rty",
        f"    px = tx - {A['x']}; py = ty - {A['y']}",
        "    pu = px * gux + py * guy; pn = -px * guy + py * gux",
        f"    f = {fmt(length * length)} - pn * pn",
        f"    d{k} = f * {fmt(1.0 / (length * length))}",
        f"    ms{k} = abs(pn) - {fmt(length)}",
        f"    sb = -pu + {fmt(sign)} * b{k} * sqrt(clip(f))",
        f"    {B['x']} = tx + sb * gux; {B['y']} = ty + sb * guy",
        f"    ex = {B['x']} - {A['x']}; ey = {B['y']} - {A['y']}",
        "    det = -guy * ey - gux * ex",
        f"    sn{k} = det * {fmt(1.0 / length)}; det = det + (det == 0.0)",
        f"    #V tvx = {gl}_vx - {gl}_w * rty; tvy = {gl}_vy + {gl}_w * rtx",
        f"    #V r1 = -guy * tvx + gux * tvy + {gl}_w * sb; r2 = ex * {A['vx']} + ey * {A['vy']}",
        f"    #V {B['vx']} = (r1 * ey - gux * r2) / det; {B['vy']} = (-guy * r2 - r1 * ex) / det",
        f"    #A tax = {gl}_ax - {gl}_al * rty - {gl}_w * {gl}_w * rtx; tay = {gl}_ay + {gl}_al * rtx - {gl}_w * {gl}_w * rty",
        f"    #A ux = {B['vx']} - {A['vx']}; uy = {B['vy']} - {A['vy']}",
        f"    #A r1 = -guy * tax + gux * tay + {gl}_al * sb + 2.0 * {gl}_w * (gux * ({B['vx']} - tvx) + guy * ({B['vy']} - tvy))",
        f"    #A r2 = ex * {A['ax']} + ey * {A['ay']} - ux * ux - uy * uy",
        f"    #A {B['ax']} = (r1 * ey - gux * r2) / det; {B['ay']} = (-guy * r2 - r1 * ex) / det",
    ]


def rpr(k: int, g: int, o: str, p: str, e: float, ulx: float, uly: float, sign: float, pv: Any) -> list[str]:
    """Guide through P about O: with d = P − O, u·d = sign·√(|d|² − e²) = c and n·d = e, so
    u = (c·d − e·d⊥)/|d|²; ω = n·(v_P − v_O)/c, α = (n·(a_P − a_O) − 2ω u·(v_P − v_O) − ω² e)/c.
    """
    O_ = {w: pv(o, w) for w in ("x", "y", "vx", "vy", "ax", "ay")}
    P = {w: pv(p, w) for w in ("x", "y", "vx", "vy", "ax", "ay")}
    O = O_  # noqa: E741 - the pivot O, as in the figure
    return [
        f"    dx = {P['x']} - {O['x']}; dy = {P['y']} - {O['y']}; dd = dx * dx + dy * dy",
        f"    f = dd - {fmt(e * e)}",
        # P on the pivot O: the guide's direction is undetermined, no closure there (and no 1/0)
        f"    d{k} = f / (dd + (dd == 0.0)) - (dd == 0.0); dd = dd + (dd == 0.0)",
        f"    ms{k} = {fmt(abs(e))} - sqrt(dd)",
        f"    cc = {fmt(sign)} * b{k} * sqrt(clip(f))",
        f"    gux = (cc * dx + {fmt(e)} * dy) / dd; guy = (cc * dy - {fmt(e)} * dx) / dd",
        f"    l{g}_t = atan2(guy * {fmt(ulx)} - gux * {fmt(uly)}, gux * {fmt(ulx)} + guy * {fmt(uly)})",
        f"    sn{k} = cc / sqrt(dd); cc = cc + (cc == 0.0)",
        f"    #V l{g}_w = (-guy * ({P['vx']} - {O['vx']}) + gux * ({P['vy']} - {O['vy']})) / cc",
        f"    #A l{g}_al = (-guy * ({P['ax']} - {O['ax']}) + gux * ({P['ay']} - {O['ay']}) - 2.0 * l{g}_w * "
        f"(gux * ({P['vx']} - {O['vx']}) + guy * ({P['vy']} - {O['vy']})) - l{g}_w * l{g}_w * {fmt(e)}) / cc",
    ]
