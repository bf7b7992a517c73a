"""Fixtures shared by the test suite, and its markers.

``workflow`` marks the tests that run Snakemake or interrupt and kill runs (minutes); ``slow`` the
tests of :data:`SLOW_MODULES` and :data:`SLOW_TESTS` (integrations through the plain-Python reference,
whole figure sets, long closed loops: seconds each). The
fast loop ``make test-fast`` (``pytest -m "not workflow and not slow"``) leaves both out;
``make test`` runs everything. A test is marked here, not in its body: ``workflow`` from the names
its code uses (:func:`runs_the_workflow`): a name containing ``snakemake`` (the command, or a helper
that builds its command line) or one of :data:`KILL_NAMES`.
"""

from __future__ import annotations

import copy
import inspect
import subprocess
import sys
from pathlib import Path
from types import CodeType

import pytest

from hubbeam.configuration.load import load_config
from hubbeam.model.models import FAMILIES
from hubbeam.model.parameters import FLEXIBLE_LINK, BeamParameters

REPO_ROOT = Path(__file__).resolve().parents[1]
CONFIG_FILE = REPO_ROOT / "config" / "config.yaml"
#: names of the calls and signals with which tests interrupt and kill processes
KILL_NAMES = {"kill", "killpg", "SIGINT", "SIGTERM", "SIGKILL"}
#: test modules whose every test is slow (but runs no workflow)
SLOW_MODULES = {"test_reference", "test_config_install", "test_validation_pybmodes", "test_quanser_plan"}
#: single tests (``module::function``, every parameter) that take seconds on a 2-core machine even with
#: the kernels compiled: whole figure sets, long nonlinear closed loops, the finite-element and
#: Exudyn references, the scipy reference of the benchmark (``pytest --durations=60`` lists them)
SLOW_TESTS = {
    "test_shaping_study::test_the_shaping_study_validates_and_its_cases_resolve",
    "test_reliability::test_every_job_of_all_puts_each_output_in_place_by_rename",
    "test_reliability::test_a_case_gives_identical_results_in_one_process_and_in_two",
    "test_reliability::test_the_map_gathered_by_the_jobs_is_the_map_of_the_configuration_s_sweep",
    "test_feedback::test_the_lqr_cost_is_the_cost_along_the_nonlinear_run",
    "test_feedback::test_small_motions_about_the_steady_spin_follow_the_linear_closed_loop",
    "test_feedback::test_decay_rate_and_frequency_of_the_nonlinear_loop_are_its_linear_pole",
    "test_sweep::test_both_figure_kinds_are_drawn",
    "test_figures::test_rerendering_gives_identical_files_without_volatile_metadata",
    "test_figures::test_eigen_figure_script_passes_named_inputs",
    "test_figures::test_every_simulation_figure_renders_pdf_and_png",
    "test_figures::test_figure_script_writes_pdf_and_png",
    "test_report::test_report_scripts_write_claims_markdown_and_html",
    "test_simulate::test_runs_free_every_allocation_of_the_numba_runtime",
    "test_benchmark::test_command_line_writes_the_tables",
    "test_benchmark::test_reference_is_converged",
    "test_nonuniform::test_ritz_converges_to_fe_in_modes",
    "test_tip_body::test_foam_linearisation_at_speed_converges_to_the_finite_elements",
    "test_validation_exudyn::test_slow_spin_up_tip_deflection_agrees_with_foam",
    "test_rig_control::test_the_covariances_are_those_of_the_estimation_errors",
    "test_sampled::test_noise_moves_the_estimate_off_the_state_and_is_the_seed_s",
    "test_maneuvers::test_pd_hub_with_a_stiff_beam_follows_the_rigid_closed_loop",
    "test_config_mutations::test_every_mutation_of_every_key_of_the_largest_configurations",
    "test_identification_fit::test_the_fits_dataset_round_trips_and_every_figure_draws_from_it",
    "test_identification_fit::test_the_95_percent_intervals_cover_the_truth_over_50_seeds",
}


def _names(code: CodeType) -> set[str]:
    """Global, attribute and local names used by ``code`` and the functions defined in it."""
    names = set(code.co_names) | set(code.co_varnames)
    for const in code.co_consts:
        if isinstance(const, CodeType):
            names |= _names(const)
    return names


def _runs_the_workflow(function) -> bool:
    names = _names(inspect.unwrap(function).__code__)
    return bool(names & KILL_NAMES) or any("snakemake" in name for name in names)


def runs_the_workflow(item: pytest.Item) -> bool:
    """Whether the test ``item``, or a fixture it uses, runs Snakemake or kills a process (see
    the module docstring)."""
    function = getattr(item, "function", None)
    if function is None:
        return False
    fixtures = getattr(item, "_fixtureinfo", None)
    definitions = fixtures.name2fixturedefs.values() if fixtures is not None else ()
    return _runs_the_workflow(function) or any(
        _runs_the_workflow(definition.func) for defs in definitions for definition in defs
        if definition.baseid.startswith("tests"))


def pytest_configure(config: pytest.Config) -> None:
    """On several workers (``pytest -n``) with the workflow tests selected, compile the simulation
    kernels once, a process per model family, before the workers start: each worker would otherwise
    compile the same kernels at once into numba's cache (minutes of CPU each after a source edit).
    Loading them from a warm cache takes seconds; the fast loop (``not workflow``) skips this."""
    workers = getattr(config.option, "numprocesses", None)
    if not workers or hasattr(config, "workerinput") or "not workflow" in (config.option.markexpr or ""):
        return
    compiling = [subprocess.Popen([sys.executable, "-c", "from hubbeam.simulation.simulate import compile_kernels; "
                                   f"compile_kernels({family!r}); compile_kernels({family!r}, sampled=True)"])
                 for family in FAMILIES]
    failed = [family for family, process in zip(FAMILIES, compiling) if process.wait() != 0]
    if failed:
        raise pytest.UsageError(f"compiling the simulation kernels of {', '.join(failed)} failed (see above)")


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    for item in items:
        if runs_the_workflow(item):
            item.add_marker(pytest.mark.workflow)
        module = item.module.__name__.rpartition(".")[2]
        if module in SLOW_MODULES or f"{module}::{getattr(item, 'originalname', item.name)}" in SLOW_TESTS:
            item.add_marker(pytest.mark.slow)


@pytest.fixture(scope="session")
def repo_root() -> Path:
    """The repository checkout (where the Snakefile and config/ live)."""
    return REPO_ROOT


@pytest.fixture(scope="session")
def _study_config() -> dict:
    return load_config(CONFIG_FILE)


@pytest.fixture
def study_config(_study_config) -> dict:
    """The validated config/config.yaml, as a private copy each test may modify."""
    return copy.deepcopy(_study_config)


@pytest.fixture(scope="session")
def flexible_link() -> BeamParameters:
    """The flexible link of a servo rig (``hubbeam.model.parameters.FLEXIBLE_LINK``), which the
    rig's tests turn with the SRV02's drive."""
    return FLEXIBLE_LINK
