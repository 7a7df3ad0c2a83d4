"""Every figure of the speed table, each as a ratio against its reference, in ONE interleaved run.

    pip install -e '.[bench]'                       # pylinkage, for the one-step reference
    python tests/benchmarks/bench_issue_table.py [--repeat 9] [--venv /tmp/mech-bench-venv]
        [--before /path/to/venv-of-the-tree-before]

Rows (mech | reference):

* ``mech dof --json four_bar.yaml`` | ``python -c pass``, and
  ``mech velocity four_bar.yaml --rpm 600`` | ``python -c "import numpy"``: whole
  commands in fresh processes, run from a throw-away virtual environment made
  with ``pip install .`` as the README's first line does (not editable, so
  bytecode is compiled and no import hook adds its cost).  The venv is made
  once at ``--venv`` and the current tree reinstalled into it on every run
  (``--no-install`` skips that).  With ``--before`` (a venv where an earlier
  tree is ``pip install``-ed), the same commands from it too, in the same
  interleaved run, and the ratio now / before.
* one position + velocity + acceleration of the four-bar (pylinkage's four-bar
  of tests/benchmarks/bench_peers.py is the reference): :func:`~mech.kinematics.solve`
  at the file's own drive angle (what ``mech velocity FILE`` and every homework
  file ask), the same with its whole result read (every point, link and joint
  packaged: what a command prints), at the drawn angle + 37°, and the lean
  closed form (``closed_form(m).state``) | pylinkage's one step with derivatives.
  With ``--before``, the drawn-angle solve (and read) is also timed in the
  earlier tree, each sample a fresh interpreter of that venv timing 500 calls.
* Newton (``method="newton"``, 5° from the drawing, tol 1e-12) on generated
  chains of 40, 100 and 200 links | the same on 4 links; linear growth is a
  ratio of n/4 (10, 25, 50) or less.
* a 3,600-step sweep with accelerations of a mechanism that does not decompose
  into dyads (the double parallelogram, the gear pair, and the moving higher
  pairs: a wheel rolling on the ground, a roller on an eccentric) | the closed-form sweep
  of the four-bar; the series alone (``analyse=False``) and the whole
  ``sweep`` (extremes refined, dead centres).

Every repeat runs every case once, in turn, so that a burst of load on the
shared machine falls on all cases alike; the table gives medians over the
repeats and the ratio of medians.  The machine this project is developed on
is shared by several engineers: absolute times move by tens of per cent
between runs, the ratios within one run much less.  Quote ratios.
"""

from __future__ import annotations

import os

# The whole commands run in the environment the user's shell gives them (:func:`user_env`): a BLAS
# thread pool numpy starts there is part of what ``import numpy`` (the reference) and each command
# cost a user.  This process's own µs timings run on one thread: there threads only add noise.
os.environ.setdefault("MECH_BENCH_USER_BLAS", os.environ.get("OPENBLAS_NUM_THREADS", "unset"))
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import math
import platform
import resource
import statistics
import subprocess
import sys
import time
import timeit
from collections.abc import Callable
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE))

from bench_growth import chain  # noqa: E402

import mech  # noqa: E402
from mech.kinematics import closed_form, solve, sweep  # noqa: E402
from mech.options import SolveOptions  # noqa: E402

FOUR_BAR = ROOT / "mechanisms" / "four_bar.yaml"
STEPS = 3600


def venv(path: Path, install: bool) -> Path:
    """A virtual environment at ``path`` with this tree ``pip install``-ed (not editable)."""
    python = path / "bin" / "python"
    if not python.exists():
        subprocess.run([sys.executable, "-m", "venv", str(path)], check=True)
        subprocess.run([str(python), "-m", "pip", "install", "-q", str(ROOT)], check=True)
    elif install:  # the tree as it is now; the dependencies are already there
        subprocess.run(
            [str(python), "-m", "pip", "install", "-q", "--force-reinstall", "--no-deps", str(ROOT)],
            check=True,
        )
    return path


#: CPU seconds (user + system) of each command line's runs, in the order run (beside the wall times).
CPU: dict[tuple[str, ...], list[float]] = {}


def user_env() -> dict[str, str]:
    """The environment as the user's shell gave it: OPENBLAS_NUM_THREADS only if they set it."""
    env = dict(os.environ)
    user = env.pop("MECH_BENCH_USER_BLAS", "unset")
    if user == "unset":
        env.pop("OPENBLAS_NUM_THREADS", None)
    else:
        env["OPENBLAS_NUM_THREADS"] = user
    return env


