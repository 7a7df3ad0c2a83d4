"""The small unit table: read ``"40 mm"`` or ``"4.8 rad/s cw"``, write SI.

Every quantity inside mech is SI (m, rad, s).  Units appear only at the two
edges: when a file is read (a bare number is in the file's ``units``, a string
may carry its own unit) and when a report is written.
"""

from __future__ import annotations

import math
import re
from enum import Enum

from mech._records import dataclass

__all__ = [
    "MAGNITUDE_RANGE",
    "Dimension",
    "Quantity",
    "format_unit",
    "parse_number",
    "parse_quantity",
    "to_unit",
    "unit_factor",
]


#: Magnitudes a file may give, in SI units: wider than any machine (a micro-hinge of
#: 1 µm to a crane of 1 km, speeds from 1e-6 to 1e6 rpm) and narrow enough that squares
#: and products of them (ω²r, r⁴ in a determinant) stay finite and normal in floating point.
MAGNITUDE_RANGE = (1e-30, 1e30)


class Dimension(str, Enum):
    """What a number measures; the value is the SI unit it is stored in."""

    LENGTH = "m"
    ANGLE = "rad"
    ANGULAR_VELOCITY = "rad/s"
    VELOCITY = "m/s"
    ACCELERATION = "m/s^2"
    ANGULAR_ACCELERATION = "rad/s^2"
    TIME = "s"
    FORCE = "N"
    TORQUE = "N m"
    MASS = "kg"
    MOMENT_OF_INERTIA = "kg m^2"
    ENERGY = "J"
    NUMBER = "1"

    @property
    def label(self) -> str:
        return self.name.lower().replace("_", " ")


_TWO_PI = 2.0 * math.pi
_DEG = math.pi / 180.0

# unit spelling -> (dimension, factor to SI)
_UNITS: dict[str, tuple[Dimension, float]] = {
    # length
    "m": (Dimension.LENGTH, 1.0),
    "mm": (Dimension.LENGTH, 1e-3),
    "cm": (Dimension.LENGTH, 1e-2),
    "dm": (Dimension.LENGTH, 1e-1),
    "km": (Dimension.LENGTH, 1e3),
    "um": (Dimension.LENGTH, 1e-6),
    "µm": (Dimension.LENGTH, 1e-6),
    "in": (Dimension.LENGTH, 0.0254),
    "ft": (Dimension.LENGTH, 0.3048),
    # angle
    "rad": (Dimension.ANGLE, 1.0),
    "deg": (Dimension.ANGLE, _DEG),
    "°": (Dimension.ANGLE, _DEG),
    "rev": (Dimension.ANGLE, _TWO_PI),
    # angular velocity
    "rad/s": (Dimension.ANGULAR_VELOCITY, 1.0),
    "rpm": (Dimension.ANGULAR_VELOCITY, _TWO_PI / 60.0),
    "rev/min": (Dimension.ANGULAR_VELOCITY, _TWO_PI / 60.0),
    "r.p.m.": (Dimension.ANGULAR_VELOCITY, _TWO_PI / 60.0),
    "rps": (Dimension.ANGULAR_VELOCITY, _TWO_PI),
    "rev/s": (Dimension.ANGULAR_VELOCITY, _TWO_PI),
    "deg/s": (Dimension.ANGULAR_VELOCITY, _DEG),
    # velocity
    "m/s": (Dimension.VELOCITY, 1.0),
    "mm/s": (Dimension.VELOCITY, 1e-3),
    "cm/s": (Dimension.VELOCITY, 1e-2),
    "km/h": (Dimension.VELOCITY, 1.0 / 3.6),
    "m/min": (Dimension.VELOCITY, 1.0 / 60.0),
    "in/s": (Dimension.VELOCITY, 0.0254),
    "ft/s": (Dimension.VELOCITY, 0.3048),
    "ft/min": (Dimension.VELOCITY, 0.3048 / 60.0),
    # acceleration
    "m/s^2": (Dimension.ACCELERATION, 1.0),
    "mm/s^2": (Dimension.ACCELERATION, 1e-3),
    "cm/s^2": (Dimension.ACCELERATION, 1e-2),
    "in/s^2": (Dimension.ACCELERATION, 0.0254),
    "ft/s^2": (Dimension.ACCELERATION, 0.3048),
    "g": (Dimension.ACCELERATION, 9.80665),
    # angular acceleration
    "rad/s^2": (Dimension.ANGULAR_ACCELERATION, 1.0),
    "deg/s^2": (Dimension.ANGULAR_ACCELERATION, _DEG),
    "rpm/s": (Dimension.ANGULAR_ACCELERATION, _TWO_PI / 60.0),
    # force and torque (loads)
    "N": (Dimension.FORCE, 1.0),
    "kN": (Dimension.FORCE, 1e3),
    "lbf": (Dimension.FORCE, 4.4482216152605),
    "Nm": (Dimension.TORQUE, 1.0),
    "N·m": (Dimension.TORQUE, 1.0),
    "N.m": (Dimension.TORQUE, 1.0),
    "Nmm": (Dimension.TORQUE, 1e-3),
    "N·mm": (Dimension.TORQUE, 1e-3),
    "kNm": (Dimension.TORQUE, 1e3),
    "kN·m": (Dimension.TORQUE, 1e3),
    # mass and moment of inertia (DESIGN § 1.4); a bare `g` is the acceleration of gravity
    "kg": (Dimension.MASS, 1.0),
    "t": (Dimension.MASS, 1e3),
    "lb": (Dimension.MASS, 0.45359237),
    "kgm^2": (Dimension.MOMENT_OF_INERTIA, 1.0),
    "kg·m^2": (Dimension.MOMENT_OF_INERTIA, 1.0),
    "kg*m^2": (Dimension.MOMENT_OF_INERTIA, 1.0),
    "kgcm^2": (Dimension.MOMENT_OF_INERTIA, 1e-4),
    "kg·cm^2": (Dimension.MOMENT_OF_INERTIA, 1e-4),
    "kgmm^2": (Dimension.MOMENT_OF_INERTIA, 1e-6),
    "kg·mm^2": (Dimension.MOMENT_OF_INERTIA, 1e-6),
    # energy (a flywheel's fluctuation of energy)
    "J": (Dimension.ENERGY, 1.0),
    "kJ": (Dimension.ENERGY, 1e3),
    "N·m·rad": (Dimension.ENERGY, 1.0),
    # time
    "s": (Dimension.TIME, 1.0),
    "ms": (Dimension.TIME, 1e-3),
    "min": (Dimension.TIME, 60.0),
}

