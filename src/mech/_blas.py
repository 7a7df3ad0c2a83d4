"""BLAS on one thread: mech's matrices are a few rows each, so a thread pool only costs.

numpy's BLAS (OpenBLAS in the wheels) starts a pool of threads when numpy is imported, and
its threads spin while they wait: on a two-core machine ``import numpy`` took 260 ms of CPU
with the pool and 130 ms without it, and 30 ms more of wall time.  The largest products mech
forms are a chain's blocks (:mod:`mech.kinematics.blocks`), far below where threads pay.  The
variables are read once, when numpy is first imported, so they are set before that, by the
console script for every command and by each worker of a batch; a variable the user set is kept.
"""

from __future__ import annotations

import os

__all__ = ["one_thread"]

#: The thread pools of the BLAS libraries numpy may be built on (OpenBLAS, MKL, OpenMP, Accelerate).
BLAS_THREADS = ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "OMP_NUM_THREADS", "VECLIB_MAXIMUM_THREADS")


def one_thread() -> None:
    """Ask every BLAS numpy may load for one thread, unless the user said otherwise (before numpy loads)."""
    for name in BLAS_THREADS:
        os.environ.setdefault(name, "1")
