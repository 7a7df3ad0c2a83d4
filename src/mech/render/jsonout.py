"""JSON for machines: plain dicts, stable keys, no rich."""

from __future__ import annotations

import json
import math
from typing import Any

from mech.errors import MechError


def dumps(data: Any) -> str:
    """Pretty JSON; NaN and infinity are written as null, never as invalid JSON."""
    return json.dumps(_clean(data), indent=2, ensure_ascii=False)


def _clean(value: Any) -> Any:
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {str(k): _clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean(v) for v in value]
    return value


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