def run_once(argv: list[str]) -> float:
    """Wall seconds of one run of ``argv``; its CPU time (the child's, by getrusage) goes to :data:`CPU`."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(argv, check=True, capture_output=True, env=user_env())
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    CPU.setdefault(tuple(argv), []).append(cpu)
    return wall


def per_call(fn: Callable[[], object], number: int) -> Callable[[], float]:
    """One sample: seconds per call over ``number`` calls."""
    return lambda: timeit.timeit(fn, number=number) / number


#: One sample of one solve of the four-bar in a venv's own interpreter: seconds per call, printed.
_SOLVE_IN = """
import timeit, mech
from mech.kinematics import solve
from mech.options import SolveOptions
m, o = mech.load({path!r}), SolveOptions()
solve(m, "acceleration", o).links
print(timeit.timeit(lambda: solve(m, "acceleration", o){read}, number=500) / 500)
"""


#: One sample of a command's solving: a fresh mechanism compiled, solved at its drawn angle and read.
_FIRST_SOLVE_IN = """
import time, mech
from mech.kinematics import solve
m = mech.load({path!r})
start = time.process_time()  # CPU: a multi-millisecond span on a loaded machine is often descheduled
solve(m, "velocity").links
print(time.process_time() - start)
"""


def first_solve_in(python: str) -> Callable[[], float]:
    """One sample: a fresh ``python`` loads the four-bar and times its first solve (all a command solves), CPU."""
    code = _FIRST_SOLVE_IN.format(path=str(FOUR_BAR))
    return lambda: float(
        subprocess.run([python, "-c", code], check=True, capture_output=True, text=True).stdout
    )


def solve_in(python: str, read: bool) -> Callable[[], float]:
    """One sample: a fresh ``python`` times 500 solves of the four-bar at its drawn angle (and reads them)."""
    code = _SOLVE_IN.format(path=str(FOUR_BAR), read=".links" if read else "")
    return lambda: float(
        subprocess.run([python, "-c", code], check=True, capture_output=True, text=True).stdout
    )


def fmt(t: float) -> str:
    if t < 1e-3:
        return f"{t * 1e6:.1f} µs"
    if t < 1.0:
        return f"{t * 1e3:.2f} ms"
    return f"{t:.2f} s"


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--repeat", type=int, default=9)
    parser.add_argument("--venv", type=Path, default=Path("/tmp/mech-bench-venv"))
    parser.add_argument("--no-install", action="store_true", help="use the venv as it is")
    parser.add_argument("--before", type=Path, help="a venv with an earlier tree pip-installed, to compare")
    parser.add_argument(
        "--quick",
        action="store_true",
        help="the commands and the one solves only (no Newton chains, no sweeps)",
    )
    parser.add_argument("--links", default="4,40,100,200", help="chain sizes for Newton (first: reference)")
    args = parser.parse_args()
    try:
        import pylinkage
        from bench_peers import pylinkage_models
    except ImportError:
        sys.exit("pylinkage is not installed: pip install -e '.[bench]'")

    env = venv(args.venv, not args.no_install)
    py, cmd = str(env / "bin" / "python"), str(env / "bin" / "mech")

    # -- the cases: name -> one sample -----------------------------------------------------------
    cases: dict[str, Callable[[], float]] = {
        "python -c pass": lambda: run_once([py, "-c", "pass"]),
        'python -c "import numpy"': lambda: run_once([py, "-c", "import numpy"]),
        "mech dof --json four_bar.yaml": lambda: run_once([cmd, "dof", "--json", str(FOUR_BAR)]),
        "mech velocity four_bar.yaml --rpm 600": lambda: run_once(
            [cmd, "velocity", str(FOUR_BAR), "--rpm", "600"]
        ),
    }
    cpu_pairs: list[tuple[tuple[str, ...], tuple[str, ...]]] = []
    if args.before is not None:
        old = str(args.before / "bin" / "mech")
        for tail in (["dof", "--json", str(FOUR_BAR)], ["velocity", str(FOUR_BAR), "--rpm", "600"]):
            cpu_pairs.append((tuple([cmd, *tail]), tuple([old, *tail])))
        cases["before: mech dof --json four_bar.yaml"] = lambda: run_once(
            [old, "dof", "--json", str(FOUR_BAR)]
        )
        cases["before: mech velocity four_bar.yaml --rpm 600"] = lambda: run_once(
            [old, "velocity", str(FOUR_BAR), "--rpm", "600"]
        )
    four = mech.load(FOUR_BAR)
    target = math.radians(60.0 + 37.0)
    moved, drawn = SolveOptions(angle=target), SolveOptions()
    for warm in (moved, drawn):  # compile, build the program and package once, outside the timing
        assert solve(four, "acceleration", warm).links
    prog = closed_form(four)
    model = pylinkage_models()[0][0]
    cases["pylinkage one step (+ v, a)"] = per_call(
        lambda: next(iter(model.step_with_derivatives(iterations=1))), 500
    )
    cases["solve() drawn angle, four-bar"] = per_call(lambda: solve(four, "acceleration", drawn), 500)
    cases["solve() drawn angle, read, four-bar"] = per_call(
        lambda: solve(four, "acceleration", drawn).links, 500
    )
    if args.before is not None:
        py_old = str(args.before / "bin" / "python")
        cases["solve() drawn angle, now (fresh interpreter)"] = solve_in(py, False)
        cases["solve() drawn angle, before (fresh interpreter)"] = solve_in(py_old, False)
        cases["solve() drawn angle, read, now (fresh interpreter)"] = solve_in(py, True)
        cases["solve() drawn angle, read, before (fresh interpreter)"] = solve_in(py_old, True)
        cases["first solve, now (fresh interpreter)"] = first_solve_in(py)
        cases["first solve, before (fresh interpreter)"] = first_solve_in(py_old)
    cases["solve() full, four-bar"] = per_call(lambda: solve(four, "acceleration", moved), 500)
    cases["closed form lean, four-bar"] = per_call(lambda: prog.state(target, -4 * math.pi, 0.0), 5000)

    sizes = [] if args.quick else [int(s) for s in args.links.split(",")]
    newton = SolveOptions(angle=math.radians(65), method="newton")
    for n in sizes:
        m = chain(n)
        solve(m, "acceleration", newton)  # compile (layout, assembly, mobility) outside the timing
        cases[f"Newton, {n} links"] = per_call(lambda m=m: solve(m, "acceleration", newton), max(1, 200 // n))

    phi = np.radians(np.linspace(0.0, 360.0, STEPS + 1))
    sweeps = {
        "four-bar (closed form)": mech.load(FOUR_BAR),
        "double parallelogram": mech.load(ROOT / "mechanisms" / "double_parallelogram.yaml"),
        "gear pair": mech.load(ROOT / "mechanisms" / "gear_pair.yaml"),
        "rolling wheel": mech.load(ROOT / "mechanisms" / "rolling_wheel.yaml"),
        "eccentric cam, roller": mech.load(ROOT / "mechanisms" / "eccentric_cam_roller.yaml"),
    }
    for label, m in ({} if args.quick else sweeps).items():
        sweep(m, phi[:10], level="acceleration", analyse=False)  # compile outside the timing
        cases[f"sweep series, {label}"] = per_call(
            lambda m=m: sweep(m, phi, level="acceleration", analyse=False), 1
        )
        cases[f"sweep whole, {label}"] = per_call(lambda m=m: sweep(m, phi, level="acceleration"), 1)

    # -- one interleaved run -------------------------------------------------------------------
    samples: dict[str, list[float]] = {name: [] for name in cases}
    for r in range(args.repeat):
        for name, sample in cases.items():
            samples[name].append(sample())
        print(f"repeat {r + 1}/{args.repeat} done", file=sys.stderr)
    med = {name: statistics.median(t) for name, t in samples.items()}

    print(
        f"one interleaved run, median of {args.repeat}; Python {platform.python_version()}, "
        f"numpy {np.__version__}, pylinkage {pylinkage.__version__} (no numba), {platform.machine()}, "
        f"{os.cpu_count()} cores shared with other jobs (load average {os.getloadavg()[0]:.1f} at the end)"
    )
    print(f"commands from {env} (pip install ., not editable)")
    print()
    print("| figure | mech | reference | ratio | target |")
    print("| --- | ---: | ---: | ---: | ---: |")

    def row(label: str, name: str, ref: str, target: str, ref_label: str | None = None) -> None:
        print(
            f"| {label} | {fmt(med[name])} | {ref_label or ref} {fmt(med[ref])} | "
            f"{med[name] / med[ref]:.2f}× | {target} |"
        )

    row("`mech dof --json four_bar.yaml`", "mech dof --json four_bar.yaml", "python -c pass", "≤ 4×")
    row(
        "`mech velocity four_bar.yaml --rpm 600`",
        "mech velocity four_bar.yaml --rpm 600",
        'python -c "import numpy"',
        "≤ 1.5×",
    )
    row(
        "one position + v + a, `solve()` at the file's drive angle",
        "solve() drawn angle, four-bar",
        "pylinkage one step (+ v, a)",
        "≤ 1×",
        "pylinkage one step",
    )
    row(
        "the same, its whole result read (every point, link, joint)",
        "solve() drawn angle, read, four-bar",
        "pylinkage one step (+ v, a)",
        "—",
        "pylinkage one step",
    )
    row(
        "one position + v + a, `solve()` at the drawn angle + 37°",
        "solve() full, four-bar",
        "pylinkage one step (+ v, a)",
        "≤ 1×",
        "pylinkage one step",
    )
    row(
        "the same, lean closed form",
        "closed form lean, four-bar",
        "pylinkage one step (+ v, a)",
        "≤ 0.3×",
        "pylinkage one step",
    )
    for n in sizes[1:]:
        row(
            f"Newton solve, {n}-link chain",
            f"Newton, {n} links",
            f"Newton, {sizes[0]} links",
            f"linear: ≤ {n / sizes[0]:.0f}×",
            f"{sizes[0]}-link Newton",
        )
    for kind in () if args.quick else ("series", "whole"):
        for label in ("double parallelogram", "gear pair", "rolling wheel", "eccentric cam, roller"):
            what = "series only" if kind == "series" else "whole sweep (extremes, dead centres)"
            print(
                f"| 3,600-step sweep, {label}, {what} | {fmt(med[f'sweep {kind}, {label}'])} | "
                f"closed-form {fmt(med[f'sweep {kind}, four-bar (closed form)'])} | "
                f"{med[f'sweep {kind}, {label}'] / med[f'sweep {kind}, four-bar (closed form)']:.0f}× | ≤ 0.25 s |"
            )

    if args.before is not None:
        print()
        print(f"the tree now against the one before ({args.before}), in the same interleaved run:")
        print()
        print("| figure | before | now | now / before | paired: median (quartiles) |")
        print("| --- | ---: | ---: | ---: | ---: |")
        for label, now, then in (
            ("`mech dof --json four_bar.yaml`", "mech dof --json four_bar.yaml", None),
            ("`mech velocity four_bar.yaml --rpm 600`", "mech velocity four_bar.yaml --rpm 600", None),
            (
                "`solve()` at the drawn angle (fresh interpreter, 500 calls)",
                "solve() drawn angle, now (fresh interpreter)",
                "solve() drawn angle, before (fresh interpreter)",
            ),
            (
                "the same, its result read",
                "solve() drawn angle, read, now (fresh interpreter)",
                "solve() drawn angle, read, before (fresh interpreter)",
            ),
            (
                "a command's solving: the first solve of a fresh four-bar, read (CPU)",
                "first solve, now (fresh interpreter)",
                "first solve, before (fresh interpreter)",
            ),
        ):
            then = then or f"before: {now}"
            # each repeat ran both, one after the other: the ratio within a repeat cancels slow load swings
            paired = statistics.quantiles(
                [a / b for a, b in zip(samples[now], samples[then], strict=True)], n=4
            )
            print(
                f"| {label} | {fmt(med[then])} | {fmt(med[now])} | {med[now] / med[then]:.3f} | "
                f"{paired[1]:.3f} ({paired[0]:.3f}–{paired[2]:.3f}) |"
            )
        print()
        print("CPU time of the same runs (user + system, getrusage), before → now:")
        print()
        print("| command | before | now | now / before | paired: median (quartiles) |")
        print("| --- | ---: | ---: | ---: | ---: |")
        for argv_now, argv_then in cpu_pairs:
            a, b = CPU[argv_now], CPU[argv_then]
            q = statistics.quantiles([x / y for x, y in zip(a, b, strict=True)], n=4)
            ma, mb = statistics.median(a), statistics.median(b)
            print(
                f"| `mech {' '.join(argv_now[1:2])}` | {fmt(mb)} | {fmt(ma)} | {ma / mb:.3f} | "
                f"{q[1]:.3f} ({q[0]:.3f}–{q[2]:.3f}) |"
            )
        print()


if __name__ == "__main__":
    main()
