"""What a sweep returns: the frozen :class:`Sweep` and what it found (gaps, events, extremes, time ratio)."""

from __future__ import annotations

import math

import numpy as np

from mech._records import dataclass
from mech.kinematics.quantities import LEVELS, check_quantity, pick

__all__ = ["DriveLaw", "Dwell", "Event", "Extreme", "Gap", "Sweep", "TimeRatio", "frozen"]


@dataclass(frozen=True, slots=True)
class Gap:
    """Drive angles ``start``–``end`` (rad) the sweep has no configuration for.

    ``cannot_close`` True: the loop cannot close there — the closed form's dyad
    ``what`` cannot reach, ``miss`` (m) from closing at worst.  False: the stretch was
    not reached — Newton continuation from the drawing stops at a limit on the way
    (``what`` says so); the loop may still close there on another circuit, so it is
    not called unable to.
    """

    start: float
    end: float
    miss: float
    what: str
    cannot_close: bool = True

    @property
    def kind(self) -> str:
        """``cannot close`` (the loop does not close there) or ``not reached`` (from the drawing)."""
        return "cannot close" if self.cannot_close else "not reached"


@dataclass(frozen=True, slots=True)
class Event:
    """A located event: a toggle (``kind="toggle"``), a dead centre (``"dead centre"``) or a change point.

    ``angle`` is the drive angle (rad); ``subject`` the output or the links in
    line; ``value`` the output's position there (slider displacement, m, or
    link angle, rad), None for a toggle.
    """

    kind: str
    angle: float
    subject: str
    value: float | None = None


@dataclass(frozen=True, slots=True)
class Dwell:
    """An output at rest over drive angles ``start``–``end`` (rad): one dwell, not dead centres.

    Over a full turn a dwell across the seam has ``start`` > ``end`` (from 300° on to 60°).
    ``value`` is where the output rests (a slider's displacement, m, or a link's angle, rad,
    in [0, 2π)); ``reverses`` says the output comes back the way it went: the dwell is then a
    limit position (a cam follower's dwell at its top or bottom), else a pause on the way.
    """

    subject: str
    start: float
    end: float
    value: float
    reverses: bool


@dataclass(frozen=True, slots=True)
class Extreme:
    """Largest and smallest value of one quantity over the sweep, with the drive angles (rad)."""

    quantity: str
    unit: str
    max_angle: float
    max_value: float
    min_angle: float
    min_value: float
    #: Where the largest (least) value is reached at a jump, not at the top of a smooth curve: the
    #: values just before and just after the angle, in the sweep's direction (a cam's acceleration
    #: where one segment of its law gives way to the next); None where it is an extreme.
    max_jump: tuple[float, float] | None = None
    min_jump: tuple[float, float] | None = None


@dataclass(frozen=True, slots=True)
class TimeRatio:
    """Quick return: crank angles (rad) of the slow and fast strokes of ``output`` and their ratio."""

    output: str
    slow: float
    fast: float

    @property
    def ratio(self) -> float:
        """Slow stroke over fast stroke (cutting / return for a shaper), ≥ 1."""
        return self.slow / self.fast


@dataclass(frozen=True, slots=True)
class DriveLaw:
    """How one drive moves over a sweep: linear in the sweep's parameter.

    ``kind`` is ``"angle"`` (a turning drive: its angle, rad, relative to
    ``relative_to`` when the file says so, else absolute) or ``"position"`` (a
    slider drive: its point's position along its path from the path's
    ``through``, m).  ``rate`` is its speed (rad/s or m/s, None where the file
    gives none); ``per_parameter`` how much it moves per unit of the parameter
    (1 for the lead drive: rad/rad, m/rad, rad/m or m/m).
    """

    drive: str
    kind: str
    rate: float | None
    per_parameter: float
    relative_to: str | None = None


def frozen(a: np.ndarray | None) -> np.ndarray | None:
    if a is not None:
        a.flags.writeable = False
    return a


