"""ARCHITECTURE.md cannot rot: every module and function it names exists, and README links to it."""

from __future__ import annotations

import importlib
import re
import sys
from pathlib import Path

import pytest

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    tomllib = pytest.importorskip("tomli")

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


def _table_rooms() -> list[set[str]]:
    """The room table's modules, row by row from the top: ``{"topology", "schema"}`` for a shared row."""
    table = TEXT.split("## The rooms", 1)[1].split("\n## ", 1)[0]
    rows = [
        line
        for line in table.splitlines()
        if line.startswith("| ") and not line.startswith(("| room", "| ---"))
    ]
    return [
        {m.removeprefix("mech.") for m in re.findall(r"`(mech\.[\w]+)`", row.split("|")[2])} for row in rows
    ]


def _contract_rooms() -> list[set[str]]:
    """The layers of pyproject's exhaustive contract over the container ``mech``, from the top."""
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    (rooms,) = [
        c
        for c in config["tool"]["importlinter"]["contracts"]
        if c["type"] == "layers" and c["containers"] == ["mech"]
    ]
    assert rooms.get("exhaustive") is True
    return [{m.strip() for m in layer.split("|")} for layer in rooms["layers"]]


def test_the_room_table_is_the_layers_contract():
    # the table is the contract: the same rooms, the same modules in each, in the same order
    assert _table_rooms() == _contract_rooms()


def test_every_module_of_mech_is_in_one_room():
    package = ROOT / "src" / "mech"
    modules = {p.stem for p in package.glob("*.py") if p.stem != "__init__"}
    modules |= {p.name for p in package.iterdir() if (p / "__init__.py").exists()}
    placed = [m for room in _contract_rooms() for m in room]
    assert sorted(placed) == sorted(modules)


def test_the_velocity_walk_goes_down_through_the_rooms():
    walk = TEXT.split("## One `mech velocity` call", 1)[1].split("\n## ", 1)[0]
    steps = re.findall(r"^\d+\. \*\*([\w ]+)\*\*", walk, flags=re.M)
    order = [m for room in _contract_rooms() for m in sorted(room)]
    assert steps == ["entry", "analysis", "loader", "kinematics", "render"]
    assert all(s in order for s in steps)


def test_readme_links_to_architecture_md():
    assert "(ARCHITECTURE.md)" in (ROOT / "README.md").read_text(encoding="utf-8")
