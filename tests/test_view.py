"""``mech view``: one self-contained page, read back in a real browser (headless Chromium).

The page's contract is DESIGN § 1.5: ``#angle=`` picks the instant, each number shown is an
element with ``data-key`` (an answer key) and ``data-value`` (SI, as ``mech velocity --json``
gives it), a fragment it cannot read shows the file's own instant.  The browser tests read
the DOM after the page's script has run (``chromium --dump-dom``) and the console (its
messages are logged to stderr), and take a screenshot.  Reference values: the four-bar and
the slider crank in closed form (tests/oracles), a six-bar against ``mech velocity --angle …
--json`` and ``mech acceleration``.  Without a browser these tests skip, saying how to
install one; ``.ci/run`` installs it, so CI runs them.
"""

from __future__ import annotations

import html as htmllib
import json
import math
import re
import subprocess
from pathlib import Path

import pytest

from cli_runner import mech
from headless import FLAGS as HEADLESS
from headless import chromium

ROOT = Path(__file__).resolve().parent.parent
MECHANISMS = ROOT / "mechanisms"
INSTALL = "no browser: apt-get install -y chromium (Debian's package; .ci/run installs it)"
CHROMIUM = chromium()
#: The page's console messages are read from the browser's log on stderr.
FLAGS = (*HEADLESS, "--enable-logging=stderr", "--v=0")
needs_browser = pytest.mark.skipif(CHROMIUM is None, reason=INSTALL)


class _Pages(dict):
    """Example's name → its page, written the first time a test asks for it (the default run
    asks only for the four-bar's; the slider crank's and the six-bar's are for the slow set)."""

    def __init__(self, folder: Path) -> None:
        super().__init__()
        self.folder = folder

    def __missing__(self, name: str) -> Path:
        path = self.folder / f"{name}.html"
        run = mech("view", str(MECHANISMS / f"{name}.yaml"), "-o", str(path))
        assert run.returncode == 0, run.stderr
        self[name] = path
        return path


@pytest.fixture(scope="module")
def pages(tmp_path_factory) -> dict[str, Path]:
    """The pages of the four-bar, the slider crank and the Watt six-bar, each written once."""
    return _Pages(tmp_path_factory.mktemp("pages"))


