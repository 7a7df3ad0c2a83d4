"""The Aronhold-Kennedy theorem, applied round after round as on a circle diagram.

Kennedy's theorem: the three I-centres of any three links in plane motion lie
on one straight line.  So for an unknown I_ik, every third link j whose I_ij
and I_jk are both known gives a line through I_ik; two such lines (or one and
a higher pair's common normal) meet in it.  Students keep score on a circle
diagram: links are points on a circle, a known I-centre is a chord drawn, and
an unknown chord that closes two triangles of drawn chords can be found.

Here each *round* looks at every unknown pair with what the previous rounds
found, so the result does not depend on the order pairs are visited; it
stops when a round finds nothing.  Everything is homogeneous (see
:mod:`mech.icentres.homogeneous`): an I-centre at infinity joins lines like any
other point, and parallel lines meet at infinity.

Conditioning.  Each known point or line carries an error estimate ``err``
(chordal distance, size units).  Joining two unit points or meeting two unit
lines divides the errors by the sine of the angle between them (the norm of
the cross product), so nearly coincident points give a poor line and nearly
coincident lines a poor point.  Among all the lines through an unknown
I-centre the best-conditioned pair is used; if even that is worse than
:data:`MAX_ERR`, the lines coincide as far as the data can tell and give no
information (the pair is left for the velocity field).

Reference: Khurmi & Gupta, *Theory of Machines*, §6.7-6.9 (Aronhold-Kennedy,
circle diagram); Uicker, Pennock & Shigley, *Theory of Machines and
Mechanisms*, §3.17-3.18.
"""

from __future__ import annotations

from collections.abc import Sequence

from mech._records import dataclass
from mech.answers import icentre_name
from mech.icentres.homogeneous import Hom, join, meet, norm, unit
from mech.icentres.inspection import Fact

__all__ = ["MAX_ERR", "Found", "kennedy", "name"]

#: Largest acceptable error estimate (chordal, size units) of a Kennedy point:
#: two lines meeting at less than ~1e-6 of their own error are "coincident".
MAX_ERR = 1e-6


@dataclass(frozen=True, slots=True)
class Found:
    """One I-centre found by inspection or by Kennedy's theorem.

    ``pair`` 0-based indices (i < j); ``hom`` the unit homogeneous point in
    size units; ``method`` how it was found; ``step`` 0 for inspection, k for
    the k-th Kennedy round; ``err`` its error estimate.
    """

    pair: tuple[int, int]
    hom: Hom
    method: str
    primary: bool
    step: int
    err: float
    xy: tuple[float, float] | None = None


@dataclass(frozen=True, slots=True)
class Line:
    """A line known to pass through an unknown I-centre, with its provenance."""

    hom: Hom
    label: str
    err: float


def name(i: int, j: int) -> str:
    """Textbook name of the I-centre of 0-based links i and j: ``I13`` (or ``I1,12`` past 9)."""
    return icentre_name(i + 1, j + 1)


def _key(i: int, j: int) -> tuple[int, int]:
    return (i, j) if i < j else (j, i)


@dataclass(frozen=True, slots=True)
class Result:
    """What Kennedy's construction gives: the found I-centres, and why the rest are missing."""

    found: dict[tuple[int, int], Found]
    missing: dict[tuple[int, int], str]
    rounds: int


def kennedy(n: int, facts: Sequence[Fact]) -> Result:
    """Complete the I-centres of an n-link mechanism from the inspection facts.

    Parameters
    ----------
    n
        Number of links (ground included).
    facts
        Points and lines from :func:`mech.icentres.inspection.facts`.

    Returns
    -------
    Result
        ``found``: pair → :class:`Found`; ``missing``: pair → why it is not
        found ("not reachable by Kennedy" or "Kennedy's lines coincide").

    Examples
    --------
    A four-bar A(0,0) B(0,1) C(2,1) D(2,0), numbered frame 1, crank 2,
    coupler 3, rocker 4: crank and rocker are parallel, so I13 is at infinity.

    >>> from mech.icentres.homogeneous import point, unit
    >>> pins = {(0, 1): (0, 0), (1, 2): (0, 1), (2, 3): (2, 1), (0, 3): (2, 0)}
    >>> fs = [Fact(p, "point", unit(point(xy)), "pin", True) for p, xy in pins.items()]
    >>> r = kennedy(4, fs)
    >>> r.found[(0, 2)].method
    'Kennedy: I12–I23 ∩ I14–I34'
    >>> abs(r.found[(0, 2)].hom[2]) < 1e-15
    True
    """
    found: dict[tuple[int, int], Found] = {}
    lines: dict[tuple[int, int], list[Line]] = {}
    for f in facts:
        if f.kind == "point":
            if f.pair not in found:
                found[f.pair] = Found(f.pair, f.hom, f.label, f.primary, 0, f.err, f.xy)
        else:
            lines.setdefault(f.pair, []).append(Line(f.hom, f.label, f.err))

    # Two higher-pair normals of one pair meet without any Kennedy line.
    pairs = [(i, k) for i in range(n) for k in range(i + 1, n)]
    degenerate: set[tuple[int, int]] = set()
    rounds = 0
    while True:
        new: dict[tuple[int, int], Found] = {}
        for pair in pairs:
            if pair in found:
                continue
            candidates = list(lines.get(pair, ()))
            i, k = pair
            for j in range(n):
                if j in pair:
                    continue
                a, b = found.get(_key(i, j)), found.get(_key(j, k))
                if a is None or b is None:
                    continue
                line = join(a.hom, b.hom)
                q = norm(line)
                if q == 0.0:
                    continue
                candidates.append(Line(unit(line), f"{name(*a.pair)}–{name(*b.pair)}", (a.err + b.err) / q))
            best = _best_meet(candidates)
            if best is None:
                if len(candidates) >= 2:
                    degenerate.add(pair)
                continue
            hom, err, l1, l2 = best
            if err > MAX_ERR:
                degenerate.add(pair)
                continue
            degenerate.discard(pair)
            new[pair] = Found(pair, hom, f"Kennedy: {l1.label} ∩ {l2.label}", False, rounds + 1, err)
        if not new:
            break
        rounds += 1
        found.update(new)
    missing = {
        p: ("Kennedy's lines coincide here" if p in degenerate else "not reachable by Kennedy")
        for p in pairs
        if p not in found
    }
    return Result(found, missing, rounds)


def _best_meet(candidates: Sequence[Line]) -> tuple[Hom, float, Line, Line] | None:
    """The best-conditioned meet of two of the lines (least propagated error)."""
    best: tuple[Hom, float, Line, Line] | None = None
    for a in range(len(candidates)):
        for b in range(a + 1, len(candidates)):
            l1, l2 = candidates[a], candidates[b]
            m = meet(l1.hom, l2.hom)
            q = norm(m)
            if q == 0.0:
                continue
            err = (l1.err + l2.err) / q
            if best is None or err < best[1]:
                best = (unit(m), err, l1, l2)
    return best
