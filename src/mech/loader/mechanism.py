"""A whole mechanism file: the top-level keys, each section read in turn, then the cross-checks.

Sections are read in the order their names depend on each other (units before
any number, links before joints, joints and points before lengths, drives,
answers and loads).  A section that cannot be read records its problems and
reads as empty, so the rest of the file is still checked and every problem
is reported at once.
"""

from __future__ import annotations

from typing import Any

import yaml

from mech.answers import names_by_kind
from mech.errors import InputError, Where
from mech.loader.answers import DEFAULT_TOLERANCE, read_answers, read_asks
from mech.loader.drives import read_drives
from mech.loader.joints import read_joints
from mech.loader.links import RawLink, read_ground, read_links
from mech.loader.loads import read_loads
from mech.loader.masses import read_flywheel, read_gravity, read_masses
from mech.loader.nodes import compose, node_kind
from mech.loader.points import read_lengths, read_points
from mech.loader.reader import NodeReader
from mech.loader.refs import check_names, check_refs, located_on
from mech.loader.units import read_units
from mech.model import (
    Claim,
    Drive,
    Flywheel,
    Joint,
    Length,
    Link,
    Load,
    Mass,
    Mechanism,
    Point,
    Tolerance,
    Vec,
)
from mech.pairs import higher_pairs

__all__ = ["TOP_KEYS", "read_mechanism"]

#: The top-level keys of a mechanism file (DESIGN § 1), in the order cli.md lists them.
TOP_KEYS = (
    "name",
    "description",
    "source",
    "units",
    "ground",
    "links",
    "joints",
    "lengths",
    "drive",
    "points",
    "answers",
    "asks",
    "loads",
    "masses",
    "gravity",
    "flywheel",
)
#: Keys of the course's later chapters that this version reads only to refuse them clearly.
NOT_YET = {
    "friction": "friction (friction circles, Coulomb at sliders) is not modelled: forces are frictionless "
    "(DESIGN § 1.4); remove `friction:`",
}

Top = dict[str, tuple[Any, Any]]


def read_mechanism(text: str, path: str) -> Mechanism:
    """The mechanism of a file's text (``path`` is used only in messages).

    Raises
    ------
    InputError
        With every problem of the file at once.
    """
    if not text.strip() or all(not ln.strip() or ln.lstrip().startswith("#") for ln in text.splitlines()):
        raise InputError(
            "the file is empty",
            where=Where(path, 1, 1),
            hint="a mechanism needs at least `links:` and `joints:` (see mechanisms/)",
        )
    r = NodeReader(text, path)
    root = compose(text, path)
    if root is None:
        raise InputError("the file is empty", where=Where(path, 1, 1))
    if not isinstance(root, yaml.MappingNode):
        raise InputError(
            f"a mechanism file must be a mapping of keys (links:, joints: …), not {node_kind(root)}",
            where=r.where(root),
            hint="start with `links: [...]` and `joints: {...}`",
            source=text,
        )
    top = r.mapping(root, "the file", allowed=(*TOP_KEYS, *NOT_YET))
    for key, message in NOT_YET.items():
        if key in top:
            r.problem(top[key][0], message)
    return _mechanism(r, root, top)


