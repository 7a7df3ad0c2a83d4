"""The ``mech`` command line: parse options, call the library, hand results to a renderer.

This module imports click and nothing heavy: numpy and rich are imported inside
the commands that need them, so ``mech dof`` over a folder starts fast.
Exit status: 0 success, 1 a failed check, 2 bad input or usage, 70 a bug, 130 interrupted,
141 the reader closed the pipe (cli.md, "Exit status").
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Iterable, Sequence
from functools import wraps
from typing import TYPE_CHECKING, Any

import click

from mech import __version__
from mech.commands import DEFAULT_FILE, Request, classify_files, count_dof, handles_errors
from mech.commands import kinematics as _kinematics
from mech.commands import solve_options as _solve_options
from mech.errors import InputError
from mech.options import OutputUnits

if TYPE_CHECKING:  # pragma: no cover
    from mech.analysis import Result

file_argument = click.argument("file", default=DEFAULT_FILE, type=click.Path(dir_okay=False, allow_dash=True))
json_option = click.option(
    "--json", "as_json", is_flag=True, help="Print JSON (structure in cli.md) instead of tables."
)


class _PastClick(Exception):
    """A closed pipe or an interrupt, carried past click's main (see :func:`run_click`)."""

    def __init__(self, original: BaseException) -> None:
        super().__init__(original)
        self.original = original


class _Group(click.Group):
    def invoke(self, ctx: click.Context) -> Any:
        try:
            return super().invoke(ctx)
        except (BrokenPipeError, KeyboardInterrupt) as exc:
            raise _PastClick(exc) from None


@click.group(cls=_Group, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, "-V", "--version", prog_name="mech", message="%(prog)s %(version)s")
@click.option(
    "--debug",
    is_flag=True,
    expose_value=False,
    is_eager=True,
    callback=lambda ctx, param, value: _debug(value),
    help="Show the traceback of a bug in mech (as MECH_DEBUG=1 does).",
)
def cli() -> None:
    """Analyse planar mechanisms described in YAML.

    \b
    mech dof mechanisms/four_bar.yaml           degrees of freedom, worked
    mech classify mechanisms/four_bar.yaml      links, joints and pairs
    mech velocity mechanisms/slider_crank.yaml --rpm 600
    mech check homework/                        verdicts on claimed answers

    FILE defaults to mechanism.yaml in this folder; - reads standard input.
    """


def _debug(on: bool) -> None:
    """``mech --debug …``: a bug's traceback is shown (read by :func:`mech.entry.guarded`)."""
    if on:
        import os

        os.environ["MECH_DEBUG"] = "1"


# -- counting -------------------------------------------------------------------------
@cli.command()
@click.argument("files", nargs=-1, type=click.Path(dir_okay=False, allow_dash=True))
@click.option(
    "--mobility",
    is_flag=True,
    help="Also compute the true mobility from the constraint Jacobian's rank (needs geometry).",
)
@json_option
def dof(files: Sequence[str], mobility: bool, as_json: bool) -> None:
    """Count degrees of freedom by Kutzbach and check Grübler's criterion.

    Shows l, j and h, the link and joint classes and the count worked out;
    several files give one table.  A bad file is reported on stderr and the
    others are still counted (exit status 2 at the end).
    """
    count_dof(files, mobility, as_json)


@cli.command(name="classify")
@file_argument
@json_option
def classify_command(file: str, as_json: bool) -> None:
    """Classify links (binary, ternary …), joints and kinematic pairs.

    Pairs are classified as the lecture notes do: by relative motion (turning,
    sliding, rolling, screw, spherical, cam or gear), by contact (lower or
    higher) and by closure (self-closed or force-closed).
    """
    classify_files(file=file, as_json=as_json)


