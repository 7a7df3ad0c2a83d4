"""Where a cam with a programme sits in a mechanism: where the cam turns and where its follower is.

The programme says how the follower moves; the mechanism's other joints say
where it is:

* the cam turns about its revolute joint on the ground (placed with ``at``);
* a translating follower slides on a prismatic joint whose ``path`` is its line
  (it rises along the path's direction: ``angle``, or ``through`` → ``toward``),
  and the path's distance from the cam's centre is the offset (a programme's
  ``offset``, when given, must agree with it);
* an oscillating follower turns about its revolute joint on the ground; its arm
  runs from that pivot to the cam joint (the knife edge or the roller's centre),
  of the length ``lengths`` gives (or as drawn, when the cam joint has ``at``).
  The cam joint's ``near`` (or ``at``) picks which of the two places where the
  arm can meet the base circle; without it, the one to the left of the line from
  the pivot to the cam's centre;
* the cam's drive gives its sense (counter-clockwise unless it says cw), its
  speed, and its ``angle``: the rotation from the programme's start.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from mech._records import dataclass
from mech.cam.profile import CamLayout, evaluate, layout_problem
from mech.cam.program import CamProgram, resolve
from mech.errors import InputError, UnsupportedError, Where
from mech.model import Joint, Mechanism, Ref
from mech.pairs.table import kind_of

if TYPE_CHECKING:
    from mech.specs import Profile

__all__ = [
    "CamSetup",
    "cam_joints",
    "cam_setup",
    "follower_motion_kind",
    "follower_slide",
    "joint_program",
    "program_profiles",
]

Vec = tuple[float, float]


@dataclass(frozen=True, slots=True)
class CamSetup:
    """A cam joint with a programme, placed: ``layout`` relative to the cam's ``centre``.

    ``angle``: the cam's rotation from the programme's start at the drawn instant
    (rad, in its sense); ``omega``: its speed (rad/s, magnitude) or ``None``.
    """

    joint: Joint
    cam: str
    follower: str
    centre: Vec
    layout: CamLayout
    angle: float
    omega: float | None


def joint_program(joint: Joint) -> CamProgram | None:
    """A cam joint's programme as the file gives it (``None`` for any other joint)."""
    program = getattr(joint.spec, "program", None)
    return program if isinstance(program, CamProgram) else None


def cam_joints(mechanism: Mechanism) -> tuple[Joint, ...]:
    """The cam joints that carry a programme, in file order."""
    return tuple(j for j in mechanism.joints if joint_program(j) is not None)


def follower_motion_kind(mechanism: Mechanism, follower: str) -> str | None:
    """``translating`` when the follower slides on the ground, ``oscillating`` when it turns
    about a pivot on the ground, ``None`` when neither (or both)."""
    ground = mechanism.ground
    slides = [
        j
        for j in mechanism.joints
        if kind_of(j).keeps_angle and j.links[:1] == (follower,) and ground in j.links
    ]
    turns = [
        j for j in mechanism.joints if kind_of(j).role == "pin" and follower in j.links and ground in j.links
    ]
    if len(slides) + len(turns) != 1:
        return None
    return "translating" if slides else "oscillating"


def _fail(joint: Joint, message: str, hint: str | None = None) -> InputError:
    return InputError(message, where=joint.where, hint=hint)


def _coords(mechanism: Mechanism, ref: Ref, joint: Joint) -> Vec:
    if ref.xy is not None:
        return ref.xy
    name = ref.name or ""
    for j in mechanism.joints:
        if j.name == name and j.place.at is not None:
            return j.place.at
    for p in mechanism.points:
        if p.name == name and p.place.at is not None:
            return p.place.at
    raise _fail(
        joint, f"the follower's path goes through {name!r}, which is not placed", "give it `at: [x, y]`"
    )


