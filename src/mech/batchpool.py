"""Run many small jobs with a time limit each, in this process or in worker processes we can kill.

Why not :class:`concurrent.futures.ProcessPoolExecutor`: it cannot stop one job
that runs too long (the pool can only be shut down whole), and a worker that
dies takes every job in flight with it.  ``mech check`` needs one file past its
``--timeout`` to become that file's error row while the others finish.

Two limits protect a batch:

* **soft**: each job runs under ``SIGALRM`` (:func:`time_limit`), which raises
  :class:`JobTimeout` inside the job after ``timeout`` seconds, so the job
  becomes its timeout row and the worker goes on with the next one;
* **hard** (worker processes only): a job still running ``timeout + grace``
  seconds after it started (stuck in C code the alarm cannot interrupt) has its
  worker killed; that job gets its timeout row, the jobs that worker still
  held are handed to a fresh worker.  A worker that dies (a crash in C code)
  costs the job it was running, and the others are run again.

Results are handed back **in job order** as soon as every earlier job is done,
so a caller can stream a sorted report while later jobs still run.

Jobs travel to the workers with their chunks (pickled), so a :class:`Pool` can be
started before its jobs exist: ``mech check`` starts its workers before it reads a
class's answer sheets, so that no worker inherits (and counts again in its resident
memory) what the parent read.
"""

from __future__ import annotations

import gc
import os
import signal
import sys
import threading
import time
from collections import deque
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any, Generic, TypeVar

from mech._blas import one_thread

if TYPE_CHECKING:  # multiprocessing is imported only when a pool starts
    from multiprocessing.context import ForkContext, ForkServerContext, SpawnContext

__all__ = ["JobTimeout", "Pool", "run_jobs", "time_limit"]

T = TypeVar("T")
R = TypeVar("R")


class JobTimeout(BaseException):
    """A job ran past its time limit.

    A ``BaseException``, so that the ``except Exception`` that turns a bug in
    one analysis into its error row does not swallow the limit.
    """


@contextmanager
def time_limit(seconds: float | None) -> Iterator[None]:
    """Raise :class:`JobTimeout` in this (main) thread after ``seconds``; no-op where it cannot."""
    usable = (
        seconds is not None
        and seconds > 0
        and hasattr(signal, "setitimer")
        and threading.current_thread() is threading.main_thread()
    )
    if not usable:
        yield
        return

    def expired(signum: int, frame: Any) -> None:
        raise JobTimeout

    previous = signal.signal(signal.SIGALRM, expired)
    signal.setitimer(signal.ITIMER_REAL, seconds)  # type: ignore[arg-type]
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


class _Limited(Generic[T, R]):
    """``work(job)`` under the soft limit; ``on_timeout(job)`` when it expires."""

    def __init__(
        self, work: Callable[[T], R], on_timeout: Callable[[T, str], R], timeout: float | None
    ) -> None:
        self.work, self.on_timeout, self.timeout = work, on_timeout, timeout

    def __call__(self, job: T) -> R:
        try:
            with time_limit(self.timeout):
                return self.work(job)
        except JobTimeout:
            return self.on_timeout(job, "timeout")


def run_jobs(
    jobs: Sequence[T],
    work: Callable[[T], R],
    on_lost: Callable[[T, str], R],
    *,
    workers: int = 1,
    timeout: float | None = None,
    chunk: int = 1,
) -> Iterator[R]:
    """``work(job)`` for every job, yielded in job order; ``on_lost(job, why)`` for a lost job.

    ``why`` is ``"timeout"`` (past ``timeout`` seconds) or ``"crash"`` (its
    worker died).  ``work`` and the jobs must be picklable for ``workers > 1``
    (module-level functions, plain data).  Closing the iterator early (or
    Ctrl-C) kills every worker.
    """
    if workers <= 1 or len(jobs) < 2:
        limited = _Limited(work, on_lost, timeout)
        for job in jobs:
            yield limited(job)
        return
    with Pool(work, on_lost, workers=min(workers, len(jobs)), timeout=timeout) as pool:
        yield from pool.map(jobs, chunk=chunk)


