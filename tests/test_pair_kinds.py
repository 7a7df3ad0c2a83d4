"""Pair kinds: every joint type has an entry in every layer's registry; each kind reads its own keys."""

from __future__ import annotations

import ast
import json
import math
import textwrap
from dataclasses import dataclass
from types import MappingProxyType

import pytest

from mech.errors import InputError
from mech.fields import NUMBER, REF, read_ref
from mech.icentres.order import kennedy_order
from mech.loader import load, loads
from mech.pairs import PairKind, register
from mech.pairs.glyph import LAYERS, SHAPES
from mech.pairs.registry import KINDS
from mech.specs import (
    Circle,
    ContactSpec,
    Curve,
    GearSpec,
    Knife,
    Line,
    PinSpec,
    Ref,
    RollingSpec,
    SlideSpec,
)
from mech.units import Dimension
from source_trees import SRC, source_trees


@pytest.mark.parametrize("jtype", list(KINDS))
def test_every_kind_entry_is_for_its_own_type(jtype):
    assert KINDS[jtype].name == jtype


def _joint(text: str):
    doc = textwrap.dedent(
        """
        units: {length: mm}
        links: [frame, a, b]
        joints:
          O: {type: revolute, links: [frame, a], at: [0, 0]}
          Q: {type: revolute, links: [frame, b], at: [100, 0]}
        """
    )
    return loads(doc + "  K: " + text + "\n", path="t.yaml").joint("K")


def test_joint_carries_the_typed_spec_of_its_kind():
    assert isinstance(_joint("{type: revolute, links: [a, b], radius: 5}").spec, PinSpec)
    assert isinstance(_joint("{type: slot, links: [a, b], path: {through: Q, angle: 0}}").spec, SlideSpec)
    gear = _joint("{type: gear, links: [a, b], teeth: [20, 40], module: 2}")
    assert isinstance(gear.spec, GearSpec)
    assert gear.spec.pitch_radii == pytest.approx((0.02, 0.04))
    assert gear.radii is None and gear.teeth == (20, 40)  # the flat attributes still read the spec


def test_profiles_are_read_in_si_and_keyed_by_link():
    j = _joint(
        "{type: cam, links: [a, b], profiles: {a: {circle: {centre: O, radius: 40}}, "
        "b: {line: {through: [0, 60], angle: 90}}}}"
    )
    assert isinstance(j.spec, ContactSpec)
    circle, line = j.profile_of["a"], j.profile_of["b"]
    assert isinstance(circle, Circle) and circle.centre.name == "O" and circle.radius == pytest.approx(0.04)
    assert isinstance(line, Line) and line.through.xy == pytest.approx((0.0, 0.06))
    assert line.angle == pytest.approx(1.5707963267948966)


def test_knife_and_curve_profiles_are_read():
    j = _joint(
        "{type: contact, links: [a, b], profiles: {a: {curve: [[0, 0], [10, 0], [10, 10], [0, 10]]}, "
        "b: {point: Q}}}"
    )
    assert isinstance(j.profile_of["a"], Curve) and len(j.profile_of["a"].points) == 4
    assert isinstance(j.profile_of["b"], Knife) and j.profile_of["b"].point.name == "Q"


def test_rolling_radii_take_null_for_a_straight_line():
    j = _joint("{type: rolling, links: [a, frame], radii: [50, null]}")
    assert isinstance(j.spec, RollingSpec)
    assert j.radii == (pytest.approx(0.05), None)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("{type: cam, links: [a, b], profiles: {c: {point: O}}}", "which it does not join"),
        ("{type: cam, links: [a, b], profiles: {a: {circle: {centre: O}}}}", "has no `radius`"),
        (
            "{type: cam, links: [a, b], profiles: {a: {circle: {centre: O, radius: 4}, point: O}}}",
            "exactly one",
        ),
        ("{type: cam, links: [a, b], profiles: {a: {curve: [[0, 0], [1, 1]]}}}", "at least 3 points"),
        ("{type: rolling, links: [a, b], radii: [null, null]}", "both null"),
        ("{type: revolute, links: [a, b], profiles: {a: {point: O}}}", "unknown key 'profiles'"),
    ],
)
def test_bad_profiles_are_located_input_errors(text, message):
    with pytest.raises(InputError) as err:
        _joint(text)
    assert message in str(err.value)
    assert "t.yaml:7:" in str(err.value)


