"""All n(n−1)/2 I-centres: inspection, Kennedy, the velocity field's cross-check.

:func:`locate` does what a student does — primary I-centres by inspection,
the rest by Kennedy's theorem — and then checks every one against the
velocity solution: the I-centre of links i and j is the one point where their
velocity fields agree.  With ``v_rel`` the relative velocity ``v_i − v_j`` at
a point O and ``Δω = ω_i − ω_j``, that point is ``O + k × v_rel / Δω``; in
homogeneous coordinates (O at the origin) it is simply

    ``(−v_rel,y, v_rel,x, Δω)``,

which is at infinity, perpendicular to ``v_rel``, when Δω = 0 — no division,
no special case.  The two must agree (to 1e-9 of the mechanism's size, widened
only by the propagated error of an ill-conditioned construction); if they do
not, that is a bug and :class:`ICentreDisagreement` is raised rather than a
wrong centre printed.  An I-centre that Kennedy cannot reach (some six-link
chains) is taken from the velocity field, and says so.

Finally every link's ω follows from the driver's through the I-centres
(:func:`omega_by_icentres`): the point I_ij moves alike as a point of i and of
j, so ``ω_j · |I_1j I_ij| = ω_i · |I_1i I_ij|`` — the *I-centre method* of
velocity analysis, shown beside the solver's relative-velocity result.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Mapping, Sequence
from dataclasses import field
from types import MappingProxyType
from typing import TYPE_CHECKING, Protocol

from mech._records import dataclass
from mech.icentres.homogeneous import Frame, Hom, at_infinity, separation, unit
from mech.icentres.inspection import Instant, facts, instant_of
from mech.icentres.kennedy import Found, kennedy, name

if TYPE_CHECKING:  # pragma: no cover
    from mech.kinematics import Kinematics
    from mech.model import Mechanism

__all__ = [
    "CHECK_TOL",
    "ICentre",
    "ICentreDisagreement",
    "ICentres",
    "LinkMotion",
    "OmegaByICentres",
    "from_instant",
    "locate",
]

Vec = tuple[float, float]

#: Kennedy's and the velocity field's I-centre must agree to this (chordal,
#: size units: ≈ |Δp|/size for points within the mechanism).
CHECK_TOL = 1e-9
#: Assumed error of the solved velocities, relative to ω·size: what the field's
#: homogeneous point is divided by when relative motion is nearly nil.
VELOCITY_NOISE = 1e-12
#: Ulps of its largest coordinate that a solved position may be off by: a mechanism 1 mm across
#: drawn 1e6 m from the origin has its points only to 2e-10 m (1.5e-7 of its size), and every
#: construction from them (Kennedy's lines, the velocity field) inherits that.
PLACEMENT_ULPS = 64.0


def placement_noise(frame: Frame) -> float:
    """How finely positions are held where the mechanism is (size units): 64 ulps of its place.

    Coordinates are floats in global metres, so a point far from the origin is known only to
    the spacing of floats there, however small the mechanism: the cross-check cannot ask
    Kennedy and the velocity field to agree more closely than the points they are built on.
    Negligible for a mechanism at the origin (1e-14 of its size for one that is its own size
    away).
    """
    far = math.hypot(*frame.origin) + frame.size
    return PLACEMENT_ULPS * sys.float_info.epsilon * far / frame.size


class ICentreDisagreement(RuntimeError):
    """Kennedy's construction and the velocity field disagree: a bug in mech.

    Not a :class:`~mech.errors.MechError`: no input can cause it legitimately,
    so it must show its traceback and be reported, never pass as bad input.
    """


class LinkMotion(Protocol):
    """What the cross-check needs of a link's motion (a :class:`mech.kinematics.LinkState`)."""

    @property
    def omega(self) -> float | None: ...  # pragma: no cover

    def velocity_at(self, point: Vec) -> Vec: ...  # pragma: no cover