_NUMBER = r"[+-]?(?:\d+(?:[_\d]*)(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?"
# compiled once: each is matched a dozen times per file read (the module-level re functions
# re-format and look the pattern up in re's cache on every call)
_PLAIN_NUMBER = re.compile(_NUMBER.replace("[_\\d]*", "\\d*"))
_QUANTITY = re.compile(rf"^\s*({_NUMBER})\s*(.*?)\s*$")
_SENSE = re.compile(r"\s+(cw|ccw|CW|CCW|clockwise|anticlockwise|counterclockwise|counter-clockwise)$")
_PER_S2 = re.compile(r"/s2$")


def _normalise_unit(unit: str) -> str:
    """Spellings users write for the same unit: ``m/s²``, ``m/s2``, ``m/sec^2``, ``RPM``."""
    u = unit.strip().replace("²", "^2").replace("**2", "^2").replace("sec", "s")
    u = _PER_S2.sub("/s^2", u)
    u = u.replace(" ", "")
    if u.lower() in ("rpm", "r.p.m.", "r.p.m", "rev/min"):
        return "rpm"
    if u in ("radians", "radian"):
        return "rad"
    if u in ("degree", "degrees"):
        return "deg"
    return u


def unit_factor(unit: str) -> tuple[Dimension, float]:
    """The dimension of ``unit`` and its factor to SI.

    Raises
    ------
    KeyError
        If the unit is unknown (the loader turns this into a located error).
    """
    return _UNITS[_normalise_unit(unit)]


def known_units(dimension: Dimension, *, ascii_only: bool = True) -> list[str]:
    """Unit spellings of one dimension: ASCII ones for hints in error messages, all for the schema."""
    return [u for u, (d, _) in _UNITS.items() if d is dimension and (u.isascii() or not ascii_only)]


def parse_number(text: str) -> float:
    """A plain number as YAML 1.1 fails to read it: ``1e3`` is 1000, not a string.

    Raises ``ValueError`` for anything else, including NaN and infinity,
    which have no place in a mechanism.
    """
    s = text.strip().replace("_", "")
    if not _PLAIN_NUMBER.fullmatch(s):
        raise ValueError(f"{text!r} is not a number")
    value = float(s)
    if not math.isfinite(value):
        raise ValueError(f"{text!r} is not a finite number")
    return value


@dataclass(frozen=True, slots=True)
class Quantity:
    """A number read from text, in SI, with the dimension its unit named.

    ``dimension`` is None for a bare number (its unit comes from context);
    ``sense`` is ``"cw"`` or ``"ccw"`` when the text ended with one.
    """

    value: float
    dimension: Dimension | None
    unit: str | None = None
    sense: str | None = None


def parse_quantity(text: str) -> Quantity:
    """Read ``"40 mm"``, ``"600 rpm"``, ``"4.8 rad/s cw"``, ``"126 m/s^2"`` or ``"1e3"``.

    Examples
    --------
    >>> parse_quantity("12 cm").value
    0.12
    >>> q = parse_quantity("10 rpm ccw"); round(q.value, 6), q.sense
    (1.047198, 'ccw')

    Raises
    ------
    ValueError
        When the text is not a number followed by an optional unit.
    KeyError
        When the unit is unknown.
    """
    s = text.strip()
    sense = None
    m = _SENSE.search(s)
    if m:
        word = m.group(1).lower()
        sense = "cw" if word in ("cw", "clockwise") else "ccw"
        s = s[: m.start()].strip()
    m = _QUANTITY.match(s)
    if not m:
        raise ValueError(f"{text!r} is not a number with a unit")
    value = parse_number(m.group(1))
    unit = m.group(2)
    if not unit:
        return Quantity(value, None, None, sense)
    try:
        dimension, factor = unit_factor(unit)
    except KeyError:
        raise KeyError(unit.strip()) from None  # name the unit as written, not as normalised
    if not math.isfinite(value * factor):
        raise ValueError(f"{text!r} is too large: it overflows in SI units")
    return Quantity(value * factor, dimension, _normalise_unit(unit), sense)


def to_unit(value: float, unit: str) -> float:
    """Convert an SI value to ``unit`` (``to_unit(0.385, "mm/s") == 385.0``)."""
    return value / unit_factor(unit)[1]


def format_unit(unit: str) -> str:
    """Pretty unit for reports: ``m/s^2`` → ``m/s²``."""
    return unit.replace("^2", "²")
