"""The analysis pipeline: one request in, one typed result out.

Every command, ``mech check`` and the drawings go through here::

    from mech.analysis import Request, analyse
    result = analyse("four_bar.yaml", Request(level="velocity", icentres=True))
    result.kinematics.links["rocker"].omega, result.icentres.centres

A :class:`Request` says what is asked (the counts, how far to solve, the drive's
overrides, I-centres, properties, a sweep, traced curves); :func:`analyse` loads the file
(or takes a :class:`~mech.model.Mechanism`), then runs only the steps the
request needs, each a public function of its own room (:func:`mech.topology.classify`,
:func:`mech.kinematics.solve`, :func:`mech.icentres.locate`,
:func:`mech.properties.summary.linkage_properties`, :func:`mech.kinematics.sweep`),
and returns a frozen :class:`Result` with the pieces asked and None for the others.

The steps are also public (:func:`solve_at`, :func:`locate_icentres`, …) for
callers that compute lazily, one piece on first use (:class:`mech.check.Analysis`).

Why one place: "load → solve at a level → locate I-centres → render" was written
again in each command, in the drawing and in the checker, each deciding the
level (is there a drive speed?) its own way.  Nothing here imports numpy, rich
or click at import time: the analyses are imported inside the steps that use
them, so ``mech dof`` stays light.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from mech._records import dataclass
from mech.errors import InputError, MechError
from mech.model import Mechanism
from mech.options import SolveOptions

if TYPE_CHECKING:  # pragma: no cover
    from mech.icentres import ICentres
    from mech.kinematics import Kinematics, Mobility, Sweep
    from mech.properties.summary import LinkageProperties
    from mech.topology import Topology

__all__ = [
    "LEVELS",
    "Curve",
    "Request",
    "Result",
    "SweepSpec",
    "analyse",
    "drawing_level",
    "drawn_positions",
    "has_speed",
    "load_mechanism",
    "locate_icentres",
    "needs_drives",
    "solve_at",
    "sweep_level",
    "trace_curves",
]

#: How far a solve goes, in order: each level includes the ones before it.
LEVELS = ("position", "velocity", "acceleration")

#: A traced locus: ``(label, points (m), kind)``, kind ``path``, ``fixed centrode`` or ``moving centrode``.
Curve = tuple[str, list[tuple[float, float]], str]


@dataclass(frozen=True, slots=True)
class SweepSpec:
    """A sweep over the drive's angle: ``steps + 1`` angles from ``start`` to ``stop`` (degrees).

    ``level`` None: velocity when a drive speed is known (options or file), else position.
    ``drive`` names the drive whose coordinate is swept (a mechanism with a slider drive or
    several drives; default the first): for a slider, ``start`` and ``stop`` are positions along
    its path in the file's length unit (no default: a stroke must be given); for a crank, angles
    in degrees (default 0 and 360).
    """

    start: float | None = 0.0
    stop: float | None = 360.0
    steps: int = 360
    level: str | None = None
    quantities: tuple[str, ...] = ()
    method: str = "auto"
    drive: str | None = None

    def __post_init__(self) -> None:
        if self.level is not None and self.level not in LEVELS:
            raise ValueError(f"level must be one of {', '.join(LEVELS)}, not {self.level!r}")


@dataclass(frozen=True, slots=True)
class Request:
    """What a command (or an answer sheet) asks of one mechanism, folded once.

    ``topology`` asks for the counts and classes (``mech dof``, ``classify``) and
    ``mobility`` for the Jacobian's rank.  ``level`` is how far to solve at the
    drive's instant: ``position``, ``velocity`` or ``acceleration``, or None for
    no instant solve.  ``options`` carries the drive's overrides (angle, rpm as ω,
    direction, α, Newton's tolerance).  The rest are asked for only when wanted:
    I-centres, the linkage's properties (with ``outputs`` for mechanical
    advantage), a sweep, the curves traced on a drawing (``paths``,
    ``centrodes``) and ``drawn``, the positions at the file's own instant with
    the speed overrides left out (what a sweep's drawings are drawn over).
    """

    level: str | None = "velocity"
    options: SolveOptions = SolveOptions()
    topology: bool = False
    mobility: bool = False
    icentres: bool = False
    properties: bool = False
    outputs: tuple[str, ...] = ()
    sweep: SweepSpec | None = None
    paths: tuple[str, ...] = ()
    centrodes: tuple[str, ...] = ()
    drawn: bool = False

    def __post_init__(self) -> None:
        if self.level is not None and self.level not in LEVELS:
            raise ValueError(f"level must be one of {', '.join(LEVELS)}, not {self.level!r}")

    @property
    def speed_given(self) -> bool:
        """True when the options set the drive's speed (--rpm, --omega or --speed)."""
        return self.options.omega is not None or self.options.speed is not None


@dataclass(frozen=True, slots=True)
class Result:
    """What :func:`analyse` found: the pieces the request asked for, None for the others."""

    mechanism: Mechanism
    request: Request
    kinematics: Kinematics | None = None
    topology: Topology | None = None
    mobility: Mobility | None = None
    #: Why the numeric mobility could not be had (``mech dof --mobility`` reports it, not fails).
    mobility_error: MechError | None = None
    icentres: ICentres | None = None
    properties: LinkageProperties | None = None
    sweep: Sweep | None = None
    curves: tuple[Curve, ...] = ()
    drawn: Kinematics | None = None

    @property
    def file(self) -> str:
        """The file the mechanism was read from (``<stdin>`` for standard input)."""
        return self.mechanism.path


# -- the steps ---------------------------------------------------------------------------------
def has_speed(mech: Mechanism, options: SolveOptions) -> bool:
    """True when the options or every one of the file's drives give a speed (velocities can be had)."""
    if options.omega is not None or options.speed is not None:
        return True
    return bool(mech.drives) and all(d.omega is not None or d.speed is not None for d in mech.drives)


def sweep_level(mech: Mechanism, options: SolveOptions) -> str:
    """A sweep's default level: velocity when any speed is known, else position."""
    if options.omega is not None or options.speed is not None:
        return "velocity"
    return "velocity" if any(d.omega is not None or d.speed is not None for d in mech.drives) else "position"


def drawing_level(
    mech: Mechanism, options: SolveOptions, *, velocity: bool, acceleration: bool, icentres: bool
) -> str:
    """How far a drawing solves: what its polygons need; velocity for I-centres when a speed is known.

    The velocities let the drawn I-centres be cross-checked with the velocity field.
    """
    level = "acceleration" if acceleration else "velocity" if velocity else "position"
    if icentres and level == "position" and has_speed(mech, options):
        level = "velocity"
    return level


def needs_drives(mech: Mechanism, request: Request) -> bool:
    """True when what ``request`` asks cannot be had without one drive per degree of freedom.

    A sweep, a traced path or centrode, velocities and accelerations, any solve at another
    angle (``--angle``) move or differentiate the drives: they need them all.  Positions at
    the file's instant (``position``, ``draw``, the properties' Grashof loops) need them only
    where the drawing does not fix the configuration: a file that draws no moving joint or
    point with ``at`` leaves every freedom no drive holds free, so it is refused at once
    (:func:`mech.kinematics.solve.refuse_underdriven`, from Kutzbach's count, located at the
    drive) instead of after an assembly and a rank that take minutes on a long chain.  A drawn
    file is placed as drawn (its properties report what needs no drive, Grashof's loops, and
    say why the rest cannot be had); a file with no drive at all is left to the solve, which
    names the joints it leaves free.
    """
    if request.sweep is not None or request.paths or request.centrodes:
        return True
    if request.level is None and not request.properties:
        return False
    if request.level in ("velocity", "acceleration") or request.options.angle is not None:
        return True
    # without any drive, the solve's own message is better: it names (and locates) the joints left free
    return bool(mech.drives) and not _draws_a_moving_location(mech)


def _draws_a_moving_location(mech: Mechanism) -> bool:
    """True when a joint or point off the ground link is drawn with ``at`` (it pins what it is on)."""
    if any(j.place.at is not None and mech.ground not in j.links for j in mech.joints):
        return True
    return any(p.place.at is not None and p.link != mech.ground for p in mech.points)


def solve_at(mech: Mechanism, level: str, options: SolveOptions) -> Kinematics:
    """The mechanism solved at the drive's instant up to ``level`` (:func:`mech.kinematics.solve`)."""
    from mech.kinematics import solve

    return solve(mech, level=level, options=options)


def locate_icentres(mech: Mechanism, kin: Kinematics | None) -> ICentres:
    """All n(n − 1)/2 I-centres, checked against ``kin``'s velocity field when it has one."""
    from mech.icentres import locate

    return locate(mech, kin)


def trace_curves(
    mech: Mechanism, options: SolveOptions, *, paths: Sequence[str] = (), centrodes: Sequence[str] = ()
) -> tuple[Curve, ...]:
    """Point paths and fixed and moving centrodes over a turn of the crank (:mod:`mech.properties.paths`)."""
    if not (paths or centrodes):
        return ()
    from mech.properties.paths import centrodes as find_centrodes
    from mech.properties.paths import point_path

    sweep_options = options.with_(angle=None)
    out: list[Curve] = []
    for name in paths:
        path = point_path(mech, name, options=sweep_options)
        out.append((f"path of {name}", [(float(x), float(y)) for x, y in path.xy], "path"))
    for link in centrodes:
        c = find_centrodes(mech, link, options=options)
        out.append(
            (f"fixed centrode of {link}", [(float(x), float(y)) for x, y in c.fixed], "fixed centrode")
        )
        out.append(
            (f"moving centrode of {link}", [(float(x), float(y)) for x, y in c.moving_now], "moving centrode")
        )
    return tuple(out)


def drawn_positions(mech: Mechanism, options: SolveOptions) -> Kinematics:
    """Positions at the file's own drive angle, the speed and angle overrides left out."""
    return solve_at(mech, "position", options.with_(omega=None, direction=None, alpha=None, angle=None))


def _sweep(mech: Mechanism, spec: SweepSpec, level: str, options: SolveOptions) -> Sweep:
    """The sweep of ``spec``; running out of memory is bad input (exit 2), never a traceback."""

    from mech.kinematics import sweep

    # the sweep refuses up front when its arrays would exceed its budget (MEMORY_BUDGET, 1 GiB); a
    # machine with less memory than that can still run out: say so
    try:
        return sweep(
            mech,
            _sweep_values(mech, spec),
            level=level,
            options=options.with_(method=spec.method),
            quantities=spec.quantities or None,
            drive=_lead(mech, spec),
        )
    except MemoryError:
        raise out_of_memory(mech, spec) from None


def _lead(mech: Mechanism, spec: SweepSpec) -> str | None:
    """The drive a sweep's values belong to: ``spec.drive``, else the first of a slider or several drives."""
    if spec.drive is not None or not mech.drives or (len(mech.drives) == 1 and mech.drives[0].link):
        return spec.drive
    return mech.drives[0].link or mech.drives[0].joint


def _sweep_values(mech: Mechanism, spec: SweepSpec) -> Any:
    """The sweep's parameter values (SI): a crank's angles (rad), or a slider's positions (m), or None.

    None (a slider drive without ``start``/``stop``) lets the sweep say a stroke is needed.
    """
    import numpy as np

    from mech.units import unit_factor

    names = [d.link or d.joint for d in mech.drives]
    lead = mech.drives[names.index(spec.drive)] if spec.drive in names else (mech.drives or [None])[0]
    if lead is not None and lead.link is None:  # a slider leads: positions in the file's length unit
        if spec.start is None or spec.stop is None:
            return None
        if spec.start == spec.stop:
            raise InputError("--from and --to must be two different positions along the slider's path")
        factor = unit_factor(mech.length_unit)[1]
        return np.linspace(spec.start * factor, spec.stop * factor, spec.steps + 1)
    start = 0.0 if spec.start is None else spec.start
    stop = 360.0 if spec.stop is None else spec.stop
    if start == stop:
        raise InputError(
            "--from and --to must be two different finite values (degrees, or a slider's positions)"
        )
    return np.radians(np.linspace(start, stop, spec.steps + 1))


def out_of_memory(mech: Mechanism, spec: SweepSpec) -> InputError:
    """The message for a sweep (or its reports) that ran out of memory."""
    return InputError(
        f"out of memory sweeping {spec.steps + 1:,} angles of {mech.label}",
        hint="give fewer --steps, or sweep the range in parts",
    )


# -- the pipeline ------------------------------------------------------------------------------
def analyse(source: str | Mechanism, request: Request | None = None) -> Result:
    """Load ``source`` (a path, ``-`` for standard input, or a loaded mechanism) and analyse it.

    Only what ``request`` asks is computed: no solve when ``level`` is None;
    the counts, I-centres, properties, a sweep and curves only when asked.

    Raises
    ------
    MechError
        Whatever the loader or the analyses raise (bad input, no assembly …).

    Examples
    --------
    >>> r = analyse("mechanisms/four_bar.yaml", Request(level="velocity"))   # doctest: +SKIP
    >>> r.kinematics.links["rocker"].omega                                   # doctest: +SKIP
    """
    request = request or Request()
    mech = source if isinstance(source, Mechanism) else load_mechanism(source)
    options = request.options
    if needs_drives(mech, request):
        from mech.kinematics.solve import refuse_underdriven

        refuse_underdriven(mech)  # one drive per freedom, from the count: before any assembly or sweep
    topology = _classify(mech) if request.topology else None
    mobility, mobility_error = _mobility(mech) if request.mobility else (None, None)
    kin = solve_at(mech, request.level, options) if request.level is not None else None
    sweep = None
    if request.sweep is not None:
        level = request.sweep.level or sweep_level(mech, options)
        sweep = _sweep(mech, request.sweep, level, options)
    icentres = locate_icentres(mech, kin) if request.icentres else None
    properties = None
    if request.properties:
        from mech.properties.summary import linkage_properties

        properties = linkage_properties(mech, options=options, outputs=request.outputs)
    curves = trace_curves(mech, options, paths=request.paths, centrodes=request.centrodes)
    drawn = drawn_positions(mech, options) if request.drawn else None
    return Result(
        mech,
        request,
        kinematics=kin,
        topology=topology,
        mobility=mobility,
        mobility_error=mobility_error,
        icentres=icentres,
        properties=properties,
        sweep=sweep,
        curves=curves,
        drawn=drawn,
    )


def load_mechanism(path: str) -> Mechanism:
    """The mechanism in the file at ``path`` (``-``: standard input), validated (:func:`mech.loader.load`)."""
    from mech.loader import load

    return load(path)


def _classify(mech: Mechanism) -> Topology:
    from mech.topology import classify

    return classify(mech)


def _mobility(mech: Mechanism) -> tuple[Mobility | None, MechError | None]:
    """The numeric mobility, or the reason it cannot be had (no geometry, no assembly)."""
    from mech.kinematics import mobility

    try:
        return mobility(mech), None
    except MechError as error:
        return None, error