@cli.command()
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True), help="Write to a file.")
@handles_errors
def schema(output: str | None) -> None:
    """Print the JSON Schema (draft-07) of the mechanism file format.

    Point your editor's YAML plugin at it for validation and completion.
    """
    from mech.render.jsonout import dumps
    from mech.schema import schema

    text = dumps(schema())
    if output:
        _write(output, text + "\n")
    else:
        click.echo(text)


# -- kinematics -----------------------------------------------------------------------
_KINEMATIC_OPTIONS = (
    file_argument,
    click.option("--rpm", type=float, help="Crank speed in rev/min (overrides the file)."),
    click.option("--omega", type=float, help="Crank speed in rad/s (overrides the file)."),
    click.option("--angle", type=float, help="Crank angle in degrees, counter-clockwise from +x."),
    click.option("--speed", type=float, help="A slider drive's speed in m/s, signed along its path."),
    click.option("--direction", type=click.Choice(["cw", "ccw"]), help="Sense of the crank's rotation."),
    click.option(
        "--tol",
        type=float,
        default=1e-12,
        show_default=True,
        help="Newton tolerance on the loop closure, relative to the mechanism's size.",
    ),
    click.option(
        "--units",
        "unit_system",
        type=click.Choice(["si", "mm", "cm"]),
        default="si",
        show_default=True,
        help="Print lengths and speeds in m, mm or cm (angles always in deg, rad/s).",
    ),
    json_option,
)

_ALPHA_OPTION = click.option(
    "--alpha", type=float, help="Crank angular acceleration in rad/s², counter-clockwise positive."
)


def kinematic_command(*, alpha: bool = False) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """The options shared by the commands that solve the mechanism, folded into a :class:`Request`.

    The command function receives ``request`` first and its own options by
    name; errors, in the options or anywhere below, are reported (exit 2).
    """

    def decorate(fn: Callable[..., Any]) -> Callable[..., Any]:
        @wraps(fn)
        @handles_errors
        def command(
            file: str,
            rpm: float | None,
            omega: float | None,
            angle: float | None,
            speed: float | None,
            direction: str | None,
            tol: float,
            unit_system: str,
            as_json: bool,
            alpha: float | None = None,
            **own: Any,
        ) -> Any:
            options = _solve_options(rpm, omega, angle, direction, tol, alpha, speed)
            return fn(Request(file, options, OutputUnits.named(unit_system), as_json), **own)

        for decorator in reversed((*_KINEMATIC_OPTIONS, *((_ALPHA_OPTION,) if alpha else ()))):
            command = decorator(command)
        return command

    return decorate


_EXPLAIN_OPTION = click.option(
    "--explain", is_flag=True, help="Write the construction out step by step, as the lecture notes draw it."
)


@cli.command()
@kinematic_command()
def position(request: Request) -> None:
    """Solve the positions of every joint and point at the crank angle."""
    _kinematics(request, "position")


@cli.command()
@_EXPLAIN_OPTION
@kinematic_command()
def velocity(request: Request, explain: bool) -> None:
    """Velocities of every point and link at the crank angle and speed.

    Absolute velocities of joints and points, angular velocities of links,
    relative velocities along links (the velocity polygon's ab, bc …), sliding
    velocities in slides and slots, and rubbing velocities at pins with a radius.
    """
    _kinematics(request, "velocity", explain)


@cli.command()
@_EXPLAIN_OPTION
@kinematic_command(alpha=True)
def acceleration(request: Request, explain: bool) -> None:
    """Accelerations (normal, tangential, Coriolis) of every point and link."""
    _kinematics(request, "acceleration", explain)


@cli.command(name="forces")
@click.option(
    "--explain", is_flag=True, help="Write each link's free body: its forces and ΣF = m a_G, ΣM_G = I_G α."
)
@kinematic_command(alpha=True)
def forces_command(request: Request, explain: bool) -> None:
    """Forces at the crank angle: what each pair carries, the input torque and its parts, the shaking.

    Without friction, from the masses, gravity and loads the file gives
    (d'Alembert's inertia forces when the drive has a speed).  The body is
    mech.render.forces.run.
    """
    from mech.render.forces import run

    run(request, explain=explain, echo=click.echo)


