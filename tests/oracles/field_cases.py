"""Mechanisms written twice: as mech YAML, and as the constraints :mod:`oracles.velocity_field` solves.

Each case is ``(yaml_text, links, constraints, drive)``.  The constraints are written out by
hand from the same geometry the YAML states (pins where the joints are, slider directions,
contact normals), never read back from mech, so a field solved from them is an independent
reference for ``mech icentres`` and ``mech velocity`` on every pair type: pins, sliders on a
moving guide, a slot, gears (external and internal), rolling, a cam, six and eight links.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["IC_CASES", "Case", "num", "pt"]

Case = tuple[str, list[str], list[tuple[Any, ...]], tuple[Any, ...]]


def num(x: float) -> str:
    """A float as YAML reads it back exactly (repr)."""
    return repr(float(x))


def pt(p: Any) -> str:
    """A point as a YAML flow list."""
    return f"[{num(p[0])}, {num(p[1])}]"


def _ang(deg: float) -> np.ndarray:
    return np.array([math.cos(math.radians(deg)), math.sin(math.radians(deg))])


def _ic_cases() -> dict[str, Case]:
    cases: dict[str, Case] = {}
    # crank-rocker at its limit position: crank and coupler in line, extended (rocker at rest)
    c = 18.75 / 24
    th = math.acos(c)
    B = np.array([math.cos(th), math.sin(th)])
    C = 4 * B
    cases["crank_rocker_at_limit"] = (
        f"""\
links: [frame, crank, coupler, rocker]
joints:
  A: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  B: {{type: revolute, links: [crank, coupler], at: {pt(B)}}}
  C: {{type: revolute, links: [coupler, rocker], at: {pt(C)}}}
  D: {{type: revolute, links: [rocker, frame], at: [3, 0]}}
drive: {{link: crank, angle: {num(math.degrees(th))}, omega: 10}}
""",
        ["frame", "crank", "coupler", "rocker"],
        [
            ("pin", (0, 0), "frame", "crank"),
            ("pin", B, "crank", "coupler"),
            ("pin", C, "coupler", "rocker"),
            ("pin", (3, 0), "rocker", "frame"),
        ],
        ("crank", 10.0),
    )
    # parallelogram: translating coupler (I13 and I24 at infinity)
    B = _ang(70)
    C = B + np.array([2.0, 0])
    cases["parallelogram_translating_coupler"] = (
        f"""\
links: [frame, crank, coupler, rocker]
joints:
  A: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  B: {{type: revolute, links: [crank, coupler], at: {pt(B)}}}
  C: {{type: revolute, links: [coupler, rocker], at: {pt(C)}}}
  D: {{type: revolute, links: [rocker, frame], at: [2, 0]}}
drive: {{link: crank, angle: 70, omega: 5}}
""",
        ["frame", "crank", "coupler", "rocker"],
        [
            ("pin", (0, 0), "frame", "crank"),
            ("pin", B, "crank", "coupler"),
            ("pin", C, "coupler", "rocker"),
            ("pin", (2, 0), "rocker", "frame"),
        ],
        ("crank", 5.0),
    )
    # crank and slotted lever: slider on a moving guide
    O2 = np.array([0, 0.5])
    A = O2 + 0.12 * _ang(35)
    cases["slotted_lever"] = (
        f"""\
links: [frame, crank, block, lever]
joints:
  O2: {{type: revolute, links: [frame, crank], at: [0, 0.5]}}
  A: {{type: revolute, links: [crank, block]}}
  S: {{type: prismatic, links: [block, lever], path: {{through: O1, toward: B}}}}
  O1: {{type: revolute, links: [lever, frame], at: [0, 0]}}
lengths: {{O2A: 0.12}}
points:
  B: {{link: lever, at: {pt(1.3 * A)}}}
drive: {{link: crank, angle: 35, omega: 20}}
""",
        ["frame", "crank", "block", "lever"],
        [
            ("pin", O2, "frame", "crank"),
            ("pin", A, "crank", "block"),
            ("prismatic", A, "block", "lever", A / np.linalg.norm(A)),
            ("pin", (0, 0), "lever", "frame"),
        ],
        ("crank", 20.0),
    )
    # Scotch yoke: pin in a slot of a yoke that slides on the frame
    P = 0.1 * _ang(60)
    cases["slot_scotch_yoke"] = (
        f"""\
links: [frame, crank, yoke]
joints:
  O: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  P: {{type: slot, links: [crank, yoke], path: {{through: Q, angle: 90}}}}
  Y: {{type: prismatic, links: [yoke, frame], path: {{through: [0, 0], angle: 0}}, point: Q}}
lengths: {{OP: 0.1}}
points:
  Q: {{link: yoke, at: [{num(P[0])}, 0]}}