@dataclass(frozen=True)
class Sweep:
    """A mechanism solved over an array of drive angles.  Arrays are read-only.

    Attributes
    ----------
    mechanism, level, method
        The mechanism's label, the level solved, ``"closed form"`` or ``"newton"``.
    drive
        The driving link; ``omega``/``alpha`` its speed (rad/s, ccw +; None
        at position level without a speed) and angular acceleration.
    angles
        (N,) drive angles, rad, in the order swept.
    points
        Names of the points, in the order of the second axis of ``positions``.
    positions, velocities, accelerations
        (N, P, 2) arrays, m, m/s, m/s² (None above the level); NaN where not
        assembled (and velocities, accelerations NaN where singular).
    links
        Moving links; ``link_angles`` (N, L) rad, unwrapped along the sweep;
        ``omegas``, ``alphas`` (N, L) rad/s, rad/s².
    slides
        Prismatic and slot joints; ``displacement`` (N, S) the slider point's
        position along its path from the path's ``through`` point, m;
        ``sliding`` (N, S) its speed along the path relative to the guide, m/s.
    assembled
        (N,) bool.
    condition
        (N,) the largest dyad condition number at each step (Newton: of Φ_q).
    gaps, toggles, dead_centres, extremes, time_ratio, notes
        What the sweep found (see the classes).  ``time_ratio`` is the bare one: the
        mechanism's one output with a time ratio (or several with the same one), else None.
    dwells
        Where an output rests over an interval (:class:`Dwell`); no dead centre lies inside one.
    time_ratios
        The time ratio of every output with two dead centres over a full, gap-free turn.
    time_ratio_refused
        (output, why) for every output without a time ratio, and ("", why) when the bare
        ``time_ratio`` is refused: reasons true of this sweep.
    change_points
        Change points passed (``kind="change point"``): a dyad's two positions
        meet and part again with the loop closed on both sides; the sweep
        continues on the branch whose tangent is continuous (:func:`~mech.kinematics.dyads.change_points`).
    parameter
        What ``angles`` holds: ``"angle"`` (the drive's angle, rad: one crank,
        or the lead of several drives) or ``"position"`` (a slider drive's
        position along its path, m).  Every event's ``angle`` is a value of it.
    drives
        With a slider drive or several drives, how each moves (:class:`DriveLaw`),
        the lead (``drive``) first; empty for one crank.
    """

    mechanism: str
    level: str
    method: str
    drive: str
    omega: float | None
    alpha: float
    angles: np.ndarray
    points: tuple[str, ...]
    positions: np.ndarray
    velocities: np.ndarray | None
    accelerations: np.ndarray | None
    links: tuple[str, ...]
    link_angles: np.ndarray
    omegas: np.ndarray | None
    alphas: np.ndarray | None
    slides: tuple[str, ...]
    displacement: np.ndarray
    sliding: np.ndarray | None
    assembled: np.ndarray
    condition: np.ndarray
    gaps: tuple[Gap, ...]
    toggles: tuple[Event, ...]
    dead_centres: tuple[Event, ...]
    extremes: tuple[Extreme, ...]
    time_ratio: TimeRatio | None
    change_points: tuple[Event, ...]
    notes: tuple[str, ...]
    parameter: str = "angle"
    drives: tuple[DriveLaw, ...] = ()
    dwells: tuple[Dwell, ...] = ()
    time_ratios: tuple[TimeRatio, ...] = ()
    time_ratio_refused: tuple[tuple[str, str], ...] = ()

    def time_ratio_of(self, output: str | None = None) -> TimeRatio | str:
        """The time ratio of ``output`` (None: the bare one), or why there is none."""
        if output is None and self.time_ratio is not None:
            return self.time_ratio
        for tr in self.time_ratios:
            if output is not None and tr.output == output:
                return tr
        why = dict(self.time_ratio_refused).get(output or "")
        return why or f"{output} is not an output whose dead centres a sweep finds"

    def series(self, quantity: str) -> np.ndarray:
        """The (N,) values of one quantity (see :func:`quantity_unit` for the keys)."""
        check_quantity(self.points, self.links, self.slides, quantity, LEVELS.index(self.level))
        arrays = {
            "link_angles": self.link_angles,
            "omegas": self.omegas,
            "alphas": self.alphas,
            "displacement": self.displacement,
            "sliding": self.sliding,
            "positions": self.positions,
            "velocities": self.velocities,
            "accelerations": self.accelerations,
        }
        return pick(arrays, {"links": self.links, "slides": self.slides, "points": self.points}, quantity)

    @property
    def max_condition(self) -> float:
        """The largest condition number met at an assembled step."""
        c = self.condition[self.assembled]
        return float(np.max(c)) if c.size else math.nan
