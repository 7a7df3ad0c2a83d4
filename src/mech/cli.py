"""The ``mech`` command line: parse options, call the library, hand results to a renderer.

This module imports click and nothing heavy: numpy and rich are imported inside
the commands that need them, so ``mech dof`` over a folder starts fast.
Exit status: 0 success, 1 a failed check, 2 bad input or usage, 70 a bug, 130 interrupted,
141 the reader closed the pipe (cli.md, "Exit status").
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Sequence
from functools import wraps
from typing import TYPE_CHECKING, Any

import click

from mech import __version__
from mech.commands import Request, handles_errors, request_of, run_command
from mech.commands.params import COMMANDS, DEBUG, Param, validate
from mech.errors import InputError
from mech.options import OutputUnits

if TYPE_CHECKING:  # pragma: no cover
    from mech.analysis import Result


def _type(p: Param) -> Any:
    """click's type for a declared parameter (:class:`mech.commands.params.Param`)."""
    if p.kind == "choice":
        return click.Choice(list(p.choices))
    if p.kind == "path":
        return click.Path(exists=p.exists, dir_okay=p.dir_okay, allow_dash=p.allow_dash, writable=p.writable)
    bounded = p.low is not None or p.high is not None
    if p.kind == "float":
        return click.FloatRange(min=p.low, max=p.high, min_open=p.low_open) if bounded else float
    if p.kind == "int":
        return click.IntRange(min=p.low, max=p.high) if bounded else int  # type: ignore[arg-type]
    return None


def params_of(command: str) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """click's options and arguments of ``command``, built from its declarations, in their order."""

    def decorate(fn: Callable[..., Any]) -> Callable[..., Any]:
        for p in reversed(COMMANDS[command]):
            if not p.is_option:
                extra = {"default": p.default} if p.default is not None else {}
                fn = click.argument(p.dest, nargs=p.nargs, required=p.required, type=_type(p), **extra)(fn)
            elif p.kind == "flag":
                fn = click.option(*p.names, p.dest, is_flag=True, help=p.help)(fn)
            else:
                # no default=None passed: click 8.5 takes an explicit None as a default given, and
                # then lets a required option (mech draw -o) go missing
                given = {"default": p.default} if p.default is not None else {}
                fn = click.option(
                    *p.names,
                    p.dest,
                    type=_type(p),
                    show_default=p.show_default,
                    required=p.required,
                    multiple=p.multiple,
                    help=p.help,
                    **given,
                )(fn)
        return fn

    return decorate


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
    *DEBUG.names,
    is_flag=True,
    expose_value=False,
    is_eager=True,
    callback=lambda ctx, param, value: _debug(value),
    help=DEBUG.help,
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
    """``mech --debug …``: a bug's traceback is shown (read by :func:`mech.commands.exits.guarded`)."""
    if on:
        import os

        os.environ["MECH_DEBUG"] = "1"


# -- counting -------------------------------------------------------------------------
@cli.command()
@params_of("dof")
def dof(**values: Any) -> None:
    """Count degrees of freedom by Kutzbach and check Grübler's criterion.

    Shows l, j and h, the link and joint classes and the count worked out;
    several files give one table.  A bad file is reported on stderr and the
    others are still counted (exit status 2 at the end).
    """
    run_command("dof", values)


@cli.command(name="classify")
@params_of("classify")
def classify_command(**values: Any) -> None:
    """Classify links (binary, ternary …), joints and kinematic pairs.

    Pairs are classified as the lecture notes do: by relative motion (turning,
    sliding, rolling, screw, spherical, cam or gear), by contact (lower or
    higher) and by closure (self-closed or force-closed).
    """
    run_command("classify", values)


@cli.command()
@params_of("schema")
@handles_errors
def schema(output: str | None) -> None:
    """Print the JSON Schema (draft-07) of the mechanism file format.

    Point your editor's YAML plugin at it for validation and completion.
    """
    from mech.render.jsonout import dumps
    from mech.schema import schema

    text = dumps(schema())
    if output:
        from mech._files import write_file

        write_file(output, text + "\n")
    else:
        click.echo(text)


