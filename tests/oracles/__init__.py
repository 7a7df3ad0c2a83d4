"""Independent references for the tests: what the answer must be, derived without mech.

Every function here works a result from the geometry and the constraint equations alone
(closed forms, a linear solve of the velocity constraints written out by hand) and imports
nothing from ``mech``: a test that compares mech against an oracle can fail.  Each module
says what it derives and from what; ``tests/oracles/test_oracles.py`` checks the oracles
themselves against textbook answers, so they are trusted for a reason.

- :mod:`oracles.four_bar`: the four-bar chain (positions, ω, α by the vector loop, and the
  same refused where it does not close or closes near a toggle; the crank-rocker's limit
  positions and time ratio by the law of cosines; the rocker angle in mpmath for derivatives
  to 30 digits).
- :mod:`oracles.slider_crank`: the slider crank, in line or offset (loop equations
  differentiated; dead centres from the collinear crank-and-rod triangles; x_B in mpmath;
  the crank's angle and ω when the slider drives, the closure differentiated in x).
- :mod:`oracles.velocity_field`: the velocity of every link of any planar chain from its
  pin, slider and contact constraints (a linear solve), and I-centres read off that field.
- :mod:`oracles.field_cases`: mechanisms written both as mech YAML and as those constraints.
- :mod:`oracles.transmission`: the four-bar's transmission angle (the cosine rule, and its
  half-angle form at a given diagonal BD), whether its crank turns fully, and which of its
  links turn fully by sampling the loop's closure at every angle of each.
- :mod:`oracles.lines`: where two lines meet (Cramer's rule; the parametric form), for
  I-centres on Kennedy's lines.
- :mod:`oracles.inversor`: the Peaucellier–Lipkin inversor's P on its straight line (inversion)
  and from the rhombus of its links, and the change point where the rhombus folds flat.
- :mod:`oracles.cam`: the textbook rise laws, a follower put on a profile taken as a bare
  polygon, the three-point radius of curvature, the oscillating example's pressure angle.
"""
