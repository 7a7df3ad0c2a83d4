"""Reference values of the cam answer keys (``pressure_angle.K``, ``pressure_angle.K.max``,
``displacement.K``) for ``mech check`` (:mod:`mech.grading`).

They come from the cam's own analysis (:func:`mech.cam.analysis.analyse`), made
once per file and shared by every claim about that cam; the linkage solver is
never started for them.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from mech.answers import Undefined

if TYPE_CHECKING:  # pragma: no cover
    from mech.grading.lazy import Analysis

__all__ = ["cam_key", "cam_value"]


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
