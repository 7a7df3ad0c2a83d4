"""Closed-form kinematics of chains that decompose into dyads: the fast path.

A crank-driven chain whose links can be placed one dyad at a time (Assur
groups of class II) has closed-form positions, and differentiating those
closed forms gives velocities and accelerations with two linear equations
per dyad.  :func:`program` finds such a decomposition of a mechanism once
and compiles it; the compiled program then evaluates

* one configuration on plain floats (``math``), a few microseconds, and
* a whole array of crank angles at once (``numpy``), for sweeps,

from **one** body of code: the program is generated as a straight-line
Python function whose only operations are arithmetic and ``sqrt``, ``cos``,
``sin``, ``atan2``, ``clip`` passed in as arguments, so the same function
runs on floats and on arrays.  Each primitive below is one template with its
formula written out, so it reads like the textbook derivation.

Why generated code and not ordinary functions (issue 12 asked for functions
"if at the same speed"; measured, they are not).  The four-bar's program was
rewritten as ordinary functions (tests/benchmarks/bench_dyad_functions.py):
one closure per step (ground, crank, point, pose, rrr) over a list of
registers, the same formulas, the same results to 1e-12, timed against the
generated function in one interleaved run (medians of 5–9 repeats, three
runs; 2 shared cores, Python 3.11, numpy 2.4).  At acceleration level on
floats the generated function takes 4.4–6.0 µs, the functions 9.0–10.1 µs
(1.7–2.0×: eleven calls and register indexing instead of locals).  ``state``
(the lean row of the benchmark table) takes 7.7–8.0 µs against pylinkage's
33–37 µs for one step with derivatives (0.20–0.23×, target ≤ 0.3×); the
functions would add 4–5 µs to it (about 0.35×, over the target).  On arrays
the functions were faster (3,601 angles in 1.5–1.6 ms against 1.8–2.7 ms),
which is 7–20 % of the four-bar's 4.3–5.1 ms 3,600-step sweep series: a lead
for the sweep's speed (the generated function keeps more arrays alive at
once), not a reason for a second body of code beside the first.  The
generation stays; :class:`_Builder` names its steps.

Primitives (Norton, *Design of Machinery*, ch. 4, 6, 7; Haug ch. 3 for the
derivative rows).  P, Q, A, O are points already known, with their velocity
and acceleration; the branch is an explicit sign taken from the drawn
configuration, so the closed form stays on the assembly the file drew:

``crank``
    a link turned by the drive about a ground pivot: ``θ = φ + const``.
``rrr``
    the apex J of two links of lengths ``lP``, ``lQ`` pinned at P and Q
    (a four-bar's coupler and rocker): circle–circle, J to the left of
    P → Q when ``sign`` is +1.  Velocity: ``(J − P)·v_J = (J − P)·v_P`` and the
    same for Q; acceleration adds ``−|v_J − v_P|²`` (the centripetal term).
``rrp``
    the point B of a link of length ``l`` from A that runs on a line of a
    known guide (a slider crank's piston): circle–line, B ahead of A along
    the path when ``sign`` is +1.  The path row ``n·(B − T) = 0`` brings the
    guide's ω and the Coriolis term ``2ω u·(v_B − v_T)``.
``rpr``
    a guide link pivoted at a known point O whose straight path must pass
    through a known point P (a crank and slotted lever): the guide's angle
    from ``n·(P − O) = e`` (e the path's offset from O), with ``ω = n·(v_P −
    v_O)/(u·(P − O))``.
``pose2`` / ``pose_angle``
    a link from two known points of it, or from one point and an angle fixed
    to another link (a slider block on its guide).

Each dyad reports a relative *discriminant* (negative: the loop cannot
close at that angle, so the program never returns a silent NaN: the caller
sees which dyad failed and by how much) and the sine of the angle between
its two constraint rows (near zero: links in line, a toggle, where the
velocity rows become singular; ``1/|sin|`` is the dyad's condition number).

Everything is computed in SI relative to a ground pivot (the constraint
system's ``centre``), so a linkage a million metres from the origin keeps
full relative precision.  Anything that does not decompose this way (a
higher pair, a slider drive, a loop of three or more links, several drives)
gets ``None`` from :func:`program` and is solved by the general Newton
solver.
"""

from __future__ import annotations

import math
from dataclasses import field
from typing import Any

from mech._records import dataclass
from mech.kinematics.constraints import System
from mech.kinematics.layout import Layout
from mech.pairs import kind_of

__all__ = [
    "ChangePoint",
    "DyadProgram",
    "FastState",
    "branches",
    "change_points",
    "closing_edge",
    "passed",
    "program",
    "route",
]

#: A relative discriminant above −this is a tangency within rounding (assembled).
SLACK = 1e-12
#: Dyad condition number up to which velocities and accelerations are reported.  Their
#: relative error grows like 2e-16·cond² (positions feed the rows, and the rows are then
#: solved: two factors of cond), measured against 50-digit mpmath on a four-bar closing
#: on its toggle: 6e-12 at cond 410, 3e-10 at 1.4e3, 1.8e-7 at 3.2e4.  1e5 keeps them
#: within about 1e-6; beyond it they are refused, not printed.
ACCURATE_COND = 1e5


