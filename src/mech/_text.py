"""Text from users' files made visible: control and direction characters shown as escapes.

A name, a title, a claim or a file name can carry any character a YAML string can: an
escape sequence that would drive the reader's terminal, or a right-to-left override that
makes ``crank`` print as ``knarc`` and a table lie about which row is which.  Wherever
such text is shown to a person it goes through :func:`visible`, which writes those
characters as ``\\x1b`` / ``\\u202e`` escapes and leaves every other character (accents,
Greek, Arabic or Hebrew letters) as it is.

It lives below every layer (no imports) so the loader, the error messages and the
renderers share one rule.
"""

from __future__ import annotations

import re

__all__ = ["INVISIBLE", "NOT_XML", "register_ascii_fallback", "visible", "xml_safe"]

# C0 controls but tab and newline, DEL, the C1 controls (CSI and friends), and the
# invisible format characters that reorder or hide text: Arabic letter mark, zero-width
# space/joiners and the left/right marks, the bidi embeddings, overrides and isolates,
# word joiner and invisible operators, the BOM as a zero-width no-break space, and the
# interlinear annotation controls.
INVISIBLE = re.compile(
    "[\x00-\x08\x0b-\x1f\x7f-\x9f\u061c\u200b-\u200f\u202a-\u202e\u2060-\u2069\ufeff\ufff9-\ufffb]"
)


def _escape(match: re.Match[str]) -> str:
    code = ord(match.group())
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def visible(text: str) -> str:
    """``text`` with control and invisible direction characters shown as ``\\xNN``/``\\uNNNN``."""
    return INVISIBLE.sub(_escape, text)


# what XML 1.0 forbids anywhere in a document (tab, newline and carriage return are allowed)
NOT_XML = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\ufffe\uffff]")


def xml_safe(document: str) -> str:
    """A serialised XML or SVG document with the characters XML 1.0 forbids shown as ``\\xNN``.

    Safe on a whole document: those characters never occur in markup itself.  Here, below every
    layer, so that the drawings' SVG writer and the check reports' JUnit share it without the
    drawings importing the report (:mod:`mech.render.safe` re-exports it).
    """
    return NOT_XML.sub(_escape, document)


# how mech's own symbols are spelt where the output cannot encode them
_SPELLINGS = {
    "θ": "theta",
    "ω": "omega",
    "α": "alpha",
    "φ": "phi",
    "ψ": "psi",
    "γ": "gamma",
    "β": "beta",
    "μ": "u",
    "Δ": "delta",
    "Σ": "sum",
    "π": "pi",
    "ρ": "rho",
    "τ": "tau",
    "σ": "sigma",
    "°": " deg",
    "−": "-",
    "–": "-",
    "—": "--",
    "·": "*",
    "×": "x",
    "²": "^2",
    "³": "^3",
    "′": "'",
    "″": "''",
    "→": "->",
    "←": "<-",
    "≈": "~",
    "≤": "<=",
    "≥": ">=",
    "≠": "!=",
    "⟂": "perp",
    "∠": "angle ",
    "∞": "inf",
    "…": "...",
    "│": "|",
    "─": "-",
    "━": "-",
    "┃": "|",
}


def _spell(error: UnicodeError) -> tuple[str, int]:
    if not isinstance(error, UnicodeEncodeError):
        raise error
    chunk = error.object[error.start : error.end]
    out = []
    for ch in chunk:
        spelt = _SPELLINGS.get(ch)
        out.append(
            spelt
            if spelt is not None
            else (
                f"\\x{ord(ch):02x}"
                if ord(ch) < 0x100
                else f"\\u{ord(ch):04x}"
                if ord(ch) < 0x10000
                else f"\\U{ord(ch):08x}"
            )
        )
    return "".join(out), error.end


def register_ascii_fallback() -> None:
    """Register the ``mech-spell`` codec error handler: symbols spelt out, the rest escaped."""
    import codecs

    codecs.register_error("mech-spell", _spell)
