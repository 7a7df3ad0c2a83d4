"""Properties of a linkage beyond its motion at one instant, as a course asks for them.

* Grashof's criterion for every four-bar loop, the class (crank-rocker …),
  which links turn fully, and the inversion of a slider-crank loop, are in
  :mod:`mech.topology.grashof` (pure Python, below this room: ``mech dof`` and
  ``mech classify`` report them); :mod:`.grashof` re-exports them.
* :mod:`.cycle` — transmission angle (at the instant, least and greatest over
  the cycle), limit positions, strokes and the quick-return time ratio.
* :mod:`.advantage` — velocity ratio and mechanical advantage by I-centres,
  loads and the input torque that balances them (virtual work).
* :mod:`.paths` — coupler curves and centrodes.

Import the submodules you need: this package imports nothing heavy itself.
"""