@dataclass(frozen=True, slots=True)
class FastState:
    """One configuration from the closed form, as flat tuples (SI): the lean result.

    ``x[k], y[k]`` is the position of ``program.points[k]`` (m), ``vx, vy``
    its velocity, ``ax, ay`` its acceleration; ``theta[k], omega[k],
    alpha[k]`` belong to ``program.links[k]`` (rad, rad/s, rad/s², ccw +).
    Fields above the asked level are None.  ``condition`` is the largest
    dyad condition number (1/|sin| of the angle between its two rows).
    Flat tuples because building pairs would cost more than the solve.
    """

    program: DyadProgram
    x: tuple[float, ...]
    y: tuple[float, ...]
    theta: tuple[float, ...]
    vx: tuple[float, ...] | None
    vy: tuple[float, ...] | None
    omega: tuple[float, ...] | None
    ax: tuple[float, ...] | None
    ay: tuple[float, ...] | None
    alpha: tuple[float, ...] | None
    condition: float

    def position(self, name: str) -> tuple[float, float]:
        """(x, y) of a named point, m."""
        k = self.program.points.index(name)
        return (self.x[k], self.y[k])

    def velocity(self, name: str) -> tuple[float, float]:
        """(vx, vy) of a named point, m/s."""
        if self.vx is None or self.vy is None:
            raise ValueError("velocities were not computed (level 0)")
        k = self.program.points.index(name)
        return (self.vx[k], self.vy[k])

    def acceleration(self, name: str) -> tuple[float, float]:
        """(ax, ay) of a named point, m/s²."""
        if self.ax is None or self.ay is None:
            raise ValueError("accelerations were not computed (level < 2)")
        k = self.program.points.index(name)
        return (self.ax[k], self.ay[k])


@dataclass(frozen=True, eq=False)
class DyadProgram:
    """A compiled closed-form solution of one single-crank mechanism.

    Attributes
    ----------
    steps
        The decomposition, one line each (``rrr C from B, D``), for notes and tests.
    links
        Moving links in the constraint system's order (q order).
    points
        Every location, in the system's ``loc_names`` order (``#`` names included).
    dyads
        Per dyad: ``(kind, what it places, what is in line at its limit)``.
    centre
        Global origin of the computed coordinates (m): add it to positions.
    drawn_angle
        The drive's angle in the drawn configuration (rad).
    source
        The generated code of the acceleration-level function (for reading).
    """

    steps: tuple[str, ...]
    links: tuple[str, ...]
    points: tuple[str, ...]
    dyads: tuple[tuple[str, str, str], ...]
    centre: tuple[float, float]
    drawn_angle: float
    drive_link: str
    source: str
    _fns: tuple[Any, Any, Any] = field(repr=False)
    _sizes: tuple[int, int, int] = field(repr=False)  # dyads, links, points
    _memo: dict[str, Any] = field(default_factory=dict, repr=False)  # lazily computed closure gaps

    # -- evaluation -------------------------------------------------------------------
    def raw(
        self,
        phi: Any,
        omega: Any = 0.0,
        alpha: Any = 0.0,
        *,
        level: int = 2,
        xp: Any = None,
        branch: tuple = (),
    ) -> tuple:
        """The flat output tuple of the generated function (see :meth:`split`).

        ``xp`` is ``math`` for floats or :data:`NUMPY` for arrays of angles.
        ``branch`` holds each dyad's branch multiplier (+1 the drawn one, −1 the
        other; floats, or arrays shaped as ``phi``): :func:`branches` gives them
        for angles reached past change points; empty, the drawn branch throughout.
        """
        xp = xp or MATH
        return self._fns[level](phi, omega, alpha, xp.sqrt, xp.cos, xp.sin, xp.atan2, xp.clip, *branch)

    def split(self, out: tuple, level: int) -> dict[str, tuple]:
        """Named slices of a raw output.

        ``disc`` (relative discriminant, < 0: cannot close), ``sin`` (dyad row
        sines), ``miss`` (how far the dyad is from closing, m; ≤ 0 when it
        closes), link origins ``lx, ly`` and angles ``lt``, points ``px, py``;
        then ``lvx, lvy, lw, pvx, pvy`` and ``lax, lay, lal, pax, pay``.
        """
        nd, nl, np_ = len(self.dyads), len(self.links), len(self.points)
        names = ["disc", "sin", "miss", "lx", "ly", "lt", "px", "py"]
        sizes = [nd, nd, nd, nl, nl, nl, np_, np_]
        if level >= 1:
            names += ["lvx", "lvy", "lw", "pvx", "pvy"]
            sizes += [nl, nl, nl, np_, np_]
        if level >= 2:
            names += ["lax", "lay", "lal", "pax", "pay"]
            sizes += [nl, nl, nl, np_, np_]
        parts, k = {}, 0
        for name, size in zip(names, sizes, strict=True):
            parts[name] = out[k : k + size]
            k += size
        return parts

    def state(self, phi: float, omega: float = 0.0, alpha: float = 0.0, *, level: int = 2) -> FastState:
        """One configuration on floats: the single-solve fast path.

        Parameters
        ----------
        phi
            Drive angle, rad, counter-clockwise from +x.
        omega, alpha
            Drive speed (rad/s) and angular acceleration (rad/s²), ccw +.
        level
            0 positions, 1 and velocities, 2 and accelerations.

        Raises
        ------
        ValueError
            When a dyad cannot close at ``phi``: which one, and by how much
            (never a NaN).  :func:`mech.kinematics.solve` words it for users.

        Examples
        --------
        >>> st = prog.state(math.radians(60), -4 * math.pi)      # doctest: +SKIP
        >>> st.omega[prog.links.index("rocker")]                 # doctest: +SKIP
        -4.785...
        """
        try:
            out = self._fns[level](phi, omega, alpha, _sqrt, _cos, _sin, _atan2, _clip)
        except ZeroDivisionError:  # a dyad that cannot close, or exactly in line: say which
            out = self._fns[0](phi, omega, alpha, _sqrt, _cos, _sin, _atan2, _clip)
            if min(out[: self._sizes[0]], default=1.0) >= -SLACK:
                raise ValueError(
                    f"singular configuration at {math.degrees(phi):.6g}°: links in line (a toggle)"
                ) from None
        nd, nl, npt = self._sizes
        if nd:
            worst = min(out[:nd])
            if worst < -SLACK:
                k = out[:nd].index(worst)
                kind, placed, _ = self.dyads[k]
                raise ValueError(
                    f"the {kind} dyad placing {placed} cannot close at {math.degrees(phi):.6g}° "
                    f"(short by {out[2 * nd + k]:.6g} m)"
                )
            small = min([abs(v) for v in out[nd : 2 * nd]]) if nd > 1 else abs(out[nd])
            cond = 1.0 / small if small > 0.0 else math.inf
        else:
            cond = 1.0
        o = 3 * nd
        theta = out[o + 2 * nl : o + 3 * nl]
        o += 3 * nl
        x, y = out[o : o + npt], out[o + npt : o + 2 * npt]
        cx, cy = self.centre
        if cx or cy:
            x = tuple([v + cx for v in x])
            y = tuple([v + cy for v in y])
        o += 2 * npt
        vx = vy = w = ax = ay = al = None
        if level >= 1:
            w = out[o + 2 * nl : o + 3 * nl]
            o += 3 * nl
            vx, vy = out[o : o + npt], out[o + npt : o + 2 * npt]
            o += 2 * npt
        if level >= 2:
            al = out[o + 2 * nl : o + 3 * nl]
            o += 3 * nl
            ax, ay = out[o : o + npt], out[o + npt : o + 2 * npt]
        return FastState(self, x, y, theta, vx, vy, w, ax, ay, al, cond)


