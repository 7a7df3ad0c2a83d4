"""The examples in docstrings run, so the documentation cannot drift from the code."""

from __future__ import annotations

import doctest
import importlib

import pytest

MODULES = [
    "mech.units",
    "mech.loader",
    "mech.check",
    "mech.icentres.homogeneous",
    "mech.icentres.kennedy",
    "mech.icentres.inspection",
    "mech.icentres.locate",
    "mech.kinematics.geometry",
    "mech.kinematics.dyads",
    "mech.kinematics.solve",
    "mech.kinematics.mobility",
    "mech.kinematics.sweep",
]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples_run(name):
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.failed == 0