def test_schema_joint_keys_come_from_the_registry(run):
    jsonschema = pytest.importorskip("jsonschema")
    schema = json.loads(run("schema").output)
    joint = schema["properties"]["joints"]["additionalProperties"]
    assert set(joint["properties"]) >= {key for k in KINDS.values() for key in k.keys}
    validator = jsonschema.Draft7Validator(schema)
    doc = {
        "links": ["frame", "w"],
        "joints": {"W": {"type": "rolling", "links": ["w", "frame"], "radii": [50, None]}},
    }
    assert validator.is_valid(doc)
    doc["joints"]["W"]["radius"] = 5  # a pin's key on a rolling pair
    assert not validator.is_valid(doc)


@pytest.mark.parametrize("jtype", list(KINDS))
def test_every_kind_says_what_the_solvers_make_of_it(jtype):
    k = KINDS[jtype]
    assert k.role in ("pin", "path", "contact", "spatial")
    assert (k.role == "spatial") == (not k.planar)
    assert k.located in ("all", "first", "none")


def test_a_profile_naming_a_point_of_another_link_is_a_located_error():
    with pytest.raises(InputError) as err:
        _joint("{type: cam, links: [a, b], profiles: {a: {circle: {centre: Q, radius: 4}}, b: {point: Q}}}")
    text = str(err.value)
    assert "t.yaml:7:" in text and "'Q', which is not a point of a" in text


# -- every kind through every hook ----------------------------------------------------------------
SLOT = """\
units: {length: mm, angle: deg}
links: [frame, crank, lever]
joints:
  O: {type: revolute, links: [frame, crank], at: [0, 0]}
  P: {type: revolute, links: [lever, frame], at: [0, -100]}
  A: {type: slot, links: [crank, lever], path: {through: P, angle: 90}}
lengths: {OA: 40}
drive: {link: crank, angle: 90, rpm: 60}
"""
SPATIAL = """\
links: [frame, a, b]
joints:
  O: {type: revolute, links: [frame, a]}
  Q: {type: revolute, links: [a, b]}
  S: {type: KIND, links: [b, frame]}
"""

#: For every registered kind, a mechanism that uses it and the joint of that kind.  A kind added
#: to the registry without an example here fails test_every_registered_kind_has_an_example.
WALK: dict[str, tuple[str, str]] = {
    "revolute": ("four_bar.yaml", "B"),
    "prismatic": ("slider_crank.yaml", "P"),
    "slot": (SLOT, "A"),
    "rolling": ("rolling_wheel.yaml", "W"),
    "cam": ("eccentric_cam_roller.yaml", "K"),
    "contact": ("CONTACT", "K"),
    "gear": ("gear_pair.yaml", None),
    "screw": (SPATIAL.replace("KIND", "screw"), "S"),
    "spherical": (SPATIAL.replace("KIND", "spherical"), "S"),
}


def _walked(kind: str):
    from tests.mechanism_texts import EXAMPLES

    source, joint = WALK[kind]
    if source == "CONTACT":  # the eccentric cam's disc and flat face, as a plain contact pair
        source = (EXAMPLES / "eccentric_cam.yaml").read_text().replace("type: cam", "type: contact")
    m = loads(source, path=f"{kind}.yaml") if "\n" in source else load(EXAMPLES / source)
    j = m.joint(joint) if joint else next(x for x in m.joints if x.type == kind)
    return m, j


def test_every_registered_kind_has_an_example():
    assert set(WALK) == set(KINDS)


@pytest.mark.parametrize("kind", list(KINDS))
def test_every_kind_reads_classifies_and_counts_its_joints(kind):
    from mech.topology import classify, dof

    m, j = _walked(kind)
    k = KINDS[kind]
    assert type(j.spec) is type(k.spec)  # read: the kind's own spec
    assert (j.name in dof(m).higher_pairs) == k.higher  # counted in h or in j
    pair = next(p for p in classify(m).pairs if p.joint == j.name)
    assert (pair.relative_motion, pair.contact) == (k.motion, k.contact)
    assert k.role in ("pin", "path", "contact", "spatial")
    assert (k.role == "spatial") == (not k.planar)
    assert k.located in ("all", "first", "none")
    words = k.icentre[1].format(joint=j.name)  # from the joints alone: what inspection gives
    assert k.icentre[0] in ("point", "infinity", "line", "none")
    order = kennedy_order(m)
    assert any(words in c.how or any(words in a for a, _ in c.lines) for c in order.centres) == (
        k.icentre[0] != "none"
    )