_sqrt, _cos, _sin, _atan2 = math.sqrt, math.cos, math.sin, math.atan2


def _clip(x: float) -> float:
    return x if x > 0.0 else 0.0


class _Numpy:
    """The array namespace handed to the generated code (numpy, with a clip at zero)."""

    def __init__(self) -> None:
        import numpy as np

        self.sqrt, self.cos, self.sin, self.atan2 = np.sqrt, np.cos, np.sin, np.arctan2
        self._max = np.maximum

    def clip(self, x: Any) -> Any:
        return self._max(x, 0.0)


class _Math:
    """The float namespace: ``math`` plus a clip at zero."""

    sqrt, cos, sin, atan2 = math.sqrt, math.cos, math.sin, math.atan2

    @staticmethod
    def clip(x: float) -> float:
        return x if x > 0.0 else 0.0


MATH = _Math()
_NUMPY: _Numpy | None = None


def numpy_namespace() -> _Numpy:
    """The numpy namespace for :meth:`DyadProgram.raw` (built on first use)."""
    global _NUMPY
    if _NUMPY is None:
        _NUMPY = _Numpy()
    return _NUMPY


# -- decomposition -------------------------------------------------------------------------


def program(comp: Any) -> DyadProgram | None:
    """The closed-form program of a compiled mechanism, or None when it does not decompose.

    Kept in the memo of the :class:`~mech.kinematics.solve.Compiled` (itself
    kept in the mechanism's).  The program is accepted only if it reproduces the drawn
    configuration and satisfies *every* constraint row of the system (so a
    row the decomposition did not use, a redundant one, still holds) at a
    few angles round the cycle; otherwise None, and Newton is used.
    """
    return comp.memo.get("program", lambda: _checked_program(comp))  # type: ignore[no-any-return]


def _checked_program(comp: Any) -> DyadProgram | None:
    """The program built and verified (or None): :func:`program`'s work, done once per compiled mechanism."""
    try:
        prog = _build(comp.layout, comp.system, comp.drawn.drive_angles)
    except _NoDecomposition:
        prog = None
    if prog is not None and not _verified(prog, comp.system):
        prog = None
    return prog


class _NoDecomposition(Exception):
    pass


def _fmt(x: float) -> str:
    return repr(float(x))


def _build(lay: Layout, sys_: System, drive_angles: tuple[float | None, ...]) -> DyadProgram:
    """Find the dyad decomposition and generate its code.

    The steps, each a method of :class:`_Builder`: the drawn frames of every
    link, the crank, then rounds of the four placement rules (a link posed
    rigidly from known points, an RRR apex, an RRP slider, an RPR guide) until
    every link is known, and the three functions compiled (one per level).
    """
    if len(lay.drives) != 1 or sys_.velocity_only or any(kind_of(j).dyad is None for j in lay.mech.joints):
        raise _NoDecomposition
    spec = lay.drives[0]
    if spec.link is None or spec.reference != lay.mech.ground or drive_angles[0] is None:
        raise _NoDecomposition
    b = _Builder(lay, sys_)
    b.ground_constants()
    b.crank(spec.link, spec.pivot, drive_angles[0])
    rules = (b.pose_rigid, b.rrr, b.rrp, b.rpr)
    while len(b.known_links) < b.n + 1 and any(rule() for rule in rules):
        pass
    if len(b.known_links) < b.n + 1:
        raise _NoDecomposition
    for name in b.pos:
        b.emit_point(name)
    fns, source = b.compile(lay.mech.label)
    return DyadProgram(
        steps=tuple(b.steps),
        links=sys_.links,
        points=tuple(b.pos),
        dyads=tuple(b.dyads),
        centre=(float(sys_.centre[0]), float(sys_.centre[1])),
        drawn_angle=float(drive_angles[0]),
        drive_link=spec.link,
        source=source,
        _fns=fns,
        _sizes=(len(b.dyads), b.n, len(b.pos)),
    )


