"""The grammar of ``answers`` keys: what each claims and in which dimension.

Shared by the loader (to validate a file at once, with locations) and by
``mech check`` (to compute only what the claims ask for).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from mech.units import Dimension

__all__ = [
    "COUNT_KEYS",
    "KEY_FORMS",
    "LINK_CLASSES",
    "AnswerKey",
    "icentre_name",
    "parse_icentre_name",
    "parse_key",
]

LINK_CLASSES = ("singular", "binary", "ternary", "quaternary", "pentagonal", "hexagonal")

#: Keys that claim an integer count, no geometry needed (in the order cli.md lists them).
_COUNTS = (
    "dof",
    "links.count",
    *(f"links.{c}" for c in LINK_CLASSES),
    "joints.count",
    "joints.binary",
    "joints.ternary",
    "joints.quaternary",
    "joints.equivalent_binary",
    "higher_pairs",
    "icentres.count",
)
COUNT_KEYS = frozenset(_COUNTS)

# family -> (number of names after it, what the names are, dimension, level needed)
# kinds: "point" = joint or named point, "link", "joint", "icpoint" = point or I-centre name
_FAMILIES: dict[str, tuple[tuple[int, ...], tuple[str, ...], Dimension | None, str]] = {
    "velocity": ((1, 2), ("point", "point"), Dimension.VELOCITY, "velocity"),
    "omega": ((1,), ("link",), Dimension.ANGULAR_VELOCITY, "velocity"),
    "omega_ratio": ((2,), ("link", "link"), Dimension.NUMBER, "velocity"),
    "sliding": ((1,), ("joint",), Dimension.VELOCITY, "velocity"),
    "rubbing": ((1,), ("joint",), Dimension.VELOCITY, "velocity"),
    "least_speed": ((1,), ("link",), Dimension.VELOCITY, "velocity"),
    "acceleration": ((1, 2), ("point", "point"), Dimension.ACCELERATION, "acceleration"),
    "alpha": ((1,), ("link",), Dimension.ANGULAR_ACCELERATION, "acceleration"),
    "coriolis": ((1,), ("joint",), Dimension.ACCELERATION, "acceleration"),
    "icentre": ((2,), ("link", "link"), Dimension.LENGTH, "velocity"),
    "distance": ((2,), ("icpoint", "icpoint"), Dimension.LENGTH, "velocity"),
}

_PLACEHOLDERS = {"point": "<point>", "link": "<link>", "joint": "<joint>", "icpoint": "<p>"}


def _forms(family: str) -> list[str]:
    """``velocity.<point>``, ``velocity.<point>.<other>`` … for one family."""
    counts, kinds, _, _ = _FAMILIES[family]
    out = []
    for n in counts:
        names = [_PLACEHOLDERS[k] for k in kinds[:n]]
        if n == 2:
            names[1] = "<other>" if kinds[1] == kinds[0] and family in ("velocity", "acceleration") else "<b>"
            names[0] = names[0] if names[1] == "<other>" else "<a>"
        out.append(".".join([family, *names]))
    return out


#: Every form a key may take, for hints.
KEY_FORMS = (*_COUNTS, "mobility", "chain", *(form for family in _FAMILIES for form in _forms(family)))


@dataclass(frozen=True, slots=True)
class AnswerKey:
    """A parsed key: ``family`` (``omega``), the ``names`` after it, what they must be.

    ``level`` is the analysis a claim needs: ``topology`` (counts),
    ``mobility`` (Jacobian rank), ``velocity`` or ``acceleration``.
    """

    family: str
    names: tuple[str, ...]
    kinds: tuple[str, ...]
    dimension: Dimension | None
    level: str

    @property
    def is_count(self) -> bool:
        return self.level in ("topology", "mobility")


def parse_key(key: str) -> AnswerKey:
    """Split an answers key and say what it needs.

    Raises ``ValueError`` with a readable reason when the key has no known form.
    """
    if key in COUNT_KEYS:
        return AnswerKey(key, (), (), Dimension.NUMBER, "topology")
    if key == "chain":
        return AnswerKey(key, (), (), None, "topology")
    if key == "mobility":
        return AnswerKey(key, (), (), Dimension.NUMBER, "mobility")
    family, _, rest = key.partition(".")
    if family not in _FAMILIES:
        raise ValueError(f"unknown answer key {key!r}")
    counts, kinds, dimension, level = _FAMILIES[family]
    names = tuple(rest.split(".")) if rest else ()
    if len(names) not in counts or any(not n for n in names):
        forms = " or ".join(f for f in KEY_FORMS if f.startswith(family + "."))
        raise ValueError(f"{key!r} does not have the form {forms}")
    return AnswerKey(family, names, kinds[: len(names)], dimension, level)


def icentre_name(a: int, b: int) -> str:
    """The textbook name of the I-centre of links numbered ``a`` and ``b`` (ground = 1).

    ``I13`` while both numbers are single digits; ``I1,12`` beyond, where ``I112``
    would be ambiguous.
    """
    a, b = min(a, b), max(a, b)
    return f"I{a}{b}" if b < 10 else f"I{a},{b}"


_IC_NAME = re.compile(r"^I(?:(\d)(\d)|(\d+),(\d+))$")


def parse_icentre_name(name: str) -> tuple[int, int] | None:
    """``I13`` → (1, 3); ``I1,12`` → (1, 12); anything else → None."""
    m = _IC_NAME.match(name)
    if not m:
        return None
    a, b = (int(g) for g in (m.groups()[:2] if m.group(1) else m.groups()[2:]))
    return (a, b) if a != b else None
