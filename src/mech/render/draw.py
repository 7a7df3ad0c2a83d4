"""``mech draw``: the analysed mechanism drawn and written (.svg or .png), with a summary for ``--json``.

The analysis (load, solve at the level the drawing needs, I-centres, traced
curves) is :func:`mech.analysis.analyse`'s; this module only draws its
:class:`~mech.analysis.Result` and writes the file, so the drawing library
(:mod:`mech.draw`) never loads files or solves.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from mech.analysis import Result
from mech.errors import InputError
from mech.options import OutputUnits

__all__ = ["check_output", "draw_file"]


def check_output(output: str) -> None:
    """Refuse an output that is not .svg or .png, a PNG without matplotlib, and a path that cannot
    be written (:func:`mech._files.check_writable`), before any solving."""
    from mech._files import check_writable

    suffix = Path(output).suffix.lower()
    if suffix not in (".svg", ".png"):
        raise InputError(
            f"cannot write a drawing as {suffix or 'a file without an extension'}: {output}",
            hint="name the output .svg or .png",
        )
    if suffix == ".png":
        from mech.draw.raster import use_matplotlib

        use_matplotlib()
    check_writable(output)


def draw_file(
    result: Result,
    output: str,
    *,
    file: str,
    velocity: bool = False,
    acceleration: bool = False,
    units: OutputUnits | None = None,
) -> dict[str, Any]:
    """Draw ``result`` into ``output`` (.svg or .png); returns a summary for ``--json``.

    ``result`` was solved at the level the drawing needs
    (:func:`mech.analysis.drawing_level`), with the I-centres and curves asked.
    """
    check_output(output)
    from mech.draw import draw, save
    from mech.shapes import Text

    kin = result.kinematics
    assert kin is not None
    centres = list(result.icentres.centres) if result.icentres is not None else None
    curves = list(result.curves)
    figure = draw(
        result.mechanism,
        kin,
        velocity=velocity,
        acceleration=acceleration,
        icentres=centres,
        units=units,
        curves=curves,
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
