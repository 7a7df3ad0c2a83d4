"""``mech draw``: load, solve at the level the drawing needs, locate I-centres, draw, write.

Kept out of :mod:`mech.cli` so the command stays a thin parse-and-call, and
out of :mod:`mech.draw` so the drawing library never loads files.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from mech.errors import InputError
from mech.options import OutputUnits, SolveOptions

__all__ = ["draw_file"]


def draw_file(
    file: str,
    output: str,
    *,
    options: SolveOptions,
    velocity: bool = False,
    acceleration: bool = False,
    icentres: bool = False,
    units: OutputUnits | None = None,
    paths: tuple[str, ...] = (),
    centrodes: tuple[str, ...] = (),
) -> dict[str, Any]:
    """Draw ``file`` into ``output`` (.svg or .png); returns a summary for ``--json``.

    Only what the drawing needs is solved: positions for the configuration
    alone, velocities for the velocity polygon, accelerations for the
    acceleration polygon.  A PNG without matplotlib fails before any solving.
    """
    suffix = Path(output).suffix.lower()
    if suffix not in (".svg", ".png"):
        raise InputError(
            f"cannot write a drawing as {suffix or 'a file without an extension'}: {output}",
            hint="name the output .svg or .png",
        )
    if suffix == ".png":
        from mech.draw.raster import use_matplotlib

        use_matplotlib()
    from mech.draw import draw, save
    from mech.draw.scene import Text
    from mech.kinematics import solve
    from mech.loader import load

    mech = load(file)
    level = "acceleration" if acceleration else "velocity" if velocity else "position"
    if icentres and level == "position" and _has_speed(mech, options):
        level = "velocity"  # lets the I-centres be cross-checked with the velocity field
    kin = solve(mech, level=level, options=options)
    centres = None
    if icentres:
        from mech.icentres import locate

        located = locate(mech, kin)
        centres = list(located.centres)
    curves = loci(mech, options, paths=paths, centrodes=centrodes)
    figure = draw(
        mech, kin, velocity=velocity, acceleration=acceleration, icentres=centres, units=units, curves=curves
    )
    save(figure, output)
    scales = [t.text for t in figure.items if isinstance(t, Text) and t.cls == "scale"]
    summary: dict[str, Any] = {
        "file": file,
        "output": output,
        "size_mm": [round(figure.width, 1), round(figure.height, 1)],
        "scales": scales,
        "icentres": [c.name for c in centres] if centres is not None else None,
        "notes": list(kin.notes),
    }
    if curves:  # only when asked: the summary's keys stay as they were for other drawings
        summary["curves"] = [{"label": label, "kind": kind} for label, _pts, kind in curves]
    return summary


def _has_speed(mech: Any, options: SolveOptions) -> bool:
    if options.omega is not None or options.speed is not None:
        return True
    return bool(mech.drives) and all(d.omega is not None or d.speed is not None for d in mech.drives)


def loci(
    mech: Any, options: SolveOptions, *, paths: tuple[str, ...] = (), centrodes: tuple[str, ...] = ()
) -> list[tuple[str, list[tuple[float, float]], str]]:
    """The curves ``mech draw --path/--centrodes`` traces: point paths, fixed and moving centrodes."""
    if not (paths or centrodes):
        return []
    from mech.properties.paths import centrodes as find_centrodes
    from mech.properties.paths import point_path

    sweep_options = options.with_(angle=None)
    out: list[tuple[str, list[tuple[float, float]], str]] = []
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
    return out