def _browse(page: Path, fragment: str, tmp_path: Path, screenshot: Path | None = None) -> tuple[str, str]:
    """The page's DOM after its script ran, and what the browser logged (console messages)."""
    assert CHROMIUM is not None
    profile = tmp_path / f"profile-{abs(hash((str(page), fragment, str(screenshot))))}"
    what = [f"--screenshot={screenshot}", "--window-size=1280,1100"] if screenshot else ["--dump-dom"]
    done = subprocess.run(
        [CHROMIUM, *FLAGS, f"--user-data-dir={profile}", *what, page.as_uri() + fragment],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    return done.stdout, done.stderr


def _shown(dom: str) -> dict[str, float | None]:
    """data-key → data-value of every number the page shows."""
    out: dict[str, float | None] = {}
    for key, value in re.findall(r'data-key="([^"]+)" data-value="([^"]*)"', dom):
        out[htmllib.unescape(key)] = float(value) if value else None
    return out


def _console_errors(log: str) -> list[str]:
    return [
        line for line in log.splitlines() if "CONSOLE" in line and ("Error" in line or "Uncaught" in line)
    ]


# -- the page as a file: no browser needed --------------------------------------------------------
def test_page_is_one_self_contained_file_under_a_megabyte(pages):
    text = pages["four_bar"].read_text(encoding="utf-8")
    assert len(text.encode("utf-8")) <= 1_000_000
    assert "<script src" not in text and "<link" not in text and "@import" not in text
    # the only address is SVG's namespace name, which is never fetched
    assert set(re.findall(r"https?://[^\s\"')]+", text)) <= {"http://www.w3.org/2000/svg"}
    assert "autoplay" not in text


def test_page_data_holds_every_step_asked(tmp_path):
    out = tmp_path / "p.html"
    run = mech("view", str(MECHANISMS / "four_bar.yaml"), "-o", str(out), "--steps", "72", "--json")
    assert run.returncode == 0, run.stderr
    info = json.loads(run.stdout)
    assert info["steps"] == 72 and info["bytes"] == len(out.read_bytes())


def test_view_of_a_file_without_a_drive_is_exit_2(tmp_path):
    run = mech("view", str(MECHANISMS / "four_bar_dof.yaml"), "-o", str(tmp_path / "p.html"))
    assert run.returncode == 2
    assert "Traceback" not in run.stderr
    assert not (tmp_path / "p.html").exists()


def test_view_of_a_slider_drive_without_its_stroke_says_what_to_give(tmp_path):
    run = mech("view", str(MECHANISMS / "elliptic_trammel.yaml"), "-o", str(tmp_path / "p.html"))
    assert run.returncode == 2
    assert "--from and --to" in run.stderr


# -- in the browser ---------------------------------------------------------------------------------
FOUR_BAR = (0.040, 0.150, 0.080, 0.150)  # AB, BC, CD, AD (m): mechanisms/four_bar.yaml
W2 = -120 * 2 * math.pi / 60  # 120 rpm clockwise


def _four_bar_branch() -> bool:
    """The assembly the file picks with ``near: [100, 80]`` (mm), at its own 60°."""
    from tests.oracles.four_bar import four_bar

    up, *_ = four_bar(*FOUR_BAR, math.radians(60), W2, upper=True)
    down, *_ = four_bar(*FOUR_BAR, math.radians(60), W2, upper=False)
    return math.dist(up, (0.1, 0.08)) < math.dist(down, (0.1, 0.08))


@needs_browser
# a Chromium launch each (about 1 s of CPU): the default run reads the page at one angle, the slow
# set at the other two as well
@pytest.mark.parametrize(
    "angle", [pytest.param(30.0, marks=pytest.mark.slow), 100.0, pytest.param(250.0, marks=pytest.mark.slow)]
)
def test_four_bar_page_shows_the_closed_form_at_the_angle_in_its_address(pages, tmp_path, angle):
    from tests.oracles.four_bar import four_bar

    dom, log = _browse(pages["four_bar"], f"#angle={angle:g}", tmp_path)
    shown = _shown(dom)
    a, b, c, d = FOUR_BAR
    _C, w3, w4, a3, a4 = four_bar(a, b, c, d, math.radians(angle), W2, upper=_four_bar_branch())
    assert shown["angle"] == pytest.approx(math.radians(angle), rel=1e-8)
    assert shown["omega.crank"] == pytest.approx(W2, rel=1e-6)
    assert shown["omega.coupler"] == pytest.approx(w3, rel=1e-5)
    assert shown["omega.rocker"] == pytest.approx(w4, rel=1e-5)
    assert shown["alpha.coupler"] == pytest.approx(a3, rel=1e-5)
    assert shown["alpha.rocker"] == pytest.approx(a4, rel=1e-5)
    assert shown["velocity.B"] == pytest.approx(abs(W2) * a, rel=1e-6)
    assert shown["velocity.C"] == pytest.approx(abs(w4) * c, rel=1e-5)
    assert shown["acceleration.C"] == pytest.approx(c * math.hypot(a4, w4 * w4), rel=1e-5)
    assert not _console_errors(log)


@needs_browser
@pytest.mark.parametrize("angle", [20.0, 135.0, 300.0])
def test_slider_crank_page_shows_the_closed_form(pages, tmp_path, angle):
    """The file's slider runs at x < 0: the oracle's (slider ahead, x > 0) mirrored about the y axis.

    Mirrored, the crank's angle is π − θ and every angular velocity and acceleration changes sign.
    """
    from tests.oracles.slider_crank import slider_crank

    w = -300 * 2 * math.pi / 60  # 300 rpm clockwise
    dom, log = _browse(pages["slider_crank"], f"#angle={angle:g}", tmp_path)
    shown = _shown(dom)
    _x, w3, v, a3, acc = slider_crank(0.150, 0.600, 0.0, math.pi - math.radians(angle), -w)
    assert shown["angle"] == pytest.approx(math.radians(angle), rel=1e-8)
    assert shown["omega.rod"] == pytest.approx(-w3, rel=1e-5)
    assert shown["alpha.rod"] == pytest.approx(-a3, rel=1e-5)
    assert shown["velocity.B"] == pytest.approx(abs(v), rel=1e-5)
    assert shown["acceleration.B"] == pytest.approx(abs(acc), rel=1e-5)
    assert not _console_errors(log)


@needs_browser
@pytest.mark.parametrize("angle", [60.0, 145.0, 290.0])
def test_six_bar_page_shows_what_mech_velocity_and_acceleration_give(pages, tmp_path, angle):
    dom, log = _browse(pages["watt_six_bar"], f"#angle={angle:g}", tmp_path)
    shown = _shown(dom)
    path = str(MECHANISMS / "watt_six_bar.yaml")
    vel = json.loads(mech("velocity", path, "--angle", f"{angle:g}", "--json").stdout)
    acc = json.loads(mech("acceleration", path, "--angle", f"{angle:g}", "--json").stdout)
    want: dict[str, float] = {}
    for name, link in vel["links"].items():
        if name != "frame":
            want[f"omega.{name}"] = link["omega"]
            want[f"alpha.{name}"] = acc["links"][name]["alpha"]
    for p, q in zip(vel["points"], acc["points"], strict=True):
        if p["speed"] > 1e-9:  # a ground pivot is not a moving point (its speed is rounding)
            want[f"velocity.{p['point']}"] = p["speed"]
            want[f"acceleration.{q['point']}"] = q["acceleration_magnitude"]
    assert len(want) >= 15
    for key, value in want.items():
        assert shown[key] == pytest.approx(value, rel=1e-5, abs=1e-9), key
    assert not _console_errors(log)


@needs_browser
@pytest.mark.parametrize("fragment", ["", "#angle=banana", "#position=12", "#angle="])
def test_a_fragment_the_page_cannot_read_shows_the_files_own_instant(pages, tmp_path, fragment):
    dom, log = _browse(pages["four_bar"], fragment, tmp_path)
    shown = _shown(dom)
    assert shown["angle"] == pytest.approx(math.radians(60), rel=1e-9)  # the file's drive: angle 60
    assert not _console_errors(log)
    button = re.search(r'<button id="play"[^>]*>([^<]*)</button>', dom)
    assert button is not None and "Play" in button.group(1)  # it does not start playing by itself


@needs_browser
def test_page_screenshot_is_not_blank(pages, tmp_path):
    Image = pytest.importorskip("PIL.Image")
    shot = tmp_path / "shot.png"
    _, log = _browse(pages["watt_six_bar"], "#angle=100", tmp_path, screenshot=shot)
    img = Image.open(shot).convert("L")
    dark = sum(img.histogram()[:128])  # pixels darker than mid-grey
    assert dark > 0.004 * img.width * img.height  # links, pins, polygons and the table are drawn
    assert not _console_errors(log)


@needs_browser
def test_page_notices_a_script_error(pages, tmp_path):
    """The console check would see a script that fails (so its silence above means something)."""
    broken = tmp_path / "broken.html"
    broken.write_text(
        pages["four_bar"]
        .read_text(encoding="utf-8")
        .replace("show(fromHash());", "show(fromHash()); nope();"),
        encoding="utf-8",
    )
    _, log = _browse(broken, "", tmp_path)
    assert _console_errors(log)


@needs_browser
def test_a_slider_drives_page_reads_position_in_the_files_unit(tmp_path):
    """The elliptic trammel driven at A (0.1 m/s along x): A = (x, 0), B = (0, y), AB = 200 mm.

    The rod's ω from v_B − v_A = ω k × (B − A): ω = v_A / y, and |v_B| = ω x
    (x = 120, y = 160 mm: ω = 0.625 rad/s ccw, |v_B| = 0.075 m/s).
    """
    page = tmp_path / "trammel.html"
    run = mech(
        "view",
        str(MECHANISMS / "elliptic_trammel.yaml"),
        "-o",
        str(page),
        "--from",
        "20",
        "--to",
        "190",
        "--steps",
        "170",
    )
    assert run.returncode == 0, run.stderr
    dom, log = _browse(page, "#position=120", tmp_path)
    shown = _shown(dom)
    assert shown["position"] == pytest.approx(0.120, rel=1e-6)
    assert shown["omega.rod"] == pytest.approx(0.1 / 0.160, rel=1e-5)
    assert shown["velocity.B"] == pytest.approx(0.1 / 0.160 * 0.120, rel=1e-5)
    assert not _console_errors(log)


@needs_browser
def test_a_page_of_two_drives_plays_the_first_and_shows_the_closed_form_at_the_files_instant(tmp_path):
    """The five-bar driven by both cranks (mechanisms/five_bar_two_cranks.yaml, its header's
    closed form at θ₂ = θ₅ = 90°): ω₃ = −9.6077, ω₄ = +9.6077 rad/s, |v_C| = 0.52035 m/s; the
    slider is the first drive's angle, the second crank moving in proportion (ω₅/ω₂ = −2)."""
    page = tmp_path / "five_bar.html"
    run = mech("view", str(MECHANISMS / "five_bar_two_cranks.yaml"), "-o", str(page))
    assert run.returncode == 0, run.stderr
    dom, log = _browse(page, "#angle=banana", tmp_path)  # the file's own instant
    shown = _shown(dom)
    assert shown["angle"] == pytest.approx(math.radians(90), rel=1e-9)
    assert shown["omega.link_2"] == pytest.approx(10.0, rel=1e-9)
    assert shown["omega.link_5"] == pytest.approx(-20.0, rel=1e-9)
    w3 = -1200 / (2 * math.sqrt(80**2 - 50**2))  # -400 - h w3 = 800 + h w3, h = C_y - B_y (mm)
    assert shown["omega.link_3"] == pytest.approx(w3, rel=1e-6)
    assert shown["omega.link_4"] == pytest.approx(-w3, rel=1e-6)
    h = math.sqrt(80**2 - 50**2) / 1000
    assert shown["velocity.C"] == pytest.approx(math.hypot(-0.4 - w3 * h, w3 * 0.050), rel=1e-6)
    assert not _console_errors(log)


def test_a_profile_cams_own_point_has_its_speed_and_acceleration_rows(tmp_path):
    """DESIGN § 1.2 and § 1.5: K of a cam is the follower's own point (here the roller's centre).

    The eccentric disc (e = 15 mm, R = 40 mm) and roller (r = 10 mm) keep the roller's centre on
    y = e sin θ + √((R + r)² − e² cos² θ) (Norton § 4.6): its speed and acceleration, by mpmath's
    derivatives of that at the page's every 30th step, at 300 rpm ccw.
    """
    import mpmath

    data = _page_data(tmp_path, "eccentric_cam_roller")
    rows = {r["key"]: r["values"] for r in data["table"]}
    e, rr, w = 0.015, 0.050, 300 * 2 * math.pi / 60
    y = lambda t: e * mpmath.sin(t) + mpmath.sqrt(rr**2 - (e * mpmath.cos(t)) ** 2)  # noqa: E731
    for i in range(0, len(data["param"]["si"]), 30):
        theta = data["param"]["si"][i]
        assert rows["velocity.K"][i] == pytest.approx(
            abs(float(mpmath.diff(y, theta))) * w, rel=1e-5, abs=1e-9
        )
        assert rows["acceleration.K"][i] == pytest.approx(
            abs(float(mpmath.diff(y, theta, 2))) * w * w, rel=1e-5, abs=1e-7
        )


def _page_data(folder: Path, name: str) -> dict:
    """The data a shipped example's page carries (its table, its steps), read from the page written."""
    page = folder / f"{name}.html"
    run = mech("view", str(MECHANISMS / f"{name}.yaml"), "-o", str(page))
    assert run.returncode == 0, run.stderr
    text = page.read_text(encoding="utf-8")
    raw = re.search(r'<script id="mech-data" type="application/json">(.*?)</script>', text, re.S).group(1)
    return json.loads(raw.replace("<\\/", "</"))


def test_a_cams_contact_has_rows_for_the_point_of_each_link_there(tmp_path):
    """DESIGN § 1.2 and § 1.5: K@cam and K@follower, each link's point where the profiles touch.

    The disc's centre E = e(cos θ, sin θ) turns about O; the roller's centre K = (0, y) with
    y = e sin θ + √((R + r)² − e² cos² θ); they touch at P = E + R (K − E)/(R + r).  The cam's
    point there moves on a circle about O: |v| = ω|P|, |a| = ω²|P| at a steady 300 rpm; the
    follower translates, so its point there moves as K does (y′ω, y″ω², by mpmath).
    """
    import mpmath

    data = _page_data(tmp_path, "eccentric_cam_roller")
    rows = {r["key"]: r["values"] for r in data["table"]}
    e, big, small, w = 0.015, 0.040, 0.010, 300 * 2 * math.pi / 60
    y = lambda t: e * mpmath.sin(t) + mpmath.sqrt((big + small) ** 2 - (e * mpmath.cos(t)) ** 2)  # noqa: E731
    for i in range(0, len(data["param"]["si"]), 30):
        theta = data["param"]["si"][i]
        ex, ey = e * math.cos(theta), e * math.sin(theta)
        k = float(y(theta))
        px, py = ex + big * (0 - ex) / (big + small), ey + big * (k - ey) / (big + small)
        assert rows["velocity.K@cam"][i] == pytest.approx(w * math.hypot(px, py), rel=1e-6)
        assert rows["acceleration.K@cam"][i] == pytest.approx(w * w * math.hypot(px, py), rel=1e-6)
        assert rows["velocity.K@follower"][i] == pytest.approx(
            abs(float(mpmath.diff(y, theta))) * w, rel=1e-5, abs=1e-9
        )
        assert rows["acceleration.K@follower"][i] == pytest.approx(
            abs(float(mpmath.diff(y, theta, 2))) * w * w, rel=1e-5, abs=1e-7
        )


def test_a_gear_s_pitch_point_and_a_rolling_wheel_s_contact_have_their_rows(tmp_path):
    """The pinion (20 teeth, module 5 mm: r₁ = 50 mm) turns at 1,200 rpm and drives a 40-tooth wheel
    (r₂ = 100 mm, ω₂ = ω₁/2): the pitch point's speed is ω₁r₁ on both, its acceleration ω₁²r₁ as
    the pinion's point and ω₂²r₂ as the wheel's.  A wheel (r = 30 mm) rolling on flat ground: its
    point at the contact is at rest, and its acceleration is ω²r toward the centre, whatever α is."""
    gear = {r["key"]: r["values"] for r in _page_data(tmp_path, "gear_pair")["table"]}
    w1 = 1200 * 2 * math.pi / 60
    w2 = w1 / 2
    for i in range(0, 360, 45):
        # the page's numbers are to 7 significant figures
        assert gear["velocity.mesh"][i] == pytest.approx(w1 * 0.050, rel=1e-6)
        assert gear["acceleration.mesh@pinion"][i] == pytest.approx(w1 * w1 * 0.050, rel=1e-6)
        assert gear["acceleration.mesh@wheel"][i] == pytest.approx(w2 * w2 * 0.100, rel=1e-6)
    wheel = {r["key"]: r["values"] for r in _page_data(tmp_path, "rolling_wheel")["table"]}
    for i in range(0, 360, 45):
        omega = wheel["omega.wheel"][i]
        assert wheel["velocity.W"][i] == pytest.approx(0.0, abs=1e-9 * abs(omega) * 0.030)
        assert wheel["acceleration.W@wheel"][i] == pytest.approx(omega * omega * 0.030, rel=1e-6)


def test_the_shown_angles_hold_no_rounding_residue(tmp_path):
    # the clockwise cam's sweep reaches a turn's end 1e-15° from 0°: shown as 0°, each angle once
    shown = _page_data(tmp_path, "cam_roller_program")["param"]["shown"]
    assert all(x == 0.0 or 1e-6 < x < 360.0 for x in shown), [x for x in shown if 0 < x < 1e-6]
    assert sorted(shown) == [float(k) for k in range(360)]
