"""Laws for random four-bars, with positions and velocities in closed form (no solver)."""

from __future__ import annotations

import itertools
import math

from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mech.icentres import Frame, Instant, Pin, from_instant
from oracles.four_bar import four_bar_clear_of_toggle


class Rigid:
    """A link's motion: ω and the velocity of the point at ``at``."""

    def __init__(self, omega, at, v):
        self.omega, self.at, self.v = omega, at, v

    def velocity_at(self, p):
        return (self.v[0] - self.omega * (p[1] - self.at[1]), self.v[1] + self.omega * (p[0] - self.at[0]))


def four_bar(a, b, c, theta, left):
    """Ground AD = 1 on the x axis; crank a at theta, ω2 = 1; coupler b; rocker c; C left of B→D
    if ``left``: oracles.four_bar's loop, taken only where it closes clear of the toggle."""
    chain = four_bar_clear_of_toggle(a, b, c, 1.0, theta, 1.0, upper=left, margin=0.05, least_det=1e-3)
    assume(chain is not None)  # assemblable, away from the toggle
    return chain


@settings(max_examples=150, deadline=None)
@given(
    a=st.floats(0.1, 2.0),
    b=st.floats(0.1, 2.0),
    c=st.floats(0.1, 2.0),
    theta=st.floats(-math.pi, math.pi),
    left=st.booleans(),
)
def test_random_four_bars_obey_kennedy_and_share_velocity_at_each_centre(a, b, c, theta, left):
    (A, B, C, D), (w2, w3, w4) = four_bar(a, b, c, theta, left)
    size = max(math.dist(p, q) for p, q in itertools.combinations((A, B, C, D), 2))
    links = ("frame", "crank", "coupler", "rocker")
    inst = Instant(
        links,
        Frame(((A[0] + B[0] + C[0] + D[0]) / 4, (A[1] + B[1] + C[1] + D[1]) / 4), size),
        pins=(
            Pin("A", ("frame", "crank"), A),
            Pin("B", ("crank", "coupler"), B),
            Pin("C", ("coupler", "rocker"), C),
            Pin("D", ("rocker", "frame"), D),
        ),
    )
    motion = {
        "frame": Rigid(0.0, A, (0.0, 0.0)),
        "crank": Rigid(w2, A, (0.0, 0.0)),
        "coupler": Rigid(w3, B, (-w2 * B[1], w2 * B[0])),
        "rocker": Rigid(w4, D, (0.0, 0.0)),
    }
    ic = from_instant(inst, motion, drivers=("crank",))  # raises if Kennedy and the field disagree
    assert ic.count == 6

    def hom(centre):
        v = (
            (centre.point[0] / size, centre.point[1] / size, 1.0)
            if centre.point
            else (*centre.direction, 0.0)
        )
        n = math.hypot(*v)
        return [x / n for x in v]

    for i, j, k in itertools.combinations((1, 2, 3, 4), 3):
        p, q, r = hom(ic.by_number(i, j)), hom(ic.by_number(j, k)), hom(ic.by_number(i, k))
        det = (
            p[0] * (q[1] * r[2] - q[2] * r[1])
            - p[1] * (q[0] * r[2] - q[2] * r[0])
            + p[2] * (q[0] * r[1] - q[1] * r[0])
        )
        assert abs(det) < 1e-9, (i, j, k)
    wref = max(abs(w2), abs(w3), abs(w4))
    for centre in ic.centres:
        if centre.point is None:
            continue
        va = motion[centre.links[0]].velocity_at(centre.point)
        vb = motion[centre.links[1]].velocity_at(centre.point)
        far = max(1.0, math.dist(centre.point, inst.frame.origin) / size)
        assert math.dist(va, vb) <= 1e-9 * wref * size * far, centre.name
    by_ic = ic.omega_by_icentres
    assert math.isclose(by_ic["coupler"], w3, rel_tol=1e-8, abs_tol=1e-9 * wref)
    assert math.isclose(by_ic["rocker"], w4, rel_tol=1e-8, abs_tol=1e-9 * wref)
