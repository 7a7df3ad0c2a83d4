"""Mechanism files as text, shared by the command-line tests of several subjects.

Each is the smallest file that shows the behaviour; the numbers the tests expect from them
are worked in the tests (or in tests/oracles), never read back from mech.
"""

from __future__ import annotations

from pathlib import Path

import yaml

__all__ = [
    "CRANK_ROCKER",
    "CRANK_ROCKER_LENGTHS",
    "DRAWN_FOUR_BAR",
    "EXAMPLES",
    "FIVE_BAR_ONE_DRIVE",
    "FOLDING_INVERSOR",
    "FOUR_BAR_NAME",
    "FOUR_BAR_PARALLELOGRAM",
    "GEARS",
    "ROLLER_CAM",
    "ROLLER_CAM_POINT_K",
    "TOGGLE_FOUR_BAR",
    "expected_refusal",
    "ladder",
    "lift",
    "slider_crank",
    "strip_answers",
]

EXAMPLES = Path(__file__).resolve().parent.parent / "mechanisms"
FOUR_BAR_NAME = "Four-bar chain ABCD (Khurmi Ex. 7.1)"


def _num(x: float) -> str:
    return repr(float(x))


def slider_crank(
    r: float = 0.1,
    L: float = 0.4,
    angle: float = 90,
    omega: float = 10,
    offset: float = 0.0,
    origin: float = 0.0,
    near_x: float | None = None,
    extra: str = "",
    drive: str | None = None,
    mm: bool = False,
) -> str:
    """In-line (or offset) slider crank, crank O at (origin, origin), path y = origin + offset.

    The slider starts near x = origin + r + L (ahead of the crank); ``drive`` replaces the
    crank drive written from ``angle`` and ``omega``; ``extra`` is appended (answers, …).
    Lengths are in metres, or with ``mm`` in millimetres (the file says `units: {length: mm}`).
    """
    nx = origin + (near_x if near_x is not None else r + L)
    drive = drive or f"{{link: crank, angle: {angle!r}, omega: {omega!r}, direction: ccw}}"
    o, y = _num(origin), _num(origin + offset)
    units = "units: {length: mm, angle: deg}\n" if mm else ""
    return f"""\
{units}links: [frame, crank, rod, piston]
joints:
  O: {{type: revolute, links: [frame, crank], at: [{o}, {o}]}}
  A: {{type: revolute, links: [crank, rod]}}
  B: {{type: revolute, links: [rod, piston], near: [{_num(nx)}, {y}]}}
  P: {{type: prismatic, links: [piston, frame], path: {{through: [{o}, {y}], angle: 0}}}}
lengths: {{OA: {_num(r)}, AB: {_num(L)}}}
drive: {drive}
{extra}"""


def strip_answers(name: str) -> str:
    """A shipped example without its answers: a problem for answer sheets."""
    return (EXAMPLES / name).read_text(encoding="utf-8").split("\nanswers:")[0] + "\n"


FOUR_BAR_PARALLELOGRAM = """\
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [1.3, 0.4]}
  D: {type: revolute, links: [rocker, frame], at: [1, 0]}
lengths: {AB: 0.5, BC: 1, CD: 0.5}
drive: {link: crank, angle: 60, omega: 10, direction: ccw}
"""

# A four-bar whose drawing puts B at 90 deg; format with ab (length AB) and angle (drive).
DRAWN_FOUR_BAR = """\
links: [frame, crank, coupler, rocker]
joints:
  A: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  B: {{type: revolute, links: [crank, coupler], at: [0, 1]}}
  C: {{type: revolute, links: [coupler, rocker], at: [2, 1]}}
  D: {{type: revolute, links: [rocker, frame], at: [2, 0]}}
lengths: {{AB: {ab}, BC: 2, CD: 1}}
drive: {{link: crank, angle: {angle}, omega: 1}}
"""

