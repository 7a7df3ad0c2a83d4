"""The geometry of one instant, and the I-centres (or lines) it gives by inspection.

Kennedy's construction needs only the geometry at the instant: where the pins
are, which way each slider's path runs, where each higher pair touches and
along which normal.  :class:`Instant` holds exactly that, in metres, so the
whole construction is a pure function of it and can be tested with geometry
built by hand; :func:`instant_of` reads it from a mechanism and its solved
positions.

The inspection rules (lecture notes 002, §6.4; Khurmi & Gupta, *Theory of
Machines*, §6.6), each said by its pair kind (:meth:`mech.pairs.base.PairKind.inspect`):

* a pin is the I-centre of the links it joins — a ternary pin gives three;
* a slider on a straight path: the I-centre lies at infinity perpendicular to
  the path, whether the guide is the frame or a moving link;
* pure rolling: the point of contact;
* a cam, gear or other point contact: the I-centre lies *somewhere on the
  common normal* — a line, not a point; Kennedy finishes it;
* a pin in a straight slot: on the normal to the slot through the pin centre.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import field
from typing import TYPE_CHECKING, Any, Literal

from mech._records import dataclass
from mech.icentres.homogeneous import Frame, Hom, ideal, line_along, unit
from mech.model import Joint, Mechanism
from mech.pairs import kind_of

if TYPE_CHECKING:  # pragma: no cover
    from mech.kinematics import Kinematics

__all__ = ["Contact", "Fact", "Instant", "Pin", "Slide", "facts", "instant_of"]

Vec = tuple[float, float]

#: Accuracy assumed for a solved position, relative to the mechanism's size:
#: the solver's default Newton tolerance.  It seeds the error estimates that
#: decide whether two Kennedy lines are too close to coincident to meet.
POSITION_NOISE = 1e-12


@dataclass(frozen=True, slots=True)
class Pin:
    """A revolute joint at ``at`` (m) joining ``links`` (two or more)."""

    joint: str
    links: tuple[str, ...]
    at: Vec


@dataclass(frozen=True, slots=True)
class Slide:
    """A straight path: ``slider`` slides along unit ``direction`` fixed in ``guide``.

    ``slot`` is True for a pin in a slot (``at`` is then the pin centre and
    the pin may also turn); False for a prismatic pair (no relative turning).
    """

    joint: str
    slider: str
    guide: str
    direction: Vec
    at: Vec | None = None
    slot: bool = False


@dataclass(frozen=True, slots=True)
class Contact:
    """A higher pair touching at ``at`` (m): rolling, or sliding along a common normal.

    ``normal`` is the common normal's unit direction (None for pure rolling,
    whose I-centre is the contact point itself).
    """

    joint: str
    type: str
    links: tuple[str, str]
    at: Vec
    normal: Vec | None = None


@dataclass(frozen=True, slots=True)
class Instant:
    """Everything Kennedy needs about one instant of a mechanism (metres).

    Attributes
    ----------
    links
        Link names in I-centre numbering order: ground first (= 1), then the
        others in file order.
    frame
        The mechanism's centre and size, which turn metres into size units.
    pins, slides, contacts
        The pairs, as located at the instant.
    """

    links: tuple[str, ...]
    frame: Frame
    pins: tuple[Pin, ...] = ()
    slides: tuple[Slide, ...] = ()
    contacts: tuple[Contact, ...] = ()

    def number(self, link: str) -> int:
        """The link's I-centre number (ground = 1)."""
        return self.links.index(link) + 1


@dataclass(frozen=True, slots=True)
class Fact:
    """What inspection says about one pair of links.

    ``pair`` are 0-based link indices (i < j); ``hom`` is a unit point or line
    in size units; ``kind`` says which; ``label`` how it was found ("pin B",
    "normal at contact"); ``err`` an estimate of its error (chordal, size
    units) that later steps propagate.
    """

    pair: tuple[int, int]
    kind: Literal["point", "line"]
    hom: Hom
    label: str
    primary: bool
    err: float = POSITION_NOISE
    xy: Vec | None = None  # the exact position (m) of a finite point, to report it unrounded


def _pair(i: int, j: int) -> tuple[int, int]:
    return (i, j) if i < j else (j, i)


