"""Kinematics of planar mechanisms: positions, velocities, accelerations, numeric mobility.

The public API::

    from mech.kinematics import solve, mobility, Kinematics, LinkState, Mobility
    kin = solve(mech, level="acceleration", options=SolveOptions(omega=12.57))
    kin.positions["C"], kin.velocity("C"), kin.links["rocker"].omega
    s = sweep(mech, np.radians(np.arange(0, 360.1, 0.1)), level="acceleration")
    s.extremes, s.dead_centres, s.time_ratio, s.series("omega.rocker")
    closed_form(mech).state(phi, omega, alpha)      # the lean few-µs path (dyads)

Modules: :mod:`.geometry` (closed-form primitives), :mod:`.layout` (what the
file locates), :mod:`.assemble` (the drawn configuration), :mod:`.constraints`
(Φ, Φ_q, γ in reference-point coordinates), :mod:`.solve` (Newton, velocity,
acceleration), :mod:`.dyads` (closed form), :mod:`.sweep` (cycles: the driver; :mod:`.sweep_backends`, :mod:`.sweep_events`,
:mod:`.roots`, :mod:`.quantities`, :mod:`.sweep_result`), :mod:`.mobility` (Jacobian rank), :mod:`.result` (frozen results).
numpy is imported here, never by ``mech`` itself.
"""

from mech.kinematics.mobility import kutzbach
from mech.kinematics.result import Kinematics, LinkState, Mobility
from mech.kinematics.solve import closed_form, mobility, solve
from mech.kinematics.sweep import Sweep, sweep

__all__ = [
    "Kinematics",
    "LinkState",
    "Mobility",
    "Sweep",
    "closed_form",
    "kutzbach",
    "mobility",
    "solve",
    "sweep",
]
