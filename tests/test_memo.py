"""mech._memo.Memo: derived values kept on the object they derive from, not in a module keyed on id()."""

from __future__ import annotations

import pickle
from pathlib import Path

import pytest

from mech._memo import Memo

FOUR_BAR = Path(__file__).resolve().parents[1] / "mechanisms" / "four_bar.yaml"


def test_memo_makes_a_value_once_and_returns_it_again():
    memo, made = Memo(), []
    assert memo.get("k", lambda: made.append(1) or 42) == 42
    assert memo.get("k", lambda: made.append(1) or 43) == 42
    assert made == [1]


def test_memo_drops_the_least_recently_used_entry_beyond_its_limit():
    memo = Memo(limit=2)
    memo.get("a", lambda: 1)
    memo.get("b", lambda: 2)
    memo.get("a", lambda: 0)  # a used again: b is now the oldest
    memo.get("c", lambda: 3)
    assert len(memo) == 2
    assert memo.get("a", lambda: -1) == 1 and memo.get("b", lambda: -2) == -2


def test_memo_keeps_no_error():
    memo = Memo()

    def fail() -> int:
        raise ValueError("no")

    with pytest.raises(ValueError):
        memo.get("k", fail)
    assert memo.get("k", lambda: 5) == 5


def test_memo_is_not_pickled_and_mechanisms_pickle_without_it():
    from mech.kinematics import solve
    from mech.loader import load

    mech = load(str(FOUR_BAR))
    solve(mech, "position")  # fills the memo with the compiled system (generated code among it)
    assert len(mech.memo) > 0
    again = pickle.loads(pickle.dumps(mech))
    assert again == mech and len(again.memo) == 0


def test_a_mechanism_is_compiled_once_and_a_new_one_afresh():
    from mech.kinematics.solve import compiled
    from mech.loader import load

    first = load(str(FOUR_BAR))
    assert compiled(first, None) is compiled(first, None)
    second = load(str(FOUR_BAR))
    assert second == first and compiled(second, None) is not compiled(first, None)