@pytest.mark.parametrize("kind", [k for k in KINDS if KINDS[k].planar])
def test_every_planar_kind_writes_rows_is_inspected_and_drawn(kind):
    from mech.draw import draw
    from mech.draw.svg import to_svg
    from mech.icentres.inspection import facts, instant_of
    from mech.kinematics import solve
    from mech.kinematics.solve import compiled

    m, j = _walked(kind)
    sys_ = compiled(m, None).system
    assert j.name in sys_.row_names  # rows: the kind's own
    kin = solve(m, "velocity")
    seen = [f for f in facts(instant_of(m, kin)) if j.name in f.label]
    assert seen  # inspected at the instant: a point or a line …
    want = "line" if KINDS[kind].icentre[0] == "line" else "point"
    assert {f.kind for f in seen} == {want}  # … the one the kind says inspection gives
    shapes = _glyph(m, kin, j)
    assert shapes  # drawn: its own glyph, not the base's nothing …
    assert all(isinstance(s, SHAPES) and s.layer in LAYERS for s in shapes)  # … in mech.shapes, layered
    assert any(s.name == j.name for s in shapes)  # … carrying its name
    svg = to_svg(draw(m, kin))
    assert f'data-name="{j.name}"' in svg  # and painted


def _glyph(m, kin, j):
    """The joint's glyph as its kind gives it, on a sheet as a configuration diagram builds one."""
    from mech.draw.config import link_colours
    from mech.draw.glyphs import Sheet
    from mech.draw.scene import Transform

    sheet = Sheet(m, kin, dict(kin.positions), {}, Transform(0.05, (0.0, 0.0), (60.0, 60.0)), link_colours(m))
    return list(KINDS[j.type].glyph(sheet, j))


@pytest.mark.parametrize("kind", [k for k in KINDS if not KINDS[k].planar])
def test_a_kind_the_planar_solvers_cannot_model_is_refused_with_its_name(kind):
    from mech.errors import UnsupportedError
    from mech.kinematics import solve

    m, j = _walked(kind)
    with pytest.raises(UnsupportedError, match=f"joint {j.name} is a {kind} pair"):
        solve(m, "velocity")


# -- a kind added as a plug-in, touching no file of mech's ------------------------------------------
class ArcSlot(PairKind):
    """A pin (a point of the first link) running in a circular slot of the second: one distance row.

    A slot cut on a circle of radius r about a point of the slotted link keeps the pin r from that
    point; the pin may turn and slide along it (h = 1).  Its I-centre lies on the radius through
    the pin, as a straight slot's lies on the normal through the pin.
    """

    name = "arc_slot"
    keys = MappingProxyType(
        {
            "arc": {
                "type": "object",
                "required": ["centre", "radius"],
                "properties": {"centre": REF, "radius": NUMBER},
            }
        }
    )
    higher = True
    motion = "sliding and turning (pin in a curved slot)"
    line_contact = True
    located = "first"
    role = "contact"
    icentre = ("line", "pin in arc slot {joint}: on the radius through the pin")

    def read(self, r, fields, what, links):
        arc = r.mapping(fields["arc"][1], f"the arc of {what}", allowed=("centre", "radius"))
        centre = read_ref(r, arc["centre"][1], f"the centre of the arc of {what}")
        radius = r.number(arc["radius"][1], "the arc's radius", Dimension.LENGTH, positive=True)
        return ArcSpec(centre, radius)

    def fixed_in(self, j):
        return j.links[:1]  # the pin's centre moves with the pin link

    def contact_problem(self, j):
        return None  # a point of its pin link, placed like any other

    def rows(self, b, j):
        from mech.pairs.rows import Distance

        pin, slotted = j.links
        p, c = b.scn(j.name), b.where(j.spec.centre)
        d = j.spec.radius / b.scale
        b.distance.append(
            Distance(b.index[pin], b.to_local(pin, p), b.index[slotted], b.to_local(slotted, c), d, j.name)
        )

    def glyph(self, view, j):
        """An arc of its slot (±20° round the pin, about the arc's centre) and the pin in it."""
        from mech.pairs.glyph import pin
        from mech.shapes import Poly, Style

        at, c = view.positions.get(j.name), view.positions.get(j.spec.centre.name)
        if at is None or c is None:
            return []
        r, a0 = j.spec.radius, math.atan2(at[1] - c[1], at[0] - c[0])
        arc = tuple(
            (c[0] + r * math.cos(a0 + math.radians(t)), c[1] + r * math.sin(a0 + math.radians(t)))
            for t in range(-20, 21, 2)
        )
        style = Style(view.colour(j.links[1]), 0.45)
        return [Poly(arc, False, style, "arc-slot", j.name, "block", world=True), *pin(view, j.name)]

    def inspect(self, seen, j):
        at, c = seen.at(j), seen.positions[j.spec.centre.name]
        n = math.hypot(at[0] - c[0], at[1] - c[1])
        seen.contact(j.name, (j.links[0], j.links[1]), at, ((at[0] - c[0]) / n, (at[1] - c[1]) / n))


