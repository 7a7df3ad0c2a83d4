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
"""
