"""The mechanism as the file describes it: immutable, SI, nothing computed.

The loader builds these objects from YAML; every analysis reads them and none
changes them.  They hold exactly what the file says (a length that was not
given is absent, a joint that was not drawn has no ``at``): deciding what
follows from it is the analyses' job.

All lengths are in metres, angles in radians (counter-clockwise from +x),
angular velocities in rad/s with counter-clockwise positive.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import field
from typing import Any

from mech._memo import Memo
from mech._records import dataclass
from mech.errors import Where
from mech.specs import JointSpec, Path, Profile, Profiles, Ref, Vec

__all__ = [
    "Claim",
    "Drive",
    "Flywheel",
    "Joint",
    "Length",
    "Link",
    "Load",
    "Mass",
    "Mechanism",
    "Path",
    "Placement",
    "Point",
    "Ref",
    "Tolerance",
    "Vec",
]


@dataclass(frozen=True, slots=True)
class Placement:
    """How a joint or point is placed, exactly as written.

    ``at``: drawn here in the analysed configuration (global, metres).
    ``near``: a hint only — initial guess and assembly branch.
    ``origin``/``toward`` with ``distance`` (along origin→toward) or ``offset``
    ``(u, v)`` (u along origin→toward, v to its left): rigidly placed relative
    to two points of the same link.  (``origin`` is the file's ``from``.)
    """

    at: Vec | None = None
    near: Vec | None = None
    origin: str | None = None
    toward: str | None = None
    distance: float | None = None
    offset: Vec | None = None

    @property
    def is_relative(self) -> bool:
        return self.origin is not None


@dataclass(frozen=True, slots=True)
class Link:
    """A kinematic link.  ``index`` is its place in the file's order (ground = 0)."""

    name: str
    index: int
    kind: str = "rigid"
    description: str | None = None
    is_ground: bool = False
    where: Where | None = field(default=None, compare=False)


@dataclass(frozen=True, slots=True)
class Joint:
    """A kinematic pair between two or more links, as the file writes it.

    ``type`` is the file's ``type:`` (``revolute``, ``cam`` …): the name of a pair kind
    of :mod:`mech.pairs`, which says what the type means (``mech.pairs.kind_of(joint)``).
    A revolute joint listing k links is one joint of order k, i.e. k − 1
    equivalent binary joints.  What belongs to the joint's type (a pin's
    radius, a slider's path, a gear's radii, a cam's profiles …) is its
    ``spec``, one of the typed specs of :mod:`mech.specs`; ``None``
    stands for the type's empty spec.  The type-specific attributes below
    (``path``, ``normal``, ``radii`` …) read the spec and are ``None`` where
    the type has no such key.
    """

    name: str
    type: str
    links: tuple[str, ...]
    place: Placement = Placement()
    spec: JointSpec | None = None
    closure: str | None = None
    where: Where | None = field(default=None, compare=False)

    # -- the spec's fields, for readers that do not care about the type --------------------
    @property
    def path(self) -> Path | None:
        return getattr(self.spec, "path", None)

    @property
    def point(self) -> str | None:
        return getattr(self.spec, "point", None)

    @property
    def radius(self) -> float | None:
        return getattr(self.spec, "radius", None)

    @property
    def normal(self) -> float | None:
        return getattr(self.spec, "normal", None)

    @property
    def pressure_angle(self) -> float | None:
        return getattr(self.spec, "pressure_angle", None)

    @property
    def radii(self) -> tuple[float | None, float | None] | None:
        return getattr(self.spec, "radii", None)

    @property
    def teeth(self) -> tuple[int, int] | None:
        return getattr(self.spec, "teeth", None)

    @property
    def module(self) -> float | None:
        return getattr(self.spec, "module", None)

    @property
    def internal(self) -> bool:
        return bool(getattr(self.spec, "internal", False))

    @property
    def profiles(self) -> Profiles:
        """Each link's curve (``(link, profile)`` pairs); empty when the pair has none."""
        return getattr(self.spec, "profiles", ())

    @property
    def profile_of(self) -> dict[str, Profile]:
        return dict(self.profiles)

    @property
    def order(self) -> int:
        """How many links meet here: 2 binary, 3 ternary, 4 quaternary …"""
        return len(self.links)

    @property
    def equivalent_binary(self) -> int:
        """Binary joints this joint is worth (a joint of k links is k − 1)."""
        return len(self.links) - 1


@dataclass(frozen=True, slots=True)
class Point:
    """A named point fixed on one link (a coupler point, a lever's far end …)."""

    name: str
    link: str
    place: Placement
    where: Where | None = field(default=None, compare=False)


@dataclass(frozen=True, slots=True)
class Length:
    """The distance between two named joints or points of one link (metres)."""

    a: str
    b: str
    value: float
    where: Where | None = field(default=None, compare=False)


@dataclass(frozen=True, slots=True)
class Drive:
    """One independent input.

    Either a link turning about a ground pivot (``link``, ``angle`` in rad,
    ``omega`` in rad/s, counter-clockwise positive, ``alpha`` in rad/s²,
    ``about`` the pivot joint), or a slider (``joint`` with ``speed`` in m/s
    along its path and ``accel`` in m/s²).  ``None`` means "not given".

    A turning drive's angle, omega and alpha are absolute (measured from the
    ground, like every angle in ``mech``) whatever ``about`` is, unless
    ``relative_to`` names a link: then they are the driven link's minus that
    link's (θ_b − θ_a, ω_b − ω_a, α_b − α_a).
    ``direction`` (``cw``/``ccw``) is the sense as written, kept even without a
    speed (a cam's programme is counted in the sense it turns).  The file's
    ``angle`` of a cam with a programme is its turn from the programme's start
    in the sense it turns; ``angle`` here is that turn counter-clockwise, like
    every angle (negative for a cam turning clockwise).
    """

    link: str | None = None
    joint: str | None = None
    angle: float | None = None
    omega: float | None = None
    alpha: float | None = None
    about: str | None = None
    speed: float | None = None
    accel: float | None = None
    direction: str | None = None
    where: Where | None = field(default=None, compare=False)
    relative_to: str | None = None


@dataclass(frozen=True, slots=True)
class Tolerance:
    """``relative`` (a fraction: 0.02 is 2%) or ``absolute`` (in SI units of the answer)."""

    value: float
    relative: bool = True

    def __str__(self) -> str:
        return f"{self.value * 100:g}%" if self.relative else f"{self.value:g}"


@dataclass(frozen=True, slots=True)
class Load:
    """An external load for mechanical advantage, the input torque and forces (no friction).

    ``target`` names a point or joint (a ``force`` (Fx, Fy) in N, in the
    file's frame) or a link (a ``torque`` in N·m, counter-clockwise positive).
    A load that varies over the cycle gives ``table`` instead: rows of the
    drive's angle (rad) and the force's two components or the torque, read
    linearly between rows and repeated every ``period`` (the table's span: 4π
    for a four-stroke engine).  ``on`` names the link a force at a pin shared
    by two moving links acts on.
    """

    target: str
    force: Vec | None = None
    torque: float | None = None
    where: Where | None = field(default=None, compare=False)
    table: tuple[tuple[float, ...], ...] | None = None
    on: str | None = None

    @property
    def is_force(self) -> bool:
        """A force at a point (else a torque on a link)."""
        return self.force is not None or (self.table is not None and len(self.table[0]) == 3)

    @property
    def period(self) -> float | None:
        """The span of a table's angles, after which it repeats (None for a constant load)."""
        return None if self.table is None else self.table[-1][0] - self.table[0][0]

    def values(self, angle: Any) -> Any:
        """The load at the drive's angles ``angle`` ((K,) rad): (K, 2) for a force, (K,) for a torque.

        A table is read linearly between its rows and repeated with its span (a four-stroke
        engine's 720°); a constant load is the same at every angle.  The one reader of a table,
        for the force solve and the loads' power balance alike (numpy is imported here, when a
        load is read).
        """
        import numpy as np

        k = np.shape(angle)[0]
        if self.table is None:
            if self.force is not None:
                return np.broadcast_to(np.asarray(self.force, float), (k, 2))
            return np.full(k, float(self.torque or 0.0))
        table = np.asarray(self.table, float)
        start, span = table[0, 0], table[-1, 0] - table[0, 0]
        t = start + np.mod(np.fmod(angle - start, span), span) if span > 0 else angle
        cols = [np.interp(t, table[:, 0], table[:, c]) for c in range(1, table.shape[1])]
        return np.stack(cols, axis=1) if len(cols) == 2 else cols[0]


@dataclass(frozen=True, slots=True)
class Mass:
    """A link's mass (kg) at its centre ``centre`` (a point or joint of the link), and its moment
    of inertia about that centre (kg·m²; 0 for a link that only translates or is given none)."""

    link: str
    mass: float
    centre: str
    inertia: float = 0.0
    where: Where | None = field(default=None, compare=False)


@dataclass(frozen=True, slots=True)
class Flywheel:
    """``flywheel: {fluctuation: 2%}``: the total coefficient of fluctuation of speed, a fraction
    ((ω_max − ω_min)/ω_mean: "±1 %" is 0.02)."""

    fluctuation: float
    where: Where | None = field(default=None, compare=False)


ClaimValue = float | Vec | str | int


@dataclass(frozen=True, slots=True)
class Claim:
    """One claimed answer for ``mech check``.

    ``key`` is as written (``omega.rocker``); ``value`` is SI (a float), a point
    ``(x, y)`` in metres, the string ``"infinity"``, an int count, or a name
    (for ``chain``).  ``sense`` is ``"cw"``/``"ccw"`` when the claim states it.
    ``dimension`` is the :class:`mech.units.Dimension` value the key expects.
    """

    key: str
    value: ClaimValue
    dimension: str | None = None
    sense: str | None = None
    tolerance: Tolerance | None = None
    text: str = ""
    where: Where | None = field(default=None, compare=False)
    marks: float | None = None  # ``{value: …, marks: 2}`` in a problem's answers (None: 1 mark)


@dataclass(frozen=True, slots=True)
class Mechanism:
    """A whole mechanism file, validated, in SI.

    ``links`` are in file order (ground wherever the file put it: ``ground``
    names it); I-centres are numbered ground first, then the others in order.
    """

    name: str | None
    path: str
    ground: str
    links: tuple[Link, ...]
    joints: tuple[Joint, ...]
    points: tuple[Point, ...] = ()
    lengths: tuple[Length, ...] = ()
    drives: tuple[Drive, ...] = ()
    answers: tuple[Claim, ...] = ()
    tolerance: Tolerance = Tolerance(0.02)
    length_unit: str = "m"
    angle_unit: str = "deg"
    asks: tuple[str, ...] = ()  # answer keys a student must answer (when `answers` carries no values)
    #: Each question's marks where the file gives them (``asks`` as a mapping, ``marks`` on an
    #: answer); a question not listed is worth 1 (DESIGN § 1.3).
    marks: tuple[tuple[str, float], ...] = ()
    loads: tuple[Load, ...] = ()  # forces at points, torques on links (DESIGN § 1.1 "Loads")
    masses: tuple[Mass, ...] = ()  # links with mass (DESIGN § 1.4); the others are massless
    gravity: Vec | None = None  # m/s², in the file's frame; None: no gravity
    flywheel: Flywheel | None = None
    source: str | None = field(default=None, repr=False, compare=False)
    #: What the analyses derive from this mechanism, kept with it (its compiled constraint system
    #: …): :class:`mech._memo.Memo`, never compared, hashed or pickled.
    memo: Memo = field(default_factory=Memo, init=False, repr=False, compare=False, hash=False)

    # -- lookups -----------------------------------------------------------------
    def marks_of(self, key: str) -> float:
        """What a question is worth: its marks from ``asks`` or ``answers``, else 1."""
        for k, m in self.marks:
            if k == key:
                return m
        return 1.0

    def link(self, name: str) -> Link:
        for link in self.links:
            if link.name == name:
                return link
        raise KeyError(name)

    def joint(self, name: str) -> Joint:
        for joint in self.joints:
            if joint.name == name:
                return joint
        raise KeyError(name)

    def point(self, name: str) -> Point:
        for point in self.points:
            if point.name == name:
                return point
        raise KeyError(name)

    @property
    def label(self) -> str:
        """The mechanism's name, or its file name."""
        return self.name or self.path

    @property
    def moving_links(self) -> tuple[Link, ...]:
        return tuple(link for link in self.links if not link.is_ground)

    @property
    def numbered_links(self) -> tuple[Link, ...]:
        """Links in I-centre numbering order: ground is 1, the others follow in file order."""
        ground = [link for link in self.links if link.is_ground]
        return tuple(ground + [link for link in self.links if not link.is_ground])

    def joints_of(self, link: str) -> tuple[Joint, ...]:
        """The joints a link takes part in (from an index made once: a link at a time over
        every joint made classifying a 10,000-link file take 70 s)."""
        return self.memo.get("joints_of", self._joints_by_link).get(link, ())

    def _joints_by_link(self) -> dict[str, tuple[Joint, ...]]:
        index: dict[str, list[Joint]] = {}
        for j in self.joints:
            for lk in dict.fromkeys(j.links):
                index.setdefault(lk, []).append(j)
        return {lk: tuple(js) for lk, js in index.items()}

    def iter_names(self) -> Iterator[str]:
        yield from (link.name for link in self.links)
        yield from (j.name for j in self.joints)
        yield from (p.name for p in self.points)

    @property
    def has_geometry(self) -> bool:
        """True when the file places anything (so positions may be solvable)."""
        return any(j.place.at is not None for j in self.joints) or any(
            p.place.at is not None for p in self.points
        )