# -- the pool -----------------------------------------------------------------------------------
def _chunks(n: int, largest: int, workers: int) -> Iterator[list[int]]:
    """Job indices in chunks of at most ``largest``, smaller as the end nears (guided scheduling).

    Each chunk is about a quarter of the jobs left per worker, so the last chunks
    are single jobs and no worker sits idle at the end while another finishes a
    full chunk.
    """
    i = 0
    while i < n:
        size = max(1, min(largest, (n - i) // (4 * workers)))
        yield list(range(i, min(i + size, n)))
        i += size


def _worker(conn: Any, slot: int, board: Any, limited: _Limited[Any, Any]) -> None:
    """Run the chunks of ``(index, job)`` the parent sends; say on ``board`` which job runs since when."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the parent's to handle: it kills us
    one_thread()  # the pool runs one worker per core: a BLAS pool in each could only oversubscribe them
    gc.freeze()  # what the parent imported lives as long as we do: no collection walks it again
    frozen: set[str] | None = set(sys.modules)
    try:
        while True:
            chunk = conn.recv()
            if chunk is None:
                return
            out = []
            while chunk:  # each job let go once done: a class's answer sheets are not kept
                index, job = chunk.pop(0)
                board[2 * slot] = index
                board[2 * slot + 1] = time.monotonic()
                out.append((index, limited(job)))
                del job
            board[2 * slot] = -1.0
            conn.send(out)
            if frozen is not None and len(sys.modules) > len(frozen):  # numpy, imported by a solve
                gc.freeze()  # (and once only: a chunk's garbage frozen with it is a few objects)
                frozen = None
    except (EOFError, BrokenPipeError, KeyboardInterrupt):
        return


#: Chunks sent to a worker ahead of its results: the next one waits in its pipe, so a worker never
#: sits idle while the parent streams the rows of the chunk it has just finished.
_IN_FLIGHT = 2


class _Slot:
    __slots__ = ("chunks", "conn", "proc")

    def __init__(self, proc: Any, conn: Any) -> None:
        self.proc, self.conn = proc, conn
        self.chunks: deque[list[int]] = deque()  # sent, results not yet back (in the order sent)

    @property
    def held(self) -> list[int]:
        """The jobs this worker holds: running, or waiting in its pipe."""
        return [i for chunk in self.chunks for i in chunk]


class Pool(Generic[T, R]):
    """Worker processes that run ``work(job)`` under the limits of the module docstring.

    The workers start when :meth:`start` is called (or when :meth:`map` first needs
    them); :meth:`map` runs one sequence of jobs and yields their results in job
    order, then closes the pool.  A worker that dies or is killed is replaced by a
    fresh one.  ``work``, ``on_lost`` and the jobs must be picklable.
    """

    def __init__(
        self,
        work: Callable[[T], R],
        on_lost: Callable[[T, str], R],
        *,
        workers: int,
        timeout: float | None = None,
    ) -> None:
        import multiprocessing as mp

        methods = mp.get_all_start_methods()
        # fork: a worker starts in milliseconds with mech already imported.  Only from a
        # single-threaded parent (the command line): forking a process with threads (a library
        # caller running Dask, say) can leave a lock held forever in the child.
        self.ctx: ForkContext | ForkServerContext | SpawnContext
        if "fork" in methods and threading.active_count() == 1:
            self.ctx = mp.get_context("fork")
        elif "forkserver" in methods:
            self.ctx = mp.get_context("forkserver")
        else:
            self.ctx = mp.get_context("spawn")
        self.limited, self.on_lost = _Limited(work, on_lost, timeout), on_lost
        self.timeout = timeout
        self.grace = None if timeout is None else 2.0 + 0.5 * timeout
        self.board = self.ctx.Array("d", [-1.0, 0.0] * workers, lock=False)
        self.slots: list[_Slot | None] = [None] * workers
        self.jobs: list[T | None] = []
        self.queue: deque[list[int]] = deque()
        self.done: dict[int, R] = {}

    def __enter__(self) -> Pool[T, R]:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def start(self) -> Pool[T, R]:
        """Start every worker now (forked from this process as it is now), before any job exists."""
        for slot, s in enumerate(self.slots):
            if s is None:
                self._start(slot)
        return self

    def map(self, jobs: Sequence[T], *, chunk: int = 1) -> Iterator[R]:
        """``work(job)`` for every job, yielded in job order (``on_lost(job, why)`` for a lost one).

        Closing the iterator early (or Ctrl-C) kills every worker; the pool is closed at the end.
        The pool keeps its own list of the jobs and lets each go once its result is yielded (a
        class's answer sheets travel in its jobs): a caller that keeps no reference to them
        holds none of the jobs that are done.
        """
        self.jobs, self.done = list(jobs), {}
        self.queue = deque(_chunks(len(self.jobs), max(1, chunk), len(self.slots)))
        del jobs
        try:
            yield from self._results()
        finally:
            self.close()

    def _job(self, index: int) -> T:
        job = self.jobs[index]
        assert job is not None, f"job {index} is sent or lost after its result was yielded"
        return job

    def _start(self, slot: int) -> _Slot:
        parent, child = self.ctx.Pipe()
        proc = self.ctx.Process(target=_worker, args=(child, slot, self.board, self.limited), daemon=True)
        proc.start()
        child.close()
        self.board[2 * slot] = -1.0
        s = _Slot(proc, parent)
        self.slots[slot] = s
        return s

    def _lose(self, slot: int, why: str) -> None:
        """A worker is dead or killed: its current job is lost, the rest go back to the queue."""
        s = self.slots[slot]
        assert s is not None
        current = int(self.board[2 * slot])
        if s.proc.is_alive():
            s.proc.kill()
        s.proc.join()
        s.conn.close()
        self.slots[slot] = None
        rest = [i for i in s.held if i != current and i not in self.done]
        if current >= 0 and current in s.held:
            self.done[current] = self.on_lost(self._job(current), why)
        elif not rest and s.held:  # died between jobs with nothing left: the first is the culprit
            self.done[s.held[0]] = self.on_lost(self._job(s.held[0]), why)
        if rest:
            self.queue.appendleft(rest)

    def _results(self) -> Iterator[R]:
        from multiprocessing.connection import wait

        emitted = 0
        while emitted < len(self.jobs):
            self._feed()
            busy = {s.conn: i for i, s in enumerate(self.slots) if s is not None and s.held}
            ready = wait(list(busy), timeout=0.25) if busy else []
            for conn in ready:
                slot = busy[conn]
                s = self.slots[slot]
                assert s is not None
                try:
                    got = s.conn.recv()  # s.conn is conn, as the Connection it is
                except (EOFError, OSError):
                    self._lose(slot, "crash")
                    continue
                for index, result in got:
                    self.done[index] = result
                s.chunks.popleft()  # a worker answers its chunks in the order they were sent
            self._police()
            while emitted in self.done:
                self.jobs[emitted] = None  # done: never sent or lost again
                yield self.done.pop(emitted)
                emitted += 1

    def _feed(self) -> None:
        """Send each worker chunks (the jobs themselves) until it holds ``_IN_FLIGHT`` of them."""
        for slot, s in enumerate(self.slots):
            while self.queue and (s is None or len(s.chunks) < _IN_FLIGHT):
                s = s or self._start(slot)
                s.chunks.append(self.queue.popleft())
                try:
                    s.conn.send([(i, self._job(i)) for i in s.chunks[-1]])
                except OSError:  # it died meanwhile: its end of the pipe says so, and _lose
                    break  # hands every job it held (this chunk too) to a fresh worker

    def _police(self) -> None:
        """Kill a worker whose job is past the hard limit, or notice one that died."""
        now = time.monotonic()
        for slot, s in enumerate(self.slots):
            if s is None or not s.held:
                continue
            if not s.proc.is_alive() and not s.conn.poll():
                self._lose(slot, "crash")
            elif (
                self.grace is not None
                and self.timeout is not None
                and self.board[2 * slot] >= 0
                and now - self.board[2 * slot + 1] > self.timeout + self.grace
            ):
                self._lose(slot, "timeout")

    def close(self) -> None:
        """Stop every worker: an idle one is told to leave, a busy one is killed."""
        for s in self.slots:
            if s is None:
                continue
            try:
                if s.proc.is_alive() and not s.held:
                    s.conn.send(None)
            except (OSError, ValueError):
                pass
        deadline = time.monotonic() + 1.0
        for s in self.slots:
            if s is None:
                continue
            if s.held:
                s.proc.kill()
            s.proc.join(max(0.0, deadline - time.monotonic()))
            if s.proc.is_alive():
                s.proc.kill()
                s.proc.join()
            s.conn.close()
        self.slots = [None] * len(self.slots)


def cpu_count() -> int:
    """CPUs this process may run on (the affinity mask where there is one)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1
