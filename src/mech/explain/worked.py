"""A result worked out line by line, each line a formula with its numbers: what a cam's law or a gear
train's value looks like written out in the notes' style.

Each :class:`Line` keeps, besides its sentence, the formula's name, the inputs it was
given (SI) and the value it gives, so a test (or a student) can rebuild the result from
the written steps alone.
"""

from __future__ import annotations

from dataclasses import field
from typing import Any

from mech._records import dataclass

__all__ = ["Line", "Worked", "g"]


def g(x: float) -> str:
    """A number as the notes write it: five significant figures, no trailing noise."""
    if x == 0 or abs(x) < 1e-12:
        return "0"
    return f"{x:.5g}"


@dataclass(frozen=True, slots=True)
class Line:
    """One line of working: ``text`` as printed; ``quantity = formula`` evaluated at ``inputs`` is ``value``."""

    text: str
    quantity: str | None = None
    formula: str | None = None
    inputs: dict[str, float] = field(default_factory=dict)
    value: float | None = None
    unit: str | None = None


@dataclass(frozen=True, slots=True)
class Worked:
    """A worked result: ``kind`` (``cam``, ``gear train``), the mechanism's name, its lines."""

    mechanism: str
    kind: str
    lines: tuple[Line, ...]

    def text(self) -> str:
        """The working as the notes write it, one line a step."""
        return "\n".join(
            [f"{self.kind.capitalize()} of {self.mechanism}, worked out:", *(ln.text for ln in self.lines)]
        )

    def as_dict(self) -> dict[str, Any]:
        """For ``--json`` (SI)."""
        return {
            "kind": self.kind,
            "lines": [
                {
                    "text": ln.text,
                    "quantity": ln.quantity,
                    "formula": ln.formula,
                    "inputs": dict(ln.inputs),
                    "value": ln.value,
                    "unit": ln.unit,
                }
                for ln in self.lines
            ],
        }