@cli.command()
@_EXPLAIN_OPTION
@click.option(
    "--circle",
    "circle_path",
    type=click.Path(dir_okay=False),
    help="Draw Kennedy's circle diagram to an .svg or .png file.",
)
@kinematic_command()
def icentres(request: Request, explain: bool, circle_path: str | None) -> None:
    """Locate all n(n−1)/2 instantaneous centres at the crank angle.

    Primary I-centres by inspection (pins, sliders, rolling contacts), the
    rest by the Aronhold-Kennedy theorem, each checked against the velocity
    solution; then every link's ω by the I-centre method beside the solver's.
    """
    from mech.analysis import Request as Asked
    from mech.analysis import analyse
    from mech.loader import load
    from mech.render.emit import choose, emit

    mechanism = load(request.file)
    if not mechanism.has_geometry and not explain and not circle_path:
        # nothing placed: the centres can still be counted, named and ordered (no coordinates)
        from mech.icentres.order import kennedy_order

        emit(
            "icentre-order",
            choose(request.as_json),
            kennedy_order(mechanism),
            echo=click.echo,
            file=request.file,
        )
        return
    result = analyse(mechanism, Asked(level="velocity", options=request.options, icentres=True))
    assert result.icentres is not None
    if circle_path:
        from mech.draw import save
        from mech.draw.kennedy import circle_diagram

        title = f"{result.mechanism.label}: Kennedy's circle diagram"
        save(circle_diagram(result.icentres, title=title), circle_path)
    emit(
        "icentres",
        choose(request.as_json),
        result,
        echo=click.echo,
        units=request.units,
        file=request.file,
        explain=explain,
    )


@cli.command(name="properties")
@click.option(
    "--output",
    "outputs",
    multiple=True,
    help="A link or point whose mechanical advantage to give (repeatable; default: every moving link).",
)
@kinematic_command()
def properties_command(request: Request, outputs: tuple[str, ...]) -> None:
    """Grashof, transmission angle, limit positions, strokes and time ratio of a linkage.

    Grashof's criterion for every four-bar loop (and the inversion of a
    slider-crank loop), the transmission angle at the crank angle and its
    least and greatest values over the cycle with the crank angles where they
    occur, the output's limit positions, every stroke and swing, and the
    quick-return time ratio.
    """
    from mech.analysis import Request as Asked
    from mech.analysis import analyse
    from mech.render.emit import choose, emit

    asked = Asked(level=None, options=request.options, properties=True, outputs=outputs)
    result = analyse(request.file, asked)
    emit(
        "properties", choose(request.as_json), result, echo=click.echo, units=request.units, file=request.file
    )


