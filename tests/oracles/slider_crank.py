"""The slider crank in closed form, in line or offset: slider position, speeds, dead centres.

Crank OA of length r about O = (0, 0), rod AB of length l, the slider B on the line y = e
ahead of the crank (x > 0).  Derived from the loop r sinθ + l sinφ = e,
x = r cosθ + l cosφ, differentiated once and twice; the dead centres from the collinear
crank-and-rod triangles (the textbook analytical method for the piston, e.g. Khurmi &
Gupta, *Theory of Machines*, here exact: no series in r/l).  :func:`slider_driven_crank`
runs the chain the other way, the slider driving: the crank's angle from the slider's x by
the law of cosines, its ω from the closure |A − B| = l differentiated with x as the input.
Nothing of mech is used.
"""

from __future__ import annotations

import math
from typing import Any

import mpmath

__all__ = ["slider_crank", "slider_dead_centres", "slider_driven_crank", "slider_x"]


def slider_crank(
    r: float, rod: float, e: float, th: float, w: float, al: float = 0.0
) -> tuple[float, float, float, float, float]:
    """x_B, ω3, v_B, α3, a_B at crank angle ``th`` (rad), crank ω and α (rod angle φ).

    x_B = r cosθ + √(l² − (e − r sinθ)²); sinφ = (e − r sinθ)/l;
    ω₃ = −r ω cosθ / (l cosφ), v = −r ω sinθ − l ω₃ sinφ,
    α₃ = (r ω² sinθ − r α cosθ + l ω₃² sinφ) / (l cosφ),
    a = −r α sinθ − r ω² cosθ − l α₃ sinφ − l ω₃² cosφ.
    """
    s = (e - r * math.sin(th)) / rod
    phi = math.asin(s)
    x = r * math.cos(th) + rod * math.cos(phi)
    w3 = -r * w * math.cos(th) / (rod * math.cos(phi))
    v = -r * w * math.sin(th) - rod * w3 * math.sin(phi)
    a3 = (r * w * w * math.sin(th) - r * al * math.cos(th) + rod * w3 * w3 * math.sin(phi)) / (
        rod * math.cos(phi)
    )
    a = (
        -r * al * math.sin(th)
        - r * w * w * math.cos(th)
        - rod * a3 * math.sin(phi)
        - rod * w3 * w3 * math.cos(phi)
    )
    return x, w3, v, a3, a


def slider_dead_centres(r: float, rod: float, e: float) -> tuple[float, float, float, float]:
    """Crank angles (rad) and slider x of the outer and inner dead centres.

    Outer: O, A, B in line with A between, sin ψ = e/(l + r); inner: the crank opposite,
    ψ = π + asin(e/(l − r)).  The slider at √((l ± r)² − e²).
    """
    outer = math.asin(e / (rod + r))
    inner = math.pi + math.asin(e / (rod - r))
    return outer, inner, math.sqrt((rod + r) ** 2 - e**2), math.sqrt((rod - r) ** 2 - e**2)


def slider_x(r: float, rod: float, e: float, th: Any) -> Any:
    """x_B = r cosθ + √(l² − (e − r sinθ)²) in mpmath (the slider ahead), for exact derivatives."""
    return r * mpmath.cos(th) + mpmath.sqrt(rod**2 - (e - r * mpmath.sin(th)) ** 2)


def slider_driven_crank(r: float, rod: float, x: float, v: float) -> tuple[float, float]:
    """Crank angle θ (rad) and ω of an in-line slider crank (e = 0) driven by its slider.

    The slider B = (x, 0) moves at ẋ = ``v``; A = (r cos θ, r sin θ) above the axis with
    |A − B| = l.  The law of cosines in O, A, B gives cos θ = (r² + x² − l²) / (2 r x);
    differentiating (r cos θ − x)² + (r sin θ)² = l² gives ω = ẋ (r cos θ − x) / (r x sin θ).
    """
    cos_t = (r * r + x * x - rod * rod) / (2 * r * x)
    th = math.acos(cos_t)  # A above the axis
    return th, v * (r * math.cos(th) - x) / (r * x * math.sin(th))
