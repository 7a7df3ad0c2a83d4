"""Free bodies: every force and couple on each link at the instant, and its equations written out.

A force analysis (:func:`mech.forces.analyse`) finds the forces all at once,
from the constraint Jacobian; a student checks them link by link, as the
textbook draws them: each link cut free, the forces of the pairs on it, its
loads and weight and the input torque, and Newton–Euler's two equations

    ΣF = m a_G,    ΣM_G = I_G α

(a massless link: ΣF = 0 and ΣM = 0 about its first joint).  :func:`free_bodies`
builds them from the analysis's own results (the pairs' forces, the input
effort, each link's accelerations), so the equations hold to rounding, and
their numbers alone rebuild any one unknown (tests do: the input torque from
the crank's moment equation).  The forces are lettered as the textbook letters
them: F₂₃ is the force on link 3 from link 2 (links numbered with the ground 1,
as for I-centres), W₃ the weight of link 3, T the input torque.
"""

from __future__ import annotations

import math
from typing import Any

from mech._records import dataclass
from mech.forces.result import ForceAnalysis
from mech.model import Mechanism

__all__ = ["Action", "FreeBody", "free_bodies", "numbers", "subscript"]

Vec = tuple[float, float]
_SUB = str.maketrans("0123456789,", "₀₁₂₃₄₅₆₇₈₉,")


def numbers(mech: Mechanism) -> dict[str, int]:
    """Each link's number: the ground 1, the others in file order (as the I-centres number them)."""
    return {link.name: i + 1 for i, link in enumerate(mech.numbered_links)}


def subscript(label: str) -> str:
    """``F23`` → ``F₂₃``, ``F2,12`` → ``F₂,₁₂``: a label as a textbook prints it."""
    head = label.rstrip("0123456789,")
    return head + label[len(head) :].translate(_SUB)


@dataclass(frozen=True, slots=True)
class Action:
    """One force or couple on a free body.

    ``label`` names it as the textbook does (``F23``, ``W3``, ``T``; printed with
    subscripts); ``what`` says where it comes from (``pin A, from link 2
    (crank)``).  ``force`` (N) acts at ``at`` (m, the point named ``point``), or
    is None for a pure couple; ``couple`` (N·m, ccw +) is the couple itself, 0 for
    a force; ``moment`` is its moment about the free body's reference point
    (``(r_P − r_G) × F + couple``).
    """

    label: str
    what: str
    force: Vec | None
    at: Vec | None
    point: str | None
    couple: float
    moment: float


