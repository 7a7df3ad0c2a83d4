"""Reference values of the cam answer keys (``pressure_angle.K``, ``pressure_angle.K.max``,
``displacement.K``) for ``mech check`` (:mod:`mech.grading`).

A programme cam's come from its own analysis (:func:`mech.cam.analysis.analyse`), made
once per file and shared by every claim about that cam; the linkage solver is never
started for them.  ``displacement.<point>`` of a cam given by its profiles (an eccentric
circle) is swept over the cam's turn instead (DESIGN § 1.2): the follower's lift from its
lowest position, along its path or about its pivot.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from mech.answers import Undefined

if TYPE_CHECKING:  # pragma: no cover
    from mech.grading.lazy import Analysis

__all__ = ["cam_key", "cam_value", "displacement"]


def cam_key(quantity: str) -> Callable[[Analysis, tuple[str, ...]], float]:
    """The compute function of a cam key: ``quantity`` of the cam joint its name names."""

    def compute(an: Analysis, names: tuple[str, ...]) -> float:
        return cam_value(an, quantity, names[0])

    return compute


def cam_value(an: Analysis, quantity: str, name: str) -> float:
    """The value of ``quantity`` for the cam joint ``name`` (SI: rad, m).

    A name that is not a cam joint with a programme is :class:`mech.answers.Undefined`.
    """
    from mech.cam.analysis import analyse
    from mech.cam.profile import evaluate
    from mech.pairs.cam.setup import cam_joints, cam_setup

    if name not in {j.name for j in cam_joints(an.mech)}:
        raise Undefined(f"cannot be computed: {name} is not a cam joint with a `program`")

    def make() -> Any:
        setup = cam_setup(an.mech, name)
        return setup, analyse(setup.layout, omega=setup.omega)

    setup, result = an.cached(f"cam:{name}", make)
    if quantity == "pressure_angle.max":
        return float(result.pressure.value)
    now = evaluate(setup.layout, [setup.angle])
    if quantity == "pressure_angle":
        return float(now.pressure[0])
    assert quantity == "displacement"
    return float(now.s[0])


def displacement(an: Analysis, names: tuple[str, ...]) -> float:
    """A follower point's lift from its lowest position over the cam's turn (m, or rad for an
    oscillating follower); a cam joint's name stands for its follower's own point (DESIGN § 1.2).

    Every point of a translating follower rises alike, and every point of an oscillating one
    turns through the same angle, so the lift is the follower's: a programme's ``s`` at the
    drive's angle, or, for profiles, its slide's travel (its angle) now less its lowest over
    a turn of the cam, the lowest being the extreme where the follower is nearest the camshaft.
    """
    joint = _cam_of(an.mech, names[0])
    if getattr(joint.spec, "program", None) is not None:
        return cam_value(an, "displacement", joint.name)
    if not joint.profiles:
        raise Undefined(
            f"cannot be computed: cam {joint.name} is described at one instant (`at`, `normal`), "
            "so its follower has no lift over a turn: give `profiles` or a `program`"
        )
    return float(an.cached(f"cam-lift:{joint.name}", lambda: _swept_lift(an, joint)))


def _cam_of(mech: Any, name: str) -> Any:
    """The cam joint ``name`` names, or whose follower (its second link) carries the point ``name``."""
    from mech.pairs import kind_of, located_on

    cams = [j for j in mech.joints if j.type == "cam" or (kind_of(j).higher and not kind_of(j).rolls)]
    for j in cams:
        if j.name == name:
            return j
    carriers = {lk for j in mech.joints if j.name == name for lk in located_on(j)}
    carriers |= {p.link for p in mech.points if p.name == name}
    for j in cams:
        if j.links[1] in carriers:
            return j
    raise Undefined(
        f"cannot be computed: {name} is neither a cam joint nor a point of a cam's follower "
        "(displacement is a follower's lift)"
    )


def _swept_lift(an: Analysis, joint: Any) -> float:
    """The follower's travel (or angle) at the drive's angle less its lowest over a turn of the cam."""
    import math

    import numpy as np

    from mech.kinematics.sweep import sweep
    from mech.pairs import kind_of

    mech, follower = an.mech, joint.links[1]
    slide = next(
        (j for j in mech.joints if kind_of(j).keeps_angle and j.links == (follower, mech.ground)), None
    )
    pivoted = any(kind_of(j).role == "pin" and set(j.links) == {follower, mech.ground} for j in mech.joints)
    if slide is None and not pivoted:
        raise Undefined(
            f"cannot be computed: the follower {follower} of {joint.name} neither slides nor turns on "
            f"{mech.ground}"
        )
    key = f"displacement.{slide.name}" if slide is not None else f"angle.{follower}"
    start = float(an.kin.drives[0].angle or 0.0)
    angles = start + np.linspace(0.0, 2.0 * math.pi, 721)
    swept = sweep(mech, angles, level="position", quantities=[key], options=an.options)
    ext = next(e for e in swept.extremes if e.quantity == key)
    series = swept.series(key)
    lowest = ext.min_value if _nearer(mech, swept, joint, ext.min_angle, ext.max_angle) else ext.max_value
    return abs(float(series[0]) - lowest)


def _nearer(mech: Any, swept: Any, joint: Any, a: float, b: float) -> bool:
    """Whether the follower is nearer the camshaft at drive angle ``a`` than at ``b`` (its lowest)."""
    import numpy as np

    from mech.pairs import kind_of, points_of

    pts = swept.points
    cam, follower = joint.links[0], joint.links[1]
    pivots = [j.name for j in mech.joints if kind_of(j).role == "pin" and set(j.links) == {cam, mech.ground}]
    own = [p for p in points_of(mech, follower) if p in pts]
    if not pivots or pivots[0] not in pts or not own:
        return True
    pos = swept.positions

    def dist(at: float) -> float:
        k = int(np.argmin(np.abs(np.mod(swept.angles - at + np.pi, 2 * np.pi) - np.pi)))
        c, f = pos[k, pts.index(pivots[0])], pos[k, pts.index(own[0])]
        return float(np.hypot(*(f - c)))

    return dist(a) <= dist(b)
