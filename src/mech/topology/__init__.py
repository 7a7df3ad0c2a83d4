"""Counting and classifying, as the lecture notes do — pure Python, no numpy.

* Links by how many joints they take part in: singular (1), binary (2),
  ternary (3), quaternary (4), pentagonal (5), hexagonal (6) …
* Joints by how many links meet there: binary (2), ternary (3) …; a joint of
  k links is worth k − 1 binary joints.
* Kinematic pairs by relative motion, by contact (lower / higher) and by
  closure (self-closed / force-closed).
* Degrees of freedom by Kutzbach, n = 3(l − 1) − 2j − h, with l links (ground
  included), j equivalent binary joints (lower pairs; rolling without slip
  counts here) and h higher pairs; and Grübler's criterion 3l − 2j − 4 = 0
  for a constrained mechanism of lower pairs only.

Reference: the lecture slides in the project's seeds (Kutzbach criterion,
Grübler's condition, types of joints); e.g. l = 4, j = 4 gives n = 1.

:mod:`.grashof` finds the four-bar and slider-crank loops from the file's
lengths and works Grashof's criterion for them (pure geometry, no numpy):
``mech dof`` and ``mech classify`` show it, and :mod:`mech.properties`, above
this room, reads the same loops.
"""

from __future__ import annotations

from typing import Any

from mech._records import dataclass
from mech.model import Mechanism
from mech.pairs import closure_of, kind_of

__all__ = ["DofCount", "LinkClass", "PairClass", "Topology", "classify", "dof"]

_LINK_CLASS_NAMES = {
    0: "isolated",
    1: "singular",
    2: "binary",
    3: "ternary",
    4: "quaternary",
    5: "pentagonal",
    6: "hexagonal",
}
_JOINT_CLASS_NAMES = {2: "binary", 3: "ternary", 4: "quaternary", 5: "quinary", 6: "senary"}


def link_class_name(order: int) -> str:
    """``2 → binary``, ``3 → ternary`` …; beyond six, ``7-joint``."""
    return _LINK_CLASS_NAMES.get(order, f"{order}-joint")


def joint_class_name(order: int) -> str:
    """``2 → binary``, ``3 → ternary`` …; beyond six, ``7-link``."""
    return _JOINT_CLASS_NAMES.get(order, f"{order}-link")


@dataclass(frozen=True, slots=True)
class DofCount:
    """Kutzbach's count, worked, and what it means.

    ``n`` may be negative (a superstructure).  ``formula`` is the count with
    the numbers substituted, as a textbook writes it.
    """

    l: int  # noqa: E741 - the textbooks' letter
    j: int
    h: int
    n: int
    joints: int
    higher_pairs: tuple[str, ...]

    @property
    def formula(self) -> str:
        """``n = 3(4 − 1) − 2·4 − 0 = 1``"""
        return f"n = 3({self.l} − 1) − 2·{self.j} − {self.h} = {self.n}"

    @property
    def grubler_value(self) -> int:
        """3l − 2j − 4: zero for a constrained mechanism of lower pairs."""
        return 3 * self.l - 2 * self.j - 4

    @property
    def grubler(self) -> str:
        """Grübler's criterion worked: ``3·4 − 2·4 − 4 = 0``, and whether it holds."""
        value = self.grubler_value
        text = f"3l − 2j − 4 = 3·{self.l} − 2·{self.j} − 4 = {value}"
        if self.h:
            return text + " (Grübler's criterion is for lower pairs only; h ≠ 0)"
        return text + (": satisfied" if value == 0 else " ≠ 0: not satisfied")

    @property
    def verdict(self) -> str:
        """Superstructure, structure, constrained mechanism, or one needing n inputs."""
        if self.n < 0:
            return "superstructure (statically indeterminate structure)"
        if self.n == 0:
            return "structure (no relative motion)"
        if self.n == 1:
            return "constrained mechanism (one input drives it)"
        return f"mechanism needing {self.n} independent inputs"

    @property
    def kind(self) -> str:
        """A short word for machines: superstructure, structure, mechanism, unconstrained."""
        if self.n < 0:
            return "superstructure"
        if self.n == 0:
            return "structure"
        if self.n == 1:
            return "constrained"
        return "unconstrained"


@dataclass(frozen=True, slots=True)
class LinkClass:
    """One link: how many joints it takes part in and what that makes it."""

    name: str
    order: int
    joints: tuple[str, ...]
    kind: str
    is_ground: bool

    @property
    def class_name(self) -> str:
        return link_class_name(self.order)


@dataclass(frozen=True, slots=True)
class PairClass:
    """One kinematic pair classified three ways, as the lecture slides do."""

    joint: str
    type: str
    links: tuple[str, ...]
    order: int
    equivalent_binary: int
    relative_motion: str
    contact: str
    closure: str
    kutzbach: str  # "j" (lower pair, counts in j) or "h" (higher pair)

    @property
    def joint_class(self) -> str:
        return joint_class_name(self.order)