@cli.command(name="sweep")
@click.option(
    "--from",
    "start",
    type=float,
    default=None,
    help="First crank angle, degrees (default 0); a slider drive's first position, file's length unit.",
)
@click.option(
    "--to",
    "stop",
    type=float,
    default=None,
    help="Last crank angle, degrees (default 360); a slider drive's last position, file's length unit.",
)
@click.option(
    "--drive",
    "lead",
    default=None,
    help="With several drives: the drive (link or slider joint) whose angle or position is swept "
    "(default the first); the others move in proportion to their speeds.",
)
@click.option(
    "--steps",
    type=click.IntRange(min=1, max=10_000_000),
    default=360,
    show_default=True,
    help="Steps (angles − 1).",
)
@click.option(
    "--level",
    type=click.Choice(["position", "velocity", "acceleration", "forces"]),
    default=None,
    help="How far to solve (default: velocity with a drive speed, else position); forces: the "
    "turning-moment diagram, the fluctuation of energy and the flywheel, the greatest pair forces.",
)
@click.option(
    "--quantity",
    "quantities",
    multiple=True,
    help="A quantity to report (repeatable): omega.rocker, velocity.B, displacement.P … (default: all).",
)
@click.option(
    "--csv",
    "csv_path",
    type=click.Path(dir_okay=False, allow_dash=True),
    help="Write the series as CSV (- for standard output, instead of the report).",
)
@click.option(
    "--method",
    type=click.Choice(["auto", "closed", "newton"]),
    default="auto",
    show_default=True,
    help="Closed-form dyads where the chain decomposes (auto), only them, or Newton with --tol.",
)
@click.option(
    "--plot",
    "plot_path",
    type=click.Path(dir_okay=False),
    help="Plot the quantities to a PNG (needs matplotlib).",
)
@click.option(
    "--animate",
    "gif_path",
    type=click.Path(dir_okay=False),
    help="Animate the cycle to a GIF (needs matplotlib).",
)
@click.option(
    "--path",
    "paths",
    multiple=True,
    help="A point whose path to trace (repeatable): its x and y become quantities (CSV columns, extent).",
)
@click.option(
    "--svg", "svg_path", type=click.Path(dir_okay=False), help="Draw the --path curves alone to an SVG file."
)
@kinematic_command()
def sweep_command(
    request: Request,
    start: float | None,
    stop: float | None,
    steps: int,
    lead: str | None,
    level: str | None,
    quantities: tuple[str, ...],
    csv_path: str | None,
    method: str,
    plot_path: str | None,
    gif_path: str | None,
    paths: tuple[str, ...],
    svg_path: str | None,
) -> None:
    """Solve over a range of crank angles (or a slider's stroke): gaps, toggles, dead centres, extremes, time ratio.

    Each step continues the last one's assembly branch.  Extremes and dead
    centres are refined between steps, not read off the grid; for a
    quick-return mechanism the time ratio of the strokes is given.
    """
    if request.options.angle is not None:
        raise InputError("--angle does not apply to a sweep", hint="give the range with --from and --to")
    given = [x for x in (start, stop) if x is not None]
    if not all(math.isfinite(x) for x in given) or (len(given) == 2 and start == stop):
        raise InputError(
            "--from and --to must be two different finite values (degrees, or a slider's positions)"
        )
    if svg_path and not paths:
        raise InputError("--svg draws the --path curves: name a point with --path")
    if csv_path == "-" and request.as_json:
        raise InputError(
            "--csv - writes the CSV to standard output, where --json would write too",
            hint="write the CSV to a file (--csv series.csv), or leave out --json",
        )
    if level == "forces":  # issue 24: the force sweep's body is mech.render.forces_sweep.run
        from mech.render.forces_sweep import Asked as ForcesAsked
        from mech.render.forces_sweep import run as force_sweep

        wanted = ForcesAsked(start, stop, steps, lead, method, quantities, csv_path, plot_path)
        refused = (("--animate", gif_path), ("--path", paths), ("--svg", svg_path))
        force_sweep(request, wanted, refused=refused, echo=click.echo, write=_write)
        return
    quantities = tuple(quantities) + tuple(f"position.{p}.{c}" for p in paths for c in ("x", "y"))
    if plot_path or gif_path:
        from mech.draw.raster import use_matplotlib

        use_matplotlib()  # fail before solving when the plot extra is missing
    from mech.analysis import Request as Asked
    from mech.analysis import SweepSpec, analyse, out_of_memory
    from mech.render.emit import choose, emit

    spec = SweepSpec(start, stop, steps, level=level, quantities=quantities, method=method, drive=lead)
    asked = Asked(level=None, options=request.options, sweep=spec, drawn=bool(gif_path or svg_path))
    result = analyse(request.file, asked)
    # the sweep refuses up front when its arrays would exceed its budget; the CSV, series or plot of
    # that many steps can still run out of memory: say so (exit 2), never a traceback
    try:
        _sweep_files(
            result,
            request.units,
            quantities,
            csv_path=csv_path,
            plot_path=plot_path,
            gif_path=gif_path,
            paths=paths,
            svg_path=svg_path,
        )
        if csv_path == "-":  # the CSV is the report on standard output
            return
        emit(
            "sweep",
            choose(request.as_json),
            result,
            echo=click.echo,
            units=request.units,
            file=request.file,
            series=quantities,
        )
    except MemoryError:
        raise out_of_memory(result.mechanism, spec) from None