def facts(instant: Instant) -> tuple[Fact, ...]:
    """The inspection rules applied to every pair of the instant.

    Returns points (pins, sliders at infinity, rolling contacts) and lines
    (common normals of cams, gears and contacts; normals to slots), in file
    order.

    Examples
    --------
    >>> inst = Instant(("frame", "crank"), Frame((0.0, 0.0), 1.0), pins=(Pin("A", ("frame", "crank"), (0.0, 0.0)),))
    >>> facts(inst)[0].label
    'pin A'
    """
    index = {name: k for k, name in enumerate(instant.links)}
    f = instant.frame
    out: list[Fact] = []
    for pin in instant.pins:
        ids = [index[lk] for lk in pin.links]
        for a in range(len(ids)):
            for b in range(a + 1, len(ids)):
                if ids[a] != ids[b]:
                    out.append(
                        Fact(
                            _pair(ids[a], ids[b]),
                            "point",
                            unit(f.hom(pin.at)),
                            f"pin {pin.joint}",
                            True,
                            xy=pin.at,
                        )
                    )
    for s in instant.slides:
        pair = _pair(index[s.slider], index[s.guide])
        ux, uy = s.direction
        if not s.slot:
            # Perpendicular to the path, at infinity: the slider translates relative to the guide.
            out.append(
                Fact(pair, "point", unit(ideal((-uy, ux))), f"slider {s.joint}: ⟂ path at infinity", True)
            )
        elif s.at is not None:
            normal = line_along(f.hom(s.at), (-uy, ux))
            out.append(Fact(pair, "line", unit(normal), f"normal to slot {s.joint}", False))
    for c in instant.contacts:
        pair = _pair(index[c.links[0]], index[c.links[1]])
        if c.normal is None:
            out.append(Fact(pair, "point", unit(f.hom(c.at)), f"rolling contact {c.joint}", True, xy=c.at))
        else:
            out.append(
                Fact(pair, "line", unit(line_along(f.hom(c.at), c.normal)), f"normal at {c.joint}", False)
            )
    return tuple(out)


# -- reading an instant from a solved mechanism -------------------------------------------
def _angle(a: float) -> Vec:
    return (math.cos(a), math.sin(a))


def _unit2(v: Vec) -> Vec | None:
    n = math.hypot(v[0], v[1])
    return None if n == 0.0 else (v[0] / n, v[1] / n)


def _centre(positions: Sequence[Vec]) -> Vec:
    if not positions:
        return (0.0, 0.0)
    return (
        math.fsum(p[0] for p in positions) / len(positions),
        math.fsum(p[1] for p in positions) / len(positions),
    )


def instant_of(mech: Mechanism, kin: Kinematics) -> Instant:
    """The geometry of ``mech`` at the instant ``kin`` was solved for.

    Pin and contact positions come from ``kin.positions``; a path's direction
    and a contact's common tangent from ``kin.joints`` (the solver turns a path
    on a moving guide with its guide), falling back to the file's ``angle`` or
    ``normal`` as drawn.

    Parameters
    ----------
    mech
        The mechanism.
    kin
        A solve of it at any level (positions suffice).
    """
    positions: Mapping[str, Vec] = kin.positions
    joints = getattr(kin, "joints", {}) or {}
    links = tuple(lk.name for lk in mech.numbered_links)
    located = [p for name, p in positions.items() if name in {j.name for j in mech.joints}] or list(
        positions.values()
    )
    frame = Frame(_centre(located), kin.size if kin.size > 0 else 1.0)
    seen = _Seen(mech, positions, joints)
    for j in mech.joints:
        kind_of(j).inspect(seen, j)
    return Instant(links, frame, tuple(seen.pins), tuple(seen.slides), tuple(seen.contacts))


@dataclass
class _Seen:
    """What the inspection rules read (the solved instant) and what they find (:class:`InstantView`)."""

    mech: Mechanism
    positions: Mapping[str, Vec]
    joints: Mapping[str, Any]
    pins: list[Pin] = field(default_factory=list)
    slides: list[Slide] = field(default_factory=list)
    contacts: list[Contact] = field(default_factory=list)

    def at(self, j: Joint) -> Vec | None:
        """Where the pair acts now: a higher pair's contact (``JointGeom.at``), not the follower's
        own point its name stands for (DESIGN § 1.2: a flat face's point on its axis is off the
        common normal), else the joint's point."""
        geom = self.joints.get(j.name)
        if geom is not None and geom.at is not None:
            return geom.at  # type: ignore[no-any-return]
        return self.positions.get(geom.point if geom is not None and geom.point else j.name)

    def direction(self, j: Joint) -> Vec | None:
        geom = self.joints.get(j.name)
        return geom.direction if geom is not None else None

    def pin(self, joint: str, links: tuple[str, ...], at: Vec) -> None:
        self.pins.append(Pin(joint, links, at))

    def slide(self, joint: str, slider: str, guide: str, direction: Vec, at: Vec | None, turns: bool) -> None:
        self.slides.append(Slide(joint, slider, guide, direction, at, slot=turns))

    def contact(self, joint: str, links: tuple[str, str], at: Vec, normal: Vec | None = None) -> None:
        self.contacts.append(Contact(joint, self.mech.joint(joint).type, links, at, normal))
