"""Every way out of a command line, each with its own status: what both parsers run their commands in.

:mod:`mech.entry` (the console script, fast path) and :mod:`mech.cli` (click) both run a
command line inside :func:`guarded`, after :func:`prepare`; living here, below both, neither
imports the other for it.  Nothing heavy is imported: a run that goes well loads only this.
"""

from __future__ import annotations

import contextlib
import errno
import os
import sys
from collections.abc import Callable, Sequence
from enum import IntEnum

__all__ = ["REPORTING", "ExitStatus", "debugging", "guarded", "is_utf8", "prepare"]


class ExitStatus(IntEnum):
    """What ``mech`` returns to the shell (cli.md, "Exit statuses"); no other status is returned."""

    OK = 0
    CHECK_FAILED = 1
    BAD_INPUT = 2
    # sysexits.h's EX_SOFTWARE: a bug in mech, never confused with a failed check or bad input
    INTERNAL_ERROR = 70
    # what a shell reports for a process SIGINT or SIGPIPE stopped (128 + the signal's number)
    INTERRUPTED = 130
    PIPE_CLOSED = 141


#: Where the internal-error message sends a user: README's section, which says what to include.
REPORTING = 'README.md, "Reporting a bug"'

#: A full disk or quota on standard output: the user's output cannot be written, not a bug.
_FULL = frozenset(
    code
    for code in (errno.ENOSPC, getattr(errno, "EDQUOT", None), errno.EFBIG, errno.EIO)
    if code is not None
)


def guarded(run: Callable[[], None], *, finalize: bool | Callable[[], bool] = True) -> None:
    """Run a command and exit so that a script can tell every way out apart.

    The command's own status (0, 1 a failed check, 2 bad input) is kept; an
    interrupt is 130 with one line; a reader that closed the pipe (``mech velocity
    f.yaml | head -1``) is 141 with no message; standard output that cannot take
    the report (a full disk) is 2 with one line saying so; anything else is a bug in
    mech: 70, with one line saying so and how to report it (``MECH_DEBUG=1`` or
    ``--debug`` before the command adds the traceback).  stdout is flushed here,
    before the interpreter's own last flush, so that a closed pipe or a full disk is
    noticed while it can still be answered.  ``finalize`` False (or a function
    answering False once the command ran): leave by :func:`os._exit` once stdout and
    stderr are flushed, skipping the interpreter's finalization (atexit handlers,
    freeing every object), for a command that has closed its files and waited for
    its workers.
    """
    status: object = 0
    try:
        try:
            run()
        except SystemExit as done:
            status = done.code
        sys.stdout.flush()
    except KeyboardInterrupt:
        status = _interrupted()
    except BrokenPipeError:
        _quiet_stdout()
        status = ExitStatus.PIPE_CLOSED
    except Exception as error:  # the last line of defence: a bug, said to be one
        status = _failed(error)
    if status is None:
        status = 0
    elif not isinstance(status, int):  # sys.exit("message"): printed, as the interpreter would
        _say(str(status))
        status = 1
    if not (finalize() if callable(finalize) else finalize):
        _leave(int(status))
    sys.exit(int(status))


def _interrupted() -> int:
    _quiet_stdout()
    _say("mech: interrupted")
    return ExitStatus.INTERRUPTED


def _failed(error: Exception) -> int:
    """The status of an exception no command answered: a closed pipe, a full stdout, or a bug."""
    if isinstance(error, OSError) and error.errno == errno.EPIPE:
        _quiet_stdout()
        return ExitStatus.PIPE_CLOSED
    if isinstance(error, OSError) and error.errno in _FULL and error.filename is None:
        # a file mech writes is named by mech._files; an unnamed write error is a stream's
        _quiet_stdout()
        _say(f"mech: cannot write standard output: {error.strerror or error}")
        return ExitStatus.BAD_INPUT
    _report_bug(error)
    return ExitStatus.INTERNAL_ERROR


def _leave(status: int) -> None:
    """Exit with ``status`` at once, after flushing stdout and stderr (see :func:`guarded`)."""
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError, ValueError, AttributeError):
            stream.flush()  # stdout was flushed by guarded (a closed pipe answered there)
    os._exit(status)


def prepare(argv: Sequence[str]) -> list[str]:
    """Set up what every command line needs before it runs; the arguments left to parse.

    A leading ``--debug`` (the group's option, :data:`mech.commands.params.DEBUG`) is read
    here, so that the plain forms that skip click honour it too; streams that cannot encode
    Unicode get mech's ASCII spellings (:func:`_make_streams_safe`).
    """
    from mech.commands.params import DEBUG

    args = list(argv)
    if args[:1] and args[0] in DEBUG.names:
        os.environ["MECH_DEBUG"] = "1"
        del args[0]
    _make_streams_safe()
    return args


def _say(line: str) -> None:
    """One line on stderr, whatever state the streams are in."""
    try:
        sys.stderr.write(line + "\n")
        sys.stderr.flush()
    except (OSError, ValueError, AttributeError):
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
    """One line saying mech failed (not the user's file), and how to report it.

    mech has no issue tracker address to print; README's "Reporting a bug" says what to
    send and where the copy of mech you have came from is the place to send it.
    """
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
        f"  This is a bug in mech {__version__}, not in your input. To report it, see {REPORTING}: "
        "send the command line, the file and this version; run it again as mech --debug … "
        "(or with MECH_DEBUG=1) to include the traceback."
    )


def is_utf8(stream: object) -> bool:
    """True for a stream that takes UTF-8 (the fast path and :func:`mech.commands.echo` write it directly)."""
    encoding = (getattr(stream, "encoding", None) or "").lower().replace("-", "").replace("_", "")
    return encoding == "utf8"


def _make_streams_safe() -> None:
    """Let output reach a terminal or file that cannot encode all of Unicode.

    mech writes θ, ω, α, °, − and box rules; a Windows console or a C-locale
    redirect may only take ASCII.  There they are spelt out (``omega``, ``deg``,
    ``-``) instead of crashing with UnicodeEncodeError; other characters become
    ``\\uNNNN`` escapes.  A UTF-8 stream (the usual case) is left alone.
    """
    for stream in (sys.stdout, sys.stderr):
        if stream is None or is_utf8(stream) or not hasattr(stream, "reconfigure"):
            continue
        from mech._text import register_ascii_fallback

        register_ascii_fallback()
        with contextlib.suppress(AttributeError, ValueError, OSError):
            stream.reconfigure(errors="mech-spell")