class _Builder:
    """The state of one decomposition: what is known so far and the code emitted for it.

    Code lines carry a level prefix: none (positions), ``#V`` (velocities) or
    ``#A`` (accelerations); :meth:`compile` keeps the lines each level needs.
    Each placement rule returns True when it placed something (the rules are
    retried in order from the first after every success, so rigid poses are
    always preferred to a new dyad).
    """

    def __init__(self, lay: Layout, sys_: System) -> None:
        self.lay, self.sys = lay, sys_
        self.n, self.scale = sys_.n, sys_.scale
        self.gi = sys_.n  # the ground's index
        self.idx = sys_.link_index
        self.pos, self.frame = self._drawn_frames()
        ground, gi = lay.mech.ground, self.gi
        self.carriers = {
            name: tuple(self.idx.get(c, gi) if c != ground else gi for c in lay.carriers.get(name, ()))
            for name in self.pos
        }
        self.on = {i: [p for p in self.pos if i in self.carriers[p]] for i in range(self.n + 1)}
        size = (
            max((math.dist(a, b) for a in self.pos.values() for b in self.pos.values()), default=1.0) or 1.0
        )
        self.tiny = 1e-9 * size
        self.known_links: set[int] = {gi}
        self.avail: set[str] = {p for p in self.pos if gi in self.carriers[p]}
        self.code: list[str] = []
        self.steps: list[str] = []
        self.dyads: list[tuple[str, str, str]] = []
        self.emitted: set[str] = set()
        self.prismatic = [ps for ps in lay.paths if kind_of(ps.type).keeps_angle]
        self._names = list(self.pos)

    def _drawn_frames(self) -> tuple[dict[str, tuple[float, float]], dict[int, tuple[float, float, float]]]:
        """Drawn positions (SI, relative to the centre) of every location, and each link's frame."""
        sys_, scale, gi, q0 = self.sys, self.scale, self.gi, self.sys.q0
        pos: dict[str, tuple[float, float]] = {}
        for name, (i, s) in sys_.local.items():
            if i == gi:
                pos[name] = (s[0] * scale, s[1] * scale)
            else:
                x, y, th = q0[3 * i : 3 * i + 3]
                c, sn = math.cos(th), math.sin(th)
                pos[name] = ((x + c * s[0] - sn * s[1]) * scale, (y + sn * s[0] + c * s[1]) * scale)
        frame = {i: (q0[3 * i] * scale, q0[3 * i + 1] * scale, q0[3 * i + 2]) for i in range(self.n)}
        frame[gi] = (0.0, 0.0, 0.0)
        return pos, frame

    # -- helpers --------------------------------------------------------------------------
    def local(self, i: int, name: str) -> tuple[float, float]:
        """A location's coordinates in link i's drawn frame."""
        x, y, th = self.frame[i]
        c, s = math.cos(th), math.sin(th)
        dx, dy = self.pos[name][0] - x, self.pos[name][1] - y
        return (c * dx + s * dy, -s * dx + c * dy)

    def pv(self, name: str, what: str) -> str:
        """The generated variable of a point's quantity (``p3_vx``)."""
        return f"p{self._names.index(name)}_{what}"

    def known_points(self, i: int, exclude: str | None = None) -> list[str]:
        return [p for p in self.on[i] if p in self.avail and p != exclude]

    def guide_direction(self, g: int, ux: float, uy: float) -> tuple[float, float]:
        """A path's direction (in its guide's frame) turned into the drawn configuration."""
        gth = self.frame[g][2]
        return (math.cos(gth) * ux - math.sin(gth) * uy, math.sin(gth) * ux + math.cos(gth) * uy)

    def path_line(self, ps: Any) -> tuple[float, float, float, float]:
        """Through point (SI, guide frame) and unit direction of a path's line row."""
        k_path = list(self.lay.paths).index(ps)
        u = self.sys.path_dirs[ps.joint][1]
        t_l = self.sys.ln_t[k_path] * self.scale
        return float(t_l[0]), float(t_l[1]), float(u[0]), float(u[1])

    # -- emitting known things ------------------------------------------------------------
    def ground_constants(self) -> None:
        gi = self.gi
        for w in ("x", "y", "t", "c", "s", "vx", "vy", "w", "ax", "ay", "al"):
            self.code.append(f"    l{gi}_{w} = {1.0 if w == 'c' else 0.0}")

    def emit_point(self, name: str) -> None:
        """A point of a known link: r = R + A s (velocity and acceleration from ω, α)."""
        if name in self.emitted:
            return
        pv = self.pv
        i = next(c for c in self.carriers[name] if c in self.known_links)
        if i == self.gi:
            x, y = self.pos[name]
            self.code += [
                f"    {pv(name, 'x')} = {_fmt(x)}; {pv(name, 'y')} = {_fmt(y)}",
                f"    #V {pv(name, 'vx')} = 0.0; {pv(name, 'vy')} = 0.0",
                f"    #A {pv(name, 'ax')} = 0.0; {pv(name, 'ay')} = 0.0",
            ]
        else:
            sx, sy = self.local(i, name)
            r = f"r_{pv(name, '')}"
            self.code += [
                f"    {r}x = l{i}_c * {_fmt(sx)} - l{i}_s * {_fmt(sy)}; "
                f"{r}y = l{i}_s * {_fmt(sx)} + l{i}_c * {_fmt(sy)}",
                f"    {pv(name, 'x')} = l{i}_x + {r}x; {pv(name, 'y')} = l{i}_y + {r}y",
                f"    #V {pv(name, 'vx')} = l{i}_vx - l{i}_w * {r}y; "
                f"{pv(name, 'vy')} = l{i}_vy + l{i}_w * {r}x",
                f"    #A {pv(name, 'ax')} = l{i}_ax - l{i}_al * {r}y - l{i}_w * l{i}_w * {r}x; "
                f"{pv(name, 'ay')} = l{i}_ay + l{i}_al * {r}x - l{i}_w * l{i}_w * {r}y",
            ]
        self.emitted.add(name)

    def place_from_point(self, i: int, name: str) -> None:
        """Origin of link i (angle, ω, α already set) from one of its known points."""
        pv = self.pv
        sx, sy = self.local(i, name)
        self.emit_point(name)
        self.code += [
            f"    l{i}_c = cos(l{i}_t); l{i}_s = sin(l{i}_t)",
            f"    rx = l{i}_c * {_fmt(sx)} - l{i}_s * {_fmt(sy)}; ry = l{i}_s * {_fmt(sx)} + l{i}_c * {_fmt(sy)}",
            f"    l{i}_x = {pv(name, 'x')} - rx; l{i}_y = {pv(name, 'y')} - ry",
            f"    #V l{i}_vx = {pv(name, 'vx')} + l{i}_w * ry; l{i}_vy = {pv(name, 'vy')} - l{i}_w * rx",
            f"    #A l{i}_ax = {pv(name, 'ax')} + l{i}_al * ry + l{i}_w * l{i}_w * rx; "
            f"l{i}_ay = {pv(name, 'ay')} - l{i}_al * rx + l{i}_w * l{i}_w * ry",
        ]
        self.known_links.add(i)
        for p in self.on[i]:
            self.avail.add(p)

    def crank(self, link: str, pivot: str | None, drawn: float) -> None:
        """The driven link: its angle is the drive's plus the drawn offset, about a ground pivot."""
        if pivot not in self.avail:
            raise _NoDecomposition
        ci = self.idx[link]
        c0 = self.sys.q0[3 * ci + 2] - drawn
        self.code += [
            f"    l{ci}_t = phi + {_fmt(c0)}",
            "    #V " + f"l{ci}_w = omega",
            "    #A " + f"l{ci}_al = alpha",
        ]
        self.place_from_point(ci, pivot)  # type: ignore[arg-type]
        self.steps.append(f"crank {link} about {pivot}")

    # -- the placement rules --------------------------------------------------------------
    def angle_rule(self, i: int) -> tuple[int, float] | None:
        """A known link whose angle gives link i's (a prismatic pair keeps their angle fixed)."""
        gi, idx, frame = self.gi, self.idx, self.frame
        for ps in self.prismatic:
            a, b = idx.get(ps.slider, gi), idx.get(ps.guide, gi)
            if a == i and b in self.known_links:
                return b, frame[a][2] - frame[b][2]
            if b == i and a in self.known_links:
                return a, frame[b][2] - frame[a][2]
        return None

    def pose_rigid(self) -> bool:
        """Links placed rigidly: from a point and a fixed angle to a known link, or from two points."""
        progress = False
        for i in range(self.n):
            if i in self.known_links:
                continue
            pts = self.known_points(i)
            rule = self.angle_rule(i)
            if rule is not None and pts:
                r, c = rule
                self.code += [
                    f"    l{i}_t = l{r}_t + {_fmt(c)}",
                    f"    #V l{i}_w = l{r}_w",
                    f"    #A l{i}_al = l{r}_al",
                ]
                self.place_from_point(i, pts[0])
                self.steps.append(
                    f"pose {self.sys.links[i]} from {pts[0]} and its angle to {_name(self.sys, r)}"
                )
                progress = True
                continue
            two = next(
                (
                    (a, b)
                    for a in pts
                    for b in pts
                    if a < b and math.dist(self.pos[a], self.pos[b]) > self.tiny
                ),
                None,
            )
            if two is not None:
                self.pose2(i, *two)
                progress = True
        return progress

    def pose2(self, i: int, a: str, b: str) -> None:
        """Link i from two of its known points: its angle from the line a→b."""
        pv = self.pv
        self.emit_point(a)
        self.emit_point(b)
        sa, sb = self.local(i, a), self.local(i, b)
        beta = math.atan2(sb[1] - sa[1], sb[0] - sa[0])
        self.code += [
            f"    dx = {pv(b, 'x')} - {pv(a, 'x')}; dy = {pv(b, 'y')} - {pv(a, 'y')}",
            f"    l{i}_t = atan2(dy, dx) - {_fmt(beta)}",
            "    #V dd = dx * dx + dy * dy; dd = dd + (dd == 0.0)",
            f"    #V l{i}_w = (dx * ({pv(b, 'vy')} - {pv(a, 'vy')}) - dy * ({pv(b, 'vx')} - {pv(a, 'vx')})) / dd",
            f"    #A l{i}_al = (dx * ({pv(b, 'ay')} - {pv(a, 'ay')}) - dy * ({pv(b, 'ax')} - {pv(a, 'ax')})) / dd",
        ]
        self.place_from_point(i, a)
        self.steps.append(f"pose {self.sys.links[i]} from {a}, {b}")

    def rrr(self) -> bool:
        """An unknown pin J of two unknown links, each with one known point: circle–circle."""
        pos, links = self.pos, self.sys.links
        for j in pos:
            if j in self.avail or len(self.carriers[j]) < 2:
                continue
            cands = [(i, self.known_points(i, j)) for i in self.carriers[j] if i not in self.known_links]
            cands = [(i, pts) for i, pts in cands if pts]
            if len(cands) < 2:
                continue
            (i1, pts1), (i2, pts2) = cands[0], cands[1]
            p, q = pts1[0], pts2[0]
            if math.dist(pos[p], pos[q]) <= self.tiny:
                continue
            self.emit_point(p)
            self.emit_point(q)
            lp, lq = math.dist(pos[p], pos[j]), math.dist(pos[q], pos[j])
            dx, dy = pos[q][0] - pos[p][0], pos[q][1] - pos[p][1]
            sign = 1.0 if dx * (pos[j][1] - pos[p][1]) - dy * (pos[j][0] - pos[p][0]) >= 0 else -1.0
            self.code += _rrr(len(self.dyads), j, p, q, lp, lq, sign, self.pv)
            self.dyads.append(("RRR", j, f"{links[i1]} and {links[i2]} in line at {j}"))
            self.steps.append(f"rrr {j} from {p}, {q} ({'left' if sign > 0 else 'right'} of {p}→{q})")
            self.avail.add(j)
            self.emitted.add(j)
            return True
        return False

    def rrp(self) -> bool:
        """A path point B on a known guide, at a fixed length from a known point A: circle–line."""
        pos = self.pos
        for ps in self.lay.paths:
            g = self.idx.get(ps.guide, self.gi)
            b = ps.point
            if g not in self.known_links or b in self.avail or b not in pos:
                continue
            rods = [(i, self.known_points(i, b)) for i in self.carriers[b] if i not in self.known_links]
            rods = [(i, pts) for i, pts in rods if pts]
            if not rods:
                continue
            a = rods[0][1][0]
            self.emit_point(a)
            tx, ty, ux, uy = self.path_line(ps)
            length = math.dist(pos[a], pos[b])
            # drawn branch: B ahead of A along the path (+1) or behind
            ugx, ugy = self.guide_direction(g, ux, uy)
            sign = 1.0 if (pos[b][0] - pos[a][0]) * ugx + (pos[b][1] - pos[a][1]) * ugy >= 0 else -1.0
            self.code += _rrp(len(self.dyads), b, a, g, tx, ty, ux, uy, length, sign, self.pv)
            self.dyads.append(
                ("RRP", b, f"{self.sys.links[rods[0][0]]} at right angles to the path of {ps.joint}")
            )
            self.steps.append(
                f"rrp {b} on the path of {ps.joint} from {a} ({'ahead' if sign > 0 else 'behind'})"
            )
            self.avail.add(b)
            self.emitted.add(b)
            return True
        return False

    def rpr(self) -> bool:
        """An unknown guide pivoted at a known point O whose path passes a known point P."""
        pos = self.pos
        for ps in self.lay.paths:
            g = self.idx.get(ps.guide, self.gi)
            p = ps.point
            if g in self.known_links or p not in self.avail:
                continue
            pts = [o for o in self.known_points(g) if math.dist(pos[o], pos[p]) > self.tiny]
            if not pts:
                continue
            o = pts[0]
            self.emit_point(o)
            self.emit_point(p)
            tx, ty, ux, uy = self.path_line(ps)
            so = self.local(g, o)
            e = -uy * (tx - so[0]) + ux * (ty - so[1])
            ugx, ugy = self.guide_direction(g, ux, uy)
            sign = 1.0 if (pos[p][0] - pos[o][0]) * ugx + (pos[p][1] - pos[o][1]) * ugy >= 0 else -1.0
            self.code += _rpr(len(self.dyads), g, o, p, float(e), ux, uy, sign, self.pv)
            what = f"{p} at the foot of the perpendicular from {o} to the path of {ps.joint}"
            self.dyads.append(("RPR", self.sys.links[g], what))
            self.steps.append(f"rpr {self.sys.links[g]} about {o} through {p}")
            self.place_from_point(g, o)
            return True
        return False

    # -- the functions --------------------------------------------------------------------
    def compile(self, label: str) -> tuple[tuple[Any, Any, Any], str]:
        """The generated function of each level (0, 1, 2) and the source of the last."""
        n, pv, names, nd = self.n, self.pv, self._names, len(self.dyads)
        outs = [f"{w}{k}" for w in ("d", "sn", "ms") for k in range(nd)]
        outs += [f"l{i}_{w}" for w in ("x", "y", "t") for i in range(n)]
        outs += [pv(p, w) for w in ("x", "y") for p in names]
        vel = [f"l{i}_{w}" for w in ("vx", "vy", "w") for i in range(n)] + [
            pv(p, w) for w in ("vx", "vy") for p in names
        ]
        acc = [f"l{i}_{w}" for w in ("ax", "ay", "al") for i in range(n)] + [
            pv(p, w) for w in ("ax", "ay") for p in names
        ]
        fns = []
        source = ""
        for level in range(3):
            lines = []
            for line in self.code:
                stripped = line.lstrip()
                if stripped.startswith("#V "):
                    if level >= 1:
                        lines.append("    " + stripped[3:])
                elif stripped.startswith("#A "):
                    if level >= 2:
                        lines.append("    " + stripped[3:])
                else:
                    lines.append(line)
            ret = outs + (vel if level >= 1 else []) + (acc if level >= 2 else [])
            # b0, b1 …: each dyad's branch, flipped (−1) past a change point (see :func:`branches`)
            branch = "".join(f", b{k}=1.0" for k in range(nd))
            source = (
                f"def run(phi, omega, alpha, sqrt, cos, sin, atan2, clip{branch}):\n"
                + "\n".join(lines)
                + "\n    return ("
                + ", ".join(ret)
                + ",)\n"
            )
            env: dict[str, Any] = {}
            exec(compile(source, f"<dyad program of {label}>", "exec"), env)  # our own generated code
            fns.append(env["run"])
        return (fns[0], fns[1], fns[2]), source


