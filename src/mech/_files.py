"""Writing an output file without losing what was at its path: every report, CSV, schema and drawing.

One helper writes every file mech is asked to write (``--junit``, ``--gradescope``,
``--csv``, ``schema -o``, ``draw -o``, ``cam -o``/``--diagram``, ``icentres --circle``,
``sweep --svg``/``--plot``/``--animate``), so that each follows the same rules:

* **A regular file (or a new one) is replaced atomically.**  The bytes go to a temporary
  file beside it, which is renamed over the path only once every byte is written and the
  file is closed.  A full disk, a bug or an interrupt part-way leaves the previous file
  whole, never a truncated one.
* **A symbolic link is followed.**  Its target is what is written (atomically, beside the
  target); the link stays a link.
* **Anything else is written through.**  A device (``/dev/null``, a terminal), a FIFO or a
  socket is opened and written in place, never replaced by a regular file.  So is the
  file that is already mech's own standard output or error (``--csv /dev/stdout`` with
  stdout redirected to a file): the bytes join that stream, in order.
* **Every failure names the path.**  A failed write, the last flush, the close or the
  rename (a full disk, a missing folder, no permission) is an
  :class:`~mech.errors.InputError` (exit status 2): ``cannot write PATH: No space left on
  device``.

:func:`check_writable` answers, before any work, whether a path could be written:
``mech check`` asks it for its report files before the first problem file is checked.
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
import sys
from collections.abc import Callable, Iterable, Iterator
from typing import IO, Any

from mech.errors import InputError, Where

__all__ = ["check_writable", "discard", "write_file", "write_with", "writing"]


def _cannot(path: str, reason: str) -> InputError:
    return InputError(f"cannot write {path}: {reason}", where=Where(path))


def _reason(exc: OSError) -> str:
    return exc.strerror or str(exc)


def _own_stream(st: os.stat_result) -> IO[str] | None:
    """mech's stdout or stderr when ``st`` is the very file it writes to, else None."""
    for stream in (sys.stdout, sys.stderr):
        try:
            own = os.fstat(stream.fileno())
        except (AttributeError, ValueError, OSError):
            continue
        if (own.st_dev, own.st_ino) == (st.st_dev, st.st_ino):
            return stream
    return None


def _stat(path: str) -> os.stat_result | None:
    """What the path names, links followed; None when nothing is there yet."""
    try:
        return os.stat(path)
    except FileNotFoundError:  # nothing yet, or a dangling link whose target will be made
        return None
    except OSError as exc:
        raise _cannot(path, _reason(exc)) from None


@contextlib.contextmanager
def writing(path: str | os.PathLike[str], *, binary: bool = False) -> Iterator[IO[Any]]:
    """A file object to write ``path``'s new content into (see the module's rules).

    The content takes the place of what was at ``path`` only when the ``with`` block
    ends without an exception; an OSError inside the block or on closing is an
    :class:`~mech.errors.InputError` naming ``path``.
    """
    name = os.fspath(path)
    st = _stat(name)
    if st is not None and stat.S_ISDIR(st.st_mode):
        raise _cannot(name, "it is a folder")
    stream = _own_stream(st) if st is not None else None
    if stream is not None:
        yield from _through_stream(name, stream, binary)
    elif st is not None and not stat.S_ISREG(st.st_mode):
        yield from _through(name, binary)
    else:
        yield from _atomic(name, st, binary)


def _through_stream(name: str, stream: IO[str], binary: bool) -> Iterator[IO[Any]]:
    """Write into mech's own stdout or stderr (the path is that stream's file)."""
    try:
        stream.flush()
        yield stream.buffer if binary else stream  # type: ignore[attr-defined]
        stream.flush()
    except OSError as exc:
        raise _cannot(name, _reason(exc)) from None


