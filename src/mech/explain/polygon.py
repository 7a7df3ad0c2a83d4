"""The construction written out: velocity and acceleration polygons step by step, as the notes draw them.

The lecture notes (seeds/002, slider crank and Example 3.1) build a velocity
diagram in steps: "Step 1. Take any point o and draw vector oa perpendicular
to OA … Step 2. From a draw ab perpendicular to AB … Step 3. From o draw a line
parallel to OB which will intersect ab at b."  :func:`polygon` writes that
construction for any mechanism that decomposes into dyads, in the order the
closed-form solver places its points (:mod:`mech.kinematics.dyads`: the crank,
then each RRR, RRP or RPR dyad, then the points found by the velocity image):

* each step's **known vectors**, with magnitude and direction (the crank pin's
  velocity ω × OA ⊥ OA; in the acceleration polygon the normal component ω²r
  toward the centre, the tangential αr, the Coriolis component 2ωv);
* the **lines of unknown length** (⊥ AB, ∥ the line of stroke) through points
  already drawn, and the point where they **intersect**;
* the **measured result**, in m/s (m/s²) and in cm on the drawing at a round
  scale (1 cm = 0.1 m/s …).

Every number is the computed one (the solver's), so the construction agrees
with ``mech velocity`` to rounding; the steps hold enough to rebuild the
polygon from them alone (tests do).  Labels follow the notes: lower-case
images of the points (a, b …), all fixed points at the pole o; a primed set
(a′, b′ …) for accelerations; the point of a moving guide under a slider is the
slider's letter with the guide's number (a₄ under A on link 4).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from mech.errors import UnsupportedError
from mech.model import Mechanism
from mech.pairs import kind_of, located_on, points_of

if TYPE_CHECKING:  # pragma: no cover
    from mech.kinematics.result import Kinematics

__all__ = ["Construction", "Known", "Measured", "Step", "UnknownLine", "construction_dict", "polygon"]

Vec = tuple[float, float]
_SUB = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


@dataclass(frozen=True, slots=True)
class Known:
    """A vector of known magnitude and direction, drawn from polygon point ``start`` to ``end``.

    ``magnitude`` in SI (m/s or m/s²), ``direction`` in rad from +x;
    ``what`` names it (``v_AO``, ``normal a_BA``); ``formula`` the arithmetic.
    ``end`` may be a construction point (``~1``) on the way to the step's result.
    """

    start: str
    end: str
    magnitude: float
    direction: float
    what: str
    formula: str


@dataclass(frozen=True, slots=True)
class UnknownLine:
    """A line of known direction (rad) and unknown length, through polygon point ``through``."""

    through: str
    direction: float
    why: str  # "⊥ AB", "∥ the line of stroke of P"


@dataclass(frozen=True, slots=True)
class Measured:
    """A result read off the polygon: vector ``name`` (``ob``) with magnitude (SI) and direction (rad)."""

    name: str
    start: str
    end: str
    magnitude: float
    direction: float
    meaning: str  # "v_B", "v_BA" …


@dataclass(frozen=True, slots=True)
class Step:
    """One step of the construction.

    ``result`` is the polygon point located: at the end of the last known
    vector (no lines), at the intersection of the two ``lines``, or by the
    velocity image (``image``: the two base points, the ratio of lengths and
    the angle turned, so that result = base₀ + ratio·R(angle)·(base₁ − base₀)).
    """

    number: int
    text: str
    known: tuple[Known, ...]
    lines: tuple[UnknownLine, ...]
    result: str
    measured: tuple[Measured, ...]
    image: tuple[str, str, float, float] | None = None


@dataclass(frozen=True, slots=True)
class Construction:
    """A polygon written out: ``kind`` velocity or acceleration, the scale (SI per cm), the steps."""

    mechanism: str
    kind: str
    unit: str
    scale: float
    pole: str
    steps: tuple[Step, ...]
    results: tuple[str, ...]  # the link rates worked out from the polygon (ω = v_BA / AB …)

    def text(self) -> str:
        """The construction as the notes write it."""
        out = [
            f"{self.kind.capitalize()} diagram of {self.mechanism}, to a scale of 1 cm = {_g(self.scale)} {self.unit}"
        ]
        for s in self.steps:
            out.append(f"Step {s.number}. {s.text}")
        out += self.results
        return "\n".join(out)


def _g(x: float) -> str:
    return f"{x:.4g}"


def _deg(a: float) -> str:
    return f"{math.degrees(a) % 360.0:.1f}°"


def _dir(v: Vec) -> float:
    return math.atan2(v[1], v[0])


def _mag(v: Vec) -> float:
    return math.hypot(v[0], v[1])


def _sub(a: Vec, b: Vec) -> Vec:
    return (a[0] - b[0], a[1] - b[1])


_STEP = re.compile(
    r"^(?:crank (?P<crank>\S+) about (?P<pivot>\S+)"
    r"|rrr (?P<j>\S+) from (?P<p>\S+), (?P<q>\S+) .*"
    r"|rrp (?P<b>\S+) on the path of (?P<pj>\S+) from (?P<a>\S+) .*"
    r"|rpr (?P<g>\S+) about (?P<o>\S+) through (?P<pp>\S+)"
    r"|pose .*)$"
)


class _Builder:
    """Walks the dyad order and writes the steps, keeping the polygon's points by label."""

    def __init__(self, mech: Mechanism, kin: Kinematics, acc: bool) -> None:
        self.mech, self.kin, self.acc = mech, kin, acc
        self.mark = "′" if acc else ""
        self.numbers = {link.name: i + 1 for i, link in enumerate(mech.numbered_links)}
        self.ground = mech.ground
        self.fixed = {n for n in kin.positions if any(lk == mech.ground for lk in self._carriers(n))}
        self.steps: list[Step] = []
        self.scale = 1.0  # SI units per cm of the drawing, set once the extent is known
        self.at: dict[str, Vec] = {"o" + self.mark: (0.0, 0.0)}  # polygon points by label (SI, from the pole)
        self.done: set[str] = set()  # mechanism points whose image is drawn
        self.counter = 0

    # -- names ----------------------------------------------------------------------------
    def _carriers(self, name: str) -> tuple[str, ...]:
        for p in self.mech.points:
            if p.name == name:
                return (p.link,)
        try:
            return located_on(self.mech.joint(name))
        except KeyError:
            return ()

    def label(self, name: str, link: str | None = None) -> str:
        if name in self.fixed and link in (None, self.ground):
            return "o" + self.mark
        base = name.lower()
        if link is not None and name not in points_of(self.mech, link):
            base += str(self.numbers[link]).translate(_SUB)
        return base + self.mark

    def value(self, name: str, link: str | None = None) -> Vec:
        v = self.kin.acceleration(name, link) if self.acc else self.kin.velocity(name, link)
        return (float(v[0]), float(v[1]))

    def omega(self, link: str) -> float:
        return float(self.kin.links[link].omega or 0.0)

    def alpha(self, link: str) -> float:
        return float(self.kin.links[link].alpha or 0.0)

    def pos(self, name: str) -> Vec:
        p = self.kin.positions[name]
        return (float(p[0]), float(p[1]))

    def link_of(self, a: str, b: str) -> str:
        common = [lk for lk in self._carriers(a) if lk in self._carriers(b) and lk != self.ground]
        if not common:
            raise UnsupportedError(f"{a} and {b} are not points of one moving link")
        return common[0]

    # -- steps ----------------------------------------------------------------------------
    def add(
        self,
        text: str,
        known: list[Known],
        lines: list[UnknownLine],
        result: str,
        measured: list[Measured],
        image: tuple[str, str, float, float] | None = None,
    ) -> None:
        self.counter += 1
        self.steps.append(
            Step(self.counter, text, tuple(known), tuple(lines), result, tuple(measured), image)
        )

    def measure(self, start: str, end: str, meaning: str) -> Measured:
        v = _sub(self.at[end], self.at[start])
        name = start.rstrip("′") + end.rstrip("′") if not self.acc else start + end
        return Measured(name, start, end, _mag(v), _dir(v), meaning)

    def rel_chain(self, start: str, link: str, frm: str, to: str, tag: str) -> tuple[list[Known], str, float]:
        """Known part of the motion of ``to`` relative to ``frm`` on ``link``, drawn from ``start``.

        Velocity: nothing is known (the relative velocity is ⊥ the link): returns ([], start, ⊥ dir).
        Acceleration: the normal component ω²·FT toward F; the tangential one is the unknown line.
        """
        r = _sub(self.pos(to), self.pos(frm))
        perp = _dir(r) + math.pi / 2
        if not self.acc:
            return [], start, perp
        w = self.omega(link)
        n = (-w * w * r[0], -w * w * r[1])
        if _mag(n) == 0.0:
            return [], start, perp
        end = f"~{tag}"
        self.at[end] = (self.at[start][0] + n[0], self.at[start][1] + n[1])
        k = Known(
            start,
            end,
            _mag(n),
            _dir(n),
            f"normal a_{to}{frm}",
            f"ω²·{frm}{to} = {_g(abs(w))}² × {_g(_mag(r))} m = {_g(_mag(n))} {self.unit}, parallel to {to}{frm}, toward {frm}",
        )
        return [k], end, perp

    @property
    def unit(self) -> str:
        return "m/s²" if self.acc else "m/s"

    def crank(self, link: str, pivot: str) -> None:
        others = [n for n in points_of(self.mech, link) if n != pivot and n in self.kin.positions]
        if not others:
            return
        a = others[0]
        r = _sub(self.pos(a), self.pos(pivot))
        w = self.omega(link)
        la, lo = self.label(a), self.label(pivot)
        va = self.value(a)
        self.at[la] = va
        self.done |= {a, pivot}
        P, A = pivot, a
        if not self.acc:
            k = Known(
                lo,
                la,
                _mag(va),
                _dir(va),
                f"v_{A}{P}",
                f"ω × {P}{A} = {_g(abs(w))} rad/s × {_g(_mag(r))} m = {_g(_mag(va))} m/s",
            )
            fixed = sorted(self.fixed & set(self.kin.positions))
            pole = (
                f"{', '.join(fixed)} are fixed points, so they are taken as the single point o on the velocity diagram. "
                if len(fixed) > 1
                else ""
            )
            text = (
                f"{pole}Take any point o and draw vector {lo}{la} perpendicular to {P}{A} "
                f"({'clockwise' if w < 0 else 'counter-clockwise'} about {P}): {lo}{la} = v_{A}{P} = {k.formula}, "
                f"direction {_deg(k.direction)}; {_g(k.magnitude / self.scale)} cm on the drawing."
            )
            self.add(text, [k], [], la, [self.measure(lo, la, f"v_{A}")])
        else:
            n = (-w * w * r[0], -w * w * r[1])
            al = self.alpha(link)
            t = (-al * r[1], al * r[0])
            known = [
                Known(
                    lo,
                    "~c" if _mag(t) else la,
                    _mag(n),
                    _dir(n),
                    f"normal a_{A}{P}",
                    f"ω²·{P}{A} = {_g(abs(w))}² × {_g(_mag(r))} m = {_g(_mag(n))} m/s², parallel to {A}{P}, toward {P}",
                )
            ]
            if _mag(t):
                self.at["~c"] = n
                known.append(
                    Known(
                        "~c",
                        la,
                        _mag(t),
                        _dir(t),
                        f"tangential a_{A}{P}",
                        f"α·{P}{A} = {_g(al)} rad/s² × {_g(_mag(r))} m = {_g(_mag(t))} m/s², ⊥ {P}{A}",
                    )
                )
            text = (
                f"Take any point o′ (the fixed points are all at o′) and draw {lo}{la} parallel to {A}{P}, toward {P}: "
                f"the normal (centripetal) acceleration {known[0].formula}"
                + (
                    f"; then the tangential component {known[1].formula}"
                    if len(known) > 1
                    else " (the crank turns at constant speed: no tangential component)"
                )
                + f". {lo}{la} = a_{A} = {_g(_mag(va))} m/s², direction {_deg(_dir(va))}; {_g(_mag(va) / self.scale)} cm."
            )
            self.add(text, known, [], la, [self.measure(lo, la, f"a_{A}")])
        self.images()

    def rrr(self, j: str, p: str, q: str) -> None:
        l1, l2 = self.link_of(p, j), self.link_of(q, j)
        lp, lq, lj = self.label(p), self.label(q), self.label(j)
        k1, s1, d1 = self.rel_chain(lp, l1, p, j, f"{j}1")
        k2, s2, d2 = self.rel_chain(lq, l2, q, j, f"{j}2")
        self.at[lj] = self.value(j)
        self.done.add(j)
        lines = [UnknownLine(s1, d1, f"⊥ {p}{j}"), UnknownLine(s2, d2, f"⊥ {q}{j}")]
        m = [
            self.measure(lp, lj, f"{'v' if not self.acc else 'a'}_{j}{p}"),
            self.measure(lq, lj, f"{'v' if not self.acc else 'a'}_{j}{q}"),
        ]
        if lp != "o" + self.mark and lq != "o" + self.mark:
            m.append(self.measure("o" + self.mark, lj, f"{'v' if not self.acc else 'a'}_{j}"))
        if not self.acc:
            text = (
                f"The velocity of {j} with respect to {p} is perpendicular to {p}{j}: from {lp} draw a line ⊥ {p}{j} "
                f"(direction {_deg(d1)}). The velocity of {j} with respect to {q} is perpendicular to {q}{j}: from {lq} "
                f"draw a line ⊥ {q}{j} (direction {_deg(d2)}). They intersect at {lj}: "
                + "; ".join(
                    f"{x.name} = {x.meaning} = {_g(x.magnitude)} m/s ({_g(x.magnitude / self.scale)} cm), direction {_deg(x.direction)}"
                    for x in m
                )
                + "."
            )
        else:
            text = (
                f"From {lp} draw the normal component of a_{j}{p}, {k1[0].formula if k1 else '0'}, then a line ⊥ {p}{j} "
                f"for its tangential component. From {lq} draw the normal component of a_{j}{q}, {k2[0].formula if k2 else '0'}, "
                f"then a line ⊥ {q}{j}. They intersect at {lj}: "
                + "; ".join(
                    f"{x.name} = {x.meaning} = {_g(x.magnitude)} m/s² ({_g(x.magnitude / self.scale)} cm), direction {_deg(x.direction)}"
                    for x in m
                )
                + "."
            )
        self.add(text, k1 + k2, lines, lj, m)
        self.images()

    def rrp(self, b: str, joint: str, a: str) -> None:
        guide = self.mech.joint(joint).links[1]
        geom = self.kin.joints[joint]
        u = geom.direction
        assert u is not None, f"{joint} is a slider: its line of stroke is solved"
        rod = self.link_of(a, b)
        la, lb = self.label(a), self.label(b)
        k1, s1, d1 = self.rel_chain(la, rod, a, b, f"{b}1")
        gl = "o" + self.mark if guide == self.ground else self.label(b, guide)
        known2: list[Known] = []
        s2 = gl
        if guide != self.ground:
            self.guide_point(guide, b)
            if self.acc:
                cor = self.kin.coriolis(joint)
                s2 = f"~{b}c"
                self.at[s2] = (self.at[gl][0] + cor[0], self.at[gl][1] + cor[1])
                known2.append(
                    Known(
                        gl,
                        s2,
                        _mag(cor),
                        _dir(cor),
                        f"Coriolis a_{b}",
                        f"2ωv = 2 × {_g(abs(self.omega(guide)))} rad/s × {_g(abs(self.kin.sliding(joint)))} m/s = {_g(_mag(cor))} m/s²",
                    )
                )
        self.at[lb] = self.value(b)
        self.done.add(b)
        lines = [
            UnknownLine(s1, d1, f"⊥ {a}{b}"),
            UnknownLine(s2, _dir(u), f"∥ the line of stroke of {joint}"),
        ]
        m = [
            self.measure("o" + self.mark, lb, f"{'v' if not self.acc else 'a'}_{b}"),
            self.measure(la, lb, f"{'v' if not self.acc else 'a'}_{b}{a}"),
        ]
        if not self.acc:
            text = (
                f"The velocity of {b} with respect to {a} is perpendicular to {a}{b}: from {la} draw a line ⊥ {a}{b} "
                f"(direction {_deg(d1)}). The velocity of slider {b} is along the line of stroke: from {gl} draw a line "
                f"parallel to the stroke (direction {_deg(_dir(u))}), which intersects it at {lb}: "
            )
        else:
            text = (
                f"From {la} draw the normal component of a_{b}{a}, {k1[0].formula if k1 else '0'}, then a line ⊥ {a}{b} for "
                f"its tangential component. "
                + (
                    f"From {gl} draw the Coriolis component {known2[0].formula}, then "
                    if known2
                    else f"From {gl} draw "
                )
                + f"a line parallel to the line of stroke (direction {_deg(_dir(u))}); they intersect at {lb}: "
            )
        text += (
            "; ".join(
                f"{x.name} = {x.meaning} = {_g(x.magnitude)} {self.unit} ({_g(x.magnitude / self.scale)} cm)"
                for x in m
            )
            + "."
        )
        self.add(text, k1 + known2, lines, lb, m)
        self.images()

    def rpr(self, guide: str, o: str, p: str) -> None:
        """A guide pivoted at O whose slide passes the known point P (a slotted lever)."""
        joint = next(
            j
            for j in self.mech.joints
            if kind_of(j).role == "path" and guide in j.links and self.kin.joints[j.name].point == p
        )
        u = self.kin.joints[joint.name].direction
        assert u is not None, f"{joint.name} is a slot: its direction is solved"
        lo, lp, lpg = self.label(o), self.label(p), self.label(p, guide)
        r = _sub(self.pos(p), self.pos(o))
        known: list[Known] = []
        k1, s1, d1 = self.rel_chain(lo, guide, o, p, f"{p}g")
        s2 = lp
        if self.acc:
            cor = self.kin.coriolis(joint.name)
            minus = (-cor[0], -cor[1])
            s2 = f"~{p}c"
            self.at[s2] = (self.at[lp][0] + minus[0], self.at[lp][1] + minus[1])
            known.append(
                Known(
                    lp,
                    s2,
                    _mag(cor),
                    _dir(minus),
                    f"Coriolis a_{p} (reversed)",
                    f"2ωv = 2 × {_g(abs(self.omega(guide)))} rad/s × {_g(abs(self.kin.sliding(joint.name)))} m/s = {_g(_mag(cor))} m/s²",
                )
            )
        self.at[lpg] = self.value(p, guide)
        lines = [UnknownLine(s1, d1, f"⊥ {o}{p}"), UnknownLine(s2, _dir(u), f"∥ the slot of {guide}")]
        m = [
            self.measure(lo, lpg, f"{'v' if not self.acc else 'a'}_{p}{o} of the point of {guide} under {p}"),
            self.measure(lpg, lp, f"{'v' if not self.acc else 'a'}_{p} relative to {guide}"),
        ]
        if not self.acc:
            text = (
                f"The velocity of {p} with respect to the point of {guide} under it is along the slot: from {lp} draw a "
                f"line parallel to the slot ({_deg(_dir(u))}). That point of {guide} turns about {o}: from {lo} draw a "
                f"line ⊥ {o}{p} ({_deg(d1)}). They intersect at {lpg}: "
            )
        else:
            text = (
                f"From {lo} draw the normal component {k1[0].formula if k1 else '0'}, then a line ⊥ {o}{p}. From {lp} draw "
                f"the Coriolis component reversed, {known[0].formula}, then a line parallel to the slot. They intersect at {lpg}: "
            )
        text += (
            "; ".join(
                f"{x.name} = {x.meaning} = {_g(x.magnitude)} {self.unit} ({_g(x.magnitude / self.scale)} cm)"
                for x in m
            )
            + "."
        )
        self.add(text, k1 + known, lines, lpg, m)
        # the guide's own points by its image from o and the point under p
        self.guide_images(guide, o, p, lpg)
        del r

    def guide_point(self, guide: str, name: str) -> None:
        """The image of the guide's point under ``name``, from two drawn points of the (known) guide."""
        known = [
            n
            for n in points_of(self.mech, guide)
            if n in self.kin.positions and (n in self.done or n in self.fixed)
        ]
        base = next(
            ((p, q) for p in known for q in known if p < q and _mag(_sub(self.pos(q), self.pos(p))) > 0), None
        )
        if base is None:
            raise UnsupportedError(f"{guide} has fewer than two drawn points: its image cannot be drawn")
        p, q = base
        self.image_step(guide, name, (p, self.label(p)), (q, self.label(q)), coincident=True)

    def guide_images(self, guide: str, o: str, p: str, lpg: str) -> None:
        lo = self.label(o)
        for name in points_of(self.mech, guide):
            if name in self.done or name not in self.kin.positions or name == o:
                continue
            self.image_step(guide, name, (o, lo), (p, lpg))

    def image_step(
        self,
        link: str,
        name: str,
        base0: tuple[str, str],
        base1: tuple[str, str],
        *,
        coincident: bool = False,
    ) -> None:
        """Locate ``name``'s image by the link's image; ``coincident``: the point of ``link`` under ``name``."""
        (n0, l0), (n1, l1) = base0, base1
        r01 = _sub(self.pos(n1), self.pos(n0))
        r0x = _sub(self.pos(name), self.pos(n0))
        ratio = _mag(r0x) / _mag(r01)
        angle = _dir(r0x) - _dir(r01)
        ln = self.label(name, link) if coincident else self.label(name)
        self.at[ln] = self.value(name, link) if coincident else self.value(name)
        if not coincident:
            self.done.add(name)
        m = [
            self.measure(
                "o" + self.mark,
                ln,
                f"{'v' if not self.acc else 'a'}_{name}" + (f" on {link}" if coincident else ""),
            )
        ]
        turned = (math.degrees(angle) + 180.0) % 360.0 - 180.0
        text = (
            f"Locate {ln} by the {'velocity' if not self.acc else 'acceleration'} image of {link}"
            + (f" (its point under {name})" if coincident else "")
            + f": {l0.rstrip('′')}{ln.rstrip('′')} / {l0.rstrip('′')}{l1.rstrip('′')} = {n0}{name} / {n0}{n1} = {_g(ratio)}, "
            f"turned {turned:.1f}° from {l0}{l1} as {n0}{name} is from {n0}{n1}: "
            f"{m[0].name} = {m[0].meaning} = {_g(m[0].magnitude)} {self.unit} ({_g(m[0].magnitude / self.scale)} cm), "
            f"direction {_deg(m[0].direction)}."
        )
        self.add(text, [], [], ln, m, image=(l0, l1, ratio, angle))

    def images(self) -> None:
        """Every link with two drawn points: its other points by the image."""
        for link in self.mech.moving_links:
            names = [n for n in points_of(self.mech, link.name) if n in self.kin.positions]
            known = [n for n in names if n in self.done or n in self.fixed]
            if len(known) < 2:
                continue
            n0, n1 = (
                known[0],
                next((n for n in known[1:] if _mag(_sub(self.pos(n), self.pos(known[0]))) > 0), None)
                or known[1],
            )
            for name in names:
                if name not in self.done and name not in self.fixed:
                    self.image_step(link.name, name, (n0, self.label(n0)), (n1, self.label(n1)))


