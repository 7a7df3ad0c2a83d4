"""A cam's follower worked out from its law at the instant, as the notes do it (``--explain``).

Khurmi & Gupta, *Theory of Machines*, ch. 20, and Norton, *Design of Machinery*, ch. 8: find
where the cam is in its programme (which segment, how far into it, x = (θ − θ₀)/β), write the
law's displacement s and its derivatives ds/dθ, d²s/dθ² with the numbers in, then v = ω ds/dθ
and a = ω² d²s/dθ², and the pressure angle.  For a translating knife-edge or roller follower
with offset e on a prime circle of radius r_p (base circle plus roller),

    tan φ = (ds/dθ − e) / (√(r_p² − e²) + s)                    (Norton eq. 8.31)

(φ = 0 for a flat face square to its stroke); for an oscillating follower the angle between
the common normal and the path of the follower's point, from the profile.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from mech.explain.worked import Line, Worked, g

if TYPE_CHECKING:
    from mech.model import Joint, Mechanism

__all__ = ["LAWS", "cam_working"]

#: The law's lift and its two derivatives in θ, as functions of x (0–1), h and β: the formulas
#: written (for the working's text) and evaluated (for its numbers): Khurmi & Gupta ch. 20.
LAWS: dict[str, tuple[str, str, str]] = {
    "uniform": ("h x", "h / β", "0"),
    "shm": ("h/2 (1 − cos πx)", "π h / (2β) · sin πx", "π² h / (2β²) · cos πx"),
    "parabolic": ("2 h x² (x ≤ ½); h (1 − 2 (1 − x)²) after", "4 h x / β; 4 h (1 − x) / β", "± 4 h / β²"),
    "cycloidal": ("h (x − sin 2πx / 2π)", "h / β · (1 − cos 2πx)", "2π h / β² · sin 2πx"),
}


def _law(law: str, x: float, h: float, beta: float) -> tuple[float, float, float]:
    """s, ds/dθ, d²s/dθ² of one rise by ``law`` at fraction ``x``, written out again here from the textbook,
    each 0 where it is rounding noise of its own scale (h, h/β, h/β²): cos(π/2) is 6e-17, not 0."""
    raw = _raw(law, x, h, beta)
    scales = (h, h / beta, h / beta**2)
    return tuple(v if abs(v) > 1e-13 * sc else 0.0 for v, sc in zip(raw, scales, strict=True))  # type: ignore[return-value]


def _raw(law: str, x: float, h: float, beta: float) -> tuple[float, float, float]:
    if law == "uniform":
        return h * x, h / beta, 0.0
    if law == "shm":
        k = math.pi * x
        return (
            h / 2 * (1 - math.cos(k)),
            math.pi * h / (2 * beta) * math.sin(k),
            math.pi**2 * h / (2 * beta**2) * math.cos(k),
        )
    if law == "parabolic":
        if x <= 0.5:
            return 2 * h * x * x, 4 * h * x / beta, 4 * h / beta**2
        return h * (1 - 2 * (1 - x) ** 2), 4 * h * (1 - x) / beta, -4 * h / beta**2
    k = 2 * math.pi * x
    return (
        h * (x - math.sin(k) / (2 * math.pi)),
        h / beta * (1 - math.cos(k)),
        2 * math.pi * h / beta**2 * math.sin(k),
    )


def _turn(mech: Mechanism, kin: Any, setup: Any) -> float:
    """The cam's turn from its programme's start at the instant ``kin`` was solved for (rad)."""
    from mech.kinematics.solve import compiled

    sys_ = compiled(mech, None).system
    drawn = float(sys_.q0[3 * sys_.link_index[setup.cam] + 2])
    now = kin.links[setup.cam].angle
    return (setup.angle + setup.layout.sense * math.remainder(now - drawn, 2 * math.pi)) % (2 * math.pi)


def cam_working(mech: Mechanism, kin: Any, joint: Joint) -> list[Line]:
    """The lines that work out ``joint``'s follower at the instant: segment, s, v, a, pressure angle."""
    from mech.pairs.cam.setup import cam_setup

    setup = cam_setup(mech, joint.name)
    lay, prog = setup.layout, setup.layout.program
    angular = lay.oscillating
    unit, scale = ("°", math.degrees(1.0)) if angular else ("mm", 1000.0)
    theta = _turn(mech, kin, setup)
    omega = abs(kin.links[setup.cam].omega or 0.0)
    sense = "counter-clockwise" if lay.sense > 0 else "clockwise"
    lines = [
        Line(
            f"Cam {joint.name}: {setup.cam} turns {sense} at ω = {g(omega)} rad/s; it is θ = "
            f"{g(math.degrees(theta))}° into its programme.",
            "theta",
            None,
            {},
            theta,
            "rad",
        )
    ]
    base, start = 0.0, 0.0
    for seg in prog.segments:
        if start <= theta < start + seg.over or seg is prog.segments[-1]:
            break
        base += seg.lift if seg.kind == "rise" else -seg.lift if seg.kind == "return" else 0.0
        start += seg.over
    beta, h = seg.over, seg.lift
    x = (theta - start) / beta
    where = (
        f"θ lies in the {seg.kind} from {g(math.degrees(start))}° over β = {g(math.degrees(beta))}°"
        + (f" (h = {g(h * scale)} {unit}, {seg.law})" if seg.kind != "dwell" else "")
        + f": x = (θ − θ₀)/β = {g(x)}; s₀ = {g(base * scale)} {unit} at its start."
    )
    lines.append(
        Line(where, "x", "(theta - start) / beta", {"theta": theta, "start": start, "beta": beta}, x)
    )
    if seg.kind == "dwell" or seg.law is None:
        s, d1, d2 = 0.0, 0.0, 0.0
        forms = ("0", "0", "0")
    else:
        s, d1, d2 = _law(seg.law, x, h, beta)
        forms = LAWS[seg.law]
    sign = -1.0 if seg.kind == "return" else 1.0
    lift, rate, accel = base + sign * s, sign * d1, sign * d2
    inputs = {"h": h, "beta": beta, "x": x, "base": base, "sign": sign}
    # an oscillating follower's lift in degrees, its rates in rad/s as everywhere in mech
    rscale, runit = (1.0, "rad") if angular else (scale, unit)
    if seg.kind == "dwell":
        written = f"s = s₀ = {g(lift * scale)} {unit}: a dwell, the follower rests (v = 0, a = 0)"
    else:
        written = f"s = s₀ {'+' if sign > 0 else '−'} {forms[0]} = {g(lift * scale)} {unit} (from the lowest position)"
    lines += [
        Line(written, "s", f"base + sign * {seg.law or 'dwell'}.s", inputs, lift, "rad" if angular else "m"),
        Line(
            f"ds/dθ = {forms[1]} = {g(sign * rate * rscale)} {runit}/rad; v = ω ds/dθ = {g(omega)} × "
            f"{g(rate * rscale)} = {g(omega * rate * rscale)} {runit}/s",
            "v",
            "omega * ds/dtheta",
            {**inputs, "omega": omega},
            omega * rate,
            "rad/s" if angular else "m/s",
        ),
        Line(
            f"d²s/dθ² = {forms[2]} = {g(sign * accel * rscale)} {runit}/rad²; a = ω² d²s/dθ² = {g(omega)}² × "
            f"{g(accel * rscale)} = {g(omega**2 * accel * rscale)} {runit}/s²",
            "a",
            "omega**2 * d2s/dtheta2",
            {**inputs, "omega": omega},
            omega**2 * accel,
            "rad/s^2" if angular else "m/s^2",
        ),
    ]
    lines.append(_pressure(lay, theta, lift, rate))
    return lines


