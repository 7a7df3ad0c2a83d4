"""Constraint rows as named records, in the few shapes every pair kind writes its rows in.

Each kind's :meth:`~mech.pairs.base.PairKind.rows` appends records of these
shapes to the compile context (:class:`RowBuilder`); the kinematics stacks them
into the arrays of :class:`mech.kinematics.constraints.System`, whose residual,
Jacobian and curvature term γ are written once per shape, with a batch axis.
All coordinates are scaled (divided by the mechanism's size) and local to the
link named by index (ground is index ``n``):

:class:`Coincide`  (2 rows) ``r_i(P) − r_j(Q) = 0``: a pin; rolling at the instant.
:class:`OnLine`    (1 row)  ``n_G·(r_S(P) − r_G(T)) + k(θ_S − θ_G) − w·h(φ) = c``: a point on a
                   line fixed in a guide (a path, a circle on a flat face with ``c = ±r``,
                   a wheel's no-slip condition with ``n`` along the line and ``k = ±r``);
                   with a :class:`Law`, a follower moved by its cam's programme, ``φ`` the
                   cam's turn.
:class:`Angle`     (1 row)  ``Σ a_k θ_k = c``: a prismatic pair's fixed angle, a drive, gears
                   on one carrier.
:class:`Distance`  (1 row)  ``½(|r_i(P) − r_j(Q)|² − d²) = 0``: two circles (or a knife edge
                   and a circle) in contact, ``d`` the sum or difference of their radii.
:class:`~mech.pairs.curves.CurveRow` (1 row): a closed spline profile against a point or a line.

``holonomic`` is False for a row that holds only at the drawn instant (a higher
pair given by its contact point and normal): it enters the velocity solve and
the mobility rank, never Newton, and refuses accelerations and sweeps.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Protocol

import numpy as np

from mech._records import dataclass

if TYPE_CHECKING:
    from mech.errors import Problem
    from mech.model import Mechanism
    from mech.pairs.curves import CurveRow
    from mech.specs import PathSpec, Ref

__all__ = ["Angle", "Coincide", "Distance", "Law", "Locator", "OnLine", "RowBuilder"]

#: A point or a direction of the mechanism as a function of q (scaled): a moving contact point.
Locator = Callable[[np.ndarray], np.ndarray]


@dataclass(frozen=True, slots=True)
class Coincide:
    """Point ``si`` of link ``i`` on point ``sj`` of link ``j`` (local, scaled): 2 rows."""

    i: int
    si: np.ndarray
    j: int
    sj: np.ndarray
    joint: str
    holonomic: bool = True


@dataclass(frozen=True, slots=True)
class Law:
    """A follower's lift as a function of its cam's turn: the term ``w·h(φ)`` of an :class:`OnLine` row.

    ``φ = phi0 + sense·(θ_cam − θ_guide)`` is the cam's turn from its programme's
    start; ``lift(φ)`` returns ``h, h′, h″`` (scaled) for an array of turns.  ``w``
    is +1 or −1: which way a rise moves the follower's coordinate.
    """

    cam: int
    sense: float
    phi0: float
    lift: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]]
    w: float = 1.0


@dataclass(frozen=True, slots=True)
class OnLine:
    """Point ``s`` of ``slider`` on the line through ``t`` of ``guide`` with normal ``n`` (local): 1 row.

    ``c`` is the signed distance kept from the line; ``k`` multiplies the
    relative angle θ_slider − θ_guide (a rolling wheel's arc length, or a turning
    follower's angle with ``n = 0``); ``law`` moves the row with a cam's programme.
    """

    slider: int
    s: np.ndarray
    guide: int
    t: np.ndarray
    n: np.ndarray
    c: float
    joint: str
    holonomic: bool = True
    k: float = 0.0
    law: Law | None = None


@dataclass(frozen=True, slots=True)
class Angle:
    """``Σ coef[link] · θ_link = c`` (link indices, ground = n): 1 row."""

    coef: dict[int, float]
    c: float
    joint: str
    holonomic: bool = True


@dataclass(frozen=True, slots=True)
class Distance:
    """Point ``si`` of link ``i`` kept at distance ``d`` from point ``sj`` of link ``j``: 1 row."""

    i: int
    si: np.ndarray
    j: int
    sj: np.ndarray
    d: float
    joint: str
    holonomic: bool = True


class RowBuilder(Protocol):
    """What a kind's :meth:`~mech.pairs.base.PairKind.rows` may read and where it writes.

    The drawn configuration is scaled (divided by :attr:`scale`) and relative to a
    ground pivot; ``index`` maps link names to q blocks (ground is ``n``); ``pos`` the
    drawn positions in metres.  ``locators`` give a location fixed in no link (a contact
    point) from q; ``contact_points`` where a pair whose location is fixed in a link (a
    follower's own point) touches; ``normals`` a contact's common normal.  Implemented by
    :class:`mech.kinematics.rows.Build`.
    """

    @property
    def mech(self) -> Mechanism: ...
    @property
    def n(self) -> int: ...
    @property
    def q0(self) -> np.ndarray: ...
    @property
    def scale(self) -> float: ...
    @property
    def index(self) -> Mapping[str, int]: ...
    @property
    def pos(self) -> Mapping[str, tuple[float, float]]: ...
    @property
    def coincide(self) -> list[Coincide]: ...
    @property
    def online(self) -> list[OnLine]: ...
    @property
    def angle(self) -> list[Angle]: ...
    @property
    def distance(self) -> list[Distance]: ...
    @property
    def curves(self) -> list[CurveRow]: ...
    @property
    def problems(self) -> list[Problem]: ...
    @property
    def notes(self) -> list[str]: ...
    @property
    def locators(self) -> dict[str, Locator]: ...
    @property
    def normals(self) -> dict[str, Locator]: ...
    @property
    def contact_points(self) -> dict[str, Locator]: ...
    @property
    def path_dirs(self) -> dict[str, tuple[int, np.ndarray]]: ...
    @property
    def path_points(self) -> dict[str, tuple[int, str]]: ...
    @property
    def on_link(self) -> Mapping[str, tuple[str, ...]]: ...
    @property
    def carriers(self) -> Mapping[str, tuple[str, ...]]: ...

    def theta(self, link: str) -> float: ...
    def to_local(self, link: str, xy: np.ndarray) -> np.ndarray: ...
    def dir_local(self, link: str, angle: float) -> np.ndarray: ...
    def where(self, ref: Ref) -> np.ndarray: ...
    def sc(self, xy: tuple[float, float]) -> np.ndarray: ...
    def scn(self, name: str) -> np.ndarray: ...
    def resolve(self, name: str) -> str: ...
    def path(self, joint: str) -> PathSpec | None: ...
    def path_angle(self, path: PathSpec) -> float: ...
