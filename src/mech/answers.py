"""The answer-key forms: every key ``answers`` and ``asks`` accept, in one table.

A form says what a key looks like and how a claim of it is read and compared:
its pattern (``omega.<link>``), how a claim is held against the value
(:class:`Compare`), the least analysis the value needs (:data:`LEVELS`), the
quantity a claim's unit must measure.  The loader reads keys with it (to
validate a file at once, with locations); ``mech check`` parses the claims
with it and asks :mod:`mech.grading` for the reference values (the compute
function of each form, keyed by its pattern).

This room sits just above the pair kinds and below the loader, so it imports
nothing of mech above :mod:`mech.units`: no compute function, no lazy import of
an analysis (issue 20: an answer key's form and its value were one row here,
and the lazy imports of the values tied the loader, the analyses and the
checker into one import circle).

How to add an answer key
------------------------
1. Add its form to :data:`KINDS` (or call :func:`register` from a module of
   your own)::

       AnswerKind("transmission_angle", Compare.MAGNITUDE, "position", Dimension.ANGLE,
                  "interior angle between coupler and output link (0–180°)")

   - ``pattern``: literal segments and placeholders joined by dots;
     placeholders name what the user writes there (:data:`PLACEHOLDERS`):
     ``<link>``, ``<a>``, ``<b>`` a link; ``<point>``, ``<other>`` a joint or
     named point; ``<joint>`` a joint; ``<p>``, ``<q>`` a point or I-centre
     (``I13``); ``<out>`` a link or a point; ``<output>`` a link or a joint (an
     output: a link, or a slider's joint).  The loader checks every name.
   - ``compare``: how a claim is held against the value (:class:`Compare`):
     ``COUNT`` exact int, ``LABEL`` exact name after ``normalise``, ``POINT``
     ``[x, y]`` within tolerance × size (``infinity=True``, for any mode,
     also reads ``infinity``; the value may then be an :class:`AtInfinity`,
     or ``math.inf`` for a magnitude),
     ``MAGNITUDE`` |claimed| vs |value|, ``SENSE`` signed when the claim says
     cw/ccw else magnitudes, ``RATIO`` signed for a negative claim else
     magnitudes, ``SIGNED`` as is.
   - ``level``: the least analysis the value needs: ``topology`` (no numpy),
     ``mobility``, ``position``, ``velocity``, ``acceleration``.  The whole
     file is solved once, at the highest level any claim needs.
   - ``dimension``: what a claim's unit must measure (a bare number is SI);
     ``also`` lists other dimensions accepted (a stroke: a length or an angle).
2. Write its compute function in :mod:`mech.grading` (the recipe is that
   module's docstring) and add it to ``mech.grading.COMPUTE`` under the same
   pattern.
3. Add a row to cli.md § answers, and a test in ``tests/test_check.py`` whose
   reference value comes from an independent derivation.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Iterator
from collections.abc import Set as AbstractSet
from enum import Enum
from functools import lru_cache

from mech._records import dataclass
from mech.units import Dimension

__all__ = [
    "COUNT_KEYS",
    "JOINT_CLASSES",
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
    "normal_chain",
    "normal_grashof",
    "parse_icentre_name",
    "parse_key",
    "register",
    "unregister",
]

LINK_CLASSES = ("singular", "binary", "ternary", "quaternary", "pentagonal", "hexagonal")
JOINT_CLASSES = ("binary", "ternary", "quaternary")

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
    "<output>": "linkjoint",
}

#: How each kind of name reads in a message ("names unknown point or I-centre 'Q'").
KIND_LABELS = {"icpoint": "point or I-centre", "linkpoint": "link or point", "linkjoint": "link or joint"}


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
    """One row of the table: a key's pattern, how a claim of it is compared, what it needs."""

    pattern: str
    compare: Compare
    level: str
    dimension: Dimension | None
    doc: str = ""
    distinct: bool = False  # the names must differ (icentre.a.b, omega_ratio.a.b)
    infinity: bool = False  # the key may be claimed `infinity` (a point, or a magnitude such as MA)
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
    """A parsed key: its form and the names after it.

    ``kinds`` say what each name must be (``link``, ``point`` …).  The form's
    ``family``, ``compare``, ``level`` and ``dimensions`` are copied onto the key
    when it is parsed (a form never changes): the checker reads them for every
    claim, as plain values.
    """

    key: str
    kind: AnswerKind
    names: tuple[str, ...]
    kinds: tuple[str, ...]
    family: str
    compare: Compare
    level: str
    dimension: Dimension | None
    dimensions: tuple[Dimension, ...]

    @classmethod
    def of(cls, key: str, kind: AnswerKind, names: tuple[str, ...], kinds: tuple[str, ...]) -> AnswerKey:
        return cls(
            key, kind, names, kinds, kind.family, kind.compare, kind.level, kind.dimension, kind.dimensions
        )

    @property
    def is_count(self) -> bool:
        return self.compare is Compare.COUNT


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


