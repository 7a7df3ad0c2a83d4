"""Output files (mech._files): nothing at a report's or a drawing's path is lost or turned into something else.

Issue 25, "Lost data": a device stays a device (written through), a symbolic link stays a link
(its target is written), a full disk is exit 2 naming the path and leaves the previous file
whole, a full standard output is exit 2 (not "a bug in mech"), and an unwritable report path
is said before the first problem file is checked.

Devices are private nodes made with ``os.mknod`` under the test's own folder — a null node
(major 1, minor 3) and a full node (1, 7), which refuses every write with ENOSPC — never the
machine's own ``/dev``.  Making them needs root (as CI runs); elsewhere those tests are
skipped, saying so.  The full disk is a small tmpfs mounted inside a private mount namespace
(``unshare -m``), gone when the test's shell ends.
"""

from __future__ import annotations

import errno
import os
import re
import shutil
import stat
import subprocess
import sys
from pathlib import Path

import pytest

from cli_runner import mech
from mech._files import check_writable, discard, write_file, write_with, writing
from mech.errors import InputError

ROOT = Path(__file__).resolve().parent.parent
FOUR_BAR = str(ROOT / "mechanisms" / "four_bar.yaml")
MECH = [sys.executable, "-m", "mech"]


def _node(folder: Path, name: str, minor: int) -> Path:
    if os.geteuid() != 0:
        pytest.skip("making a private device node (os.mknod) needs root, as CI runs")
    path = folder / name
    os.mknod(path, stat.S_IFCHR | 0o666, os.makedev(1, minor))
    return path


@pytest.fixture
def null(tmp_path: Path) -> Path:
    """A private null device (1, 3): takes every byte."""
    return _node(tmp_path, "null", 3)


@pytest.fixture
def full(tmp_path: Path) -> Path:
    """A private full device (1, 7): every write fails with ENOSPC, as on a full disk."""
    return _node(tmp_path, "full", 7)


def is_device(path: Path) -> bool:
    return stat.S_ISCHR(os.lstat(path).st_mode)


def run(
    *args: str, stdout: int | None = subprocess.PIPE, cwd: Path = ROOT
) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ, NO_COLOR="1", COLUMNS="120")
    return subprocess.run(
        [*MECH, *args], stdout=stdout, stderr=subprocess.PIPE, text=True, env=env, cwd=cwd, timeout=300
    )


# -- the helper ---------------------------------------------------------------------------------
def test_a_new_file_is_written_with_the_usual_permissions(tmp_path: Path) -> None:
    target = tmp_path / "r.txt"
    write_file(target, "abc")
    assert target.read_text() == "abc"
    mask = os.umask(0)
    os.umask(mask)
    assert stat.S_IMODE(target.stat().st_mode) == 0o666 & ~mask
    assert [p.name for p in tmp_path.iterdir()] == ["r.txt"]  # no temporary file left


def test_an_existing_file_keeps_its_permissions(tmp_path: Path) -> None:
    target = tmp_path / "r.txt"
    target.write_text("old")
    target.chmod(0o640)
    write_file(target, ["new", " text"])
    assert target.read_text() == "new text"
    assert stat.S_IMODE(target.stat().st_mode) == 0o640


def test_a_failed_write_leaves_the_previous_file_whole(tmp_path: Path) -> None:
    target = tmp_path / "drawing.svg"
    target.write_text("<svg>good</svg>")

    def half(f):  # a disk that fills part-way through
        f.write(b"<svg>trunc")
        raise OSError(errno.ENOSPC, "No space left on device")

    with pytest.raises(InputError, match=r"cannot write .*drawing\.svg: No space left on device"):
        write_with(target, half)
    assert target.read_text() == "<svg>good</svg>"
    assert [p.name for p in tmp_path.iterdir()] == ["drawing.svg"]


def test_an_exception_inside_leaves_the_previous_file_whole(tmp_path: Path) -> None:
    target = tmp_path / "r.csv"
    target.write_text("old")
    with pytest.raises(KeyboardInterrupt), writing(target) as f:
        f.write("partial")
        raise KeyboardInterrupt
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["r.csv"]