def cam_setup(
    mechanism: Mechanism, joint: str | None = None, *, omega: float | None = None, sense: int | None = None
) -> CamSetup:
    """Place the cam with a programme (``joint`` names it when there are several).

    ``omega`` (rad/s, magnitude) and ``sense`` (+1 ccw, −1 cw) override the drive.
    The steps: the cam joint (:func:`_pick_cam`), the follower's motion and the
    programme resolved for it, the cam's pivot, the drive's angle and sense
    (:func:`_drive_of`), the follower's layout (:func:`_translating` or
    :func:`_oscillating`), then the layout and the drawing checked
    (:func:`_check_drawn`).

    Raises :class:`~mech.errors.InputError` (located at the cam joint) when the
    layout cannot be read or is impossible, :class:`~mech.errors.UnsupportedError`
    when the file has no cam with a programme.
    """
    cj = _pick_cam(mechanism, joint)
    raw = joint_program(cj)
    assert raw is not None
    cam, follower = cj.links[0], cj.links[1]
    ground = mechanism.ground
    motion = follower_motion_kind(mechanism, follower)
    if motion is None:
        raise _fail(
            cj,
            f"the follower {follower} of {cj.name} must either slide on one prismatic joint "
            f"with {ground} or turn about one revolute joint on {ground}",
            "a programme moves the second link of `links: [cam, follower]`: give it a prismatic "
            "joint (translating) or a pivot (oscillating) on the ground",
        )
    if motion == "oscillating" and raw.follower != "flat" and raw.offset is not None:
        raise _fail(
            cj,
            "`offset` belongs to a translating follower (or an oscillating flat face)",
            "an oscillating follower's place is its pivot and its arm's length",
        )
    program = resolve(raw, motion)
    pivots = [
        j for j in mechanism.joints if kind_of(j).role == "pin" and cam in j.links and ground in j.links
    ]
    if len(pivots) != 1 or pivots[0].place.at is None:
        raise _fail(
            cj,
            f"the cam {cam} must turn about one revolute joint on {ground} placed with `at`",
            f"e.g. O: {{type: revolute, links: [{ground}, {cam}], at: [0, 0]}}",
        )
    centre = pivots[0].place.at
    angle, drive_sense, drive_omega = _drive_of(mechanism, cam)
    sense = drive_sense if sense is None else sense
    omega = drive_omega if omega is None else omega
    if program.motion == "translating":
        layout = _translating(mechanism, cj, program, centre, sense)
    else:
        layout = _oscillating(mechanism, cj, program, centre, sense, angle)
    problem = layout_problem(layout)
    if problem:
        raise _fail(cj, problem)
    _check_drawn(cj, program, layout, centre, angle)
    return CamSetup(cj, cam, follower, centre, layout, angle, omega)


def _pick_cam(mechanism: Mechanism, joint: str | None) -> Joint:
    """The cam joint with a programme: the only one, or the one ``joint`` names."""
    cams = cam_joints(mechanism)
    if not cams:
        raise UnsupportedError(
            "this mechanism has no cam joint with a `program`",
            where=Where(mechanism.path),
            hint="give a cam joint `program: {base_radius, follower, segments}` (cli.md § mech cam)",
        )
    if joint is None:
        if len(cams) > 1:
            raise UnsupportedError(
                f"this mechanism has {len(cams)} cams with a programme ({', '.join(j.name for j in cams)})",
                where=Where(mechanism.path),
                hint="name one with --joint",
            )
        return cams[0]
    named = [j for j in cams if j.name == joint]
    if not named:
        raise UnsupportedError(
            f"no cam joint {joint!r} with a programme",
            where=Where(mechanism.path),
            hint="cams: " + ", ".join(j.name for j in cams),
        )
    return named[0]


def _drive_of(mechanism: Mechanism, cam: str) -> tuple[float, int, float | None]:
    """The cam's turn from the programme's start (rad, in its sense), its sense (+1 ccw, −1 cw)
    and its speed (rad/s, magnitude; None without one), from the drive that turns it."""
    drive = next((d for d in mechanism.drives if d.link == cam), None)
    # the model keeps the cam's turn counter-clockwise; the programme counts it in the drive's sense
    drawn_cw = drive is not None and drive.direction == "cw"
    angle = drive.angle if drive is not None and drive.angle is not None else 0.0
    angle = -angle if drawn_cw else angle
    if drive is not None and drive.omega is not None:
        sense = -1 if drive.omega < 0 else 1
    else:
        sense = -1 if drive is not None and drive.direction == "cw" else 1
    omega = abs(drive.omega) if drive is not None and drive.omega is not None else None
    return angle, sense, omega


def follower_slide(mechanism: Mechanism, follower: str) -> Joint:
    """The prismatic joint a translating follower slides on, on the ground (cam_setup checked it is one)."""
    ground = mechanism.ground
    return next(
        j for j in mechanism.joints if kind_of(j).keeps_angle and j.links[0] == follower and ground in j.links
    )


def _translating(mechanism: Mechanism, cj: Joint, program: CamProgram, centre: Vec, sense: int) -> CamLayout:
    """A translating follower on its prismatic joint's path: its axis and signed offset."""
    slide = follower_slide(mechanism, cj.links[1])
    if slide.path is None:
        raise _fail(slide, f"the follower's prismatic joint {slide.name} needs a `path`: its line")
    through = _coords(mechanism, slide.path.through, slide)
    if slide.path.angle is not None:
        axis = slide.path.angle
    else:
        assert slide.path.toward is not None
        to = _coords(mechanism, slide.path.toward, slide)
        if math.dist(to, through) == 0:
            raise _fail(slide, f"the path of {slide.name} goes toward its own `through` point")
        axis = math.atan2(to[1] - through[1], to[0] - through[0])
    # signed offset: positive on the side where the cam's surface moves the way the follower rises
    nx, ny = -math.sin(axis), math.cos(axis)
    e_n = (through[0] - centre[0]) * nx + (through[1] - centre[1]) * ny
    offset = -sense * e_n
    size = program.base_radius + program.stroke + abs(offset)
    if program.offset is not None and abs(program.offset - offset) > 1e-6 * size:
        raise _fail(
            cj,
            f"the programme's offset {program.offset:.6g} m disagrees with the path of {slide.name}, "
            f"which puts the follower's line {offset:.6g} m from the cam's centre "
            "(positive on the side where the cam's surface moves the way the follower rises)",
            "move the path, or leave `offset` out and let the path decide",
        )
    return CamLayout(program, sense=sense, axis=axis, offset=offset)