# -- kinematics -----------------------------------------------------------------------
def kinematic_command(command: str) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """A command that solves the mechanism: its declared options, folded into a :class:`Request`.

    The command function receives ``request`` first and its own options by
    name; errors, in the options or anywhere below, are reported (exit 2).
    """
    solving = {p.dest for p in COMMANDS["position"]} | {"alpha"}

    def decorate(fn: Callable[..., Any]) -> Callable[..., Any]:
        def command_(**values: Any) -> Any:
            own = {k: v for k, v in values.items() if k not in solving}
            return fn(request_of(values, COMMANDS[command]), **own)

        # handles_errors names the command after fn (less "_command") and finds file and --json
        return params_of(command)(handles_errors(wraps(fn)(command_)))

    return decorate


@cli.command()
@params_of("position")
def position(**values: Any) -> None:
    """Solve the positions of every joint and point at the crank angle."""
    run_command("position", values)


@cli.command()
@params_of("velocity")
def velocity(**values: Any) -> None:
    """Velocities of every point and link at the crank angle and speed.

    Absolute velocities of joints and points, angular velocities of links,
    relative velocities along links (the velocity polygon's ab, bc …), sliding
    velocities in slides and slots, and rubbing velocities at pins with a radius.
    """
    run_command("velocity", values)


@cli.command()
@params_of("acceleration")
def acceleration(**values: Any) -> None:
    """Accelerations (normal, tangential, Coriolis) of every point and link."""
    run_command("acceleration", values)


@cli.command(name="forces")
@kinematic_command("forces")
def forces_command(request: Request, explain: bool) -> None:
    """Forces at the crank angle: what each pair carries, the input torque and its parts, the shaking.

    Without friction, from the masses, gravity and loads the file gives
    (d'Alembert's inertia forces when the drive has a speed).  The body is
    mech.render.forces.run.
    """
    from mech.render.forces import run

    run(request, explain=explain, echo=click.echo)


@cli.command()
@kinematic_command("icentres")
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

    _writable(circle_path)
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
@kinematic_command("properties")
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
@kinematic_command("sweep")
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
    _writable(None if csv_path == "-" else csv_path, plot_path, gif_path, svg_path)
    if level == "forces":  # issue 24: the force sweep's body is mech.render.forces_sweep.run
        from mech._files import write_file
        from mech.render.forces_sweep import Asked as ForcesAsked
        from mech.render.forces_sweep import run as force_sweep

        wanted = ForcesAsked(start, stop, steps, lead, method, quantities, csv_path, plot_path)
        refused = (("--animate", gif_path), ("--path", paths), ("--svg", svg_path))
        force_sweep(request, wanted, refused=refused, echo=click.echo, write=write_file)
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
    from mech._files import write_file
    from mech.render import sweep as render

    sweep, quantities, drawn = result.sweep, quantities_asked, result.drawn
    assert sweep is not None
    if csv_path == "-":
        click.echo(render.sweep_csv(sweep, units=units, quantities=quantities), nl=False)
    elif csv_path:
        write_file(csv_path, render.sweep_csv(sweep, units=units, quantities=quantities))
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
@params_of("check")
def check_command(**values: Any) -> None:
    """Check claimed answers against computed ones: files, folders, answer sheets.

    Every file under PATHS (recursively, *.yaml and *.yml) is a row: its
    answers are checked, computing only what they ask; each answer passes,
    fails (with the computed value, the error and the mistake it matches) or
    is an error (it could not be computed, or the file could not be read).
    Exit status 0 when all pass, 1 when any fails or errors, 2 on a usage
    error, 130 when interrupted (no report file is left behind).
    """
    from mech.commands import check_usage

    problem = check_usage(values)
    if problem is not None:
        raise click.UsageError(problem)
    run_command("check", values)


# -- the live page --------------------------------------------------------------------
@cli.command(name="view")
@kinematic_command("view")
def view_command(request: Request, output: str, steps: int, start: float | None, stop: float | None) -> None:
    """Write one self-contained HTML page that plays the mechanism's cycle.

    Slider, play/pause and speed; the configuration with the velocity and
    acceleration polygons; I-centres, coupler paths, centrodes and the
    transmission angle as layers; the numbers of the instant shown.  It
    needs no network and no server: post it, or open it from disk.
    """
    import json

    from mech._files import check_writable, write_file
    from mech.view import page, summary

    check_writable(output)  # before any solving
    html = page(request.file, options=request.options, steps=steps, start=start, stop=stop)
    write_file(output, html)
    info = summary(html, file=request.file, output=output)
    click.echo(
        json.dumps(info)
        if request.as_json
        else f"wrote {output}: {info['steps']} instants, {info['bytes']:,} bytes"
    )


