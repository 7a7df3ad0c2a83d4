"""The ``mech`` console script: the commonest command lines run without importing click.

Importing click costs about two start-ups of the interpreter (it loads
``inspect``, ``uuid``, ``platform``, ``gettext`` …), more than counting a
four-bar's degrees of freedom.  So the plainest command lines of the hot
commands are recognised here and handed straight to their bodies in
:mod:`mech.commands`:

* ``mech dof [--json] [--mobility] FILE …``
* ``mech classify [--json] [FILE]``
* ``mech position|velocity|acceleration [FILE]`` with ``--rpm``, ``--omega``,
  ``--angle``, ``--speed``, ``--direction``, ``--tol``, ``--units``,
  ``--json`` (and ``--explain``; ``--alpha`` for acceleration).

Each form is a sentence of click's grammar that click would parse to the same
call: options spelt exactly (``--rpm 600`` or ``--rpm=600``, the last of a
repeated one wins), values that convert as click converts them (``float``,
an exact choice), paths that are not folders.  Anything else — ``--help``,
``--``, a misspelt or abbreviated option, a value click would refuse, a
folder, another command, an output stream that is not UTF-8 — goes to
:mod:`mech.cli`, where click parses it and answers as it always has.  A new
option of these commands is only ever handled by click until it is added
here, so forgetting this module costs speed, never behaviour.
"""

from __future__ import annotations

import errno
import os
import sys
from collections.abc import Callable, Sequence
from typing import Any

__all__ = ["main"]

_FLOATS = ("--rpm", "--omega", "--angle", "--speed", "--tol")
_CHOICES = {"--direction": ("cw", "ccw"), "--units": ("si", "mm", "cm")}
_KINEMATIC = ("position", "velocity", "acceleration")


def main(argv: Sequence[str] | None = None) -> None:
    """Entry point of the ``mech`` console script and ``python -m mech``."""
    args = list(sys.argv[1:] if argv is None else argv)
    run = _fast(args)
    if run is None:
        from mech.cli import main as click_main

        click_main(args)
        return
    _standalone(run)


def _fast(args: list[str]) -> Callable[[], None] | None:
    """The call click would make for ``args``, or None when click must read them."""
    if not args or not (_utf8(sys.stdout) and _utf8(sys.stderr)):
        return None
    command, rest = args[0], args[1:]
    if command == "dof":
        read = _read(rest, flags=("--json", "--mobility"), values=())
        if read is None or not _files_ok(read[0] or ["mechanism.yaml"]):
            return None
        files, options = read
        from mech.commands import count_dof

        return lambda: count_dof(tuple(files), "--mobility" in options, "--json" in options)
    if command == "classify":
        read = _read(rest, flags=("--json",), values=())
        if read is None or len(read[0]) > 1 or not _files_ok(read[0] or ["mechanism.yaml"]):
            return None
        files, options = read
        from mech.commands import classify_files

        return lambda: classify_files(files[0] if files else "mechanism.yaml", "--json" in options)
    if command in _KINEMATIC:
        flags = ("--json",) if command == "position" else ("--json", "--explain")
        values = (*_FLOATS, *_CHOICES, *(("--alpha",) if command == "acceleration" else ()))
        read = _read(rest, flags=flags, values=values)
        if read is None or len(read[0]) > 1 or not _files_ok(read[0] or ["mechanism.yaml"]):
            return None
        files, options = read
        return _kinematic(command, files[0] if files else "mechanism.yaml", options)
    return None


def _read(
    args: list[str], *, flags: Sequence[str], values: Sequence[str]
) -> tuple[list[str], dict[str, Any]] | None:
    """Positional arguments and converted options, or None for anything not plainly one of them."""
    positional: list[str] = []
    options: dict[str, Any] = {}
    i = 0
    while i < len(args):
        token = args[i]
        i += 1
        if token == "-" or not token.startswith("-"):
            positional.append(token)
            continue
        name, eq, given = token.partition("=")
        if name in flags and not eq:
            options[name] = True
        elif name in values:
            if not eq:
                if i == len(args):
                    return None
                given = args[i]
                i += 1
            value = _convert(name, given)
            if value is None:
                return None
            options[name] = value
        else:
            return None
    return positional, options


def _convert(name: str, text: str) -> Any:
    """``text`` as click converts it for option ``name``; None where click would refuse it."""
    if name in _CHOICES:
        return text if text in _CHOICES[name] else None
    try:
        return float(text)  # click.FLOAT converts with float() itself
    except ValueError:
        return None


def _files_ok(files: list[str]) -> bool:
    """click's ``Path(dir_okay=False)``: a folder is refused (by click, with its message)."""
    return not any(f != "-" and os.path.isdir(f) for f in files)


def _kinematic(command: str, file: str, options: dict[str, Any]) -> Callable[[], None]:
    from mech.commands import Request, handles_errors, kinematics, solve_options
    from mech.options import OutputUnits

    @handles_errors
    def run() -> None:
        solved = solve_options(
            options.get("--rpm"),
            options.get("--omega"),
            options.get("--angle"),
            options.get("--direction"),
            options.get("--tol", 1e-12),
            options.get("--alpha"),
            options.get("--speed"),
        )
        request = Request(file, solved, OutputUnits.named(options.get("--units", "si")), "--json" in options)
        kinematics(request, command, bool(options.get("--explain")))

    return run


def _utf8(stream: Any) -> bool:
    encoding = (getattr(stream, "encoding", None) or "").lower().replace("-", "").replace("_", "")
    return encoding == "utf8"


def _standalone(run: Callable[[], None]) -> None:
    """Run as click's standalone mode runs a command: the same exits on ^C and a closed pipe."""
    try:
        run()
    except (EOFError, KeyboardInterrupt):
        from mech.commands import echo

        echo("", err=True)
        echo("Aborted!", err=True)
        sys.exit(1)
    except OSError as error:
        if error.errno != errno.EPIPE:
            raise
        import click.utils

        pacify: Any = click.utils.PacifyFlushWrapper  # what click's standalone mode does on EPIPE
        sys.stdout = pacify(sys.stdout)
        sys.stderr = pacify(sys.stderr)
        sys.exit(1)
    sys.exit(0)