def _sweep_files(
    result: Result,
    units: OutputUnits,
    quantities_asked: tuple[str, ...],
    *,
    csv_path: str | None,
    plot_path: str | None,
    gif_path: str | None,
    paths: tuple[str, ...],
    svg_path: str | None,
) -> None:
    """The files ``mech sweep`` writes beside its report: CSV, PNG plot, GIF, the paths' SVG."""
    from mech.render import sweep as render

    sweep, quantities, drawn = result.sweep, quantities_asked, result.drawn
    assert sweep is not None
    if csv_path == "-":
        click.echo(render.sweep_csv(sweep, units=units, quantities=quantities), nl=False)
    elif csv_path:
        _write(csv_path, render.sweep_csv(sweep, units=units, quantities=quantities))
    if plot_path:
        render.sweep_plot_file(plot_path, sweep, units=units, quantities=quantities)
    if gif_path:
        assert drawn is not None
        render.sweep_animation_file(gif_path, result.mechanism, drawn, sweep, paths=paths)
    if svg_path:
        from mech.draw import save
        from mech.draw.config import curves_figure

        curves = [
            (
                f"path of {p}",
                [(float(x), float(y)) for x, y in sweep.positions[:, sweep.points.index(p), :]],
                "path",
            )
            for p in paths
        ]
        title = f"{result.mechanism.label}: paths"
        assert drawn is not None
        save(curves_figure(result.mechanism, drawn, curves, title=title), svg_path)


# -- checking answers -----------------------------------------------------------------
@cli.command(name="check")
@click.argument("paths", nargs=-1, required=True, type=click.Path(exists=True))
@click.option(
    "--answers",
    "answers",
    type=click.Path(exists=True),
    help="A student's answer sheet, or a folder of sheets (one per student) to check a class.",
)
@click.option(
    "-j",
    "--jobs",
    type=click.IntRange(min=1),
    default=None,
    help="Worker processes (default: one per CPU core; 1: no pool).",
)
@click.option(
    "--junit", type=click.Path(dir_okay=False), help="Also write JUnit XML (one testcase per answer)."
)
@click.option(
    "--gradescope", type=click.Path(dir_okay=False), help="Also write a Gradescope autograder results.json."
)
@click.option(
    "--csv",
    "csv_path",
    type=click.Path(dir_okay=False),
    help="Also write a CSV gradebook (student, problem …).",
)
@click.option("-q", "--quiet", is_flag=True, help="List only files, students and answers that did not pass.")
@click.option(
    "-v", "--verbose", is_flag=True, help="List every answer (default: one line per file, or per student)."
)
@click.option(
    "--timeout",
    type=click.FloatRange(min=0, min_open=True),
    default=30.0,
    show_default=True,
    help="Seconds one problem file may take before it is an error row (the others finish).",
)
@json_option
@handles_errors
def check_command(
    paths: Sequence[str],
    answers: str | None,
    jobs: int | None,
    junit: str | None,
    gradescope: str | None,
    csv_path: str | None,
    quiet: bool,
    verbose: bool,
    timeout: float,
    as_json: bool,
) -> None:
    """Check claimed answers against computed ones: files, folders, answer sheets.

    Every file under PATHS (recursively, *.yaml and *.yml) is a row: its
    answers are checked, computing only what they ask; each answer passes,
    fails (with the computed value, the error and the mistake it matches) or
    is an error (it could not be computed, or the file could not be read).
    Exit status 0 when all pass, 1 when any fails or errors, 2 on a usage
    error, 130 when interrupted (no report file is left behind).
    """
    from mech.batch import CheckOptions
    from mech.commands import check_paths, check_targets, check_usage

    targets = check_targets(junit, gradescope, csv_path)
    problem = check_usage(answers, targets)
    if problem is not None:
        raise click.UsageError(problem)
    options = CheckOptions(paths=tuple(paths), answers=answers, jobs=jobs, timeout=timeout)
    check_paths(options, targets, quiet=quiet, verbose=verbose, as_json=as_json)