# Two gears about O1 = (0, 0) and O2 = (x2, 0); format with x2 and size (teeth/module or radii).
GEARS = """\
links: [frame, g1, g2]
joints:
  O1: {{type: revolute, links: [frame, g1], at: [0, 0]}}
  O2: {{type: revolute, links: [frame, g2], at: [{x2}, 0]}}
  M: {{type: gear, links: [g1, g2], {size}}}
drive: {{link: g1, rpm: 600}}
"""

# A compound gear train: the middle shaft carries two gears (40 and 15 teeth), each meshing with
# another; both meshes are points of the middle link (m on link 3, twice).  Module 2.5 mm:
# pitch radii 25/50 (centres 75 apart) and 18.75/51.25 (centres 70 apart).
COMPOUND_GEAR = """\
name: Compound gear train
units: {length: mm, angle: deg}
links: [frame, input, compound, output]
joints:
  O1: {type: revolute, links: [frame, input], at: [0, 0]}
  O2: {type: revolute, links: [frame, compound], at: [75, 0]}
  O3: {type: revolute, links: [frame, output], at: [75, 70]}
  M12: {type: gear, links: [input, compound], teeth: [20, 40], module: 2.5}
  M23: {type: gear, links: [compound, output], teeth: [15, 41], module: 2.5}
drive: {link: input, rpm: 1200, direction: cw}
"""

# AB = 1, BC = 2, CD = 1, AD = 2 at 180 deg: crank and coupler fold onto AD (a toggle).
TOGGLE_FOUR_BAR = """\
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [1, 1]}
  D: {type: revolute, links: [rocker, frame], at: [2, 0]}
lengths: {AB: 1, BC: 2, CD: 1}
drive: {link: crank, angle: 180, omega: 10}
"""

CRANK_ROCKER_LENGTHS = dict(a=1.0, b=3.0, c=2.5, d=3.0)  # Grashof, crank the shortest
CRANK_ROCKER = """\
name: crank rocker
links: [frame, crank, coupler, rocker]
joints:
  A: {type: revolute, links: [frame, crank], at: [0, 0]}
  B: {type: revolute, links: [crank, coupler]}
  C: {type: revolute, links: [coupler, rocker], near: [3, 2]}
  D: {type: revolute, links: [rocker, frame], at: [3, 0]}
lengths: {AB: 1, BC: 3, CD: 2.5}
drive: {link: crank, angle: 90, omega: 10, direction: ccw}
"""

# The Peaucellier–Lipkin inversor, drawn at 60° (tests/oracles/inversor.py derives P by hand): its
# rhombus folds flat at θ* = 2 acos(0.8), a change point of the dyad that places P.
FOLDING_INVERSOR = """
name: Peaucellier-Lipkin inversor
units: {length: m, angle: deg}
links: [frame, crank, l2, l3, l4, l5, l6, l7]
joints:
  O: {type: revolute, links: [frame, l2, l3], at: [0, 0]}
  Q: {type: revolute, links: [frame, crank], at: [1, 0]}
  C: {type: revolute, links: [crank, l4, l5]}
  A: {type: revolute, links: [l2, l4, l6], near: [1.5, 1.3]}
  B: {type: revolute, links: [l3, l5, l7], near: [1.5, -1.3]}
  P: {type: revolute, links: [l6, l7], near: [1.28, 0.5]}
lengths: {QC: 1, OA: 2, OB: 2, CA: 1.2, CB: 1.2, AP: 1.2, BP: 1.2}
drive: {link: crank, angle: 60, omega: 1}
"""


def ladder(dyads: int) -> str:
    """A crank and a chain of dyads, each hung from the last dyad's pin and a ground pivot."""
    joints = ["  O: {type: revolute, links: [frame, crank], at: [0, 0]}"]
    joints.append("  P0: {type: revolute, links: [crank, u1], at: [0.2, 0.9]}")
    for k in range(1, dyads + 1):
        carried = [f"u{k}", f"v{k}"] + ([f"u{k + 1}"] if k < dyads else [])
        joints.append(
            f"  P{k}: {{type: revolute, links: [{', '.join(carried)}], at: [{k + 0.2}, {0.9 + 0.05 * (k % 2)}]}}"
        )
        joints.append(f"  G{k}: {{type: revolute, links: [v{k}, frame], at: [{k + 1}, 0]}}")
    links = [
        "frame",
        "crank",
        *(f"u{k}" for k in range(1, dyads + 1)),
        *(f"v{k}" for k in range(1, dyads + 1)),
    ]
    return f"links: [{', '.join(links)}]\njoints:\n" + "\n".join(joints) + "\ndrive: {link: crank, rpm: 60}\n"