@dataclass(frozen=True)
class ArcSpec:
    centre: Ref | None = None
    radius: float | None = None


# A four-bar whose rocker is replaced by a slot: the coupler's end C runs on a circle of radius
# CD = 170 mm about D, as the rocker's end does, so the coupler moves exactly as in the four-bar
# (Khurmi's ABCD: AB 40, BC 150, CD 170, AD 150 mm); C is drawn where the four-bar puts it.
ARC_FOUR_BAR = """\
units: {{length: mm, angle: deg}}
links: [frame, crank, coupler]
joints:
  A: {{type: revolute, links: [frame, crank], at: [0, 0]}}
  B: {{type: revolute, links: [crank, coupler]}}
  C: {{type: arc_slot, links: [coupler, frame], at: [{cx}, {cy}], arc: {{centre: D, radius: 170}}}}
points:
  D: {{link: frame, at: [150, 0]}}
lengths: {{AB: 40, BC: 150}}
drive: {{link: crank, angle: 60, omega: 12.566}}
"""


@pytest.fixture
def arc_slot():
    register(ArcSlot())
    yield
    del KINDS["arc_slot"]


def test_a_plug_in_kind_registered_from_outside_reads_solves_inspects_and_draws(arc_slot):
    from tests.oracles.four_bar import four_bar

    from mech.draw import draw
    from mech.draw.svg import to_svg
    from mech.icentres import locate
    from mech.kinematics import solve
    from mech.options import SolveOptions
    from mech.schema import schema
    from mech.topology import dof

    c, *_ = four_bar(0.040, 0.150, 0.170, 0.150, math.radians(60), 12.566)
    m = loads(ARC_FOUR_BAR.format(cx=c[0] * 1000, cy=c[1] * 1000), path="arc.yaml")
    assert m.joint("C").spec == ArcSpec(Ref(name="D"), pytest.approx(0.170))
    assert dof(m).n == 1 and dof(m).higher_pairs == ("C",)
    assert (
        "arc_slot" in schema()["properties"]["joints"]["additionalProperties"]["properties"]["type"]["enum"]
    )
    for deg in (60.0, 100.0, 200.0):
        kin = solve(m, "acceleration", SolveOptions(angle=math.radians(deg)))
        c, w3, _, a3, _ = four_bar(0.040, 0.150, 0.170, 0.150, math.radians(deg), 12.566)
        assert kin.positions["C"] == pytest.approx(tuple(c), abs=1e-9 * 0.2)
        assert kin.links["coupler"].omega == pytest.approx(w3, rel=1e-9)
        assert kin.links["coupler"].alpha == pytest.approx(a3, rel=1e-9)
    kin = solve(m, "velocity")
    ic = {i.name: i for i in locate(m, kin).centres}
    # I13 (frame–coupler) is where the crank's line AB meets the radius DC (Kennedy)
    b, c = kin.positions["B"], kin.positions["C"]
    i13 = ic["I13"].point
    assert (b[0] * i13[1] - b[1] * i13[0]) == pytest.approx(0.0, abs=1e-9)
    assert ((c[0] - 0.15) * (i13[1] - c[1]) - c[1] * (i13[0] - c[0])) == pytest.approx(0.0, abs=1e-9)
    assert 'data-name="C"' in to_svg(draw(m, kin))