def _write(path: str, text: str | Iterable[str]) -> None:
    """Write a report file atomically; exit 2 if it cannot be (:func:`mech.commands.write_report`)."""
    from mech.commands import write_report

    write_report(path, text)


# -- drawings -------------------------------------------------------------------------
@cli.command(name="draw")
@click.option(
    "-o",
    "--output",
    required=True,
    type=click.Path(dir_okay=False),
    help="The drawing to write: .svg or .png.",
)
@click.option(
    "--velocity", is_flag=True, help="Add the velocity polygon (o, a, b …) beside the configuration."
)
@click.option("--acceleration", is_flag=True, help="Add the acceleration polygon with its components.")
@click.option("--icentres", "with_icentres", is_flag=True, help="Mark the I-centres on the configuration.")
@click.option("--path", "paths", multiple=True, help="Trace a point's path over the cycle (repeatable).")
@click.option(
    "--centrodes", multiple=True, help="Draw a link's fixed and moving centrodes over the cycle (repeatable)."
)
@click.option(
    "--forces", "with_forces", is_flag=True, help="Draw the force vectors (F₂₃ …) on the configuration."
)
@click.option(
    "--free-body",
    "free_bodies",
    multiple=True,
    metavar="LINK",
    help="Add LINK's free-body diagram (repeatable).",
)
@kinematic_command(alpha=True)
def draw_command(
    request: Request,
    output: str,
    velocity: bool,
    acceleration: bool,
    with_icentres: bool,
    paths: tuple[str, ...],
    centrodes: tuple[str, ...],
    with_forces: bool = False,
    free_bodies: tuple[str, ...] = (),
) -> None:
    """Draw the configuration diagram to scale, with polygons and I-centres on request.

    SVG is written by mech itself; PNG needs the optional matplotlib
    (pip install 'planar-mech[plot]').
    """
    from mech.analysis import Request as Asked
    from mech.analysis import analyse, drawing_level, load_mechanism
    from mech.render.draw import check_output, draw_file
    from mech.render.emit import choose, emit

    check_output(output)
    if with_forces or free_bodies:  # issue 24: drawn by mech.render.forces.draw_forces
        from mech.render.forces import draw_forces

        others = {"--velocity": velocity, "--acceleration": acceleration, "--icentres": with_icentres}
        summary = draw_forces(request, output, free_bodies=free_bodies, refused={**others, "--path": paths})
        emit("draw", choose(request.as_json), summary, echo=click.echo, name=summary["name"])
        return
    mechanism = load_mechanism(request.file)
    level = drawing_level(
        mechanism, request.options, velocity=velocity, acceleration=acceleration, icentres=with_icentres
    )
    asked = Asked(level, request.options, icentres=with_icentres, paths=paths, centrodes=centrodes)
    result = analyse(mechanism, asked)
    summary = draw_file(
        result, output, file=request.file, velocity=velocity, acceleration=acceleration, units=request.units
    )
    emit("draw", choose(request.as_json), summary, echo=click.echo, name=mechanism.label)


