"""The computed side of a check: one problem's analysis, each piece made on first use and kept.

Compute functions of answer keys (:mod:`mech.grading`) read what they need
from an :class:`Analysis`: the topology, the numeric mobility, the solution at
the highest level any claim needs, the I-centres, and anything costlier kept
with :meth:`Analysis.cached`.  Only what the claims ask is computed: counting
DOF never imports numpy.

A solve that fails is kept as its error, so that every claim needing it gets
the same reason without solving again; a bug in an analysis is kept as an
:class:`InternalError` (one file's rows say so, the batch goes on).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

from mech.answers import LEVELS, AnswerKey, parse_key
from mech.errors import MechError
from mech.model import Claim, Mechanism
from mech.options import SolveOptions
from mech.units import Dimension

if TYPE_CHECKING:  # pragma: no cover
    from mech.icentres import ICentres
    from mech.kinematics import Kinematics
    from mech.topology import Topology

__all__ = ["NOISE", "Analysis", "InternalError"]

#: Errors below this fraction of the mechanism's own scale are rounding, not a wrong answer.
NOISE = 1e-6

_SOLVED = ("position", "velocity", "acceleration")


class InternalError(Exception):
    """A bug in mech met while checking: reported as an error row that says it is a bug.

    Not a :class:`MechError` (the input is not at fault) and not swallowed:
    the row names the exception and where it was raised, the exit status is 1.
    """

    @classmethod
    def of(cls, exc: BaseException) -> InternalError:
        import traceback

        frames = traceback.extract_tb(exc.__traceback__)
        ours = [f for f in frames if "/mech/" in f.filename.replace("\\", "/")] or frames
        at = (
            f" at {'/'.join(ours[-1].filename.replace(chr(92), '/').split('/')[-2:])}:{ours[-1].lineno}"
            if ours
            else ""
        )
        return cls(f"internal error in mech (a bug, please report it): {type(exc).__name__}: {exc}{at}")


class Analysis:
    """The computed side of a check, each piece made on first use and kept.

    A solve that fails is kept as its error, so that every claim needing it
    gets the same reason without solving again.
    """

    #: Errors below this fraction of the mechanism's own scale are rounding (see mech.check).
    noise = NOISE

    def __init__(self, mech: Mechanism, *, options: SolveOptions | None = None) -> None:
        self.mech = mech
        self.options = options or SolveOptions()
        self.level = "topology"
        self._cache: dict[str, Any] = {}

    def need(self, claims: Sequence[Claim] | Sequence[str] | Sequence[AnswerKey]) -> None:
        """Raise the solve level to the highest any claim (or key) needs, before anything is solved."""
        for claim in claims:
            if isinstance(claim, AnswerKey):
                level = claim.level
            else:
                level = parse_key(claim if isinstance(claim, str) else claim.key).level
            if level in _SOLVED and LEVELS.index(level) > LEVELS.index(self.level):
                self.level = level
                # a solve made for a lower level is not enough any more
                for name in [n for n in self._cache if n not in ("topology", "mobility")]:
                    del self._cache[name]

    def cached(self, name: str, make: Callable[[], Any]) -> Any:
        """``make()`` once per analysis (a solve's error is kept and raised again): for answer keys
        whose reference value costs (a sweep for ``transmission_angle.min``)."""
        if name not in self._cache:
            try:
                self._cache[name] = make()
            except MechError as error:
                self._cache[name] = error
            except Exception as exc:  # a bug in an analysis: one file's rows say so, the batch goes on
                self._cache[name] = InternalError.of(exc)
        value = self._cache[name]
        if isinstance(value, (MechError, InternalError)):
            raise value
        return value

    def below(self, level: str) -> Analysis | None:
        """This problem solved only to ``level`` (made once, kept), or None when ``level`` is not below.

        The whole file is solved once at the highest level its claims need; when that
        solve fails (an acceleration without the profiles' curvature), a key that needs
        less — a velocity — is computed again from a solve of its own level, so that an
        uncomputable acceleration costs only itself (issue 22).
        """
        if level not in _SOLVED or LEVELS.index(level) >= LEVELS.index(self.level):
            return None

        def make() -> Analysis:
            sub = Analysis(self.mech, options=self.options)
            sub.level = level
            for name in ("topology", "mobility"):
                if name in self._cache:
                    sub._cache[name] = self._cache[name]
            return sub

        return self.cached(f"below:{level}", make)  # type: ignore[no-any-return]

    @property
    def topology(self) -> Topology:
        from mech.topology import classify

        return self.cached("topology", lambda: classify(self.mech))  # type: ignore[no-any-return]

    @property
    def mobility(self) -> int | None:
        def make() -> int | None:
            if "kin" in self._cache and not isinstance(self._cache["kin"], MechError):
                return self._cache["kin"].mobility.numeric  # type: ignore[no-any-return]
            from mech.kinematics import mobility

            return mobility(self.mech).numeric

        return self.cached("mobility", make)  # type: ignore[no-any-return]

    @property
    def kin(self) -> Kinematics:
        def make() -> Kinematics:
            from mech.analysis import solve_at

            level = self.level if self.level in _SOLVED else "position"
            return solve_at(self.mech, level, self.options)

        return self.cached("kin", make)  # type: ignore[no-any-return]

    @property
    def icentres(self) -> ICentres:
        def make() -> ICentres:
            from mech.analysis import locate_icentres

            return locate_icentres(self.mech, self.kin)

        return self.cached("icentres", make)  # type: ignore[no-any-return]

    # -- the mechanism's own scales, for the rounding floor ---------------------------------
    @property
    def omega_ref(self) -> float:
        """The fastest link's |ω| (rad/s); for a pure translation, the fastest point's speed / size."""
        kin = self.kin
        w = max((abs(s.omega or 0.0) for s in kin.links.values()), default=0.0)
        if w > 0.0:
            return w
        speeds = [math.hypot(*s.velocity) for s in kin.links.values() if s.velocity is not None]
        return max(speeds, default=0.0) / kin.size if kin.size > 0 else 0.0

    def scale(self, dimension: Dimension | None) -> float:
        """The mechanism's natural unit of a quantity: size, ω, ω·size, ω²·size, ω².

        Angles need no solve (their unit is the radian).  A key answered without the
        linkage solver (a cam's programme, which the instant solver cannot place) gets
        no rounding floor when that solve fails: its tolerance alone decides.
        """
        if dimension in (None, Dimension.NUMBER, Dimension.ANGLE):
            return 1.0
        try:
            size = self.kin.size
            w = self.omega_ref
        except MechError:
            return 0.0
        return {
            Dimension.LENGTH: size,
            Dimension.ANGULAR_VELOCITY: w,
            Dimension.VELOCITY: w * size,
            Dimension.ACCELERATION: w * w * size,
            Dimension.ANGULAR_ACCELERATION: w * w,
        }.get(dimension, 1.0)