drive: {{link: crank, angle: 60, omega: 10, direction: ccw}}
""",
        ["frame", "crank", "yoke"],
        [
            ("pin", (0, 0), "frame", "crank"),
            ("normal", P, "crank", "yoke", (1, 0)),
            ("prismatic", (P[0], 0), "yoke", "frame", (1, 0)),
        ],
        ("crank", 10.0),
    )
    n20 = (math.sin(math.radians(20)), math.cos(math.radians(20)))
    cases["gears_external"] = (
        """\
links: [frame, g1, g2]
joints:
  O1: {type: revolute, links: [frame, g1], at: [0, 0]}
  O2: {type: revolute, links: [frame, g2], at: [0.15, 0]}
  M: {type: gear, links: [g1, g2], radii: [0.05, 0.1], pressure_angle: 20}
drive: {link: g1, omega: 30, direction: cw}
""",
        ["frame", "g1", "g2"],
        [
            ("pin", (0, 0), "frame", "g1"),
            ("pin", (0.15, 0), "frame", "g2"),
            ("normal", (0.05, 0), "g1", "g2", n20),
        ],
        ("g1", -30.0),
    )
    cases["gears_internal"] = (
        """\
links: [frame, pinion, ring]
joints:
  O1: {type: revolute, links: [frame, pinion], at: [0, 0]}
  O2: {type: revolute, links: [frame, ring], at: [0.15, 0]}
  M: {type: gear, links: [pinion, ring], radii: [0.05, 0.2], internal: true, pressure_angle: 20}
drive: {link: pinion, omega: 30, direction: ccw}
""",
        ["frame", "pinion", "ring"],
        [
            ("pin", (0, 0), "frame", "pinion"),
            ("pin", (0.15, 0), "frame", "ring"),
            ("normal", (-0.05, 0), "pinion", "ring", n20),
        ],
        ("pinion", 30.0),
    )
    # a wheel rolling on the ground, driven through a crank and rod
    Bc, rw = 0.1 * _ang(60), 0.05
    C = np.array([Bc[0] + math.sqrt(0.3**2 - (rw - Bc[1]) ** 2), rw])
    cases["rolling_wheel"] = (
        f"""\
links: [frame, crank, rod, wheel]
joints:
  O: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  A: {{type: revolute, links: [crank, rod], at: {pt(Bc)}}}
  C: {{type: revolute, links: [rod, wheel], at: {pt(C)}}}
  R: {{type: rolling, links: [wheel, frame], at: [{num(C[0])}, 0]}}
drive: {{link: crank, angle: 60, omega: 10}}
""",
        ["frame", "crank", "rod", "wheel"],
        [
            ("pin", (0, 0), "frame", "crank"),
            ("pin", Bc, "crank", "rod"),
            ("pin", C, "rod", "wheel"),
            ("pin", (C[0], 0), "wheel", "frame"),
        ],
        ("crank", 10.0),
    )
    cases["cam_offset_follower"] = (
        """\
links: [frame, cam, follower]
joints:
  O: {type: revolute, links: [frame, cam], at: [0, 0]}
  G: {type: prismatic, links: [follower, frame], path: {through: [0.01, 0], angle: 90}, point: T}
  K: {type: cam, links: [cam, follower], at: [0.01, 0.04], normal: 120}
points:
  T: {link: follower, at: [0.01, 0.04]}
drive: {link: cam, omega: 10}
""",
        ["frame", "cam", "follower"],
        [
            ("pin", (0, 0), "frame", "cam"),
            ("prismatic", (0.01, 0.04), "follower", "frame", (0, 1)),
            ("normal", (0.01, 0.04), "cam", "follower", _ang(120)),
        ],
        ("cam", 10.0),
    )
    Aq, Bq = np.array([math.cos(math.radians(30)), 0]), np.array([0, 0.5])
    cases["elliptic_trammel"] = (
        f"""\
links: [frame, sx, bar, sy]
joints:
  PA: {{type: prismatic, links: [sx, frame], path: {{through: [0, 0], angle: 0}}, point: A}}
  A: {{type: revolute, links: [sx, bar], at: {pt(Aq)}}}
  B: {{type: revolute, links: [bar, sy], at: {pt(Bq)}}}
  PB: {{type: prismatic, links: [sy, frame], path: {{through: [0, 0], angle: 90}}, point: B}}
