"""The ``mech`` console script: the commonest command lines run without importing click.

Importing click costs about two start-ups of the interpreter (it loads
``inspect``, ``uuid``, ``platform``, ``gettext`` …), more than counting a
four-bar's degrees of freedom.  So the plainest command lines of the hot
commands (:data:`mech.commands.params.FAST`: ``dof``, ``classify``, ``check``,
``position``, ``velocity``, ``acceleration``) are read here, from the same
declarations click's commands are built from (:mod:`mech.commands.params`), and
handed straight to their bodies in :mod:`mech.commands`.

Each form taken is one that click would parse to the same call: options spelt
exactly (``--rpm 600`` or ``--rpm=600``, the last of a repeated one wins), values
that convert as click converts them, paths that click would accept.  Anything else
— ``--help``, ``--``, a misspelt or abbreviated option, a value click would refuse,
another command, an output stream that is not UTF-8 — goes to :mod:`mech.cli`,
where click parses it and answers as it always has.

Everything, from reading the arguments to importing click, runs inside
:func:`mech.commands.exits.guarded`: a Ctrl-C at any moment after this module is
loaded exits 130 with one line, never a traceback.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Sequence

__all__ = ["main"]


def main(argv: Sequence[str] | None = None) -> None:
    """Entry point of the ``mech`` console script and ``python -m mech``."""
    from mech._blas import one_thread

    one_thread()  # before any command imports numpy
    try:
        from mech.commands.exits import guarded
    except KeyboardInterrupt:  # Ctrl-C while the guard itself loads: the guard's answer, by hand
        sys.stderr.write("mech: interrupted\n")
        raise SystemExit(130) from None

    batch = [False]

    def run() -> None:
        from mech.commands.exits import prepare

        args = prepare(sys.argv[1:] if argv is None else argv)
        body = _fast(args)
        if body is None:
            from mech.cli import run_click

            run_click(args)
            return
        batch[0] = args[0] == "check"
        body()

    # A batch's thousands of results need no tearing down: once its report is written and the
    # streams flushed, the process leaves without the interpreter's finalization (~15 ms for
    # 1,000 files, a fiftieth of the whole command).
    guarded(run, finalize=lambda: not batch[0])


def _fast(args: list[str]) -> Callable[[], None] | None:
    """The call click would make for ``args``, or None when click must read them."""
    from mech.commands.exits import is_utf8
    from mech.commands.params import FAST, read

    if not args or args[0] not in FAST or not (is_utf8(sys.stdout) and is_utf8(sys.stderr)):
        return None
    command = args[0]
    values = read(command, args[1:])
    if values is None:
        return None
    from mech.commands import check_usage, run_command

    if command == "check" and check_usage(values) is not None:
        return None  # click says it, as a usage error
    return lambda: run_command(command, values)
