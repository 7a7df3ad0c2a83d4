"""mech._records.dataclass behaves as dataclasses.dataclass (the reference), only cheaper to define."""

from __future__ import annotations

import copy
import dataclasses
import pickle
from dataclasses import field

import pytest

from mech._records import dataclass
from mech.options import SolveOptions


def _define(decorator):
    """The same frozen, slotted record, defined with ``decorator``."""

    @decorator(frozen=True, slots=True)
    class Record:
        """A record with every kind of field mech uses."""

        a: int
        b: float = 1.5
        c: tuple[int, ...] = field(default_factory=tuple)
        where: str | None = field(default=None, compare=False)
        secret: str = field(default="", repr=False)

        def __post_init__(self) -> None:
            if self.a < 0:
                raise ValueError("a must be ≥ 0")

        def double(self) -> int:
            return 2 * self.a

    return Record


OURS, THEIRS = _define(dataclass), _define(dataclasses.dataclass)
CALLS = [
    ((1,), {}),
    ((2, 2.5), {}),
    ((3,), {"c": (1, 2)}),
    ((), {"a": 4, "where": "x.yaml:3:1"}),
    ((5,), {"secret": "s"}),
]


@pytest.mark.parametrize("warm", [0, 40])  # before and after the real __init__ is compiled
def test_records_construct_compare_hash_and_print_as_dataclasses_do(warm):
    for k in range(warm):
        OURS(k)
    for args, kwargs in CALLS:
        ours, theirs = OURS(*args, **kwargs), THEIRS(*args, **kwargs)
        assert repr(ours) == repr(theirs).replace(THEIRS.__qualname__, OURS.__qualname__)
        assert dataclasses.astuple(ours) == dataclasses.astuple(theirs)
        assert hash(ours) == hash(theirs)
        assert ours == OURS(*args, **kwargs) and ours.double() == theirs.double()
    assert OURS(1, where="a") == OURS(1, where="b")  # compare=False
    assert OURS(1) != OURS(2) and OURS(1) != THEIRS(1)
    assert OURS(1, c=[]).c == [] and OURS(1).c == ()  # a factory is called per instance


@pytest.mark.parametrize("warm", [0, 40])
def test_records_refuse_bad_arguments_as_dataclasses_do(warm):
    for k in range(warm):
        OURS(k)
    for args, kwargs in [((), {}), ((1, 2.0, (), None, "", 9), {}), ((1,), {"a": 2}), ((1,), {"nope": 1})]:
        with pytest.raises(TypeError):
            THEIRS(*args, **kwargs)
        with pytest.raises(TypeError):
            OURS(*args, **kwargs)
    with pytest.raises(ValueError, match="≥ 0"):
        OURS(-1)


def test_records_are_frozen_slotted_and_copyable():
    r = OURS(3, c=(1,))
    with pytest.raises(dataclasses.FrozenInstanceError):
        r.a = 4  # type: ignore[misc]
    with pytest.raises(dataclasses.FrozenInstanceError):
        del r.b  # type: ignore[misc]
    assert not hasattr(r, "__dict__") and OURS.__slots__ == THEIRS.__slots__
    assert dataclasses.replace(r, b=9.0) == OURS(3, 9.0, (1,))
    assert [f.name for f in dataclasses.fields(OURS)] == ["a", "b", "c", "where", "secret"]
    assert OURS.__match_args__ == THEIRS.__match_args__
    assert copy.deepcopy(r) == r and copy.copy(r) == r
    opts = SolveOptions(angle=1.0, tol=1e-10)  # a record of mech's own, importable by name
    assert pickle.loads(pickle.dumps(opts)) == opts
    assert dataclasses.asdict(r) == {"a": 3, "b": 1.5, "c": (1,), "where": None, "secret": ""}


def test_an_unfrozen_record_is_mutable_and_unhashable_as_dataclasses_make_it():
    @dataclass
    class Plain:
        x: int = 0

    p = Plain()
    p.x = 2
    assert p == Plain(2) and Plain.__hash__ is None
