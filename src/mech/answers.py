"""The answer-key registry: every key ``answers`` and ``asks`` accept, in one table.

The loader reads keys with it (to validate a file at once, with locations) and
``mech check`` computes reference values with it (only what the claims ask).
This module is imported by the loader, so it stays light: no numpy, no rich;
compute functions import what they need inside their bodies.

How to add an answer key
------------------------
1. Write ``def _my_key(an, names) -> value``: the reference value, SI, computed
   from ``an``, a :class:`mech.check.Analysis` (``an.mech`` the model,
   ``an.topology``, ``an.mobility``, ``an.kin`` the solution at the level the
   key declares, ``an.icentres``; anything else: import it inside the function,
   call it on ``an.mech`` / ``an.kin`` and, if it is costly, keep it with
   ``an.cached("name", make)``).  ``names`` are the names the key's placeholders
   matched, in order.  Raise :class:`Undefined` ("ω of b is zero …") when the
   quantity does not exist for this mechanism, a :class:`mech.errors.MechError`
   when it cannot be computed (the verdict is then an error row with the reason).
2. Add one line to :data:`KINDS` (or call :func:`register` from this module)::

       AnswerKind("transmission_angle", Compare.MAGNITUDE, "position", Dimension.ANGLE, _tangle,
                  "interior angle between coupler and output link (0–180°)")

   - ``pattern``: literal segments and placeholders joined by dots;
     placeholders name what the user writes there (:data:`PLACEHOLDERS`):
     ``<link>``, ``<a>``, ``<b>`` a link; ``<point>``, ``<other>`` a joint or
     named point; ``<joint>`` a joint; ``<p>``, ``<q>`` a point or I-centre
     (``I13``); ``<out>`` a link or a point.  The loader checks every name.
   - ``compare``: how a claim is held against the value (:class:`Compare`):
     ``COUNT`` exact int, ``LABEL`` exact name after ``normalise``, ``POINT``
     ``[x, y]`` within tolerance × size (``infinity=True`` also reads
     ``infinity``; the value may then be an :class:`AtInfinity`),
     ``MAGNITUDE`` |claimed| vs |value|, ``SENSE`` signed when the claim says
     cw/ccw else magnitudes, ``RATIO`` signed for a negative claim else
     magnitudes, ``SIGNED`` as is.
   - ``level``: the least analysis the value needs: ``topology`` (no numpy),
     ``mobility``, ``position``, ``velocity``, ``acceleration``.  The whole
     file is solved once, at the highest level any claim needs.
   - ``dimension``: what a claim's unit must measure (a bare number is SI);
     ``also`` lists other dimensions accepted (a stroke: a length or an angle).
3. Add a row to cli.md § answers, and a test in ``tests/test_check.py`` whose
   reference value comes from an independent derivation.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Iterable, Iterator
from collections.abc import Set as AbstractSet
from enum import Enum
from functools import lru_cache
from typing import Any

from mech._records import dataclass
from mech.units import Dimension

__all__ = [
    "COUNT_KEYS",
    "KEY_FORMS",
    "KINDS",
    "LEVELS",
    "LINK_CLASSES",
    "PLACEHOLDERS",
    "AnswerKey",
    "AnswerKind",
    "AtInfinity",
    "Compare",
    "ICentreNames",
    "Undefined",
    "icentre_name",
    "names_by_kind",
    "parse_icentre_name",
    "parse_key",
    "register",
]

LINK_CLASSES = ("singular", "binary", "ternary", "quaternary", "pentagonal", "hexagonal")

#: Analysis levels, least first: a claim needs its key's level and every level below it.
LEVELS = ("topology", "mobility", "position", "velocity", "acceleration")

#: What each placeholder of a pattern stands for (the loader checks names against these sets).
PLACEHOLDERS: dict[str, str] = {
    "<link>": "link",
    "<a>": "link",
    "<b>": "link",
    "<point>": "point",
    "<other>": "point",
    "<joint>": "joint",
    "<p>": "icpoint",
    "<q>": "icpoint",
    "<out>": "linkpoint",
}

#: How each kind of name reads in a message ("names unknown point or I-centre 'Q'").
KIND_LABELS = {"icpoint": "point or I-centre", "linkpoint": "link or point"}


class Compare(str, Enum):
    """How a claim is held against the computed value (see the module docstring)."""

    COUNT = "count"
    LABEL = "label"
    POINT = "point"
    MAGNITUDE = "magnitude"
    SENSE = "sense"
    RATIO = "ratio"
    SIGNED = "signed"


class Undefined(Exception):
    """The asked quantity does not exist here (a ratio over a link at rest …): an error row."""


@dataclass(frozen=True, slots=True)
class AtInfinity:
    """A point at infinity (an I-centre of two links that translate relative to each other).

    ``direction`` is a unit vector along which it lies, when known; ``label``
    names it in messages.
    """

    direction: tuple[float, float] | None = None
    label: str = ""


@dataclass(frozen=True, slots=True)
class AnswerKind:
    """One row of the registry: a key pattern and how its reference value is had."""

    pattern: str
    compare: Compare
    level: str
    dimension: Dimension | None
    compute: Callable[[Any, tuple[str, ...]], Any]
    doc: str = ""
    distinct: bool = False  # the names must differ (icentre.a.b, omega_ratio.a.b)
    infinity: bool = False  # a POINT key may be claimed `infinity`
    normalise: Callable[[str], str] | None = None  # LABEL: the name both sides are compared in
    also: tuple[Dimension, ...] = ()  # further dimensions a claim's unit may measure

    def __post_init__(self) -> None:
        if self.level not in LEVELS:
            raise ValueError(f"{self.pattern}: level must be one of {', '.join(LEVELS)}, not {self.level!r}")
        for part in self.parts:
            if part.startswith("<") and part not in PLACEHOLDERS:
                raise ValueError(
                    f"{self.pattern}: unknown placeholder {part} (known: {', '.join(PLACEHOLDERS)})"
                )

    @property
    def parts(self) -> tuple[str, ...]:
        return tuple(self.pattern.split("."))

    @property
    def family(self) -> str:
        """The literal segments before the first placeholder (``omega``, ``links.count``)."""
        out = []
        for part in self.parts:
            if part.startswith("<"):
                break
            out.append(part)
        return ".".join(out)

    @property
    def dimensions(self) -> tuple[Dimension, ...]:
        return ((self.dimension,) if self.dimension is not None else ()) + self.also


@dataclass(frozen=True, slots=True)
class AnswerKey:
    """A parsed key: its registry row and the names after it.

    ``kinds`` say what each name must be (``link``, ``point`` …); ``level`` is
    the analysis a claim needs.
    """

    key: str
    kind: AnswerKind
    names: tuple[str, ...]
    kinds: tuple[str, ...]

    @property
    def family(self) -> str:
        return self.kind.family

    @property
    def compare(self) -> Compare:
        return self.kind.compare

    @property
    def dimension(self) -> Dimension | None:
        return self.kind.dimension

    @property
    def dimensions(self) -> tuple[Dimension, ...]:
        return self.kind.dimensions

    @property
    def level(self) -> str:
        return self.kind.level

    @property
    def is_count(self) -> bool:
        return self.kind.compare is Compare.COUNT


# -- the registry ---------------------------------------------------------------------------
_BY_HEAD: dict[str, list[AnswerKind]] = {}
_KINDS: list[AnswerKind] = []


def register(kind: AnswerKind) -> AnswerKind:
    """Add a key pattern to the registry (a pattern registered twice is a bug: ValueError)."""
    if any(k.pattern == kind.pattern for k in _KINDS):
        raise ValueError(f"answer key {kind.pattern} is registered twice")
    _KINDS.append(kind)
    _BY_HEAD.setdefault(kind.parts[0], []).append(kind)
    _parse_cached.cache_clear()
    return kind


def parse_key(key: str) -> AnswerKey:
    """Match an answers key against the registry and say what it needs.

    Raises ``ValueError`` with a readable reason when the key has no known form.

    Examples
    --------
    >>> k = parse_key("omega.rocker")
    >>> k.names, k.kinds, k.level, k.compare.value
    (('rocker',), ('link',), 'velocity', 'sense')
    """
    return _parse_cached(key)


def _parse(key: str) -> AnswerKey:
    parts = key.split(".")
    candidates = _BY_HEAD.get(parts[0], ())
    if not candidates:
        raise ValueError(f"unknown answer key {key!r}")
    best: tuple[int, AnswerKind] | None = None
    for kind in candidates:
        pattern = kind.parts
        if len(pattern) != len(parts):
            continue
        literal = 0
        for want, got in zip(pattern, parts, strict=True):
            if want.startswith("<"):
                if not got:
                    break
            elif want != got:
                break
            else:
                literal += 1
        else:
            if best is None or literal > best[0]:
                best = (literal, kind)
    if best is None:
        forms = " or ".join(k.pattern for k in candidates)
        if len(candidates) == 1 and not any(p.startswith("<") for p in candidates[0].parts):
            raise ValueError(f"unknown answer key {key!r}")
        raise ValueError(f"{key!r} does not have the form {forms}")
    kind = best[1]
    names = tuple(got for want, got in zip(kind.parts, parts, strict=True) if want.startswith("<"))
    kinds = tuple(PLACEHOLDERS[p] for p in kind.parts if p.startswith("<"))
    return AnswerKey(key, kind, names, kinds)


_parse_cached = lru_cache(maxsize=4096)(_parse)


def names_by_kind(
    links: Iterable[str], joints: Iterable[str], points: Iterable[str], n_links: int
) -> dict[str, AbstractSet[str]]:
    """The names each placeholder kind accepts in one mechanism (for the loader's checks).

    ``points`` are the named points (joints are points too); I-centres are
    named ``I12`` … for ``n_links`` links, ground first: a lazy set
    (:class:`ICentreNames`), since a 10,000-link file has 50 million of them.
    """
    link_names, joint_names = set(links), set(joints)
    point_names = joint_names | set(points)
    return {
        "link": link_names,
        "joint": joint_names,
        "point": point_names,
        "icpoint": ICentreNames(frozenset(point_names), n_links),
        "linkpoint": link_names | point_names,
    }


class ICentreNames(AbstractSet[str]):
    """The named points of a mechanism and its I-centres' names, without building the latter.

    Membership parses the name (``I13``, ``I1,12``) and checks its numbers
    against the number of links, so ``mech dof`` on a 10,000-link file with
    answers no longer spends a minute and 2.9 GB naming 50 million I-centres
    (issue 11).  Iterating still yields every name, lazily.
    """

    __slots__ = ("n_links", "points")

    #: Above this many I-centres a near-miss hint looks among the named points only.
    SUGGEST = 5_000

    def __init__(self, points: frozenset[str], n_links: int) -> None:
        self.points, self.n_links = points, n_links

    def _icentre(self, name: str) -> bool:
        pair = parse_icentre_name(name)
        if pair is None:
            return False
        a, b = min(pair), max(pair)
        return a >= 1 and b <= self.n_links and icentre_name(a, b) == name

    def __contains__(self, name: object) -> bool:
        return isinstance(name, str) and (name in self.points or self._icentre(name))

    def _icentres(self) -> Iterator[str]:
        n = self.n_links
        return (icentre_name(a, b) for a in range(1, n + 1) for b in range(a + 1, n + 1))

    def __iter__(self) -> Iterator[str]:
        yield from self.points
        yield from (ic for ic in self._icentres() if ic not in self.points)

    def __len__(self) -> int:
        shared = sum(1 for p in self.points if self._icentre(p))
        return len(self.points) + self.n_links * (self.n_links - 1) // 2 - shared

    def suggestions(self) -> AbstractSet[str] | Iterator[str]:
        """What a did-you-mean hint looks among: every name, or the points alone when too many."""
        return self if self.n_links * (self.n_links - 1) // 2 <= self.SUGGEST else self.points


# -- built-in keys: compute functions (an: mech.check.Analysis; names: the key's names) ------
def _count(attr: str) -> Callable[[Any, tuple[str, ...]], int]:
    def compute(an: Any, names: tuple[str, ...]) -> int:
        return int(getattr(an.topology.count, attr))

    return compute


def _link_class(cls: str) -> Callable[[Any, tuple[str, ...]], int]:
    def compute(an: Any, names: tuple[str, ...]) -> int:
        return len(an.topology.link_classes().get(cls, ()))

    return compute


def _joint_class(cls: str) -> Callable[[Any, tuple[str, ...]], int]:
    def compute(an: Any, names: tuple[str, ...]) -> int:
        return len(an.topology.joint_classes().get(cls, ()))

    return compute


def _icentre_count(an: Any, names: tuple[str, ...]) -> int:
    return int(an.topology.icentres)


def _mobility(an: Any, names: tuple[str, ...]) -> int:
    value = an.mobility
    if value is None:
        raise Undefined("cannot be computed: the file has no geometry for a Jacobian")
    return int(value)


def _chain(an: Any, names: tuple[str, ...]) -> str | None:
    return an.topology.chain


def normal_chain(name: str) -> str:
    """``Four Bar chain``, ``4-bar``, ``fourbar`` → ``four-bar``: one spelling per chain."""
    s = name.strip().lower().replace("_", "-").replace(" ", "-")
    s = re.sub(r"'s\b", "", s)
    s = re.sub(r"-(chain|mechanism|linkage)$", "", s)
    return {"fourbar": "four-bar", "4-bar": "four-bar", "fivebar": "five-bar", "5-bar": "five-bar"}.get(s, s)


def _position(an: Any, names: tuple[str, ...]) -> tuple[float, float]:
    p = an.kin.positions.get(names[0])
    if p is None:
        raise Undefined(
            f"cannot be computed: {names[0]} has no position of its own (a contact or slider joint)"
        )
    return (float(p[0]), float(p[1]))


def _velocity(an: Any, names: tuple[str, ...]) -> tuple[float, float]:
    kin = an.kin
    return kin.velocity(names[0]) if len(names) == 1 else kin.relative_velocity(names[0], names[1])


def _acceleration(an: Any, names: tuple[str, ...]) -> tuple[float, float]:
    kin = an.kin
    return kin.acceleration(names[0]) if len(names) == 1 else kin.relative_acceleration(names[0], names[1])


def _omega(an: Any, names: tuple[str, ...]) -> float:
    return float(an.kin.links[names[0]].omega)


def _alpha(an: Any, names: tuple[str, ...]) -> float:
    return float(an.kin.links[names[0]].alpha)


def _omega_ratio(an: Any, names: tuple[str, ...]) -> float:
    wa, wb = an.kin.links[names[0]].omega, an.kin.links[names[1]].omega
    if abs(wb) <= an.noise * an.omega_ref:
        raise Undefined(
            f"cannot be computed: ω of {names[1]} is zero, so ω_{names[0]}/ω_{names[1]} is undefined"
        )
    return float(wa / wb)


def _sliding(an: Any, names: tuple[str, ...]) -> float:
    return float(an.kin.sliding(names[0]))


def _rubbing(an: Any, names: tuple[str, ...]) -> float:
    return float(an.kin.rubbing(names[0]))


def _coriolis(an: Any, names: tuple[str, ...]) -> tuple[float, float]:
    return an.kin.coriolis(names[0])


def _least_speed(an: Any, names: tuple[str, ...]) -> float:
    from mech.check import least_speed

    return least_speed(an.mech, an.kin, names[0])


def _icentre(an: Any, names: tuple[str, ...]) -> tuple[float, float] | AtInfinity:
    ic = an.icentres.get(names[0], names[1])
    if ic.at_infinity:
        return AtInfinity(getattr(ic, "direction", None), f"I-centre {names[0]}–{names[1]}")
    return (float(ic.point[0]), float(ic.point[1]))


def _distance(an: Any, names: tuple[str, ...]) -> float | AtInfinity:
    points = []
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
            return AtInfinity(getattr(ic, "direction", None), name)
        points.append(tuple(ic.point))
    return math.dist(points[0], points[1])


def _property(name: str) -> Callable[[Any, tuple[str, ...]], Any]:
    """A linkage-property key computed in :mod:`mech.properties.keys` (imported when first asked)."""

    def compute(an: Any, names: tuple[str, ...]) -> Any:
        from mech.properties import keys

        return getattr(keys, name)(an, names)

    compute.__name__ = name
    return compute


def _normal_grashof(name: str) -> str:
    from mech.properties.keys import normal_grashof

    return normal_grashof(name)


_D = Dimension
KINDS: tuple[AnswerKind, ...] = (
    AnswerKind("dof", Compare.COUNT, "topology", _D.NUMBER, _count("n"), "Kutzbach's count"),
    AnswerKind("links.count", Compare.COUNT, "topology", _D.NUMBER, _count("l"), "links"),
    *(
        AnswerKind(f"links.{c}", Compare.COUNT, "topology", _D.NUMBER, _link_class(c), f"{c} links")
        for c in LINK_CLASSES
    ),
    AnswerKind("joints.count", Compare.COUNT, "topology", _D.NUMBER, _count("joints"), "joints as written"),
    *(
        AnswerKind(f"joints.{c}", Compare.COUNT, "topology", _D.NUMBER, _joint_class(c), f"{c} joints")
        for c in ("binary", "ternary", "quaternary")
    ),
    AnswerKind(
        "joints.equivalent_binary", Compare.COUNT, "topology", _D.NUMBER, _count("j"), "j of Kutzbach's count"
    ),
    AnswerKind("higher_pairs", Compare.COUNT, "topology", _D.NUMBER, _count("h"), "h of Kutzbach's count"),
    AnswerKind("icentres.count", Compare.COUNT, "topology", _D.NUMBER, _icentre_count, "n(n − 1)/2"),
    AnswerKind(
        "mobility", Compare.COUNT, "mobility", _D.NUMBER, _mobility, "rank of the constraint Jacobian"
    ),
    AnswerKind("chain", Compare.LABEL, "topology", None, _chain, "the chain's name", normalise=normal_chain),
    AnswerKind(
        "position.<point>", Compare.POINT, "position", _D.LENGTH, _position, "where a point is, [x, y]"
    ),
    AnswerKind("velocity.<point>", Compare.MAGNITUDE, "velocity", _D.VELOCITY, _velocity, "speed of a point"),
    AnswerKind(
        "velocity.<point>.<other>", Compare.MAGNITUDE, "velocity", _D.VELOCITY, _velocity, "relative velocity"
    ),
    AnswerKind("omega.<link>", Compare.SENSE, "velocity", _D.ANGULAR_VELOCITY, _omega, "angular velocity"),
    AnswerKind(
        "omega_ratio.<a>.<b>", Compare.RATIO, "velocity", _D.NUMBER, _omega_ratio, "ω_a/ω_b", distinct=True
    ),
    AnswerKind(
        "sliding.<joint>", Compare.MAGNITUDE, "velocity", _D.VELOCITY, _sliding, "speed along a slide"
    ),
    AnswerKind(
        "rubbing.<joint>", Compare.MAGNITUDE, "velocity", _D.VELOCITY, _rubbing, "rubbing speed at a pin"
    ),
    AnswerKind(
        "least_speed.<link>",
        Compare.MAGNITUDE,
        "velocity",
        _D.VELOCITY,
        _least_speed,
        "least speed on the line",
    ),
    AnswerKind(
        "acceleration.<point>",
        Compare.MAGNITUDE,
        "acceleration",
        _D.ACCELERATION,
        _acceleration,
        "acceleration",
    ),
    AnswerKind(
        "acceleration.<point>.<other>",
        Compare.MAGNITUDE,
        "acceleration",
        _D.ACCELERATION,
        _acceleration,
        "relative acceleration",
    ),
    AnswerKind(
        "alpha.<link>", Compare.SENSE, "acceleration", _D.ANGULAR_ACCELERATION, _alpha, "angular accel."
    ),
    AnswerKind(
        "coriolis.<joint>",
        Compare.MAGNITUDE,
        "acceleration",
        _D.ACCELERATION,
        _coriolis,
        "Coriolis component",
    ),
    AnswerKind(
        "icentre.<a>.<b>",
        Compare.POINT,
        "velocity",
        _D.LENGTH,
        _icentre,
        "an I-centre, [x, y] or infinity",
        distinct=True,
        infinity=True,
    ),
    AnswerKind(
        "distance.<p>.<q>",
        Compare.MAGNITUDE,
        "velocity",
        _D.LENGTH,
        _distance,
        "between points",
        distinct=True,
    ),
    # linkage properties (mech.properties; DESIGN § 1.1 "Answer keys for linkage properties")
    AnswerKind(
        "grashof",
        Compare.LABEL,
        "topology",
        None,
        _property("grashof"),
        "Grashof class of the driven four-bar loop",
        normalise=_normal_grashof,
    ),
    AnswerKind(
        "transmission_angle",
        Compare.MAGNITUDE,
        "position",
        _D.ANGLE,
        _property("transmission_angle"),
        "coupler–output interior angle at the instant (0–180°)",
    ),
    AnswerKind(
        "transmission_angle.min",
        Compare.MAGNITUDE,
        "position",
        _D.ANGLE,
        _property("transmission_angle_min"),
        "least transmission angle over the cycle",
    ),
    AnswerKind(
        "transmission_angle.max",
        Compare.MAGNITUDE,
        "position",
        _D.ANGLE,
        _property("transmission_angle_max"),
        "greatest transmission angle over the cycle",
    ),
    AnswerKind(
        "time_ratio", Compare.MAGNITUDE, "position", _D.NUMBER, _property("time_ratio"), "slow / fast stroke"
    ),
    AnswerKind(
        "stroke.<joint>",
        Compare.MAGNITUDE,
        "position",
        _D.LENGTH,
        _property("stroke"),
        "a slider's travel, or a frame pivot's swing",
        also=(_D.ANGLE,),
    ),
    AnswerKind(
        "mechanical_advantage.<out>",
        Compare.MAGNITUDE,
        "velocity",
        _D.NUMBER,
        _property("mechanical_advantage"),
        "output load over input effort (1/m for a point output of a crank)",
    ),
    AnswerKind(
        "input_torque",
        Compare.SIGNED,
        "velocity",
        _D.TORQUE,
        _property("input_torque"),
        "torque on the input link balancing the loads (ccw +)",
    ),
    AnswerKind(
        "input_force",
        Compare.SIGNED,
        "velocity",
        _D.FORCE,
        _property("input_force"),
        "force on a slider drive balancing the loads",
    ),
)
for _kind in KINDS:
    register(_kind)

#: Keys that claim an integer count, no geometry needed.
COUNT_KEYS = frozenset(k.pattern for k in KINDS if k.compare is Compare.COUNT and k.level == "topology")


def key_forms() -> tuple[str, ...]:
    """Every form a key may take (registered so far), for hints and docs."""
    return tuple(k.pattern for k in _KINDS)


#: Every built-in form a key may take, for hints (``key_forms()`` includes later registrations).
KEY_FORMS = key_forms()


# -- I-centre names -------------------------------------------------------------------------
def icentre_name(a: int, b: int) -> str:
    """The textbook name of the I-centre of links numbered ``a`` and ``b`` (ground = 1).

    ``I13`` while both numbers are single digits; ``I1,12`` beyond, where ``I112``
    would be ambiguous.
    """
    a, b = min(a, b), max(a, b)
    return f"I{a}{b}" if b < 10 else f"I{a},{b}"


_IC_NAME = re.compile(r"^I(?:(\d)(\d)|(\d+),(\d+))$")


def parse_icentre_name(name: str) -> tuple[int, int] | None:
    """``I13`` → (1, 3); ``I1,12`` → (1, 12); anything else → None."""
    m = _IC_NAME.match(name)
    if not m:
        return None
    a, b = (int(g) for g in (m.groups()[:2] if m.group(1) else m.groups()[2:]))
    return (a, b) if a != b else None


# -- cams given by their follower's programme (mech.cam), DESIGN § 1.1 -----------------------
def _cam(quantity: str) -> Callable[[Any, tuple[str, ...]], float]:
    """A cam's own analysis answers these keys (the linkage solver is never started for them)."""

    def compute(an: Any, names: tuple[str, ...]) -> float:
        from mech.cam.answers import cam_value

        return cam_value(an, quantity, names[0])

    return compute


for _kind in (
    AnswerKind(
        "pressure_angle.<joint>",
        Compare.MAGNITUDE,
        "topology",
        _D.ANGLE,
        _cam("pressure_angle"),
        "a cam's pressure angle at the drive angle",
    ),
    AnswerKind(
        "pressure_angle.<joint>.max",
        Compare.MAGNITUDE,
        "topology",
        _D.ANGLE,
        _cam("pressure_angle.max"),
        "a cam's largest pressure angle over the turn",
    ),
    AnswerKind(
        "displacement.<point>",
        Compare.MAGNITUDE,
        "topology",
        _D.LENGTH,
        _cam("displacement"),
        "a cam follower's lift from its lowest position (an angle for an oscillating one)",
        also=(_D.ANGLE,),
    ),
):
    register(_kind)


# -- forces (issue 24, DESIGN § 1.4): compute functions in mech.forces.keys ------------------
def _forces(name: str) -> Callable[[Any, tuple[str, ...]], Any]:
    """A force key computed in :mod:`mech.forces.keys` (imported when first asked)."""

    def compute(an: Any, names: tuple[str, ...]) -> Any:
        from mech.forces import keys

        return getattr(keys, name)(an, names)

    compute.__name__ = name
    return compute


def _supersede(kind: AnswerKind) -> None:
    """Put ``kind`` in the place of the registered key of the same pattern, in the registry and in
    :data:`KINDS` (input_torque and input_force now count the links' inertia and weight when the
    file gives masses)."""
    global KINDS
    old = next(k for k in _KINDS if k.pattern == kind.pattern)
    _KINDS[_KINDS.index(old)] = kind
    heads = _BY_HEAD[kind.parts[0]]
    heads[heads.index(old)] = kind
    KINDS = tuple(kind if k is old else k for k in KINDS)
    _parse_cached.cache_clear()


for _kind in (
    AnswerKind(
        "input_torque",
        Compare.SIGNED,
        "velocity",
        _D.TORQUE,
        _forces("input_torque"),
        "torque on the input link balancing the loads, and the links' inertia and weight (ccw +)",
    ),
    AnswerKind(
        "input_force",
        Compare.SIGNED,
        "velocity",
        _D.FORCE,
        _forces("input_force"),
        "force on a slider drive balancing the loads, and the links' inertia and weight",
    ),
):
    _supersede(_kind)
for _kind in (
    AnswerKind(
        "force.<joint>", Compare.MAGNITUDE, "position", _D.FORCE, _forces("force"), "force a pair carries"
    ),
    AnswerKind(
        "force.<joint>.x", Compare.SIGNED, "position", _D.FORCE, _forces("force_x"), "on its second link, x"
    ),
    AnswerKind(
        "force.<joint>.y", Compare.SIGNED, "position", _D.FORCE, _forces("force_y"), "on its second link, y"
    ),
    AnswerKind(
        "shaking_force", Compare.MAGNITUDE, "position", _D.FORCE, _forces("shaking_force"), "|−Σ m a_G|"
    ),
    AnswerKind(
        "shaking_moment",
        Compare.SENSE,
        "position",
        _D.TORQUE,
        _forces("shaking_moment"),
        "−Σ (r_G × m a_G + I_G α) about the drive's pivot (ccw +)",
    ),
    AnswerKind(
        "torque.mean",
        Compare.SENSE,
        "position",
        _D.TORQUE,
        _forces("torque_mean"),
        "mean input torque, cycle",
    ),
    AnswerKind(
        "energy.fluctuation",
        Compare.MAGNITUDE,
        "position",
        _D.ENERGY,
        _forces("energy_fluctuation"),
        "greatest minus least of ∫(T − T_mean) dθ",
    ),
    AnswerKind(
        "flywheel.inertia",
        Compare.MAGNITUDE,
        "position",
        _D.MOMENT_OF_INERTIA,
        _forces("flywheel_inertia"),
        "ΔE / (ω² C_s)",
    ),
):
    register(_kind)
