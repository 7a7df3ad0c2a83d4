"""The grammar of ``answers`` keys: what each claims and in which dimension.

Shared by the loader (to validate a file at once, with locations) and by
``mech check`` (to compute only what the claims ask for).
"""

from __future__ import annotations

from dataclasses import dataclass

from mech.units import Dimension

__all__ = ["COUNT_KEYS", "KEY_FORMS", "LINK_CLASSES", "AnswerKey", "parse_key"]

LINK_CLASSES = ("singular", "binary", "ternary", "quaternary", "pentagonal", "hexagonal")

#: Keys that claim an integer count (or a chain name), no geometry needed.
COUNT_KEYS = frozenset(
    {
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
    }
)

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

#: Every form a key may take, for hints.
KEY_FORMS = (
    "dof",
    "mobility",
    "chain",
    "links.count",
    *(f"links.{c}" for c in LINK_CLASSES),
    "joints.count",
    "joints.binary",
    "joints.ternary",
    "joints.quaternary",
    "joints.equivalent_binary",
    "higher_pairs",
    "icentres.count",
    "velocity.<point>",
    "velocity.<point>.<other>",
    "omega.<link>",
    "omega_ratio.<a>.<b>",
    "sliding.<joint>",
    "rubbing.<joint>",
    "least_speed.<link>",
    "acceleration.<point>",
    "acceleration.<point>.<other>",
    "alpha.<link>",
    "coriolis.<joint>",
    "icentre.<a>.<b>",
    "distance.<p>.<q>",
)


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
