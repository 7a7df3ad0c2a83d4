"""Claimed answers → verdicts: the library behind ``mech check``.

Each claim (a :class:`~mech.model.Claim`, from a file's ``answers`` or from an
answer sheet) gets one :class:`Verdict`:

* **pass** — the computed value agrees within the tolerance;
* **fail** — it does not (the verdict carries the computed value, the error
  and the tolerance it was held to);
* **error** — the value could not be computed (the mechanism cannot be solved
  as asked, a ratio's denominator is zero …), with the reason.

Only what the claims ask is computed.  Counts (``dof``, ``links.*``,
``joints.*``, ``higher_pairs``, ``icentres.count``, ``chain``) use
:mod:`mech.topology` alone, so checking a folder of DOF exercises never imports
numpy; ``mobility`` needs the constraint Jacobian's rank; kinematic keys solve
the mechanism once, at the highest level any claim needs; I-centre keys locate
the I-centres from that solution.

Tolerances (the textbook convention: an answer is judged against the true
value, not the other way round):

* relative ``t``: pass when ``|computed − claimed| ≤ t·|computed|``;
* absolute ``t`` (SI units of the answer): pass when ``|computed − claimed| ≤ t``;
* a point (``icentre``): the distance between the claimed and the computed
  point, against ``t·size`` (``size``: the mechanism's largest distance between
  two joints) or an absolute length;
* counts and chain names are exact.

A claim of exactly zero cannot meet a relative tolerance of a value that is
zero only to rounding, so every comparison also passes when the error is below
1e-6 of the mechanism's own scale for that quantity (its size, its fastest
link's ω, and their products).

Nothing here prints or imports rich; :mod:`mech.render.check` makes tables,
JSON, JUnit XML, Gradescope and CSV from the same :class:`Verdict` objects.

One file's trip runs one way, down the rooms, and comes back by returning:
:mod:`mech.batch` (files, sheets, the report) hands each problem file to
:mod:`mech.batchpool`, whose workers run :func:`mech.check.problem.run_task`
(load, then :mod:`mech.check.verdicts` for every claim); a failed claim goes
down to :mod:`mech.diagnose`, and every value comes from :mod:`mech.grading`
over :mod:`mech.analysis`.  None of them imports a room above it.

==========================  ==========================================================
:mod:`~.verdicts`           :class:`Verdict`, :class:`FileResult`, :func:`check`: claims → verdicts
:mod:`~.problem`            one problem file: its own answers (:func:`check_file`), or every
                            student's sheet (what a worker of ``mech check`` runs)
==========================  ==========================================================
"""

from __future__ import annotations

from mech.check.problem import check_file, probe
from mech.check.verdicts import ERROR, FAIL, IGNORED, PASS, FileResult, Verdict, check, error_result
from mech.grading import Analysis, InternalError

__all__ = [
    "ERROR",
    "FAIL",
    "IGNORED",
    "PASS",
    "Analysis",
    "FileResult",
    "InternalError",
    "Verdict",
    "check",
    "check_file",
    "error_result",
    "probe",
]
