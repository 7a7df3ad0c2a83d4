"""A cam's profile from its follower's programme, by kinematic inversion.

Hold the cam still and turn the rest of the mechanism the other way about the
cam's centre O: the follower then takes, one after another, the places it has
relative to the cam, and the cam's profile is what touches all of them
(Khurmi & Gupta, *Theory of Machines*, ch. 20, "construction of cam profiles";
Rattan, *Theory of Machines*, ch. 6; Norton, *Design of Machinery*, ch. 8).
Instead of drawing the places and joining them by hand, the same inversion is
done analytically here, with the lift's exact derivatives:

* **knife edge** — the profile is the path of the edge relative to the cam
  (the *pitch curve*);
* **roller** — the pitch curve is the path of the roller's centre; the profile
  is that curve offset inward by the roller radius along its normal;
* **flat face** — the profile is the envelope of the face's lines.  With the
  face at distance ``h(θ)`` from O along its unit normal ``m`` turning at angle
  ``α(θ)`` relative to the cam, the envelope point is
  ``q = h m + (h'/α') m⊥`` and its radius of curvature is
  ``ρ = h + (h'/α')'/α'``; for a translating follower ``ρ = r_b + s + s''``
  (Norton eq. 8.30).

Pressure angle: the angle between the common normal at the contact (the
pitch curve's normal, through the roller centre) and the direction the
follower's point moves.  For a translating follower with offset ``e`` it is
``tan φ = (ds/dθ − e) / (√(r_p² − e²) + s)`` (Norton eq. 8.31), with
``r_p`` the prime circle (base radius plus roller radius).

Conventions.  ``σ = +1`` for a cam turning counter-clockwise, −1 clockwise;
``θ`` is its rotation from the programme's start in that sense.  The offset
``e`` is positive when the follower's line is displaced to the side where the
cam's surface moves the same way as the follower rises (the side that lowers
the pressure angle on the rise).  Coordinates are relative to O; the cam's
own frame is the fixed frame at the programme's start (θ = 0).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from mech._records import dataclass
from mech.cam.program import CamProgram, follower_motion

__all__ = ["CamLayout", "CamState", "evaluate", "layout_problem", "swing"]

FloatArray = NDArray[np.float64]
Vec = tuple[float, float]


@dataclass(frozen=True, slots=True)
class CamLayout:
    """Where the follower is, relative to the cam's centre O (all SI).

    ``sense``: +1 when the cam turns counter-clockwise, −1 clockwise.
    Translating follower: ``axis`` is the direction it rises (rad from +x) and
    ``offset`` its signed offset (see the module's conventions).
    Oscillating follower: ``pivot`` (relative to O) and ``arm`` (pivot to the
    knife edge or roller centre, or the face's distance from the pivot for a
    flat face), ``branch`` (+1 or −1) which of the two places the arm can touch
    the base circle from: +1 is to the left of the line from the pivot to O.
    """

    program: CamProgram
    sense: int = 1
    axis: float = math.pi / 2
    offset: float = 0.0
    pivot: Vec | None = None
    arm: float | None = None
    branch: int = 1

    @property
    def oscillating(self) -> bool:
        return self.program.motion == "oscillating"

    @property
    def roller(self) -> float:
        """The roller radius (0 for a knife edge or a flat face)."""
        return (self.program.roller_radius or 0.0) if self.program.follower == "roller" else 0.0

    @property
    def prime_radius(self) -> float:
        """The prime circle: base circle plus roller (Norton's R_p)."""
        return self.program.base_radius + self.roller


@dataclass(frozen=True, slots=True)
class CamState:
    """The follower and the cam's profile at cam angles ``theta`` (arrays of one length N).

    ``s, ds, d2s, d3s``: the lift and its derivatives against θ.
    ``point``: the follower's point (knife edge, roller centre, or where a
    flat face crosses its axis) in the fixed frame, relative to O, (N, 2).
    ``pitch``: the pitch curve in the cam's frame (the follower's point
    relative to the cam), (N, 2).  ``profile``: the cam's surface in its own
    frame, (N, 2).  ``contact``: the point of contact in the fixed frame.
    ``pressure``: the signed pressure angle (rad).  ``rho``: the pitch curve's
    radius of curvature (the profile's, for a flat face); positive where it is
    convex, negative where concave, ``inf`` where straight.  ``normal``: the unit
    common normal at the contact in the fixed frame (out of the cam, toward the
    follower).
    """

    theta: FloatArray
    s: FloatArray
    ds: FloatArray
    d2s: FloatArray
    d3s: FloatArray
    point: FloatArray
    pitch: FloatArray
    profile: FloatArray
    contact: FloatArray
    pressure: FloatArray
    rho: FloatArray
    normal: FloatArray


def _perp(v: FloatArray) -> FloatArray:
    """k × v for rows of 2-vectors (a quarter turn counter-clockwise)."""
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


def _rot(v: FloatArray, angle: FloatArray) -> FloatArray:
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], axis=-1)