@dataclass(frozen=True, slots=True)
class ICentre:
    """The instantaneous centre of two links.

    Attributes
    ----------
    links
        The two link names, in numbering order.
    numbers
        Their I-centre numbers (ground = 1), ``numbers[0] < numbers[1]``.
    name
        ``I13`` (``I1,12`` once numbers pass 9).
    point
        ``(x, y)`` in m, or None when at infinity (or undetermined).
    direction
        Unit direction of a centre at infinity (turned into [0°, 180°)), else None.
    at_infinity
        True when the centre is at infinity (the two links translate relative
        to each other: equal ω).
    method
        How it was found: ``pin B``, ``slider P: ⟂ path at infinity``,
        ``rolling contact R``, ``Kennedy: I12–I23 ∩ I14–I34``,
        ``velocity field (not reachable by Kennedy)``.
    primary
        True for the I-centres found by inspection (pins, sliders, rolling).
    step
        0 by inspection, k for the k-th round of Kennedy's construction,
        None from the velocity field.
    check
        Separation from the velocity field's centre (chordal, size units), or
        None when not cross-checked (velocities not solved, or no relative
        motion at this instant).
    """

    links: tuple[str, str]
    numbers: tuple[int, int]
    name: str
    point: Vec | None
    direction: Vec | None
    at_infinity: bool
    method: str
    primary: bool
    step: int | None = None
    check: float | None = None

    @property
    def found(self) -> bool:
        """False when neither Kennedy nor the velocity field could locate it."""
        return self.point is not None or self.direction is not None


@dataclass(frozen=True, slots=True)
class OmegaByICentres:
    """A link's angular velocity by the I-centre method.

    ``omega`` rad/s (counter-clockwise positive); ``via`` the I-centres used
    (``I12, I13, I23`` …, or ``driver``); ``solver`` the relative-velocity
    solution's ω for comparison (None when velocities were not solved).
    """

    link: str
    omega: float
    via: str
    solver: float | None = None


