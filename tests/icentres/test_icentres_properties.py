"""Laws for random four-bars, with positions and velocities in closed form (no solver)."""

from __future__ import annotations

import itertools
import math

from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mech.icentres import Frame, Instant, Pin, from_instant


class Rigid:
    """A link's motion: ω and the velocity of the point at ``at``."""

    def __init__(self, omega, at, v):
        self.omega, self.at, self.v = omega, at, v

    def velocity_at(self, p):
        return (self.v[0] - self.omega * (p[1] - self.at[1]), self.v[1] + self.omega * (p[0] - self.at[0]))


def four_bar(a, b, c, theta, left):
    """Ground AD = 1 on the x axis; crank a at theta; coupler b; rocker c; C by circle intersection."""
    A, D = (0.0, 0.0), (1.0, 0.0)
    B = (a * math.cos(theta), a * math.sin(theta))
    dx, dy = D[0] - B[0], D[1] - B[1]
    d = math.hypot(dx, dy)
    assume(abs(b - c) + 0.05 < d < b + c - 0.05)  # assemblable, away from the toggle
    along = (b * b - c * c + d * d) / (2 * d)
    h = math.sqrt(b * b - along * along)
    s = 1.0 if left else -1.0
    C = (B[0] + (along * dx - s * h * dy) / d, B[1] + (along * dy + s * h * dx) / d)
    # Velocities, crank at ω2 = 1: v_C = v_B + ω3 k×(C−B) = ω4 k×(C−D), solved by Cramer's rule.
    vB = (-B[1], B[0])
    r3, r4 = (C[0] - B[0], C[1] - B[1]), (C[0] - D[0], C[1] - D[1])
    # ω3 (−r3y, r3x) − ω4 (−r4y, r4x) = −vB
    m11, m12, m21, m22 = -r3[1], r4[1], r3[0], -r4[0]
    det = m11 * m22 - m12 * m21
    assume(abs(det) > 1e-3)
    w3 = (-vB[0] * m22 + vB[1] * m12) / det
    w4 = (m11 * -vB[1] + m21 * vB[0]) / det
    return (A, B, C, D), (1.0, w3, w4)


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
