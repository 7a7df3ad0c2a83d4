"""Closed-form kinematics of chains that decompose into dyads: the fast path.

A crank-driven chain whose links can be placed one dyad at a time (Assur
groups of class II) has closed-form positions, and differentiating those
closed forms gives velocities and accelerations with two linear equations
per dyad.  :func:`program` finds such a decomposition of a mechanism once
and compiles it; the compiled program then evaluates

* one configuration on plain floats (``math``), a few microseconds, and
* a whole array of crank angles at once (``numpy``), for sweeps,

from **one** body of code: the program is generated as a straight-line
Python function whose only operations are arithmetic and ``sqrt``, ``cos``,
``sin``, ``atan2``, ``clip`` passed in as arguments, so the same function
runs on floats and on arrays.  Each primitive below is one template with its
formula written out, so it reads like the textbook derivation.

Each dyad reports a relative *discriminant* (negative: the loop cannot
close at that angle, so the program never returns a silent NaN: the caller
sees which dyad failed and by how much) and the sine of the angle between
its two constraint rows (near zero: links in line, a toggle, where the
velocity rows become singular; ``1/|sin|`` is the dyad's condition number).

Everything is computed in SI relative to a ground pivot (the constraint
system's ``centre``), so a linkage a million metres from the origin keeps
full relative precision.  Anything that does not decompose this way (a
higher pair, a slider drive, a loop of three or more links, several drives)
gets ``None`` from :func:`program` and is solved by the general Newton
solver.

The package: :mod:`.program` (the compiled program, evaluated on floats or on
arrays), :mod:`.build` (the decomposition and the generated code), :mod:`.templates`
(each primitive's code, with its formula), :mod:`.cycle` (where the loop closes round
the cycle, its change points, the route and branches to an angle).
"""

from mech.kinematics.dyads.build import closes, program
from mech.kinematics.dyads.cycle import (
    ChangePoint,
    branches,
    change_points,
    closing_edge,
    closure_gaps,
    passed,
    route,
)
from mech.kinematics.dyads.program import (
    ACCURATE_COND,
    MATH,
    SLACK,
    DyadProgram,
    FastState,
    numpy_namespace,
)

__all__ = [
    "ACCURATE_COND",
    "MATH",
    "SLACK",
    "ChangePoint",
    "DyadProgram",
    "FastState",
    "branches",
    "change_points",
    "closes",
    "closing_edge",
    "closure_gaps",
    "numpy_namespace",
    "passed",
    "program",
    "route",
]