def unregister(pattern: str) -> AnswerKind:
    """Remove a key pattern from the registry (a plug-in's, or a test's); KeyError if it is not there."""
    kind = next((k for k in _KINDS if k.pattern == pattern), None)
    if kind is None:
        raise KeyError(pattern)
    _KINDS.remove(kind)
    _BY_HEAD[kind.parts[0]].remove(kind)
    if not _BY_HEAD[kind.parts[0]]:
        del _BY_HEAD[kind.parts[0]]
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
    return AnswerKey.of(key, kind, names, kinds)


_parse_cached = lru_cache(maxsize=4096)(_parse)


def names_by_kind(
    links: Iterable[str],
    joints: Iterable[str],
    points: Iterable[str],
    n_links: int,
    contacts: Iterable[tuple[str, Iterable[str]]] = (),
) -> dict[str, AbstractSet[str]]:
    """The names each placeholder kind accepts in one mechanism (for the loader's checks).

    ``points`` are the named points (joints are points too); I-centres are
    named ``I12`` … for ``n_links`` links, ground first: a lazy set
    (:class:`ICentreNames`), since a 10,000-link file has 50 million of them.
    ``contacts`` are the higher pairs with their links: ``K@cam`` names the cam's
    point at the contact K (DESIGN § 1.2), a point like any other.
    """
    link_names, joint_names = set(links), set(joints)
    point_names = joint_names | set(points)
    point_names |= {f"{joint}@{link}" for joint, on in contacts for link in on}
    return {
        "link": link_names,
        "joint": joint_names,
        "point": point_names,
        "icpoint": ICentreNames(frozenset(point_names), n_links),
        "linkpoint": link_names | point_names,
        "linkjoint": link_names | joint_names,
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


# -- how two labels are compared (LABEL keys' ``normalise``) -----------------------------------
def normal_chain(name: str) -> str:
    """``Four Bar chain``, ``4-bar``, ``fourbar`` → ``four-bar``: one spelling per chain."""
    s = name.strip().lower().replace("_", "-").replace(" ", "-")
    s = re.sub(r"'s\b", "", s)
    s = re.sub(r"-(chain|mechanism|linkage)$", "", s)
    return {"fourbar": "four-bar", "4-bar": "four-bar", "fivebar": "five-bar", "5-bar": "five-bar"}.get(s, s)


def normal_grashof(name: str) -> str:
    """``Crank Rocker``, ``crank_rocker`` → ``crank-rocker``; ``triple rocker`` → ``non-grashof``."""
    s = re.sub(r"[\s_–—]+", "-", name.strip().lower())
    return {
        "triple-rocker": "non-grashof",
        "nongrashof": "non-grashof",
        "drag-link": "double-crank",
        "rocker-crank": "crank-rocker",
        "changepoint": "change-point",
    }.get(s, s)


_D = Dimension
KINDS: tuple[AnswerKind, ...] = (
    AnswerKind("dof", Compare.COUNT, "topology", _D.NUMBER, "Kutzbach's count"),
    AnswerKind("links.count", Compare.COUNT, "topology", _D.NUMBER, "links"),
    *(AnswerKind(f"links.{c}", Compare.COUNT, "topology", _D.NUMBER, f"{c} links") for c in LINK_CLASSES),
    AnswerKind("joints.count", Compare.COUNT, "topology", _D.NUMBER, "joints as written"),
    *(AnswerKind(f"joints.{c}", Compare.COUNT, "topology", _D.NUMBER, f"{c} joints") for c in JOINT_CLASSES),
    AnswerKind("joints.equivalent_binary", Compare.COUNT, "topology", _D.NUMBER, "j of Kutzbach's count"),
    AnswerKind("higher_pairs", Compare.COUNT, "topology", _D.NUMBER, "h of Kutzbach's count"),
    AnswerKind("icentres.count", Compare.COUNT, "topology", _D.NUMBER, "n(n − 1)/2"),
    AnswerKind("mobility", Compare.COUNT, "mobility", _D.NUMBER, "rank of the constraint Jacobian"),
    AnswerKind("chain", Compare.LABEL, "topology", None, "the chain's name", normalise=normal_chain),
    AnswerKind("position.<point>", Compare.POINT, "position", _D.LENGTH, "where a point is, [x, y]"),
    AnswerKind("velocity.<point>", Compare.MAGNITUDE, "velocity", _D.VELOCITY, "speed of a point"),
    AnswerKind("velocity.<point>.<other>", Compare.MAGNITUDE, "velocity", _D.VELOCITY, "relative velocity"),
    AnswerKind("omega.<link>", Compare.SENSE, "velocity", _D.ANGULAR_VELOCITY, "angular velocity"),
    AnswerKind("omega_ratio.<a>.<b>", Compare.RATIO, "velocity", _D.NUMBER, "ω_a/ω_b", distinct=True),
    AnswerKind("sliding.<joint>", Compare.MAGNITUDE, "velocity", _D.VELOCITY, "speed along a slide"),
    AnswerKind("rubbing.<joint>", Compare.MAGNITUDE, "velocity", _D.VELOCITY, "rubbing speed at a pin"),
    AnswerKind("least_speed.<link>", Compare.MAGNITUDE, "velocity", _D.VELOCITY, "least speed on the line"),
    AnswerKind("acceleration.<point>", Compare.MAGNITUDE, "acceleration", _D.ACCELERATION, "acceleration"),
    AnswerKind(
        "acceleration.<point>.<other>",
        Compare.MAGNITUDE,
        "acceleration",
        _D.ACCELERATION,
        "relative acceleration",
    ),
    AnswerKind("alpha.<link>", Compare.SENSE, "acceleration", _D.ANGULAR_ACCELERATION, "angular accel."),
    AnswerKind("coriolis.<joint>", Compare.MAGNITUDE, "acceleration", _D.ACCELERATION, "Coriolis component"),
    AnswerKind(
        "icentre.<a>.<b>",
        Compare.POINT,
        "velocity",
        _D.LENGTH,
        "an I-centre, [x, y] or infinity",
        distinct=True,
        infinity=True,
    ),
    AnswerKind(
        "distance.<p>.<q>",
        Compare.MAGNITUDE,
        "velocity",
        _D.LENGTH,
        "between points (infinity to an I-centre at infinity)",
        distinct=True,
        infinity=True,
    ),
    # linkage properties (DESIGN § 1.1 "Answer keys for linkage properties")
    AnswerKind(
        "grashof",
        Compare.LABEL,
        "topology",
        None,
        "Grashof class of the driven four-bar loop",
        normalise=normal_grashof,
    ),
    AnswerKind(
        "transmission_angle",
        Compare.MAGNITUDE,
        "position",
        _D.ANGLE,
        "coupler–output interior angle at the instant (0–180°)",
    ),
    AnswerKind(
        "transmission_angle.min",
        Compare.MAGNITUDE,
        "position",
        _D.ANGLE,
        "least transmission angle over the cycle",
    ),
    AnswerKind(
        "transmission_angle.max",
        Compare.MAGNITUDE,
        "position",
        _D.ANGLE,
        "greatest transmission angle over the cycle",
    ),
    AnswerKind("time_ratio", Compare.MAGNITUDE, "position", _D.NUMBER, "slow / fast stroke"),
    AnswerKind(
        "time_ratio.<output>",
        Compare.MAGNITUDE,
        "position",
        _D.NUMBER,
        "slow / fast stroke of one output (a link, or a slider's joint)",
    ),
    AnswerKind(
        "stroke.<joint>",
        Compare.MAGNITUDE,
        "position",
        _D.LENGTH,
        "a slider's travel, or a frame pivot's swing",
        also=(_D.ANGLE,),
    ),
    AnswerKind(
        "mechanical_advantage.<out>",
        Compare.MAGNITUDE,
        "velocity",
        _D.NUMBER,
        "output load over input effort (1/m for a point output of a crank); infinity at a dead centre",
        infinity=True,
    ),
    AnswerKind(
        "input_torque",
        Compare.SIGNED,
        "velocity",
        _D.TORQUE,
        "torque on the input link balancing the loads, and the links' inertia and weight (ccw +)",
    ),
    AnswerKind(
        "input_force",
        Compare.SIGNED,
        "velocity",
        _D.FORCE,
        "force on a slider drive balancing the loads, and the links' inertia and weight",
    ),
    # forces (issue 24, DESIGN § 1.4): solved by mech.forces from the position up (level position:
    # the force solve takes the rates and accelerations it needs itself)
    AnswerKind("force.<joint>", Compare.MAGNITUDE, "position", _D.FORCE, "force a pair carries"),
    AnswerKind("force.<joint>.x", Compare.SIGNED, "position", _D.FORCE, "on its second link, x"),
    AnswerKind("force.<joint>.y", Compare.SIGNED, "position", _D.FORCE, "on its second link, y"),
    AnswerKind("shaking_force", Compare.MAGNITUDE, "position", _D.FORCE, "|−Σ m a_G|"),
    AnswerKind(
        "shaking_moment",
        Compare.SENSE,
        "position",
        _D.TORQUE,
        "−Σ (r_G × m a_G + I_G α) about the drive's pivot (ccw +)",
    ),
    AnswerKind("torque.mean", Compare.SENSE, "position", _D.TORQUE, "mean input torque, cycle"),
    AnswerKind(
        "energy.fluctuation",
        Compare.MAGNITUDE,
        "position",
        _D.ENERGY,
        "greatest minus least of ∫(T − T_mean) dθ",
    ),
    AnswerKind("flywheel.inertia", Compare.MAGNITUDE, "position", _D.MOMENT_OF_INERTIA, "ΔE / (ω² C_s)"),
    # cams given by their follower's programme (DESIGN § 1.1): the cam's own analysis answers these
    # (level topology: the linkage solver is never started for them)
    AnswerKind(
        "pressure_angle.<joint>",
        Compare.MAGNITUDE,
        "topology",
        _D.ANGLE,
        "a cam's pressure angle at the drive angle",
    ),
    AnswerKind(
        "pressure_angle.<joint>.max",
        Compare.MAGNITUDE,
        "topology",
        _D.ANGLE,
        "a cam's largest pressure angle over the turn",
    ),
    AnswerKind(
        "displacement.<point>",
        Compare.MAGNITUDE,
        "topology",
        _D.LENGTH,
        "a cam follower's lift from its lowest position (an angle for an oscillating one)",
        also=(_D.ANGLE,),
    ),
)
for _kind in KINDS:
    register(_kind)

#: Keys that claim an integer count, no geometry needed.
COUNT_KEYS = frozenset(k.pattern for k in KINDS if k.compare is Compare.COUNT and k.level == "topology")


def key_forms() -> tuple[str, ...]:
    """Every form a key may take (registered so far), for hints and docs."""
    return tuple(k.pattern for k in _KINDS)


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