def test_a_plug_in_kinds_own_glyph_is_drawn_an_arc_of_its_slot_through_its_pin(arc_slot):
    """ArcSlot's glyph (its own, no drawing code of mech's names it): an arc about D through C."""
    import xml.etree.ElementTree as ET

    from tests.oracles.four_bar import four_bar

    from mech.draw import draw
    from mech.draw.svg import to_svg
    from mech.kinematics import solve

    c, *_ = four_bar(0.040, 0.150, 0.170, 0.150, math.radians(60), 12.566)
    m = loads(ARC_FOUR_BAR.format(cx=c[0] * 1000, cy=c[1] * 1000), path="arc.yaml")
    root = ET.fromstring(to_svg(draw(m, solve(m, "velocity"))))
    ns = "{http://www.w3.org/2000/svg}"
    arcs = [e for e in root.iter(f"{ns}polyline") if e.get("class") == "arc-slot"]
    assert [e.get("data-name") for e in arcs] == ["C"]
    centre = next(e for e in root.iter(f"{ns}circle") if e.get("data-name") == "D")
    pin = next(e for e in root.iter(f"{ns}circle") if e.get("class") == "pin" and e.get("data-name") == "C")
    d = (float(centre.get("cx")), float(centre.get("cy")))
    radius = math.dist(d, (float(pin.get("cx")), float(pin.get("cy"))))
    points = [tuple(map(float, xy.split(","))) for xy in arcs[0].get("points").split()]
    assert len(points) == 21
    assert [math.dist(d, p) for p in points] == pytest.approx([radius] * 21, abs=0.02)  # SVG keeps 0.01 mm
    swept = math.degrees(
        math.atan2(points[-1][1] - d[1], points[-1][0] - d[0])
        - math.atan2(points[0][1] - d[1], points[0][0] - d[0])
    )
    assert abs(math.remainder(swept, 360)) == pytest.approx(40, abs=0.5)


def test_a_glyph_that_gives_something_other_than_a_layered_shape_is_refused_with_its_kind(arc_slot):
    from tests.oracles.four_bar import four_bar

    from mech.draw import draw
    from mech.kinematics import solve
    from mech.shapes import Line, Text

    c, *_ = four_bar(0.040, 0.150, 0.170, 0.150, math.radians(60), 12.566)
    m = loads(ARC_FOUR_BAR.format(cx=c[0] * 1000, cy=c[1] * 1000), path="arc.yaml")
    kin = solve(m, "velocity")
    for wrong in (Text((0.0, 0.0), "C"), Line((0.0, 0.0), (1.0, 1.0), name="C")):  # a text; no layer
        KINDS["arc_slot"].glyph = lambda view, j, wrong=wrong: [wrong]
        with pytest.raises(TypeError, match="the arc_slot pair's glyph gave"):
            draw(m, kin)


def _kind_names_compared(tree: ast.AST) -> list[int]:
    """Lines that compare a joint's ``type`` or a kind's ``name`` with a kind's name written out."""
    names = set(KINDS)

    def literal(node: ast.AST) -> bool:
        if isinstance(node, ast.Constant):
            return node.value in names
        if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
            return any(literal(e) for e in node.elts)
        return False

    def asks_type(node: ast.AST) -> bool:
        return isinstance(node, ast.Attribute) and node.attr in ("type", "name")

    return [
        node.lineno
        for node in ast.walk(tree)
        if isinstance(node, ast.Compare)
        and any(asks_type(side) for side in (node.left, *node.comparators))
        and any(literal(side) for side in (node.left, *node.comparators))
    ]


def test_nothing_outside_the_pair_kinds_branches_on_a_kind_by_name():
    # issue 20 item 1: a layer asks the kind for a property (kind_of(j).meshes), never
    # `j.type == "gear"` or `kind_of(j).name in ("slot", "prismatic")`
    found = [
        f"{path.relative_to(SRC)}:{line}"
        for path, _, tree in source_trees()
        if "pairs" not in path.relative_to(SRC).parts
        for line in _kind_names_compared(tree)
    ]
    assert found == []
