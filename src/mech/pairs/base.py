"""The base of every pair kind: one class whose hooks say everything a kind of joint means.

A joint type (``revolute``, ``cam``, ``gear`` …) is the unit of design, as a
``Joint`` subclass is in sympy.physics.mechanics: one subclass of
:class:`PairKind` per type, one instance of it in the registry
(:data:`mech.pairs.registry.KINDS`), and every layer asks that instance instead
of branching on the type's name.  What a kind says:

* **reading** — the keys it adds to a joint (:attr:`PairKind.keys`, each with its
  JSON-Schema fragment) and :meth:`PairKind.read`, which turns them into the
  kind's typed spec (:mod:`mech.specs`);
* **classification** — the lecture notes' facts: lower or higher (Kutzbach's j or
  h), the relative motion, line or surface contact, self or force closure;
* **what the solvers make of it** — :attr:`PairKind.role`, which links it is a
  point of (:attr:`PairKind.located`), whether a path pair keeps the links'
  relative angle (:attr:`PairKind.keeps_angle`), whether its profiles roll
  (:attr:`PairKind.rolls`), how closed-form dyads close it (:attr:`PairKind.dyad`);
* **its constraint rows** — :meth:`PairKind.rows`, in the row shapes of
  :mod:`mech.pairs.rows`;
* **its I-centre by inspection** — :attr:`PairKind.icentre` from the joints
  alone, :meth:`PairKind.inspect` at a solved instant;
* **its glyph** — :meth:`PairKind.glyph`, the geometry a configuration diagram
  draws at the joint: shapes of :mod:`mech.shapes` (the notes' signs are helpers of
  :mod:`mech.pairs.glyph`) from what a :class:`~mech.pairs.glyph.GlyphView` lets it read.

The hooks are given small protocols of what they may read (the drawn
configuration, the solved instant, the page), never the layers' own classes,
so this package imports nothing above :mod:`mech.model`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any, ClassVar, Protocol

from mech._records import dataclass
from mech.errors import Problem, UnsupportedError
from mech.specs import BareSpec, JointSpec, Profile

if TYPE_CHECKING:
    from mech.fields import Fields, Reader
    from mech.model import Joint, Mechanism
    from mech.pairs.glyph import GlyphView, Shape
    from mech.pairs.rows import RowBuilder

#: A wrench on one link: force (N) and moment (N·m, ccw +) about the point it is given for.
Wrench = tuple[float, float, float]

Vec = tuple[float, float]


@dataclass(frozen=True, slots=True)
class PairForce:
    """The force a pair carries at the instant: ``force`` (N, global) acting on link ``on`` from ``by``.

    ``at`` is where it acts (m): a pin's centre, a contact point, or for a sliding
    pair the point of the guide where the normal force acts, ``offset`` (m) along
    the path from the slider's point.  ``normal`` is the signed component along the
    pair's normal (a slider's side thrust, a cam's or a gear's tooth load), None for a pin.
    ``couple`` (N·m, ccw +) is what a sliding pair takes about the slider's point: N·offset,
    or, with no normal force, a couple alone (a guide holding a follower from turning), when
    ``offset`` is None.
    """

    joint: str
    on: str
    by: str
    force: Vec
    at: Vec | None
    normal: float | None = None
    offset: float | None = None
    couple: float | None = None

    @property
    def magnitude(self) -> float:
        return float((self.force[0] ** 2 + self.force[1] ** 2) ** 0.5)


class Carriers(Protocol):
    """Who carries each location and each link's locations (the layout, or the row builder)."""

    @property
    def on_link(self) -> Mapping[str, tuple[str, ...]]: ...
    @property
    def carriers(self) -> Mapping[str, tuple[str, ...]]: ...


__all__ = ["Carriers", "InstantView", "PairKind", "Wrench", "contact_forces"]


