"""JSON Schema (draft-07) of mechanism file format 1, for editors' YAML plugins.

It describes the shape of a file (keys, types, enumerations) so an editor can
complete and flag typos as you write.  The loader checks more than a schema
can (names that must exist, lengths on one link, units of the right kind), so
a file the schema accepts may still be refused by ``mech`` with a located
message.  ``mech schema`` prints it.

Generated from the loader's own tables, so the two cannot drift apart: the key
tuples of each section (:data:`mech.loader.mechanism.TOP_KEYS`,
:data:`~mech.loader.drives.DRIVE_KEYS` …) decide which keys the schema lists,
their enumerations (link kinds, closures, directions, unit spellings) come
from the same tuples the loader checks values against, and each joint type's
keys come from the pair-kind registry.  What is written here is only the JSON
type of each key (its *fragment*); a key the loader reads with no fragment
here fails at import, not in an editor.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from mech.fields import NAME as _NAME
from mech.fields import NUMBER as _NUMBER
from mech.fields import XY as _XY
from mech.loader.answers import ANSWER_KEYS
from mech.loader.drives import DIRECTIONS, DRIVE_KEYS
from mech.loader.joints import CLOSURES, COMMON_JOINT_KEYS
from mech.loader.links import LINK_KEYS, LINK_KINDS
from mech.loader.loads import LOAD_KEYS
from mech.loader.masses import FLYWHEEL_KEYS, MASS_KEYS
from mech.loader.mechanism import TOP_KEYS
from mech.loader.points import PLACE_KEYS, POINT_KEYS
from mech.loader.units import UNITS_KEYS
from mech.pairs import KINDS
from mech.units import known_units


def _only(keys: Iterable[str], fragments: Mapping[str, Any]) -> dict[str, Any]:
    """``{key: fragment}`` for exactly ``keys``, in their order (a key without a fragment raises)."""
    return {k: fragments[k] for k in keys}


_PLACE_FRAGMENTS: dict[str, Any] = {
    "at": {**_XY, "description": "Drawn here, in the analysed configuration."},
    "near": {**_XY, "description": "A hint: initial guess and assembly branch."},
    "from": {**_NAME, "description": "Placed relative to this point of the same link…"},
    "toward": {**_NAME, "description": "…along the line toward this one."},
    "distance": _NUMBER,
    "offset": {**_XY, "description": "[u, v]: u along from→toward, v to its left."},
}
_PLACE = _only(PLACE_KEYS, _PLACE_FRAGMENTS)

_JOINT_COMMON: dict[str, Any] = _only(
    COMMON_JOINT_KEYS,
    {
        "type": {"type": "string"},  # an enum of the kinds registered when asked: _joints()
        "links": {"type": "array", "items": _NAME, "minItems": 2},
        "description": {"type": "string"},
        "closure": {"enum": list(CLOSURES)},
        **_PLACE,
    },
)


def _joints() -> dict[str, Any]:
    """The ``joints`` section, from the pair-kind registry as it is now (plug-ins included).

    A key two kinds share (``path``, ``profiles``) is listed once with any shape; per type,
    only its own keys are allowed (draft-07 if/then), so a `radius` on a gear is flagged.
    """
    common = {**_JOINT_COMMON, "type": {"enum": list(KINDS)}}
    keys: dict[str, Any] = {key: {} for kind in KINDS.values() for key in kind.keys}
    per_kind = [
        {
            "if": {"properties": {"type": {"const": name}}, "required": ["type"]},
            "then": {"propertyNames": {"enum": [*common, *k.keys]}, "properties": dict(k.keys)},
        }
        for name, k in KINDS.items()
    ]
    return {
        "type": "object",
        "minProperties": 1,
        "additionalProperties": {
            "type": "object",
            "required": ["type", "links"],
            "additionalProperties": False,
            "properties": {**common, **keys},
            "allOf": per_kind,
        },
    }


_DRIVE: dict[str, Any] = _only(
    DRIVE_KEYS,
    {
        "link": _NAME,
        "joint": _NAME,
        "angle": _NUMBER,
        "rpm": _NUMBER,
        "omega": _NUMBER,
        "direction": {"enum": list(DIRECTIONS)},
        "alpha": _NUMBER,
        "about": _NAME,
        "relative_to": {
            **_NAME,
            "description": "angle, omega and alpha are the driven link's minus this link's "
            "(default: absolute, measured from the ground)",
        },
        "speed": _NUMBER,
        "accel": _NUMBER,
        "acceleration": _NUMBER,
    },
)


def _in(unit: str, example: str) -> dict[str, Any]:
    """A number whose bare form is in ``unit`` whatever the file's ``units`` (DESIGN § 1.4: masses,
    inertias, gravity, loads; answers are SI), or a string with its unit."""
    return {**_NUMBER, "description": f"A bare number is in {unit}, or a string with its unit ({example})."}


_ANGLE = {**_NUMBER, "description": "The drive's angle: a bare number is in the file's angle unit."}


def _table(unit: str, example: str, values: int) -> dict[str, Any]:
    """``{table: [[angle, value…], …]}``: a load over the drive's angle."""
    cells = [_ANGLE] + [_in(unit, example)] * values
    row = {"type": "array", "items": cells, "minItems": 1 + values, "maxItems": 1 + values}
    return {
        "type": "object",
        "required": ["table"],
        "additionalProperties": False,
        "properties": {"table": {"type": "array", "items": row, "minItems": 2}},
    }