# A five-bar: Kutzbach 3·4 − 2·5 = 2 freedoms, one drive (line 10). Undrawn: only the drive places B.
FIVE_BAR_ONE_DRIVE = """\
units: {length: mm}
links: [frame, a, b, c, d]
joints:
  A: {type: revolute, links: [frame, a], at: [0, 0]}
  B: {type: revolute, links: [a, b]}
  C: {type: revolute, links: [b, c], near: [60, 80]}
  D: {type: revolute, links: [c, d]}
  E: {type: revolute, links: [d, frame], at: [120, 0]}
lengths: {AB: 40, BC: 70, CD: 70, DE: 40}
drive: {link: a, angle: 80, rpm: 60}
"""

#: Issue 21's roller cam of one's own: offset 10 mm, base circle 30, roller 10; rise 40 mm over
#: 120° (cycloidal), dwell 60°, return over 90° (SHM), dwell 90°; the cam turns clockwise, 300 rpm.
ROLLER_CAM = """\
units: {length: mm, angle: deg}
links: [frame, cam, follower]
joints:
  O: {type: revolute, links: [frame, cam], at: [0, 0]}
  K: {type: cam, links: [cam, follower],
      program: {base_radius: 30, follower: roller, roller_radius: 10, offset: 10,
                segments: [{rise: 40, over: 120, law: cycloidal}, {dwell: 60},
                           {return: 40, over: 90, law: shm}, {dwell: 90}]}}
  S: {type: prismatic, links: [follower, frame], path: {through: [-10, 0], angle: 90}}
drive: {link: cam, angle: 60, rpm: 300, direction: cw}
"""
#: The same cam, its follower's point on the slide named: the roller's centre K.
ROLLER_CAM_POINT_K = ROLLER_CAM.replace("angle: 90}}\n", "angle: 90}, point: K}\n")
assert ROLLER_CAM_POINT_K != ROLLER_CAM

KINEMATIC = ("position", "velocity", "acceleration", "icentres")


def lift(angle: float = 30) -> str:
    """A crank O–A (100 mm, 3 kg at its middle G) and a rod A–B (250 mm) lifting a 20 kg platform B
    up the vertical through O, under gravity, the crank at ``angle`` degrees and no speed given."""
    return f"""\
units: {{length: mm, angle: deg}}
links: [frame, crank, rod, platform]
joints:
  O: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  A: {{type: revolute, links: [crank, rod]}}
  B: {{type: revolute, links: [rod, platform], near: [0, 300]}}
  S: {{type: prismatic, links: [platform, frame], path: {{through: [0, 0], angle: 90}}}}
lengths: {{OA: 100, AB: 250}}
points:
  G: {{link: crank, from: O, toward: A, distance: 50}}
masses:
  crank: {{mass: 3, centre: G}}
  platform: {{mass: 20, centre: B}}
gravity: [0, -9.81]
drive: {{link: crank, angle: {angle:g}}}
"""


def _drives(data: dict) -> list[dict]:
    drive = data.get("drive") or []
    return drive if isinstance(drive, list) else [drive]