def _name(sys_: System, i: int) -> str:
    return sys_.links[i] if i < sys_.n else sys_.ground


def _rrr(k: int, j: str, p: str, q: str, lp: float, lq: float, sign: float, pv: Any) -> list[str]:
    """Circle–circle apex J: 16·area² = ((lP+lQ)² − d²)(d² − (lP−lQ)²), J = P + a·d̂ + sign·h·d̂⊥.

    The product form keeps the discriminant accurate next to a toggle, where
    one factor goes to zero (no cancellation of two large numbers).
    """
    P = {w: pv(p, w) for w in ("x", "y", "vx", "vy", "ax", "ay")}
    Q = {w: pv(q, w) for w in ("x", "y", "vx", "vy", "ax", "ay")}
    J = {w: pv(j, w) for w in ("x", "y", "vx", "vy", "ax", "ay")}
    s2, m2 = (lp + lq) ** 2, (lp - lq) ** 2
    return [
        f"    dx = {Q['x']} - {P['x']}; dy = {Q['y']} - {P['y']}; dd = dx * dx + dy * dy",
        f"    f1 = {_fmt(s2)} - dd; f2 = dd - {_fmt(m2)}",
        # base points that coincide leave the apex undetermined: no closure there (and no 1/0)
        f"    d{k} = f1 * f2 * {_fmt(1.0 / (s2 * s2))} - (dd == 0.0); dd = dd + (dd == 0.0)",
        f"    ms{k} = ({_fmt(abs(lp - lq) - (lp + lq))} + abs(2.0 * sqrt(dd) - {_fmt(abs(lp - lq) + lp + lq)})) * 0.5",
        f"    a = ({_fmt(lp * lp - lq * lq)} + dd) / (2.0 * dd); h = {_fmt(sign)} * b{k} * sqrt(clip(f1 * f2)) / (2.0 * dd)",
        f"    {J['x']} = {P['x']} + a * dx - h * dy; {J['y']} = {P['y']} + a * dy + h * dx",
        f"    epx = {J['x']} - {P['x']}; epy = {J['y']} - {P['y']}; eqx = {J['x']} - {Q['x']}; eqy = {J['y']} - {Q['y']}",
        "    det = epx * eqy - epy * eqx",
        f"    sn{k} = det * {_fmt(1.0 / (lp * lq))}; det = det + (det == 0.0)",
        f"    #V r1 = epx * {P['vx']} + epy * {P['vy']}; r2 = eqx * {Q['vx']} + eqy * {Q['vy']}",
        f"    #V {J['vx']} = (r1 * eqy - epy * r2) / det; {J['vy']} = (epx * r2 - r1 * eqx) / det",
        f"    #A ux = {J['vx']} - {P['vx']}; uy = {J['vy']} - {P['vy']}; wx = {J['vx']} - {Q['vx']}; wy = {J['vy']} - {Q['vy']}",
        f"    #A r1 = epx * {P['ax']} + epy * {P['ay']} - ux * ux - uy * uy",
        f"    #A r2 = eqx * {Q['ax']} + eqy * {Q['ay']} - wx * wx - wy * wy",
        f"    #A {J['ax']} = (r1 * eqy - epy * r2) / det; {J['ay']} = (epx * r2 - r1 * eqx) / det",
    ]


