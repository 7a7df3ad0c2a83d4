"""Frozen results of a kinematic solve: link states, point queries, mobility.

Everything is SI (m, rad, m/s, rad/s, m/s², rad/s²), angles counter-clockwise
from +x, angular quantities counter-clockwise positive.  Mappings are
read-only views and vectors are tuples, so one analysis cannot corrupt what
another reads.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from types import MappingProxyType
from typing import Any

from mech._records import dataclass
from mech.errors import InputError
from mech.model import Drive

__all__ = ["Fields", "JointGeom", "Kinematics", "LinkState", "Mobility"]

Vec = tuple[float, float]

_LEVELS = ("position", "velocity", "acceleration")


@dataclass(frozen=True, slots=True)
class LinkState:
    """Position, velocity and acceleration of one rigid link.

    ``origin`` is a point fixed in the link (its ground pivot or first joint),
    ``angle`` the direction of its reference line (origin → its next joint;
    a slider's path direction) in [0, 2π).  ``velocity``/``acceleration`` are
    those of ``origin``; ``omega``/``alpha`` counter-clockwise positive.
    Fields of a level not solved are None.
    """

    name: str
    origin: Vec
    angle: float
    velocity: Vec | None = None
    omega: float | None = None
    acceleration: Vec | None = None
    alpha: float | None = None

    def velocity_at(self, point: Vec) -> Vec:
        """Velocity (m/s) of the point of this link at global ``point`` (m): v_O + ω × r."""
        if self.velocity is None or self.omega is None:
            raise InputError(f"velocities of {self.name} were not solved (ask for level='velocity')")
        rx, ry = point[0] - self.origin[0], point[1] - self.origin[1]
        return (self.velocity[0] - self.omega * ry, self.velocity[1] + self.omega * rx)

    def acceleration_at(self, point: Vec) -> Vec:
        """Acceleration (m/s²) of the point of this link at ``point``: a_O + α × r − ω² r."""
        if self.acceleration is None or self.alpha is None or self.omega is None:
            raise InputError(f"accelerations of {self.name} were not solved (ask for level='acceleration')")
        rx, ry = point[0] - self.origin[0], point[1] - self.origin[1]
        w2 = self.omega * self.omega
        return (
            self.acceleration[0] - self.alpha * ry - w2 * rx,
            self.acceleration[1] + self.alpha * rx - w2 * ry,
        )


@dataclass(frozen=True, slots=True)
class Mobility:
    """How many ways a mechanism can move, counted two ways.

    Attributes
    ----------
    kutzbach
        ``3(l − 1) − 2j − h`` from the file's links and pairs.
    numeric
        ``3n − rank Φ_q`` at the drawn configuration (n moving links): the true
        mobility, which sees what Kutzbach's count misses (a double
        parallelogram has kutzbach 0 and numeric 1).  None without geometry.
    condition
        Largest over smallest non-zero singular value of Φ_q: how far the
        configuration is from losing a constraint (large: near a toggle).  For a
        large chain solved block by block (:mod:`mech.kinematics.blocks`), the
        largest condition number of a block of Φ_q with its drive rows, which
        is what decides a toggle there (an SVD of the whole is cubic in the chain).
    free
        Moving links that can move with no drive held: the links the null
        space of Φ_q touches.
    locked
        Moving links that cannot move at all (a rigid structure with ground).
    redundant
        Constraint equations that repeat others (rows − rank): over-constraint.
    notes
        Remarks (a count that disagrees, the configuration used).
    """

    kutzbach: int
    numeric: int | None
    condition: float
    free: tuple[str, ...] = ()
    locked: tuple[str, ...] = ()
    redundant: int = 0
    notes: tuple[str, ...] = ()

    def describe(self) -> str:
        """One line for reports: the numeric mobility and why it differs from Kutzbach's."""
        if self.numeric is None:
            return "not computed (the file has no geometry)"
        text = f"{self.numeric} (3n − rank Φq)"
        if self.numeric == self.kutzbach:
            return text + ", as Kutzbach's count"
        if self.numeric > self.kutzbach:
            why = f"{self.redundant} redundant constraint(s)" if self.redundant else "special geometry"
            return text + f"; Kutzbach's {self.kutzbach} misses {why}: it moves"
        return text + f"; below Kutzbach's {self.kutzbach}: singular here (condition {self.condition:.3g})"