drive: {{link: bar, omega: 2, about: A}}
""",
        ["frame", "sx", "bar", "sy"],
        [
            ("prismatic", Aq, "sx", "frame", (1, 0)),
            ("pin", Aq, "sx", "bar"),
            ("pin", Bq, "bar", "sy"),
            ("prismatic", Bq, "sy", "frame", (0, 1)),
        ],
        ("bar", 2.0),
    )
    st = dict(O1=(0, 0), a=(1, 1), b=(1.2, -0.4), d=(2.5, 1.8), e=(2.8, 0.3), c=(3.6, 1.5), O2=(4, 0.2))
    pairs = dict(
        O1=("frame", "T1"),
        a=("T1", "B1"),
        b=("T1", "B2"),
        d=("B1", "T2"),
        e=("B2", "T2"),
        c=("T2", "B4"),
        O2=("B4", "frame"),
    )
    cases["stephenson_six_bar"] = (
        "links: [frame, T1, B1, B2, T2, B4]\njoints:\n"
        + "".join(
            f"  {k}: {{type: revolute, links: [{a}, {b}], at: {pt(st[k])}}}\n" for k, (a, b) in pairs.items()
        )
        + "drive: {link: T1, omega: 10, angle: 45}\n",
        ["frame", "T1", "B1", "B2", "T2", "B4"],
        [("pin", st[k], a, b) for k, (a, b) in pairs.items()],
        ("T1", 10.0),
    )
    t = np.array([0.2, 1.4]) / math.hypot(0.2, 1.4)
    cases["six_bar_slider_on_moving_rocker"] = (
        """\
links: [frame, crank, coupler, rocker, block, link5]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler], at: [0.5, 0.866]}
  C: {type: revolute, links: [coupler, rocker], at: [2.2, 1.4]}
  D: {type: revolute, links: [rocker, frame], at: [2, 0]}
  S: {type: prismatic, links: [block, rocker], path: {through: D, toward: C}, point: F}
  F: {type: revolute, links: [block, link5], at: [2.1, 0.7]}
  G: {type: revolute, links: [link5, frame], at: [3.5, 1.0]}
drive: {link: crank, omega: 10}
""",
        ["frame", "crank", "coupler", "rocker", "block", "link5"],
        [
            ("pin", (0, 0), "frame", "crank"),
            ("pin", (0.5, 0.866), "crank", "coupler"),
            ("pin", (2.2, 1.4), "coupler", "rocker"),
            ("pin", (2, 0), "rocker", "frame"),
            ("prismatic", (2.1, 0.7), "block", "rocker", t),
            ("pin", (2.1, 0.7), "block", "link5"),
            ("pin", (3.5, 1.0), "link5", "frame"),
        ],
        ("crank", 10.0),
    )
    # eight links, some I-centres beyond Kennedy (from tests/icentres; positions in mm)
    j8 = dict(
        P02=((32.383, 15.085), "frame", "crank"),
        P03=((65.093, 7.244), "frame", "L3"),
        P06=((53.588, 36.569), "frame", "L6"),
        P12=((5.800, 50.744), "L1", "crank"),
        P14=((3.750, 43.365), "L1", "L4"),
        P15=((6.986, 9.071), "L1", "L5"),
        P35=((42.452, 82.685), "L3", "L5"),
        P46=((12.380, 22.324), "L4", "L6"),
        P47=((62.743, 94.771), "L4", "L7"),
        P57=((57.710, 39.668), "L5", "L7"),
    )
    cases["eight_links_beyond_kennedy"] = (
        "units: {length: mm, angle: deg}\nlinks: [frame, L1, crank, L3, L4, L5, L6, L7]\njoints:\n"
        + "".join(
            f"  {k}: {{type: revolute, links: [{a}, {b}], at: [{p[0]}, {p[1]}]}}\n"
            for k, (p, a, b) in j8.items()
        )
        + "drive: {link: crank, omega: 6}\n",
        ["frame", "L1", "crank", "L3", "L4", "L5", "L6", "L7"],
        [("pin", (p[0] / 1000, p[1] / 1000), a, b) for p, a, b in j8.values()],
        ("crank", 6.0),
    )
    # slider crank driven by its piston (the driver has w = 0: the I-centre method must still work)
    A = 0.1 * _ang(45)
    Bx = A[0] + math.sqrt(0.4**2 - A[1] ** 2)
    cases["slider_driven_crank"] = (
        f"""\
links: [frame, crank, rod, piston]
joints:
  O: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  A: {{type: revolute, links: [crank, rod], at: {pt(A)}}}
  B: {{type: revolute, links: [rod, piston], near: [0.45, 0]}}
  P: {{type: prismatic, links: [piston, frame], path: {{through: [0, 0], angle: 0}}}}
lengths: {{AB: 0.4}}
drive: {{joint: P, speed: 2}}
""",
        ["frame", "crank", "rod", "piston"],
        [
            ("pin", (0, 0), "frame", "crank"),
            ("pin", A, "crank", "rod"),
            ("pin", (Bx, 0), "rod", "piston"),
            ("prismatic", (Bx, 0), "piston", "frame", (1, 0)),
        ],
        ("slide", (Bx, 0), "piston", (1, 0), 2.0),
    )
    return cases


IC_CASES = _ic_cases()