def _rrp(
    k: int,
    b: str,
    a: str,
    g: int,
    tx: float,
    ty: float,
    ux: float,
    uy: float,
    length: float,
    sign: float,
    pv: Any,
) -> list[str]:
    """Circle–line: B = T + s·u with |B − A| = l, s = −(T−A)·u + sign·√(l² − ((T−A)·n)²).

    Rows for the derivatives: ``n·v_B = n·v_T + ω_g s`` (the path turns with
    its guide) and ``(B − A)·v_B = (B − A)·v_A``; differentiated again, the
    path row gains ``α_g s + 2ω_g u·(v_B − v_T)``, the Coriolis term.
    """
    A = {w: pv(a, w) for w in ("x", "y", "vx", "vy", "ax", "ay")}
    B = {w: pv(b, w) for w in ("x", "y", "vx", "vy", "ax", "ay")}
    gl = f"l{g}"
    return [
        f"    gux = {gl}_c * {_fmt(ux)} - {gl}_s * {_fmt(uy)}; guy = {gl}_s * {_fmt(ux)} + {gl}_c * {_fmt(uy)}",
        f"    rtx = {gl}_c * {_fmt(tx)} - {gl}_s * {_fmt(ty)}; rty = {gl}_s * {_fmt(tx)} + {gl}_c * {_fmt(ty)}",
        f"    tx = {gl}_x + rtx; ty = {gl}_y + rty",
        f"    px = tx - {A['x']}; py = ty - {A['y']}",
        "    pu = px * gux + py * guy; pn = -px * guy + py * gux",
        f"    f = {_fmt(length * length)} - pn * pn",
        f"    d{k} = f * {_fmt(1.0 / (length * length))}",
        f"    ms{k} = abs(pn) - {_fmt(length)}",
        f"    sb = -pu + {_fmt(sign)} * b{k} * sqrt(clip(f))",
        f"    {B['x']} = tx + sb * gux; {B['y']} = ty + sb * guy",
        f"    ex = {B['x']} - {A['x']}; ey = {B['y']} - {A['y']}",
        "    det = -guy * ey - gux * ex",
        f"    sn{k} = det * {_fmt(1.0 / length)}; det = det + (det == 0.0)",
        f"    #V tvx = {gl}_vx - {gl}_w * rty; tvy = {gl}_vy + {gl}_w * rtx",
        f"    #V r1 = -guy * tvx + gux * tvy + {gl}_w * sb; r2 = ex * {A['vx']} + ey * {A['vy']}",
        f"    #V {B['vx']} = (r1 * ey - gux * r2) / det; {B['vy']} = (-guy * r2 - r1 * ex) / det",
        f"    #A tax = {gl}_ax - {gl}_al * rty - {gl}_w * {gl}_w * rtx; tay = {gl}_ay + {gl}_al * rtx - {gl}_w * {gl}_w * rty",
        f"    #A ux = {B['vx']} - {A['vx']}; uy = {B['vy']} - {A['vy']}",
        f"    #A r1 = -guy * tax + gux * tay + {gl}_al * sb + 2.0 * {gl}_w * (gux * ({B['vx']} - tvx) + guy * ({B['vy']} - tvy))",
        f"    #A r2 = ex * {A['ax']} + ey * {A['ay']} - ux * ux - uy * uy",
        f"    #A {B['ax']} = (r1 * ey - gux * r2) / det; {B['ay']} = (-guy * r2 - r1 * ex) / det",
    ]


