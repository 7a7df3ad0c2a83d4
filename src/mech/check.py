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
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import field
from typing import TYPE_CHECKING, Any

from mech._records import dataclass
from mech.answers import LEVELS, AnswerKey, AtInfinity, Compare, Undefined, parse_key
from mech.errors import MechError, Problem, Where
from mech.model import Claim, Mechanism, Tolerance
from mech.options import SolveOptions
from mech.pairs import located_on
from mech.units import Dimension, format_unit, parse_quantity, to_unit

if TYPE_CHECKING:  # pragma: no cover
    from mech.kinematics import Kinematics
    from mech.topology import Topology

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
]

PASS = "pass"
FAIL = "fail"
ERROR = "error"
#: A sheet key that is not a question of its problem (or a sheet entry naming no problem):
#: reported, never scored.
IGNORED = "ignored"

#: Errors below this fraction of the mechanism's own scale are rounding, not a wrong answer.
NOISE = 1e-6

_SOLVED = ("position", "velocity", "acceleration")


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

    @property
    def passed(self) -> bool:
        return self.status == PASS

    @property
    def scored(self) -> bool:
        """Counted in a score (pass, fail, error); an ignored sheet key is not."""
        return self.status != IGNORED


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


def check_file(path: str, *, options: SolveOptions | None = None) -> FileResult:
    """Load one problem file and check the answers it carries.

    The function to map over many machines (Dask ``client.map``, Ray): it
    takes a path and returns a picklable, frozen result; a file that cannot
    be read becomes its error row instead of an exception, and a file with no
    answers a ``skipped`` row (``mech check`` runs the same function).
    """
    from mech.batch import probe, special_result
    from mech.loader import load

    why = probe(path)  # a FIFO or a device is never opened; a dangling link is named
    if why is not None:
        return special_result(path, why)
    try:
        mech = load(path)
    except MechError as error:
        return error_result(path, error)
    if not mech.answers:
        return FileResult(path=path, name=mech.name, skipped=True)
    return FileResult(path=path, name=mech.name, verdicts=check(mech, options=options))


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
    analysis.need(claims)
    return tuple(_verdict(claim, analysis, tolerance) for claim in claims)