@dataclass(frozen=True, slots=True)
class JointGeom:
    """What joint queries need about one joint in the analysed configuration.

    ``point`` names the location of the pair (a revolute's pin, a slider's point,
    a contact point) and ``at`` is where it is; ``direction`` a unit vector: a path's direction, or a
    contact's common tangent (normal turned +90°).
    """

    name: str
    type: str
    links: tuple[str, ...]
    point: str | None = None
    direction: Vec | None = None
    radius: float | None = None
    at: Vec | None = None  # where the pair acts in this configuration, m


class Fields:
    """The named mappings of a :class:`Kinematics`, made together from the solve's lean state.

    ``size`` may be left None and measured on first use (``measure``): it is
    the largest distance between two joints, the one quantity that grows with
    the square of the number of points.
    """

    __slots__ = ("carriers", "joint_names", "joints", "links", "positions", "size")

    def __init__(
        self,
        positions: Mapping[str, Vec],
        links: Mapping[str, LinkState],
        carriers: Mapping[str, tuple[str, ...]],
        joints: Mapping[str, JointGeom],
        size: float | None = None,
        joint_names: frozenset[str] = frozenset(),
    ) -> None:
        self.positions, self.links, self.carriers, self.joints = positions, links, carriers, joints
        self.size, self.joint_names = size, joint_names

    def measure(self) -> float:
        """Largest distance between two joints (all located points if fewer than two joints)."""
        pts = [p for n, p in self.positions.items() if n in self.joint_names]
        if len(pts) < 2:
            pts = list(self.positions.values())
        if len(pts) > 64:  # all pairs, but in one array operation
            import numpy as np

            xy = np.asarray(pts)
            best = 0.0
            for k in range(0, len(pts), 256):
                d = xy[k : k + 256, None, :] - xy[None, :, :]
                best = max(best, float(np.sqrt(np.max(np.einsum("ijk,ijk->ij", d, d)))))
            return best
        return max((math.dist(a, b) for k, a in enumerate(pts) for b in pts[k + 1 :]), default=0.0)


