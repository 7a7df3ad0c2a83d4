"""The one place that decides colour and width (rich honours NO_COLOR and non-tty)."""

from __future__ import annotations

import os
from functools import lru_cache
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # pragma: no cover
    from rich.box import Box
    from rich.console import Console


@lru_cache(maxsize=1)
def stdout() -> Console:
    """The console for reports.  Piped output is plain text, $COLUMNS (default 120) wide."""
    from rich.console import Console

    # markup=False: names, claims and messages come from users' files, and "[/b]" in a
    # mechanism's name must print as written, not be read (or fail) as rich markup.
    # Styles are given as Text styles instead.
    console = Console(highlight=False, markup=False)
    if not console.is_terminal:
        width = int(os.environ.get("COLUMNS", 120))
        return Console(highlight=False, markup=False, width=width, color_system=None)
    if os.environ.get("NO_COLOR"):
        # rich drops colour for NO_COLOR but keeps bold; we promise plain text
        return Console(highlight=False, markup=False, color_system=None)
    return console


def is_plain(console: Console) -> bool:
    """True when the console writes plain text (not a terminal, or NO_COLOR set)."""
    return not console.is_terminal or console.no_color or console.color_system is None


def table_box(console: Console) -> Box:
    """Rounded boxes on a terminal, simple ruled text otherwise."""
    from rich import box

    return box.SIMPLE if is_plain(console) else box.ROUNDED
