"""The ``mech`` console script: the commonest command lines run without importing click.

Importing click costs about two start-ups of the interpreter (it loads
``inspect``, ``uuid``, ``platform``, ``gettext`` …), more than counting a
four-bar's degrees of freedom.  So the plainest command lines of the hot
commands are recognised here and handed straight to their bodies in
:mod:`mech.commands`:

* ``mech dof [--json] [--mobility] FILE …``
* ``mech classify [--json] [FILE]``
* ``mech check PATH …`` with ``--junit``, ``--gradescope``, ``--csv``, ``--answers``,
  ``--jobs`` (``-j``), ``--timeout``, ``--quiet`` (``-q``), ``--verbose`` (``-v``), ``--json``;
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

import contextlib
import errno
import math
import os
import stat
import sys
from collections.abc import Callable, Sequence
from typing import Any

__all__ = ["main"]

_FLOATS = ("--rpm", "--omega", "--angle", "--speed", "--tol")
_CHOICES = {"--direction": ("cw", "ccw"), "--units": ("si", "mm", "cm")}
_KINEMATIC = ("position", "velocity", "acceleration")
_PATHS = ("--junit", "--gradescope", "--csv", "--answers")


def main(argv: Sequence[str] | None = None) -> None:
    """Entry point of the ``mech`` console script and ``python -m mech``."""
    args = prepare(sys.argv[1:] if argv is None else argv)
    run = _fast(args)
    if run is None:
        from mech.cli import run_click

        guarded(lambda: run_click(args))
        return
    # A batch's thousands of results need no tearing down: once its report is written and the
    # streams flushed, the process leaves without the interpreter's finalization (~15 ms for
    # 1,000 files, a fiftieth of the whole command).
    guarded(run, finalize=args[0] != "check")


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

        return lambda: classify_files(
            file=files[0] if files else "mechanism.yaml", as_json="--json" in options
        )
    if command == "check":
        return _check(rest)
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
    args: list[str],
    *,
    flags: Sequence[str],
    values: Sequence[str],
    short: dict[str, str] | None = None,
) -> tuple[list[str], dict[str, Any]] | None:
    """Positional arguments and converted options, or None for anything not plainly one of them.

    ``short``: one-letter spellings (``-j``) of long options, taken only alone (``-j 2``,
    never ``-j2``, ``-j=2`` or ``-qv``).
    """
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
        if short and token in short:
            name, eq, given = short[token], "", ""
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
    if name in _PATHS:
        return text
    if name == "--jobs":  # click.IntRange(min=1); only plain digits are taken here
        return int(text) if text.isascii() and text.isdigit() and int(text) >= 1 else None
    if name == "--timeout":  # click.FloatRange(min=0, min_open=True); only finite values here
        try:
            value = float(text)
        except ValueError:
            return None
        return value if 0 < value < math.inf else None
    try:
        return float(text)  # click.FLOAT converts with float() itself
    except ValueError:
        return None


def _files_ok(files: list[str]) -> bool:
    """click's ``Path(dir_okay=False)``: a folder is refused (by click, with its message)."""
    return not any(f != "-" and os.path.isdir(f) for f in files)


def _path_ok(path: str, *, exists: bool, dir_okay: bool = True) -> bool:
    """What click's ``Path(exists=…, dir_okay=…)`` accepts (it refuses the rest, with its message)."""
    try:
        st = os.stat(path)
    except OSError:
        return not exists
    if not dir_okay and stat.S_ISDIR(st.st_mode):
        return False
    return os.access(path, os.R_OK)


def _check(args: list[str]) -> Callable[[], None] | None:
    """``mech check PATH … [--junit F] [--gradescope F] [--csv F] [--answers P] [-j N] [--timeout S]
    [-q] [-v] [--json]``: the call click would make, or None."""
    read = _read(
        args,
        flags=("--quiet", "--verbose", "--json"),
        values=(*_PATHS, "--jobs", "--timeout"),
        short={"-q": "--quiet", "-v": "--verbose", "-j": "--jobs"},
    )
    if read is None:
        return None
    paths, options = read
    if not paths or not all(p != "-" and _path_ok(p, exists=True) for p in paths):
        return None
    answers = options.get("--answers")
    if answers is not None and not _path_ok(answers, exists=True):
        return None
    reports = [options.get(o) for o in ("--junit", "--gradescope", "--csv")]
    if not all(r is None or _path_ok(r, exists=False, dir_okay=False) for r in reports):
        return None
    from mech.batch import CheckOptions
    from mech.commands import check_paths, check_targets, check_usage

    targets = check_targets(*reports)
    if check_usage(answers, targets) is not None:
        return None  # click says it, as a usage error
    return lambda: check_paths(
        CheckOptions(  # inside the run: guarded answers whatever it could raise
            paths=tuple(paths),
            answers=answers,
            jobs=options.get("--jobs"),
            timeout=options.get("--timeout", 30.0),
        ),
        targets,
        quiet="--quiet" in options,
        verbose="--verbose" in options,
        as_json="--json" in options,
    )


def _kinematic(command: str, file: str, options: dict[str, Any]) -> Callable[[], None]:
    from mech.commands import Request, handles_errors, kinematics, solve_options
    from mech.options import OutputUnits

    @handles_errors(command=command)
    def run(*, file: str, as_json: bool) -> None:
        solved = solve_options(
            options.get("--rpm"),
            options.get("--omega"),
            options.get("--angle"),
            options.get("--direction"),
            options.get("--tol", 1e-12),
            options.get("--alpha"),
            options.get("--speed"),
        )
        request = Request(file, solved, OutputUnits.named(options.get("--units", "si")), as_json)
        kinematics(request, command, bool(options.get("--explain")))

    return lambda: run(file=file, as_json="--json" in options)