# -- cams -----------------------------------------------------------------------------
@cli.command(name="cam")
@file_argument
@click.option("--rpm", type=float, help="Cam speed in rpm (overrides the file's drive).")
@click.option(
    "--direction", type=click.Choice(["cw", "ccw"]), help="The sense the cam turns (overrides the drive)."
)
@click.option("--joint", help="The cam joint to analyse, when the file has several with a programme.")
@click.option(
    "--step",
    type=click.FloatRange(min=0.1, max=360.0),
    default=30.0,
    show_default=True,
    help="Cam angle between rows of the motion table, degrees.",
)
@click.option(
    "--samples",
    type=click.IntRange(min=36, max=100_000),
    default=1440,
    show_default=True,
    help="Cam angles sampled over the turn (points on the profile).",
)
@click.option(
    "-o", "--output", type=click.Path(dir_okay=False), help="Draw the cam profile to scale (.svg or .png)."
)
@click.option("--diagram", type=click.Path(dir_okay=False), help="Plot the s–v–a–j diagrams (.svg or .png).")
@json_option
@handles_errors
def cam_command(
    file: str,
    rpm: float | None,
    direction: str | None,
    joint: str | None,
    step: float,
    samples: int,
    output: str | None,
    diagram: str | None,
    as_json: bool,
) -> None:
    """Generate a cam's profile from its follower's programme and analyse it.

    The follower's displacement, velocity, acceleration and jerk over the turn,
    the largest pressure angle and where, the least radius of curvature against
    the roller (undercut named) or a flat face's cusp; -o draws the profile to
    scale, --diagram the s–v–a–j diagrams.
    """
    from mech.cam.analysis import analyse
    from mech.loader import load
    from mech.pairs.cam.setup import cam_setup

    if rpm is not None and not (rpm > 0 and math.isfinite(rpm)):
        raise InputError(f"--rpm must be a positive number, not {rpm:g}")
    mechanism = load(file)
    sense = None if direction is None else (1 if direction == "ccw" else -1)
    omega = None if rpm is None else rpm * 2 * math.pi / 60
    setup = cam_setup(mechanism, joint, omega=omega, sense=sense)
    result = analyse(setup.layout, omega=setup.omega, samples=samples)
    if output is not None or diagram is not None:
        from mech.draw import save
        from mech.draw.cam import diagram_figure, profile_figure

        if output is not None:
            save(profile_figure(setup, result, title=mechanism.label), output)
        if diagram is not None:
            save(diagram_figure(result, title=mechanism.label), diagram)
    from mech.render.emit import choose, emit

    context = {"file": file, "name": mechanism.name, "label": mechanism.label, "step_deg": step}
    emit("cam", choose(as_json), (setup, result), echo=click.echo, **context)


def main(argv: Sequence[str] | None = None) -> None:
    """Run a command line through click, with every way out given its own status.

    The console script is :func:`mech.entry.main`; this is its click half, also
    callable on its own (tests, scripts).  See :func:`mech.entry.guarded`.
    """
    from mech.entry import guarded, prepare

    args = prepare(sys.argv[1:] if argv is None else argv)
    guarded(lambda: run_click(args))


def run_click(args: list[str]) -> None:
    """Parse ``args`` with click and run the command; exit with its status.

    click's standalone mode would turn a closed pipe (EPIPE) into status 1 — a
    failed check's — and ^C into "Aborted!" with status 1; here a closed pipe
    and an interrupt leave as :class:`BrokenPipeError` and
    :class:`KeyboardInterrupt` for :func:`mech.entry.guarded` to answer, and
    usage errors keep click's message and status 2.
    """
    try:
        status = cli.main(args=args, prog_name="mech", standalone_mode=False)
    except _PastClick as carried:
        raise carried.original from None
    except click.exceptions.Abort:  # ^C at a prompt, or click's own wrapping of it
        raise KeyboardInterrupt from None
    except click.ClickException as error:
        error.show()
        sys.exit(error.exit_code)
    sys.exit(status if isinstance(status, int) else 0)


if __name__ == "__main__":  # pragma: no cover
    main()