def _mechanism(r: NodeReader, root: yaml.MappingNode, top: Top) -> Mechanism:
    # the title is free text, kept as written (JSON carries it whole); its control and
    # direction characters are escaped where it is printed, by the consoles (mech.render.console)
    # and the error messages — names of links and joints refuse them instead
    name = r.optional(top, "name", r.text_value)
    r.optional(top, "description", r.text_value)
    r.optional(top, "source", r.text_value)
    r.optional(top, "units", lambda n: read_units(r, n))
    links_raw, ground = _links_and_ground(r, root, top)
    link_names = [n for n, _, _ in links_raw]
    links = tuple(
        Link(
            name=n,
            index=i,
            kind=extra.get("kind", "rigid"),
            description=extra.get("description"),
            is_ground=(n == ground),
            where=r.where(node),
        )
        for i, (n, node, extra) in enumerate(links_raw)
    )
    joints: list[Joint] = []
    if "joints" in top:
        joints = r.guard(lambda: read_joints(r, top["joints"][1], set(link_names)), [])
    points: list[Point] = []
    if "points" in top:
        points = r.guard(lambda: read_points(r, top["points"][1], set(link_names)), [])

    names: list[tuple[str, str, Where | None]] = [(n, "link", r.where(node)) for n, node, _ in links_raw]
    names += [(j.name, "joint", j.where) for j in joints]
    names += [(p.name, "point", p.where) for p in points]
    r.problems += check_names(names)
    located = located_on(joints, points)
    # a joint whose own error is reported counts as on every link, so nothing echoes it
    r.problems += check_refs(joints, points, {**located, **{n: set(link_names) for n in r.tainted}})
    lengths: list[Length] = []
    if "lengths" in top:
        lengths = r.guard(lambda: read_lengths(r, top["lengths"][1], located), [])
    drives: list[Drive] = []
    if "drive" in top:
        drives = r.guard(lambda: read_drives(r, top["drive"][1], set(link_names), ground, joints), [])
    answers, tolerance, asks = _questions(r, top, links, joints, points)
    loads: tuple[Load, ...] = ()
    if "loads" in top:
        loads = r.guard(lambda: read_loads(r, top["loads"][1], link_names, joints, points), ())
    masses, gravity, flywheel = _dynamics(r, top, link_names, ground, located)
    r.fail()
    return Mechanism(
        name=name,
        path=r.path,
        ground=ground or "",
        links=links,
        joints=tuple(joints),
        points=tuple(points),
        lengths=tuple(lengths),
        drives=tuple(drives),
        answers=tuple(answers),
        asks=asks,
        loads=loads,
        masses=masses,
        gravity=gravity,
        flywheel=flywheel,
        tolerance=tolerance,
        length_unit=r.length_unit,
        angle_unit=r.angle_unit,
        source=r.text,
    )


def _links_and_ground(r: NodeReader, root: yaml.MappingNode, top: Top) -> tuple[list[RawLink], str | None]:
    """The links as read and the ground's name; a missing ``links:`` or ``joints:`` is a problem."""
    links_raw: list[RawLink] = []
    if "links" not in top:
        r.problem(root, "the file has no `links:`", "list the links: `links: [frame, crank, …]`")
    else:
        links_raw = r.guard(lambda: read_links(r, top["links"][1]), [])
    if "joints" not in top:
        r.problem(
            root,
            "the file has no `joints:`",
            "add `joints:` with e.g. `A: {type: revolute, links: [frame, crank]}`",
        )
    ground = read_ground(r, root, top, [n for n, _, _ in links_raw])
    return links_raw, ground


def _questions(
    r: NodeReader, top: Top, links: tuple[Link, ...], joints: list[Joint], points: list[Point]
) -> tuple[list[Claim], Tolerance, tuple[str, ...]]:
    """``answers`` (claims and the file's tolerance) and ``asks``, keys checked against the names."""
    answers: list[Claim] = []
    tolerance = DEFAULT_TOLERANCE
    asks: tuple[str, ...] = ()
    if "answers" not in top and "asks" not in top:
        return answers, tolerance, asks  # the names' kinds (I-centres too) cost more than the rest
    kinds = names_by_kind(
        (link.name for link in links),
        (j.name for j in joints),
        (p.name for p in points),
        len(links),
        higher_pairs(joints),
    )
    if "answers" in top:
        answers, tolerance = r.guard(lambda: read_answers(r, top["answers"][1], kinds), ([], tolerance))
    if "asks" in top:
        asks = r.guard(lambda: read_asks(r, top["asks"][1], kinds), ())
    return answers, tolerance, asks


def _dynamics(
    r: NodeReader, top: Top, links: list[str], ground: str | None, located: dict[str, set[str]]
) -> tuple[tuple[Mass, ...], Vec | None, Flywheel | None]:
    """``masses``, ``gravity`` and ``flywheel`` (DESIGN § 1.4), each only when the file gives it."""
    masses: tuple[Mass, ...] = ()
    if "masses" in top:
        masses = r.guard(lambda: read_masses(r, top["masses"][1], links, ground, located), ())
    gravity = r.optional(top, "gravity", lambda n: read_gravity(r, n))
    flywheel = r.optional(top, "flywheel", lambda n: read_flywheel(r, n))
    return masses, gravity, flywheel