def _rpr(k: int, g: int, o: str, p: str, e: float, ulx: float, uly: float, sign: float, pv: Any) -> list[str]:
    """Guide through P about O: with d = P − O, u·d = sign·√(|d|² − e²) = c and n·d = e, so
    u = (c·d − e·d⊥)/|d|²; ω = n·(v_P − v_O)/c, α = (n·(a_P − a_O) − 2ω u·(v_P − v_O) − ω² e)/c.
    """
    O_ = {w: pv(o, w) for w in ("x", "y", "vx", "vy", "ax", "ay")}
    P = {w: pv(p, w) for w in ("x", "y", "vx", "vy", "ax", "ay")}
    O = O_  # noqa: E741 - the pivot O, as in the figure
    return [
        f"    dx = {P['x']} - {O['x']}; dy = {P['y']} - {O['y']}; dd = dx * dx + dy * dy",
        f"    f = dd - {_fmt(e * e)}",
        # P on the pivot O: the guide's direction is undetermined, no closure there (and no 1/0)
        f"    d{k} = f / (dd + (dd == 0.0)) - (dd == 0.0); dd = dd + (dd == 0.0)",
        f"    ms{k} = {_fmt(abs(e))} - sqrt(dd)",
        f"    cc = {_fmt(sign)} * b{k} * sqrt(clip(f))",
        f"    gux = (cc * dx + {_fmt(e)} * dy) / dd; guy = (cc * dy - {_fmt(e)} * dx) / dd",
        f"    l{g}_t = atan2(guy * {_fmt(ulx)} - gux * {_fmt(uly)}, gux * {_fmt(ulx)} + guy * {_fmt(uly)})",
        f"    sn{k} = cc / sqrt(dd); cc = cc + (cc == 0.0)",
        f"    #V l{g}_w = (-guy * ({P['vx']} - {O['vx']}) + gux * ({P['vy']} - {O['vy']})) / cc",
        f"    #A l{g}_al = (-guy * ({P['ax']} - {O['ax']}) + gux * ({P['ay']} - {O['ay']}) - 2.0 * l{g}_w * "
        f"(gux * ({P['vx']} - {O['vx']}) + guy * ({P['vy']} - {O['vy']})) - l{g}_w * l{g}_w * {_fmt(e)}) / cc",
    ]