@dataclass(frozen=True, slots=True)
class FreeBody:
    """One link cut free: its actions and Newton–Euler's equations with the numbers.

    ``about`` names the point moments are taken about (the centre of mass of a
    massive link, else the link's first joint) at ``about_at``; ``mass`` (kg),
    ``inertia`` (kg·m² about G), ``acceleration`` a_G (m/s²) and ``alpha`` (rad/s²)
    are the kinetic side: ``m_a`` = m a_G and ``i_alpha`` = I_G α (zero for a
    massless link).  ``sum_force`` and ``sum_moment`` are the actions' sums, equal
    to them to rounding.
    """

    link: str
    number: int
    about: str
    about_at: Vec
    mass: float
    inertia: float
    acceleration: Vec
    alpha: float
    actions: tuple[Action, ...]
    sum_force: Vec
    sum_moment: float
    m_a: Vec
    i_alpha: float

    def equations(self) -> tuple[str, str, str]:
        """ΣFx, ΣFy and ΣM about the reference point, each with its terms and both sides' numbers."""
        fx = [(a.label, a.force[0]) for a in self.actions if a.force is not None]
        fy = [(a.label, a.force[1]) for a in self.actions if a.force is not None]
        mz = [(a.label, a.moment) for a in self.actions]
        massive = self.mass > 0.0
        rhs_x = (
            f"m a_Gx = {_g(self.mass)} × {_g(self.acceleration[0])} = {_g(self.m_a[0])}" if massive else "0"
        )
        rhs_y = (
            f"m a_Gy = {_g(self.mass)} × {_g(self.acceleration[1])} = {_g(self.m_a[1])}" if massive else "0"
        )
        rhs_m = f"I_G α = {_g(self.inertia)} × {_g(self.alpha)} = {_g(self.i_alpha)}" if massive else "0"
        about = subscript(self.about) if len(self.about) <= 3 else self.about
        return (
            f"ΣFx = {_terms(fx)} = {_g(self.sum_force[0])} N;  {rhs_x} N",
            f"ΣFy = {_terms(fy)} = {_g(self.sum_force[1])} N;  {rhs_y} N",
            f"ΣM_{about} = {_terms(mz)} = {_g(self.sum_moment)} N·m;  {rhs_m} N·m",
        )

    def text(self) -> list[str]:
        """The free body as lines: what acts, then the three equations."""
        head = f"link {self.number} ({self.link})"
        if self.mass > 0.0:
            head += (
                f": m = {_g(self.mass)} kg, I_G = {_g(self.inertia)} kg·m² about {self.about} "
                f"({_g(self.about_at[0])}, {_g(self.about_at[1])}) m; "
                f"a_G = ({_g(self.acceleration[0])}, {_g(self.acceleration[1])}) m/s², α = {_g(self.alpha)} rad/s²"
            )
        else:
            head += (
                f": massless; moments about {self.about} ({_g(self.about_at[0])}, {_g(self.about_at[1])}) m"
            )
        lines = [head]
        for a in self.actions:
            if a.force is None:
                lines.append(f"  {subscript(a.label)} = {_g(a.couple)} N·m (couple): {a.what}")
            else:
                where = f" at {a.point}" if a.point else ""
                at = f" ({_g(a.at[0])}, {_g(a.at[1])}) m" if a.at is not None else ""
                lines.append(
                    f"  {subscript(a.label)}{where}{at} = ({_g(a.force[0])}, {_g(a.force[1])}) N, "
                    f"moment {_g(a.moment)} N·m: {a.what}"
                )
        lines.extend("  " + e for e in self.equations())
        return lines


def _g(x: float) -> str:
    """A number with 10 significant figures: enough to rebuild one unknown from the others."""
    return f"{x:.10g}".replace("-", "−") if math.isfinite(x) else str(x)


def _terms(terms: list[tuple[str, float]]) -> str:
    if not terms:
        return "0"
    out = ""
    for k, (_label, v) in enumerate(terms):
        sign = "−" if v < 0 else "+"
        out += (f"{sign} " if k else ("−" if v < 0 else "")) + f"{abs(v):.10g} "
    return out.strip()


def free_bodies(mech: Mechanism, kin: Any, fa: ForceAnalysis) -> tuple[FreeBody, ...]:
    """Every moving link's free body at the instant of ``kin`` (its force analysis ``fa``).

    Empty when the pairs' forces are indeterminate: a free body needs them all.
    """
    if not fa.determinate:
        return ()
    return tuple(free_body(mech, kin, fa, link.name) for link in mech.moving_links)


def free_body(mech: Mechanism, kin: Any, fa: ForceAnalysis, link: str) -> FreeBody:
    """The free body of ``link`` (any link, the ground too: what the pairs put on the frame)."""
    num = numbers(mech)
    mass = next((m for m in mech.masses if m.link == link), None)
    record = next((r for r in fa.inertia if r.link == link), None)
    if mass is not None and record is not None:
        about, about_at = mass.centre, record.centre
    else:
        about = next((j.name for j in mech.joints_of(link) if j.name in kin.positions), "")
        about_at = tuple(kin.positions[about]) if about else tuple(kin.links[link].origin)
    raw = _pair_actions(mech, fa, link, num) + _load_actions(mech, kin, fa, link, num)
    actions = tuple(_about(a, about_at) for a in raw)
    forces = [a.force for a in actions if a.force is not None]
    m_a: Vec = (0.0, 0.0)
    i_alpha, acc, alpha, inertia = 0.0, (0.0, 0.0), 0.0, 0.0
    if mass is not None and record is not None:
        acc, alpha, inertia = record.acceleration, record.alpha, mass.inertia
        m_a = (-record.force[0], -record.force[1])
        i_alpha = -record.couple
    return FreeBody(
        link=link,
        number=num[link],
        about=about,
        about_at=(float(about_at[0]), float(about_at[1])),
        mass=mass.mass if mass is not None else 0.0,
        inertia=inertia,
        acceleration=acc,
        alpha=alpha,
        actions=actions,
        sum_force=(math.fsum(f[0] for f in forces), math.fsum(f[1] for f in forces)),
        sum_moment=math.fsum(a.moment for a in actions),
        m_a=m_a,
        i_alpha=i_alpha,
    )