@dataclass(frozen=True, slots=True)
class Topology:
    """Everything ``mech classify`` and ``mech dof`` report about a file."""

    name: str
    path: str
    ground: str
    links: tuple[LinkClass, ...]
    pairs: tuple[PairClass, ...]
    count: DofCount
    chain: str | None
    #: Four-bar and slider-crank loops whose lengths the file gives (:mod:`mech.topology.grashof`).
    loops: tuple[Any, ...] = ()
    length_unit: str = "m"

    def link_classes(self) -> dict[str, tuple[str, ...]]:
        """Class name → links of that class, in the order of the classes."""
        out: dict[str, list[str]] = {}
        for link in sorted(self.links, key=lambda c: c.order):
            out.setdefault(link.class_name, []).append(link.name)
        return {k: tuple(v) for k, v in out.items()}

    def joint_classes(self) -> dict[str, tuple[str, ...]]:
        """Class name → joints of that class (by how many links meet there)."""
        out: dict[str, list[str]] = {}
        for pair in sorted(self.pairs, key=lambda p: p.order):
            out.setdefault(pair.joint_class, []).append(pair.joint)
        return {k: tuple(v) for k, v in out.items()}

    @property
    def icentres(self) -> int:
        """N = n(n − 1)/2 instantaneous centres for n links."""
        n = len(self.links)
        return n * (n - 1) // 2


def dof(mechanism: Mechanism) -> DofCount:
    """Kutzbach's count n = 3(l − 1) − 2j − h for a planar mechanism.

    A joint listing k links counts k − 1 in j.  Slot, cam, gear and contact
    joints are higher pairs (h).  Rolling without slip, screw and spherical
    pairs count in j (the latter two only for counting: the planar solvers
    reject them).

    Examples
    --------
    The four-bar of the slides (l = 4, j = 4): ``n = 3(4 − 1) − 2·4 − 0 = 1``.
    """
    l = len(mechanism.links)  # noqa: E741
    j = sum(jt.equivalent_binary for jt in mechanism.joints if not kind_of(jt).higher)
    higher = tuple(jt.name for jt in mechanism.joints if kind_of(jt).higher)
    h = len(higher)
    return DofCount(
        l=l, j=j, h=h, n=3 * (l - 1) - 2 * j - h, joints=len(mechanism.joints), higher_pairs=higher
    )


def classify(mechanism: Mechanism) -> Topology:
    """Classify links, joints and pairs and count the degrees of freedom.

    Where the file gives a four-bar loop's lengths, Grashof's criterion for it
    comes too (:func:`mech.topology.grashof.linkage_loops`, pure Python).
    """
    links = tuple(
        LinkClass(
            name=link.name,
            order=len(js := mechanism.joints_of(link.name)),
            joints=tuple(j.name for j in js),
            kind=link.kind,
            is_ground=link.is_ground,
        )
        for link in mechanism.links
    )
    pairs = tuple(
        PairClass(
            joint=j.name,
            type=j.type,
            links=j.links,
            order=j.order,
            equivalent_binary=j.equivalent_binary,
            relative_motion=kind_of(j).motion,
            contact=kind_of(j).contact,
            closure="self-closed" if closure_of(j) == "self" else "force-closed",
            kutzbach="h" if kind_of(j).higher else "j",
        )
        for j in mechanism.joints
    )
    return Topology(
        name=mechanism.label,
        path=mechanism.path,
        ground=mechanism.ground,
        links=links,
        pairs=pairs,
        count=dof(mechanism),
        chain=chain_name(mechanism),
        loops=_loops(mechanism),
        length_unit=mechanism.length_unit,
    )


def _loops(mechanism: Mechanism) -> tuple[Any, ...]:
    """Grashof loops, when the file gives any geometry (a DOF exercise does not even import them)."""
    if not mechanism.lengths and not any(j.place.at is not None for j in mechanism.joints):
        return ()
    from mech.topology.grashof import linkage_loops

    return linkage_loops(mechanism)


def chain_name(mechanism: Mechanism) -> str | None:
    """The textbook name of the chain, where it has one.

    four-bar (4 links, 4 turning pairs), slider-crank (3 turning, 1 sliding),
    double-slider (2 and 2), five-bar, watt and stephenson (six links, seven
    binary turning pairs, two ternary links: adjacent in Watt's chain, apart
    in Stephenson's).  None for anything else.
    """
    joints = mechanism.joints
    if any(kind_of(j).higher or j.order != 2 for j in joints):
        return None
    kinds = [kind_of(j) for j in joints]
    if not all(k.role == "pin" or k.keeps_angle for k in kinds):  # turning and sliding pairs only
        return None
    n_links, n_joints = len(mechanism.links), len(joints)
    prismatic = sum(1 for k in kinds if k.keeps_angle)
    if n_links == 4 and n_joints == 4:
        return {0: "four-bar", 1: "slider-crank", 2: "double-slider"}.get(prismatic)
    if n_links == 5 and n_joints == 5 and prismatic == 0:
        return "five-bar"
    if n_links == 6 and n_joints == 7:
        ternary = [link.name for link in mechanism.links if len(mechanism.joints_of(link.name)) == 3]
        if len(ternary) != 2 or any(
            len(mechanism.joints_of(link.name)) not in (2, 3) for link in mechanism.links
        ):
            return None
        adjacent = any(set(ternary) <= set(j.links) for j in joints)
        return "watt" if adjacent else "stephenson"
    return None
