"""The compiled mechanism: everything about it that does not depend on the asked angle or speed.

Layout, drawn configuration, constraint system, mobility and Φ_q as drawn, made once
and kept on the mechanism (:func:`compiled`); with them the checks that depend on
the mechanism alone, also made once: Kutzbach's refusal of an under-driven file
(:func:`refuse_underdriven`) and the toggle test of the drawn configuration
(:attr:`Compiled.singular`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import field

import numpy as np

from mech._memo import Memo
from mech._records import dataclass
from mech.errors import GeometryError, InputError, Where
from mech.kinematics.assemble import Drawn, assemble
from mech.kinematics.blocks import BlockForm
from mech.kinematics.constraints import System, build_system
from mech.kinematics.layout import Layout, layout
from mech.kinematics.linalg import SINGULAR, blocks_of, is_singular, padded_svd, pinv
from mech.kinematics.mobility import kutzbach, numeric_mobility
from mech.kinematics.result import Mobility
from mech.model import Mechanism
from mech.pairs import kind_of

__all__ = ["Compiled", "compiled", "instant_pairs", "instant_why", "mobility", "refuse_underdriven"]


@dataclass(frozen=True, slots=True)
class Compiled:
    """Everything about a mechanism that does not depend on the asked angle or speed.

    With it, what is judged of the drawn configuration, each made once when first
    asked and kept in :attr:`memo`: the toggle test (:attr:`singular`), the SVD of Φ_q
    as drawn that the drawn rates are solved and bounded with (:meth:`drawn_svd`,
    :meth:`drawn_inverse`; a large chain's block condition, :meth:`drawn_blocks`),
    and whether the drives match the mobility (:meth:`refuse_drives`).
    """

    mech: Mechanism
    layout: Layout
    drawn: Drawn
    system: System
    mobility: Mobility
    #: Φ_q with the drive rows at the drawn configuration (read-only): the rates of a solve that
    #: is not moved use it again.
    jacobian: np.ndarray
    #: Whether Φ_q is singular as drawn, judged block by block (a large chain); None: by the
    #: drawn SVD when first asked (:attr:`singular`).
    judged: bool | None
    #: What is derived from it in turn (each solve's plan, the closed-form program, the drawn checks).
    memo: Memo = field(default_factory=Memo, init=False, repr=False, compare=False, hash=False)

    @property
    def singular(self) -> bool:
        """Φ_q with drive rows is singular at the drawn configuration (a toggle drawn)."""
        if self.judged is not None:
            return self.judged
        return self.memo.get("singular", lambda: is_singular(self.jacobian, self.drawn_svd()[1]))

    def drawn_svd(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The SVD of Φ_q with drive rows as drawn (:func:`~mech.kinematics.linalg.padded_svd`), made once."""
        return self.memo.get("drawn svd", lambda: padded_svd(self.jacobian))

    def drawn_inverse(self) -> np.ndarray:
        """Φ_q⁺ as drawn, from :meth:`drawn_svd` (for the componentwise error bound of the drawn rates)."""
        return self.memo.get("drawn inverse", lambda: pinv(self.drawn_svd()))

    def drawn_blocks(self, form: BlockForm) -> tuple[float, np.ndarray | None]:
        """A large chain's block condition number as drawn, and its null vector when singular, made once."""
        return self.memo.get("drawn blocks", lambda: form.condition(self.jacobian))

    def refuse_drives(self, count: int) -> None:
        """Refuse ``count`` drives where the mobility by the Jacobian's rank asks for another number.

        At a drawn toggle the rank drops and mobility looks one higher: that is the
        singularity (reported by the velocity solve), not a missing drive.  Judged once
        per mechanism and count; the error is raised afresh each time.

        Raises
        ------
        InputError
            The drives are more or fewer than the mobility: how many it needs.
        """
        numeric = self.mobility.numeric
        mismatch = self.memo.get(
            ("drives match", count),
            lambda: (
                numeric is not None
                and count != numeric
                and not (numeric > count and count == kutzbach(self.mech) and self.singular)
            ),
        )
        if not mismatch or numeric is None:
            return
        mech, more = self.mech, count > numeric
        raise InputError(
            f"{mech.label} has mobility {numeric} (from the constraint Jacobian's rank) but "
            f"{count} drive{'s' if count != 1 else ''}: "
            + ("more drives than it can take" if more else f"it needs {numeric} inputs"),
            where=mech.drives[0].where if mech.drives else None,
            hint=(
                "remove a drive"
                if more
                else f"give one drive per degree of freedom: drive: [{{link: …, rpm: …}}, …] ({numeric} of them)"
            ),
            source=mech.source,
        )


def compiled(
    mech: Mechanism, angles: tuple[float | None, ...] | None, *, allow_free: bool = False
) -> Compiled:
    """Layout, drawn configuration, constraint system and mobility of ``mech`` (remembered).

    Kept in the mechanism's own memo (:class:`mech._memo.Memo`): the model is
    immutable, so an entry never goes stale, and it goes when the mechanism goes.
    """
    return mech.memo.get(("compiled", angles, allow_free), lambda: _compile(mech, angles, allow_free))


def _compile(mech: Mechanism, angles: tuple[float | None, ...] | None, allow_free: bool) -> Compiled:
    lay = layout(mech)
    drawn = assemble(lay, drive_angles=angles, allow_free=allow_free)
    system = build_system(lay, drawn)
    jac = system.jacobian(system.q0)  # once, for the rank, the drawn toggle and the drawn rates
    jac.setflags(write=False)
    form = blocks_of(system)
    if form is None:
        mob = numeric_mobility(mech, system, system.q0, jacobian=jac)
        return Compiled(mech, lay, drawn, system, mob, jac, None)  # the toggle: judged if asked
    # A large chain, square with its drives: judged block by block, as its velocities are solved
    # (two dense SVDs of a 6,000-column Φ_q took 380 s on a 2,000-link chain of dyads).
    cond, null = form.condition(jac)
    singular = cond > SINGULAR
    mob = numeric_mobility(
        mech, system, system.q0, jacobian=jac, nonsingular=None if singular else (form, cond)
    )
    comp = Compiled(mech, lay, drawn, system, mob, jac, singular)
    comp.memo.get("drawn blocks", lambda: (cond, null))  # the drawn rates' check, judged already
    return comp


def mobility(mech: Mechanism) -> Mobility:
    """Numeric mobility at the drawn configuration; no drive needed.

    A file whose data leave the configuration free (no drive angle, nothing
    drawn on the moving links) is assembled in some consistent configuration,
    which gives the generic rank (:func:`mech.kinematics.mobility.numeric_mobility`).
    It lives here, beside :func:`compiled`, so that :mod:`.mobility` (the rank
    itself) never imports the solver that imports it.

    Raises
    ------
    InputError
        When the file has no geometry (nothing placed by ``at``).
    GeometryError
        When it cannot be assembled.

    Examples
    --------
    >>> from mech.kinematics import mobility                    # doctest: +SKIP
    >>> mobility(mech).numeric                                  # doctest: +SKIP
    1
    """
    if not mech.has_geometry:
        raise InputError(
            "numeric mobility needs geometry: nothing in the file is placed",
            hint="place the ground joints with at and give the links' lengths",
        )
    try:
        return compiled(mech, None, allow_free=True).mobility
    except (GeometryError, InputError) as error:
        # A ground pivot without `at` is put anywhere by a free assembly: a gear mesh or a length
        # that then fails quotes a distance mech made up.  Name the pivot instead.
        unplaced = [
            j
            for j in mech.joints
            if mech.ground in j.links
            and kind_of(j).located != "none"
            and j.place.at is None
            and not j.place.is_relative
            and not kind_of(j).higher
        ]
        if not unplaced:
            raise
        first = unplaced[0]
        raise GeometryError(
            f"{first.name} is on the ground link {mech.ground} but not placed, so the assembly put it "
            f"anywhere and then: {error.problems[0].message}",
            where=first.where,
            hint=f"place it with at: [x, y] (every joint on the {mech.ground} needs one)",
            source=mech.source,
        ) from error


def refuse_underdriven(mech: Mechanism) -> None:
    """Refuse, from the counts alone, a mechanism with more degrees of freedom than drives.

    Each joint writes at most the rows Kutzbach counts for it (a pin of k links
    2(k − 1), a prismatic or rolling pair 2, a slot, cam, contact or gear 1:
    :func:`mech.kinematics.mobility.kutzbach`), so ``rank Φ_q ≤ 2j + h`` and the
    true mobility ``3(l − 1) − rank Φ_q`` is at least Kutzbach's count.  When
    that count alone exceeds the drives, the mechanism can move with every
    drive held whatever its geometry: refused here, before the assembly and the
    rank (a dense SVD that takes minutes on a 2,000-link chain).  The count may
    be *below* the true mobility (a double parallelogram: 0 against 1), so it
    never refuses the other way; that is the rank's test in :func:`solve`.

    Raises
    ------
    InputError
        Kutzbach's count exceeds the number of drives: the message names both
        and how many inputs are needed.
    """
    count = kutzbach(mech)
    given = len(mech.drives)
    if count <= given or not mech.has_geometry:  # nothing placed: the assembly says so at once
        return
    from mech.topology import dof

    drives = f"{given} drive{'s' if given != 1 else ''}" if given else "no drive"
    raise InputError(
        f"{mech.label} has {count} degree{'s' if count != 1 else ''} of freedom ({dof(mech).formula}; "
        f"special geometry can only add to that) but {drives}: it needs {count} "
        f"input{'s' if count != 1 else ''}, one drive per degree of freedom",
        # with no drive, at the driven link's likeliest place: the first moving link, where `links` names it
        where=mech.drives[0].where if mech.drives else _first_moving_link(mech),
        hint=f"give one drive per degree of freedom: drive: [{{link: …, angle: …, rpm: …}}, …] ({count} of them)",
        source=mech.source,
    )


def _first_moving_link(mech: Mechanism) -> Where:
    """Where the file names its first moving link (the file itself when that is not known)."""
    moving = [lk for lk in mech.links if not lk.is_ground and lk.where is not None]
    return moving[0].where if moving else Where(mech.path)  # type: ignore[return-value]


def instant_why(mech: Mechanism, names: Sequence[str]) -> str:
    """Why the pairs ``names`` are known at the drawn instant only, for the refusals that say so.

    A gear pair with its pitch circles given rolls relative to a link both its centres are fixed
    in (:func:`mech.pairs.gearing.gear_row`); where there is none, the circles are known only as
    they touch now, which is not for want of a profile.
    """
    joints = [mech.joint(n) for n in names]
    if joints and all(j.radii or getattr(j.spec, "pitch_radii", None) for j in joints):
        return (
            "the pitch circles are given, but no one link, an arm or the frame, holds both centres of a pair"
        )
    return "no profile is given"


def instant_pairs(names: Sequence[str]) -> str:
    """``joint K describes`` / ``joints K, L describe``: the higher pairs known at one instant."""
    if len(names) == 1:
        return f"joint {names[0]} describes"
    return f"joints {', '.join(names)} describe"
