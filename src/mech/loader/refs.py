"""Cross-references between sections: one namespace, names on the right link, no placement cycles.

These checks run once every section is read, on the model's records (not on
nodes), so each problem is placed at the joint or point that names the wrong
thing.
"""

from __future__ import annotations

from collections.abc import Iterable

from mech.errors import Problem, Where
from mech.model import Joint, Point
from mech.pairs import kind_of

__all__ = ["check_names", "check_refs", "located_on", "placement_cycles"]


def located_on(joints: list[Joint], points: list[Point]) -> dict[str, set[str]]:
    """Name → links it is a point of (see :func:`mech.pairs.located_on`)."""
    out: dict[str, set[str]] = {}
    for j in joints:
        links = kind_of(j).located_on(j)
        if links:
            out[j.name] = set(links)
    for p in points:
        out[p.name] = {p.link}
    return out


def check_names(entries: Iterable[tuple[str, str, Where | None]]) -> list[Problem]:
    """Links, joints and points share one namespace: ``(name, kind, where)`` used twice is a problem."""
    seen: dict[str, str] = {}
    problems = []
    for name, kind, where in entries:
        if name in seen:
            problems.append(
                Problem(
                    f"the name {name!r} is used twice (a {seen[name]} and a {kind})",
                    where,
                    "links, joints and points share one set of names",
                )
            )
        else:
            seen[name] = kind
    return problems


def check_refs(joints: list[Joint], points: list[Point], located: dict[str, set[str]]) -> list[Problem]:
    """Names used in from/toward, path, point and profiles must be on the right link."""
    problems: list[Problem] = []
    for j in joints:
        if j.place.is_relative:
            for ref in (j.place.origin, j.place.toward):
                if ref is not None and not (located.get(ref, set()) & set(j.links)):
                    problems.append(
                        Problem(
                            f"joint {j.name} is placed from {ref!r}, which is not a point of {' or '.join(j.links)}",
                            j.where,
                            _points_of(j.links, located, j.name),
                        )
                    )
        if kind_of(j).role == "path" and len(j.links) == 2:
            problems += _slider_refs(j, joints, points, located)
        problems += _profile_refs(j, located)
    for p in points:
        for ref in (p.place.origin, p.place.toward):
            if ref is not None and p.link not in located.get(ref, set()):
                problems.append(
                    Problem(
                        f"point {p.name} is placed from {ref!r}, which is not a point of {p.link}",
                        p.where,
                        _points_of((p.link,), located, p.name),
                    )
                )
    problems.extend(placement_cycles([*joints, *points]))
    return problems


def _points_of(links: Iterable[str], located: dict[str, set[str]], placed: str) -> str:
    """The hint of a placement from a name that is not on the link: the names that are (but ``placed``)."""
    on = sorted(
        name
        for name, carriers in located.items()
        if carriers & set(links) and name != placed and not name.startswith("#")
    )
    return (
        f"place it from a joint or point of {' or '.join(links)}: {', '.join(on[:12]) or 'none is named yet'}"
    )


def _slider_refs(
    j: Joint, joints: list[Joint], points: list[Point], located: dict[str, set[str]]
) -> list[Problem]:
    """A slider's path is fixed in its guide; the point that runs on it is a point of the mover."""
    problems: list[Problem] = []
    mover, guide = j.links
    w = j.where
    if j.path is not None:
        for path_ref in (j.path.through, j.path.toward):
            if (
                path_ref is not None
                and path_ref.name is not None
                and guide not in located.get(path_ref.name, set())
            ):
                problems.append(
                    Problem(
                        f"the path of {j.name} goes through {path_ref.name!r}, which is not a point of the guide {guide}",
                        w,
                        "a path is fixed in the guide (the second link): name one of its joints or points, or give coordinates",
                    )
                )
    if j.point is not None:
        if j.point != j.name and mover not in located.get(j.point, set()):
            problems.append(
                Problem(
                    f"`point` of {j.name} is {j.point!r}, which is not a point of {mover}",
                    w,
                    f"name a joint or point of {mover}",
                )
            )
    elif kind_of(j).keeps_angle and j.path is not None:
        # a slot's pin is the slot joint itself; a prismatic slider runs on a point of its own
        others = [o.name for o in joints if o is not j and mover in o.links and not kind_of(o).keeps_angle]
        others += [p.name for p in points if p.link == mover]
        if len(others) != 1:
            problems.append(
                Problem(
                    f"joint {j.name} does not say which point of {mover} runs on its path ({len(others)} candidates)",
                    w,
                    f"add `point: <name>` ({', '.join(others) or 'give the slider a joint or point'})",
                )
            )
    return problems


def _profile_refs(j: Joint, located: dict[str, set[str]]) -> list[Problem]:
    """A profile is fixed in its link: the points it names must be points of that link."""
    problems: list[Problem] = []
    for link, prof in j.profiles:
        for ref in (getattr(prof, k, None) for k in ("centre", "through", "toward", "point")):
            name = getattr(ref, "name", None)
            if name is not None and link not in located.get(name, set()):
                problems.append(
                    Problem(
                        f"the profile of {link} in joint {j.name} names {name!r}, which is not a point of {link}",
                        j.where,
                        f"a profile is fixed in its link: name a joint or point of {link}, or give coordinates",
                    )
                )
    return problems


def placement_cycles(placed: Iterable[Joint | Point]) -> list[Problem]:
    """Relative placements (``from``/``toward``) that lead back to themselves.

    A point placed from itself, or points placed from each other in a ring,
    have no position to start from: assembly would chase its own tail.  One
    problem per cycle, at its first member's line, naming the whole ring.
    """
    items = list(placed)
    refs = {
        it.name: [r for r in (it.place.origin, it.place.toward) if r is not None]
        for it in items
        if it.place.is_relative
    }
    where = {it.name: it.where for it in items}
    problems: list[Problem] = [
        Problem(
            f"{name} is placed from {r[0]} toward {r[1]}: one point gives no direction",
            where[name],
            "`toward` names a second point of the link, other than `from`",
        )
        for name, r in refs.items()
        if len(r) == 2 and r[0] == r[1] and r[0] != name
    ]
    rings: set[frozenset[str]] = set()
    state: dict[str, int] = {}  # 1: on the current path, 2: done
    for start in refs:
        if start in state:
            continue
        path: list[str] = []
        stack = [(start, iter(refs[start]))]
        state[start] = 1
        path.append(start)
        while stack:
            name, todo = stack[-1]
            nxt = next(todo, None)
            if nxt is None:
                stack.pop()
                path.pop()
                state[name] = 2
                continue
            if state.get(nxt) == 1 and frozenset(path[path.index(nxt) :]) not in rings:
                rings.add(frozenset(path[path.index(nxt) :]))
                ring = [*path[path.index(nxt) :], nxt]
                what = (
                    f"{nxt} is placed from itself"
                    if len(ring) == 2
                    else f"{nxt} is placed from {ring[1]}, which leads back to it"
                )
                problems.append(
                    Problem(
                        f"{what}: the placements form a cycle ({' → '.join(ring)})",
                        where.get(nxt),
                        "place one of them with `at`, or from/toward joints placed otherwise",
                    )
                )
            elif nxt in refs and nxt not in state:
                state[nxt] = 1
                path.append(nxt)
                stack.append((nxt, iter(refs[nxt])))
    return problems
