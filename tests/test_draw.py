"""Drawings: well-formed SVG, the expected elements, polygons to their stated scale."""

from __future__ import annotations

import math
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from cli_runner import mech, no_traceback, strict_json
from mech.draw import draw, save
from mech.draw.polygon import acceleration_polygon, velocity_polygon
from mech.draw.scene import nice_scale
from mech.draw.svg import to_svg
from mech.errors import MechError
from mech.kinematics import solve
from mech.loader import load
from mech.pairs import kind_of
from mechanism_texts import expected_refusal, slider_crank

ROOT = Path(__file__).resolve().parent.parent
MECHANISMS = ROOT / "mechanisms"
SVG = "{http://www.w3.org/2000/svg}"


def kinematic_examples() -> list[Path]:
    """Shipped examples with a driven speed and geometry: the ones drawn with their polygons."""
    out = []
    for path in sorted(MECHANISMS.glob("*.yaml")):
        m = load(path)
        speeds = all(d.omega is not None or d.speed is not None for d in m.drives)
        if m.drives and m.has_geometry and speeds:
            out.append(path)
    return out


def _solve(path: Path, level: str = "acceleration"):
    m = load(path)
    return m, solve(m, level=level)


def _parse(svg: str) -> ET.Element:
    return ET.fromstring(svg.encode("utf-8"))


def _panel_scales(root: ET.Element) -> list[float]:
    """The numbers of the "1 cm = X unit" captions, in panel order."""
    out = []
    for t in root.iter(f"{SVG}text"):
        if t.get("class") == "scale":
            out.append(float(re.match(r"1 cm = ([0-9.]+)", t.text or "").group(1)))
    return out


def _vectors(root: ET.Element) -> dict[str, float]:
    """data-name → length (mm) of every polygon vector shaft."""
    out = {}
    for line in root.iter(f"{SVG}line"):
        if line.get("class") == "vector":
            x1, y1, x2, y2 = (float(line.get(k)) for k in ("x1", "y1", "x2", "y2"))
            out[line.get("data-name")] = math.hypot(x2 - x1, y2 - y1)
    return out


# -- well-formed and complete ------------------------------------------------------------
@pytest.mark.parametrize("path", kinematic_examples(), ids=lambda p: p.stem)
def test_every_kinematic_example_draws_well_formed_svg(path):
    m = load(path)
    acc = expected_refusal(path.read_text(encoding="utf-8"), "acceleration") is None
    if not acc:  # a contact given by point and normal has no curvature: velocities only
        with pytest.raises(MechError):
            solve(m, level="acceleration")
    kin = solve(m, level="acceleration" if acc else "velocity")
    root = _parse(to_svg(draw(m, kin, velocity=True, acceleration=acc)))
    assert root.tag == f"{SVG}svg"
    assert root.get("width").endswith("mm")
    pins = [c.get("data-name") for c in root.iter(f"{SVG}circle") if c.get("class") == "pin"]
    revolutes = [j.name for j in m.joints if kind_of(j).role == "pin" and j.name in kin.positions]
    assert sorted(pins) == sorted(revolutes)
    labels = {t.text for t in root.iter(f"{SVG}text") if t.get("class") == "label"}
    assert len(labels) >= len(revolutes)
    assert _vectors(root), "the velocity polygon has vectors"


def test_four_bar_svg_has_pins_labels_ground_and_vectors():
    m, kin = _solve(MECHANISMS / "four_bar.yaml", "velocity")
    root = _parse(to_svg(draw(m, kin, velocity=True)))
    circles = [c for c in root.iter(f"{SVG}circle") if c.get("class") == "pin"]
    assert len(circles) == 4
    labels = {t.text for t in root.iter(f"{SVG}text") if t.get("class") == "label"}
    assert labels == {"A", "B", "C", "D"}
    assert sum(1 for p in root.iter(f"{SVG}polygon") if p.get("class") == "ground-pivot") == 2
    assert set(_vectors(root)) == {"ab", "bc", "dc"}
    images = {t.text for t in root.iter(f"{SVG}text") if t.get("class") == "image-label"}
    assert images == {"a, d", "b", "c"}


