"""The I-centres of a linkage from its joints alone: which are primary, and the order Kennedy finds the rest.

A student meets the instantaneous centres before any drawing: number the links
(ground is 1), count N = n(n − 1)/2, write down the primary centres by inspection
and then find the others by the Aronhold-Kennedy theorem — I_ij lies on the line
through I_ik and I_jk for every third link k, so two such lines fix it.  None of
that needs a coordinate, so :func:`kennedy_order` works on the joints alone (it
imports no numpy) and ``mech icentres`` uses it for a file that places nothing.

The inspection rules (lecture notes 002, §6.4; Khurmi & Gupta §6.6), each pair kind's
:attr:`~mech.pairs.base.PairKind.icentre`:

* a pin (``revolute``) is the I-centre of every pair of links it joins;
* a sliding pair (``prismatic``): at infinity, perpendicular to the path;
* pure rolling: the point of contact;
* a cam, a gear mesh or other point contact, or a pin in a slot: only a line (the common
  normal, or the normal to the slot through the pin), which Kennedy must cross
  with one more line.

Kennedy's lines are used as the construction uses them: a centre is found once two
lines through known centres (or one and its contact normal) cross it.  Which pairs
of centres give which lines is pure topology; whether two lines happen to coincide
at some instant is geometry, and is left to the located construction.
"""

from __future__ import annotations

from itertools import combinations

from mech._records import dataclass
from mech.model import Joint, Mechanism
from mech.pairs import kind_of

__all__ = ["OrderedCentre", "TopologyCentres", "kennedy_order"]


@dataclass(frozen=True, slots=True)
class OrderedCentre:
    """One I-centre: ``numbers`` (i < j, ground = 1), how it is found, and when.

    ``step`` is 0 for a primary centre, else its place in Kennedy's order;
    ``lines`` names the two lines that fix it (``("I12", "I23")`` is the line
    through I12 and I23); a line that inspection gives is named by its joint.
    """

    name: str
    links: tuple[str, str]
    numbers: tuple[int, int]
    how: str
    step: int | None
    lines: tuple[tuple[str, str], ...] = ()


@dataclass(frozen=True, slots=True)
class TopologyCentres:
    """Every I-centre of a mechanism, in the order they are found, and the ones Kennedy cannot reach."""

    path: str
    name: str
    numbered: tuple[str, ...]
    centres: tuple[OrderedCentre, ...]

    @property
    def count(self) -> int:
        n = len(self.numbered)
        return n * (n - 1) // 2

    @property
    def primary(self) -> tuple[OrderedCentre, ...]:
        return tuple(c for c in self.centres if c.step == 0)

    @property
    def unreached(self) -> tuple[OrderedCentre, ...]:
        return tuple(c for c in self.centres if c.step is None)


def _name(i: int, j: int) -> str:
    return f"I{i}{j}" if max(i, j) < 10 else f"I{i},{j}"


def kennedy_order(mech: Mechanism) -> TopologyCentres:
    """All n(n − 1)/2 I-centres of ``mech``: primary by inspection, the rest in Kennedy's order."""
    numbered = tuple(link.name for link in mech.numbered_links)
    number = {name: k + 1 for k, name in enumerate(numbered)}
    known: dict[tuple[int, int], OrderedCentre] = {}
    given_lines: dict[tuple[int, int], list[str]] = {}
    for joint in mech.joints:
        _inspect(joint, number, known, given_lines)
    step = 0
    pairs = list(combinations(range(1, len(numbered) + 1), 2))
    while True:
        found = _next(pairs, known, given_lines)
        if found is None:
            break
        (i, j), lines = found
        step += 1
        how = "Kennedy: on " + " and on ".join(_line_words(a, b) for a, b in lines)
        known[(i, j)] = OrderedCentre(
            _name(i, j), (numbered[i - 1], numbered[j - 1]), (i, j), how, step, lines
        )
    centres = [*sorted((c for c in known.values() if c.step == 0), key=lambda c: c.numbers)]
    centres += sorted((c for c in known.values() if c.step), key=lambda c: c.step or 0)
    for i, j in pairs:
        if (i, j) not in known:
            partial = given_lines.get((i, j), [])
            how = (
                "not reached by Kennedy's theorem from the primary centres"
                + (f" (known only to lie on the line {partial[0]})" if partial else "")
                + ": it needs the velocity solution (mech icentres on a placed file)"
            )
            centres.append(OrderedCentre(_name(i, j), (numbered[i - 1], numbered[j - 1]), (i, j), how, None))
    return TopologyCentres(mech.path, mech.label, numbered, tuple(centres))


def _inspect(
    joint: Joint,
    number: dict[str, int],
    known: dict[tuple[int, int], OrderedCentre],
    given_lines: dict[tuple[int, int], list[str]],
) -> None:
    kind, words = kind_of(joint).icentre  # point, infinity, line or none, and how the notes say it
    links = [name for name in joint.links if name in number]
    for a, b in combinations(links, 2):
        i, j = sorted((number[a], number[b]))
        if i == j or (i, j) in known:
            continue
        if kind in ("point", "infinity"):
            names = (a, b) if number[a] < number[b] else (b, a)
            known[(i, j)] = OrderedCentre(_name(i, j), names, (i, j), words.format(joint=joint.name), 0)
        elif kind == "line":
            given_lines.setdefault((i, j), []).append(words.format(joint=joint.name))


def _next(
    pairs: list[tuple[int, int]],
    known: dict[tuple[int, int], OrderedCentre],
    given_lines: dict[tuple[int, int], list[str]],
) -> tuple[tuple[int, int], tuple[tuple[str, str], ...]] | None:
    """The first unknown centre (in numbering order) that two lines fix, with those lines."""
    for i, j in pairs:
        if (i, j) in known:
            continue
        lines: list[tuple[str, str]] = [(g, "") for g in given_lines.get((i, j), [])[:1]]
        for k in range(1, max(max(p) for p in pairs) + 1):
            if k in (i, j):
                continue
            ik, jk = tuple(sorted((i, k))), tuple(sorted((j, k)))
            if ik in known and jk in known:
                lines.append((known[ik].name, known[jk].name))  # type: ignore[index]
            if len(lines) == 2:
                return (i, j), tuple(lines)
    return None


def _line_words(a: str, b: str) -> str:
    return a if not b else f"{a}–{b}"