def _verified(prog: DyadProgram, sys_: System) -> bool:
    """The program satisfies every constraint row at the drawn angle and at eight others."""
    import numpy as np

    n, scale = sys_.n, sys_.scale
    phis = [prog.drawn_angle] + [prog.drawn_angle + k * math.pi / 4 for k in range(1, 8)]
    ok_any = False
    for k, phi in enumerate(phis):
        try:
            out = prog.raw(phi, level=0, xp=MATH)
        except ZeroDivisionError:
            # a dyad's two base points coincide at this angle (the Peaucellier crank pin on its
            # fixed pivot): the apex is undetermined there, which says nothing about the others
            if k == 0:
                return False
            continue
        parts = prog.split(out, 0)
        if min(parts["disc"], default=1.0) < -SLACK:
            if k == 0:
                return False
            continue
        q = np.empty(3 * n)
        q[0::3] = np.asarray(parts["lx"]) / scale
        q[1::3] = np.asarray(parts["ly"]) / scale
        q[2::3] = parts["lt"]
        c_ang = sys_.ang_c.copy()
        for r in sys_.drive_rows:
            off = r - 2 * sys_.pc_i.size - sys_.ln_s.size
            if off >= 0:
                c_ang[off] += phi - prog.drawn_angle
        res = sys_.phi(q, sys_.ln_c, c_ang)
        if res.size and float(np.max(np.abs(res))) > 1e-9:
            return False
        ok_any = True
    return ok_any


# -- where the loop closes -----------------------------------------------------------------
def _worst_disc(prog: DyadProgram, phi: float) -> float:
    out = prog.raw(phi, level=0)
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
    out = prog.raw(prog.drawn_angle + d, level=0, xp=numpy_namespace())
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


def reachable(prog: DyadProgram, target: float) -> bool:
    """True when the crank can turn from the drawn angle to ``target`` (either way) without a gap."""
    return route(prog, target) is not None


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
    return float(prog.raw(phi, level=0)[k])


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
            out = prog.raw(prog.drawn_angle + d, level=0, xp=numpy_namespace())
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
    out = prog.raw(phi, level=0)
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
    (:func:`~mech.kinematics.solve.move_to`) tries them; a way with a gap in
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
