"""Round the cycle of a closed-form program: where the loop cannot close, its change points, the way to an angle.

A drive angle is reached from the drawn one by turning the crank the short way
round, or the long way where a gap (an angle range where a dyad cannot close)
blocks it (:func:`route`); past a change point a dyad continues on the branch
with a continuous tangent (:func:`branches`, :func:`passed`).  Gaps and change
points are found once per program and remembered on it.
"""

from __future__ import annotations

import math
from typing import Any

from mech._records import dataclass
from mech.kinematics.dyads.program import SLACK, DyadProgram, numpy_namespace

__all__ = ["ChangePoint", "branches", "change_points", "closing_edge", "closure_gaps", "passed", "route"]


# -- where the loop closes -----------------------------------------------------------------
def _worst_disc(prog: DyadProgram, phi: float) -> float:
    out = prog.raw(phi, level=prog.positions_level())
    return min(out[: len(prog.dyads)], default=1.0)


def closing_edge(prog: DyadProgram, good: float, bad: float) -> float:
    """Bisect between an angle where every dyad closes and one where one does not (to rounding).

    The last drive angle (rad) that still closes: the edge of a gap, a toggle (the sweep's too).
    """
    for _ in range(200):
        mid = 0.5 * (good + bad)
        if mid in (good, bad):
            break
        if _worst_disc(prog, mid) < -SLACK:
            bad = mid
        else:
            good = mid
    return good


def _golden_min(f: Any, lo: float, hi: float, iters: int = 80) -> tuple[float, float]:
    """Minimum of a unimodal ``f`` on [lo, hi] by golden-section search: (x, f(x))."""
    g = (math.sqrt(5.0) - 1.0) / 2.0
    a, b = lo, hi
    c, d = b - g * (b - a), a + g * (b - a)
    fc, fd = f(c), f(d)
    for _ in range(iters):
        if fc < fd:
            b, d, fd = d, c, fc
            c = b - g * (b - a)
            fc = f(c)
        else:
            a, c, fc = c, d, fd
            d = a + g * (b - a)
            fd = f(d)
    return (c, fc) if fc < fd else (d, fd)


def closure_gaps(prog: DyadProgram, samples: int = 2048) -> tuple[tuple[float, float], ...]:
    """Drive-angle offsets ``(lo, hi)`` in (0, 2π), from the drawn angle, where the loop cannot close.

    Sampled at ``samples`` angles, then each edge bisected to rounding; a
    dip of the discriminant towards zero between samples is searched for its
    minimum, so that a gap narrower than the sampling is not stepped over.
    """
    hit = prog._memo.get("gaps")
    if hit is not None:
        return hit  # type: ignore[no-any-return]
    import numpy as np

    two_pi = 2.0 * math.pi
    d = np.linspace(0.0, two_pi, samples + 1)
    out = prog.raw(prog.drawn_angle + d, level=prog.positions_level(), xp=numpy_namespace())
    nd = len(prog.dyads)
    if nd == 0:
        prog._memo["gaps"] = ()
        return ()
    disc = np.min(np.vstack(np.broadcast_arrays(*out[:nd])), axis=0)
    bad = disc < -SLACK
    # dips: local minima that stay positive but come close to zero
    for k in range(1, samples):
        if not bad[k] and disc[k] <= disc[k - 1] and disc[k] <= disc[k + 1] and disc[k] < 1e-3:
            x, v = _golden_min(lambda t: _worst_disc(prog, prog.drawn_angle + t), d[k - 1], d[k + 1])
            if v < -SLACK:
                lo = closing_edge(prog, prog.drawn_angle + d[k - 1], prog.drawn_angle + x) - prog.drawn_angle
                hi = closing_edge(prog, prog.drawn_angle + d[k + 1], prog.drawn_angle + x) - prog.drawn_angle
                prog._memo.setdefault("dips", []).append((lo, hi))
    gaps: list[tuple[float, float]] = list(prog._memo.pop("dips", []))
    k = 0
    while k <= samples:
        if bad[k]:
            start = k
            while k <= samples and bad[k]:
                k += 1
            lo = (
                closing_edge(prog, prog.drawn_angle + d[start - 1], prog.drawn_angle + d[start])
                - prog.drawn_angle
            )
            end = min(k, samples)
            hi = (
                closing_edge(prog, prog.drawn_angle + d[end], prog.drawn_angle + d[end - 1])
                - prog.drawn_angle
            )
            gaps.append((lo, hi))
        k += 1
    result = tuple(sorted(gaps))
    prog._memo["gaps"] = result
    return result


