"""Cams from their follower's motion programme: the mathematics of a programme.

* :mod:`mech.cam.program` — the programme (segments of rise, dwell, return) as
  plain records, and the follower's lift against cam angle;
* :mod:`mech.cam.laws` — the motion laws (uniform velocity, SHM, uniform
  acceleration and retardation, cycloidal) with exact derivatives;
* :mod:`mech.cam.read` — a joint's ``program`` read from the file, located;
* :mod:`mech.cam.profile` — the cam's profile for a knife-edge, roller or
  flat-faced follower, translating (in-line or offset) or oscillating, its
  pressure angle and radius of curvature;
* :mod:`mech.cam.analysis` — the whole turn analysed: s, v, a, jerk, the
  largest pressure angle, the least radius of curvature against the roller.

Where a programme sits in a mechanism (the cam's pivot, the follower's path or
pivot, the drive) is the cam pair kind's business (:mod:`mech.pairs.cam`),
which also gives the pair its constraint rows from the law.  This package sits
below the pairs: it imports numpy (in its computing modules) but nothing of
mech's above the model, and never rich or click.
"""
