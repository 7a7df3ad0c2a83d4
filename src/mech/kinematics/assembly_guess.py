"""The first guess of the drawn configuration: closed-form dyads in dependency order.

A location is placed directly where one equation gives it at once (the same
point, a relative placement, a guide's far end on its ray, a crank's end along
the drive angle), else as a dyad apex (two lengths to known points: circle–circle;
a length and a path: circle–line), round after round until a round places
nothing.  The branch is chosen by ``near`` or, failing that, by the documented
default rule, noted: a dyad apex lies to the **left of P → Q** (P listed first
in the file); a point at a length from a known point on a path lies at the
intersection **farther along the path's direction**.  Gauss–Newton then
polishes the guess (:mod:`.assemble`).
"""

from __future__ import annotations

import math

import numpy as np

from mech.kinematics.assembly_equations import Dir, Dist, Eq, OnLine, OnLineToward, Rel, Same
from mech.kinematics.geometry import circle_circle, circle_line
from mech.kinematics.layout import Layout

__all__ = ["construct"]


def construct(
    lay: Layout,
    eqs: list[Eq],
    known: dict[str, np.ndarray],
    near: dict[str, tuple[float, float]],
    centre: np.ndarray,
    scale: float,
) -> tuple[dict[str, np.ndarray], list[str], list[str]]:
    """First guesses: closed-form dyads in dependency order; notes on default branches.

    Returns guesses for every unknown, the branch notes, and gap messages for
    dyads that could not close (used if Gauss–Newton cannot close them either).
    Each round places what it can: directly (:meth:`_Guess.direct`), else as a
    dyad apex (:meth:`_Guess.dyad`), until a round places nothing.
    """
    g = _Guess(lay, known, near, centre, scale)
    unknown = [n for n, c in lay.carriers.items() if c and n not in g.pos]
    progress = True
    while progress:
        progress = False
        for n in unknown:
            if n in g.pos:
                continue
            mine = [e for e in eqs if n in e.names]
            found = g.direct(n, mine)
            if found is None:
                found = g.dyad(n, mine)
            if found is not None:
                g.pos[n] = np.asarray(found, dtype=float)
                progress = True
    # Whatever construction could not reach: near, else a spread-out default.
    for k, n in enumerate(unknown):
        if n not in g.pos:
            if n in g.hint:
                g.pos[n] = g.hint[n]
            else:
                g.pos[n] = np.array([0.3 + 0.1 * k, 0.4 - 0.05 * k])
                g.notes.append(
                    f"{n}: position found by least squares from a default guess (give near to choose)"
                )
    return g.pos, g.notes, g.gaps


