"""Shared fixtures: the example library and a way to run the CLI in-process."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

ROOT = Path(__file__).resolve().parent.parent
MECHANISMS = ROOT / "mechanisms"


def example_files() -> list[Path]:
    """Every shipped example mechanism."""
    return sorted(MECHANISMS.glob("*.yaml"))


@pytest.fixture
def run():
    """Run ``mech ARGS`` in-process; returns click's Result (exit_code, stdout, stderr)."""
    from mech.cli import cli

    runner = CliRunner()

    def _run(*args: str, input: str | None = None):
        return runner.invoke(cli, list(args), input=input, catch_exceptions=False, prog_name="mech")

    return _run


@pytest.fixture
def write(tmp_path: Path):
    """Write a YAML text to a file in a temporary folder and return its path."""

    def _write(text: str, name: str = "m.yaml") -> Path:
        path = tmp_path / name
        path.write_text(text, encoding="utf-8")
        return path

    return _write


# -- the suite's cost, test by test (MECH_TEST_CPU=report.tsv python -m pytest) ------------------
# Wall time on a shared machine measures the neighbours; the CPU a test spends (its own process and
# the children it waited for) does not, and it is what the budget of issue 20 item 8 is about:
# the default run at most 90 s of CPU.  Tests above a few seconds of CPU are marked `slow`.
_CPU: list[tuple[float, str]] = []


def _cpu_now() -> float:
    import resource

    own, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


@pytest.hookimpl(wrapper=True)
def pytest_runtest_protocol(item, nextitem):
    import os

    if not os.environ.get("MECH_TEST_CPU"):
        return (yield)
    start = _cpu_now()
    try:
        return (yield)
    finally:
        _CPU.append((_cpu_now() - start, item.nodeid))


def pytest_sessionfinish(session, exitstatus):
    import os

    target = os.environ.get("MECH_TEST_CPU")
    if target and _CPU:
        lines = [f"{cpu:.3f}\t{node}" for cpu, node in sorted(_CPU, reverse=True)]
        Path(target).write_text(f"{sum(c for c, _ in _CPU):.1f}\ttotal\n" + "\n".join(lines) + "\n")


def pytest_collection_finish(session):
    # Everything collection made (the modules, their constants, some 2,600 items) lives to the end of
    # the run; frozen, the garbage collector's full passes stop walking it again and again (in the
    # default run its passes took 5.2 s of CPU, 3.8 s after the freeze).  Garbage is collected
    # first, so none is kept.
    import gc

    gc.collect()
    gc.freeze()