def expected_refusal(text: str, command: str) -> str | None:
    """The words of the refusal ``command`` must give for this file, or None if it must answer.

    Read from the file's own content: counting (dof, classify) needs no geometry; positions
    need a path for every slider and a placed joint; velocities need a speed for every drive;
    accelerations need profile curvature, which a contact given only as a point and a normal
    (``at`` + ``normal``) does not have.  I-centres of a file that places nothing are listed
    without coordinates.
    """
    if command not in KINEMATIC:
        return None
    data = yaml.safe_load(text)
    joints = list((data.get("joints") or {}).values())
    if command == "icentres" and not any("at" in j for j in joints):
        return None  # joints alone: the centres in Kennedy's order, without coordinates
    if any(j.get("type") == "prismatic" and "path" not in j for j in joints):
        return "has no path"  # a slider needs its line before anything can be placed
    if not any("at" in j for j in joints):
        return "positions need geometry"
    if command == "position":
        return None
    if any(not ({"rpm", "omega", "speed"} & set(d)) for d in _drives(data)):
        return "has no speed"
    if command == "acceleration" and any(j.get("type") == "cam" and "normal" in j for j in joints):
        return "curvature"
    return None


def epicyclic(ring: str = "[planet, frame]", extra: str = "", pressure: str = "") -> str:
    """An epicyclic train in mm: sun 20, planet 30, the frame a fixed ring of 80, the sun and the
    arm on two pins at one axis (the origin), the planet's centre Q at (50, 0); the sun driven at
    1000 rpm ccw.  ``ring`` lists the ring mesh's links (either order: its radii follow), ``pressure``
    is appended to both meshes (``", pressure_angle: 20"``), ``extra`` to the file (loads …)."""
    radii = "[30, 80]" if ring.startswith("[planet") else "[80, 30]"
    return f"""\
units: {{length: mm, angle: deg}}
links: [frame, sun, arm, planet]
joints:
  O: {{type: revolute, links: [frame, sun], at: [0, 0]}}
  O2: {{type: revolute, links: [frame, arm], at: [0, 0]}}
  Q: {{type: revolute, links: [arm, planet], at: [50, 0]}}
  m1: {{type: gear, links: [sun, planet], radii: [20, 30]{pressure}}}
  m2: {{type: gear, links: {ring}, radii: {radii}, internal: true{pressure}}}
drive: {{link: sun, rpm: 1000, direction: ccw}}
{extra}"""


def rack_and_pinion(
    pitch: str = "radii: [50, null]",
    *,
    pressure: str = ", pressure_angle: 20",
    loads: str = "R: {force: [-1000, 0]}",
    extra: str = "",
) -> str:
    """A pinion of pitch radius 50 mm turning on the origin at 60 rpm ccw, its rack sliding along
    y = −50 mm (its point R at (0, −50)); ``pitch`` and ``pressure`` are the mesh's fields (line 6
    of the file), ``loads`` its one load (none when empty), ``extra`` appended (answers …)."""
    load = f"loads:\n  {loads}\n" if loads else ""
    return f"""\
units: {{length: mm, angle: deg}}
links: [frame, pinion, rack]
joints:
  O: {{type: revolute, links: [frame, pinion], at: [0, 0]}}
  S: {{type: prismatic, links: [rack, frame], path: {{through: [0, -50], angle: 0}}, point: R}}
  mesh: {{type: gear, links: [pinion, rack], {pitch}{pressure}}}
points:
  R: {{link: rack, at: [0, -50]}}
{load}drive: {{link: pinion, rpm: 60, direction: ccw}}
{extra}"""


#: An in-line slider crank (crank 0.1 m, rod 0.3 m) driven by its piston at 2 m/s from x = 0.3 m,
#: a torque of 15 N·m held on the crank.
SLIDER_DRIVEN = """\
units: {length: m, angle: deg}
links: [frame, crank, rod, piston]
joints:
  O: {type: revolute, links: [frame, crank], at: [0, 0]}
  A: {type: revolute, links: [crank, rod], near: [0.02, 0.1]}
  B: {type: revolute, links: [rod, piston], at: [0.3, 0]}
  P: {type: prismatic, links: [piston, frame], path: {through: [0, 0], angle: 0}}
lengths: {OA: 0.1, AB: 0.3}
drive: {joint: P, speed: 2}
loads: {crank: {torque: 15}}
"""