class _Guess:
    """Positions guessed so far (scaled), with the branch notes and gaps met on the way."""

    def __init__(
        self,
        lay: Layout,
        known: dict[str, np.ndarray],
        near: dict[str, tuple[float, float]],
        centre: np.ndarray,
        scale: float,
    ) -> None:
        self.order = {n: i for i, n in enumerate(lay.mech.iter_names())}
        self.pos = dict(known)
        self.hint = {n: (np.asarray(v, dtype=float) - centre) / scale for n, v in near.items()}
        self.notes: list[str] = []
        self.gaps: list[str] = []

    def pick(self, name: str, candidates: list[tuple[float, float] | None], rule: str) -> np.ndarray:
        """The branch nearest ``near``; without one, the first (the default rule, noted)."""
        cands = [np.array(c) for c in candidates if c is not None]
        if name in self.hint:
            return min(cands, key=lambda c: float(np.hypot(*(c - self.hint[name]))))
        self.notes.append(f"{name}: {rule} by the default rule (give near to choose the other branch)")
        return cands[0]

    def direct(self, n: str, mine: list[Eq]) -> np.ndarray | None:
        """A placement that gives ``n`` at once: the same point, a relative placement, a guide's
        far end on its ray, a crank's end along the drive angle."""
        pos = self.pos
        for e in mine:
            others = [m for m in e.names if m != n]
            if not all(m in pos for m in others):
                continue
            if isinstance(e, Same) and e.names[0] == n:
                return pos[e.names[1]]
            if isinstance(e, Rel) and e.names[0] == n:
                o, t = pos[e.names[1]], pos[e.names[2]]
                w = t - o
                m = float(np.hypot(*w)) or 1.0
                ev = w / m
                return o + e.u * ev + e.v * np.array([-ev[1], ev[0]])
            if isinstance(e, OnLineToward) and e.names[2] == n:
                # a guide's far end Q: at its length from T, on the ray T → P (the slider's side)
                t, p = pos[e.names[1]], pos[e.names[0]]
                lengths = [d for d in mine if isinstance(d, Dist) and set(d.names) == {n, e.names[1]}]
                w = p - t
                m = float(np.hypot(*w))
                if lengths and m > 0:
                    return self.pick(
                        n,
                        [tuple(t + lengths[0].length * w / m), tuple(t - lengths[0].length * w / m)],
                        f"on the ray {e.names[1]}→{e.names[0]}",
                    )
            if isinstance(e, Dir) and e.names[1] == n:
                lengths = [d for d in mine if isinstance(d, Dist) and set(d.names) == set(e.names[:2])]
                if lengths:
                    psi = e.angle([pos[m] if m != n else pos[e.names[0]] for m in e.names])
                    return pos[e.names[0]] + lengths[0].length * np.array([math.cos(psi), math.sin(psi)])
        return None

    def dyad(self, n: str, mine: list[Eq]) -> np.ndarray | None:
        """``n`` as a dyad apex: two lengths to known points, or a length and a path."""
        pos = self.pos
        circles = [
            (pos[next(m for m in d.names if m != n)], d.length, next(m for m in d.names if m != n))
            for d in mine
            if isinstance(d, Dist) and all(m in pos for m in d.names if m != n)
        ]
        lines = [
            d
            for d in mine
            if isinstance(d, (OnLine, OnLineToward))
            and d.names[0] == n
            and all(m in pos for m in d.names[1:])
        ]
        if len(circles) >= 2:
            return self._two_circles(n, circles)
        if circles and lines:
            return self._circle_and_line(n, circles[0], lines[0])
        return None

    def _two_circles(self, n: str, circles: list[tuple[np.ndarray, float, str]]) -> np.ndarray:
        """Circle–circle, left of P → Q (P listed first in the file) unless ``near`` says otherwise."""
        (c1, r1, n1), (c2, r2, n2) = sorted(circles[:2], key=lambda c: self.order.get(c[2], 0))
        left, gap = circle_circle(tuple(c1), r1, tuple(c2), r2, left=True)
        right, _ = circle_circle(tuple(c1), r1, tuple(c2), r2, left=False)
        if left is None:
            d = float(np.hypot(*(c2 - c1)))
            self.gaps.append(
                f"the loop {n1}–{n}–{n2} cannot close: {n1} and {n2} are "
                f"{{{d}}} apart but the lengths {n1}{n} and {n}{n2} are {{{r1}}} and "
                f"{{{r2}}} (gap {{{gap}}})"
            )
            return c1 + r1 * (c2 - c1) / (d or 1.0)
        return self.pick(n, [left, right], f"left of {n1}→{n2}")

    def _circle_and_line(self, n: str, circle: tuple[np.ndarray, float, str], ln: Eq) -> np.ndarray:
        """Circle–line, the intersection farther along the path unless ``near`` says otherwise."""
        pos = self.pos
        c, r, centre_name = circle
        if isinstance(ln, OnLine):
            t, u = pos[ln.names[1]], np.array([ln.n[1], -ln.n[0]])
        else:
            t, q = pos[ln.names[1]], pos[ln.names[2]]
            u = (q - t) / (float(np.hypot(*(q - t))) or 1.0)
        fwd, gap = circle_line(tuple(c), r, tuple(t), tuple(u), forward=True)
        back, _ = circle_line(tuple(c), r, tuple(t), tuple(u), forward=False)
        if fwd is None:
            self.gaps.append(
                f"{n} cannot reach its path: the path passes {{{gap}}} beyond the length {centre_name}{n} = {{{r}}}"
            )
            return t + float((c - t) @ u) * u
        return self.pick(n, [fwd, back], "the intersection farther along the path")
