"""Grading: the reference value of every answer key, computed from one problem's analysis.

The forms of the keys (pattern, comparison, level, dimension) are in
:mod:`mech.answers`, below the loader, which reads them; their values are here,
above :mod:`mech.analysis`, which computes them: :data:`COMPUTE` maps each
form's pattern to its compute function, and :func:`value` looks a parsed key up
in it.  ``mech check`` (:mod:`mech.check`) holds each claim against the value,
and :mod:`mech.diagnose` computes the usual wrong values of a failed one.

How to write a compute function
-------------------------------
``def my_key(an, names) -> value``: the reference value, SI, computed from
``an``, an :class:`Analysis` (``an.mech`` the model, ``an.topology``,
``an.mobility``, ``an.kin`` the solution at the level the key's form declares,
``an.icentres``; anything else: import it inside the function, call it on
``an.mech`` / ``an.kin`` and, if it is costly, keep it with
``an.cached("name", make)``).  ``names`` are the names the key's placeholders
matched, in order.  Raise :class:`mech.answers.Undefined` ("ω of b is zero …")
when the quantity does not exist for this mechanism, a
:class:`mech.errors.MechError` when it cannot be computed (the verdict is then
an error row with the reason).  Add it to :data:`COMPUTE` under its form's
pattern (or call :func:`register` from a module of your own, with the form
registered in :mod:`mech.answers`); ``tests/test_check_keys.py`` checks that
every form has its function and every function its form.

Nothing here imports numpy at import time: the counts of a DOF exercise are
graded from the topology alone.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from mech.answers import JOINT_CLASSES, LINK_CLASSES, AnswerKey
from mech.grading import cam, forces, keys, properties
from mech.grading.cam import cam_key
from mech.grading.lazy import NOISE, Analysis, InternalError

__all__ = ["COMPUTE", "NOISE", "Analysis", "Compute", "InternalError", "register", "value"]

#: ``compute(an, names) -> value``: the reference value of a key, from the problem's analysis.
Compute = Callable[[Analysis, tuple[str, ...]], Any]

#: The compute function of every form of :data:`mech.answers.KINDS`, by the form's pattern.
COMPUTE: dict[str, Compute] = {
    "dof": keys.count("n"),
    "links.count": keys.count("l"),
    **{f"links.{c}": keys.link_class(c) for c in LINK_CLASSES},
    "joints.count": keys.count("joints"),
    **{f"joints.{c}": keys.joint_class(c) for c in JOINT_CLASSES},
    "joints.equivalent_binary": keys.count("j"),
    "higher_pairs": keys.count("h"),
    "icentres.count": keys.icentre_count,
    "mobility": keys.mobility,
    "chain": keys.chain,
    "position.<point>": keys.position,
    "velocity.<point>": keys.velocity,
    "velocity.<point>.<other>": keys.velocity,
    "omega.<link>": keys.omega,
    "omega_ratio.<a>.<b>": keys.omega_ratio,
    "sliding.<joint>": keys.sliding,
    "rubbing.<joint>": keys.rubbing,
    "least_speed.<link>": keys.least_speed_of,
    "acceleration.<point>": keys.acceleration,
    "acceleration.<point>.<other>": keys.acceleration,
    "alpha.<link>": keys.alpha,
    "coriolis.<joint>": keys.coriolis,
    "icentre.<a>.<b>": keys.icentre,
    "distance.<p>.<q>": keys.distance,
    "grashof": properties.grashof,
    "transmission_angle": properties.transmission_angle,
    "transmission_angle.min": properties.transmission_angle_min,
    "transmission_angle.max": properties.transmission_angle_max,
    "time_ratio": properties.time_ratio,
    "time_ratio.<output>": properties.time_ratio,
    "stroke.<joint>": properties.stroke,
    "mechanical_advantage.<out>": properties.mechanical_advantage,
    "input_torque": forces.input_torque,  # with masses, their inertia and weight count (issue 24)
    "input_force": forces.input_force,
    "force.<joint>": forces.force,
    "force.<joint>.x": forces.force_x,
    "force.<joint>.y": forces.force_y,
    "shaking_force": forces.shaking_force,
    "shaking_moment": forces.shaking_moment,
    "torque.mean": forces.torque_mean,
    "energy.fluctuation": forces.energy_fluctuation,
    "flywheel.inertia": forces.flywheel_inertia,
    "pressure_angle.<joint>": cam_key("pressure_angle"),
    "pressure_angle.<joint>.max": cam_key("pressure_angle.max"),
    "displacement.<point>": cam.displacement,
}


def register(pattern: str, compute: Compute) -> Compute:
    """Add the compute function of a form registered in :mod:`mech.answers` (twice is a bug: ValueError)."""
    if pattern in COMPUTE:
        raise ValueError(f"answer key {pattern} has a compute function already")
    COMPUTE[pattern] = compute
    return compute


def value(akey: AnswerKey, an: Analysis) -> Any:
    """The reference value (SI) of a parsed key, from ``an``.

    Raises what the compute function raises (:class:`mech.answers.Undefined`,
    :class:`mech.errors.MechError`), and :class:`InternalError` for a form with
    no compute function (a key registered in :mod:`mech.answers` alone: a bug).
    """
    compute = COMPUTE.get(akey.kind.pattern)
    if compute is None:
        raise InternalError(
            f"internal error in mech (a bug, please report it): answer key {akey.kind.pattern} "
            "has a form but no compute function (mech.grading.COMPUTE)"
        )
    return compute(an, akey.names)
