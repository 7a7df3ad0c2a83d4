"""Diagnosed mistakes: which usual wrong way of working a failed answer the claim matches.

When an answer fails, :func:`diagnose` computes the values the usual mistakes
would give — each from the mechanism itself, never guessed — and names the one
the claim matches within the answer's own tolerance:

* **the opposite sense** — the signed value with its sign turned (a claim with
  cw/ccw, a negative ratio);
* **a unit slip** — the value ×10, ×100, ×1000 or divided by them (mm or cm
  written as a bare number in m), rpm read as rad/s or the reverse
  (×60/2π, ×2π/60), degrees read as radians or the reverse (×180/π, ×π/180);
* **Coriolis left out** — a slider point's acceleration on a turning guide
  without its Coriolis component ``2 ω × v``; a Coriolis claim without the 2;
* **only the normal or only the tangential component** — of a relative
  acceleration ``a_BA`` (``ω² AB`` or ``α AB``), or of an absolute one where the
  other term of ``a_B = a_A + a_BA`` is left out;
* **a relative velocity for an absolute one, or the reverse** — ``v_BA`` for
  ``v_B`` (A another point of B's link), ``v_B`` or ``v_A`` for ``v_BA``;
* **ω (or α) of the wrong link** — another link's value, or that value with its sense turned;
* **the reciprocal time ratio** (fast over slow) and **half the stroke** (the amplitude);
* **the other assembly branch** — the mechanism solved again with one dyad
  closed the other way (a ``near`` hint mirrored across the line of its two
  neighbours, or to the other intersection with a slider's path), and the
  asked quantity taken from that solution.

A candidate that is itself within the tolerance of the right answer says
nothing and is dropped, so a right answer can never match a mistake; a claim
that matches none gets no diagnosis.  Cheap candidates are tried first; the
other branch (a solve) only when none of them matches.  Nothing here may break a
verdict: a candidate that cannot be computed is skipped.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from mech import grading
from mech.answers import AnswerKey, AtInfinity, Compare
from mech.grading import Analysis
from mech.pairs import kind_of
from mech.units import Dimension

if TYPE_CHECKING:  # pragma: no cover
    from mech.model import Claim, Tolerance

__all__ = ["diagnose", "diagnosis"]

Vec = tuple[float, float]
_KINEMATIC = ("position", "velocity", "acceleration")


def diagnose(claim: Claim, akey: AnswerKey, value: Any, an: Analysis, tol: Tolerance) -> str | None:
    """The usual mistake a failed claim matches (``"the opposite sense"``), or None."""
    found = diagnosis(claim, akey, value, an, tol)
    return None if found is None else found[0]


def diagnosis(
    claim: Claim, akey: AnswerKey, value: Any, an: Analysis, tol: Tolerance
) -> tuple[str, float] | None:
    """The usual mistake a failed claim matches and how closely: (words, miss), or None.

    ``miss`` is the claim's distance from the mistake's value, relative to that value (for a
    point, to the mechanism's size): a copied classmate's answer that the claim matches more
    closely is named instead (:func:`mech.check.classes.copied`).
    """
    if akey.compare in (Compare.COUNT, Compare.LABEL) or isinstance(value, AtInfinity):
        return None
    if akey.compare is Compare.POINT:
        if isinstance(claim.value, str):
            return None
        match = _point_match(tol, an, (float(value[0]), float(value[1])))
        found = _first(_point_candidates(akey, value, an), claim.value, match)
        if found is None:
            return None
        size = an.kin.size or 1.0
        return found[0], math.dist(found[1], claim.value) / size  # type: ignore[arg-type]
    to_space = _space(akey, claim)
    claimed = _claimed(akey, claim)
    right = to_space(value)
    scalar_match = _scalar_match(tol, right)
    found = _first(_cheap(akey, claim, value, right, an, to_space), claimed, scalar_match)
    if found is None and akey.level in _KINEMATIC:
        found = _first(_branch_candidates(akey, an, to_space), claimed, scalar_match)
    if found is None:
        return None
    text, candidate = found
    return text, abs(claimed - candidate) / abs(candidate) if candidate else math.inf


# -- comparing a candidate with the claim -------------------------------------------------------
def _space(akey: AnswerKey, claim: Claim) -> Callable[[Any], float]:
    """Raw value (scalar or vector) → the number the claim is compared with (as check does)."""
    signed = (
        (akey.compare is Compare.SENSE and claim.sense is not None)
        or akey.compare is Compare.SIGNED
        or (akey.compare is Compare.RATIO and float(claim.value) < 0)  # type: ignore[arg-type]
    )

    def to_space(raw: Any) -> float:
        if isinstance(raw, tuple):
            return math.hypot(raw[0], raw[1])
        return float(raw) if signed else abs(float(raw))

    return to_space


def _claimed(akey: AnswerKey, claim: Claim) -> float:
    v = float(claim.value)  # type: ignore[arg-type]
    if akey.compare is Compare.SENSE and claim.sense is not None:
        return -abs(v) if claim.sense == "cw" else abs(v)
    if akey.compare in (Compare.SIGNED, Compare.RATIO) and v < 0:
        return v
    return abs(v) if akey.compare is not Compare.SIGNED else v


def _allowed(tol: Tolerance, reference: float) -> float:
    return tol.value * abs(reference) if tol.relative else tol.value


def _scalar_match(tol: Tolerance, right: float) -> Callable[[float, float], bool]:
    def match(candidate: float, claimed: float) -> bool:
        if not math.isfinite(candidate):
            return False
        if abs(candidate - right) <= _allowed(tol, right):  # says nothing: it is (almost) the right answer
            return False
        return abs(candidate - claimed) <= _allowed(tol, candidate)

    return match


def _point_match(tol: Tolerance, an: Analysis, right: Vec) -> Callable[[Vec, Vec], bool]:
    size = an.kin.size
    allowed = tol.value * size if tol.relative else tol.value

    def match(candidate: Vec, claimed: Vec) -> bool:
        if math.dist(candidate, right) <= allowed:  # says nothing: it is (almost) the right point
            return False
        return math.dist(candidate, claimed) <= allowed

    return match


def _first(
    candidates: Iterator[tuple[str, Any]], claimed: Any, match: Callable[[Any, Any], bool]
) -> tuple[str, Any] | None:
    """The first candidate the claim matches: its words and its value."""
    for text, candidate in candidates:
        try:
            if match(candidate, claimed):
                return text, candidate
        except (TypeError, ValueError, ArithmeticError):
            continue
    return None


# -- candidates that need no new solve -------------------------------------------------------------
def _unit_slips(dimension: Dimension | None) -> Iterator[tuple[float, str]]:
    """(factor, words) for the unit slips of a quantity: claimed = right value × factor."""
    if dimension in (None, Dimension.NUMBER):
        return
    suffix = {Dimension.LENGTH: "", Dimension.VELOCITY: "/s", Dimension.ACCELERATION: "/s²"}.get(dimension)
    for f, unit in ((10.0, "dm"), (100.0, "cm"), (1000.0, "mm")):
        why = f": {unit}{suffix} written as a bare number in m{suffix}" if suffix is not None else ""
        yield f, f"a unit slip (×{f:g}{why})"
        yield 1.0 / f, f"a unit slip (÷{f:g})"
    rpm = 60.0 / (2.0 * math.pi)
    deg = 180.0 / math.pi
    if dimension is Dimension.ANGULAR_VELOCITY:
        yield rpm, "a unit slip (the value in rpm, given as rad/s)"
        yield 1.0 / rpm, "a unit slip (rad/s converted as if it were rpm)"
    if dimension in (Dimension.ANGLE, Dimension.ANGULAR_VELOCITY, Dimension.ANGULAR_ACCELERATION):
        yield deg, "a unit slip (degrees given as radians)"
        yield 1.0 / deg, "a unit slip (radians given as degrees)"


def _point_candidates(akey: AnswerKey, value: Any, an: Analysis) -> Iterator[tuple[str, Vec]]:
    x, y = value
    for factor, text in _unit_slips(Dimension.LENGTH):
        yield text, (x * factor, y * factor)
    if akey.level in _KINEMATIC:
        for text, alt in _branches(an):
            try:
                raw = grading.value(akey, alt)
            except Exception:  # that branch cannot give this point
                continue
            if not isinstance(raw, AtInfinity):
                yield text, (float(raw[0]), float(raw[1]))


def _cheap(
    akey: AnswerKey, claim: Claim, value: Any, right: float, an: Analysis, to_space: Callable[[Any], float]
) -> Iterator[tuple[str, float]]:
    family, names = akey.family, akey.names
    if (akey.compare is Compare.SENSE and claim.sense is not None) or akey.compare in (
        Compare.SIGNED,
        Compare.RATIO,
    ):
        yield "the opposite sense" + _turns(akey, right), -right
    for factor, text in _unit_slips(akey.dimension):
        yield text, right * factor
    if family == "time_ratio" and right:
        yield (
            "the reciprocal (fast stroke over slow; the time ratio is the slow stroke's time over the fast)",
            (1.0 / right),
        )
    elif family == "stroke":
        yield "half the stroke (the amplitude, not the travel from one end to the other)", right / 2.0
    elif family == "force" and names and right:
        yield from _tooth_parts(names[0], right, an)
    for text, raw in _physics(family, names, an):
        yield text, to_space(raw)


def _tooth_parts(joint: str, right: float, an: Analysis) -> Iterator[tuple[str, float]]:
    """A tooth load worked as its tangential part (the torque over the pitch radius) or its radial
    part: the teeth push along the line of action, at the pressure angle φ to the pitch line."""
    from mech.pairs import kind_of

    j = next((k for k in an.mech.joints if k.name == joint), None)
    phi = getattr(j, "pressure_angle", None) if j is not None and kind_of(j).meshes else None
    if phi:
        yield (
            "the tangential part only (the tooth load is along the line of action: F_t / cos φ)",
            right * math.cos(phi),
        )
        yield "the radial part only (F_t tan φ, the part that pushes the gears apart)", right * math.sin(phi)


def _turns(akey: AnswerKey, right: float) -> str:
    """What the right sense is: how the link turns (ω), or which way its α points (a link
    turning ccw and slowing has a cw α: "turns" would say the wrong thing of it)."""
    if not right:
        return ""
    sense = "ccw" if right > 0 else "cw"
    if akey.family == "omega":
        return f" ({akey.names[0]} turns {sense})"
    if akey.family == "alpha":
        return f" (α of {akey.names[0]} is {sense})"
    return ""


def _physics(family: str, names: tuple[str, ...], an: Analysis) -> Iterator[tuple[str, Any]]:
    """Wrong ways of working a kinematic quantity, each computed from the solution."""
    if family in ("omega", "alpha"):
        attr = "omega" if family == "omega" else "alpha"
        symbol = "ω" if family == "omega" else "α"
        for other, state in an.kin.links.items():
            if other != names[0] and other != an.mech.ground and getattr(state, attr) is not None:
                yield f"{symbol} of the wrong link ({other}'s)", getattr(state, attr)
                # …and written with the wrong sense (a signed claim: the other link's value, negated)
                yield f"{symbol} of the wrong link ({other}'s), with the wrong sense", -getattr(state, attr)
    elif family == "velocity":
        yield from _velocity_mixups(names, an)
    elif family == "acceleration":
        yield from _acceleration_parts(names, an)
    elif family == "coriolis":
        c = an.kin.coriolis(names[0])
        yield "Coriolis without the factor 2 (ω v, not 2 ω v)", (c[0] / 2.0, c[1] / 2.0)


def _neighbours(an: Analysis, point: str) -> Iterator[tuple[str, str]]:
    """(link, other point) for every moving link carrying ``point`` and every other located point on it."""
    kin, mech = an.kin, an.mech
    for link in kin.carriers.get(point, ()):
        if link == mech.ground:
            continue
        for other, carriers in kin.carriers.items():
            if other != point and link in carriers and other in kin.positions:
                yield link, other


def _sub(a: Vec, b: Vec) -> Vec:
    return (a[0] - b[0], a[1] - b[1])


def _add(a: Vec, b: Vec) -> Vec:
    return (a[0] + b[0], a[1] + b[1])


def _velocity_mixups(names: tuple[str, ...], an: Analysis) -> Iterator[tuple[str, Any]]:
    kin = an.kin
    if len(names) == 1:
        b = names[0]
        vb = kin.velocity(b)
        for link, a in _neighbours(an, b):
            va = kin.velocity(a, link)
            yield f"the velocity of {b} relative to {a} (v_{b}{a}), not {b}'s absolute velocity", _sub(vb, va)
    else:
        b, a = names
        yield f"the absolute velocity of {b}, not relative to {a}", kin.velocity(b)
        yield f"the absolute velocity of {a}, not {b} relative to it", kin.velocity(a)


def _acceleration_parts(names: tuple[str, ...], an: Analysis) -> Iterator[tuple[str, Any]]:
    kin, mech = an.kin, an.mech
    if len(names) == 2:
        b, a = names
        for link, other in _neighbours(an, b):
            if other != a:
                continue
            st = kin.links[link]
            r = _sub(kin.positions[b], kin.positions[a])
            w, al = st.omega or 0.0, st.alpha or 0.0
            yield f"only the normal component of a_{b}{a} (ω²·{a}{b})", (-w * w * r[0], -w * w * r[1])
            yield f"only the tangential component of a_{b}{a} (α·{a}{b})", (-al * r[1], al * r[0])
            return
        return
    b = names[0]
    ab = kin.acceleration(b)
    for j in mech.joints:  # a slider point on a turning guide: Coriolis left out
        geom = kin.joints.get(j.name)
        if geom is None or kind_of(geom.type).role != "path" or geom.point != b:
            continue
        c = kin.coriolis(j.name)
        if math.hypot(*c) > 0.0:
            yield f"Coriolis left out (2 ω v at {j.name})", _sub(ab, c)
    fixed = {n for n, carriers in kin.carriers.items() if mech.ground in carriers}
    for link, a in _neighbours(an, b):
        st = kin.links[link]
        r = _sub(kin.positions[b], kin.positions[a])
        w, al = st.omega or 0.0, st.alpha or 0.0
        normal = (-w * w * r[0], -w * w * r[1])
        tangential = (-al * r[1], al * r[0])
        if a in fixed:
            yield f"only the normal component (ω²·{a}{b}, {link} about {a})", normal
            yield f"only the tangential component (α·{a}{b}, {link} about {a})", tangential
        else:
            aa = kin.acceleration(a, link)
            yield f"the tangential component of a_{b}{a} left out", _add(aa, normal)
            yield f"the normal component of a_{b}{a} left out", _add(aa, tangential)


# -- the other assembly branch -------------------------------------------------------------------
def _branch_candidates(
    akey: AnswerKey, an: Analysis, to_space: Callable[[Any], float]
) -> Iterator[tuple[str, float]]:
    for text, alt in _branches(an):
        try:
            raw = grading.value(akey, alt)
        except Exception:  # that branch cannot give this quantity: no diagnosis from it
            continue
        if isinstance(raw, AtInfinity):
            continue
        yield text, to_space(raw)


def _branches(an: Analysis) -> list[tuple[str, Analysis]]:
    """The mechanism solved with each dyad closed the other way (kept on the analysis, made once)."""

    def make() -> list[tuple[str, Analysis]]:
        out = []
        for joint, near, text in _mirrors(an):
            alt = _resolved(an, joint, near)
            if alt is not None:
                out.append((f"the other assembly branch ({text})", alt))
        return out

    try:
        return an.cached("other_branches", make)  # type: ignore[no-any-return]
    except Exception:  # no other branch to offer
        return []


def _resolved(an: Analysis, joint: Any, near: Vec) -> Analysis | None:
    """``an``'s mechanism with ``joint`` on the other side: its dyad closed the other way, else assembled anew.

    A chain of dyads closes one dyad the other way in the solve it has already compiled
    (:attr:`~mech.options.SolveOptions.flipped`: one evaluation); a chain the dyads do not
    decompose, or whose other side breaks a row no dyad used, is assembled afresh from
    ``near``, the joint's mirror image, as the general route assembles any drawing.
    """
    flipped = Analysis(an.mech, options=an.options.with_(flipped=(joint.name,)))
    flipped.level = an.level
    try:
        return _moved(an, flipped, joint)
    except Exception:  # no dyad to close the other way, that side breaks another row (or a bug): assemble it
        pass
    mech = an.mech
    moved = replace(joint, place=replace(joint.place, near=near))
    other = replace(mech, joints=tuple(moved if j is joint else j for j in mech.joints), answers=(), asks=())
    alt = Analysis(other, options=an.options)
    alt.level = an.level
    try:
        return _moved(an, alt, joint)
    except Exception:  # the other branch does not assemble
        return None


def _moved(an: Analysis, alt: Analysis, joint: Any) -> Analysis | None:
    """``alt`` when it puts ``joint`` elsewhere than ``an`` does; None when it came back to the same place."""
    p = alt.kin.positions[joint.name]
    if math.dist(p, an.kin.positions[joint.name]) <= 1e-6 * an.kin.size:
        return None  # the same configuration (the joint is placed by a drive, or its dyad is in line)
    return alt


def _mirrors(an: Analysis) -> Iterator[tuple[Any, Vec, str]]:
    """(joint, mirrored near hint, words) for each moving pin a dyad places."""
    mech, kin = an.mech, an.kin
    driven = {d.link for d in mech.drives if getattr(d, "link", None)}
    sliders = {}
    for j in mech.joints:
        geom = kin.joints.get(j.name)
        if geom is not None and kind_of(geom.type).keeps_angle and geom.point and geom.direction and geom.at:
            sliders[geom.point] = (j, geom)
    for j in mech.joints:
        if kind_of(j).role != "pin" or j.place.at is not None or j.place.is_relative:
            continue
        if j.name not in kin.positions or driven & set(j.links) or mech.ground in j.links:
            continue
        p = kin.positions[j.name]
        partners = []
        for link in j.links:
            others = [
                n
                for n, carriers in kin.carriers.items()
                if n != j.name and link in carriers and n in kin.positions
            ]
            if others:
                partners.append((link, others[0]))
        if j.name in sliders:
            _, geom = sliders[j.name]
            slider_link = geom.links[0]
            rod = [(lk, k) for lk, k in partners if lk != slider_link]
            if not rod:
                continue
            k = kin.positions[rod[0][1]]
            u = geom.direction
            t = geom.at
            if t is None or u is None:  # a slider not located at this instant: no mirror to offer
                continue
            s = (k[0] - t[0]) * u[0] + (k[1] - t[1]) * u[1]
            foot = (t[0] + s * u[0], t[1] + s * u[1])
            q = (2 * foot[0] - p[0], 2 * foot[1] - p[1])
            if math.dist(q, p) <= 1e-9 * kin.size:
                continue
            yield j, q, f"{j.name} {_side(q, k, u, along=True)} {rod[0][1]}"
        elif len(partners) == 2:
            (_, n1), (_, n2) = partners
            a, b = kin.positions[n1], kin.positions[n2]
            d = _sub(b, a)
            length = math.hypot(*d)
            if length == 0.0:
                continue
            u = (d[0] / length, d[1] / length)
            s = (p[0] - a[0]) * u[0] + (p[1] - a[1]) * u[1]
            foot = (a[0] + s * u[0], a[1] + s * u[1])
            q = (2 * foot[0] - p[0], 2 * foot[1] - p[1])
            if math.dist(q, p) <= 1e-9 * kin.size:
                continue  # on the line: both branches meet
            yield j, q, f"{j.name} {_side(q, foot, u, along=False)} {n1}{n2}"


def _side(q: Vec, ref: Vec, u: Vec, *, along: bool) -> str:
    """Where q lies from ref: along the line u (left/right, above/below), or across it."""
    dx, dy = q[0] - ref[0], q[1] - ref[1]
    horizontal = abs(u[0]) >= abs(u[1])
    if along == horizontal:
        return "right of" if dx > 0 else "left of"
    return "above" if dy > 0 else "below"