def _dot(a: FloatArray, b: FloatArray) -> FloatArray:
    return np.einsum("...i,...i->...", a, b)  # type: ignore[no-any-return]


def _cross(a: FloatArray, b: FloatArray) -> FloatArray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]  # type: ignore[no-any-return]


def layout_problem(layout: CamLayout) -> str | None:
    """Why the follower cannot sit on the base circle as laid out, or ``None``."""
    prog = layout.program
    rp = layout.prime_radius
    if prog.follower == "roller" and not (prog.roller_radius or 0.0) > 0:
        return "a roller follower needs `roller_radius`"
    if not layout.oscillating:
        if prog.follower != "flat" and abs(layout.offset) >= rp:
            return (
                f"the offset {abs(layout.offset):.6g} m is not less than the prime circle's radius "
                f"{rp:.6g} m (base + roller): the follower's line misses the cam"
            )
        return None
    if layout.pivot is None or layout.arm is None:
        return "an oscillating follower needs its pivot and its arm's length"
    d = math.hypot(*layout.pivot)
    if not d > 1e-9 * (prog.base_radius + layout.roller):
        return "the follower's pivot is at the cam's centre: it cannot swing the follower off the cam"
    if prog.follower == "flat":
        if abs(prog.base_radius - layout.arm) > d:
            return "the flat face cannot touch the base circle from that pivot"
        return None
    if not (abs(layout.arm - d) <= rp <= layout.arm + d):
        return (
            f"an arm of {layout.arm:.6g} m about a pivot {d:.6g} m from the cam's centre "
            f"cannot reach the prime circle (radius {rp:.6g} m)"
        )
    return None


def _start_point(layout: CamLayout) -> FloatArray:
    """Where the oscillating arm's point meets the prime circle at the start (relative to O)."""
    p = np.array(layout.pivot, dtype=float)
    d = float(np.hypot(*p))
    L, r = float(layout.arm), layout.prime_radius  # type: ignore[arg-type]
    # along P→O a distance a from P, then sideways b
    a = (L * L - r * r + d * d) / (2 * d)
    b = math.sqrt(max(L * L - a * a, 0.0))
    along = -p / d
    return p + a * along + layout.branch * b * _perp(along)  # type: ignore[no-any-return]


def swing(layout: CamLayout) -> tuple[float, float]:
    """An oscillating follower's angle at the programme's start and the sense a rise swings it (±1).

    For a knife edge or a roller the angle is the arm's (pivot → point); for a flat
    face, its normal's.  At lift ``s`` the angle is ``start + sense·s``: the follower
    link turns by exactly ``sense·s`` (the law's own lift, in radians).
    """
    p = np.array(layout.pivot, dtype=float)
    if layout.program.follower == "flat":
        d = float(np.hypot(*p))
        delta = math.atan2(p[1], p[0])
        rb, face = layout.program.base_radius, float(layout.arm)  # type: ignore[arg-type]
        # m·p − face = r_b at the start (the face touches the base circle, the cam on its far side)
        g0 = delta + layout.branch * math.acos(max(-1.0, min(1.0, (rb + face) / d)))
        # the face must move away from O as it rises: dh/dγ = m⊥·p
        return g0, math.copysign(1.0, -math.sin(g0 - delta) * d)
    c0 = _start_point(layout)
    r0 = (c0 - p) / layout.arm
    return math.atan2(r0[1], r0[0]), math.copysign(1.0, float(np.dot(c0, _perp(r0))))  # away from O


