"""Counting and classification: the slides' worked counts, link and joint classes, pair classes."""

from __future__ import annotations

from pathlib import Path

import pytest

from mech.loader import load, loads
from mech.topology import chain_name, classify, dof

MECHANISMS = Path(__file__).resolve().parent.parent / "mechanisms"


def example_files() -> list[Path]:
    return sorted(MECHANISMS.glob("*.yaml"))


def chain(links: list[str], joints: dict[str, tuple[str, list[str]]]) -> str:
    """A YAML text of a chain given as {joint: (type, [links])}."""
    lines = [f"links: [{', '.join(links)}]", "joints:"]
    for name, (jtype, jl) in joints.items():
        lines.append(f"  {name}: {{type: {jtype}, links: [{', '.join(jl)}]}}")
    return "\n".join(lines) + "\n"


def ring(n: int) -> str:
    """A single closed loop of n links and n binary revolute joints."""
    links = ["frame"] + [f"L{i}" for i in range(1, n)]
    joints = {f"J{i}": ("revolute", [links[i], links[(i + 1) % n]]) for i in range(n)}
    return chain(links, joints)


# The slides (seeds/003, "Kutzbach Criterion" and Grübler's worked examples):
# l = 3, j = 3 -> 0; l = 4, j = 4 -> 1; l = 5, j = 5 -> 2.
@pytest.mark.parametrize(("n", "expected"), [(3, 0), (4, 1), (5, 2)])
def test_single_loops_count_as_the_slides_show(n, expected):
    count = dof(loads(ring(n)))
    assert (count.l, count.j, count.h, count.n) == (n, n, 0, expected)


def test_higher_pair_case_l4_j3_h1_gives_two():
    # slides 003: "n = 3(4 − 1) − 2·3 − 1 = 2"
    text = chain(
        ["frame", "cam", "follower", "roller"],
        {
            "O": ("revolute", ["frame", "cam"]),
            "G": ("prismatic", ["follower", "frame"]),
            "R": ("revolute", ["roller", "follower"]),
            "K": ("cam", ["roller", "cam"]),
        },
    )
    count = dof(loads(text))
    assert (count.l, count.j, count.h, count.n) == (4, 3, 1, 2)
    assert count.formula == "n = 3(4 − 1) − 2·3 − 1 = 2"


def test_ternary_joint_counts_as_two_binary_joints():
    # slides 003, "Ternary joint ... is equivalent to two binary joints"
    text = chain(
        ["frame", "a", "b", "c", "d", "e"],
        {
            "A": ("revolute", ["frame", "a"]),
            "B": ("revolute", ["a", "b", "c"]),  # ternary
            "C": ("revolute", ["b", "d"]),
            "D": ("revolute", ["c", "e"]),
            "E": ("revolute", ["d", "frame"]),
            "F": ("revolute", ["e", "frame"]),
        },
    )
    t = classify(loads(text))
    assert t.count.j == 7 and t.count.joints == 6 and t.count.n == 1
    assert t.joint_classes() == {"binary": ("A", "C", "D", "E", "F"), "ternary": ("B",)}


def test_link_classes_and_grubler():
    t = classify(loads(ring(4)))
    assert t.link_classes() == {"binary": ("frame", "L1", "L2", "L3")}
    assert t.count.grubler_value == 0
    assert "satisfied" in t.count.grubler
    assert t.chain == "four-bar"
    assert t.icentres == 6


@pytest.mark.parametrize(
    ("n", "kind", "verdict"),
    [
        (-1, "superstructure", "superstructure"),
        (0, "structure", "structure"),
        (1, "constrained", "constrained mechanism"),
    ],
)
def test_verdicts(n, kind, verdict):
    from mech.topology import DofCount

    count = DofCount(l=4, j=4, h=0, n=n, joints=4, higher_pairs=())
    assert count.kind == kind and count.verdict.startswith(verdict)


def test_more_than_one_dof_needs_that_many_inputs():
    count = dof(loads(ring(5)))
    assert count.verdict == "mechanism needing 2 independent inputs"


def test_pair_classification_follows_the_slides():
    text = chain(
        ["frame", "cam", "follower", "wheel", "nut"],
        {
            "O": ("revolute", ["frame", "cam"]),
            "G": ("prismatic", ["follower", "frame"]),
            "K": ("cam", ["follower", "cam"]),
            "R": ("rolling", ["wheel", "frame"]),
            "S": ("screw", ["nut", "frame"]),
        },
    )
    pairs = {p.joint: p for p in classify(loads(text)).pairs}
    assert (pairs["O"].relative_motion, pairs["O"].contact, pairs["O"].closure) == (
        "turning",
        "lower",
        "self-closed",
    )
    assert (pairs["G"].relative_motion, pairs["G"].contact) == ("sliding", "lower")
    assert (pairs["K"].contact, pairs["K"].closure, pairs["K"].kutzbach) == ("higher", "force-closed", "h")
    assert (pairs["R"].relative_motion, pairs["R"].kutzbach) == ("rolling", "j")
    assert pairs["S"].relative_motion == "screw"


def test_form_closed_cam():
    text = "links: [frame, cam, follower]\njoints:\n  K: {type: cam, links: [follower, cam], closure: form}\n"
    (pair,) = classify(loads(text)).pairs
    assert pair.closure == "self-closed"