def test_svg_is_deterministic():
    m, kin = _solve(MECHANISMS / "slider_crank.yaml", "velocity")
    assert to_svg(draw(m, kin, velocity=True)) == to_svg(draw(m, kin, velocity=True))


def test_subscripts_as_the_notes_write_them():
    m, kin = _solve(MECHANISMS / "watt_six_bar.yaml", "velocity")
    root = _parse(to_svg(draw(m, kin, velocity=True)))
    labels = {t.text for t in root.iter(f"{SVG}text") if t.get("class") == "label"}
    assert {"O₂", "O₄", "O₆"} <= labels
    assert "o₄c" in _vectors(root)


# -- to scale -------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("name", "expected"),
    [
        ("four_bar.yaml", {"ab": ("B",), "dc": ("C",), "bc": ("C", "B")}),
        ("slider_crank.yaml", {"oa": ("A",), "ob": ("B",), "od": ("D",), "ab": ("B", "A")}),
    ],
)
def test_velocity_polygon_lengths_match_velocities_at_stated_scale(name, expected):
    m, kin = _solve(MECHANISMS / name, "velocity")
    root = _parse(to_svg(draw(m, kin, velocity=True)))
    scale = _panel_scales(root)[1]  # configuration first, then the velocity polygon
    lengths = _vectors(root)
    for vector, points in expected.items():
        v = kin.velocity(points[0]) if len(points) == 1 else kin.relative_velocity(*points)
        measured = lengths[vector] / 10 * scale  # mm → cm → m/s
        assert measured == pytest.approx(math.hypot(*v), rel=2e-3, abs=0.01 * scale), vector


def test_velocity_polygon_of_slotted_lever_shows_sliding_velocity():
    m, kin = _solve(MECHANISMS / "crank_slotted_lever_quick_return.yaml", "velocity")
    data = velocity_polygon(m, kin)
    sliding = [v for v in data.vectors if v.kind == "sliding"]
    assert len(sliding) == 1
    assert math.hypot(*sliding[0].value) == pytest.approx(abs(kin.sliding("slot")), rel=1e-9)
    assert sliding[0].name == "a₄a"  # the lever (link 4)'s point under A, to A


def test_acceleration_polygon_components_add_up_and_match_scale():
    m, kin = _solve(MECHANISMS / "four_bar.yaml", "acceleration")
    data = acceleration_polygon(m, kin)
    bc = data.vector("b′c′")
    rel = kin.relative_acceleration("C", "B")
    assert bc.value == pytest.approx(rel, rel=1e-9)
    parts = [v for v in data.vectors if v.kind in ("normal", "tangential") and v.link == "coupler"]
    assert len(parts) == 2
    total = (sum(p.value[0] for p in parts), sum(p.value[1] for p in parts))
    assert total == pytest.approx(rel, rel=1e-9)
    normal = next(p for p in parts if p.kind == "normal")
    w = kin.links["coupler"].omega
    assert math.hypot(*normal.value) == pytest.approx(
        w * w * math.dist(kin.positions["B"], kin.positions["C"])
    )
    root = _parse(to_svg(draw(m, kin, acceleration=True)))
    scale = _panel_scales(root)[1]
    assert _vectors(root)["d′c′"] / 10 * scale == pytest.approx(math.hypot(*kin.acceleration("C")), rel=2e-3)


def test_coriolis_component_drawn_at_a_slider_on_a_moving_guide():
    m, kin = _solve(MECHANISMS / "whitworth_quick_return.yaml", "acceleration")
    data = acceleration_polygon(m, kin)
    cor = next(v for v in data.vectors if v.kind == "coriolis")
    assert cor.value == pytest.approx(kin.coriolis("slot"), rel=1e-9)


