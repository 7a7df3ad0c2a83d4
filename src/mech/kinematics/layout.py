"""What the solvers read from a :class:`~mech.model.Mechanism`: named locations and the links carrying them.

A *location* is anything with a position: a revolute joint (its pin centre),
a slot joint (the pin running in the slot, unless the joint names its
``point``), a rolling/cam/gear/contact joint (the contact point of the instant
drawn) and every named point.  A prismatic joint has no location of its own:
its ``point`` (default: the slider's only other joint) runs on its path.

A slider with no located point at all gets a synthetic one, ``#joint.point``, at
its path's ``through`` in the drawing (never reported).

A location is *carried* by the links it is fixed in: every link of a revolute,
the pin link of a slot, the link of a point.  A contact point of a higher pair
is carried by none (it moves along both profiles).

Nothing here needs numpy; it is pure bookkeeping shared by assembly,
constraints and results.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace

from mech._records import dataclass
from mech.errors import Problem, UnsupportedError, collect
from mech.model import Drive, Joint, Mechanism, Point, Ref, Vec
from mech.pairs import kind_of
from mech.pairs.path import PathSpec

__all__ = ["DriveSpec", "Layout", "PathSpec", "layout"]


@dataclass(frozen=True, slots=True)
class DriveSpec:
    """A drive resolved against the layout.

    Rotary: ``link`` turns about ``pivot``; its angle is the direction
    ``pivot → toward`` (``toward`` None when the link has no other located
    point: then the angle is the link's own frame angle), measured from
    ``reference``: the ground, whatever ``pivot`` is, unless the drive says
    ``relative_to`` (DESIGN § 1.1 "Drives are absolute").  Then
    ``reference_line`` is the pair of locations whose direction is that
    link's angle θ_a (its frame: first located point → next).  Slider:
    ``joint`` names a prismatic or slot joint whose point moves along its path.
    """

    drive: Drive
    link: str | None = None
    reference: str | None = None
    pivot: str | None = None
    toward: str | None = None
    joint: str | None = None
    reference_line: tuple[str, str] | None = None


@dataclass(frozen=True, slots=True)
class Layout:
    """The located things of a mechanism and who carries them.

    Attributes
    ----------
    carriers
        location name → links it is fixed in (file order); empty for contact points.
    alias
        joint name → the location it stands for (a slot joint naming its ``point``).
    on_link
        link → its located names, ordered: drive pivot or ground pivot first, then
        joints in file order, then points.  The first two define the link's frame.
    paths
        prismatic and slot joints.
    contacts
        rolling, cam, gear and contact joints (velocity-level pairs).
    drives
        the file's drives, resolved.
    """

    mech: Mechanism
    carriers: dict[str, tuple[str, ...]]
    alias: dict[str, str]
    on_link: dict[str, tuple[str, ...]]
    paths: tuple[PathSpec, ...]
    contacts: tuple[Joint, ...]
    drives: tuple[DriveSpec, ...]

    def resolve(self, name: str) -> str:
        """The location a name stands for (a joint alias or itself)."""
        return self.alias.get(name, name)

    def ref_xy(self, ref: Ref, positions: Mapping[str, Vec]) -> Vec:
        """Where a reference is in ``positions``: its own coordinates, or its location's."""
        if ref.xy is not None:
            return ref.xy
        assert ref.name is not None  # a Ref is coordinates or a name (model.Ref)
        return positions[self.resolve(ref.name)]


def layout(mech: Mechanism) -> Layout:
    """Read the located things of ``mech`` (remembered in its memo: the model is immutable).

    The steps: which links carry each location (:func:`_carriers`), each
    prismatic or slot joint's path and the point on it (:func:`_path_spec`),
    the drives (:func:`_drive_spec`), and each link's locations in order,
    its pivot first (:func:`_on_link`).

    Raises
    ------
    UnsupportedError
        For a screw or spherical pair: the planar solvers cannot model them.
    InputError
        For a prismatic joint whose slider point cannot be inferred, a drive
        on a link with no pivot, and similar gaps, all reported at once.
    """
    return mech.memo.get("layout", lambda: _planar_layout(mech))


def _planar_layout(mech: Mechanism) -> Layout:
    """:func:`_layout` once every pair is known to be planar (checked once, with the layout)."""
    for j in mech.joints:
        if not kind_of(j).planar:
            raise UnsupportedError(
                f"joint {j.name} is a {j.type} pair: planar solvers cannot model a "
                f"{j.type} pair; mech dof still counts it",
                where=j.where,
            )
    return _layout(mech)


def _layout(mech: Mechanism) -> Layout:
    problems: list[Problem] = []
    carriers, alias = _carriers(mech)
    # Joints of each link in file order, then its points.
    point_names = {p.name for p in mech.points}
    joint_locs: dict[str, list[str]] = {lk.name: [] for lk in mech.links}
    point_locs: dict[str, list[str]] = {lk.name: [] for lk in mech.links}
    for name, links in carriers.items():
        for link_name in links:
            (point_locs if name in point_names else joint_locs)[link_name].append(name)

    _placed_from_contacts(mech, carriers, problems)
    paths: list[PathSpec] = []
    for j in mech.joints:
        if kind_of(j).role == "path":
            spec = _path_spec(mech, j, carriers, joint_locs, point_locs, problems)
            if spec is not None:
                paths.append(spec)

    contacts = tuple(j for j in mech.joints if kind_of(j).role == "contact")
    for j in contacts:
        if len(j.links) != 2:
            problems.append(Problem(f"{j.type} joint {j.name} must join exactly two links", j.where))

    drives: list[DriveSpec] = []
    for d in mech.drives:
        drive = _drive_spec(mech, d, carriers, joint_locs, point_locs, problems)
        if drive is not None:
            drives.append(drive)
    on_link = _on_link(mech, drives, carriers, joint_locs, point_locs)
    _reference_lines(mech, drives, on_link, problems)
    collect(problems, source=mech.source)
    return Layout(mech, carriers, alias, on_link, tuple(paths), contacts, tuple(drives))


def _placed_from_contacts(
    mech: Mechanism, carriers: dict[str, tuple[str, ...]], problems: list[Problem]
) -> None:
    """Refuse a point or joint placed from or toward a contact of the instant, naming what to use.

    A profile cam's, a rolling or a gear pair's contact is a point of no link: it runs round
    both profiles as they turn, so nothing fixed in a link is placed by it (the assembly has
    no equation that moves it).  A cam's follower has an own point its joint's name stands for
    elsewhere (DESIGN § 1.2: the roller's centre, the knife edge): the hint names it.
    """
    contacts = {j.name: j for j in mech.joints if carriers.get(j.name) == ()}
    items: list[Point | Joint] = [*mech.points, *mech.joints]
    for item in items:
        place = item.place
        for word, ref in (("from", place.origin), ("toward", place.toward)):
            pair = contacts.get(ref or "")
            if pair is None:
                continue
            prof = dict(pair.profiles or {}).get(pair.links[-1])
            own = getattr(getattr(prof, "centre", None) or getattr(prof, "point", None), "name", None)
            hint = (
                f"place it {word} {own}, the point of {pair.links[-1]} that {pair.name} stands for elsewhere"
                if own in carriers
                else "place it from points fixed in the link: its joints, or points with at:"
            )
            problems.append(
                Problem(
                    f"{item.name} is placed {word} {ref}, where the links of the {pair.type} joint {ref} touch: "
                    "a point of no link (it runs round both profiles as they turn)",
                    item.where,
                    hint,
                )
            )


def _carriers(mech: Mechanism) -> tuple[dict[str, tuple[str, ...]], dict[str, str]]:
    """Location → the links it is a point of (none for a contact), and slot joints' aliases."""
    carriers: dict[str, tuple[str, ...]] = {}
    alias: dict[str, str] = {}
    for j in mech.joints:
        kind = kind_of(j)
        if kind.role == "path" and kind.located == "first" and j.point is not None:
            alias[j.name] = j.point  # a slot naming the pin's point: the joint stands for it
        elif kind.role in ("pin", "contact") or (kind.role == "path" and kind.located == "first"):
            carriers[j.name] = kind.fixed_in(j)  # a contact point is carried by none
    for p in mech.points:
        carriers[p.name] = (p.link,)
    return carriers, alias


def _path_spec(
    mech: Mechanism,
    j: Joint,
    carriers: dict[str, tuple[str, ...]],
    joint_locs: dict[str, list[str]],
    point_locs: dict[str, list[str]],
    problems: list[Problem],
) -> PathSpec | None:
    """A prismatic or slot joint's path and the slider's point that runs on it (None: a problem)."""
    if len(j.links) != 2:
        problems.append(Problem(f"{j.type} joint {j.name} must join exactly two links", j.where))
        return None
    slider, guide = j.links
    if j.path is None:
        problems.append(
            Problem(
                f"{j.type} joint {j.name} has no path",
                j.where,
                hint="add path: {through: P, angle: a} or path: {through: P, toward: Q}",
            )
        )
        return None
    if kind_of(j).located == "first":  # a slot: its own pin, unless it names one
        point = j.point if j.point is not None else j.name
    elif j.point is not None:
        own = _own_point(mech, j, slider, carriers, joint_locs, problems)
        if own is None:
            return None
        point = own
    elif not joint_locs[slider] and not point_locs[slider]:
        # A slider with no located point of its own (a follower touched only by a cam):
        # the point of it that lies on the path's ``through`` when drawn.
        point = f"#{j.name}.point"
        carriers[point] = (slider,)
        joint_locs[slider].append(point)
    else:
        others = joint_locs[slider]
        if len(others) != 1:
            choices = ", ".join(others + point_locs[slider]) or "none"
            problems.append(
                Problem(
                    f"prismatic joint {j.name}: cannot tell which point of {slider} runs on "
                    f"the path ({slider}'s located points: {choices})",
                    j.where,
                    hint="add point: NAME to the joint",
                )
            )
            return None
        point = others[0]
    if point not in carriers:
        problems.append(Problem(f"{j.type} joint {j.name}: point {point} is not a located point", j.where))
        return None
    return PathSpec(j.name, j.type, slider, guide, point, j.path)


def _own_point(
    mech: Mechanism,
    j: Joint,
    slider: str,
    carriers: dict[str, tuple[str, ...]],
    joint_locs: dict[str, list[str]],
    problems: list[Problem],
) -> str | None:
    """The slider's point ``j.point`` names; a profile cam's joint stands for its follower's own point.

    DESIGN § 1.2: ``point: K`` on the follower's slide means the follower's own point.  A cam
    given by profiles touches where the curves meet, a point of no link; its follower's own point
    is its roller's centre or knife edge when the profile names one, else (a flat face) the point
    of the follower on the path, any of which keeps the follower on its path.
    """
    pair = next((p for p in mech.joints if p.name == j.point), None)
    if pair is None or carriers.get(pair.name) != () or not pair.profiles:
        return j.point
    if pair.links[-1] != slider:
        problems.append(
            Problem(
                f"{j.type} joint {j.name}: point {pair.name} is the own point of {pair.name}'s follower "
                f"{pair.links[-1]}, not of the slider {slider}",
                j.where,
                hint=f"name a point of {slider}",
            )
        )
        return None
    ref = getattr(dict(pair.profiles).get(slider), "centre", None) or getattr(
        dict(pair.profiles).get(slider), "point", None
    )
    if ref is not None and ref.name is not None and ref.name in carriers:
        return ref.name  # type: ignore[no-any-return]
    point = f"#{j.name}.point"  # the follower's point on the path, where `through` is when drawn
    carriers[point] = (slider,)
    joint_locs[slider].append(point)
    return point


def _on_link(
    mech: Mechanism,
    drives: list[DriveSpec],
    carriers: dict[str, tuple[str, ...]],
    joint_locs: dict[str, list[str]],
    point_locs: dict[str, list[str]],
) -> dict[str, tuple[str, ...]]:
    """Each link's locations, its pivot first (the drive's, else one it shares with the ground)."""
    ground = mech.ground
    pivots = {s.link: s.pivot for s in drives if s.link is not None}
    on_link: dict[str, tuple[str, ...]] = {}
    for lk in mech.links:
        names = joint_locs[lk.name] + point_locs[lk.name]
        first = pivots.get(lk.name)
        if first is None and lk.name != ground:
            first = next((n for n in names if ground in carriers[n]), None)
        if first is not None:
            names = [first] + [n for n in names if n != first]
        on_link[lk.name] = tuple(names)
    return on_link


def _reference_lines(
    mech: Mechanism, drives: list[DriveSpec], on_link: dict[str, tuple[str, ...]], problems: list[Problem]
) -> None:
    """A drive relative to a moving link measures from that link's first two locations (in place)."""
    for k, spec in enumerate(drives):
        if spec.link is None or spec.reference == mech.ground:
            continue
        line = on_link.get(spec.reference, ())  # type: ignore[arg-type]
        if len(line) < 2:
            problems.append(
                Problem(
                    f"drive: {spec.link} is driven relative_to {spec.reference}, which has no line of its "
                    f"own to measure from (it needs two located joints or points)",
                    spec.drive.where,
                    hint="drive it from the ground (omit relative_to) or relative to a link with two joints",
                )
            )
            continue
        drives[k] = replace(spec, reference_line=(line[0], line[1]))


def _drive_spec(
    mech: Mechanism,
    d: Drive,
    carriers: dict[str, tuple[str, ...]],
    joint_locs: dict[str, list[str]],
    point_locs: dict[str, list[str]],
    problems: list[Problem],
) -> DriveSpec | None:
    """Resolve one drive: its pivot, reference link and the joint its angle points at."""
    if d.joint is not None:
        try:
            j = mech.joint(d.joint)
        except KeyError:
            problems.append(Problem(f"drive: no joint named {d.joint}", d.where))
            return None
        if kind_of(j).role != "path":
            problems.append(
                Problem(
                    f"drive: joint {d.joint} is a {j.type} joint; a slider drive needs a "
                    "prismatic or slot joint",
                    d.where,
                )
            )
            return None
        return DriveSpec(d, joint=d.joint)
    if d.link is None:
        problems.append(Problem("drive: give link (a turning input) or joint (a slider input)", d.where))
        return None
    link = d.link
    if link == mech.ground:
        problems.append(Problem(f"drive: {link} is the ground link; drive a moving link", d.where))
        return None
    if d.about is not None:
        pivot = d.about
        if pivot not in carriers or link not in carriers[pivot]:
            problems.append(Problem(f"drive: about {pivot} must be a revolute joint of {link}", d.where))
            return None
    else:
        pins = [n for n in joint_locs.get(link, []) if mech.ground in carriers[n]]
        if len(pins) != 1:
            problems.append(
                Problem(
                    f"drive: {link} has {'no' if not pins else 'more than one'} pivot on "
                    f"{mech.ground}" + (f" ({', '.join(pins)})" if pins else ""),
                    d.where,
                    hint="name the pivot with about: JOINT",
                )
            )
            return None
        pivot = pins[0]
    # Absolute unless the drive says otherwise, whatever link the pivot joins (DESIGN § 1.1).
    reference = d.relative_to or mech.ground
    rest = [n for n in joint_locs.get(link, []) + point_locs.get(link, []) if n != pivot]
    return DriveSpec(d, link=link, reference=reference, pivot=pivot, toward=rest[0] if rest else None)
