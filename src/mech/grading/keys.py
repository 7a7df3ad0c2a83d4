"""Reference values of the counting, kinematic and I-centre answer keys, for ``mech check``.

Each function is ``compute(an, names)``: ``an`` is the problem's
:class:`~mech.grading.lazy.Analysis` (``an.mech`` the model, ``an.topology``,
``an.mobility``, ``an.kin`` the solution at the level the claims need,
``an.icentres``), ``names`` the names the key's placeholders matched.  The
value is SI; a quantity that does not exist here raises
:class:`~mech.answers.Undefined`.  :data:`mech.grading.COMPUTE` keys them by
their form's pattern.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING

from mech.answers import AtInfinity, Undefined, parse_icentre_name
from mech.errors import InputError
from mech.grading.lazy import NOISE
from mech.pairs import located_on

if TYPE_CHECKING:  # pragma: no cover
    from mech.grading.lazy import Analysis
    from mech.icentres import ICentre
    from mech.kinematics import Kinematics
    from mech.model import Mechanism

__all__ = [
    "acceleration",
    "alpha",
    "chain",
    "coriolis",
    "count",
    "distance",
    "icentre",
    "icentre_count",
    "joint_class",
    "least_speed",
    "least_speed_of",
    "link_class",
    "mobility",
    "omega",
    "omega_ratio",
    "position",
    "rubbing",
    "sliding",
    "velocity",
]

Vec = tuple[float, float]


# -- counts (the topology alone: no numpy) ------------------------------------------------------
def count(attr: str) -> Callable[[Analysis, tuple[str, ...]], int]:
    """A count of Kutzbach's: ``n``, ``l``, ``j``, ``h`` or the joints as written."""

    def compute(an: Analysis, names: tuple[str, ...]) -> int:
        return int(getattr(an.topology.count, attr))

    return compute


def link_class(cls: str) -> Callable[[Analysis, tuple[str, ...]], int]:
    """How many links of a class (binary, ternary …)."""

    def compute(an: Analysis, names: tuple[str, ...]) -> int:
        return len(an.topology.link_classes().get(cls, ()))

    return compute


def joint_class(cls: str) -> Callable[[Analysis, tuple[str, ...]], int]:
    """How many joints of a class (binary, ternary …)."""

    def compute(an: Analysis, names: tuple[str, ...]) -> int:
        return len(an.topology.joint_classes().get(cls, ()))

    return compute


def icentre_count(an: Analysis, names: tuple[str, ...]) -> int:
    return int(an.topology.icentres)


def mobility(an: Analysis, names: tuple[str, ...]) -> int:
    value = an.mobility
    if value is None:
        raise Undefined("cannot be computed: the file has no geometry for a Jacobian")
    return int(value)


def chain(an: Analysis, names: tuple[str, ...]) -> str | None:
    return an.topology.chain


# -- the solution at the drive's instant -----------------------------------------------------------
def position(an: Analysis, names: tuple[str, ...]) -> Vec:
    name = names[0]
    p = an.kin.position(name) if "@" in name else an.kin.positions.get(name)
    if p is None:
        raise Undefined(
            f"cannot be computed: {names[0]} has no position of its own (a contact or slider joint)"
        )
    return (float(p[0]), float(p[1]))


def velocity(an: Analysis, names: tuple[str, ...]) -> Vec:
    kin = an.kin
    return kin.velocity(names[0]) if len(names) == 1 else kin.relative_velocity(names[0], names[1])


def acceleration(an: Analysis, names: tuple[str, ...]) -> Vec:
    kin = an.kin
    return kin.acceleration(names[0]) if len(names) == 1 else kin.relative_acceleration(names[0], names[1])


def omega(an: Analysis, names: tuple[str, ...]) -> float:
    return float(an.kin.links[names[0]].omega)  # type: ignore[arg-type]


def alpha(an: Analysis, names: tuple[str, ...]) -> float:
    return float(an.kin.links[names[0]].alpha)  # type: ignore[arg-type]


