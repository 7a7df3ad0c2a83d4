"""Cams from their follower's motion programme.

* :mod:`mech.cam.program` — the programme (segments of rise, dwell, return) as
  plain records, and the follower's lift against cam angle;
* :mod:`mech.cam.laws` — the motion laws (uniform velocity, SHM, uniform
  acceleration and retardation, cycloidal) with exact derivatives;
* :mod:`mech.cam.profile` — the cam's profile for a knife-edge, roller or
  flat-faced follower, translating (in-line or offset) or oscillating, its
  pressure angle and radius of curvature;
* :mod:`mech.cam.analysis` — the whole turn analysed: s, v, a, jerk, the
  largest pressure angle, the least radius of curvature against the roller;
* :mod:`mech.cam.mechanism` — the layout read from a mechanism file's joints.

This package imports numpy (in its computing modules) but never rich or click.

The pair-kind registry (:mod:`mech.pairs`) plugs a programme in through the two
functions below (see :mod:`mech.pairs.specs`); they import nothing heavy until
called.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from mech.cam.program import CamProgram
    from mech.model import Joint, Mechanism
    from mech.pairs.specs import Profile

__all__ = ["program_profiles", "read_program"]


def read_program(reader: Any, node: Any, what: str) -> CamProgram:
    """A cam joint's ``program`` read from its YAML node (:func:`mech.cam.read.read_program`)."""
    from mech.cam.read import read_program as read

    return read(reader, node, what)


def program_profiles(
    mech: Mechanism, joint: Joint, positions: dict[str, tuple[float, float]] | None = None
) -> dict[str, Profile]:
    """The profiles a cam's programme gives, keyed by link (:func:`mech.cam.mechanism.program_profiles`)."""
    from mech.cam.mechanism import program_profiles as profiles

    return profiles(mech, joint, positions)
