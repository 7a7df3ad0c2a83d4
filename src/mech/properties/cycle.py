"""Transmission angle, limit positions, strokes and the quick-return time ratio.

The transmission angle μ of a four-bar loop is the interior angle between the
coupler and the output link at their joint (0–180°): with the crank AB, the
coupler BC and the output CD pivoted at D, μ = ∠BCD.  Force flows best at
90° and not at all at 0° or 180° (Norton, *Design of Machinery*, § 3.3;
Khurmi & Gupta, *Theory of Machines*, § 5.5).  Its least and greatest values
over the cycle are found by a sweep of the included angle ∠BCD
(:func:`mech.kinematics.sweep`, quantity ``included.B.C.D``), whose extremes
are refined between steps to rounding — the same refinement every other
extreme of a sweep gets.

Limit positions (dead centres of the output: where a rocker or a slider
reverses) and the quick-return time ratio are the sweep's own; the stroke of
a slider is the range of its displacement, the swing of a rocker the range of
its angle; a link whose angle comes round a whole turn (a parallelogram's rocker) has
none.  Where coupler and output fold into line — at a toggle, the edge of a gap, or at a
change point the branch passes — the transmission angle is exactly 0 or 180°: the sweep
reads it at those events, located to rounding, as it does every extreme of a position.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import field
from typing import TYPE_CHECKING

from mech._records import dataclass
from mech.errors import UnsupportedError
from mech.model import Mechanism
from mech.options import SolveOptions
from mech.pairs import kind_of
from mech.topology.grashof import FourBarLoop, linkage_loops

if TYPE_CHECKING:  # pragma: no cover
    import numpy as np

    from mech.kinematics import Kinematics, Sweep
    from mech.kinematics.sweep_result import Extreme

__all__ = [
    "Cycle",
    "LimitPosition",
    "Stroke",
    "Transmission",
    "cycle",
    "transmission_angle",
    "transmission_loop",
]

Vec = tuple[float, float]


@dataclass(frozen=True, slots=True)
class Transmission:
    """Where the transmission angle is measured: ∠(coupler_joint, joint, pivot) in ``loop``.

    ``joint`` joins ``coupler`` and ``output``; ``coupler_joint`` is the
    coupler's other joint in the loop (the crank pin), ``pivot`` the output's
    pivot on the frame.
    """

    loop: FourBarLoop
    driver: str
    coupler: str
    output: str
    coupler_joint: str
    joint: str
    pivot: str

    @property
    def quantity(self) -> str:
        """The sweep quantity of the angle: ``included.B.C.D``."""
        return f"included.{self.coupler_joint}.{self.joint}.{self.pivot}"


def transmission_loop(mech: Mechanism, positions: Mapping[str, Vec] | None = None) -> Transmission:
    """The four-bar loop whose crank is driven, with its coupler and output named.

    Raises
    ------
    UnsupportedError
        When no four-bar loop has the driven link beside the frame (a slider
        crank has no four-bar loop; its transmission is not defined this way).
    """
    drive = next((d.link for d in mech.drives if d.link is not None), None)
    for loop in linkage_loops(mech, positions):
        if not isinstance(loop, FourBarLoop) or loop.frame is None:
            continue
        f = loop.links.index(loop.frame)
        beside = (loop.links[(f + 1) % 4], loop.links[(f + 3) % 4])
        if drive is not None and drive not in beside:
            continue
        driver = drive or beside[0]
        k = loop.links.index(driver)
        toward = 1 if loop.links[(k + 1) % 4] != loop.frame else -1
        coupler = loop.links[(k + toward) % 4]
        output = loop.links[(k + 2 * toward) % 4]

        def joint_of(a: str, b: str, loop: FourBarLoop = loop) -> str:
            for i in range(4):
                if {loop.links[i], loop.links[(i + 1) % 4]} == {a, b}:
                    return loop.joints[i]
            raise AssertionError(f"{a} and {b} are not neighbours in the loop")  # pragma: no cover

        return Transmission(
            loop=loop,
            driver=driver,
            coupler=coupler,
            output=output,
            coupler_joint=joint_of(driver, coupler),
            joint=joint_of(coupler, output),
            pivot=joint_of(output, loop.frame),
        )
    raise UnsupportedError(
        f"{mech.label} has no four-bar loop of turning pairs with the driven link beside the frame",
        hint="the transmission angle is the angle between coupler and output of a four-bar loop",
    )


def included_angle(p: Vec, q: Vec, r: Vec) -> float:
    """The angle p–q–r at q, 0 to π (rad)."""
    u = (p[0] - q[0], p[1] - q[1])
    w = (r[0] - q[0], r[1] - q[1])
    return abs(math.atan2(u[0] * w[1] - u[1] * w[0], u[0] * w[0] + u[1] * w[1]))


def transmission_angle(mech: Mechanism, kin: Kinematics) -> tuple[Transmission, float]:
    """The transmission angle at the instant solved (rad, 0 to π), with where it is measured."""
    t = transmission_loop(mech, kin.positions)
    pos = kin.positions
    return t, included_angle(pos[t.coupler_joint], pos[t.joint], pos[t.pivot])


@dataclass(frozen=True, slots=True)
class LimitPosition:
    """A dead centre of an output, or a dwell it comes back from: the drive angle (rad) and its position.

    ``value`` is a slider's displacement along its path (m) or a link's angle (rad).
    ``until`` is the drive angle where a dwell ends (rad; the output rests from
    ``crank_angle`` to it), None for a dead centre.
    """

    output: str
    crank_angle: float
    value: float
    unit: str
    until: float | None = None


@dataclass(frozen=True, slots=True)
class Stroke:
    """The travel of a slider (m) or the swing of a link pivoted on the frame (rad) over the cycle.

    ``joint`` is the prismatic joint or the revolute joint on the frame the
    answer key names; ``subject`` the slider joint or the swinging link;
    ``low``/``high`` the extreme positions with their drive angles.
    """

    joint: str
    subject: str
    unit: str
    low: float
    low_angle: float
    high: float
    high_angle: float
    #: The link that moves: the slider's block (``subject`` is then its joint), or the swinging link.
    link: str = ""

    @property
    def value(self) -> float:
        return self.high - self.low


@dataclass(frozen=True, slots=True)
class Cycle:
    """What happens over one turn of the crank.

    ``transmission`` is None when the mechanism has no four-bar loop with the
    driven crank; ``mu_min``/``mu_max`` (rad) with the drive angles
    ``mu_min_angle``/``mu_max_angle`` (rad) where they occur.  ``strokes`` are
    keyed by joint name; ``turning`` lists joints whose output never reverses over a
    full turn (a link that turns right round, a gear turning on: no stroke, DESIGN § 1.2).
    ``time_ratio`` is slow over fast stroke (≥ 1) of ``time_ratio_output`` (the bare
    one); ``time_ratios`` every output's, by name; ``time_ratio_why`` why each output
    without one ("" for the bare one) has none.
    """

    sweep: Sweep
    transmission: Transmission | None
    mu_min: float | None
    mu_min_angle: float | None
    mu_max: float | None
    mu_max_angle: float | None
    limits: tuple[LimitPosition, ...]
    strokes: Mapping[str, Stroke]
    turning: tuple[str, ...]
    time_ratio: float | None
    time_ratio_output: str | None
    gaps: tuple[tuple[float, float], ...]
    time_ratios: Mapping[str, float] = field(default_factory=dict)
    time_ratio_why: Mapping[str, str] = field(default_factory=dict)


def _stroke_subjects(mech: Mechanism) -> list[tuple[str, str, str]]:
    """(joint, kind, subject): every prismatic joint, and the revolute joints on the frame.

    A prismatic joint's stroke is its travel along its path (DESIGN § 1.1, ``stroke.<joint>``):
    a slider's on the frame, and equally a block's along a moving guide (the block in a
    slotted lever travels 2·O₂A along the lever).  A revolute joint on the frame gives the
    swing of the link it carries, the crank's own pivot excepted.
    """
    drive = next((d.link for d in mech.drives if d.link is not None), None)
    out = []
    for j in mech.joints:
        if kind_of(j).keeps_angle:
            out.append((j.name, "displacement", j.name))
        elif kind_of(j).role == "pin" and mech.ground in j.links and j.order == 2:
            other = next(lk for lk in j.links if lk != mech.ground)
            if other != drive:
                out.append((j.name, "angle", other))
    return out


def cycle(mech: Mechanism, *, options: SolveOptions | None = None, steps: int = 360) -> Cycle:
    """Sweep one turn of the crank and read the transmission angle, limits, strokes and time ratio.

    Parameters
    ----------
    mech
        A mechanism with one crank (a turning drive about a frame pivot).
    options
        Solver options (``angle`` must be None: the sweep sets it).
    steps
        Steps of the sweep; every extreme and dead centre is refined between
        them, so the default 1° grid gives them to rounding.

    Raises
    ------
    UnsupportedError
        Not one turning drive (the sweep's own message).
    """
    import numpy as np

    from mech.kinematics import solve
    from mech.kinematics.sweep_events import turns_fully

    options = (options or SolveOptions()).with_(angle=None)
    base = solve(mech, "position", options.with_(omega=None, direction=None, alpha=None))
    try:
        trans: Transmission | None = transmission_loop(mech, base.positions)
    except UnsupportedError:
        trans = None
    subjects = _stroke_subjects(mech)
    slides_and_links = [
        f"displacement.{s}" if kind == "displacement" else f"angle.{s}" for _j, kind, s in subjects
    ]
    quantities = ([trans.quantity] if trans else []) + slides_and_links
    sw = _cycle_sweep(mech, base, options, steps, quantities, slides_and_links)
    ext = {e.quantity: e for e in sw.extremes}
    other = _other_branch(mech, base, sw, options, quantities)
    if other is not None:
        joined = _whole_circuit(sw, other, ext)
        # an output that comes round a whole turn over the joined circuit (a crank driven by its
        # rocker) keeps the drawn branch's reading, as before: only swings are joined
        ext, other = (joined, other) if joined is not None else (ext, None)
    mu = ext.get(trans.quantity) if trans else None  # 0 or 180° where coupler and output fold in line
    mu_min = (mu.min_value, mu.min_angle) if mu else None
    mu_max = (mu.max_value, mu.max_angle) if mu else None
    strokes: dict[str, Stroke] = {}
    turning: list[str] = []
    movers = {j.name: j.links[0] for j in mech.joints}  # a prismatic joint's first link moves on the second
    for (joint, kind, subject), key in zip(subjects, slides_and_links, strict=True):
        link = movers[joint] if kind == "displacement" else subject
        e = ext.get(key)
        if e is not None and _turns_on(sw, subject):
            turning.append(joint)
            continue
        if e is None:
            series = sw.series(key)
            ok = np.isfinite(series)
            if kind == "angle" and turns_fully(series, ok, sw.angles):
                turning.append(joint)
            elif np.any(ok):  # does not move at all over the cycle
                v = float(series[ok][0])
                strokes[joint] = Stroke(
                    joint, subject, "m" if kind == "displacement" else "rad", v, 0.0, v, 0.0, link
                )
            continue
        strokes[joint] = Stroke(
            joint,
            subject,
            e.unit,
            e.min_value,
            e.min_angle,
            e.max_value,
            e.max_angle,
            link,
        )
    limits = _limits(sw)
    if other is not None:  # the other branch's dead centres are the output's limits too
        limits = _joined_limits(limits, _limits(other), base.size)
    return Cycle(
        sweep=sw,
        transmission=trans,
        mu_min=mu_min[0] if mu_min else None,
        mu_min_angle=mu_min[1] if mu_min else None,
        mu_max=mu_max[0] if mu_max else None,
        mu_max_angle=mu_max[1] if mu_max else None,
        limits=limits,
        strokes=strokes,
        turning=tuple(turning),
        time_ratio=sw.time_ratio.ratio if sw.time_ratio else None,
        time_ratio_output=sw.time_ratio.output if sw.time_ratio else None,
        gaps=tuple((g.start, g.end) for g in sw.gaps),
        time_ratios={r.output: r.ratio for r in sw.time_ratios},
        time_ratio_why=dict(sw.time_ratio_refused),
    )


def _limits(sw: Sweep) -> tuple[LimitPosition, ...]:
    """The outputs' dead centres and the dwells they come back from, by crank angle."""
    limits = tuple(
        LimitPosition(
            e.subject,
            e.angle,
            float(e.value) if e.value is not None else math.nan,
            "m" if e.subject in sw.slides else "rad",
        )
        for e in sw.dead_centres
    ) + tuple(  # a follower's dwell at its lowest or highest is its limit position
        LimitPosition(d.subject, d.start, d.value, "m" if d.subject in sw.slides else "rad", d.end)
        for d in sw.dwells
        if d.reverses
    )
    return tuple(sorted(limits, key=lambda lp: lp.crank_angle))


def _joined_limits(
    ours: tuple[LimitPosition, ...], theirs: tuple[LimitPosition, ...], size: float
) -> tuple[LimitPosition, ...]:
    """Both branches' dead centres, each once: an output the flipped dyad does not move (a lever
    placed before it) has the same dead centre on both, at the same drive angle and position."""

    def same(a: LimitPosition, b: LimitPosition) -> bool:
        scale = size if a.unit == "m" else 1.0
        return (
            a.output == b.output
            and abs(math.remainder(a.crank_angle - b.crank_angle, 2 * math.pi)) <= 1e-9
            and abs(a.value - b.value) <= 1e-9 * scale
        )

    more = tuple(lp for lp in theirs if not any(same(lp, o) for o in ours))
    return tuple(sorted(ours + more, key=lambda lp: lp.crank_angle))


def _other_branch(
    mech: Mechanism, base: Kinematics, sw: Sweep, options: SolveOptions, quantities: list[str]
) -> Sweep | None:
    """The drawn circuit's other assembly branch, swept over the same drive angles, or None.

    A drive that cannot turn fully (a non-Grashof four-bar's input) stops at its toggles, where the
    dyad folding flat has its two closures meet; the motion goes on through them on the dyad's
    other closure, back over the same drive angles.  One circuit is then both branches, joined at
    the two toggles, and an output's limits are over both: the extreme of one branch at a toggle is
    the input's limit, not the output's (the output passes it moving).  Swept by the closed form,
    from the drawing with that one dyad closed the other way (every other dyad keeping its side).

    None when there is nothing to join (the drive turns fully), or when the sweep's two ends are
    not toggles of one dyad of the closed form (several dyads, a Newton sweep): the circuit is
    then not known to be these two branches.
    """
    import dataclasses

    import numpy as np

    from mech.errors import MechError
    from mech.kinematics import solve, sweep
    from mech.kinematics.compiled import compiled
    from mech.kinematics.dyads import program

    if len(sw.toggles) != 2 or not sw.gaps or not all(g.cannot_close for g in sw.gaps):
        return None
    whats = {t.subject for t in sw.toggles}
    prog = program(compiled(mech, None))
    if prog is None or len(whats) != 1:
        return None
    placed = [d[1] for d in prog.dyads if d[2] in whats]
    if len(placed) != 1:
        return None
    try:
        flipped = solve(
            mech, "position", options.with_(omega=None, direction=None, alpha=None, flipped=(placed[0],))
        )
    except MechError:
        return None
    pos = flipped.positions
    joints = tuple(
        dataclasses.replace(j, place=dataclasses.replace(j.place, near=(pos[j.name][0], pos[j.name][1])))
        if j.place.at is None and j.name in pos
        else j
        for j in mech.joints
    )
    try:
        twin = sweep(
            dataclasses.replace(mech, joints=joints),
            sw.angles,
            level="position",
            options=options,
            quantities=quantities or None,
        )
    except MechError:
        return None
    ends = sorted(t.angle for t in sw.toggles)
    if len(twin.toggles) != 2 or not np.allclose(sorted(t.angle for t in twin.toggles), ends, atol=1e-9):
        return None  # not the same stretch of the drive: not the circuit's other half
    return twin


def _whole_circuit(sw: Sweep, other: Sweep, ext: Mapping[str, Extreme]) -> dict[str, Extreme] | None:
    """Each quantity's extremes over both branches of the circuit; None when a link's angle turns over it.

    A link's angle is unwrapped along each sweep on its own; the other branch's is moved by whole
    turns to meet this one's at the first toggle.  When it then misses by a whole turn at the
    second, the link comes round a whole turn over the circuit.
    """
    import numpy as np

    from mech.kinematics.sweep_result import Extreme

    theirs = {e.quantity: e for e in other.extremes}
    ok, ok2 = sw.assembled, other.assembled
    both = ok & ok2
    if not np.any(both):
        return None
    # the steps next to the two toggles, where the branches meet
    ends = [int(np.argmin(np.where(both, np.abs(sw.angles - t.angle), np.inf))) for t in sw.toggles]
    turn = 2.0 * math.pi
    out: dict[str, Extreme] = {}
    for q, e in ext.items():
        f = theirs.get(q)
        if f is None:
            out[q] = e
            continue
        shift = 0.0
        if q.startswith("angle."):
            a, b = sw.series(q), other.series(q)
            k = [round(float(a[i] - b[i]) / turn) for i in ends]
            if k[0] != k[1]:
                return None
            shift = turn * k[0]
        lo = (
            (e.min_value, e.min_angle)
            if e.min_value <= f.min_value + shift
            else (f.min_value + shift, f.min_angle)
        )
        hi = (
            (e.max_value, e.max_angle)
            if e.max_value >= f.max_value + shift
            else (f.max_value + shift, f.max_angle)
        )
        out[q] = Extreme(q, e.unit, hi[1], hi[0], lo[1], lo[0])
    return out


def _turns_on(sw: Sweep, subject: str) -> bool:
    """An output that never reverses over a full, gap-free turn of the crank: a gear turning on.

    It has no dead centre and no dwell it comes back from; its range over the turn (a 3:1
    gear's 120°) is no stroke (DESIGN § 1.2: a stroke belongs to an output that reverses).
    Only the outputs whose dead centres the sweep finds are judged (a slider or a link on the
    frame); a block on a moving guide keeps its travel.
    """
    import numpy as np

    full = sw.angles.size > 2 and abs(abs(float(sw.angles[-1] - sw.angles[0])) - 2.0 * math.pi) < 1e-9
    if not full or not bool(np.all(sw.assembled)):
        return False
    outputs = {name for name, _why in sw.time_ratio_refused} | {r.output for r in sw.time_ratios}
    if subject not in outputs:
        return False
    return not any(e.subject == subject for e in sw.dead_centres) and not any(
        d.subject == subject and d.reverses for d in sw.dwells
    )


def _cycle_sweep(
    mech: Mechanism,
    base: Kinematics,
    options: SolveOptions,
    steps: int,
    quantities: list[str],
    outputs: list[str],
) -> Sweep:
    """The sweep the properties are read on: a turn of the crank, or the drawn circuit's part of it.

    Over one turn of the crank, as the notes read a linkage: past a change point the loop need
    not come back where it started (a change-point four-bar's rocker runs 211° on over a turn and
    comes back after two); its swing is then what it covers over that turn.
    """
    import numpy as np

    from mech.kinematics import sweep

    def over(angles: np.ndarray) -> Sweep:
        return sweep(mech, angles, level="position", options=options, quantities=quantities or None)

    sw = over(np.linspace(0.0, 2.0 * math.pi, steps + 1))
    # separate circuits are parted by gaps where the loop cannot close; steps that are not assembled
    # only because they sit on a change point (where the circuits meet) part nothing
    drawn = base.drives[0].angle if base.drives else None
    window = _drawn_circuit(sw.angles, sw.assembled, drawn) if sw.gaps else None
    if window is not None:  # the turn met other circuits: read the drawn one's alone
        return over(np.linspace(window[0], window[1], steps + 1))
    return sw


def _drawn_circuit(angles: np.ndarray, ok: np.ndarray, drawn: float | None) -> tuple[float, float] | None:
    """The drive angles around the drawn circuit, when a turn assembled separate circuits; else None.

    A drive that cannot turn fully (a rocker driving a crank-rocker) meets, over a whole turn,
    the same branch of the closed form on each circuit of the loop (C above AD, and its mirror
    below); no motion joins them. Extremes read over all of them join positions of different
    circuits (the crank's stroke from one circuit's low to the other's high). The window runs
    from the unassembled step before the drawn circuit to the one after it, so the sweep of it
    locates both limit positions as before and holds nothing of another circuit.
    """
    import numpy as np

    n = angles.size - 1  # a full turn: step n is step 0 again
    if drawn is None or n < 2 or abs(angles[-1] - angles[0] - 2.0 * math.pi) > 1e-9:
        return None
    turn = 2.0 * math.pi
    k = int(np.argmin(np.abs((angles[:n] - drawn + math.pi) % turn - math.pi)))
    if not ok[k] or bool(np.all(ok[:n])):
        return None
    left, right = k, k
    while ok[(left - 1) % n]:
        left -= 1
    while ok[(right + 1) % n]:
        right += 1
    if int(np.count_nonzero(ok[:n])) == right - left + 1:
        return None  # one circuit: nothing else was read
    lo, hi = left - 1, right + 1
    return float(angles[lo % n] + turn * (lo // n)), float(angles[hi % n] + turn * (hi // n))


def stroke_joints(mech: Mechanism) -> Sequence[str]:
    """The joints a ``stroke.<joint>`` key may name."""
    return [j for j, _k, _s in _stroke_subjects(mech)]