# -- change points: where a dyad's two positions meet and the loop still closes --------------
#: Golden-section minima of a dyad's discriminant within this of zero touch it (a tangency).
TOUCH = SLACK
_CHANGE_STEP = 1e-6  # rad either side of a tangency: where the signed root is read (see change_points)


@dataclass(frozen=True, slots=True)
class ChangePoint:
    """A change point (bifurcation) of one dyad: its two positions meet, the loop closes either side.

    ``dyad`` is the dyad's index in :attr:`DyadProgram.dyads`; ``offset`` the drive
    angle from the drawn one (rad, in (0, 2π)); ``what`` says what meets what
    (``P meets C (l6 and l7 in line at P)``).
    """

    dyad: int
    offset: float
    what: str


def _dyad_disc(prog: DyadProgram, k: int, phi: float) -> float:
    return float(prog.raw(phi, level=prog.positions_level())[k])


def change_points(prog: DyadProgram, samples: int = 2048) -> tuple[ChangePoint, ...]:
    """Where a dyad's discriminant touches zero without the loop failing to close: change points.

    At a toggle the discriminant crosses zero (the loop cannot close beyond: a
    gap); at a change point it only touches it, ``disc ≈ c (φ − φ*)²``, so its
    two roots meet and part again (the Peaucellier inversor folding flat: P
    meets C).  Both continuations are smooth curves, but the drawn sign
    ``+√disc`` follows the one whose tangent turns abruptly; the root that
    continues with a continuous tangent is ``sign·g(φ)``, ``g`` the signed
    square root of the discriminant, whose sign changes there — the
    predictor–corrector continuation's choice.  Located by golden section on
    the dyad's own discriminant round every sampled minimum below 1e-3 (the
    neighbours assembled), kept when it is within :data:`TOUCH` of zero and
    grows quadratically on both sides (``√disc`` doubles with the distance: a
    simple root of ``g``); the angle is then the root of the signed ``g``
    read at ±1e-6 rad (to about 1e-10 rad).  Remembered on the program.
    """
    hit = prog._memo.get("changes")
    if hit is not None:
        return hit  # type: ignore[no-any-return]
    import numpy as np

    found: list[ChangePoint] = []
    nd = len(prog.dyads)
    if nd:
        d = np.linspace(0.0, 2.0 * math.pi, samples + 1)
        with np.errstate(all="ignore"):
            out = prog.raw(prog.drawn_angle + d, level=prog.positions_level(), xp=numpy_namespace())
        discs = np.vstack(np.broadcast_arrays(*out[:nd]))
        ok = np.min(discs, axis=0) >= -SLACK
        v, left, right = discs[:, 1:-1], discs[:, :-2], discs[:, 2:]
        dips = (v <= left) & (v <= right) & ((v < left) | (v < right)) & (v < 1e-3) & ok[:-2] & ok[2:]
        for k, i in zip(*np.nonzero(dips), strict=True):  # i + 1: the sample of the dip
            at = _touch(prog, int(k), prog.drawn_angle + d[i], prog.drawn_angle + d[i + 2])
            if at is not None:
                found.append(ChangePoint(int(k), float(at - prog.drawn_angle), _meets(prog, int(k), at)))
    result = tuple(sorted(found, key=lambda c: c.offset))
    prog._memo["changes"] = result
    return result


def _touch(prog: DyadProgram, k: int, lo: float, hi: float) -> float | None:
    """The angle where dyad k's discriminant touches zero between ``lo`` and ``hi``, or None."""
    x, v = _golden_min(lambda t: _dyad_disc(prog, k, t), lo, hi)
    if abs(v) > TOUCH:
        return None  # a near miss (the roots pass close, never meet) or a dip below zero (a gap)
    h = _CHANGE_STEP
    try:
        s = [math.sqrt(max(_dyad_disc(prog, k, x + t), 0.0)) for t in (-2 * h, -h, h, 2 * h)]
    except ZeroDivisionError:
        return None
    if min(s) <= 0.0 or not all(1.5 < a / b < 2.5 for a, b in ((s[0], s[1]), (s[3], s[2]))):
        return None  # not a simple root of the signed √disc: no sign to flip
    return x - h + 2.0 * h * s[1] / (s[1] + s[2])


