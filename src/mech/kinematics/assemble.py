"""The drawn configuration: global positions of every location from the file's data.

Unknowns are the positions of the locations not placed by ``at``; equations
are the file's lengths, the drive angles, "point on path" for prismatic and
slot joints, and relative placements (``from``/``toward`` with ``distance`` or
``offset``).  A first guess comes from closed-form dyads (two lengths to known
points, a length and a path, a drive direction, a relative placement), with
the branch chosen by ``near`` or, failing that, by a documented default rule
reported in the notes:

* a dyad apex (two lengths to known joints P, Q, P listed first in the file)
  lies to the **left of P → Q**;
* a point at a length from a known point on a path lies at the intersection
  **farther along the path's direction** (``through → toward``, or ``angle``).

Gauss–Newton with least-squares steps then polishes every equation at once,
so over-determined but consistent files (a double parallelogram) assemble.
The equations are written by :mod:`.assembly_equations`, the first guess made
by :mod:`.assembly_guess`; this module polishes, checks and explains.
Work is done in shifted, scaled coordinates (origin at a drawn ground joint,
lengths divided by the mechanism's size), so tolerances are relative.

Errors, all in the file's length unit:

* drawn data that disagree with a length or a drive angle also given:
  :class:`InputError` saying by how much — between fixed locations (ground
  pivots) beyond 1e-6 of the size, on a moving location drawn with ``at``
  beyond drawing precision (1e-3 of the size: within it the point is moved to
  where the exact data put it, with a note);
* no assembly (a loop that cannot close): :class:`GeometryError` with the gap;
* a location the data leaves free: :class:`GeometryError` naming it (from the
  SVD null vector) and what to add.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np

from mech._records import dataclass
from mech.errors import GeometryError, InputError, Problem, Where
from mech.kinematics.assembly_equations import Dir, Dist, Eq, Spring, equations, placements, where_of
from mech.kinematics.assembly_guess import construct
from mech.kinematics.layout import Layout
from mech.model import Joint, Mechanism, Placement, Point
from mech.pairs import kind_of
from mech.topology import dof
from mech.units import to_unit

__all__ = ["Drawn", "assemble", "complete"]

_AGREE = 1e-6  # exact data (lengths, angles) that must close together: relative to size
#: Drawing precision: a moving point drawn with ``at`` may lie this far (relative to the
#: mechanism's size) from where the exact lengths and angles put it — 0.1 mm on a 100 mm
#: figure, a coordinate copied to three significant figures.  The exact data win (the point
#: is moved, with a note); farther than this, the drawing and the numbers disagree (an error
#: naming the point).  It was 1e-6, which refused coordinates copied to two decimals.
_DRAWING = 1e-3
#: The springs' weight in the polishing pass: what a drawing may still pull the exact data by
#: is w² of its disagreement (1e-18 of it), while a location only the drawing fixes stays put.
_LET_GO = 1e-9
_CONVERGED = 1e-12  # Gauss-Newton residual, relative to size
_ACCEPT = 1e-10  # accepted residual when convergence is slow (tangent circles)


@dataclass(frozen=True, slots=True)
class Drawn:
    """The assembled (drawn) configuration.

    Attributes
    ----------
    positions
        location name (and synthetic ``#joint.through``/``#joint.toward`` for
        path coordinates) → global position, metres.
    drive_angles
        per drive, the drawn angle (rad) of a rotary drive, None for a slider.
    scale
        the length scale used (m): the largest datum (length, drawn distance).
    notes
        branch choices made by rule.
    """

    positions: dict[str, tuple[float, float]]
    drive_angles: tuple[float | None, ...]
    scale: float
    notes: tuple[str, ...]
    centre: tuple[float, float] = (0.0, 0.0)
    relative: dict[str, tuple[float, float]] | None = (
        None  # positions − centre, never rounded through absolute
    )


#: residual (rows,) and Jacobian (rows, 2·unknowns) of all equations at scaled positions x
_System = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]


def _unscale(p: np.ndarray, scale: float, centre: np.ndarray) -> np.ndarray:
    return p * scale + centre


# -- assembly ------------------------------------------------------------------------
def assemble(
    lay: Layout, *, drive_angles: Sequence[float | None] | None = None, allow_free: bool = False
) -> Drawn:
    """Positions of every location in the drawn configuration.

    The steps: what the file places (:func:`placements`), the scale and
    origin (:func:`_frame`), the equations (:func:`equations`), drawn data
    checked against them (:func:`_check_drawn`), a closed-form first guess
    (:func:`construct`) polished by Gauss–Newton (:func:`_solve`), the
    drawing's own drive angles read where the file gives none.

    Parameters
    ----------
    lay
        The mechanism's layout.
    drive_angles
        Per drive, an angle (rad) to use where the file's drive gives none
        (``--angle`` on a file that only draws ground pivots).
    allow_free
        Accept a configuration the data leave free (any consistent one, noted):
        enough for a mobility count, never for an answer.

    Raises
    ------
    InputError
        Drawn positions disagree with given lengths or drive angles.
    GeometryError
        The data cannot be assembled, or leaves a location free.
    """
    mech = lay.mech
    if not mech.has_geometry:
        grounded = [j for j in mech.joints if mech.ground in j.links]
        raise InputError(
            "positions need geometry: nothing in the file is placed",
            where=grounded[0].where if grounded and grounded[0].where else Where(mech.path),
            source=mech.source,
            hint="place the ground joints with at: [x, y] and give the links' lengths "
            "(mech dof and mech classify need neither)",
        )
    _check_contacts(lay)
    unit = mech.length_unit

    def fmt(v: float) -> str:
        return f"{to_unit(v, unit):.6g} {unit}"

    known, near, places = placements(lay)
    scale, centre = _frame(lay, known, near, places)
    eqs, resolved_angles = equations(lay, places, scale, drive_angles, fmt)
    # Every name an equation uses must be a location.
    problems = [
        Problem(f"{e.text}: {n} is not a joint or point with a position")
        for e in eqs
        for n in e.names
        if n not in lay.carriers and n not in known
    ]
    if problems:
        raise InputError(problems=problems, source=mech.source)
    scaled_known = {n: (np.asarray(xy, dtype=float) - centre) / scale for n, xy in known.items()}
    # A moving location drawn with ``at`` is good to the drawing's precision, while the lengths
    # and angles a file gives are exact: solve for it too, held to its drawing by a weak spring,
    # so that where the drawing is rounded the exact numbers win (and any disagreement larger
    # than drawing precision is reported by _solve).  Ground locations and path coordinates stay fixed.
    soft = {
        n: v for n, v in scaled_known.items() if lay.carriers.get(n) and mech.ground not in lay.carriers[n]
    }
    fixed = {n: v for n, v in scaled_known.items() if n not in soft}
    _check_drawn(mech, eqs, scaled_known, set(soft), (scale, fmt))
    guess, notes, gaps = construct(lay, eqs, scaled_known, near, centre, scale)
    guess.update(soft)
    # Contact points of higher pairs are data of the instant (``at``), never unknowns.
    unknown = [n for n, c in lay.carriers.items() if c and n not in fixed]
    solved = _solve(lay, eqs, guess, fixed, soft, unknown, gaps, notes, (scale, centre, fmt), allow_free)

    positions: dict[str, tuple[float, float]] = {}
    for n, p in fixed.items():
        xy = p * scale + centre
        positions[n] = (float(xy[0]), float(xy[1]))
    # Relative to the centre (a ground pivot) as well: far from the origin, absolute coordinates
    # round a millimetre link's end to the ulp there (1.2e-4 m at 1e12 m), so the constraint
    # system is built from these instead.
    relative = {n: (float(p[0] * scale), float(p[1] * scale)) for n, p in fixed.items()}
    for n in unknown:
        rel = solved[n] * scale
        relative[n] = (float(rel[0]), float(rel[1]))
        p = rel + centre
        positions[n] = (float(p[0]), float(p[1]))
    for e in eqs:  # a drive's equation holds on the whole line: the point must be on the ray
        if isinstance(e, Dir):
            pts = [(np.asarray(positions[n]) - centre) / scale for n in e.names]
            if not e.forward(pts):
                raise GeometryError(
                    _disagreement(e, pts, scale, fmt),
                    where=e.where,
                    hint="give near: on the driven link's other joint, on the side the crank points to",
                )
    _check_drawing(lay, positions, fmt)
    _drawn_drive_angles(lay, positions, resolved_angles)
    complete(lay, positions)
    cx, cy = float(centre[0]), float(centre[1])
    for n, xy in positions.items():
        relative.setdefault(n, (xy[0] - cx, xy[1] - cy))
    return Drawn(positions, tuple(resolved_angles), scale, tuple(notes), (cx, cy), relative)


def _frame(
    lay: Layout,
    known: dict[str, tuple[float, float]],
    near: dict[str, tuple[float, float]],
    places: dict[str, Placement],
) -> tuple[float, np.ndarray]:
    """Scale: the largest datum; origin: a drawn ground location (translation invariance)."""
    mech = lay.mech
    data = [abs(x.value) for x in mech.lengths]
    pts = list(known.values()) + list(near.values())
    if pts:
        arr = np.array(pts, dtype=float)
        data.append(float(np.max(np.ptp(arr, axis=0))) if len(pts) > 1 else 0.0)
    for pl in places.values():
        if pl.distance is not None:
            data.append(abs(pl.distance))
        if pl.offset is not None:
            data.append(math.hypot(*pl.offset))
    scale = max(data) if data and max(data) > 0 else 1.0
    grounded = [n for n in lay.on_link.get(mech.ground, ()) if n in known]
    centre = np.array(known[grounded[0]] if grounded else (pts[0] if pts else (0.0, 0.0)), dtype=float)
    return scale, centre


def _check_drawn(
    mech: Mechanism,
    eqs: list[Eq],
    scaled_known: dict[str, np.ndarray],
    soft: set[str],
    frame: tuple[float, Callable[[float], str]],
) -> None:
    """Drawn data must agree with the lengths and drive angles given as well.

    Between fixed locations (ground pivots, path coordinates) the data are exact and must agree
    to 1e-6 of the size.  An equation on a moving location drawn with ``at`` (in ``soft``) is
    judged by drawing precision instead: it is refused here only when no movement of its drawn
    points within :data:`_DRAWING` of the size could close it (to first order, the residual
    exceeds ``_DRAWING`` times the sum of its gradients' norms over those points), so every
    refusal here is one the solve would make, said at the length or angle that disagrees; the
    rest is left to the solve, which moves the points and notes it.
    """
    scale, fmt = frame
    disagree: list[Problem] = []
    agree_hint = "make the drawing and the numbers agree, or give only one of them (`at` on a moving joint means drawn here)"
    for e in eqs:
        if all(n in scaled_known for n in e.names):
            p = [scaled_known[n] for n in e.names]
            r, grads = e.value(p)
            # how far the residual can go if each drawn moving point moves by drawing precision
            slack = sum(float(np.linalg.norm(g, 2)) for n, g in zip(e.names, grads, strict=True) if n in soft)
            opposite = isinstance(e, Dir) and not e.forward(p)
            if float(np.max(np.abs(r))) > _AGREE + _DRAWING * slack or opposite:
                disagree.append(Problem(_disagreement(e, p, scale, fmt), e.where, agree_hint))
    if disagree:
        raise InputError(problems=disagree, source=mech.source)


def _solve(
    lay: Layout,
    eqs: list[Eq],
    guess: dict[str, np.ndarray],
    fixed: dict[str, np.ndarray],
    soft: dict[str, np.ndarray],
    unknown: list[str],
    gaps: list[str],
    notes: list[str],
    frame: tuple[float, np.ndarray, Callable[[float], str]],
    allow_free: bool,
) -> dict[str, np.ndarray]:
    """Gauss–Newton from the first guess: every unknown location (scaled), checked.

    Raises when the loop cannot close, when a drawn moving location lies farther
    from its solved place than drawing precision, or when the data leave a
    location free (unless ``allow_free``); notes a drawing rounded to agree.
    """
    if not unknown:
        return {}
    mech = lay.mech
    scale, centre, fmt = frame
    col = {n: i for i, n in enumerate(unknown)}
    x = np.concatenate([guess[n] for n in unknown])
    live = [e for e in eqs if any(n in col for n in e.names)]
    springs: list[Eq] = [Spring(n, v) for n, v in soft.items()]

    def system(xv: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        eq_all = live + springs
        nrows = sum(e.rows for e in eq_all)
        res = np.empty(nrows)
        jac = np.zeros((nrows, xv.size))
        row = 0
        for e in eq_all:
            pos = [xv[2 * col[n] : 2 * col[n] + 2] if n in col else fixed[n] for n in e.names]
            r, grads = e.value(pos)
            res[row : row + e.rows] = r
            for n, g in zip(e.names, grads, strict=False):
                if n in col:
                    jac[row : row + e.rows, 2 * col[n] : 2 * col[n] + 2] += g
            row += e.rows
        return res, jac

    x, res_all, jac = _gauss_newton(system, x)
    if springs:
        x, res_all, jac = _let_go(system, x, springs)
    res = res_all[: sum(e.rows for e in live)]  # the file's equations, without the springs
    worst = float(np.max(np.abs(res))) if res.size else 0.0
    if worst > _AGREE:
        raise GeometryError(
            _no_assembly(mech.label, live, res, gaps, scale, fmt),
            where=_worst_where(live, res) or (lay.drives[0].drive.where if lay.drives else None),
            hint="check the lengths; a rocker or a slider has limits: try another crank angle (--angle)",
        )
    moved = {n: float(np.hypot(*(x[2 * col[n] : 2 * col[n] + 2] - v))) for n, v in soft.items()}
    far = [n for n, d in moved.items() if d > _DRAWING]
    if far:
        raise InputError(
            problems=[
                Problem(
                    f"{n} is drawn at ({fmt(_unscale(soft[n], scale, centre)[0])}, "
                    f"{fmt(_unscale(soft[n], scale, centre)[1])}), but the lengths and angles put it "
                    f"{fmt(moved[n] * scale)} away",
                    where_of(mech, n),
                    "make the drawing and the numbers agree, or give only one of them "
                    "(`at` on a moving joint means drawn here)",
                )
                for n in far
            ],
            source=mech.source,
        )
    if moved and max(moved.values()) > _ACCEPT:  # drawn data rounded to a few decimals
        n = max(moved, key=moved.__getitem__)
        notes.append(
            f"drawn positions moved by up to {fmt(moved[n] * scale)} ({n}) to agree with the given "
            f"lengths and angles (drawing precision: within {_DRAWING:g} of the size)"
        )
    if allow_free:
        if jac.shape[0] < x.size or np.linalg.matrix_rank(jac, tol=1e-8) < x.size:
            notes.append("the file leaves the configuration free: one consistent configuration used")
    else:
        _check_determined(system, x, jac, unknown, lay)
    return {n: x[2 * col[n] : 2 * col[n] + 2] for n in unknown}


def _drawn_drive_angles(
    lay: Layout, positions: dict[str, tuple[float, float]], resolved_angles: list[float | None]
) -> None:
    """Drive angles not given: read from the drawing (in place).  A disc with only its pivot
    (a cam, a gear) has no line to read, and its drawn angle is taken as 0.
    """
    for k, spec in enumerate(lay.drives):
        if resolved_angles[k] is None and spec.link is not None:
            if spec.pivot is None or spec.toward is None:  # (a rotary drive always has a pivot)
                resolved_angles[k] = 0.0
                continue
            pivot_xy, toward_xy = positions[spec.pivot], positions[spec.toward]
            drawn = math.atan2(toward_xy[1] - pivot_xy[1], toward_xy[0] - pivot_xy[0])
            if spec.reference_line is not None:  # θ_b − θ_a
                r0, r1 = (positions[n] for n in spec.reference_line)
                drawn = math.remainder(drawn - math.atan2(r1[1] - r0[1], r1[0] - r0[0]), 2 * math.pi)
            resolved_angles[k] = drawn


def _let_go(system: _System, x: np.ndarray, springs: list[Eq]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Polish with the springs all but let go, so the exact data win (a spring leaks w² of a gap).

    Returns x and the residual and Jacobian with the springs at their usual weight again.
    """
    for spring in springs:
        spring.weight = _LET_GO  # type: ignore[attr-defined]
    x, _, _ = _gauss_newton(system, x)
    for spring in springs:
        spring.weight = Spring.weight  # type: ignore[attr-defined]
    res, jac = system(x)
    return x, res, jac


def _gauss_newton(
    system: _System, x: np.ndarray, max_iter: int = 100
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Least-squares Gauss–Newton with step halving; returns (x, residual, Jacobian)."""
    res, jac = system(x)
    norm = float(np.linalg.norm(res))
    for _ in range(max_iter):
        if norm == 0.0 or float(np.max(np.abs(res))) < _CONVERGED * 1e-3:
            break
        step = np.linalg.lstsq(jac, -res, rcond=None)[0]
        t = 1.0
        while True:
            x_new = x + t * step
            res_new, jac_new = system(x_new)
            norm_new = float(np.linalg.norm(res_new))
            if norm_new < norm or t < 1e-6:
                break
            t *= 0.5
        if norm_new >= norm and t < 1e-6:
            break
        x, res, jac, norm = x_new, res_new, jac_new, norm_new
        if float(np.max(np.abs(t * step))) < 1e-15:
            break
    return x, res, jac


def _check_determined(
    system: _System, x: np.ndarray, jac: np.ndarray, unknown: list[str], lay: Layout
) -> None:
    """Raise when the equations leave a continuous freedom (not merely a tangent double root)."""
    n = x.size
    if jac.shape[0] >= n:
        s = np.linalg.svd(jac, compute_uv=False)
        if s[-1] > 1e-8 * max(s[0], 1.0):
            return
    _, s, vt = np.linalg.svd(jac)
    s_full = np.zeros(n)
    s_full[: s.size] = s
    null = vt[s_full <= 1e-8 * max(s_full[0] if s.size else 1.0, 1.0)]
    # A tangent (double) root is determined; a real freedom stays solvable when nudged.
    free_dirs = []
    for v in null:
        nudged, res, _ = _gauss_newton(system, x + 1e-3 * v, max_iter=30)
        # no equation at all on a location (a ground pivot without `at`): any nudge stands
        closes = res.size == 0 or float(np.max(np.abs(res))) <= _ACCEPT
        if closes and float(np.linalg.norm(nudged - x)) > 1e-4:
            free_dirs.append(v)
    if not free_dirs:
        return
    weight = np.zeros(len(unknown))
    for v in free_dirs:
        weight = np.maximum(weight, np.hypot(v[0::2], v[1::2]))
    names = [unknown[i] for i in np.argsort(-weight) if weight[i] > 0.2 * weight.max()]
    hint = (
        "place one of them with at, give a length that fixes it, or give it a relative placement; "
        "a mechanism with more degrees of freedom than drives needs one drive per freedom"
    )
    undriven = [s for s in lay.drives if s.link is not None and s.drive.angle is None and s.toward in names]
    unplaced = [n for n in names if lay.mech.ground in lay.carriers.get(n, ())]
    if unplaced:  # the usual cause: a ground pivot the file does not place
        where_first = next(x for x in lay.mech.joints if x.name == unplaced[0]).where
        raise GeometryError(
            f"{unplaced[0]} is on the ground link {lay.mech.ground} but not placed: "
            f"{', '.join(names)} can still move with everything given",
            where=where_first,
            hint=f"place it with at: [x, y] (every joint on the {lay.mech.ground} needs one)",
        )
    if undriven:
        hint = f"give the drive of {undriven[0].link} an angle (or draw {undriven[0].toward} with at)"
    listed = ", ".join(names)
    located: list[Joint | Point] = [*lay.mech.joints, *lay.mech.points]
    first = next((x for x in located if x.name in names), None)
    message = (
        f"the file does not fix where {listed} {'is' if len(names) == 1 else 'are'}: "
        f"{'it' if len(names) == 1 else 'they'} can still move with everything given"
    )
    count = dof(lay.mech)
    if len(lay.drives) < count.n and not undriven:
        # the usual cause: a mechanism of several degrees of freedom given fewer drives
        drives = f"{len(lay.drives)} drive{'s' if len(lay.drives) != 1 else ''}"
        message = (
            f"{lay.mech.label} has {count.n} degrees of freedom ({count.formula}) but {drives}: " + message
        )
        hint = f"give one drive per degree of freedom: drive: [{{link: …, angle: …, rpm: …}}, …] ({count.n} of them)"
    raise GeometryError(message, where=first.where if first is not None else Where(lay.mech.path), hint=hint)


def _disagreement(e: Eq, p: list[np.ndarray], scale: float, fmt: Callable[[float], str]) -> str:
    """``length BC = 150 mm but the drawing gives 148.3 mm`` and the like."""
    if isinstance(e, Dist):
        d = float(np.hypot(*(p[1] - p[0]))) * scale
        return f"{e.text} but the drawing gives {fmt(d)} (off by {fmt(abs(d - e.length * scale))})"
    if isinstance(e, Dir):
        w = p[1] - p[0]
        drawn = math.atan2(w[1], w[0])
        psi = e.angle(p)
        return (
            f"{e.text} but the drawing gives {math.degrees(drawn - psi + e.phi):.6g}° "
            f"(off by {abs(math.degrees(math.remainder(drawn - psi, 2 * math.pi))):.3g}°)"
        )
    r, _ = e.value(p)
    return f"{e.text}: the drawing is off by {fmt(float(np.hypot(*r)) * scale if r.size == 2 else abs(float(r[0])) * scale)}"


def _worst_where(eqs: list[Eq], res: np.ndarray) -> Where | None:
    """Where the equation that misses most was written (for a located message)."""
    row, best, where = 0, -1.0, None
    for e in eqs:
        r = res[row : row + e.rows]
        row += e.rows
        miss = float(np.max(np.abs(r))) if r.size else 0.0
        if miss > best and e.where is not None:
            best, where = miss, e.where
    return where


def _no_assembly(
    label: str, eqs: list[Eq], res: np.ndarray, gaps: list[str], scale: float, fmt: Callable[[float], str]
) -> str:
    """The gap of the closest assembly, in the file's unit."""
    import re

    def units(text: str) -> str:
        return re.sub(r"\{([^}]*)\}", lambda m: fmt(float(m.group(1)) * scale), text)

    if gaps:
        return f"cannot assemble {label}: " + "; ".join(units(g) for g in gaps)
    row, parts = 0, []
    for e in eqs:
        r = res[row : row + e.rows]
        row += e.rows
        miss = float(np.hypot(*r)) if r.size == 2 else abs(float(r[0]))
        if miss > _ACCEPT:
            parts.append((miss, f"{e.text} misses by {fmt(miss * scale)}"))
    parts.sort(reverse=True)
    return f"cannot assemble {label}: in the closest configuration " + "; ".join(p for _, p in parts[:3])


def _check_contacts(lay: Layout) -> None:
    """Higher pairs describe the drawn instant: each needs what its kind says (its contact point)."""
    problems = [p for j in lay.contacts if (p := kind_of(j).contact_problem(j)) is not None]
    if problems:
        raise InputError(problems=problems, source=lay.mech.source)


def _check_drawing(
    lay: Layout, positions: dict[str, tuple[float, float]], fmt: Callable[[float], str]
) -> None:
    """Each pair as drawn must be possible (gears' centres as far apart as their pitch radii say)."""
    problems = [
        p for j in lay.mech.joints if (p := kind_of(j).drawing_problem(lay, j, positions, fmt)) is not None
    ]
    if problems:
        raise InputError(problems=problems, source=lay.mech.source)


def complete(lay: Layout, positions: dict[str, tuple[float, float]]) -> None:
    """Positions each pair's kind derives in a configuration (a gear's pitch point from its centres)."""
    for j in lay.mech.joints:
        kind_of(j).complete(lay, j, positions)
