"""JSON for machines: plain dicts, stable keys, no rich.

The contract every command's ``--json`` keeps (cli.md, "The JSON contract"): each
report — one per mechanism file — opens with ``command`` (the command that made
it), ``file`` (the path as given, ``<stdin>`` for ``-``), ``name`` (the
mechanism's name, or its file's when it has none) and carries ``units`` (the
unit of every kind of number in it); an error under ``--json`` is JSON too, on
stdout, with the same three keys and ``error``.  :func:`stamp` and
:func:`error_record` are the one place these keys are written.
"""

from __future__ import annotations

import json
import math
import re
from typing import Any

from mech._text import INVISIBLE
from mech.errors import MechError


def dumps(data: Any) -> str:
    """Pretty JSON; NaN and infinity are written as null, never as invalid JSON.

    Text from users' files is carried whole (a title with a right-to-left override decodes to
    that very character), but control and direction characters are written as JSON's own
    ``\\uXXXX`` escapes, so that JSON shown on a terminal cannot drive or reorder it.  They can
    only stand inside strings, where the escape means the same character.
    """
    return INVISIBLE.sub(_json_escape, json.dumps(_clean(data), indent=2, ensure_ascii=False))


def _json_escape(match: re.Match[str]) -> str:
    return f"\\u{ord(match.group()):04x}"


def _clean(value: Any) -> Any:
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {str(k): _clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean(v) for v in value]
    return value


def stamp(
    record: dict[str, Any], *, command: str, file: str | None, name: str | None, units: Any = None
) -> dict[str, Any]:
    """``record`` with the contract's keys first: ``command``, ``file``, ``name``; then its own.

    ``units`` is added where the record has none.  A key the record already has
    (``file``, ``name``) keeps the record's value only if the contract has none.
    """
    head = {"command": command, "file": file if file is not None else record.get("file"), "name": name}
    if head["name"] is None:
        head["name"] = record.get("name", record.get("mechanism"))
    out = {**head, **{k: v for k, v in record.items() if k not in head}}
    if "units" not in out:
        out["units"] = units
    return out


def error_record(command: str, file: str | None, error: MechError) -> dict[str, Any]:
    """An error under ``--json``: the contract's keys, ``name`` null, and ``error``."""
    return {"command": command, "file": file, "name": None, "error": error_dict(error)}


def error_dict(error: MechError) -> dict[str, Any]:
    """An error as JSON: its problems with file, line, column, message and hint."""
    return {
        "type": type(error).__name__,
        "problems": [
            {
                "file": p.where.path if p.where else None,
                "line": p.where.line if p.where else None,
                "column": p.where.column if p.where else None,
                "message": p.message,
                "hint": p.hint,
            }
            for p in error.problems
        ],
    }