def _utf8(stream: Any) -> bool:
    encoding = (getattr(stream, "encoding", None) or "").lower().replace("-", "").replace("_", "")
    return encoding == "utf8"


# mech.commands.ExitStatus, written out so that a run that goes well imports nothing for them
INTERNAL_ERROR = 70
INTERRUPTED = 130
PIPE_CLOSED = 141
ISSUES_URL = "https://github.com/planar-mech/mech/issues"


def guarded(run: Callable[[], None], *, finalize: bool = True) -> None:
    """Run a command and exit so that a script can tell every way out apart.

    The command's own status (0, 1 a failed check, 2 bad input) is kept; an
    interrupt is 130 with one line; a reader that closed the pipe (``mech velocity
    f.yaml | head -1``) is 141 with no message; anything else is a bug in mech: 70,
    with one line saying so and how to report it (``MECH_DEBUG=1`` or ``--debug``
    before the command adds the traceback).  stdout is flushed here, before the
    interpreter's own last flush, so that a closed pipe is noticed while it can
    still be answered.  ``finalize=False``: leave by :func:`os._exit` once stdout and
    stderr are flushed, skipping the interpreter's finalization (atexit handlers, freeing
    every object), for a command that has closed its files and waited for its workers.
    """
    status: Any = 0
    try:
        try:
            run()
        except SystemExit as done:
            status = done.code
        sys.stdout.flush()
    except KeyboardInterrupt:
        _quiet_stdout()
        _say("mech: interrupted")
        status = INTERRUPTED
    except BrokenPipeError:
        _quiet_stdout()
        status = PIPE_CLOSED
    except Exception as error:  # the last line of defence: a bug, said to be one
        if isinstance(error, OSError) and error.errno == errno.EPIPE:
            _quiet_stdout()
            status = PIPE_CLOSED
        else:
            _report_bug(error)
            status = INTERNAL_ERROR
    if status is None:
        status = 0
    elif not isinstance(status, int):  # sys.exit("message"): printed, as the interpreter would
        _say(str(status))
        status = 1
    if not finalize:
        _leave(status)
    sys.exit(status)


def _leave(status: int) -> None:
    """Exit with ``status`` at once, after flushing stdout and stderr (see :func:`guarded`)."""
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError, ValueError, AttributeError):
            stream.flush()  # stdout was flushed by guarded (a closed pipe answered there)
    os._exit(status)


def prepare(argv: Sequence[str]) -> list[str]:
    """Set up what every command line needs before it runs; the arguments left to parse.

    A leading ``--debug`` (the group's option) is read here, so that the plain forms
    that skip click honour it too; streams that cannot encode Unicode get mech's
    ASCII spellings (:func:`_make_streams_safe`).
    """
    args = list(argv)
    if args[:1] == ["--debug"]:
        os.environ["MECH_DEBUG"] = "1"
        del args[0]
    _make_streams_safe()
    return args


def _say(line: str) -> None:
    """One line on stderr, whatever state the streams are in."""
    try:
        sys.stderr.write(line + "\n")
        sys.stderr.flush()
    except (OSError, ValueError):
        pass


def _quiet_stdout() -> None:
    """Point stdout at the null device, so the interpreter's last flush cannot fail again."""
    try:
        null = os.open(os.devnull, os.O_WRONLY)
        os.dup2(null, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):
        pass


def debugging() -> bool:
    """True when a bug should show its traceback (``MECH_DEBUG`` set, not 0 or empty)."""
    return os.environ.get("MECH_DEBUG", "") not in ("", "0")


def _report_bug(error: BaseException) -> None:
    """One line saying mech failed (not the user's file), and how to report it."""
    import traceback

    from mech import __version__
    from mech._text import visible

    if debugging():
        traceback.print_exception(error)
    frames = traceback.extract_tb(error.__traceback__) if error.__traceback__ else []
    at = f" at {os.path.basename(frames[-1].filename)}:{frames[-1].lineno}" if frames else ""
    message = visible(
        f"{type(error).__name__}: {error}".splitlines()[0] if str(error) else type(error).__name__
    )
    _say(
        f"mech: internal error{at}: {message}\n"
        f"  This is a bug in mech {__version__}, not in your input. Please report it at {ISSUES_URL} "
        "with the command line and the file; run it again as mech --debug … (or with MECH_DEBUG=1) to include the traceback."
    )


def _make_streams_safe() -> None:
    """Let output reach a terminal or file that cannot encode all of Unicode.

    mech writes θ, ω, α, °, − and box rules; a Windows console or a C-locale
    redirect may only take ASCII.  There they are spelt out (``omega``, ``deg``,
    ``-``) instead of crashing with UnicodeEncodeError; other characters become
    ``\\uNNNN`` escapes.  A UTF-8 stream (the usual case) is left alone.
    """
    for stream in (sys.stdout, sys.stderr):
        if stream is None or _utf8(stream) or not hasattr(stream, "reconfigure"):
            continue
        from mech._text import register_ascii_fallback

        register_ascii_fallback()
        with contextlib.suppress(AttributeError, ValueError, OSError):
            stream.reconfigure(errors="mech-spell")
