"""Verdicts on claimed answers: one mechanism's claims held against its computed values.

See :mod:`mech.check` for what a verdict means and how tolerances are applied.
The values come from :mod:`mech.grading` (one :class:`~mech.grading.Analysis`
per problem, shared by every student's claims); a failed answer is explained by
:mod:`mech.diagnose` when it matches a usual mistake.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Sequence
from dataclasses import field
from typing import Any

from mech import grading
from mech._records import dataclass
from mech.answers import AnswerKey, AtInfinity, Compare, Undefined, parse_key
from mech.diagnose import diagnosis
from mech.errors import MechError, Problem, Where
from mech.grading import NOISE, Analysis, InternalError
from mech.model import Claim, Mechanism, Tolerance
from mech.options import SolveOptions
from mech.units import Dimension, format_unit, parse_quantity, to_unit

__all__ = [
    "ERROR",
    "FAIL",
    "IGNORED",
    "PASS",
    "FileResult",
    "Verdict",
    "check",
    "error_result",
]

PASS = "pass"
FAIL = "fail"
ERROR = "error"
#: A sheet key that is not a question of its problem (or a sheet entry naming no problem):
#: reported, never scored.
IGNORED = "ignored"


@dataclass(frozen=True, slots=True)
class Verdict:
    """The verdict on one claimed answer.

    Attributes
    ----------
    key
        The answer key as written (``omega.rocker``); ``file`` for a row that
        stands for a whole file that could not be read.
    status
        ``"pass"``, ``"fail"`` or ``"error"``.
    claimed
        The claim as written (``"4.8 rad/s cw"``).
    computed
        The value it was compared with, SI: a float (signed where a sense was
        claimed), an int count, a chain name, a point ``(x, y)``, the string
        ``"infinity"``, or None when nothing could be computed.
    unit
        SI unit of ``computed`` (``"rad/s"``), None for counts and names.
    error
        ``|computed − claimed|`` in SI (for a point: the distance between the
        points), None where it has no meaning.
    allowed
        The largest error that passes, SI (the tolerance made absolute).
    tolerance
        The tolerance as given (``"2%"``, ``"0.05"`` SI), None for exact keys.
    message
        One sentence a student can act on.
    where
        Where the claim was written (file or sheet, line, column).
    diagnosis
        For a failed answer, the usual mistake the claim matches, computed
        (``"the opposite sense"``, ``"the other assembly branch (C below AD)"``);
        None when it matches none of them.
    marks
        What the question is worth (DESIGN § 1.3: ``asks`` as a mapping, or
        ``marks`` on an answer; 1 by default): a pass earns them all, anything
        else none.  An ignored sheet key is worth 0.
    diagnosis_miss
        How far the claim is from the diagnosed mistake's value, relative to it (not
        reported): a classmate's variant the claim matches more closely is named instead.
    """

    key: str
    status: str
    claimed: str = ""
    computed: Any = None
    unit: str | None = None
    error: float | None = None
    allowed: float | None = None
    tolerance: str | None = None
    message: str = ""
    where: Where | None = field(default=None, compare=False)
    diagnosis: str | None = None
    marks: float = 1.0
    diagnosis_miss: float | None = field(default=None, compare=False)

    @property
    def passed(self) -> bool:
        return self.status == PASS

    @property
    def earned(self) -> float:
        """The marks this answer earns: all of them for a pass, none otherwise."""
        return self.marks if self.status == PASS else 0.0

    @property
    def out_of(self) -> float:
        """The marks it is scored out of (0 for an ignored sheet key)."""
        return self.marks if self.status != IGNORED else 0.0

    @property
    def scored(self) -> bool:
        """Counted in a score (pass, fail, error); an ignored sheet key is not."""
        return self.status != IGNORED

    def __reduce__(self) -> tuple[Any, tuple[Any, ...]]:
        # Pickled as its fields, and read back with the words every row repeats (its key, status,
        # unit, tolerance, diagnosis) shared: the process gathering a batch of 20,000 files from
        # its workers holds one "2%" and one "velocity.B", not one per row.
        return _unpickled, tuple(getattr(self, name) for name in Verdict.__match_args__)


def _unpickled(
    key: str,
    status: str,
    claimed: str,
    computed: Any,
    unit: str | None,
    error: float | None,
    allowed: float | None,
    tolerance: str | None,
    message: str,
    where: Where | None,
    diagnosis: str | None,
    marks: float = 1.0,
    diagnosis_miss: float | None = None,
) -> Verdict:
    """A pickled verdict read back (:meth:`Verdict.__reduce__`)."""
    return Verdict(
        sys.intern(key),
        sys.intern(status),
        claimed,
        computed,
        None if unit is None else sys.intern(unit),
        error,
        allowed,
        None if tolerance is None else sys.intern(tolerance),
        message,
        where,
        None if diagnosis is None else sys.intern(diagnosis),
        marks,
        diagnosis_miss,
    )


@dataclass(frozen=True, slots=True)
class FileResult:
    """Every verdict for one problem file (and one student, with answer sheets).

    A file that cannot be read or checked at all is *one* error verdict with
    key ``file``; its located problems are kept in ``problems`` for JSON.
    ``skipped`` is True for a file with nothing to check (no answers; with
    sheets, a problem that asks nothing).  ``sheet`` is True for a row about an
    answer sheet itself (a sheet that cannot be read, an entry that names no
    problem file): ``path`` is then the sheet's, and the row is not a problem
    file in the counts.  ``excluded`` is True for a problem file left out of
    every score (with sheets: it cannot be read, or asks nothing — the
    teacher's error, reported once).
    """

    path: str
    name: str | None = None
    verdicts: tuple[Verdict, ...] = ()
    student: str | None = None
    problems: tuple[Problem, ...] = ()
    skipped: bool = False
    sheet: bool = False
    excluded: bool = False

    @property
    def passed(self) -> int:
        return sum(v.status == PASS for v in self.verdicts)

    @property
    def ignored(self) -> int:
        return sum(v.status == IGNORED for v in self.verdicts)

    @property
    def failed(self) -> int:
        return sum(v.status == FAIL for v in self.verdicts)

    @property
    def errors(self) -> int:
        return sum(v.status == ERROR for v in self.verdicts)

    @property
    def total(self) -> int:
        """Scored verdicts (ignored sheet keys are not counted)."""
        return sum(v.status != IGNORED for v in self.verdicts)

    @property
    def earned(self) -> float:
        """Marks earned over the scored answers (DESIGN § 1.3)."""
        return sum(v.earned for v in self.verdicts)

    @property
    def out_of(self) -> float:
        """Marks asked: what the scored answers are worth, the same for every student."""
        return sum(v.out_of for v in self.verdicts)

    @property
    def ok(self) -> bool:
        return self.passed == self.total


def error_result(
    path: str,
    error: MechError,
    *,
    student: str | None = None,
    name: str | None = None,
    sheet: bool = False,
) -> FileResult:
    """A file that could not be checked: one error row carrying the error's problems."""
    first = error.problems[0] if error.problems else Problem(str(error))
    more = len(error.problems) - 1
    message = first.message + (f" (and {more} more problem{'s' if more > 1 else ''})" if more > 0 else "")
    where = first.where
    if where is not None and where.line:
        message = f"{where.line}:{where.column}: {message}"
    return FileResult(
        path=path,
        name=name,
        verdicts=(Verdict("file", ERROR, message=message, where=where),),
        student=student,
        problems=tuple(error.problems),
        sheet=sheet,
    )


def check(
    mech: Mechanism,
    claims: Sequence[Claim] | None = None,
    *,
    tolerance: Tolerance | None = None,
    options: SolveOptions | None = None,
    analysis: Analysis | None = None,
) -> tuple[Verdict, ...]:
    """Verdicts on ``claims`` (default: the file's own answers), in their order.

    Parameters
    ----------
    mech
        The mechanism, as loaded.
    claims
        Claims to check; ``mech.answers`` when None.
    tolerance
        Default tolerance for claims that give none; the file's when None.
    options
        Solver options (Newton's tolerance); drives come from the file.
    analysis
        An :class:`Analysis` to reuse, so that several students' claims on one
        problem share one solve.

    Examples
    --------
    >>> from mech.loader import loads
    >>> m = loads('''
    ... links: [frame, a, b]
    ... joints:
    ...   A: {type: revolute, links: [frame, a]}
    ...   B: {type: revolute, links: [a, b]}
    ...   C: {type: revolute, links: [b, frame]}
    ... answers: {dof: 1}
    ... ''')
    >>> [(v.key, v.status, v.computed) for v in check(m)]
    [('dof', 'fail', 0)]
    """
    claims = mech.answers if claims is None else tuple(claims)
    tolerance = tolerance or mech.tolerance
    analysis = analysis or Analysis(mech, options=options)
    akeys = [parse_key(claim.key) for claim in claims]
    analysis.need(akeys)
    return tuple(
        _verdict(claim, akey, analysis, tolerance) for claim, akey in zip(claims, akeys, strict=True)
    )


# -- one claim -------------------------------------------------------------------------------
def _verdict(claim: Claim, akey: AnswerKey, analysis: Analysis, default: Tolerance) -> Verdict:
    base = Verdict(claim.key, ERROR, claimed=claim.text or str(claim.value), where=claim.where)
    tolerance = claim.tolerance or default
    try:
        value = grading.value(akey, analysis)
        verdict = _COMPARE[akey.compare](claim, akey, value, analysis, tolerance, base)
    except MechError as error:
        lower = analysis.below(akey.level)  # the whole solve failed: this key may need less of it
        if lower is not None:
            return _verdict(claim, akey, lower, default)
        return _replace(base, status=ERROR, message=f"cannot be computed: {_reason(error)}")
    except (Undefined, InternalError) as why:
        return _replace(base, status=ERROR, message=str(why))
    except Exception as exc:  # a bug in a key's computation: this row says so, the others stand
        return _replace(base, status=ERROR, message=str(InternalError.of(exc)))
    if verdict.status == FAIL:
        try:
            found = diagnosis(claim, akey, value, analysis, tolerance)
        except Exception:  # a diagnosis is a bonus: it never costs the verdict
            found = None
        if found:
            verdict = _replace(verdict, diagnosis=found[0], diagnosis_miss=found[1])
    return verdict


def _reason(error: MechError) -> str:
    p = error.problems[0] if error.problems else None
    text = p.message if p else str(error)
    if p is not None and p.hint:
        text += f" ({p.hint})"
    return text


def _replace(v: Verdict, **changes: Any) -> Verdict:
    """``dataclasses.replace`` for a verdict, without its per-call walk over the fields' metadata."""
    return Verdict(**{name: changes.pop(name, getattr(v, name)) for name in _VERDICT_FIELDS}, **changes)


_VERDICT_FIELDS = Verdict.__match_args__


# -- comparisons, one per Compare mode ----------------------------------------------------------
_FLOAT_MAX = 2**1024  # the first whole number a float cannot hold


def _cmp_count(
    claim: Claim, akey: AnswerKey, computed: Any, an: Analysis, tol: Tolerance, base: Verdict
) -> Verdict:
    key = akey.key
    ok = computed == claim.value
    off = abs(computed - int(claim.value))  # type: ignore[arg-type]
    return _replace(
        base,
        status=PASS if ok else FAIL,
        computed=computed,
        error=float(off) if off < _FLOAT_MAX else math.inf,  # a claim of 4,000 digits is off by "infinity"
        allowed=0.0,
        message=f"{key} = {computed}" if ok else f"{key} is {computed}, not {claim.value}",
    )


def _cmp_label(
    claim: Claim, akey: AnswerKey, computed: Any, an: Analysis, tol: Tolerance, base: Verdict
) -> Verdict:
    normal = akey.kind.normalise or (lambda s: s.strip().lower())
    ok = computed is not None and normal(str(claim.value)) == normal(str(computed))
    shown = computed if computed is not None else f"none of the named {akey.key}s"
    return _replace(
        base,
        status=PASS if ok else FAIL,
        computed=computed,
        message=f"{akey.key} is {shown}" if ok else f"the {akey.key} is {shown}, not {claim.value}",
    )


# -- kinematic quantities --------------------------------------------------------------------
def _mag(v: tuple[float, float]) -> float:
    return math.hypot(v[0], v[1])


def _show(value: float, claim: Claim, dimension: Dimension, *, sense: bool) -> str:
    """``value`` (SI) in the unit the claim was written in, with cw/ccw for a signed angular value."""
    unit = dimension.value
    try:
        q = parse_quantity(claim.text)
        if q.unit:
            unit = q.unit
    except (KeyError, ValueError):
        pass
    shown = to_unit(abs(value) if sense else value, unit) if unit != "1" else value
    text = f"{shown:.4g}" + ("" if unit == "1" else f" {format_unit(unit)}")
    if sense and value != 0.0:
        text += " ccw" if value > 0 else " cw"
    return text


def _compare(
    claim: Claim,
    base: Verdict,
    computed: float,
    claimed: float,
    dimension: Dimension,
    tolerance: Tolerance,
    analysis: Analysis,
    *,
    sense: bool = False,
    what: str = "",
) -> Verdict:
    """A scalar claim against its computed value: relative to the computed value, or absolute."""
    err = abs(computed - claimed)
    allowed = tolerance.value * abs(computed) if tolerance.relative else tolerance.value
    floor = NOISE * analysis.scale(dimension)
    shown = _show(computed, claim, dimension, sense=sense)
    ok = err <= allowed or err <= floor
    common = {
        "computed": computed,
        "unit": dimension.value,
        "error": err,
        "allowed": allowed,
        "tolerance": str(tolerance),
    }
    if ok:
        return _replace(base, status=PASS, message=f"{what}{shown}", **common)
    slip = (
        ""
        if dimension in (Dimension.NUMBER,) or sense
        else _unit_slip(computed, claimed, claim, tolerance, dimension)
    )
    if slip:
        message = f"{what}{shown}{slip}"
    elif (
        sense
        and computed * claimed < 0
        and abs(computed) > floor
        and abs(abs(computed) - abs(claimed)) <= allowed
    ):
        message = f"wrong sense: {what}{shown}, claimed {claim.sense or ('ccw' if claimed > 0 else 'cw')}"
    elif sense and computed * claimed < 0 and abs(computed) > floor:
        # the magnitude is wrong too: the larger error is named first (issue 22)
        off = abs(abs(computed) - abs(claimed)) / abs(computed)
        message = (
            f"{what}{shown}: the magnitude is off by {off:.1%} (allowed {tolerance}), and the sense is wrong"
        )
    elif tolerance.relative and abs(computed) > floor:  # a value at rest (2e-16) has no relative error
        message = f"{what}{shown}: off by {err / abs(computed):.1%} (allowed {tolerance})"
    else:
        message = f"{what}{shown}: off by {_show(err, claim, dimension, sense=False)} (allowed {tolerance})"
    return _replace(base, status=FAIL, message=message, **common)


_SLIPS = {1e3: "mm", 1e2: "cm"}
#: What a length unit becomes in the unit of each quantity a slip hint may name (mm → mm/s …).
_SLIP_SUFFIX = {Dimension.LENGTH: "", Dimension.VELOCITY: "/s", Dimension.ACCELERATION: "/s^2"}


def _unit_slip(
    computed: float,
    claimed: float,
    claim: Claim,
    tolerance: Tolerance,
    dimension: Dimension = Dimension.LENGTH,
) -> str:
    """A hint when a bare claim is the computed value in mm or cm: bare numbers are SI.

    The unit it suggests measures the claim's own quantity (``mm/s`` for a speed):
    a student who follows the hint must get a pass, not an error (issue 22).
    """
    suffix = _SLIP_SUFFIX.get(dimension)
    if suffix is None:
        return ""
    if computed == 0.0 or not claim.text or not claim.text.lstrip("[-+ ").replace(".", "", 1)[:1].isdigit():
        return ""
    try:
        if parse_quantity(claim.text.split(",")[0].strip("[] ")).unit is not None:
            return ""
    except (KeyError, ValueError):
        return ""
    for factor, unit in _SLIPS.items():
        if abs(claimed - computed * factor) <= max(
            tolerance.value if tolerance.relative else 0.02, 0.02
        ) * abs(computed * factor):
            unit += suffix
            return f'; the claim looks like {unit}: a bare number is SI (write e.g. "{claimed:g} {unit}")'
    return ""


def _signed_claim(claim: Claim) -> float:
    v = float(claim.value)  # type: ignore[arg-type]
    if claim.sense == "cw":
        return -abs(v)
    if claim.sense == "ccw":
        return abs(v)
    return v


def _cmp_sense(
    claim: Claim, akey: AnswerKey, value: Any, an: Analysis, tol: Tolerance, base: Verdict
) -> Verdict:
    """``omega.<link>`` / ``alpha.<link>``: the sign is checked only when the claim says cw or ccw."""
    dimension = akey.dimension or Dimension.NUMBER
    if claim.sense is not None:
        return _compare(claim, base, value, _signed_claim(claim), dimension, tol, an, sense=True)
    return _compare(claim, base, abs(value), abs(float(claim.value)), dimension, tol, an)  # type: ignore[arg-type]


def _cmp_magnitude(
    claim: Claim, akey: AnswerKey, value: Any, an: Analysis, tol: Tolerance, base: Verdict
) -> Verdict:
    """Vectors and speeds by magnitude.  An infinite value (a distance to a point at infinity, a
    mechanical advantage at a dead centre) passes a claim of ``infinity`` and fails any number;
    a claim of ``infinity`` fails any finite value."""
    unit = (akey.dimension or Dimension.NUMBER).value
    infinite = isinstance(value, AtInfinity) or (isinstance(value, float) and math.isinf(value))
    if infinite:
        what = (
            f"{value.label} is at infinity{_direction(value)}: the {akey.family} is infinite"
            if isinstance(value, AtInfinity)
            else f"∞ (dead centre): the {akey.family} is infinite"
        )
        ok = claim.value == "infinity"
        return _replace(base, status=PASS if ok else FAIL, computed="infinity", unit=unit, message=what)
    magnitude = _mag(value) if isinstance(value, tuple) else abs(value)
    if claim.value == "infinity":
        shown = _show(magnitude, claim, akey.dimension or Dimension.NUMBER, sense=False)
        return _replace(
            base, status=FAIL, computed=magnitude, unit=unit, message=f"{shown}, finite: not infinity"
        )
    return _compare(
        claim,
        base,
        magnitude,
        abs(_number(claim)),
        akey.dimension or Dimension.NUMBER,
        tol,
        an,
    )


def _cmp_ratio(
    claim: Claim, akey: AnswerKey, value: Any, an: Analysis, tol: Tolerance, base: Verdict
) -> Verdict:
    """A negative claim says the two turn opposite ways and is checked signed; a positive one
    is the textbook's velocity ratio, a magnitude."""
    claimed = _number(claim)
    what = "ω ratio " if akey.family == "omega_ratio" else ""
    dimension = akey.dimension or Dimension.NUMBER
    if claimed < 0:
        return _compare(claim, base, value, claimed, dimension, tol, an, what=what)
    return _compare(claim, base, abs(value), claimed, dimension, tol, an, what=what)


def _cmp_signed(
    claim: Claim, akey: AnswerKey, value: Any, an: Analysis, tol: Tolerance, base: Verdict
) -> Verdict:
    return _compare(claim, base, float(value), _number(claim), akey.dimension or Dimension.NUMBER, tol, an)


def _number(claim: Claim) -> float:
    """A scalar key's claim as a number (the sheet reader gives a point only to point keys)."""
    if isinstance(claim.value, tuple):
        raise TypeError(f"{claim.key}: a point claimed for a scalar answer")
    return float(claim.value)


# -- points (I-centres, positions) -------------------------------------------------------------
def _fmt_point(p: tuple[float, float], claim: Claim) -> str:
    unit = "m"
    if claim.text.startswith("["):
        for part in claim.text.strip("[]").split(","):
            try:
                q = parse_quantity(part)
            except (KeyError, ValueError):
                continue
            if q.unit:
                unit = q.unit
    big = max(abs(p[0]), abs(p[1]))
    x, y = (c if abs(c) > 1e-9 * big else 0.0 for c in p)  # rounding noise shown as 0
    return f"({to_unit(x, unit):.4g}, {to_unit(y, unit):.4g}) {unit}"


def _direction(ic: Any) -> str:
    d = getattr(ic, "direction", None)
    return f" (direction {math.degrees(math.atan2(d[1], d[0])) % 180.0:.1f}°)" if d else ""


def _cmp_point(
    claim: Claim, akey: AnswerKey, value: Any, an: Analysis, tol: Tolerance, base: Verdict
) -> Verdict:
    """A point within the tolerance times the mechanism's size (or an absolute length)."""
    size = an.kin.size
    allowed = tol.value * size if tol.relative else tol.value
    tol_text = f"{tol} of size {size:.4g} m" if tol.relative else str(tol)
    common = {"unit": "m", "allowed": allowed, "tolerance": tol_text}
    noun = "the I-centre" if akey.family == "icentre" else (akey.names[0] if akey.names else akey.key)
    if claim.value == "infinity":
        if isinstance(value, AtInfinity):
            return _replace(
                base, status=PASS, computed="infinity", message="at infinity" + _direction(value), **common
            )
        return _replace(
            base,
            status=FAIL,
            computed=tuple(value),
            message=f"{noun} is at {_fmt_point(value, claim)}, not at infinity",
            **common,
        )
    if isinstance(value, AtInfinity):
        return _replace(
            base,
            status=FAIL,
            computed="infinity",
            message=f"{noun} is at infinity" + _direction(value) + ", not at a point",
            **common,
        )
    point = tuple(value)
    claimed = claim.value
    err = math.dist(point, claimed)  # type: ignore[arg-type]
    ok = err <= allowed or err <= NOISE * size
    shown = _fmt_point(point, claim)  # type: ignore[arg-type]
    message = shown if ok else f"{noun} is at {shown}: {err / size:.1%} of the size away (allowed {tol_text})"
    if not ok:
        far = max(point, key=abs)
        near = float(claimed[point.index(far)])  # type: ignore[index]  # a point key's claim is a pair
        message += _unit_slip(far, near, claim, Tolerance(0.02))
    return _replace(base, status=PASS if ok else FAIL, computed=point, error=err, message=message, **common)


_COMPARE: dict[Compare, Callable[..., Verdict]] = {
    Compare.COUNT: _cmp_count,
    Compare.LABEL: _cmp_label,
    Compare.POINT: _cmp_point,
    Compare.MAGNITUDE: _cmp_magnitude,
    Compare.SENSE: _cmp_sense,
    Compare.RATIO: _cmp_ratio,
    Compare.SIGNED: _cmp_signed,
}