@pytest.mark.parametrize(
    ("types", "expected"),
    [
        (["revolute"] * 4, "four-bar"),
        (["revolute", "revolute", "revolute", "prismatic"], "slider-crank"),
        (["revolute", "prismatic", "revolute", "prismatic"], "double-slider"),
    ],
)
def test_four_link_chain_names(types, expected):
    links = ["frame", "a", "b", "c"]
    joints = {f"J{i}": (t, [links[i], links[(i + 1) % 4]]) for i, t in enumerate(types)}
    assert chain_name(loads(chain(links, joints))) == expected


def test_watt_and_stephenson_are_told_apart():
    # Watt: the two ternary links are joined to each other; Stephenson: they are not.
    watt = {
        "A": ["frame", "t1"],
        "B": ["t1", "t2"],
        "C": ["t2", "b1"],
        "D": ["b1", "frame"],
        "E": ["t1", "b2"],
        "F": ["b2", "b3"],
        "G": ["b3", "t2"],
    }
    steph = {
        "A": ["frame", "b1"],
        "B": ["b1", "t2"],
        "C": ["t2", "b2"],
        "D": ["b2", "frame"],
        "E": ["frame", "b3"],
        "F": ["b3", "t2"],
        "G": ["frame", "t1"],
    }
    links = ["frame", "t1", "t2", "b1", "b2", "b3"]
    assert chain_name(loads(chain(links, {k: ("revolute", v) for k, v in watt.items()}))) == "watt"
    # In this Stephenson chain frame and t2 are the ternary links (not adjacent).
    steph_links = ["frame", "t1", "t2", "b1", "b2", "b3"]
    steph["G"] = ["t1", "b1"]
    steph["A"] = ["frame", "t1"]
    assert (
        chain_name(loads(chain(steph_links, {k: ("revolute", v) for k, v in steph.items()}))) == "stephenson"
    )


# -- the shipped examples: each claims its own counts; they must hold -----------------------
COUNT_KEYS = {"dof", "links.count", "joints.count", "joints.equivalent_binary", "higher_pairs", "chain"}


@pytest.mark.parametrize("path", example_files(), ids=lambda p: p.name)
def test_example_counts_match_their_claims(path):
    m = load(path)
    t = classify(m)
    computed = {
        "dof": t.count.n,
        "links.count": t.count.l,
        "joints.count": t.count.joints,
        "joints.equivalent_binary": t.count.j,
        "higher_pairs": t.count.h,
        "chain": t.chain,
        "icentres.count": t.icentres,
    }
    classes = t.link_classes()
    for name in ("singular", "binary", "ternary", "quaternary", "pentagonal", "hexagonal"):
        computed[f"links.{name}"] = len(classes.get(name, ()))
    jc = t.joint_classes()
    for name in ("binary", "ternary", "quaternary"):
        computed[f"joints.{name}"] = len(jc.get(name, ()))
    claims = {c.key: c.value for c in m.answers if c.key in computed}
    assert claims, f"{path.name} claims no counts"
    assert {k: computed[k] for k in claims} == claims


# Pinned to the slides (seeds/003): each file's Kutzbach count with the slide it comes from.
SLIDE_COUNTS = {
    "structure_three_bar.yaml": (3, 3, 0, 0),  # slide "l = 3 and j = 3: n = 0"
    "four_bar_dof.yaml": (4, 4, 0, 1),  # slide "l = 4 and j = 4: n = 1"
    "five_bar.yaml": (5, 5, 0, 2),  # slide "l = 5 and j = 5: n = 2"
    "higher_pair_dof2.yaml": (4, 3, 1, 2),  # slide "l = 4, Jb = 3, h = 1: dof = 2"
    "eleven_link_chain.yaml": (11, 15, 0, 0),  # slide "l = 11, Jb = 15: dof = 0"
    "seven_link_chain.yaml": (7, 8, 0, 2),  # slide "l = 7, Jb = 8: dof = 2"
    "nine_link_chain.yaml": (9, 10, 0, 4),  # slide "l = 9, Jb = 10: dof = 4"
    "eight_link_chain.yaml": (8, 10, 0, 1),  # slide "l = 8, Jb = 10: 21 − 20 − 0 = 1"
}


@pytest.mark.parametrize(("name", "expected"), SLIDE_COUNTS.items())
def test_slide_counts(name, expected):
    count = dof(load(MECHANISMS / name))
    assert (count.l, count.j, count.h, count.n) == expected


def test_topology_imports_nothing_from_the_rooms_above_it():
    # ROOMS.md: topology sits below kinematics and properties.  Every import counts, those inside a
    # function too (Grashof's loops were once imported from mech.properties inside classify).
    import ast

    above = ("mech.properties", "mech.kinematics", "mech.icentres", "mech.analysis", "mech.check")
    package = Path(__file__).resolve().parent.parent / "src" / "mech" / "topology"
    found = []
    for path in sorted(package.glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = (
                [a.name for a in node.names]
                if isinstance(node, ast.Import)
                else [node.module or ""]
                if isinstance(node, ast.ImportFrom)
                else []
            )
            found += [f"{path.name}:{node.lineno} {n}" for n in names if n.startswith(above)]
    assert not found, found