def _through(name: str, binary: bool) -> Iterator[IO[Any]]:
    """Write in place into a device, FIFO or socket (it stays what it is)."""
    try:
        fd = os.open(name, os.O_WRONLY | os.O_TRUNC)  # it exists: nothing is created
        f: IO[Any] = os.fdopen(fd, "wb") if binary else os.fdopen(fd, "w", encoding="utf-8", newline="")
    except OSError as exc:
        raise _cannot(name, _reason(exc)) from None
    try:
        with f:
            yield f
    except OSError as exc:  # the last write, the flush on closing
        raise _cannot(name, _reason(exc)) from None


def _atomic(name: str, st: os.stat_result | None, binary: bool) -> Iterator[IO[Any]]:
    """Write a temporary file beside the (link's) target and rename it over the target."""
    real = os.path.realpath(name) if os.path.islink(name) else name
    folder, base = os.path.split(os.path.abspath(real))
    tmp = os.path.join(folder, f".{base}.mech-{os.getpid()}-{os.urandom(4).hex()}.tmp")
    try:
        # 0o666 less the umask, as any new file; an existing one keeps its permissions
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
    except OSError as exc:
        raise _cannot(name, _reason(exc)) from None
    done = False
    try:
        if binary:
            f: IO[Any] = os.fdopen(fd, "wb")
        else:
            f = os.fdopen(fd, "w", encoding="utf-8", newline="")
        with f:
            yield f
        if st is not None:
            os.chmod(tmp, stat.S_IMODE(st.st_mode))
        os.replace(tmp, real)
        done = True
    except OSError as exc:
        raise _cannot(name, _reason(exc)) from None
    finally:
        if not done:
            with contextlib.suppress(OSError):
                os.unlink(tmp)


def write_file(path: str | os.PathLike[str], content: str | bytes | Iterable[str]) -> None:
    """Write ``content`` (text, bytes, or text in pieces as they are made) to ``path``."""
    binary = isinstance(content, bytes)
    with writing(path, binary=binary) as f:
        if isinstance(content, (str, bytes)):
            f.write(content)
        else:
            f.writelines(content)


def write_with(path: str | os.PathLike[str], write: Callable[[IO[bytes]], None]) -> None:
    """Let ``write`` (matplotlib's ``savefig``, PIL's ``save``) write binary content to ``path``."""
    with writing(path, binary=True) as f:
        write(f)


def check_writable(path: str | os.PathLike[str]) -> None:
    """Raise the :class:`~mech.errors.InputError` that writing ``path`` would raise, before any work.

    Existing non-regular targets must open for writing; anywhere else a temporary file
    must be creatable beside the (link's) target, as :func:`writing` will create one.
    Nothing at ``path`` is changed.
    """
    name = os.fspath(path)
    st = _stat(name)
    if st is not None and stat.S_ISDIR(st.st_mode):
        raise _cannot(name, "it is a folder")
    if st is not None and (_own_stream(st) is not None or not stat.S_ISREG(st.st_mode)):
        if not stat.S_ISFIFO(st.st_mode) and not os.access(name, os.W_OK):
            raise _cannot(name, os.strerror(errno.EACCES))
        return
    real = os.path.realpath(name) if os.path.islink(name) else name
    folder, base = os.path.split(os.path.abspath(real))
    probe = os.path.join(folder, f".{base}.mech-{os.getpid()}-{os.urandom(4).hex()}.tmp")
    try:
        os.close(os.open(probe, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600))
    except OSError as exc:
        raise _cannot(name, _reason(exc)) from None
    with contextlib.suppress(OSError):
        os.unlink(probe)


def discard(path: str | os.PathLike[str]) -> None:
    """Remove the regular file at ``path`` (a link's regular target); leave anything else.

    An interrupted ``mech check`` removes the old report so that it cannot pass for this
    run's; a device, a FIFO or a folder is never removed, and a link stays a link.
    """
    name = os.fspath(path)
    real = os.path.realpath(name) if os.path.islink(name) else name
    with contextlib.suppress(OSError):
        if stat.S_ISREG(os.lstat(real).st_mode):
            os.unlink(real)
