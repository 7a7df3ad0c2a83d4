"""The dyad decomposition of a compiled mechanism, generated as straight-line code and verified.

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

"""

from __future__ import annotations

import math
from functools import partial
from typing import Any

from mech.kinematics.constraints import System
from mech.kinematics.dyads.program import MATH, SLACK, DyadProgram
from mech.kinematics.dyads.templates import constants, fmt, rpr, rrp, rrr
from mech.kinematics.layout import Layout
from mech.pairs import kind_of

__all__ = ["closes", "program"]


def program(comp: Any, level: int = 0, *, whole_turn: bool = True) -> DyadProgram | None:
    """The closed-form program of a compiled mechanism, or None when it does not decompose.

    Kept in the memo of the :class:`~mech.kinematics.compiled.Compiled` (itself
    kept in the mechanism's).  The program is accepted only if it reproduces the drawn
    configuration and satisfies *every* constraint row of the system (so a
    row the decomposition did not use, a redundant one, still holds) at a
    few angles round the cycle; otherwise None, and Newton is used.  ``level``
    is the level the caller evaluates next: when the program is first made, that
    level's function is the one compiled and checked (one compilation, not two).

    A program is made checked at the drawn angle only; ``whole_turn`` (every caller but a
    solve at the file's own angle) asks for the seven other angles too, checked once when
    first asked.  A homework file solved at its drawn instant pays for one angle's check,
    not eight (issue 22's throughput: most of a file's first solve was the program's making).
    """
    prog: DyadProgram | None = comp.memo.get("program", lambda: _checked_program(comp, level))
    if prog is None or not whole_turn:
        return prog
    return prog if prog.memo("whole turn", lambda: _verified(prog, comp.system, 8)) else None


def _checked_program(comp: Any, level: int) -> DyadProgram | None:
    """The program built and verified (or None): :func:`program`'s work, done once per compiled mechanism."""
    try:
        prog = _build(comp.layout, comp.system, comp.drawn.drive_angles)
    except _NoDecomposition:
        return None
    prog.function(level)
    return prog if _verified(prog, comp.system, 1) else None


class _NoDecomposition(Exception):
    pass