@pytest.mark.parametrize("extent", [1e-6, 0.0123, 0.5, 3.0, 47.0, 1e5])
def test_nice_scale_is_round_and_fits(extent):
    s = nice_scale(extent, 100.0)
    mantissa = s / 10 ** math.floor(math.log10(s))
    assert any(math.isclose(mantissa, m) for m in (1, 2, 2.5, 5))
    assert extent / s * 10 <= 100.0 + 1e-9  # fits in 100 mm
    assert extent / s * 10 > 100.0 / 2.5 - 1e-9  # and is not needlessly small


# -- I-centres ------------------------------------------------------------------------------
def _centre(name, point=None, direction=None):
    return SimpleNamespace(name=name, point=point, direction=direction, at_infinity=point is None)


def test_icentres_drawn_as_points_and_arrows_to_infinity():
    m, kin = _solve(MECHANISMS / "slider_crank.yaml", "velocity")
    centres = [
        _centre("I12", kin.positions["O"]),
        _centre("I23", kin.positions["A"]),
        _centre("I14", None, (0.0, 1.0)),
    ]
    root = _parse(to_svg(draw(m, kin, icentres=centres)))
    marks = [c.get("data-name") for c in root.iter(f"{SVG}circle") if c.get("class") == "icentre"]
    assert sorted(marks) == ["I12", "I23"]
    texts = [t.text for t in root.iter(f"{SVG}text") if t.get("class") == "icentre-label"]
    assert "I14 → ∞" in texts
    arrows = [ln for ln in root.iter(f"{SVG}line") if ln.get("class") == "icentre-arrow"]
    assert len(arrows) == 1
    (x1, y1, x2, y2) = (float(arrows[0].get(k)) for k in ("x1", "y1", "x2", "y2"))
    assert abs(x2 - x1) < 1e-6 and y2 < y1  # points up the page, the way (0, 1) goes


def test_icentres_from_the_locator_overlay():
    from mech.icentres import locate

    m, kin = _solve(MECHANISMS / "four_bar.yaml", "velocity")
    ic = locate(m, kin)
    root = _parse(to_svg(draw(m, kin, icentres=ic.centres)))
    texts = " ".join(t.text for t in root.iter(f"{SVG}text") if t.get("class") == "icentre-label")
    for name in ("I12", "I13", "I14", "I23", "I24", "I34"):
        assert name in texts


# -- command line ------------------------------------------------------------------------
def test_cli_draw_writes_svg(run, tmp_path):
    out = tmp_path / "fb.svg"
    result = run("draw", str(MECHANISMS / "four_bar.yaml"), "-o", str(out), "--velocity", "--icentres")
    assert result.exit_code == 0, result.output
    root = _parse(out.read_text(encoding="utf-8"))
    assert _vectors(root)


def test_cli_draw_json_summary_states_scales(run, tmp_path):
    out = tmp_path / "sc.svg"
    result = run(
        "draw", str(MECHANISMS / "slider_crank.yaml"), "-o", str(out), "--velocity", "--json", "--units", "mm"
    )
    assert result.exit_code == 0
    assert '"1 cm = 500 mm/s"' in result.stdout


def test_cli_draw_refuses_unknown_format(run, tmp_path):
    result = run("draw", str(MECHANISMS / "four_bar.yaml"), "-o", str(tmp_path / "x.pdf"))
    assert result.exit_code == 2
    assert "name the output .svg or .png" in result.stderr