class InstantView(Protocol):
    """What a kind's :meth:`~PairKind.inspect` reads of a solved instant and where it says what it sees.

    Implemented by :mod:`mech.icentres.inspection` (metres, global).
    """

    @property
    def mech(self) -> Mechanism: ...
    @property
    def positions(self) -> Mapping[str, Vec]: ...

    def at(self, j: Joint) -> Vec | None:
        """Where the joint's point is at the instant (a slider's point, a pin, a contact)."""
        ...

    def direction(self, j: Joint) -> Vec | None:
        """The joint's path direction, or a contact's common tangent, as solved (None if not known)."""
        ...

    def pin(self, joint: str, links: tuple[str, ...], at: Vec) -> None:
        """A pin at ``at``: the I-centre of every pair of the links it joins."""
        ...

    def slide(self, joint: str, slider: str, guide: str, direction: Vec, at: Vec | None, turns: bool) -> None:
        """A straight path along ``direction``; ``turns``: the slider may turn on it (a pin in a slot)."""
        ...

    def contact(self, joint: str, links: tuple[str, str], at: Vec, normal: Vec | None = None) -> None:
        """A higher pair touching at ``at``: rolling (no ``normal``), else sliding along a common normal."""
        ...


class PairKind:
    """One joint type: subclass it, set the class attributes, override the hooks it needs.

    Attributes
    ----------
    name
        The ``type:`` a file writes.
    keys
        Key → JSON-Schema fragment, for the keys this type adds to the common
        ones (``type``, ``links``, placement, ``closure``, ``description``).
    spec
        The spec a joint of this type has when its file gives none of its keys.
    higher
        Counted in Kutzbach's h (one freedom removed) rather than j.
    motion
        The lecture notes' classification by relative motion.
    line_contact
        Line or point contact (a higher pair in the strict sense), else surface.
    closure
        ``self`` or ``force``: how the elements are kept together by default.
    planar
        The planar solvers can model it.
    located
        Which of the joint's links it is a *point* of (where a length may end):
        ``"all"``, ``"first"`` (a slot's pin) or ``"none"`` (a prismatic pair).
    max_links
        How many links one joint of this type may join (None: any number).
    role
        What the position solvers make of it: ``pin`` (a point fixed in every link it
        joins), ``path`` (a point of the first link on a line of the second), ``contact``
        (a higher pair whose contact point is fixed in neither link), ``spatial`` (refused).
    keeps_angle
        A path pair that also keeps its two links' relative angle (a prismatic pair:
        the block turns with its guide); a pin in a slot does not.
    rolls
        Its profiles roll on each other without slip (rolling, gears); a cam slides.
    meshes
        Teeth keep its links' speed ratio: a stage of a gear train (``--explain`` writes
        the train's value stage by stage).
    dyad
        How the closed-form dyads use it (``pin`` of an RRR or RRP dyad or a crank's
        pivot, ``path`` of an RRP or RPR dyad), or None: a mechanism with such a
        joint is solved by Newton.
    icentre
        What inspection gives from the joints alone (:mod:`mech.icentres.order`):
        ``point`` (its I-centre), ``infinity`` (a point at infinity), ``line`` (only a
        line through it), or ``none``; and how the notes say it (``{joint}`` is filled in).
    """

    name: ClassVar[str]
    keys: ClassVar[Mapping[str, dict[str, Any]]] = {}
    spec: ClassVar[JointSpec] = BareSpec()
    higher: ClassVar[bool] = False
    motion: ClassVar[str]
    line_contact: ClassVar[bool] = False
    closure: ClassVar[str] = "self"
    planar: ClassVar[bool] = True
    located: ClassVar[str] = "all"
    max_links: ClassVar[int | None] = 2
    role: ClassVar[str] = "contact"
    keeps_angle: ClassVar[bool] = False
    rolls: ClassVar[bool] = False
    meshes: ClassVar[bool] = False
    dyad: ClassVar[str | None] = None
    icentre: ClassVar[tuple[str, str]] = ("none", "")

    def __repr__(self) -> str:
        return f"<pair kind {self.name}>"

    # -- reading ------------------------------------------------------------------------------
    def read(self, r: Reader, fields: Fields, what: str, links: tuple[str, ...]) -> JointSpec:
        """The typed spec from the joint's own keys (only this kind's keys are in ``fields``).

        Problems are reported through ``r`` (located, collected); the default is the
        kind's empty spec, for a kind with no keys of its own.
        """
        return self.spec

    # -- where the joint is ---------------------------------------------------------------------
    def fixed_in(self, j: Joint) -> tuple[str, ...]:
        """The links the joint's point is fixed in (it moves with them), for the position solvers.

        A pin is fixed in every link it joins; a pin in a slot in its pin link; a contact
        point moves along both profiles (fixed in neither); a prismatic pair has no point.
        """
        if self.role == "pin":
            return tuple(j.links)
        if self.role == "path" and self.located == "first":
            return j.links[:1]
        return ()

    def drawn_at(self, mech: Mechanism, j: Joint) -> Vec | None:
        """Where the file's own data draw the joint when it has no ``at`` (None: it is solved for)."""
        return None

    # -- the drawn configuration ----------------------------------------------------------------
    def contact_problem(self, j: Joint) -> Problem | None:
        """What a contact pair's drawing lacks for its rows (its contact point), or None.

        The default, for a pair whose contact point is fixed in neither link: the file
        must draw it (``at``) unless profiles (or a programme) make the pair move.
        """
        if self.role != "contact" or j.place.at is not None:
            return None
        if j.profiles or getattr(j.spec, "program", None) is not None:
            return None
        return Problem(
            f"{j.type} joint {j.name} has no contact point: positions and velocities need it",
            j.where,
            f"give `at: [x, y]`, the contact point in the drawn configuration{self.contact_hint}, "
            "and `normal`, the common normal's angle",
        )

    #: What else may stand for the contact point, said in :meth:`contact_problem`'s hint.
    contact_hint: ClassVar[str] = ""

    def complete(self, view: Carriers, j: Joint, positions: dict[str, Vec]) -> None:
        """Positions the kind derives in a configuration (drawn or solved): a gear's pitch point."""

    def drawing_problem(
        self, view: Carriers, j: Joint, positions: Mapping[str, Vec], fmt: Callable[[float], str]
    ) -> Problem | None:
        """What makes the pair impossible as drawn (``fmt`` writes a length in the file's unit), or None."""
        return None

    def drawn_profiles(self, mech: Mechanism, j: Joint, contact: Vec | None) -> list[tuple[str, Profile]]:
        """The curves a configuration diagram draws on the pair's links: the joint's ``profiles``.

        ``contact`` is the contact point at the instant drawn (None when unknown).
        """
        return list(j.profiles)

    # -- the drawing --------------------------------------------------------------------------------
    def glyph(self, view: GlyphView, j: Joint) -> Sequence[Shape]:
        """The shapes a configuration diagram draws for the joint (:mod:`mech.pairs.glyph`).

        Lines, outlines and circles of :mod:`mech.shapes`, each on one of
        :data:`mech.pairs.glyph.LAYERS`, in page mm from ``view.page``, or in world metres where a shape says ``world``
        (which the drawing then holds in its view).  The default draws nothing: a pair
        the planar solvers refuse has no place in a planar drawing.
        """
        return ()

    # -- kinematics -----------------------------------------------------------------------------
    def rows(self, b: RowBuilder, j: Joint) -> None:
        """Append the joint's constraint rows to ``b`` (in the shapes of :mod:`mech.pairs.rows`).

        Problems (a contact point missing, profiles that do not touch) go to
        ``b.problems``, all reported at once.  The default refuses: the planar
        solvers cannot model a kind without rows (the layout says so first).
        """
        raise UnsupportedError(
            f"joint {j.name} is a {j.type} pair: planar solvers cannot model it", where=j.where
        )

    # -- forces -----------------------------------------------------------------------------------
    def forces(
        self, j: Joint, wrenches: Mapping[str, Wrench], at: Vec | None, direction: Vec | None
    ) -> list[PairForce]:
        """The force the pair carries, from what its rows put on each of its links.

        ``wrenches[link]`` is the force on that link from this joint and its moment about
        ``at`` (the pair's point at the instant; ``direction`` its path or common tangent).
        The default, for a pin or any pair that acts at its point: the force on each link
        after the first, from the first (a binary joint: on its second link, as DESIGN
        § 1.4's ``force.<joint>.x`` reads it).
        """

        first = j.links[0]
        return [
            PairForce(j.name, link, first, (wrenches[link][0], wrenches[link][1]), at)
            for link in j.links[1:]
            if link in wrenches
        ]

    def pushes(self, j: Joint) -> str | None:
        """How this joint's force is carried where its kinematic rows only say how it moves: None (its
        own rows carry it), ``"instant"`` (:meth:`reaction_rows`, at a solved instant: a force solve
        over many angles then goes angle by angle) or ``"stacked"`` (:meth:`push`, from each
        configuration of a stack: :mod:`mech.forces.series` solves all angles at once)."""
        return "instant" if type(self).reaction_rows is not PairKind.reaction_rows else None

    def push(self, j: Joint, sys_: Any, q: Any) -> tuple[Any, Any] | None:
        """Where (scaled) and along which unit normal this joint pushes at the configuration ``q``
        (scaled), when :meth:`pushes` says ``"stacked"``; :func:`push_row` makes its row."""
        return None

    def other_flank(self, j: Joint, mech: Mechanism, positions: Mapping[str, Vec], force: Vec) -> bool:
        """Whether the force ``force`` its :meth:`reaction_rows` carried on the second link pulls where
        the pair can only push (gear teeth): the force is then solved again on the mirror line
        (the view's ``flanks``, −1).  Never, by default."""
        return False

    def force_note(
        self, j: Joint, mech: Mechanism, positions: Mapping[str, Vec], force: PairForce
    ) -> str | None:
        """What the solved ``force`` of the pair means that a reader must be told (a cam that would
        have to pull its follower), or None."""
        return None

    def reaction_rows(self, j: Joint, view: Any) -> Sequence[Sequence[float]] | None:
        """Rows that carry this pair's force where its kinematic rows only say how it moves (a gear
        pair on fixed centres keeps its speed ratio as an angle row, but pushes along its line of
        action); None: its own rows carry it."""
        return None

    # -- instantaneous centres -------------------------------------------------------------------
    def inspect(self, seen: InstantView, j: Joint) -> None:
        """Say what inspection sees of the joint at a solved instant (lecture notes 002, §6.4).

        The default sees nothing: a pair the planar solvers refuse has no planar I-centre.
        """

    # -- classification -------------------------------------------------------------------------
    def located_on(self, joint: Joint) -> tuple[str, ...]:
        """The links ``joint`` is a *point* of (where a length may end), by :attr:`located`."""
        if self.located == "none":
            return ()
        if self.located == "first":
            return joint.links[:1]
        return joint.links

    @property
    def contact(self) -> str:
        """Lower (surface contact) or higher (line or point contact)."""
        return "higher" if self.line_contact else "lower"