# -- what is computed, once and only when asked ------------------------------------------
class Analysis:
    """The computed side of a check, each piece made on first use and kept.

    A solve that fails is kept as its error, so that every claim needing it
    gets the same reason without solving again.
    """

    #: Errors below this fraction of the mechanism's own scale are rounding (see the module doc).
    noise = NOISE

    def __init__(self, mech: Mechanism, *, options: SolveOptions | None = None) -> None:
        self.mech = mech
        self.options = options or SolveOptions()
        self.level = "topology"
        self._cache: dict[str, Any] = {}

    def need(self, claims: Sequence[Claim] | Sequence[str]) -> None:
        """Raise the solve level to the highest any claim (or key) needs, before anything is solved."""
        for claim in claims:
            level = parse_key(claim if isinstance(claim, str) else claim.key).level
            if level in _SOLVED and LEVELS.index(level) > LEVELS.index(self.level):
                self.level = level
                # a solve made for a lower level is not enough any more
                for name in [n for n in self._cache if n not in ("topology", "mobility")]:
                    del self._cache[name]

    def cached(self, name: str, make: Callable[[], Any]) -> Any:
        """``make()`` once per analysis (a solve's error is kept and raised again): for answer keys
        whose reference value costs (a sweep for ``transmission_angle.min``)."""
        return self._get(name, make)

    def _get(self, name: str, make: Callable[[], Any]) -> Any:
        if name not in self._cache:
            try:
                self._cache[name] = make()
            except MechError as error:
                self._cache[name] = error
            except Exception as exc:  # a bug in an analysis: one file's rows say so, the batch goes on
                self._cache[name] = InternalError.of(exc)
        value = self._cache[name]
        if isinstance(value, (MechError, InternalError)):
            raise value
        return value

    @property
    def topology(self) -> Topology:
        from mech.topology import classify

        return self._get("topology", lambda: classify(self.mech))

    @property
    def mobility(self) -> int | None:
        def make() -> int | None:
            if "kin" in self._cache and not isinstance(self._cache["kin"], MechError):
                return self._cache["kin"].mobility.numeric
            from mech.kinematics import mobility

            return mobility(self.mech).numeric

        return self._get("mobility", make)

    @property
    def kin(self) -> Kinematics:
        def make() -> Kinematics:
            from mech.analysis import solve_at

            level = self.level if self.level in _SOLVED else "position"
            return solve_at(self.mech, level, self.options)

        return self._get("kin", make)

    @property
    def icentres(self) -> Any:
        def make() -> Any:
            try:
                from mech.analysis import locate_icentres
            except ImportError as exc:  # the module, or its locate(), is not there
                if exc.name != "mech.icentres":
                    raise
                from mech.errors import UnsupportedError

                raise UnsupportedError("I-centres are not available in this version of mech") from None
            return locate_icentres(self.mech, self.kin)

        return self._get("icentres", make)

    # -- the mechanism's own scales, for the rounding floor ---------------------------------
    @property
    def omega_ref(self) -> float:
        """The fastest link's |ω| (rad/s); for a pure translation, the fastest point's speed / size."""
        kin = self.kin
        w = max((abs(s.omega or 0.0) for s in kin.links.values()), default=0.0)
        if w > 0.0:
            return w
        speeds = [math.hypot(*s.velocity) for s in kin.links.values() if s.velocity is not None]
        return max(speeds, default=0.0) / kin.size if kin.size > 0 else 0.0

    def scale(self, dimension: Dimension | None) -> float:
        """The mechanism's natural unit of a quantity: size, ω, ω·size, ω²·size, ω².

        Angles need no solve (their unit is the radian).  A key answered without the
        linkage solver (a cam's programme, which the instant solver cannot place) gets
        no rounding floor when that solve fails: its tolerance alone decides.
        """
        if dimension in (None, Dimension.NUMBER, Dimension.ANGLE):
            return 1.0
        try:
            size = self.kin.size
            w = self.omega_ref
        except MechError:
            return 0.0
        return {
            Dimension.LENGTH: size,
            Dimension.ANGULAR_VELOCITY: w,
            Dimension.VELOCITY: w * size,
            Dimension.ACCELERATION: w * w * size,
            Dimension.ANGULAR_ACCELERATION: w * w,
        }.get(dimension, 1.0)


# -- one claim -------------------------------------------------------------------------------
def _verdict(claim: Claim, analysis: Analysis, default: Tolerance) -> Verdict:
    akey = parse_key(claim.key)
    base = Verdict(claim.key, ERROR, claimed=claim.text or str(claim.value), where=claim.where)
    tolerance = claim.tolerance or default
    try:
        value = akey.kind.compute(analysis, akey.names)
        verdict = _COMPARE[akey.compare](claim, akey, value, analysis, tolerance, base)
    except MechError as error:
        return _replace(base, status=ERROR, message=f"cannot be computed: {_reason(error)}")
    except (Undefined, InternalError) as why:
        return _replace(base, status=ERROR, message=str(why))
    except Exception as exc:  # a bug in a key's computation: this row says so, the others stand
        return _replace(base, status=ERROR, message=str(InternalError.of(exc)))
    if verdict.status == FAIL:
        from mech.diagnose import diagnose

        try:
            found = diagnose(claim, akey, value, analysis, tolerance)
        except Exception:  # a diagnosis is a bonus: it never costs the verdict
            found = None
        if found:
            verdict = _replace(verdict, diagnosis=found)
    return verdict


