"""The drives of one solve as used: the file's, with the command's overrides, angles read from the drawing.

Below the solver and the march, which both start from them (:func:`drives_as_used`),
and from the time scale they set (:func:`omega_ref_of`).
"""

from __future__ import annotations

import math
from dataclasses import replace

from mech.errors import InputError
from mech.kinematics.assemble import Drawn
from mech.kinematics.layout import Layout
from mech.model import Drive, Mechanism
from mech.options import SolveOptions

__all__ = ["angle_text", "drives_as_used", "omega_ref_of"]


def drives_as_used(
    mech: Mechanism, lay: Layout, drawn: Drawn, options: SolveOptions, lvl: int
) -> tuple[Drive, ...]:
    """The drives as used: overrides applied, angle from the drawing, omega signed."""
    out = []
    for k, (d, spec) in enumerate(zip(mech.drives, lay.drives, strict=False)):
        if spec.link is not None:
            if options.speed is not None:
                raise InputError(
                    f"--speed sets a slider drive; the drive of {d.link} turns",
                    where=d.where,
                    hint="use --rpm or --omega",
                )
            omega = d.omega
            if options.omega is not None:
                sign = (
                    -1.0
                    if (options.direction == "cw" or (options.direction is None and (d.omega or 0) < 0))
                    else 1.0
                )
                omega = sign * options.omega
            elif options.direction is not None and omega is not None:
                omega = abs(omega) * (-1.0 if options.direction == "cw" else 1.0)
            angle = options.angle if options.angle is not None else drawn.drive_angles[k]
            if angle is None:
                raise InputError(
                    f"drive of {d.link}: no angle given and none can be read from the drawing",
                    where=d.where,
                    hint="give drive.angle (or --angle)",
                )
            alpha = options.alpha if options.alpha is not None else (d.alpha or 0.0)
            if lvl >= 1 and omega is None:
                raise InputError(
                    f"drive of {d.link} has no speed: give rpm or omega (or --rpm)", where=d.where
                )
            out.append(replace(d, angle=float(angle), omega=omega, alpha=alpha))
        else:
            if options.angle is not None:
                raise InputError(
                    f"--angle applies to a turning drive; the drive of {d.joint} is a slider", where=d.where
                )
            turning = [
                flag
                for flag, given in (
                    ("--rpm/--omega", options.omega is not None),
                    ("--direction", options.direction is not None),
                    ("--alpha", options.alpha is not None),
                )
                if given
            ]
            if turning:
                raise InputError(
                    f"{', '.join(turning)} set a turning drive; the drive of {d.joint} is a slider",
                    where=d.where,
                    hint="give its speed with --speed (m/s, signed along its path) or speed: in the file",
                )
            speed = options.speed if options.speed is not None else d.speed
            if lvl >= 1 and speed is None:
                raise InputError(f"slider drive of {d.joint} has no speed: give speed (m/s)", where=d.where)
            out.append(replace(d, speed=speed, accel=d.accel or 0.0))
    if lvl >= 1 and not out:
        raise InputError(
            f"{mech.label} has no drive: give rpm or omega (or --rpm)",
            hint="add drive: {link: crank, angle: 60, rpm: 120}",
        )
    return tuple(out)


def omega_ref_of(drives: tuple[Drive, ...], scale: float) -> float:
    """Time scale 1/ω: the fastest drive (a slider's v/size), 1 when nothing moves."""
    rates: list[float] = []
    for d in drives:
        rate = d.omega if d.link is not None else (None if d.speed is None else d.speed / scale)
        if rate is not None:
            rates.append(abs(rate))
    best = max(rates, default=0.0)
    return best if best > 0 and math.isfinite(best) else 1.0


def angle_text(a: float | None) -> str:
    """An angle for a message; a drive angle the file does not give is said so."""
    return f"{math.degrees(a):.6g}°" if a is not None else "(no angle given)"