def push_row(view: Any, j: Joint, at: Vec, normal: Vec) -> list[float]:
    """The row of a push along ``normal`` at ``at``: [n, (P − R₁) × n] on the first link, its opposite
    on the second (R the link's origin).  Its multiplier is the force two profiles in contact put on
    each other (a gear's tooth load, a cam's contact force); what the kinematic rows say of the pair
    (a speed ratio, a follower's law) is the same constraint given the pins and slides."""
    row = [0.0] * view.width
    for link, sign in ((j.links[0], 1.0), (j.links[1], -1.0)):
        col, (ox, oy) = view.column(link), view.origin(link)
        row[col] += sign * normal[0]
        row[col + 1] += sign * normal[1]
        row[col + 2] += sign * ((at[0] - ox) * normal[1] - (at[1] - oy) * normal[0])
    return row


def contact_forces(
    j: Joint, wrenches: Mapping[str, Wrench], at: Vec | None, direction: Vec | None
) -> list[PairForce]:
    """A higher pair's force on its second link at the contact, with its component along the
    common normal (the tangent ``direction`` turned −90°): a cam's or a gear's tooth load."""

    on, by = j.links[1], j.links[0]
    if on not in wrenches:
        return []
    fx, fy, _ = wrenches[on]
    normal = None
    if direction is not None:
        normal = fx * direction[1] - fy * direction[0]
    return [PairForce(j.name, on, by, (fx, fy), at, normal=normal)]