@cli.command(name="key")
@params_of("key")
def key_command(**values: Any) -> None:
    """Every problem's answers to its questions: the teacher's key.

    For each problem file under PATHS, the computed answer to each of its
    questions (its answers' keys, else its asks), with its marks; --json or
    --csv FILE for tools. Exit 1 when a question cannot be computed, 2 when
    a file cannot be read.
    """
    from mech.commands.classroom import key_command as run

    run(values)


@cli.command(name="variants")
@params_of("variants")
def variants_command(**values: Any) -> None:
    """A problem for each student: its numbers drawn from the file's vary:, kept by its keep:.

    Writes OUTPUT/<student>/<file> (the student's problem, drawn positions
    recomputed), a drawing to scale beside it, and OUTPUT/key.csv and
    OUTPUT/key.json. A student's variant depends only on the seed, the file
    and the student's id.
    """
    from mech.commands.classroom import variants_command as run

    run(values)


# -- drawings -------------------------------------------------------------------------
@cli.command(name="draw")
@kinematic_command("draw")
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
        refused = {**others, "--path": paths, "--centrodes": centrodes}
        summary = draw_forces(request, output, free_bodies=free_bodies, refused=refused)
        emit("draw", choose(request.as_json), summary, echo=click.echo, name=summary["name"])
        return
    mechanism = load_mechanism(request.file)
    if paths or centrodes:
        _one_turn(mechanism, "--path" if paths else "--centrodes", paths)
    level = drawing_level(
        mechanism, request.options, velocity=velocity, acceleration=acceleration, icentres=with_icentres
    )
    asked = Asked(level, request.options, icentres=with_icentres, paths=paths, centrodes=centrodes)
    result = analyse(mechanism, asked)
    summary = draw_file(
        result, output, file=request.file, velocity=velocity, acceleration=acceleration, units=request.units
    )
    emit("draw", choose(request.as_json), summary, echo=click.echo, name=mechanism.label)


def _writable(*paths: str | None) -> None:
    """Say now, before any solving, that an output file cannot be written (exit 2, naming it)."""
    from mech._files import check_writable

    for path in paths:
        if path:
            check_writable(path)


def _one_turn(mechanism: Any, option: str, paths: tuple[str, ...]) -> None:
    """Refuse ``mech draw --path/--centrodes`` on a file whose drive is not one crank, saying what can.

    The traced curves come from a crank's whole turn; ``mech draw`` has no ``--drive``.
    ``mech sweep --path P --svg`` sweeps the first drive (or the one ``--drive`` names).
    """
    drives = mechanism.drives
    if len(drives) <= 1 and (not drives or drives[0].link is not None):
        return  # one crank (or none: the analysis says so)
    what = f"{len(drives)} drives" if len(drives) > 1 else f"a slider drive ({drives[0].joint})"
    point = paths[0] if paths else "P"
    hint = (
        f"draw a path with mech sweep {mechanism.path or 'FILE'} --path {point} --svg paths.svg "
        "(it sweeps the first drive, or the one --drive names)"
    )
    if not paths:
        hint = "centrodes are drawn for a mechanism driven by one crank; " + hint
    raise InputError(f"{mechanism.label} has {what}: mech draw {option} traces one crank's turn", hint=hint)


# -- cams -----------------------------------------------------------------------------
@cli.command(name="cam")
@params_of("cam")
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

    validate(COMMANDS["cam"], {"rpm": rpm})
    _writable(output, diagram)
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
    callable on its own (tests, scripts).  See :func:`mech.commands.exits.guarded`.
    """
    from mech.commands.exits import guarded, prepare

    guarded(lambda: run_click(prepare(sys.argv[1:] if argv is None else argv)))


def run_click(args: list[str]) -> None:
    """Parse ``args`` with click and run the command; exit with its status.

    click's standalone mode would turn a closed pipe (EPIPE) into status 1 — a
    failed check's — and ^C into "Aborted!" with status 1; here a closed pipe
    and an interrupt leave as :class:`BrokenPipeError` and
    :class:`KeyboardInterrupt` for :func:`mech.commands.exits.guarded` to answer, and
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