def test_a_symlink_stays_a_link_and_its_target_is_written(tmp_path: Path) -> None:
    (tmp_path / "real").mkdir()
    target = tmp_path / "real" / "report.xml"
    target.write_text("old")
    link = tmp_path / "report.xml"
    link.symlink_to(target)
    write_file(link, "new")
    assert link.is_symlink() and os.readlink(link) == str(target)
    assert target.read_text() == "new"


def test_a_dangling_symlink_gets_its_target_made(tmp_path: Path) -> None:
    link = tmp_path / "out.csv"
    link.symlink_to(tmp_path / "made.csv")
    write_file(link, "x,y\n")
    assert link.is_symlink() and (tmp_path / "made.csv").read_text() == "x,y\n"


def test_a_device_is_written_through_and_stays_a_device(null: Path) -> None:
    write_file(null, "anything")
    write_with(null, lambda f: f.write(b"\x89PNG"))
    assert is_device(null)


def test_a_full_device_is_an_input_error_naming_it(full: Path) -> None:
    with pytest.raises(
        InputError, match=re.escape(f"cannot write {full}: No space left on device")
    ) as caught:
        write_file(full, "x" * 10)
    assert caught.value.exit_code == 2
    assert is_device(full)


def test_a_folder_is_refused_naming_it(tmp_path: Path) -> None:
    with pytest.raises(InputError, match="it is a folder"):
        write_file(tmp_path, "x")
    with pytest.raises(InputError, match="it is a folder"):
        check_writable(tmp_path)


def test_an_unwritable_path_is_found_before_writing(tmp_path: Path) -> None:
    with pytest.raises(InputError, match="No such file or directory"):
        check_writable(tmp_path / "no" / "such" / "r.xml")
    check_writable(tmp_path / "r.xml")
    assert list(tmp_path.iterdir()) == []  # the probe left nothing


def test_discard_removes_a_report_but_never_a_device_or_a_link(tmp_path: Path, null: Path) -> None:
    report = tmp_path / "old.xml"
    report.write_text("stale")
    discard(report)
    assert not report.exists()
    discard(null)
    assert is_device(null)
    target = tmp_path / "t.xml"
    target.write_text("stale")
    link = tmp_path / "l.xml"
    link.symlink_to(target)
    discard(link)
    assert link.is_symlink() and not target.exists()


# -- every output of the command line -----------------------------------------------------------
def test_reports_to_a_device_leave_it_a_device(tmp_path: Path, null: Path) -> None:
    others = [_node(tmp_path, name, 3) for name in ("junit", "grades", "null.svg")]
    checked = run("check", FOUR_BAR, "-j", "1", "--junit", str(null), "--csv", str(others[0]))
    assert checked.returncode == 0, checked.stderr
    assert run("check", FOUR_BAR, "-j", "1", "--gradescope", str(others[1])).returncode == 0
    assert run("sweep", FOUR_BAR, "--steps", "12", "--csv", str(null)).returncode == 0
    assert run("schema", "-o", str(null)).returncode == 0
    drawn = run("draw", FOUR_BAR, "-o", str(others[2]))
    assert drawn.returncode == 0, drawn.stderr
    assert all(is_device(p) for p in (null, *others))


def test_two_reports_may_share_a_device(null: Path) -> None:
    both = run("check", FOUR_BAR, "-j", "1", "--junit", str(null), "--csv", str(null))
    assert both.returncode == 0, both.stderr
    assert is_device(null)


def test_a_report_to_a_full_device_is_exit_2_naming_it(full: Path) -> None:
    for args in (
        ("check", FOUR_BAR, "-j", "1", "--junit", str(full)),
        ("sweep", FOUR_BAR, "--steps", "12", "--csv", str(full)),
        ("schema", "-o", str(full)),
    ):
        done = run(*args)
        assert done.returncode == 2, (args, done.stderr)
        assert f"cannot write {full}: No space left on device" in done.stderr
        assert "internal error" not in done.stderr
    assert is_device(full)


def test_a_csv_through_a_symlink_writes_the_target(tmp_path: Path) -> None:
    target = tmp_path / "data" / "series.csv"
    target.parent.mkdir()
    target.write_text("old")
    link = tmp_path / "series.csv"
    link.symlink_to(target)
    # in process: `sweep` is click's in a process too (not the console script's fast path)
    assert mech("sweep", FOUR_BAR, "--steps", "12", "--csv", str(link)).returncode == 0
    assert link.is_symlink()
    assert target.read_text().startswith("angle [deg],")


