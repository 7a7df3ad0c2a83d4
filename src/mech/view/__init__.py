"""``mech view``: the mechanism as one self-contained HTML page that plays its cycle.

::

    from mech.view import page
    html = page("mechanisms/four_bar.yaml")          # one string: styles, script and data inline
    Path("four_bar.html").write_text(html)

The page needs no network and no server (a teacher posts it, a student opens it from
disk).  Its data come from one sweep (:func:`mech.kinematics.sweep`, ``steps`` instants
starting at the file's own instant, :mod:`.data`); its script (``page.js``, plain, no
framework, no build step) only draws.  Its contract (DESIGN § 1.5): on load it reads
``#angle=<deg>`` (``#position=<length>`` for a slider drive) and shows the nearest
instant computed, or the file's own instant when it cannot read the fragment; it never
starts playing by itself; each number it shows is an element with ``data-key`` (an
answer key: ``omega.rocker``, ``velocity.C``, ``angle``) and ``data-value`` in SI.
"""

from __future__ import annotations

import json
import math
import re
from importlib import resources
from typing import TYPE_CHECKING

from mech.errors import InputError
from mech.options import SolveOptions

if TYPE_CHECKING:  # pragma: no cover
    from mech.kinematics.result import Kinematics
    from mech.model import Mechanism

__all__ = ["page", "summary"]


def page(
    source: str | Mechanism,
    *,
    options: SolveOptions | None = None,
    steps: int = 360,
    start: float | None = None,
    stop: float | None = None,
) -> str:
    """The page of ``source`` (a path, ``-``, or a loaded mechanism) as HTML text.

    Parameters
    ----------
    options
        The drive's overrides (``angle``: the instant the page opens on; speed; sense).
    steps
        A crank's turn in ``steps`` instants (360: 1° apart); a slider's stroke in ``steps``
        steps from ``start`` to ``stop`` (``steps + 1`` instants, both ends included).
    start, stop
        A slider drive's stroke, in the file's length unit (required for one); a
        crank's range is its whole turn from the file's own angle.

    Raises
    ------
    InputError
        A mechanism without a drive or geometry, a slider drive without its stroke.
    """
    from mech.analysis import Request, SweepSpec, analyse, has_speed, load_mechanism
    from mech.view.data import page_data

    options = options or SolveOptions()
    mech = load_mechanism(source) if isinstance(source, str) else source
    if not mech.drives:
        raise InputError(
            f"{mech.label} has no drive: the page plays the drive's cycle",
            hint="add drive: {link: crank, angle: …, rpm: …}",
        )
    level = "acceleration" if has_speed(mech, options) else "position"
    drawn = _drawn(mech, options, level)
    level = drawn.level
    lead = mech.drives[0]
    if lead.link is not None:
        own = next((d.angle for d in drawn.drives if d.link == lead.link and d.angle is not None), 0.0)
        first = math.degrees(own)
        spec = SweepSpec(first, first + 360.0 - 360.0 / steps, max(steps - 1, 1), level=level)
    else:
        if start is None or stop is None:
            raise InputError(
                f"{mech.label} is driven by the slider {lead.joint}: the page needs its stroke",
                hint="give --from and --to, positions along its path in the file's length unit",
            )
        spec = SweepSpec(start, stop, steps, level=level)  # both ends of the stroke: steps + 1 instants
    result = analyse(mech, Request(level=None, options=options.with_(angle=None), sweep=spec))
    assert result.sweep is not None
    data = page_data(mech, drawn, result.sweep)
    return _html(data)


def _drawn(mech: Mechanism, options: SolveOptions, level: str) -> Kinematics:
    """The solve at the page's own instant, at the highest level the file allows."""
    from mech.analysis import solve_at
    from mech.errors import MechError

    try:
        return solve_at(mech, level, options)
    except MechError:
        if level != "acceleration":
            raise
        return solve_at(mech, "velocity", options)  # a contact known by point and normal: no curvature


def _html(data: dict[str, object]) -> str:
    """The page: the template with its style, script and data put inline."""
    files = resources.files("mech.view")
    template = files.joinpath("page.html").read_text(encoding="utf-8")
    style = files.joinpath("page.css").read_text(encoding="utf-8")
    script = files.joinpath("page.js").read_text(encoding="utf-8")
    text = json.dumps(data, separators=(",", ":"), allow_nan=False, ensure_ascii=False)
    text = text.replace("</", "<\\/")  # a name cannot close the script element
    title = str(data["title"]).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    parts = {"title": title, "style": style, "data": text, "script": script}
    return re.sub(r"\{\{(title|style|data|script)\}\}", lambda m: parts[m.group(1)], template)


def summary(html: str, *, file: str, output: str) -> dict[str, object]:
    """What ``mech view --json`` prints about the page it wrote: where, how big, how many instants."""
    match = re.search(r'"param":\{"kind":"(\w+)","si":\[([^\]]*)\]', html)
    steps = len(match.group(2).split(",")) if match else 0
    return {
        "file": file,
        "output": output,
        "bytes": len(html.encode("utf-8")),
        "steps": steps,
        "parameter": match.group(1) if match else None,
    }