class InternalError(Exception):
    """A bug in mech met while checking: reported as an error row that says it is a bug.

    Not a :class:`MechError` (the input is not at fault) and not swallowed:
    the row names the exception and where it was raised, the exit status is 1.
    """

    @classmethod
    def of(cls, exc: BaseException) -> InternalError:
        import traceback

        frames = traceback.extract_tb(exc.__traceback__)
        ours = [f for f in frames if "/mech/" in f.filename.replace("\\", "/")] or frames
        at = (
            f" at {'/'.join(ours[-1].filename.replace(chr(92), '/').split('/')[-2:])}:{ours[-1].lineno}"
            if ours
            else ""
        )
        return cls(f"internal error in mech (a bug, please report it): {type(exc).__name__}: {exc}{at}")


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
def _cmp_count(
    claim: Claim, akey: AnswerKey, computed: Any, an: Analysis, tol: Tolerance, base: Verdict
) -> Verdict:
    key = akey.key
    ok = computed == claim.value
    return _replace(
        base,
        status=PASS if ok else FAIL,
        computed=computed,
        error=float(abs(computed - int(claim.value))),  # type: ignore[arg-type]
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
        "" if dimension in (Dimension.NUMBER,) or sense else _unit_slip(computed, claimed, claim, tolerance)
    )
    if slip:
        message = f"{what}{shown}{slip}"
    elif sense and computed * claimed < 0 and abs(computed) > floor:
        message = f"wrong sense: {what}{shown}, claimed {claim.sense or ('ccw' if claimed > 0 else 'cw')}"
    elif tolerance.relative and computed != 0.0:
        message = f"{what}{shown}: off by {err / abs(computed):.1%} (allowed {tolerance})"
    else:
        message = f"{what}{shown}: off by {_show(err, claim, dimension, sense=False)} (allowed {tolerance})"
    return _replace(base, status=FAIL, message=message, **common)


_SLIPS = {1e3: "mm", 1e2: "cm"}


def _unit_slip(computed: float, claimed: float, claim: Claim, tolerance: Tolerance) -> str:
    """A hint when a bare claim is the computed value in mm or cm: bare numbers are SI."""
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


def least_speed(mech: Mechanism, kin: Kinematics, link: str) -> float:
    """The least speed (m/s) of any point on the line through a link's joints.

    For a point ``P(s) = A + s·u`` on the line (``u`` a unit vector along it),
    ``v(s) = v_A + ω k × (s u) = v_A + ω s u⊥``: the component along the line,
    ``v_A · u``, is the same for every point (the line is rigid), and the
    component across it, ``v_A · u⊥ + ω s``, vanishes at ``s = −(v_A · u⊥)/ω``
    (the foot of the perpendicular from the link's I-centre).  So the least
    speed is ``|v_A · u|`` for a turning link and ``|v_A|`` for a translating one.

    Raises
    ------
    InputError
        When the link has fewer than two joints with a point, or its joints are
        not on one line.
    """
    from mech.errors import InputError

    names = [j.name for j in mech.joints if link in located_on(j) and j.name in kin.positions]
    if len(names) < 2:
        raise InputError(
            f"least_speed needs two joints on {link} to draw its line; it has {len(names)}"
            + (f" ({', '.join(names)})" if names else "")
        )
    a = kin.positions[names[0]]
    far = max(names[1:], key=lambda n: math.dist(a, kin.positions[n]))
    b = kin.positions[far]
    length = math.dist(a, b)
    if length <= 0.0:
        raise InputError(f"the joints of {link} coincide: no line through them")
    u = ((b[0] - a[0]) / length, (b[1] - a[1]) / length)
    for n in names[1:]:
        p = kin.positions[n]
        off = abs((p[0] - a[0]) * u[1] - (p[1] - a[1]) * u[0])
        if off > 1e-9 * max(kin.size, length):
            raise InputError(
                f"the joints of {link} ({', '.join(names)}) are not on one line: least_speed is for a link's line of joints"
            )
    va = kin.velocity(names[0], link)
    omega = kin.links[link].omega or 0.0
    if abs(omega) * length <= NOISE * max(_mag(va), 1e-300):
        return _mag(va)
    return abs(va[0] * u[0] + va[1] * u[1])


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