_N = _in("N", '"2 kN"')
_NM = _in("N·m, counter-clockwise positive", '"20 N m"')
_SI = _in("SI (m, m/s, m/s², rad/s, rad/s²)", '"385 mm"')

#: ``vary``: a range or a list of values for a scalar of the file, by its dotted path (DESIGN § 1.3).
_VARY = {
    "oneOf": [
        {
            "type": "object",
            "required": ["from", "to"],
            "additionalProperties": False,
            "properties": {
                "from": {"type": "number"},
                "to": {"type": "number"},
                "step": {"type": "number", "exclusiveMinimum": 0},
            },
            "description": "A range in the file's units: from, to and step (default 1).",
        },
        {"type": "array", "minItems": 1, "description": "A list: one of these."},
    ]
}
#: ``keep``: an answer key's label, or bounds on its value (DESIGN § 1.3).
_KEEP = {
    "oneOf": [
        {"type": ["string", "number"], "description": "The label or value the key must have."},
        {
            "type": "object",
            "minProperties": 1,
            "additionalProperties": False,
            "properties": {"at_least": _SI, "at_most": _SI},
            "description": "Bounds on the key's value, with units (at_least: 35 deg).",
        },
    ]
}

_SECTIONS: dict[str, Any] = {
    "name": {"type": "string"},
    "description": {"type": "string"},
    "source": {"type": "string"},
    "units": {
        "type": "object",
        "additionalProperties": False,
        "properties": {
            key: {"enum": known_units(dimension, ascii_only=False)} for key, dimension in UNITS_KEYS.items()
        },
    },
    "ground": _NAME,
    "links": {
        "oneOf": [
            {"type": "array", "items": _NAME, "minItems": 2},
            {
                "type": "object",
                "additionalProperties": {
                    "oneOf": [
                        {"type": "null"},
                        {
                            "type": "object",
                            "additionalProperties": False,
                            "properties": _only(
                                LINK_KEYS,
                                {"kind": {"enum": list(LINK_KINDS)}, "description": {"type": "string"}},
                            ),
                        },
                    ]
                },
            },
        ]
    },
    "joints": {},  # made by _joints() when the schema is asked for
    "lengths": {"type": "object", "additionalProperties": _NUMBER},
    "points": {
        "type": "object",
        "additionalProperties": {
            "type": "object",
            "required": ["link"],
            "additionalProperties": False,
            "properties": _only(POINT_KEYS, {"link": _NAME, "description": {"type": "string"}, **_PLACE}),
        },
    },
    "drive": {
        "oneOf": [
            {"$ref": "#/definitions/drive"},
            {"type": "array", "items": {"$ref": "#/definitions/drive"}, "minItems": 1},
        ]
    },
    "loads": {
        "type": "object",
        "description": "Loads for mechanical advantage, the input torque and forces: {P: {force: [Fx, Fy]}} (N) "
        "at a point, {link: {torque: T}} (N m, ccw +) on a link; either may be a table over the drive's angle "
        "({table: [[angle, Fx, Fy], …]} or {table: [[angle, T], …]}); `on` names the link a force at a shared pin "
        "acts on (DESIGN § 1.4).",
        "additionalProperties": {
            "type": "object",
            "additionalProperties": False,
            "properties": _only(
                LOAD_KEYS,
                {
                    "force": {
                        "oneOf": [
                            {"type": "array", "items": _N, "minItems": 2, "maxItems": 2},
                            _table("N", '"2 kN"', 2),
                        ]
                    },
                    "torque": {"oneOf": [_NM, _table("N·m", '"20 N m"', 1)]},
                    "on": _NAME,
                },
            ),
        },
    },
    "masses": {
        "type": "object",
        "description": "Links with mass (DESIGN § 1.4): {link: {mass: 5, centre: G, inertia: 0.08}} in kg and "
        "kg m^2 (or radius_of_gyration, a length); the others are massless.",
        "additionalProperties": {
            "type": "object",
            "required": ["mass", "centre"],
            "additionalProperties": False,
            "properties": _only(
                MASS_KEYS,
                {
                    "mass": _in("kg", '"2 kg"'),
                    "centre": _NAME,
                    "inertia": _in("kg·m² about the centre", '"0.012 kg m^2"'),
                    "radius_of_gyration": _in("the file's length unit", '"60 mm"'),
                },
            ),
        },
    },
    "gravity": {
        "type": "array",
        "items": _in("m/s²", '"9.81 m/s^2"'),
        "minItems": 2,
        "maxItems": 2,
        "description": "[gx, gy] in m/s^2 (none by default).",
    },
    "flywheel": {
        "type": "object",
        "additionalProperties": False,
        "required": ["fluctuation"],
        "properties": _only(
            FLYWHEEL_KEYS,
            {
                "fluctuation": {
                    "type": ["string", "number"],
                    "description": "e.g. 2% (total, (w_max - w_min)/w_mean)",
                }
            },
        ),
    },
    "asks": {
        "oneOf": [
            {"type": "array", "items": {"type": "string"}},
            {"type": "object", "additionalProperties": {"type": "number", "exclusiveMinimum": 0}},
        ],
        "description": "Answer keys a student must answer (mech check --answers), when `answers` gives no "
        "values: a list (1 mark each) or a mapping of key to marks.",
    },
    "vary": {
        "type": "object",
        "minProperties": 1,
        "additionalProperties": _VARY,
        "description": "mech variants: dotted paths of scalars to {from, to, step} ranges or lists of values.",
    },
    "keep": {
        "type": "object",
        "additionalProperties": _KEEP,
        "description": "mech variants: answer keys each variant must keep: a label, or {at_least, at_most}.",
    },
    "answers": {
        "type": "object",
        "properties": {"tolerance": {"type": "string", "pattern": r"^\s*\d+(\.\d*)?\s*%\s*$"}},
        "additionalProperties": {
            "oneOf": [
                {"type": ["number", "string"]},
                {"type": "array", "items": _SI, "minItems": 2, "maxItems": 2},
                {
                    "type": "object",
                    "required": ["value"],
                    "additionalProperties": False,
                    "properties": _only(
                        ANSWER_KEYS,
                        {
                            "value": {},
                            "tolerance": {"type": ["string", "number"]},
                            "marks": {"type": "number", "exclusiveMinimum": 0},
                        },
                    ),
                },
            ]
        },
    },
}


def schema() -> dict[str, Any]:
    """The JSON Schema of the file format, with every pair kind registered now."""
    return {
        "$schema": "http://json-schema.org/draft-07/schema#",
        "$id": "https://github.com/planar-mech/mech/schema/format-1.json",
        "title": "mech mechanism file (format 1)",
        "description": "A planar mechanism: links, joints, lengths, drive and claimed answers. See cli.md.",
        "type": "object",
        "additionalProperties": False,
        "required": ["links", "joints"],
        "properties": _only(TOP_KEYS, {**_SECTIONS, "joints": _joints()}),
        "definitions": {"drive": {"type": "object", "additionalProperties": False, "properties": _DRIVE}},
    }


#: The schema as built in (the built-in kinds); :func:`schema` includes kinds registered later.
SCHEMA: dict[str, Any] = schema()