class Kinematics:
    """Positions, velocities and accelerations of a mechanism at one instant.

    Build it with :func:`mech.kinematics.solve`.  Points are looked up by
    name; a link's state gives the velocity of any point fixed in it.

    The solve keeps its lean state (the scaled coordinates, or the closed
    form's flat output) and the named mappings below are built from it on
    first use, once: a caller who reads one link's ω does not pay for every
    point, joint and the size.  Read-only: no attribute can be set.

    Attributes
    ----------
    mechanism
        The mechanism's label (name or file).
    level
        ``position``, ``velocity`` or ``acceleration``: how far it was solved.
    positions
        Every joint with a location and every named point → (x, y), m.
    links
        Every link (ground included) → :class:`LinkState`.
    size
        The mechanism's characteristic length: largest distance between two
        joints in this configuration, m.
    mobility
        :class:`Mobility` at the drawn configuration.
    notes
        Branch choices made by rule, and warnings.
    drives
        The drives used, after command-line overrides: ``angle`` filled in
        from the drawing where the file gave none, ``omega`` signed
        (counter-clockwise positive), ``alpha`` 0 where not given.
    carriers
        Location → the links it is fixed in (empty for a contact point).
    joints
        Joint name → :class:`JointGeom`.
    """

    __slots__ = ("_build", "_fields", "_notes", "drives", "ground", "level", "mechanism", "mobility")

    mechanism: str
    level: str
    mobility: Mobility
    drives: tuple[Drive, ...]
    ground: str
    _notes: tuple[str, ...] | Callable[[], tuple[str, ...]]
    _build: Callable[[], Fields] | None
    _fields: Fields | None

    def __init__(
        self,
        mechanism: str,
        level: str,
        positions: Mapping[str, Vec],
        links: Mapping[str, LinkState],
        size: float,
        mobility: Mobility,
        notes: tuple[str, ...],
        drives: tuple[Drive, ...],
        carriers: Mapping[str, tuple[str, ...]],
        joints: Mapping[str, JointGeom],
        ground: str,
    ) -> None:
        fields = Fields(positions, links, carriers, joints, size)
        self._init(mechanism, level, mobility, drives, ground, notes, None, fields)

    def _init(
        self,
        mechanism: str,
        level: str,
        mobility: Mobility,
        drives: tuple[Drive, ...],
        ground: str,
        notes: tuple[str, ...] | Callable[[], tuple[str, ...]],
        build: Callable[[], Fields] | None,
        fields: Fields | None,
    ) -> None:
        setter = object.__setattr__
        setter(self, "mechanism", mechanism)
        setter(self, "level", level)
        setter(self, "mobility", mobility)
        setter(self, "drives", drives)
        setter(self, "ground", ground)
        setter(self, "_notes", notes)
        setter(self, "_build", build)
        setter(self, "_fields", fields)

    @classmethod
    def lazy(
        cls,
        mechanism: str,
        level: str,
        mobility: Mobility,
        drives: tuple[Drive, ...],
        ground: str,
        notes: tuple[str, ...] | Callable[[], tuple[str, ...]],
        build: Callable[[], Fields],
    ) -> Kinematics:
        """A result whose named mappings (and notes, when a callable) are made by ``build`` on first use."""
        self = cls.__new__(cls)
        self._init(mechanism, level, mobility, drives, ground, notes, build, None)
        return self

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError(f"Kinematics is read-only (cannot set {name})")

    def __delattr__(self, name: str) -> None:
        raise AttributeError(f"Kinematics is read-only (cannot delete {name})")

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickle the built result as plain dicts (the lean state refers to compiled code)."""
        f = self._all()
        return (
            _unpickle,
            (
                self.mechanism,
                self.level,
                dict(f.positions),
                dict(f.links),
                self.size,
                self.mobility,
                self.notes,
                self.drives,
                dict(f.carriers),
                dict(f.joints),
                self.ground,
            ),
        )

    def __repr__(self) -> str:
        return f"Kinematics({self.mechanism!r}, level={self.level!r})"

    def _all(self) -> Fields:
        fields = self._fields
        if fields is None:
            assert self._build is not None
            fields = self._build()
            object.__setattr__(self, "_fields", fields)
            object.__setattr__(self, "_build", None)
        return fields

    @property
    def positions(self) -> Mapping[str, Vec]:
        return self._all().positions

    @property
    def links(self) -> Mapping[str, LinkState]:
        return self._all().links

    @property
    def carriers(self) -> Mapping[str, tuple[str, ...]]:
        return self._all().carriers

    @property
    def joints(self) -> Mapping[str, JointGeom]:
        return self._all().joints

    @property
    def size(self) -> float:
        f = self._all()
        if f.size is None:
            f.size = f.measure()
        return f.size

    @property
    def notes(self) -> tuple[str, ...]:
        notes = self._notes
        if callable(notes):
            notes = notes()
            object.__setattr__(self, "_notes", notes)
        return notes

    # -- helpers -----------------------------------------------------------------
    def _need(self, level: str) -> None:
        if _LEVELS.index(self.level) < _LEVELS.index(level):
            raise InputError(f"{level}s were not solved (solve with level={level!r})")

    def _at_link(self, name: str) -> tuple[JointGeom, str] | None:
        """``<joint>@<link>`` (DESIGN § 1.2): the joint and the link whose point at its contact is meant.

        None for a plain name.  The joint's point now is its ``at`` (a higher pair's contact
        point, a gear's pitch point, a pin, a slider's point); ``link`` must be one it joins.
        """
        if "@" not in name:
            return None
        joint, _, link = name.partition("@")
        j = self.joints.get(joint)
        if j is None:
            raise InputError(f"{name}: no joint named {joint}", hint=f"joints: {', '.join(self.joints)}")
        if link not in j.links:
            either = " or ".join(f"{joint}@{lk}" for lk in j.links)
            raise InputError(f"{name}: {link} is not a link of joint {joint}", hint=f"say {either}")
        if j.at is None:
            raise InputError(f"{name}: joint {joint} has no point in this configuration")
        return j, link

    def position(self, name: str) -> Vec:
        """Where a point is (m): a named point or joint, or ``<joint>@<link>``, that link's point at the
        joint's contact now (where the follower touches the cam, the pitch point of a gear)."""
        return self._where(name)

    def _where(self, name: str) -> Vec:
        pair = self._at_link(name)
        if pair is not None:
            return pair[0].at  # type: ignore[return-value]
        try:
            return self.positions[name]
        except KeyError:
            if name in self.joints:
                j = self.joints[name]
                raise InputError(
                    f"joint {name} is a {j.type} joint with no point of its own"
                    + (f"; its point is {j.point}" if j.point else ""),
                    hint=f"use sliding({name!r}) for the speed along it",
                ) from None
            known = ", ".join(sorted(self.positions))
            raise InputError(f"no point named {name}", hint=f"known points: {known}") from None

    def _state(self, link: str) -> LinkState:
        try:
            return self.links[link]
        except KeyError:
            raise InputError(f"no link named {link}", hint=f"links: {', '.join(self.links)}") from None

    def _choose(self, name: str, link: str | None, what: str) -> LinkState:
        """The link whose point at ``name`` is meant: named (``K@cam``), given, or the unique carrier."""
        pair = self._at_link(name)
        if pair is not None:
            if link is not None and link != pair[1]:
                raise InputError(f"{name} is a point of {pair[1]}, not of {link}")
            return self._state(pair[1])
        if link is not None:
            return self._state(link)
        carriers = self.carriers.get(name, ())
        if carriers:
            moving = [c for c in carriers if c != self.ground]
            return self._state(moving[0] if moving else carriers[0])
        joint = self.joints.get(name)
        choices = joint.links if joint else tuple(self.links)
        raise InputError(
            f"{name} is a contact point: the {what} of the points of {' and '.join(choices)} there differ",
            hint=f"say whose point is meant: {name}@{choices[0]} or {name}@{choices[-1]} "
            "(the point of that link at the contact; mech's tables list both)",
        )

    # -- queries -----------------------------------------------------------------
    def velocity(self, name: str, link: str | None = None) -> Vec:
        """Absolute velocity (m/s) of a point.

        ``name`` may be ``<joint>@<link>``: that link's point at the joint's contact now
        (DESIGN § 1.2: ``K@cam``, ``K@follower``).  ``link`` picks the link whose
        coincident point is meant: needed only at a contact point of a higher pair (cam, gear, contact, rolling) whose
        two links move differently there; any link may be named, giving the
        velocity of that link's point coincident with ``name`` (for a slotted
        lever, the lever's point under the slider).
        """
        self._need("velocity")
        p = self._where(name)
        if link is None and "@" not in name and not self.carriers.get(name, ()):
            joint = self.joints.get(name)
            if joint is not None:  # rolling: both agree
                va = self._state(joint.links[0]).velocity_at(p)
                vb = self._state(joint.links[1]).velocity_at(p)
                spin = max(abs(st.omega or 0.0) for st in self.links.values()) * self.size
                scale = max(math.hypot(*va), math.hypot(*vb), spin)
                if math.hypot(va[0] - vb[0], va[1] - vb[1]) <= 1e-9 * scale:
                    return va
        return self._choose(name, link, "velocities").velocity_at(p)

    def acceleration(self, name: str, link: str | None = None) -> Vec:
        """Absolute acceleration (m/s²) of a point; ``link`` as in :meth:`velocity`."""
        self._need("acceleration")
        return self._choose(name, link, "accelerations").acceleration_at(self._where(name))

    def relative_velocity(
        self, a: str, b: str, *, link_a: str | None = None, link_b: str | None = None
    ) -> Vec:
        """``v_a − v_b`` (m/s): the vector **ba** of the velocity polygon ("velocity of a relative to b")."""
        va, vb = self.velocity(a, link_a), self.velocity(b, link_b)
        return (va[0] - vb[0], va[1] - vb[1])

    def relative_acceleration(
        self, a: str, b: str, *, link_a: str | None = None, link_b: str | None = None
    ) -> Vec:
        """``a_a − a_b`` (m/s²)."""
        aa, ab = self.acceleration(a, link_a), self.acceleration(b, link_b)
        return (aa[0] - ab[0], aa[1] - ab[1])

    def _joint(self, name: str, roles: tuple[str, ...], what: str) -> JointGeom:
        """The joint ``name``, whose kind must play one of ``roles`` (pin, path, contact) for ``what``."""
        from mech.pairs import KINDS, kind_of

        j = self.joints.get(name)
        if j is None:
            raise InputError(f"no joint named {name}", hint=f"joints: {', '.join(self.joints)}")
        if kind_of(j.type).role not in roles:
            types = [t for t, k in KINDS.items() if k.role in roles]
            raise InputError(f"{what} needs a {' or '.join(types)} joint; {name} is {j.type}")
        return j

    def sliding(self, joint: str) -> float:
        """Speed (m/s) of sliding at a joint, signed along its direction.

        Prismatic or slot: the slider point's velocity relative to the guide,
        along the path (``through → toward``, or ``angle``).  Cam, contact or
        gear: the slip along the common tangent (normal turned +90°), first
        link relative to the second.
        """
        self._need("velocity")
        j = self._joint(joint, ("path", "contact"), "sliding")
        if j.at is None:
            raise InputError(f"joint {joint} has no contact point in this configuration")
        p = j.at
        a, b = j.links
        va = self._state(a).velocity_at(p)
        vb = self._state(b).velocity_at(p)
        u = j.direction or (1.0, 0.0)
        return (va[0] - vb[0]) * u[0] + (va[1] - vb[1]) * u[1]

    def rubbing(self, joint: str) -> float:
        """Rubbing velocity (m/s) at a pin: ``|ω_i − ω_j| · radius``.

        For a pin joining more than two links, the largest over all pairs
        (the pin rubs fastest in the bearing that turns fastest relative to it).
        """
        self._need("velocity")
        j = self._joint(joint, ("pin",), "rubbing")
        if j.radius is None:
            raise InputError(f"joint {joint} has no radius", hint="add radius: (pin radius) to the joint")
        omegas = [self._state(lk).omega or 0.0 for lk in j.links]
        return max(abs(a - b) for a in omegas for b in omegas) * j.radius

    def sliding_acceleration(self, joint: str) -> float:
        """Acceleration (m/s²) of sliding at a prismatic or slot joint, signed along its path.

        The slider point's acceleration relative to the coincident point of the
        guide, less the Coriolis term: ``a_P − a_P' − 2 ω × v_slide = s̈ u``
        (the path is straight, so nothing is left across it).
        """
        self._need("acceleration")
        j = self._joint(joint, ("path",), "sliding acceleration")
        if j.at is None:
            raise InputError(f"joint {joint} has no point on its path in this configuration")
        slider, guide = j.links
        a_s = self._state(slider).acceleration_at(j.at)
        a_g = self._state(guide).acceleration_at(j.at)
        cor = self.coriolis(joint)
        u = j.direction or (1.0, 0.0)
        return (a_s[0] - a_g[0] - cor[0]) * u[0] + (a_s[1] - a_g[1] - cor[1]) * u[1]

    def coriolis(self, joint: str) -> Vec:
        """Coriolis acceleration (m/s²) at a prismatic or slot joint: ``2 ω_guide × v_slide``.

        It is the term by which the slider point's acceleration differs from
        that of the coincident guide point, beyond the sliding acceleration
        along the path: ``a_P = a_P' + a_slide·u + 2 ω × v_slide``.
        """
        self._need("velocity")
        j = self._joint(joint, ("path",), "coriolis")
        w = self._state(j.links[1]).omega or 0.0
        s = self.sliding(joint)
        u = j.direction or (1.0, 0.0)
        return (-2.0 * w * s * u[1], 2.0 * w * s * u[0])


def _unpickle(*fields: Any) -> Kinematics:
    """A pickled :class:`Kinematics` back, its mappings read-only again."""
    mechanism, level, positions, links, size, mobility, notes, drives, carriers, joints, ground = fields
    ro = MappingProxyType
    return Kinematics(
        mechanism,
        level,
        ro(positions),
        ro(links),
        size,
        mobility,
        notes,
        drives,
        ro(carriers),
        ro(joints),
        ground,
    )