def test_a_full_standard_output_is_exit_2_not_a_bug(full: Path) -> None:
    for args in (("schema",), ("velocity", FOUR_BAR), ("dof", FOUR_BAR), ("sweep", FOUR_BAR, "--csv", "-")):
        with open(full, "w") as out:
            done = run(*args, stdout=out.fileno())
        assert done.returncode == 2, (args, done.stderr)
        assert "cannot write standard output: No space left on device" in done.stderr
        assert "internal error" not in done.stderr and "Traceback" not in done.stderr


def test_an_unwritable_report_path_is_said_before_the_first_file(tmp_path: Path) -> None:
    missing = tmp_path / "no-such-folder" / "report.xml"
    for option in ("--junit", "--gradescope", "--csv"):
        done = run("check", str(ROOT / "mechanisms"), "-j", "1", option, str(missing))
        assert done.returncode == 2
        assert done.stdout == ""  # not a file was checked
        assert f"cannot write {missing}: No such file or directory" in done.stderr


def test_an_interrupted_check_leaves_a_device_report_path_alone(monkeypatch, null: Path) -> None:
    import mech.batch
    from mech.cli import main  # in process: the console script's fast path leaves by os._exit

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(mech.batch, "run", interrupted)
    with pytest.raises(SystemExit) as done:
        main(["check", FOUR_BAR, "--junit", str(null)])
    assert done.value.code == 130
    assert is_device(null)


# -- a full disk --------------------------------------------------------------------------------
def _in_small_tmpfs(tmp_path: Path, script: str) -> str:
    """Run ``script`` (sh) in ``tmp_path`` with a 256 KiB tmpfs mounted over it, privately."""
    if os.geteuid() != 0 or shutil.which("unshare") is None:
        pytest.skip("a private tmpfs needs root and unshare, as CI runs")
    mounted = f"mount -t tmpfs -o size=256k tmpfs {tmp_path} || exit 99; cd {tmp_path} && {script}"
    env = dict(os.environ, NO_COLOR="1", PYTHONPATH=os.pathsep.join(sys.path))
    done = subprocess.run(
        ["unshare", "-m", "sh", "-c", mounted], capture_output=True, text=True, env=env, timeout=300
    )
    if done.returncode == 99:
        pytest.skip(f"cannot mount a private tmpfs here: {done.stderr.strip()}")
    assert done.returncode == 0, done.stderr
    return done.stdout


FILL = (
    f"{sys.executable} -c \"f=open('filler','wb')\ntry:\n    f.write(b'0'*10**7)\nexcept OSError:\n    pass\n"
    'try:\n    f.close()\nexcept OSError:\n    pass"'
)


@pytest.mark.parametrize(
    "command",
    [
        ("draw", FOUR_BAR, "--velocity", "--acceleration", "-o", "{out}.svg"),
        ("sweep", FOUR_BAR, "--steps", "360", "--path", "C", "--svg", "{out}.svg"),
        ("cam", str(ROOT / "mechanisms" / "cam_roller_program.yaml"), "-o", "{out}.svg"),
        ("sweep", FOUR_BAR, "--steps", "3600", "--csv", "{out}.csv"),
    ],
    ids=["draw", "sweep-svg", "cam", "sweep-csv"],
)
def test_a_full_disk_leaves_the_previous_output_whole(tmp_path: Path, command: tuple[str, ...]) -> None:
    out = "good"
    suffix = command[-1].rsplit(".", 1)[1]
    name = f"{out}.{suffix}"
    argv = " ".join(f"'{a.format(out=out)}'" for a in command)
    mech = " ".join(MECH)
    script = (
        f"printf 'previous good output' > {name} && {FILL} && "
        f'said=$({mech} {argv} 2>&1); echo "status=$?"; echo "$said"; printf content=; cat {name}'
    )
    said = _in_small_tmpfs(tmp_path, script)
    assert "status=2" in said, said
    assert f"cannot write {name}: No space left on device" in said
    assert said.rstrip().endswith("content=previous good output"), said[-300:]
