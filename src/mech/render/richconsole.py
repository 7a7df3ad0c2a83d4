"""rich's console as mech prints reports on it: a closed pipe is the pipe's status, users' text is shown, not obeyed.

Made once (:func:`rich_console_class`) and used by both printers of a report: the terminal's
(:func:`mech.render.console.stdout`) and the plain one, when it hands a table to rich
(:class:`mech.render.plain.PlainConsole`).  Below both, so neither imports the other for it.
"""

from __future__ import annotations

from collections.abc import Iterable
from functools import lru_cache
from typing import TYPE_CHECKING

from mech._text import visible

if TYPE_CHECKING:  # pragma: no cover
    from rich.console import Console
    from rich.segment import Segment

__all__ = ["rich_console_class"]


@lru_cache(maxsize=1)
def rich_console_class() -> type[Console]:
    """rich's Console, except that a reader who closed the pipe is not a failed run,
    and that text from users' files cannot drive the terminal.

    rich answers EPIPE by exiting with status 1, which in mech means "a check
    failed"; this one stops writing and lets :func:`mech.entry.guarded` give the
    pipe's own status (141).  Every rich console mech prints reports with is one.
    """
    from rich.console import Console as RichConsole
    from rich.segment import Segment

    class Console(RichConsole):
        def on_broken_pipe(self) -> None:
            self.quiet = True
            raise BrokenPipeError

        def _render_buffer(self, buffer: Iterable[Segment]) -> str:
            # the one gate every report's text passes on its way out: a title, a path or a
            # claim from a user's file may hold a terminal escape or a direction override,
            # shown here as \x1b / \u202e (the rule of mech._text.visible); rich's own
            # colour codes are added after this, from the segments' styles
            return super()._render_buffer(
                s if s.control else Segment(visible(s.text), s.style) for s in buffer
            )

    return Console