def _oscillating(
    mechanism: Mechanism, cj: Joint, program: CamProgram, centre: Vec, sense: int, angle: float
) -> CamLayout:
    """An oscillating follower about its ground pivot: its arm, and the branch the drawing picks."""
    ground = mechanism.ground
    follower = cj.links[1]
    turn = next(
        j for j in mechanism.joints if kind_of(j).role == "pin" and follower in j.links and ground in j.links
    )
    if turn.place.at is None:
        raise _fail(turn, f"the follower's pivot {turn.name} must be placed with `at`")
    pivot = (turn.place.at[0] - centre[0], turn.place.at[1] - centre[1])
    arm = program.offset or 0.0 if program.follower == "flat" else _arm(mechanism, cj, turn)
    layout = CamLayout(program, sense=sense, pivot=pivot, arm=arm, branch=1)
    hint = cj.place.at or cj.place.near
    if hint is not None and program.follower != "flat" and layout_problem(layout) is None:
        target = (hint[0] - centre[0], hint[1] - centre[1])

        def miss(branch: int) -> float:
            st = evaluate(CamLayout(program, sense=sense, pivot=pivot, arm=arm, branch=branch), [angle])
            return math.dist(tuple(st.point[0]), target)

        if miss(-1) < miss(1):
            layout = CamLayout(program, sense=sense, pivot=pivot, arm=arm, branch=-1)
    return layout


def _check_drawn(cj: Joint, program: CamProgram, layout: CamLayout, centre: Vec, angle: float) -> None:
    """A cam joint drawn with ``at`` must be where the programme puts the follower's point."""
    if cj.place.at is None or program.follower == "flat":
        return
    at = evaluate(layout, [angle]).point[0]
    drawn = (cj.place.at[0] - centre[0], cj.place.at[1] - centre[1])
    gap = math.dist(tuple(at), drawn)
    size = program.base_radius + layout.roller + (program.stroke if not layout.oscillating else 0.0)
    if gap > 1e-4 * size:
        raise _fail(
            cj,
            f"{cj.name} is drawn {gap:.6g} m from where the programme puts the follower's point "
            f"at a cam angle of {math.degrees(angle):.6g}° ({at[0] + centre[0]:.6g}, {at[1] + centre[1]:.6g}) m",
            "leave `at` out (mech places it), or draw it there",
        )


def program_profiles(
    mechanism: Mechanism, joint: Joint, positions: dict[str, tuple[float, float]] | None = None
) -> dict[str, Profile]:
    """The profiles a cam's programme gives, in the drawn configuration, keyed by link.

    The cam gets the generated surface as a closed :class:`~mech.specs.Curve`
    (720 points, the cam turned by its drive angle); the follower a
    :class:`~mech.specs.Knife` at its edge, a :class:`~mech.specs.Circle`
    (the roller) or a :class:`~mech.specs.Line` (the flat face), placed
    where the programme puts it at that angle.  ``positions`` is not needed:
    the programme and the layout place everything.
    """
    import math as _math

    import numpy as np

    from mech.specs import Circle, Curve, Knife, Line

    del positions
    setup = cam_setup(mechanism, joint.name)
    lay = setup.layout
    theta = np.linspace(0.0, 2 * _math.pi, 720, endpoint=False)
    st = evaluate(lay, theta)
    c, s = _math.cos(lay.sense * setup.angle), _math.sin(lay.sense * setup.angle)
    ox, oy = setup.centre
    curve = tuple((float(c * x - s * y + ox), float(s * x + c * y + oy)) for x, y in st.profile)
    now = evaluate(lay, [setup.angle])
    point = (float(now.point[0][0] + ox), float(now.point[0][1] + oy))
    kind = lay.program.follower
    follower: Profile
    if kind == "knife":
        follower = Knife(Ref(xy=point))
    elif kind == "roller":
        follower = Circle(Ref(xy=point), lay.roller)
    else:
        contact = (float(now.contact[0][0] + ox), float(now.contact[0][1] + oy))
        if lay.oscillating:
            assert lay.pivot is not None
            pivot = (lay.pivot[0] + ox, lay.pivot[1] + oy)
            direction = _math.atan2(contact[1] - pivot[1], contact[0] - pivot[0])
            follower = Line(Ref(xy=contact), angle=direction)
        else:
            follower = Line(Ref(xy=contact), angle=lay.axis + _math.pi / 2)
    return {setup.cam: Curve(curve), setup.follower: follower}


def _arm(mechanism: Mechanism, cj: Joint, turn: Joint) -> float:
    """The oscillating arm: pivot to the cam joint, from ``lengths`` or as drawn."""
    for length in mechanism.lengths:
        if {length.a, length.b} == {cj.name, turn.name}:
            return length.value
    if cj.place.at is not None and turn.place.at is not None:
        return math.dist(cj.place.at, turn.place.at)
    raise _fail(
        cj,
        f"the oscillating follower's arm from {turn.name} to {cj.name} has no length",
        f"add `lengths: {{{turn.name}{cj.name}: …}}` (pivot to the knife edge or roller centre)",
    )
