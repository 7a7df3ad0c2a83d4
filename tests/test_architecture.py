"""ARCHITECTURE.md cannot rot: every module and function it names exists, and README links to it."""

from __future__ import annotations

import importlib
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
TEXT = (ROOT / "ARCHITECTURE.md").read_text(encoding="utf-8")
NAMES = sorted(set(re.findall(r"`(mech(?:\.\w+)+)`", TEXT)))


def resolve(dotted: str) -> object:
    """The module, or the attribute of the longest importable module prefix, that ``dotted`` names."""
    parts = dotted.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            obj: object = importlib.import_module(".".join(parts[:cut]))
        except ModuleNotFoundError:
            continue
        for attr in parts[cut:]:
            obj = getattr(obj, attr)
        return obj
    raise ModuleNotFoundError(dotted)


def test_architecture_names_enough_to_follow_a_call():
    assert len(NAMES) > 40


@pytest.mark.parametrize("dotted", NAMES)
def test_every_name_in_architecture_md_exists(dotted):
    assert resolve(dotted) is not None


def test_the_velocity_walk_goes_through_each_room_in_order():
    walk = TEXT.split("## One `mech velocity` call", 1)[1].split("\n## ", 1)[0]
    rooms = re.findall(r"^\d+\. \*\*([\w ]+)\*\*", walk, flags=re.M)
    assert rooms == ["cli", "analysis pipeline", "loader", "kinematics", "render"]


def test_readme_links_to_architecture_md():
    assert "(ARCHITECTURE.md)" in (ROOT / "README.md").read_text(encoding="utf-8")