def polygon(mech: Mechanism, kin: Kinematics, *, kind: str = "velocity") -> Construction:
    """The velocity (or acceleration) polygon of ``mech`` at the instant solved in ``kin``, step by step.

    Raises
    ------
    UnsupportedError
        The mechanism does not decompose into a crank and dyads (the order of
        construction is the closed-form solver's), or has several drives.
    """
    from mech.draw.scene import nice_scale
    from mech.kinematics.dyads import program
    from mech.kinematics.solve import compiled

    if kind not in ("velocity", "acceleration"):
        raise ValueError(f"kind is velocity or acceleration, not {kind!r}")
    prog = program(compiled(mech, None)) if len(mech.drives) == 1 and mech.drives[0].link else None
    if prog is None:
        raise UnsupportedError(
            f"{mech.label} does not decompose into a crank and dyads: the construction cannot be written out step by step",
            hint="--explain follows the dyad order of the closed-form solution",
        )
    acc = kind == "acceleration"
    b = _Builder(mech, kin, acc)
    values = [b.value(n) for n in kin.positions]
    extent = max((_mag(v) for v in values), default=1.0)
    b.scale = nice_scale(extent, 100.0)
    for line in prog.steps:
        m = _STEP.match(line)
        if m is None or line.startswith("pose"):
            continue
        if m.group("crank"):
            b.crank(m.group("crank"), m.group("pivot"))
        elif m.group("j"):
            b.rrr(m.group("j"), m.group("p"), m.group("q"))
        elif m.group("b"):
            b.rrp(m.group("b"), m.group("pj"), m.group("a"))
        elif m.group("g"):
            b.rpr(m.group("g"), m.group("o"), m.group("pp"))
    b.images()
    results = []
    drive = mech.drives[0].link
    for link in mech.moving_links:
        st = kin.links[link.name]
        rate = st.alpha if acc else st.omega
        if link.name == drive or rate is None:
            continue
        names = [n for n in points_of(mech, link.name) if n in kin.positions]
        if len(names) < 2:
            continue
        n0, n1 = names[0], names[1]
        length = _mag(_sub(b.pos(n1), b.pos(n0)))
        if length == 0.0:
            continue
        sense = "counter-clockwise" if rate > 0 else "clockwise"
        if not acc:
            rel = _mag(_sub(b.value(n1), b.value(n0)))
            results.append(
                f"Angular velocity of {link.name}: ω = v_{n1}{n0} / {n0}{n1} = {_g(rel)} / {_g(length)} = {_g(abs(rate))} rad/s ({sense})"
                if rate
                else f"Angular velocity of {link.name}: 0 (it translates)"
            )
        else:
            results.append(
                f"Angular acceleration of {link.name}: α = a^t_{n1}{n0} / {n0}{n1} = {_g(abs(rate) * length)} / {_g(length)} = {_g(abs(rate))} rad/s² ({sense})"
            )
    return Construction(mech.label, kind, b.unit, b.scale, "o" + b.mark, tuple(b.steps), tuple(results))