def _about(a: Action, ref: Vec) -> Action:
    """The action with its moment about ``ref``."""
    from dataclasses import replace

    moment = a.couple
    if a.force is not None and a.at is not None:
        moment += (a.at[0] - ref[0]) * a.force[1] - (a.at[1] - ref[1]) * a.force[0]
    return replace(a, moment=moment)


def _pair_actions(mech: Mechanism, fa: ForceAnalysis, link: str, num: dict[str, int]) -> list[Action]:
    """The pairs' forces on ``link``: each as its kind reports it, or its reaction (third law)."""
    out = []
    for p in fa.pairs:
        if link not in (p.on, p.by):
            continue
        on, by = (p.on, p.by) if p.on == link else (p.by, p.on)
        f = p.force if p.on == link else (-p.force[0], -p.force[1])
        kind = next((j.type for j in mech.joints if j.name == p.joint), "pair")
        what = f"{kind} {p.joint}, from link {num[by]} ({by})"
        if p.normal is not None:
            what += f"; normal force {p.normal:.6g} N"
        out.append(Action(_label("F", num[by], num[on]), what, f, p.at, p.joint, 0.0, 0.0))
    return out


def _label(head: str, a: int, b: int) -> str:
    return f"{head}{a}{b}" if a < 10 and b < 10 else f"{head}{a},{b}"


def _load_actions(
    mech: Mechanism, kin: Any, fa: ForceAnalysis, link: str, num: dict[str, int]
) -> list[Action]:
    """The loads, weight and input effort on ``link``."""
    import numpy as np

    from mech.forces.core import load_value
    from mech.pairs import load_link

    out = []
    angle = np.array([fa.drive_angle or 0.0])
    for load in mech.loads:
        value = load_value(load, angle)
        if load.is_force:
            if load_link(mech, load) == link:
                f = (float(value[0, 0]), float(value[0, 1]))
                at = tuple(kin.positions[load.target])
                out.append(Action(f"P{load.target}", f"load at {load.target}", f, at, load.target, 0.0, 0.0))
        elif load.target == link:
            out.append(
                Action(f"M{num[link]}", f"torque load on {link}", None, None, None, float(value[0]), 0.0)
            )
    for r in fa.inertia:
        if r.link == link and (r.weight[0] or r.weight[1]):
            centre = next(m.centre for m in mech.masses if m.link == link)
            out.append(Action(f"W{num[link]}", "weight m g", r.weight, r.centre, centre, 0.0, 0.0))
    out.extend(_effort_actions(mech, kin, fa, link))
    return out


def _effort_actions(mech: Mechanism, kin: Any, fa: ForceAnalysis, link: str) -> list[Action]:
    """The input torque on the driven link (and back on the link it turns on), or a slider
    drive's force along its path on the slider and back on its guide."""
    e = fa.effort
    if e is None or not mech.drives:
        return []
    d = mech.drives[0]
    if e.kind == "torque":
        if link == d.link:
            return [Action("T", f"input torque on {link}", None, None, None, e.value, 0.0)]
        if link == d.relative_to:
            return [Action("T", f"input torque's reaction, from {d.link}", None, None, None, -e.value, 0.0)]
        return []
    joint = next(j for j in mech.joints if j.name == d.joint)
    geom = kin.joints.get(joint.name)
    if geom is None or geom.direction is None or link not in joint.links:
        return []
    u, sign = geom.direction, (1.0 if link == joint.links[0] else -1.0)
    f = (sign * e.value * u[0], sign * e.value * u[1])
    return [Action("P", f"input force along {joint.name}", f, geom.at, joint.name, 0.0, 0.0)]
