"""The compile context of the constraint rows: what a pair kind's rows read, and where they go.

Each joint's kind writes its rows (:meth:`mech.pairs.base.PairKind.rows`) into
a :class:`Build`, which implements :class:`mech.pairs.rows.RowBuilder`: the
drawn configuration scaled by the mechanism's size and relative to a ground
pivot, the links' q blocks, and the lists of row records
(:mod:`mech.pairs.rows`) that :func:`mech.kinematics.constraints.build_system`
stacks into arrays.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import field
from typing import TYPE_CHECKING

import numpy as np

from mech._records import dataclass
from mech.pairs.path import PathSpec, path_angle

if TYPE_CHECKING:
    from mech.errors import Problem
    from mech.kinematics.layout import Layout
    from mech.model import Mechanism, Ref
    from mech.pairs.curves import CurveRow
    from mech.pairs.rows import Angle, Coincide, Distance, Locator, OnLine

__all__ = ["Build"]


@dataclass(eq=False)
class Build:
    """What a kind's row function reads (the drawn configuration) and where it writes its rows.

    Coordinates are scaled (divided by the mechanism's size) and relative to
    ``centre``; ``index`` maps link names to q blocks (ground is ``n``).
    """

    lay: Layout
    pos: dict[str, tuple[float, float]]
    index: dict[str, int]
    n: int
    q0: np.ndarray
    scale: float
    sc: Callable[[tuple[float, float]], np.ndarray]
    scn: Callable[[str], np.ndarray]
    paths: dict[str, PathSpec]
    coincide: list[Coincide] = field(default_factory=list)
    online: list[OnLine] = field(default_factory=list)
    angle: list[Angle] = field(default_factory=list)
    distance: list[Distance] = field(default_factory=list)
    curves: list[CurveRow] = field(default_factory=list)
    problems: list[Problem] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)  # what the rows approximate, said once
    path_dirs: dict[str, tuple[int, np.ndarray]] = field(default_factory=dict)
    path_points: dict[str, tuple[int, str]] = field(default_factory=dict)
    locators: dict[str, Locator] = field(default_factory=dict)  # moving contact point, from q
    normals: dict[str, Locator] = field(default_factory=dict)  # its common normal (unit), from q
    contact_points: dict[str, Locator] = field(default_factory=dict)  # where a pair touches, from q

    @property
    def mech(self) -> Mechanism:
        return self.lay.mech

    @property
    def on_link(self) -> Mapping[str, tuple[str, ...]]:
        return self.lay.on_link

    @property
    def carriers(self) -> Mapping[str, tuple[str, ...]]:
        return self.lay.carriers

    def resolve(self, name: str) -> str:
        return self.lay.resolve(name)

    def path(self, joint: str) -> PathSpec | None:
        return self.paths.get(joint)

    def path_angle(self, path: PathSpec) -> float:
        return path_angle(path.path, self.pos, self.lay.resolve)

    def theta(self, link: str) -> float:
        i = self.index[link]
        return 0.0 if i == self.n else float(self.q0[3 * i + 2])

    def to_local(self, link: str, xy: np.ndarray) -> np.ndarray:
        """Global scaled ``xy`` in ``link``'s frame as drawn."""
        i = self.index[link]
        if i == self.n:
            return np.array(xy, float)
        x, y, th = self.q0[3 * i : 3 * i + 3].tolist()  # Python floats: the same IEEE operations
        c, s = math.cos(th), math.sin(th)
        dx, dy = float(xy[0]) - x, float(xy[1]) - y
        return np.array([c * dx + s * dy, -s * dx + c * dy])

    def dir_local(self, link: str, angle: float) -> np.ndarray:
        """A global direction (rad) as drawn, in ``link``'s frame."""
        th = self.theta(link)
        return np.array([math.cos(angle - th), math.sin(angle - th)])

    def where(self, ref: Ref) -> np.ndarray:
        """A :class:`~mech.model.Ref` (coordinates or a name) as drawn, scaled."""
        if ref.xy is not None:
            return self.sc(ref.xy)
        return self.scn(self.lay.resolve(ref.name or ""))
