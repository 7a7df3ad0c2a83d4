"""What a joint says beyond ``type``, ``links`` and its placement, as typed records; and the
references (``Ref``, ``Path``) they are written with.

A :class:`~mech.model.Joint` carries one of these as ``joint.spec``, chosen by
its type (see :data:`mech.pairs.registry.KINDS`), instead of one flat record
of optional fields that mostly do not apply.  All values are SI (metres,
radians), exactly as the file gives them: nothing here is computed.

Profiles (DESIGN § 1.1, "Higher pairs that move") are curves fixed in a link,
given in the drawn configuration:

* :class:`Circle` — ``{circle: {centre: P, radius: r}}`` (an eccentric cam, a roller,
  a wheel, a pitch circle);
* :class:`Line` — ``{line: {through: P, angle: a}}`` or ``{line: {through: P, toward: Q}}``
  (a flat-faced follower, a rack, the ground);
* :class:`Knife` — ``{point: P}`` (a knife edge);
* :class:`Curve` — ``{curve: [[x, y], …]}`` (a closed smooth curve through the points).

These four types are the whole profile interface: anything that makes a profile
(the loader, or a cam programme in :mod:`mech.cam`) produces one of them, and
the kinematics evaluates them (:mod:`mech.kinematics.profiles`).  A cam
programme plugs in through two functions of :mod:`mech.cam`:

``read_program(reader, node, what) -> object``
    reads the ``program`` mapping of a cam joint (``reader`` is the loader's
    node reader: ``reader.number``, ``reader.mapping``, ``reader.problem`` …),
    returning an immutable value stored as :attr:`ContactSpec.program`;
``program_profiles(mech, joint, positions) -> dict[str, Profile]``
    the profiles, keyed by link name, that the programme gives in the drawn
    configuration (``positions``: drawn location name → ``(x, y)`` in metres):
    typically a :class:`Curve` on the cam and a :class:`Knife`, :class:`Circle`
    (roller) or :class:`Line` (flat face) on the follower.

This module sits below :mod:`mech.model` (which holds a joint's spec and re-exports
``Vec``, ``Ref`` and ``Path``) and imports nothing of mech's but :mod:`mech._records`.
"""

from __future__ import annotations

from mech._records import dataclass

__all__ = [
    "BareSpec",
    "Circle",
    "ContactSpec",
    "Curve",
    "GearSpec",
    "JointSpec",
    "Knife",
    "Line",
    "Path",
    "PathSpec",
    "PinSpec",
    "Profile",
    "Profiles",
    "Ref",
    "RollingSpec",
    "SlideSpec",
    "Vec",
]


Vec = tuple[float, float]


@dataclass(frozen=True, slots=True)
class Ref:
    """A location named in a file: coordinates ``xy`` or the name of a joint or point."""

    xy: Vec | None = None
    name: str | None = None

    def __str__(self) -> str:
        return self.name if self.name is not None else f"({self.xy[0]:g}, {self.xy[1]:g})"  # type: ignore[index]


@dataclass(frozen=True, slots=True)
class Path:
    """A straight line fixed in a guide link: through a point, at an angle or toward a point.

    On a moving guide, ``angle`` is the line's direction in the analysed
    (drawn) configuration; ``toward`` keeps it fixed to the guide's points.
    """

    through: Ref
    angle: float | None = None
    toward: Ref | None = None


@dataclass(frozen=True, slots=True)
class PathSpec:
    """A path pair as the layout resolved it: ``point`` of ``slider`` runs on ``path`` fixed in ``guide``."""

    joint: str
    type: str
    slider: str
    guide: str
    point: str
    path: Path


@dataclass(frozen=True, slots=True)
class Circle:
    """A circle fixed in its link: ``centre`` a point of the link (or coordinates as drawn)."""

    centre: Ref
    radius: float


@dataclass(frozen=True, slots=True)
class Line:
    """A straight line fixed in its link, through ``through`` at ``angle`` or toward ``toward``.

    ``angle`` is the line's direction in the drawn configuration.
    """

    through: Ref
    angle: float | None = None
    toward: Ref | None = None


@dataclass(frozen=True, slots=True)
class Knife:
    """A knife edge: the profile is the single point ``point`` of the link."""

    point: Ref


@dataclass(frozen=True, slots=True)
class Curve:
    """A closed smooth curve through ``points`` (global coordinates, drawn configuration).

    The kinematics interpolates a periodic cubic spline through them (see
    :mod:`mech.kinematics.profiles` for why), so a cam profile needs no more
    points than its shape does.
    """

    points: tuple[Vec, ...]


Profile = Circle | Line | Knife | Curve

#: ``(link, profile)`` pairs in the file's order (a tuple keeps the spec hashable).
Profiles = tuple[tuple[str, Profile], ...]


@dataclass(frozen=True, slots=True)
class BareSpec:
    """A kind with no keys of its own (screw, spherical)."""


@dataclass(frozen=True, slots=True)
class PinSpec:
    """A revolute joint: ``radius`` is the pin's radius (m), for rubbing velocity."""

    radius: float | None = None


@dataclass(frozen=True, slots=True)
class SlideSpec:
    """A prismatic or slot joint: ``point`` of the first link runs on ``path`` fixed in the second."""

    path: Path | None = None
    point: str | None = None


@dataclass(frozen=True, slots=True)
class ContactSpec:
    """A cam or contact pair.

    ``normal`` (rad) is the common normal's angle at the instant drawn;
    ``profiles`` each link's curve (then the pair moves); ``program`` a cam's
    follower programme, as :func:`mech.cam.read_program` read it.
    """

    normal: float | None = None
    profiles: Profiles = ()
    program: object | None = None


@dataclass(frozen=True, slots=True)
class RollingSpec:
    """A pure-rolling pair: ``radii`` (m; ``None`` for a straight line) or ``profiles``."""

    radii: tuple[float | None, float | None] | None = None
    profiles: Profiles = ()


@dataclass(frozen=True, slots=True)
class GearSpec:
    """A gear pair: pitch ``radii`` or ``teeth`` with ``module``, ``pressure_angle``, ``internal``."""

    normal: float | None = None
    pressure_angle: float | None = None
    radii: Vec | None = None
    teeth: tuple[int, int] | None = None
    module: float | None = None
    internal: bool = False
    profiles: Profiles = ()

    @property
    def pitch_radii(self) -> Vec | None:
        """``radii``, or ``teeth × module / 2``; None when the file gives neither, or a rack's (a null radius)."""
        if self.radii is not None:
            return None if None in self.radii else self.radii
        if self.teeth is not None and self.module is not None:
            return (self.teeth[0] * self.module / 2.0, self.teeth[1] * self.module / 2.0)
        return None


JointSpec = BareSpec | PinSpec | SlideSpec | ContactSpec | RollingSpec | GearSpec
