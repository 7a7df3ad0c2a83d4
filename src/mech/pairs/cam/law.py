"""A cam with a programme moves its follower by the programme's law, exactly, in every command.

The programme says how far the follower is from where it starts, as a function
of the cam's turn: ``s(φ)`` with its derivatives in closed form
(:func:`mech.cam.program.follower_motion`).  That is one constraint row, in the
shape of a point on a line with a law (:class:`mech.pairs.rows.OnLine` with
:class:`mech.pairs.rows.Law`):

* a translating follower (sliding on the frame along ``u``, the direction it
  rises): ``u·(r_F(P) − O) − s(φ) = c``, P the follower's own point;
* an oscillating follower (turning about its pivot on the frame):
  ``θ_F − σ_f·s(φ) = c``, σ_f the sense a rise swings it (:func:`mech.cam.profile.swing`);

with ``φ = φ₀ + σ(θ_cam − θ_frame)`` the cam's turn from the programme's start in
the sense it turns, and ``c`` what the drawn configuration gives (the drawing is
the programme's at the drive's angle).  The row's Jacobian carries ``s′(φ)`` and
its curvature term ``s″(φ)·φ̇²``: positions, velocities and accelerations of the
follower are the law's own, to rounding, in single solves and sweeps alike.  No
profile is fitted: the profile matters only for where the two links touch, which
:func:`mech.cam.profile.evaluate` gives in closed form too.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from mech.cam.profile import CamLayout, evaluate, swing
from mech.cam.program import follower_motion
from mech.pairs.cam.setup import cam_setup, follower_slide
from mech.pairs.rows import Law, OnLine

if TYPE_CHECKING:
    from mech.model import Joint
    from mech.pairs.rows import RowBuilder

__all__ = ["programme_rows"]


def programme_rows(b: RowBuilder, j: Joint) -> None:
    """The follower's row from its cam's law, and the contact point and common normal as functions of q."""
    setup = cam_setup(b.mech, j.name)
    lay, prog = setup.layout, setup.layout.program
    cam, follower = b.index[setup.cam], b.index[setup.follower]
    ground = b.index[b.mech.ground]
    sense = float(lay.sense)
    phi0 = setup.angle - sense * b.theta(setup.cam)  # the cam's turn is φ₀ + σθ_cam
    zero = np.zeros(2)
    if lay.oscillating:
        _, sf = swing(lay)

        def angle_lift(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
            m = follower_motion(prog, phi)
            return m.s, m.ds, m.d2s

        law = Law(cam, sense, phi0, angle_lift, w=sf)
        s_drawn = float(angle_lift(np.array([setup.angle]))[0][0])
        c = b.theta(setup.follower) - sf * s_drawn
        row = OnLine(follower, zero, ground, zero, zero, c, j.name, k=1.0, law=law)
    else:
        scale = b.scale

        def length_lift(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
            m = follower_motion(prog, phi)
            return m.s / scale, m.ds / scale, m.d2s / scale

        law = Law(cam, sense, phi0, length_lift)
        slide = b.path(follower_slide(b.mech, setup.follower).name)
        assert slide is not None  # the setup found the slide; the layout resolved its point
        u = np.array([math.cos(lay.axis), math.sin(lay.axis)])
        o, p = b.sc(setup.centre), b.scn(slide.point)
        c = float(u @ (p - o)) - float(length_lift(np.array([setup.angle]))[0][0])
        row = OnLine(follower, b.to_local(setup.follower, p), ground, o, u, c, j.name, law=law)
    b.online.append(row)
    _contact(b, j, setup.centre, lay, phi0, sense, setup.cam)


def _contact(
    b: RowBuilder, j: Joint, centre: tuple[float, float], lay: CamLayout, phi0: float, sense: float, cam: str
) -> None:
    """Where the cam touches its follower, and their common normal, at the configuration q (scaled)."""
    o = b.sc(centre)
    i = b.index[cam]

    def state(q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        st = evaluate(lay, [phi0 + sense * float(q[3 * i + 2])])
        return o + st.contact[0] / b.scale, st.normal[0]

    b.contact_points[j.name] = lambda q: state(q)[0]
    b.normals[j.name] = lambda q: state(q)[1]