def test_cli_draw_png_without_matplotlib_says_how_to_install(run, tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # import matplotlib now raises ImportError
    result = run("draw", str(MECHANISMS / "four_bar.yaml"), "-o", str(tmp_path / "x.png"))
    assert result.exit_code == 2
    assert "pip install 'planar-mech[plot]'" in result.stderr
    assert not (tmp_path / "x.png").exists()


@pytest.mark.parametrize("command", ["dof", "check"])
def test_dof_and_check_never_import_drawing_code(command):
    code = (
        "import sys; from mech.cli import main\n"
        f"try:\n    main([{command!r}, sys.argv[1]])\nexcept SystemExit:\n    pass\n"
        "print('LOADED=' + ','.join(sorted(m for m in sys.modules if m == 'matplotlib' or m.startswith('mech.draw'))))\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code, str(MECHANISMS / "four_bar.yaml")],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=120,
    )
    assert "LOADED=\n" in result.stdout, result.stdout + result.stderr


def test_save_by_extension(tmp_path):
    m, kin = _solve(MECHANISMS / "four_bar.yaml", "position")
    save(draw(m, kin), tmp_path / "a.svg")
    assert (tmp_path / "a.svg").read_text(encoding="utf-8").startswith("<?xml")


def test_profiles_are_drawn_on_their_links_where_the_pair_has_moved():
    from mech.draw.config import configuration
    from mech.options import SolveOptions

    m = load(MECHANISMS / "eccentric_cam.yaml")
    kin = solve(m, "velocity", SolveOptions(angle=math.radians(120)))
    page = configuration(m, kin)
    profiles = [i for i in page.items if getattr(i, "cls", None) == "profile"]
    circles = [i for i in profiles if hasattr(i, "r")]
    assert {i.name for i in profiles} == {"cam", "follower"} and len(circles) == 1
    # the disc is drawn about E where E is now, not where the file drew it
    (circle,) = circles
    (dot,) = [i for i in page.items if getattr(i, "cls", None) == "point" and i.name == "E"]
    assert circle.centre == pytest.approx(dot.centre)
    assert kin.positions["E"][0] == pytest.approx(0.015 * math.cos(math.radians(120)), abs=1e-15)


def test_a_programmed_cams_surface_is_drawn_turned_with_the_cam():
    from mech.draw.config import configuration
    from mech.options import SolveOptions

    m = load(MECHANISMS / "cam_roller_program.yaml")
    drawn = configuration(m, solve(m, "position"))
    turned = configuration(m, solve(m, "position", SolveOptions(angle=math.radians(150))))

    def surface(page):
        (poly,) = [i for i in page.items if getattr(i, "cls", None) == "profile" and hasattr(i, "points")]
        return poly

    a, b = surface(drawn), surface(turned)
    assert len(a.points) == len(b.points) == 720
    assert a.points != b.points  # carried round with the cam, not left as drawn


# -- through the command line as a user runs it (cli_runner: tracebacks shown) -----------
HOSTILE_DRAW = """\
name: "Crank <&\\"'> \\u00e9 ]]> </svg> <!-- x"
links: ["fr<am>e&", "cr'a\\"nk", rod, "pist\\u00f6n"]
ground: "fr<am>e&"
joints:
  "O<1>": {type: revolute, links: ["fr<am>e&", "cr'a\\"nk"], at: [0, 0]}
  "A&": {type: revolute, links: ["cr'a\\"nk", rod]}
  B: {type: revolute, links: [rod, "pist\\u00f6n"], near: [0.5, 0]}
  P: {type: prismatic, links: ["pist\\u00f6n", "fr<am>e&"], path: {through: [0, 0], angle: 0}}
lengths: {"O<1>-A&": 0.1, "A&-B": 0.4}
drive: {link: "cr'a\\"nk", angle: 60, omega: 10}
"""


def test_draw_hostile_names_give_well_formed_svg_carrying_them_as_text(tmp_path):
    """<, &, quotes, unicode, "]]>" and "<!--" in link, joint and mechanism names."""
    m = tmp_path / "h.yaml"
    m.write_text(HOSTILE_DRAW, encoding="utf-8")
    out = tmp_path / "h.svg"
    p = mech("draw", str(m), "-o", str(out), "--velocity", "--acceleration", "--icentres", "--json")
    no_traceback(p)
    assert p.returncode == 0, p.stderr
    strict_json(p.stdout)
    root = ET.parse(out).getroot()
    texts = ["".join(t.itertext()) for t in root.iter("{http://www.w3.org/2000/svg}text")]
    assert "Crank <&\"'> é ]]> </svg> <!-- x" in texts
    assert "O<1>" in texts and "A&" in texts


def test_draw_name_with_a_control_character_gives_well_formed_svg(tmp_path):
    """A control character (YAML "\\x01", pasted text) XML 1.0 cannot hold is kept out of the SVG."""
    m = tmp_path / "h.yaml"
    m.write_text(HOSTILE_DRAW.replace("\\u00e9 ]]>", "\\x01 ]]>", 1), encoding="utf-8")
    out = tmp_path / "h.svg"
    p = mech("draw", str(m), "-o", str(out))
    no_traceback(p)
    assert p.returncode == 0
    ET.parse(out)


def test_draw_of_a_mechanism_at_rest_states_no_absurd_scale(tmp_path):
    """ω = 0: the polygons shrink to the pole; no scale like "1 cm = 2×10^-301 m/s" is stated."""
    m = tmp_path / "r.yaml"
    m.write_text(HOSTILE_DRAW.replace("omega: 10", "omega: 0"), encoding="utf-8")
    out = tmp_path / "r.svg"
    p = mech("draw", str(m), "-o", str(out), "--velocity", "--acceleration", "--json")
    no_traceback(p)
    assert p.returncode == 0
    ET.parse(out)
    scales = strict_json(p.stdout)["scales"]
    exps = [int(x.translate(_FROM_SUPER)) for s in scales for x in re.findall(r"10([⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+)", s)]
    assert all(abs(e) < 30 for e in exps), scales


_FROM_SUPER = str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789")


@pytest.mark.parametrize(
    "size, scale", [(1e-7, "1 cm = 5×10⁻⁸ m"), (1.0, "1 cm = 0.5 m"), (1e9, "1 cm = 5×10⁸ m")]
)
def test_draw_of_tiny_and_huge_mechanisms_keeps_the_sheet_and_a_round_scale(tmp_path, size, scale):
    """Crank 0.1 um or 1e9 m: same sheet size, round stated scale, no nan/inf in any attribute."""
    m = tmp_path / "s.yaml"
    m.write_text(slider_crank(size, 4 * size, 60, 10), encoding="utf-8")
    out = tmp_path / "s.svg"
    p = mech("draw", str(m), "-o", str(out), "--velocity", "--acceleration", "--icentres", "--json")
    no_traceback(p)
    assert p.returncode == 0, p.stderr
    d = strict_json(p.stdout)
    assert d["scales"][0] == scale
    assert 100 < d["size_mm"][0] < 500 and 50 < d["size_mm"][1] < 500
    text = out.read_text(encoding="utf-8")
    assert not re.search(r'="[^"]*(nan|inf)[^"]*"', text, re.I)
    ET.fromstring(text.encode("utf-8"))


def test_draw_png_without_matplotlib_and_an_unknown_suffix_are_exit_2(tmp_path):
    """matplotlib blocked in a fresh interpreter: .png is exit 2 with the pip hint, nothing written."""
    m = tmp_path / "s.yaml"
    m.write_text(slider_crank(0.1, 0.4, 60, 10), encoding="utf-8")
    png = tmp_path / "s.png"
    code = (
        "import sys; sys.modules['matplotlib'] = None\n"
        "from mech.cli import main\n"
        f"main(['draw', {str(m)!r}, '-o', {str(png)!r}])\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr, proc.stderr[-800:]
    assert "planar-mech[plot]" in proc.stderr and not png.exists()
    p = mech("draw", str(m), "-o", str(tmp_path / "s.pdf"))
    no_traceback(p)
    assert p.returncode == 2


def test_draw_to_a_missing_folder_is_exit_2(tmp_path):
    """As ``check --junit`` to a missing folder: "cannot write", exit 2, not FileNotFoundError."""
    f = tmp_path / "m.yaml"
    f.write_text(slider_crank(), encoding="utf-8")
    p = mech("draw", str(f), "-o", str(tmp_path / "no" / "such" / "x.svg"))
    no_traceback(p)
    assert p.returncode == 2


def test_exponents_are_typeset_as_superscripts():
    from mech.draw.scene import fmt

    assert fmt(5e-5) == "5×10⁻⁵"
    assert fmt(1.25e12) == "1.25×10¹²"
    assert "^" not in fmt(3e-300)


def test_every_mesh_point_of_a_compound_gear_has_a_distinct_label():
    """Both meshes of the middle shaft are points of link 3: m12₃ and m23₃, never m₃ twice."""
    from mech.loader import loads
    from mechanism_texts import COMPOUND_GEAR

    m = loads(COMPOUND_GEAR, path="compound_gear.yaml")
    kin = solve(m, "acceleration")
    for data in (velocity_polygon(m, kin), acceleration_polygon(m, kin)):
        labels = [im.label for im in data.images]
        assert len(labels) == len(set(labels)), labels
        assert {"m12₃", "m23₃"} <= {label.rstrip("′") for label in labels}
    root = _parse(to_svg(draw(m, kin, velocity=True)))
    shown = [t.text for t in root.iter(f"{SVG}text") if t.get("class") == "image-label"]
    assert not any("m₃" in text for text in shown), shown


def test_far_icentres_give_their_true_distance_from_the_frames_first_pivot():
    """The shaper's far I-centres: arrows at the edge with distances from O₂ (its first pivot), alike in every drawing."""
    from mech.icentres import locate

    m, kin = _solve(MECHANISMS / "crank_slotted_lever_quick_return.yaml", "velocity")
    centres = locate(m, kin).centres
    texts = list(_parse(to_svg(draw(m, kin, icentres=list(centres)))).iter(f"{SVG}text"))
    far = [t for t in texts if t.get("class") == "icentre-label" and "→" in (t.text or "")]
    assert far
    notes = [t.text for t in texts if t.get("class") == "icentre-note"]
    assert len(notes) == 1 and notes[0].endswith("from O₂"), notes  # the named point
    first = next(j for j in m.joints if m.ground in j.links and kind_of(j).role == "pin")
    pivot = kin.positions[first.name]
    measured = 0
    for t in far:
        for name, value in re.findall(r"(I\d+) → ([0-9.]+) mm", t.text):
            c = next(c for c in centres if c.name == name)
            assert float(value) == pytest.approx(math.dist(c.point, pivot) * 1000, rel=5e-4)
            measured += 1
    assert measured >= 2
    # the same numbers with the velocity polygon beside it (the label does not depend on the sheet)
    again = [
        t.text
        for t in _parse(to_svg(draw(m, kin, velocity=True, icentres=list(centres)))).iter(f"{SVG}text")
        if t.get("class") == "icentre-label" and "→" in (t.text or "")
    ]
    assert sorted(again) == sorted(t.text for t in far)


@pytest.mark.parametrize("option", [("--path", "C"), ("--centrodes", "link_3")])
def test_tracing_a_two_drive_file_is_refused_with_a_command_line_hint(run, tmp_path, option):
    """The hint names options of real commands, never a Python call (issue 25, item 13)."""
    from mech.cli import cli

    result = run("draw", str(MECHANISMS / "five_bar_two_cranks.yaml"), "-o", str(tmp_path / "x.svg"), *option)
    assert result.exit_code == 2
    err = result.stderr
    assert "sweep(" not in err and "drive=" not in err
    hinted = re.search(r"mech (\w+) \S+ (.*?) \(", err)
    assert hinted is not None, err
    command = cli.commands[hinted.group(1)]
    known = {o for p in command.params for o in getattr(p, "opts", ())}
    named = set(re.findall(r"--[a-z-]+", err.split("hint:", 1)[1]))
    assert named and named <= known, named - known
    assert not (tmp_path / "x.svg").exists()


def test_labels_are_placed_without_measuring_every_segment_of_a_long_path(monkeypatch):
    """A 10,000-step path: each label measures only the segments within its reach (issue 25,
    item 9), and lands exactly where measuring every segment puts it."""
    from mech.draw import config, scene

    m = load(MECHANISMS / "four_bar.yaml")
    kin = solve(m, level="position")
    dense = [
        (0.05 + 0.06 * math.cos(t), 0.05 + 0.04 * math.sin(t)) for t in np.linspace(0, 2 * math.pi, 10_001)
    ]
    calls = 0
    measure = scene._seg_dist

    def counted(p, a, b):
        nonlocal calls
        calls += 1
        return measure(p, a, b)

    monkeypatch.setattr(scene, "_seg_dist", counted)
    fast = config.configuration(m, kin, curves=[("path of P", dense, "path")])
    # every segment, as before: no segment is ever out of reach
    monkeypatch.setattr(scene, "_near_segments", lambda segs, box, reach: list(segs))
    calls_fast, calls = calls, 0
    slow = config.configuration(m, kin, curves=[("path of P", dense, "path")])
    assert to_svg(fast) == to_svg(slow)
    assert calls_fast < calls / 50, (calls_fast, calls)


@pytest.mark.parametrize(
    "name", ["cam_follower", "cam_roller_program", "cam_flat_follower", "cam_valve_khurmi"]
)
def test_a_translating_cam_follower_is_drawn_with_its_stem_in_its_guide(name):
    """As ``mech cam -o`` and the notes draw it: the follower's stem on its line of stroke, from
    the follower outward (away from the cam's pivot), held by a guide hatched on both sides."""
    m, kin = _solve(MECHANISMS / f"{name}.yaml", "position")
    root = _parse(to_svg(draw(m, kin)))

    def ends(e: ET.Element) -> tuple[tuple[float, float], tuple[float, float]]:
        x1, y1, x2, y2 = (float(e.get(k)) for k in ("x1", "y1", "x2", "y2"))
        return (x1, y1), (x2, y2)

    lines = list(root.iter(f"{SVG}line"))
    (stem,) = [ends(e) for e in lines if e.get("class") == "stem"]
    (stroke,) = [ends(e) for e in lines if e.get("class") == "stroke-line"]
    (pivot,) = [
        (float(e.get("cx")), float(e.get("cy"))) for e in root.iter(f"{SVG}circle") if e.get("class") == "pin"
    ]
    a, b = stem
    length = math.dist(a, b)
    u = ((b[0] - a[0]) / length, (b[1] - a[1]) / length)
    n = (-u[1], u[0])

    def off(p: tuple[float, float]) -> float:  # signed distance from the stem's axis
        return (p[0] - a[0]) * n[0] + (p[1] - a[1]) * n[1]

    def along(p: tuple[float, float]) -> float:
        return (p[0] - a[0]) * u[0] + (p[1] - a[1]) * u[1]

    assert length > 5.0  # mm on the page: a stem, not a dot
    assert off(stroke[0]) == pytest.approx(0, abs=0.05) and off(stroke[1]) == pytest.approx(0, abs=0.05)
    assert math.dist(b, pivot) > math.dist(a, pivot) + 0.9 * length  # outward, away from the cam
    guide = [
        side
        for e in lines
        if e.get("class") == "hatch"
        for p in ends(e)
        for side in (-1, 1)
        if off(p) * side == pytest.approx(1.6, abs=0.05) and 0 < along(p) < length
    ]
    assert guide.count(-1) >= 3 and guide.count(1) >= 3, guide
