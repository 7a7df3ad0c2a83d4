"""Values derived from one immutable object, computed once and kept on the object itself.

A model or a compiled system is frozen, so whatever is derived from it (the
constraint system of a mechanism, its drives as overridden, its closed-form
program) never goes stale and can be remembered.  Remembering it in a
module-level dictionary keyed on ``id(obj)`` is fragile (an id is reused once
the object is gone, so each entry must hold the object to stay valid) and is
state shared by every caller.  A :class:`Memo` is a field of the object
instead: it lives and dies with it, and nothing outside can see it.

It is never compared, hashed or pickled (an unpickled object starts with an
empty memo: what it held, generated code among it, is rebuilt where needed).
It lives below every layer and imports nothing.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable
from typing import Any, TypeVar

__all__ = ["Memo"]

T = TypeVar("T")


class Memo:
    """A small least-recently-used store of derived values: ``memo.get(key, make)``.

    ``limit`` bounds it for keys that vary (the drives of each solve's options);
    the oldest entry is dropped beyond it.  An error raised by ``make`` is not kept.
    """

    __slots__ = ("_limit", "_values")

    def __init__(self, limit: int = 64) -> None:
        self._values: dict[Hashable, Any] = {}
        self._limit = limit

    def get(self, key: Hashable, make: Callable[[], T]) -> T:
        """The value kept under ``key``, made by ``make()`` the first time."""
        values = self._values
        if key in values:
            value = values.pop(key)  # re-inserted last: most recently used
            values[key] = value
            return value  # type: ignore[no-any-return]
        value = make()
        values[key] = value
        if len(values) > self._limit:
            del values[next(iter(values))]
        return value

    def __len__(self) -> int:
        return len(self._values)

    def __reduce__(self) -> tuple[type[Memo], tuple[int]]:
        return (Memo, (self._limit,))

    def __repr__(self) -> str:
        return f"Memo({len(self._values)} kept)"