def evaluate(layout: CamLayout, theta: ArrayLike) -> CamState:
    """The follower, the pitch curve and the profile at cam angles ``theta`` (rad).

    Raises ``ValueError`` when :func:`layout_problem` finds the layout impossible.
    """
    problem = layout_problem(layout)
    if problem:
        raise ValueError(problem)
    prog = layout.program
    sig = float(layout.sense)
    th = np.atleast_1d(np.asarray(theta, dtype=float))
    m = follower_motion(prog, th)
    s, s1, s2 = m.s, m.ds, m.d2s
    col = s[:, None]
    if prog.follower == "flat":
        return _flat(layout, th, m)
    if not layout.oscillating:
        u = np.array([math.cos(layout.axis), math.sin(layout.axis)])
        n = _perp(u)
        e_n = -sig * layout.offset  # the offset measured along k × u
        d0 = math.sqrt(layout.prime_radius**2 - layout.offset**2)
        c = e_n * n + (d0 + col) * u
        c1 = s1[:, None] * u
        c2 = s2[:, None] * u
        w = np.broadcast_to(u, c.shape)
    else:
        p = np.array(layout.pivot, dtype=float)
        psi0, sf = swing(layout)
        psi = psi0 + sf * s
        rhat = np.stack([np.cos(psi), np.sin(psi)], axis=-1)
        L = float(layout.arm)  # type: ignore[arg-type]
        c = p + L * rhat
        c1 = sf * s1[:, None] * L * _perp(rhat)
        c2 = sf * s2[:, None] * L * _perp(rhat) - (s1**2)[:, None] * L * rhat
        w = sf * _perp(rhat)
    # the point's path relative to the cam, differentiated in the fixed frame
    a_ = c1 - sig * _perp(c)
    b_ = c2 - 2 * sig * _perp(c1) - c
    pitch = _rot(c, -sig * th)
    orient = -sig  # the follower goes round the cam against its turning
    speed = np.hypot(a_[:, 0], a_[:, 1])
    t_ccw = orient * a_ / speed[:, None]
    n_out = np.stack([t_ccw[:, 1], -t_ccw[:, 0]], axis=-1)
    r = layout.roller
    contact = c - r * n_out
    profile = _rot(contact, -sig * th)
    with np.errstate(divide="ignore"):
        rho = speed**3 / (orient * _cross(a_, b_))
    pressure = np.arctan2(_dot(a_, w), np.abs(_dot(a_, _perp(w))))
    return CamState(th, s, s1, s2, m.d3s, c, pitch, profile, contact, pressure, rho, n_out)


def _flat(layout: CamLayout, th: FloatArray, m: object) -> CamState:
    """A flat-faced follower: the profile is the envelope of the face's lines."""
    from mech.cam.laws import Motion

    assert isinstance(m, Motion)
    prog = layout.program
    sig = float(layout.sense)
    s, s1, s2 = m.s, m.ds, m.d2s
    rb = prog.base_radius
    if not layout.oscillating:
        u = np.array([math.cos(layout.axis), math.sin(layout.axis)])
        n = _perp(u)
        e_n = -sig * layout.offset
        gamma = np.full_like(th, layout.axis)
        h, h1, h2 = rb + s, s1, s2
        point = e_n * n + (rb + s)[:, None] * u
    else:
        p = np.array(layout.pivot, dtype=float)
        face = float(layout.arm)  # type: ignore[arg-type]  # the face's distance from the pivot
        g0, sf = swing(layout)
        gamma = g0 + sf * s
        mm = np.stack([np.cos(gamma), np.sin(gamma)], axis=-1)
        mp = _dot(mm, np.broadcast_to(p, mm.shape))
        mperp_p = _dot(_perp(mm), np.broadcast_to(p, mm.shape))
        h = mp - face
        h1 = sf * s1 * mperp_p
        h2 = sf * s2 * mperp_p - s1**2 * mp
        point = p - face * mm
    mm = np.stack([np.cos(gamma), np.sin(gamma)], axis=-1)
    if layout.oscillating:
        al1 = sf * s1 - sig
        al2 = sf * s2
    else:
        al1 = np.full_like(th, -sig)
        al2 = np.zeros_like(th)
    q_over = h1 / al1  # h'/α'
    contact = h[:, None] * mm + q_over[:, None] * _perp(mm)  # fixed frame, relative to O
    profile = _rot(contact, -sig * th)
    rho = h + (h2 * al1 - h1 * al2) / al1**3
    if layout.oscillating:
        w = sf * _perp(contact - np.array(layout.pivot, dtype=float))
    else:
        w = np.broadcast_to(np.array([math.cos(layout.axis), math.sin(layout.axis)]), contact.shape)
    pressure = np.arctan2(_dot(w, _perp(mm)), _dot(w, mm))
    return CamState(th, s, s1, s2, m.d3s, point, profile, profile, contact, pressure, rho, mm)
