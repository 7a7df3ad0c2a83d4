"""A compiled closed-form program: one configuration on floats, or an array of drive angles at once.

:class:`DyadProgram` holds the generated functions (one per level: positions,
velocities, accelerations) of one decomposition (:mod:`.build`) and slices their
flat output (:meth:`DyadProgram.split`); :meth:`DyadProgram.state` is the lean
single-solve path, :class:`FastState` its result.  The same functions run on
floats (:data:`MATH`) and on numpy arrays (:func:`numpy_namespace`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import field
from typing import Any

from mech._records import dataclass

__all__ = ["ACCURATE_COND", "MATH", "SLACK", "DyadProgram", "FastState", "numpy_namespace"]

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
    sources
        The generated code of each level's function (positions; and velocities; and
        accelerations), compiled when that level is first evaluated (:meth:`function`):
        compiling costs about as much as a solve by the general route, and one command
        needs one level.
    """

    steps: tuple[str, ...]
    links: tuple[str, ...]
    points: tuple[str, ...]
    dyads: tuple[tuple[str, str, str], ...]
    centre: tuple[float, float]
    drawn_angle: float
    writer: Callable[[int], str] = field(repr=False)  # the source of a level, written when first asked
    _sizes: tuple[int, int, int] = field(repr=False)  # dyads, links, points
    #: The numbers the sources name ``_k0``, ``_k1`` …: this mechanism's lengths, offsets, branch signs.
    constants: tuple[float, ...] = field(default=(), repr=False)
    #: The compiled functions (keys 0, 1, 2) and what is found once round the cycle (gaps, change points).
    _memo: dict[Any, Any] = field(default_factory=dict, repr=False)

    @property
    def sources(self) -> tuple[str, str, str]:
        """The generated code of each level's function (positions; and velocities; and accelerations)."""
        return (self.source_of(0), self.source_of(1), self.source_of(2))

    @property
    def source(self) -> str:
        """The generated code of the acceleration-level function (for reading)."""
        return self.source_of(2)

    def memo(self, key: str, make: Callable[[], Any]) -> Any:
        """A value derived from the program, made once (the whole turn's check)."""
        if key not in self._memo:
            self._memo[key] = make()
        return self._memo[key]

    def source_of(self, level: int) -> str:
        """The code of one level's function, written when first asked (one command needs one level)."""
        src = self._memo.get(("source", level))
        if src is None:
            src = self._memo[("source", level)] = self.writer(level)
        return src  # type: ignore[no-any-return]

    # -- evaluation -------------------------------------------------------------------
    def function(self, level: int) -> Any:
        """The generated function of ``level`` (0, 1 or 2), compiled when first asked."""
        fn = self._memo.get(level)
        if fn is None:
            fn = self._memo[level] = _maker(self.source_of(level))(*self.constants)
        return fn

    def positions_level(self) -> int:
        """The lowest level already compiled (0 if none): its outputs start with everything level 0 gives.

        What needs only discriminants and positions (the gaps and change points round
        the cycle, the program's own check) uses it, so that it compiles no other level.
        """
        return next((k for k in (0, 1, 2) if k in self._memo), 0)

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

        ``xp`` is :data:`MATH` for floats or :func:`numpy_namespace` for arrays of angles.
        ``branch`` holds each dyad's branch multiplier (+1 the drawn one, −1 the
        other; floats, or arrays shaped as ``phi``): :func:`branches` gives them
        for angles reached past change points; empty, the drawn branch throughout.
        """
        xp = xp or MATH
        return self.function(level)(phi, omega, alpha, xp.sqrt, xp.cos, xp.sin, xp.atan2, xp.clip, *branch)

    def configuration(self, parts: dict[str, tuple], scale: float) -> Any:
        """The scaled coordinates q (x, y, θ per link, the solver's) of one configuration of
        :meth:`split`'s ``parts``, its lengths divided by ``scale``."""
        import numpy as np

        q = np.empty(3 * len(self.links))
        q[0::3] = np.asarray(parts["lx"]) / scale
        q[1::3] = np.asarray(parts["ly"]) / scale
        q[2::3] = parts["lt"]
        return q

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
            out = self.function(level)(phi, omega, alpha, _sqrt, _cos, _sin, _atan2, _clip)
        except ZeroDivisionError:  # a dyad that cannot close, or exactly in line: say which
            out = self.function(0)(phi, omega, alpha, _sqrt, _cos, _sin, _atan2, _clip)
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


#: Compiled makers by their source: mechanisms of one structure (a class's four-bars, a folder of
#: slider cranks) generate the same source with their own constants, and compile it once per process.
_MAKERS: dict[str, Any] = {}
_MAKERS_KEPT = 256


def _maker(source: str) -> Any:
    """``make(_k0, …)`` of a generated source, compiled once per process (compiling costs more than a solve)."""
    make = _MAKERS.get(source)
    if make is None:
        env: dict[str, Any] = {}
        exec(compile(source, "<dyad program>", "exec"), env)  # our own generated code
        if len(_MAKERS) >= _MAKERS_KEPT:
            _MAKERS.pop(next(iter(_MAKERS)))
        make = _MAKERS[source] = env["make"]
    return make