def _pressure(lay: Any, theta: float, lift: float, rate: float) -> Line:
    """The pressure angle: Norton's formula for a translating follower, the profile's otherwise."""
    from mech.cam.profile import evaluate

    prog = lay.program
    if not lay.oscillating and prog.follower == "flat":
        return Line(
            "Pressure angle: 0° (a flat face square to its line of stroke).", "pressure", "0", {}, 0.0, "rad"
        )
    if not lay.oscillating:
        rp, e = lay.prime_radius, lay.offset
        phi = math.atan2(rate - e, math.sqrt(rp * rp - e * e) + lift)
        return Line(
            f"Pressure angle: tan φ = (ds/dθ − e) / (√(r_p² − e²) + s) = ({g(rate * 1000)} − {g(e * 1000)}) / "
            f"(√({g(rp * 1000)}² − {g(e * 1000)}²) + {g(lift * 1000)}) mm, φ = {g(math.degrees(phi))}°",
            "pressure",
            "atan2(ds/dtheta - e, sqrt(rp**2 - e**2) + s)",
            {"ds/dtheta": rate, "e": e, "rp": rp, "s": lift},
            phi,
            "rad",
        )
    phi = float(evaluate(lay, [theta]).pressure[0])
    return Line(
        f"Pressure angle: the common normal at the contact against the path of the follower's point "
        f"(the profile at θ): φ = {g(math.degrees(phi))}°",
        "pressure",
        "profile",
        {"theta": theta},
        phi,
        "rad",
    )


def working(mech: Mechanism, kin: Any) -> Worked:
    """Every programme cam of ``mech`` worked out at the instant."""
    from mech.pairs.cam.setup import cam_joints

    lines: list[Line] = []
    for j in cam_joints(mech):
        lines += cam_working(mech, kin, j)
    return Worked(mech.label, "cam", tuple(lines))