def omega_ratio(an: Analysis, names: tuple[str, ...]) -> float:
    wa, wb = an.kin.links[names[0]].omega, an.kin.links[names[1]].omega
    assert wa is not None and wb is not None  # a velocity solve gives every link's ω
    if abs(wb) <= an.noise * an.omega_ref:
        raise Undefined(
            f"cannot be computed: ω of {names[1]} is zero, so ω_{names[0]}/ω_{names[1]} is undefined"
        )
    return float(wa / wb)


def sliding(an: Analysis, names: tuple[str, ...]) -> float:
    return float(an.kin.sliding(names[0]))


def rubbing(an: Analysis, names: tuple[str, ...]) -> float:
    return float(an.kin.rubbing(names[0]))


def coriolis(an: Analysis, names: tuple[str, ...]) -> Vec:
    return an.kin.coriolis(names[0])


def least_speed_of(an: Analysis, names: tuple[str, ...]) -> float:
    return least_speed(an.mech, an.kin, names[0])


def least_speed(mech: Mechanism, kin: Kinematics, link: str) -> float:
    """The least speed (m/s) of any point on the line through a link's joints.

    For a point ``P(s) = A + s·u`` on the line (``u`` a unit vector along it),
    ``v(s) = v_A + ω k × (s u) = v_A + ω s u⊥``: the component along the line,
    ``v_A · u``, is the same for every point (the line is rigid), and the
    component across it, ``v_A · u⊥ + ω s``, vanishes at ``s = −(v_A · u⊥)/ω``
    (the foot of the perpendicular from the link's I-centre).  So the least
    speed is ``|v_A · u|`` for a turning link and ``|v_A|`` for a translating one.

    Raises
    ------
    InputError
        When the link has fewer than two joints with a point, or its joints are
        not on one line.
    """
    names = [j.name for j in mech.joints if link in located_on(j) and j.name in kin.positions]
    if len(names) < 2:
        raise InputError(
            f"least_speed needs two joints on {link} to draw its line; it has {len(names)}"
            + (f" ({', '.join(names)})" if names else "")
        )
    a = kin.positions[names[0]]
    far = max(names[1:], key=lambda n: math.dist(a, kin.positions[n]))
    b = kin.positions[far]
    length = math.dist(a, b)
    if length <= 0.0:
        raise InputError(f"the joints of {link} coincide: no line through them")
    u = ((b[0] - a[0]) / length, (b[1] - a[1]) / length)
    for n in names[1:]:
        p = kin.positions[n]
        off = abs((p[0] - a[0]) * u[1] - (p[1] - a[1]) * u[0])
        if off > 1e-9 * max(kin.size, length):
            raise InputError(
                f"the joints of {link} ({', '.join(names)}) are not on one line: least_speed is for a link's line of joints"
            )
    va = kin.velocity(names[0], link)
    w = kin.links[link].omega or 0.0
    if abs(w) * length <= NOISE * max(math.hypot(*va), 1e-300):
        return math.hypot(*va)
    return abs(va[0] * u[0] + va[1] * u[1])


# -- I-centres ---------------------------------------------------------------------------------------
def icentre(an: Analysis, names: tuple[str, ...]) -> Vec | AtInfinity:
    ic = an.icentres.get(names[0], names[1])
    if ic.at_infinity:
        return AtInfinity(ic.direction, f"I-centre {names[0]}–{names[1]}")
    return _located(ic)


def distance(an: Analysis, names: tuple[str, ...]) -> float | AtInfinity:
    points: list[Vec] = []
    for name in names:
        if name in an.kin.positions:
            points.append(an.kin.positions[name])
            continue
        numbers = parse_icentre_name(name)
        numbered = an.mech.numbered_links
        if numbers is None or not all(1 <= n <= len(numbered) for n in numbers):
            raise Undefined(f"cannot be computed: {name} is neither a point nor an I-centre")
        ic = an.icentres.get(numbered[numbers[0] - 1].name, numbered[numbers[1] - 1].name)
        if ic.at_infinity:
            return AtInfinity(ic.direction, name)
        points.append(_located(ic))
    return math.dist(points[0], points[1])


def _located(ic: ICentre) -> Vec:
    """An I-centre's point; one neither Kennedy nor the velocity field could locate is undefined."""
    if ic.point is None:
        raise Undefined(f"cannot be computed: the I-centre {ic.name} could not be located ({ic.method})")
    return (float(ic.point[0]), float(ic.point[1]))
