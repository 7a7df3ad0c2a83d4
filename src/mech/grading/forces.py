"""Reference values of the force answer keys, for ``mech check`` (DESIGN § 1.4).

Each function is ``compute(an, names)`` of :data:`mech.grading.COMPUTE` (the keys'
forms are in :mod:`mech.answers`): ``an`` is the check's analysis of one file (it
gives the mechanism ``an.mech``, the drive's overrides ``an.options`` and a cache
``an.cached(name, make)``), ``names`` the names the key's placeholders matched.
They solve the forces themselves, once per file: the instant's analysis
(:func:`mech.forces.analyse`) for the pair forces, the input effort and the
shaking, the cycle's (:func:`mech.forces.cycle.force_cycle`) for the mean
torque, the fluctuation of energy and the flywheel.  numpy is imported only
inside the functions, when a claim asks for one of these keys.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from mech.answers import Undefined

if TYPE_CHECKING:  # pragma: no cover
    from mech.grading.lazy import Analysis

__all__ = [
    "energy_fluctuation",
    "flywheel_inertia",
    "force",
    "force_x",
    "force_y",
    "input_force",
    "input_torque",
    "shaking_force",
    "shaking_moment",
    "torque_mean",
]

#: Grid of the cycle the keys integrate over (the integrals and extremes are refined
#: between its steps, so they do not depend on it).
CYCLE_STEPS = 360


def _instant(an: Analysis) -> Any:
    from mech.forces import analyse

    return an.cached("forces.instant", lambda: analyse(an.mech, an.options))


def _cycle(an: Analysis) -> Any:
    from mech.forces.cycle import force_cycle

    return an.cached("forces.cycle", lambda: force_cycle(an.mech, an.options, steps=CYCLE_STEPS))


def _pair(an: Analysis, joint: str) -> Any:
    from mech.forces.core import unsaid_on, unsaid_text

    links = unsaid_on(an.mech).get(joint)
    if links is not None:
        raise Undefined(f"cannot be computed: {unsaid_text(joint, links)}")
    fa = _instant(an)
    if not fa.determinate:
        raise Undefined(f"cannot be computed: {fa.note}")
    try:
        return fa.pair(joint)
    except KeyError:
        raise Undefined(
            f"cannot be computed: joint {joint} carries no force of its own (no constraint rows)"
        ) from None


def force(an: Analysis, names: tuple[str, ...]) -> tuple[float, float]:
    """The force the pair carries (N): its vector on the second link named in its ``links``."""
    return _pair(an, names[0]).force  # type: ignore[no-any-return]


def force_x(an: Analysis, names: tuple[str, ...]) -> float:
    """The x component (N) of the pair's force on its second link."""
    return float(_pair(an, names[0]).force[0])


def force_y(an: Analysis, names: tuple[str, ...]) -> float:
    """The y component (N) of the pair's force on its second link."""
    return float(_pair(an, names[0]).force[1])


def _effort(an: Analysis, kind: str) -> float:
    """The input effort with the links' inertia and weight when the file gives masses; the loads
    alone otherwise, by virtual work (:func:`mech.grading.properties.input_torque`)."""
    from mech.grading import properties

    if not an.mech.masses:
        return float(properties.input_torque(an, ()) if kind == "torque" else properties.input_force(an, ()))
    effort = _instant(an).effort
    if effort is None:
        raise Undefined("cannot be computed: the mechanism has no moving drive")
    return properties.effort_value(effort, kind)


def input_torque(an: Analysis, names: tuple[str, ...]) -> float:
    """The torque on the input link (N·m, ccw +): the loads', and the links' inertia and weight."""
    return _effort(an, "torque")


def input_force(an: Analysis, names: tuple[str, ...]) -> float:
    """The force along a slider drive's path (N): the loads', and the links' inertia and weight."""
    return _effort(an, "force")


def shaking_force(an: Analysis, names: tuple[str, ...]) -> tuple[float, float]:
    """−Σ m a_G (N): what the moving links' inertia puts on the frame."""
    return _instant(an).shaking_force  # type: ignore[no-any-return]


def shaking_moment(an: Analysis, names: tuple[str, ...]) -> float:
    """−Σ (r_G × m a_G + I_G α) about the drive's pivot (N·m, ccw +)."""
    return float(_instant(an).shaking_moment)


def _torque_cycle(an: Analysis) -> Any:
    cycle = _cycle(an)
    if cycle.kind != "torque":
        raise Undefined("cannot be computed: the drive is a slider, not a turning crank")
    if cycle.mean is None:
        raise Undefined("cannot be computed: the mechanism cannot be solved over the whole cycle")
    return cycle


def torque_mean(an: Analysis, names: tuple[str, ...]) -> float:
    """The mean input torque over the loads' cycle (N·m, ccw +), at the drive's constant speed."""
    return float(_torque_cycle(an).mean)


def energy_fluctuation(an: Analysis, names: tuple[str, ...]) -> float:
    """ΔE (J): the greatest minus the least of ∫ (T − T_mean) dθ over the cycle."""
    return float(_torque_cycle(an).fluctuation)


def flywheel_inertia(an: Analysis, names: tuple[str, ...]) -> float:
    """The flywheel's moment of inertia (kg·m²) that holds the speed within ``flywheel: {fluctuation}``."""
    cycle = _torque_cycle(an)
    if cycle.coefficient is None:
        raise Undefined("cannot be computed: the file gives no flywheel: {fluctuation: …}")
    if cycle.flywheel is None:
        raise Undefined("cannot be computed: the drive has no speed (give its rpm)")
    return float(cycle.flywheel)