def _meets(prog: DyadProgram, k: int, phi: float) -> str:
    """What meets what at dyad k's change point: the placed point and any named point on it."""
    kind, placed, line = prog.dyads[k]
    out = prog.raw(phi, level=prog.positions_level())
    parts = prog.split(out, 0)
    names = prog.points
    j = names.index(placed) if placed in names else -1
    if j < 0:
        return f"the {kind} dyad's two positions meet ({line})"
    px, py = parts["px"], parts["py"]
    size = max(
        (math.hypot(px[a] - px[b], py[a] - py[b]) for a in range(len(names)) for b in range(a)), default=1.0
    )
    others = [
        n
        for i, n in enumerate(names)
        if i != j
        and not n.startswith("#")
        and math.hypot(px[i] - px[j], py[i] - py[j]) <= 1e-6 * (size or 1.0)
    ]
    if others:
        return f"{placed} meets {', '.join(others)} ({line})"
    return f"{placed}'s two positions meet ({line})"


def route(prog: DyadProgram, target: float) -> float | None:
    """How far the crank turns from the drawn angle to reach ``target`` (rad, signed), or None.

    The short way round first, then the other, as Newton continuation
    (:func:`~mech.kinematics.moving.move_to`) tries them; a way with a gap in
    it is not taken; None when both have one.
    """
    two_pi = 2.0 * math.pi
    delta = (target - prog.drawn_angle + math.pi) % two_pi - math.pi
    if delta == 0.0:
        return 0.0
    gaps = closure_gaps(prog)
    for way in (delta, delta - math.copysign(two_pi, delta)):
        if way > 0 and all(lo > way for lo, _ in gaps):
            return way
        if way < 0 and all(hi < way + two_pi for _, hi in gaps):
            return way
    return None


def crossed(prog: DyadProgram, ref: float, phi: Any) -> list[Any]:
    """Per change point, how many times turning from ``ref`` to ``phi`` passes it (floats or arrays).

    ``ref`` is the drawn angle or one a whole number of turns from it; a change
    point at ``ref`` or at ``phi`` itself is not passed.
    """
    import numpy as np

    two_pi = 2.0 * math.pi
    lo, hi = np.minimum(ref, phi), np.maximum(ref, phi)
    counts = []
    for c in change_points(prog):
        u = prog.drawn_angle + c.offset
        n = np.maximum(np.ceil((hi - u) / two_pi) - np.floor((lo - u) / two_pi) - 1.0, 0.0)
        counts.append(n if np.ndim(phi) else float(n))
    return counts


def branches(prog: DyadProgram, ref: float, phi: Any) -> tuple:
    """Each dyad's branch multiplier at ``phi`` reached by turning from ``ref``: () when none flips.

    Past each change point of a dyad its sign flips, so the configuration
    continues with a continuous tangent (:func:`change_points`).
    """
    changes = change_points(prog)
    if not changes:
        return ()
    import numpy as np

    flips: list[Any] = [1.0] * len(prog.dyads)
    for c, n in zip(changes, crossed(prog, ref, phi), strict=True):
        flips[c.dyad] = flips[c.dyad] * np.where(np.remainder(n, 2.0) == 1.0, -1.0, 1.0)
    return tuple(f if np.ndim(phi) else float(f) for f in flips)


def passed(prog: DyadProgram, ref: float, phi: float) -> list[tuple[float, ChangePoint]]:
    """The change points met turning from ``ref`` to ``phi`` (angles, rad, in the order met)."""
    two_pi = 2.0 * math.pi
    out = []
    for c in change_points(prog):
        a = ref + ((prog.drawn_angle + c.offset - ref) % two_pi)
        if phi < ref:
            a -= two_pi
        while (ref < a < phi) or (phi < a < ref):
            if abs(a - phi) > 1e-9:  # on it (to the angle's accuracy) is not past it
                out.append((a, c))
            a += two_pi if phi > ref else -two_pi
    return sorted(out, key=lambda t: abs(t[0] - ref))