@dataclass(frozen=True, slots=True)
class ICentres:
    """All I-centres of a mechanism at one instant.

    Look one up with :meth:`get` (link names), :meth:`by_number` (textbook
    numbers) or :meth:`named` (``"I13"``).
    """

    mechanism: str
    links: tuple[str, ...]
    centres: tuple[ICentre, ...]
    size: float
    rounds: int
    omegas: tuple[OmegaByICentres, ...] = ()
    notes: tuple[str, ...] = ()
    _by_pair: Mapping[tuple[int, int], ICentre] = field(default_factory=dict, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_by_pair", MappingProxyType({c.numbers: c for c in self.centres}))

    @property
    def n(self) -> int:
        """Number of links, ground included."""
        return len(self.links)

    @property
    def count(self) -> int:
        """N = n(n − 1)/2."""
        return len(self.centres)

    @property
    def formula(self) -> str:
        """The count worked: ``N = n(n − 1)/2 = 4·3/2 = 6``."""
        n = self.n
        return f"N = n(n − 1)/2 = {n}·{n - 1}/2 = {n * (n - 1) // 2}"

    @property
    def omega_by_icentres(self) -> dict[str, float]:
        """Link → ω (rad/s, ccw +) by the I-centre method, from the driver's ω."""
        return {o.link: o.omega for o in self.omegas}

    def by_number(self, i: int, j: int) -> ICentre:
        """The I-centre I_ij by textbook numbers (ground = 1), either order."""
        key = (i, j) if i < j else (j, i)
        try:
            return self._by_pair[key]
        except KeyError:
            raise KeyError(f"no I-centre I{i}{j} among {self.n} links") from None

    def get(self, a: str, b: str) -> ICentre:
        """The I-centre of links ``a`` and ``b`` (by name, either order)."""
        try:
            return self.by_number(self.links.index(a) + 1, self.links.index(b) + 1)
        except ValueError:
            raise KeyError(f"no link named {a if a not in self.links else b}") from None

    def named(self, label: str) -> ICentre:
        """The I-centre called ``I13`` (or ``I1,12``)."""
        for c in self.centres:
            if c.name == label:
                return c
        raise KeyError(f"no I-centre named {label}")


# -- the velocity field ----------------------------------------------------------------
def _field(
    instant: Instant, motion: Mapping[str, LinkMotion]
) -> tuple[dict[tuple[int, int], tuple[Hom, float]], float]:
    """Every pair's I-centre from the velocity field: pair → (unit hom, err).

    Pairs with no relative motion at this instant (relative velocity and Δω
    both below the noise) are left out: every point is their I-centre.
    """
    f = instant.frame
    o = f.origin
    states: dict[str, tuple[float, Vec]] = {}
    for lk in instant.links:
        st = motion.get(lk)
        if st is None or st.omega is None:
            return {}, -1.0  # no velocities for this link: nothing to check against
        states[lk] = (st.omega, st.velocity_at(o))
    ref = max(max(abs(w), math.hypot(*v) / f.size) for w, v in states.values())
    if ref == 0.0:
        return {}, 0.0
    noise = VELOCITY_NOISE + placement_noise(f)  # velocities are solved from the placed points
    out: dict[tuple[int, int], tuple[Hom, float]] = {}
    n = len(instant.links)
    for i in range(n):
        wi, vi = states[instant.links[i]]
        for j in range(i + 1, n):
            wj, vj = states[instant.links[j]]
            ux = (vi[0] - vj[0]) / (ref * f.size)
            uy = (vi[1] - vj[1]) / (ref * f.size)
            h = (-uy, ux, (wi - wj) / ref)
            size = math.hypot(*h)
            if size <= 100 * noise:
                continue
            out[(i, j)] = (unit(h), noise / size)
    return out, ref


def _centre(
    instant: Instant,
    pair: tuple[int, int],
    hom: Hom | None,
    method: str,
    primary: bool,
    step: int | None,
    check: float | None,
    xy: Vec | None = None,
) -> ICentre:
    i, j = pair
    links = (instant.links[i], instant.links[j])
    nums = (i + 1, j + 1)
    if hom is None:
        return ICentre(links, nums, name(i, j), None, None, False, method, primary, step, check)
    if xy is not None:
        return ICentre(links, nums, name(i, j), xy, None, False, method, primary, step, check)
    if at_infinity(hom):
        return ICentre(
            links, nums, name(i, j), None, instant.frame.direction(hom), True, method, primary, step, check
        )
    return ICentre(links, nums, name(i, j), instant.frame.xy(hom), None, False, method, primary, step, check)


def from_instant(
    instant: Instant,
    motion: Mapping[str, LinkMotion] | None = None,
    *,
    drivers: Sequence[str] = (),
    mechanism: str = "",
) -> ICentres:
    """Locate every I-centre of an instant; cross-check and complete with ``motion``.

    Parameters
    ----------
    instant
        The geometry (pins, paths, contacts) at the instant, m.
    motion
        Link name → its motion (ω and ``velocity_at``), every link including
        ground; None for a position-only analysis (no cross-check, and an
        I-centre Kennedy cannot reach stays undetermined).
    drivers
        Links whose motion is given (the drives): the I-centre method starts
        from them.
    mechanism
        A label for reports.

    Raises
    ------
    ICentreDisagreement
        Kennedy's centre and the velocity field's differ beyond tolerance.
    """
    result = kennedy(len(instant.links), facts(instant))
    field_, ref = _field(instant, motion) if motion is not None else ({}, 0.0)
    notes: list[str] = []
    at_rest = motion is not None and ref == 0.0
    if at_rest:
        notes.append(
            "every link is at rest (drive speed 0): nothing to cross-check against the velocity field"
        )
    centres: list[ICentre] = []
    placed = placement_noise(instant.frame)  # Kennedy's lines are drawn through the placed points
    n = len(instant.links)
    for i in range(n):
        for j in range(i + 1, n):
            pair = (i, j)
            k: Found | None = result.found.get(pair)
            fv = field_.get(pair)
            if k is not None:
                check = None
                if fv is not None:
                    check = separation(k.hom, fv[0])
                    tol = CHECK_TOL + k.err + fv[1] + placed
                    if not check <= tol:
                        raise ICentreDisagreement(
                            f"{name(*pair)} ({instant.links[i]}, {instant.links[j]}): {k.method} gives "
                            f"{_describe(instant, k.hom)} but the velocity field gives "
                            f"{_describe(instant, fv[0])} (separation {check:.3g} > {tol:.3g} of the size)"
                        )
                elif motion is not None and not at_rest:
                    notes.append(
                        f"{name(*pair)} not cross-checked: {instant.links[i]} and {instant.links[j]} "
                        "have no relative motion at this instant"
                    )
                centres.append(_centre(instant, pair, k.hom, k.method, k.primary, k.step, check, k.xy))
            elif fv is not None:
                why = result.missing[pair]
                centres.append(_centre(instant, pair, fv[0], f"velocity field ({why})", False, None, None))
            else:
                why = result.missing[pair]
                what = "velocities not solved" if motion is None else "no relative motion at this instant"
                centres.append(
                    _centre(instant, pair, None, f"undetermined ({why}; {what})", False, None, None)
                )
    omegas = omega_by_icentres(instant, centres, motion, drivers) if motion is not None else ()
    return ICentres(
        mechanism, instant.links, tuple(centres), instant.frame.size, result.rounds, omegas, tuple(notes)
    )


def _describe(instant: Instant, h: Hom) -> str:
    if at_infinity(h):
        d = instant.frame.direction(h)
        return f"∞ at {math.degrees(math.atan2(d[1], d[0])):.6g}°"
    x, y = instant.frame.xy(h)
    return f"({x:.9g}, {y:.9g}) m"


# -- the I-centre method of velocity analysis -------------------------------------------
def omega_by_icentres(
    instant: Instant,
    centres: Sequence[ICentre],
    motion: Mapping[str, LinkMotion],
    drivers: Sequence[str],
) -> tuple[OmegaByICentres, ...]:
    """Each link's ω from the drivers' through the I-centres.

    For a known link i and an unknown j: the point I_ij has one velocity
    whether it is taken on i or on j, so with I_1j the centre of j relative
    to ground, ``ω_j = (r × v_i(I_ij)) / |r|²`` with ``r = I_ij − I_1j`` —
    the textbook ``ω_j / ω_i = I_1i I_ij / I_1j I_ij`` with its sign.  If I_1j
    is at infinity, j translates (ω_j = 0); if I_ij is, i and j turn alike
    (ω_j = ω_i).  Only the drivers' motion is read from ``motion``; every
    other link is reached link by link, in numbering order.

    Returns
    -------
    tuple of OmegaByICentres
        In numbering order; links no chain of I-centres reaches are left out.
    """
    f = instant.frame
    links = instant.links
    by_pair = {(c.numbers[0] - 1, c.numbers[1] - 1): c for c in centres}

    def centre(i: int, j: int) -> ICentre | None:
        c = by_pair.get((i, j) if i < j else (j, i))
        return c if c is not None and c.found else None

    # Twist of each known link relative to ground: (ω, velocity of the point at f.origin).
    twist: dict[int, tuple[float, Vec]] = {0: (0.0, (0.0, 0.0))}
    via: dict[int, str] = {0: "ground"}
    for d in drivers:
        if d in links and d in motion:
            st = motion[d]
            twist[links.index(d)] = (float(st.omega or 0.0), st.velocity_at(f.origin))
            via[links.index(d)] = "driver"

    def velocity(i: int, p: Vec) -> Vec:
        w, v0 = twist[i]
        return (v0[0] - w * (p[1] - f.origin[1]), v0[1] + w * (p[0] - f.origin[0]))

    progress = True
    while progress:
        progress = False
        for j in range(1, len(links)):
            if j in twist:
                continue
            c1j = centre(0, j)
            if c1j is None:
                continue
            for i in sorted(twist):
                cij = centre(i, j)
                if i == 0 or cij is None:
                    continue
                vi = velocity(i, cij.point) if cij.point is not None else (0.0, 0.0)
                got = _propagate(twist[i][0], vi, c1j, cij, f.size)
                if got is None:
                    continue
                w, v = got
                if v is None:  # turning about I_1j: the velocity at the origin follows
                    cx, cy = c1j.point  # type: ignore[misc]
                    v = (-w * (f.origin[1] - cy), w * (f.origin[0] - cx))
                twist[j] = (w, v)
                via[j] = f"{name(0, i)}, {name(0, j)}, {name(i, j)}"
                progress = True
                break
    out = []
    for k in sorted(twist):
        if k == 0:
            continue
        moving = motion.get(links[k])
        out.append(OmegaByICentres(links[k], twist[k][0], via[k], None if moving is None else moving.omega))
    return tuple(out)


def _propagate(
    wi: float,
    vi: Vec,
    c1j: ICentre,
    cij: ICentre,
    size: float,
) -> tuple[float, Vec | None] | None:
    """Link j's motion from link i's through I_ij and I_1j (None if this triple cannot tell).

    ``wi`` is link i's ω and ``vi`` the velocity of its point at I_ij (unused
    when I_ij is at infinity).  Returns ``(ω_j, v)`` where ``v`` is j's
    translation velocity when j translates, else None (j turns about I_1j).
    """
    if cij.point is None:  # I_ij at infinity: i and j do not turn relative to each other
        if c1j.point is None:
            return None  # both translate: this triple gives no speed
        return (wi, None)
    if c1j.point is None:  # I_1j at infinity: j translates, with I_ij's velocity
        return (0.0, vi)
    rx, ry = cij.point[0] - c1j.point[0], cij.point[1] - c1j.point[1]
    r2 = rx * rx + ry * ry
    if r2 <= (1e-9 * size) ** 2:
        return None  # I_ij on I_1j: this triple says nothing about ω_j
    return ((rx * vi[1] - ry * vi[0]) / r2, None)


def locate(mech: Mechanism, kin: Kinematics | None = None) -> ICentres:
    """All I-centres of ``mech`` at the instant ``kin`` describes.

    Parameters
    ----------
    mech
        The mechanism.
    kin
        Its solve (:func:`mech.kinematics.solve`), at velocity level for the
        cross-check, the completion and the I-centre method; at position level
        Kennedy still runs.  None: solved here at velocity level with the
        file's drive.

    Returns
    -------
    ICentres
        ``count`` = n(n−1)/2 centres, each with how it was found.

    Raises
    ------
    ICentreDisagreement
        Kennedy and the velocity field disagree (a bug).

    Examples
    --------
    >>> import mech
    >>> from mech.icentres import locate
    >>> ic = locate(mech.load("mechanisms/four_bar.yaml"))     # doctest: +SKIP
    >>> ic.named("I13").method                                   # doctest: +SKIP
    'Kennedy: I12–I23 ∩ I14–I34'
    """
    if kin is None:
        from mech.kinematics import solve

        kin = solve(mech, level="velocity")
    instant = instant_of(mech, kin)
    motion: dict[str, LinkMotion] | None = None
    if kin.level != "position":
        motion = dict(kin.links)
        if mech.ground not in motion:
            motion[mech.ground] = _Ground()
    drivers = []
    for d in kin.drives:
        if d.link is not None:
            drivers.append(d.link)
        elif d.joint is not None:
            drivers.append(mech.joint(d.joint).links[0])
    return from_instant(instant, motion, drivers=drivers, mechanism=mech.label)


class _Ground:
    """The ground link's motion when the solve omits it: at rest."""

    omega = 0.0

    @staticmethod
    def velocity_at(point: Vec) -> Vec:
        del point
        return (0.0, 0.0)