def construction_dict(c: Construction) -> dict[str, Any]:
    """A construction for ``--json`` (SI; directions in degrees)."""
    return {
        "kind": c.kind,
        "unit": c.unit,
        "scale_per_cm": c.scale,
        "pole": c.pole,
        "steps": [
            {
                "step": s.number,
                "text": s.text,
                "known": [
                    {
                        "from": k.start,
                        "to": k.end,
                        "magnitude": k.magnitude,
                        "direction": math.degrees(k.direction),
                        "what": k.what,
                        "formula": k.formula,
                    }
                    for k in s.known
                ],
                "lines": [
                    {"through": ln.through, "direction": math.degrees(ln.direction), "why": ln.why}
                    for ln in s.lines
                ],
                "result": s.result,
                "image": None
                if s.image is None
                else {
                    "from": s.image[0],
                    "toward": s.image[1],
                    "ratio": s.image[2],
                    "angle": math.degrees(s.image[3]),
                },
                "measured": [
                    {
                        "name": m.name,
                        "from": m.start,
                        "to": m.end,
                        "magnitude": m.magnitude,
                        "direction": math.degrees(m.direction),
                        "meaning": m.meaning,
                    }
                    for m in s.measured
                ],
            }
            for s in c.steps
        ],
        "results": list(c.results),
    }