def _build(lay: Layout, sys_: System, drive_angles: tuple[float | None, ...]) -> DyadProgram:
    """Find the dyad decomposition and generate its code.

    The steps, each a method of :class:`_Builder`: the drawn frames of every
    link, the crank, then rounds of the four placement rules (a link posed
    rigidly from known points, an RRR apex, an RRP slider, an RPR guide) until
    every link is known, and the code of each level's function written (compiled
    when first evaluated: :meth:`DyadProgram.function`).
    """
    if len(lay.drives) != 1 or sys_.velocity_only or any(kind_of(j).dyad is None for j in lay.mech.joints):
        raise _NoDecomposition
    spec = lay.drives[0]
    if spec.link is None or spec.reference != lay.mech.ground or drive_angles[0] is None:
        raise _NoDecomposition
    b = _Builder(lay, sys_)
    with constants() as values:
        b.ground_constants()
        b.crank(spec.link, spec.pivot, drive_angles[0])
        rules = (b.pose_rigid, b.rrr, b.rrp, b.rpr)
        while len(b.known_links) < b.n + 1 and any(rule() for rule in rules):
            pass
        if len(b.known_links) < b.n + 1:
            raise _NoDecomposition
        for name in b.pos:
            b.emit_point(name)
    return DyadProgram(
        steps=tuple(b.steps),
        links=sys_.links,
        points=tuple(b.pos),
        dyads=tuple(b.dyads),
        centre=(float(sys_.centre[0]), float(sys_.centre[1])),
        drawn_angle=float(drive_angles[0]),
        writer=partial(b.source, len(values)),
        constants=tuple(values),
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
        self._index = {name: k for k, name in enumerate(self._names)}

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
        return f"p{self._index[name]}_{what}"

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
                f"    {pv(name, 'x')} = {fmt(x)}; {pv(name, 'y')} = {fmt(y)}",
                f"    #V {pv(name, 'vx')} = 0.0; {pv(name, 'vy')} = 0.0",
                f"    #A {pv(name, 'ax')} = 0.0; {pv(name, 'ay')} = 0.0",
            ]
        else:
            sx, sy = self.local(i, name)
            r = f"r_{pv(name, '')}"
            self.code += [
                f"    {r}x = l{i}_c * {fmt(sx)} - l{i}_s * {fmt(sy)}; "
                f"{r}y = l{i}_s * {fmt(sx)} + l{i}_c * {fmt(sy)}",
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
            f"    rx = l{i}_c * {fmt(sx)} - l{i}_s * {fmt(sy)}; ry = l{i}_s * {fmt(sx)} + l{i}_c * {fmt(sy)}",
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
            f"    l{ci}_t = phi + {fmt(c0)}",
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
                    f"    l{i}_t = l{r}_t + {fmt(c)}",
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
            f"    l{i}_t = atan2(dy, dx) - {fmt(beta)}",
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
            self.code += rrr(len(self.dyads), j, p, q, lp, lq, sign, self.pv)
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
            self.code += rrp(len(self.dyads), b, a, g, tx, ty, ux, uy, length, sign, self.pv)
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
            self.code += rpr(len(self.dyads), g, o, p, float(e), ux, uy, sign, self.pv)
            what = f"{p} at the foot of the perpendicular from {o} to the path of {ps.joint}"
            self.dyads.append(("RPR", self.sys.links[g], what))
            self.steps.append(f"rpr {self.sys.links[g]} about {o} through {p}")
            self.place_from_point(g, o)
            return True
        return False

    # -- the functions --------------------------------------------------------------------
    def source(self, count: int, level: int) -> str:
        """The code of one level's function (0, 1, 2), inside a maker taking the ``count`` constants.

        The code names its constants (``_k0`` …), so it is the structure's: a class's four-bars
        write the same lines, and the source is kept by them (:data:`_SOURCES`), written once.
        """
        key = (tuple(self.code), self.n, len(self.pos), len(self.dyads), count, level)
        src = _SOURCES.get(key)
        if src is None:
            if len(_SOURCES) >= _SOURCES_KEPT:
                _SOURCES.pop(next(iter(_SOURCES)))
            src = _SOURCES[key] = self._source(count, level)
        return src

    def _source(self, count: int, level: int) -> str:
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
        # b0, b1 …: each dyad's branch, flipped (−1) past a change point (see :func:`branches`)
        branch = "".join(f", b{k}=1.0" for k in range(nd))
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
        # run() inside make(_k0, _k1 …): the source names the constants, make binds this mechanism's
        return (
            f"def make({''.join(f'_k{i}, ' for i in range(count))}):\n"
            f"  def run(phi, omega, alpha, sqrt, cos, sin, atan2, clip{branch}):\n"
            + "\n".join("  " + line for line in lines)
            + "\n      return ("
            + ", ".join(ret)
            + ",)\n  return run\n"
        )


#: Sources already written, by the code lines and sizes they are written from (oldest dropped first).
_SOURCES: dict[tuple[Any, ...], str] = {}
_SOURCES_KEPT = 256


def _name(sys_: System, i: int) -> str:
    return sys_.links[i] if i < sys_.n else sys_.ground


def _verified(prog: DyadProgram, sys_: System, angles: int) -> bool:
    """The program satisfies every constraint row at the drawn angle (and ``angles`` − 1 others round the cycle).

    Evaluated by the level already compiled, the rows of all eight configurations at once.
    """
    import numpy as np

    scale = sys_.scale
    level = prog.positions_level()
    qs: list[np.ndarray] = []
    turned: list[float] = []
    for k in range(angles):
        phi = prog.drawn_angle + k * math.pi / 4
        try:
            out = prog.raw(phi, level=level, xp=MATH)
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
        qs.append(prog.configuration(parts, scale))
        turned.append(phi - prog.drawn_angle)
    return _rows_hold(sys_, qs, turned)


def closes(prog: DyadProgram, sys_: System, phi: float, out: tuple) -> bool:
    """The raw output ``out`` of ``prog`` at ``phi`` satisfies every constraint row of the system.

    What a solve off the drawn branches checks (:attr:`~mech.options.SolveOptions.flipped`): a
    dyad closed the other way can leave a row the decomposition did not use broken (a double
    parallelogram's redundant link), which the drawn branch's check (:func:`_verified`) never saw.
    """
    parts = prog.split(out, 0)
    if min(parts["disc"], default=1.0) < -SLACK:
        return False
    return _rows_hold(sys_, [prog.configuration(parts, sys_.scale)], [phi - prog.drawn_angle])


def _rows_hold(sys_: System, qs: list[Any], turned: list[float]) -> bool:
    """Every constraint row holds (to 1e-9 of the size) at each configuration, the drive turned by ``turned``."""
    import numpy as np

    c_ang = np.tile(sys_.ang_c, (len(qs), 1))
    for r in sys_.drive_rows:
        off = r - 2 * sys_.pc_i.size - sys_.ln_s.size
        if off >= 0:
            c_ang[:, off] += turned
    res = sys_.phi(np.array(qs), sys_.ln_c, c_ang)
    return not (res.size and float(np.abs(res).max()) > 1e-9)