# -- the default run and the slow one --------------------------------------------------------------
# `python -m pytest` leaves out the tests marked slow (pyproject: -m "not slow"); `.ci/run` runs
# them after the README's commands (`python -m pytest -m slow`).  Each entry: a test (or a file),
# and what makes it slow, measured with MECH_TEST_CPU on the development machine.  On a quiet
# machine the default run (1,929 tests) took about 78 s of CPU, the process tree's, and the slow
# set (741, these and the ones marked in their files) about 290 s.
SLOW: dict[str, str] = {
    "tests/test_types.py": "mypy over src/: 21 s of CPU",
    "tests/test_entry.py::test_command_line_answers_as_click_answers": "two processes per command line: 33 s",
    "tests/test_draw.py::test_labels_are_placed_without_measuring_every_segment_of_a_long_path": "15 s",
    "tests/test_check_dask.py": "a dask cluster: 5 s",
    "tests/test_files.py::test_reports_to_a_device_leave_it_a_device": "a process per output device: 3.5 s",
    "tests/test_files.py::test_a_full_standard_output_is_exit_2_not_a_bug": "a process per command: 1.9 s",
    "tests/test_files.py::test_a_report_to_a_full_device_is_exit_2_naming_it": "1.8 s",
    "tests/test_files.py::test_a_full_disk_leaves_the_previous_output_whole": "a process per output: 3.5 s",
    "tests/kinematics/test_sweep_cli.py::test_plot_and_animation_are_written": "matplotlib and a GIF: 3.8 s",
    "tests/kinematics/test_sweep_cli.py::test_a_stroke_past_the_reach_is_swept_to_the_limit_it_cannot_pass": "2.8 s",
    "tests/test_check_batch.py::test_each_way_the_solver_fails_is_one_error_row_among_200_files_with_one_or_two_jobs": (
        "200 files twice: 3.6 s"
    ),
    "tests/test_check_batch.py::test_a_file_past_the_time_limit_is_an_error_row_and_the_others_finish": (
        "waits for a time limit to pass"
    ),
    "tests/test_cli.py::test_no_file_gives_a_traceback_or_an_undocumented_status": "every example, every command: 2 s",
    "tests/test_cli.py::test_a_reader_that_has_closed_the_pipe_gives_141_and_no_message": "a pipeline each: 2.8 s",
    "tests/kinematics/test_dyads.py::test_closed_form_and_newton_agree_on_examples": "every example twice: 4.6 s",
    # hypothesis over every Grashof class, each drawn four-bar swept at 360 and 3,600 steps: 24 s
    "tests/properties/test_cycle.py::test_transmission_angle_extremes_and_strokes_of_every_grashof_class_are_the_closed_forms": (
        "40 four-bars, two cycles each: 24 s"
    ),
    "tests/forces/test_cli_forces.py::test_every_example_answers_in_strict_json_or_refuses_it_as_bad_input": (
        "every example through every force command: 15 s"
    ),
    "tests/forces/test_cli_forces.py::test_no_hostile_file_gives_a_traceback_from_a_force_command": "2 s",
    "tests/forces/test_force_cycle.py::test_gears_are_swept_step_by_step_and_carry_their_tooth_load_all_round": "5.5 s",
    "tests/forces/test_force_cycle.py::test_the_greatest_pin_force_and_its_angle_match_a_newton_euler_scan": (
        "a Newton-Euler scan per pin: 9 s"
    ),
    "tests/test_variants.py::test_the_same_seed_writes_the_same_bytes_and_the_roster_order_changes_no_variant": (
        "classes of 40 written three times: 8 s"
    ),
    "tests/test_variants.py::test_every_variant_keeps_its_keep_and_its_key_is_the_closed_form": "40 variants: 5 s",
    "tests/kinematics/test_sweep.py::test_dwell_ends_found_on_a_newton_walk_are_the_programmes_as_on_the_marched_grid": (
        "2.5 s"
    ),
    "tests/test_variants.py::test_a_class_is_graded_against_its_own_variants_a_copy_is_diagnosed_and_marks_add_up": (
        "a class of 40 graded: 5.5 s"
    ),
    # whole-library scans of every source file's syntax tree
    "tests/test_layers.py::test_no_cache_is_keyed_on_object_ids": "every source parsed: 2.4 s",
    "tests/test_long_functions.py": "every source parsed: 2.2 s",
    "tests/test_json_contract.py::test_check_json_of_every_example_is_strict_and_all_pass": "every example: 1.8 s",
    "tests/test_loader.py::test_a_ten_thousand_joint_chain_is_read_with_every_joint_located": "1.4 s",
    "tests/test_check_sheets.py::test_class_reports_are_identical_with_one_and_two_jobs": "worker processes: 1.4 s",
    "tests/kinematics/test_sweep_cli.py::test_sweep_steps_beyond_the_memory_budget_are_refused": "1.3 s",
    # every example through a whole output, or a process per case (measured 1-5 s of CPU each)
    "tests/test_draw.py::test_every_kinematic_example_draws_well_formed_svg": "every example drawn: 5 s",
    "tests/test_plain.py::test_kinematics_tables_print_as_rich_prints_them": "every example, both consoles: 5 s",
    "tests/test_plain.py::test_counting_tables_print_as_rich_prints_them": "1.2 s",
    "tests/test_json_contract.py::test_every_example_answers_in_strict_json_or_refuses_as_its_file_says": "3 s",
    "tests/kinematics/test_march.py::test_moving_higher_pairs_march_in_stacks_as_the_step_by_step_sweep_solves_them": (
        "every moving higher pair, both ways: 3 s"
    ),
    "tests/test_startup.py::test_kinematics_tables_piped_import_numpy_but_no_rich": "a process per command: 1.9 s",
    "tests/test_check_batch.py::test_a_deeply_nested_file_is_one_error_row_and_the_batch_goes_on": "1.5 s",
    "tests/test_check_batch.py::test_cli_interrupted_exits_130_and_leaves_no_report": "a process and a signal: 1.2 s",
    "tests/properties/test_cycle.py::test_transmission_angle_extremes_of_every_grashof_class_are_at_the_ends_of_bd": (
        "hypothesis: 1.4 s"
    ),
    "tests/cam/test_profile.py::test_oscillating_follower_placed_on_profile_reproduces_the_programme": "1.3 s",
    "tests/kinematics/test_sweep_cli.py::test_two_drive_sweep_says_not_reached_never_cannot_close": "1.2 s",
    "tests/forces/test_cli_forces.py::test_force_sweep_plots_the_turning_moment_diagram": "matplotlib: 1.2 s",
    # the browser: a Chromium launch each, about 1 s of CPU; the default run keeps the four-bar's
    # page (closed form at 100°; at 30° and 250° too in the slow set, marked in test_view.py) and
    # the page's own size
    "tests/test_view.py::test_slider_crank_page_shows_the_closed_form": "Chromium, 3 launches",
    "tests/test_view.py::test_six_bar_page_shows_what_mech_velocity_and_acceleration_give": "Chromium, 3 launches",
    "tests/test_view.py::test_a_fragment_the_page_cannot_read_shows_the_files_own_instant": "Chromium per fragment",
    "tests/test_view.py::test_page_screenshot_is_not_blank": "Chromium",
    "tests/test_view.py::test_page_notices_a_script_error": "Chromium",
    "tests/test_view.py::test_a_slider_drives_page_reads_position_in_the_files_unit": "Chromium",
    "tests/test_view.py::test_a_page_of_two_drives_plays_the_first_and_shows_the_closed_form_at_the_files_instant": (
        "Chromium, 2 s"
    ),
}


def pytest_collection_modifyitems(config, items):
    for item in items:
        # an entry is a file, a test, or a class; the node id's prefixes are tried against it
        parts = item.nodeid.split("[", 1)[0].split("::")
        if any("::".join(parts[:n]) in SLOW for n in range(1, len(parts) + 1)):
            item.add_marker(pytest.mark.slow)
