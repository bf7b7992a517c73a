"""Reliability: bad input, interrupted runs, diverged runs, determinism, guard rails.

What other test files already prove is not repeated here:

* every kind of bad config value, missing key, unknown key, illegal or duplicate case name, one at
  a time through ``check_schema`` (tests/test_config.py), and one Snakefile run with two of
  them (``test_snakefile_stops_on_a_bad_config_before_any_rule``); here: every listed kind
  together through the Snakefile with ``--configfile`` (incl. ``numerics.convergence_check``);
* ``write_netcdf`` failing by an exception or a refused rename, and ``open_result`` on damaged
  files (tests/test_io.py); here: writers killed by SIGKILL, a real Snakemake run killed twice
  and resumed, and every job of `all` writing its outputs by rename (the jobs of a small
  configuration's plan, hubbeam.pipeline.plan, each run through its rule's script);
* a truncated file given to ``figure_simulation.py`` (tests/test_figures.py); here: every job of
  those that reads result files;
* TLAM at 3.5 rad/s recorded as diverged by ``simulate`` and a synthetic diverged run drawn as
  such (tests/test_simulate.py, tests/test_figures.py); here: the real run through the workflow,
  which goes on to draw Fig. 5 and mark the divergence;
* the ``numerics.step_warning`` and ``max_steps`` warnings (tests/test_simulate.py); here: the
  convergence check, determinism and the rebuild of a run from its attributes.
"""

from __future__ import annotations

import json
import math
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import matplotlib.text
import numpy as np
import pytest
import xarray as xr
import yaml
from synthetic_results import CONFIG_FILE, REPO, case_of, run_script, simulation_params, small_study

from hubbeam.configuration.load import ConfigError
from hubbeam.model.matrices import assemble, to_dataset
from hubbeam.model.parameters import BeamParameters
from hubbeam.pipeline.plan import build_plan
from hubbeam.pipeline.steps import file_paths
from hubbeam.plotting.style import styled
from hubbeam.reporting.products import PAPER_PRODUCTS
from hubbeam.results.io import ResultFileError, open_result, staged, write_netcdf
from hubbeam.results.reader import DatasetError, simulation_inputs
from hubbeam.simulation.simulate import compile_kernels, simulate
from hubbeam.simulation.sweep import run_sweep

SNAKEFILE = REPO / "Snakefile"


@pytest.fixture(scope="module", autouse=True)
def compiled_kernel():
    """Compile the kernel into numba's disk cache first, so that subprocesses only load it."""
    compile_kernels()


@pytest.fixture(scope="module")
def setup(_study_config):
    return BeamParameters.from_config(_study_config), _study_config["numerics"], _study_config


def snakemake_command(workdir: Path, *args: str) -> list[str]:
    return [sys.executable, "-m", "snakemake", "--snakefile", str(SNAKEFILE), "--directory",
            str(workdir), "--cores", "1", *args]


def temporaries(directory: Path) -> list[Path]:
    """Hidden temporaries of the atomic writers (``.<name>.<random>.tmp``) under ``directory``."""
    return sorted(p for p in directory.rglob(".*.tmp")) if directory.exists() else []


def result_files(directory: Path) -> list[Path]:
    """The netCDF files under their real names (not inside a hidden staging directory)."""
    return sorted(p for p in directory.rglob("*.nc")
                  if not any(part.startswith(".") for part in p.relative_to(directory).parts))


# ---------------------------------------------------------------------------------------------
# bad configuration through the Snakefile: every listed kind, one message, no traceback

BAD_SECTIONS = (
    "beam:\n  length: -8.0\n  density: -2.7e+3\n  youngs_modulus: 0.0\n"
    "numerics:\n  modes: 21\n  output_step: 0.0\n  rtol: fast\n"
    "  convergence_check: {tolerance_factor: 1.5, extra_modes: 0, threshold_m: 1.0e-4, tighten: 2}\n",
    [("beam.length", "got -8.0; allowed: a number > 0"),
     ("beam.density", "got -2700.0; allowed: a number > 0"),
     ("beam.youngs_modulus", "got 0.0; allowed: a number > 0"),
     ("numerics.modes", "got 21; allowed: an integer >= 1 and <= 20"),
     ("numerics.output_step", "got 0.0; allowed: a number > 0"),
     ("numerics.rtol", "got 'fast' (text)"),
     ("numerics.rtol", "allowed: a number >= 2.220446049250313e-14 and < 1"),
     ("numerics.convergence_check.tolerance_factor", "got 1.5; allowed: a number > 0 and < 1"),
     ("numerics.convergence_check.extra_modes", "got 0; allowed: an integer >= 1"),
     ("numerics.convergence_check.tighten", "unknown key (value 2); allowed keys here: "
                                            "tolerance_factor, extra_modes, threshold_m")],
)
VALID_CASE = "{model: FOAM, maneuver: {kind: prescribed, wf: 1.0, tf: 5.0}, t_end: 9.0}"
BAD_CASES = (
    "cases:\n"
    "  fig04_foam: {model: FEM}\n"
    "  fig04_cfoam: {maneuver: {kind: ramp}}\n"
    "  fig05_foam_wf2p8: {t_end: long}\n"
    "  fig05_foam_wf3p5: {t_end: 0.005}\n"
    "  fig05_tlam_wf2p8: {t_end: -1.0}\n"
    "  fig05_tlam_wf3p5: {t_end: 1e12}\n"
    "  fig06_foam_n1: {modes: 0}\n"
    "  fig06_foam_n3: {modes: 25}\n"
    "  fig10_foam_mt0p1: {tip_mass: {position: 9.0}}\n"
    "  fig10_tlam_mt0p1: {tip_mass: {position: -1.0}}\n"
    "  fig10_foam_mt0p5: {tip_mass: {mass: -0.5}}\n"
    "  tab3_foam_tau50: {maneuver: {tf: 0.0}}\n"
    "  tab3_foam_tau100: {maneuver: {tf: -10.0}}\n"
    "  no_wf: {model: FOAM, maneuver: {kind: prescribed, tf: 5.0}, t_end: 9.0}\n"
    "  no_time: {model: FOAM, maneuver: {kind: prescribed, wf: 1.0, tf: 5.0}}\n"
    f"  bad name: {VALID_CASE}\n"
    f"  FIG04_foam: {VALID_CASE}\n"
    f"  twice: {VALID_CASE}\n"
    f"  twice: {VALID_CASE}\n",
    [("cases.fig04_foam.model", "got 'FEM'; allowed: one of TLAM, FOAM, SFOAM, CFOAM"),
     ("cases.fig04_cfoam.maneuver.kind", "got 'ramp'; allowed: one of prescribed, torque"),
     ("cases.fig05_foam_wf2p8.t_end", "got 'long' (text); allowed: a number > 0"),
     ("cases.fig05_foam_wf3p5.t_end", "got 0.005; allowed: at least one output step, "
                                      "t_end >= numerics.output_step = 0.01"),
     ("cases.fig05_tlam_wf2p8.t_end", "got -1.0; allowed: a number > 0"),
     # 25 values per output time: the 23 of a FOAM run with 5 modes and the tip body's centre (2);
     # (1e14 + 1) x 25 x 8 bytes = 17.76 PiB
     ("cases.fig05_tlam_wf3p5.t_end", "got 1e+12 s: case fig05_tlam_wf3p5 (TLAM, 5 modes) would store "
                                      "100000000000001 output times x 25 values x 8 bytes = 17.76 PiB, above "
                                      "the memory budget numerics.memory_budget_mb = 2048 MiB"),
     ("cases.fig06_foam_n1.modes", "got 0; allowed: an integer >= 1 and <= 20"),
     ("cases.fig06_foam_n3.modes", "got 25; allowed: an integer >= 1 and <= 20"),
     ("cases.fig10_foam_mt0p1.tip_mass.position", "got 9.0; allowed: 0 <= position <= beam.length = 8.0"),
     ("cases.fig10_tlam_mt0p1.tip_mass.position", "got -1.0; allowed: a number >= 0"),
     ("cases.fig10_foam_mt0p5.tip_mass.mass", "got -0.5; allowed: a number >= 0"),
     ("cases.tab3_foam_tau50.maneuver.tf", "got 0.0; allowed: a number > 0"),
     ("cases.tab3_foam_tau100.maneuver.tf", "got -10.0; allowed: a number > 0"),
     ("cases.no_wf.maneuver.wf", "missing (required when kind is 'prescribed'); allowed: a number > 0"),
     ("cases.no_time.t_end", "missing (required); allowed: a number > 0"),
     ("cases.bad name", "illegal case name 'bad name'; allowed: letters, digits, '_' and '-'"),
     ("cases.FIG04_foam", "'FIG04_foam' differs from 'fig04_foam' only in letter case; allowed: "
                          "names distinct ignoring case"),
     ("cases.twice", "repeated key in {bad} (lines 19 and 20); allowed: each key once per mapping")],
)


@pytest.mark.parametrize("text, expected", [BAD_SECTIONS, BAD_CASES], ids=["beam-numerics", "cases"])
def test_every_kind_of_config_error_stops_the_snakefile_with_one_message(tmp_path, text, expected):
    bad = tmp_path / "bad.yaml"
    bad.write_text(text)
    workdir = tmp_path / "work"
    workdir.mkdir()
    run = subprocess.run(snakemake_command(workdir, "--configfile", str(CONFIG_FILE), str(bad)),
                         cwd=REPO, capture_output=True, text=True, timeout=300)
    output = run.stdout + run.stderr
    assert run.returncode != 0
    assert "Traceback" not in output and 'File "' not in output, output
    assert output.count("invalid hubbeam configuration") == 1
    problems = [line.removeprefix("  - ") for line in output.splitlines() if line.startswith("  - ")]
    assert f"{len(problems)} problems:" in output
    for key, fragment in expected:
        fragment = fragment.format(bad=bad)
        assert any(p.startswith(f"{key}: ") and fragment in p for p in problems), (key, fragment, problems)
    # rejected before any computation: no job ran, nothing was written
    assert sorted(os.listdir(workdir)) in ([], [".snakemake"])
    assert not (workdir / ".snakemake" / "incomplete").exists() or not os.listdir(workdir / ".snakemake" / "incomplete")


def test_bad_convergence_settings_are_rejected_by_simulate(setup):
    params, numerics, config = setup
    case = case_of(config, "fig05_foam_wf2p8")
    for settings, message in [
        ({"tolerance_factor": 0.0, "extra_modes": 2, "threshold_m": 1e-4},
         "tolerance_factor: got 0.0; allowed: a number > 0 and < 1"),
        ({"tolerance_factor": 0.1, "extra_modes": 2.0, "threshold_m": 1e-4},
         r"extra_modes: got 2.0 \(decimal number\); allowed: an integer >= 1"),
        ({"tolerance_factor": 0.1, "extra_modes": 2, "threshold_m": -1.0},
         "threshold_m: got -1.0; allowed: a number > 0"),
        ({"tolerance_factor": 0.1, "extra_modes": 2, "threshold_m": 1e-4, "x": 1}, r"convergence_check.x: unknown key"),
    ]:
        with pytest.raises(ConfigError, match=message):
            simulate(case, params, numerics, convergence_check=settings)


# ---------------------------------------------------------------------------------------------
# atomic writes: killed writers, every rule script, a killed and resumed workflow

WRITER = textwrap.dedent("""
    import sys
    import numpy as np, xarray as xr
    from hubbeam.results.io import staged, write_netcdf

    directory = sys.argv[1]
    versions = [xr.Dataset({"x": ("i", np.full(200_000, float(k)))}, attrs={"version": k})
                for k in (1, 2)]
    k = 0
    while True:
        write_netcdf(versions[k % 2], f"{directory}/result.nc")
        with staged(f"{directory}/table.csv", f"{directory}/table.md") as (csv, md):
            csv.write_text(f"version\\n{k % 2 + 1}\\n" * 20_000)
            md.write_text(f"| version |\\n| {k % 2 + 1} |\\n" * 20_000)
        k += 1
""")


def test_a_killed_writer_leaves_the_old_file_or_none_and_the_next_write_cleans_up(tmp_path):
    """SIGKILL a process that rewrites a netCDF file and a staged pair of text files in a loop,
    at the moment a temporary exists: every file under its own name is complete, and the next
    write of the same file removes what the killed one left."""
    for _attempt in range(5):  # a kill can land just after a rename: try again
        writer = subprocess.Popen([sys.executable, "-c", WRITER, str(tmp_path)], start_new_session=True)
        try:
            deadline = time.monotonic() + 120
            while not temporaries(tmp_path) or not (tmp_path / "result.nc").exists():
                assert writer.poll() is None and time.monotonic() < deadline, "the writer stopped"
                time.sleep(0.001)
        finally:
            os.killpg(writer.pid, signal.SIGKILL)
            writer.wait(timeout=60)
        left = temporaries(tmp_path)
        if left:
            break
    assert left, "never killed while writing"
    assert all(p.name.startswith(".") for p in left)
    result = open_result(tmp_path / "result.nc")
    assert result.attrs["version"] in (1, 2)
    np.testing.assert_array_equal(result["x"].values, float(result.attrs["version"]))
    for name, lines in (("table.csv", ["version", "{v}"]), ("table.md", ["| version |", "| {v} |"])):
        path = tmp_path / name
        if path.exists():  # absent only if the kill came before its first rename
            text = path.read_text()
            version = 1 if "1" in text else 2
            assert text == "\n".join(line.format(v=version) for line in lines * 20_000) + "\n"
    write_netcdf(result, tmp_path / "result.nc")
    with staged(tmp_path / "table.csv", tmp_path / "table.md") as (csv, md):
        csv.write_text("new\n")
        md.write_text("new\n")
    assert temporaries(tmp_path) == []
    assert sorted(p.name for p in tmp_path.iterdir()) == ["result.nc", "table.csv", "table.md"]


def test_staged_writes_nothing_when_the_writer_fails_or_forgets_a_file(tmp_path):
    (tmp_path / "a.csv").write_text("old\n")
    with pytest.raises(RuntimeError), staged(tmp_path / "a.csv", tmp_path / "a.md") as (csv, md):
        csv.write_text("new\n")
        md.write_text("new\n")
        raise RuntimeError("the figure could not be drawn")
    with pytest.raises(FileNotFoundError, match=f"did not produce {tmp_path / 'a.md'}"):
        with staged(tmp_path / "a.csv", tmp_path / "a.md") as (csv, _md):
            csv.write_text("new\n")
    assert sorted(os.listdir(tmp_path)) == ["a.csv"] and (tmp_path / "a.csv").read_text() == "old\n"


@pytest.fixture(scope="module")
def small_run(tmp_path_factory):
    """Every job of `all` of the small study (tests/synthetic_results.py: the paper's products and
    a study's in one configuration, seconds of computing) run without Snakemake: taken from the
    configuration's plan (hubbeam.pipeline.plan) in the order of its jobs, each through its rule's
    script with the plan's files and params. A figure (outputs ``pdf`` and ``png``) is drawn by
    the first job of each script; the others, the same code on other runs at about 2 s each (every
    figure is drawn in tests/test_figures.py), get stand-in files, which the reports embed and the
    archive bundles as bytes. Returns the working directory, the plan and, per job, the files
    renamed into place while it ran (None for a stand-in)."""
    root = tmp_path_factory.mktemp("small")
    renamed: list[Path] = []
    real = os.replace

    def record(source, destination, *args, **kwargs):
        real(source, destination, *args, **kwargs)
        renamed.append(Path(destination).resolve())

    with pytest.MonkeyPatch.context() as patch:
        patch.chdir(root)  # the study's folder and the archive's members are relative to it
        config_file = root / "small.yaml"
        config_file.write_text(yaml.safe_dump(small_study(), sort_keys=False))
        plan = build_plan(yaml.safe_load(config_file.read_text()), [config_file], REPO)
        patch.setattr(os, "replace", record)
        runs, drawn = [], set()
        for planned in plan.jobs():
            job, function = planned.job, planned.job.params["job"]
            if set(job.output) == {"pdf", "png"} and function in drawn:
                for path in file_paths(job.output):
                    Path(path).parent.mkdir(parents=True, exist_ok=True)
                    Path(path).write_bytes(b"stand-in figure")
                runs.append((planned, None))
                continue
            drawn.add(function)
            before = len(renamed)
            run_script(function, input=dict(job.input), output=dict(job.output), params=dict(job.params),
                       log=job.log)
            runs.append((planned, set(renamed[before:])))
    return root, plan, runs


def test_every_job_of_all_puts_each_output_in_place_by_rename(small_run):
    """Each output of every job of `snakemake all` (netCDF, csv, md, tex, pdf, png, html, MATLAB,
    the archive, the kernels' markers) appears by an atomic rename, never by writing under its own
    name; and the jobs in the plan's order, from nothing, build every target."""
    root, plan, runs = small_run
    for planned, renamed in runs:
        if renamed is not None:
            expected = {(root / path).resolve() for path in file_paths(planned.job.output)}
            assert expected <= renamed, (planned.rule, sorted(map(str, expected - renamed)))
    assert all((root / target).is_file() for target in plan.targets)
    assert temporaries(root) == []
    ran = {planned.job.params["job"] for planned, renamed in runs if renamed is not None}
    validation = {"validate_exudyn", "validate_models", "validate_case", "validate_comparison", "validate_modes",
                  "validate_convergence", "validate_nonuniform", "validation_report"}  # `snakemake validate` only
    control = {"control_sample_time", "control_robustness", "control_export"}  # a `control` section only
    assert ran == {step.params["job"] for rule, step in plan.steps.items() if rule not in validation | control}


def test_the_map_gathered_by_the_jobs_is_the_map_of_the_configuration_s_sweep(small_run):
    """The sweep's chunk and gather jobs, given the plan's params, write exactly the map that
    run_sweep gives for the configuration's Sweep in one go."""
    root, plan, _ = small_run
    (name, sweep), = plan.settings.sweeps.items()
    gathered = open_result(root / plan.paths.sweep(name))
    whole = run_sweep(sweep, plan.settings.beam)
    xr.testing.assert_identical(gathered.drop_attrs(deep=False), whole.drop_attrs(deep=False))
    assert json.loads(gathered.attrs["sweep_config"]) == sweep.to_dict()


# ---------------------------------------------------------------------------------------------
# damaged inputs: every job that reads result files names the file

#: jobs that take result files without reading them as results: the archive bundles their bytes
BUNDLING = {"hubbeam.pipeline.jobs.reports:archive"}


def relocated(files, place) -> dict:
    """A job's named files with each path replaced by ``place(path)``."""
    return {name: place(value) if isinstance(value, str) else [place(path) for path in value]
            for name, value in files.items()}


def truncate(source: Path, target: Path) -> Path:
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_bytes(source.read_bytes()[:1500])
    return target


def test_a_truncated_input_is_named_by_every_job_reading_it(small_run, tmp_path):
    """For every script of `all` that reads a netCDF result (its first job of the small study's):
    its first such input truncated, it fails naming that file and writes no output."""
    root, plan, runs = small_run
    checked = set()
    for planned, _ in runs:
        job = planned.job
        script = job.params["job"]
        results = [path for path in file_paths(job.input) if path.endswith(".nc")]
        if script in checked or script in BUNDLING or not results:
            continue
        checked.add(script)
        folder = tmp_path / script.replace(":", "_")
        bad = truncate(root / results[0], folder / "in" / Path(results[0]).name)
        out = folder / "out"
        inputs = relocated(job.input, lambda path: str(bad) if path == results[0] else str(root / path))  # noqa: B023
        outputs = relocated(job.output, lambda path: str(out / Path(path).name))  # noqa: B023
        with pytest.raises(ResultFileError, match=f"result file {bad} cannot be read, it is corrupted or truncated"):
            run_script(script, input=inputs, output=outputs, params=dict(job.params),
                       log=str(folder / "log"))
        assert not out.exists() or not list(out.iterdir()), script
    jobs = "hubbeam.pipeline.jobs."
    assert checked >= {jobs + name for name in (
        "simulation:simulate", "tables:table3", "figures:simulation_figure", "figures:files_figure",
        "figures:study_figure", "claims:claims", "reports:reproduction_report", "reports:study_report",
        "claims:reading", "sweeps:sweep", "figures:figure_sweep", "linear:linear_mode_shapes")}


# ---------------------------------------------------------------------------------------------
# a real workflow run killed twice (SIGTERM, then SIGKILL) and resumed


def tiny_config() -> dict:
    """config/config.yaml with every case shortened to 6 s with a 4 s maneuver, at most 2 modes,
    coarse output; TLAM at 3.5 rad/s still diverges (during the spin-up)."""
    config = yaml.safe_load(CONFIG_FILE.read_text())
    config["numerics"] |= {"quadrature_points": 16, "rtol": 1e-6, "atol": 1e-8, "output_step": 0.05}
    for case in config["cases"].values():
        case["t_end"] = 6.0
        case["maneuver"]["tf"] = 4.0
        case["modes"] = min(case.get("modes", 2), 2)
    return config


TARGETS = ["results/figures/fig05.pdf", "results/figures/fig05.png",
           *(f"results/simulations/{case}.nc" for case in ("fig10_tlam_mt0p5", "fig10_foam_mt0p5"))]


def start(workdir: Path, *args: str) -> subprocess.Popen:
    """Snakemake in its own process group (a kill of the group reaches the running jobs too)."""
    return subprocess.Popen(snakemake_command(workdir, *args, *TARGETS), cwd=REPO, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True)


def wait_until(found, process: subprocess.Popen, what: str, timeout: float = 400.0):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        result = found()
        if result:
            return result
        if process.poll() is not None:
            pytest.fail(f"snakemake ended before {what}:\n{process.stdout.read()[-3000:]}")
        time.sleep(0.002)
    os.killpg(process.pid, signal.SIGKILL)
    pytest.fail(f"no {what} within {timeout} s")


def assert_results_are_complete_or_absent(results: Path) -> None:
    for path in result_files(results):
        open_result(path)  # raises ResultFileError naming a partial file


def test_a_killed_workflow_leaves_no_partial_result_and_resumes(tmp_path):
    workdir = tmp_path / "work"
    (workdir / "config").mkdir(parents=True)
    (workdir / "config" / "config.yaml").write_text(yaml.safe_dump(tiny_config()))
    results = workdir / "results"
    simulations = results / "simulations"

    def new_results(before):
        return lambda: set(simulations.glob("*.nc")) - before if simulations.exists() else set()

    # 1. SIGTERM as the first simulation appears: Snakemake lets the running job finish, stops
    run = start(workdir)
    wait_until(new_results(set()), run, "a simulation result")
    run.send_signal(signal.SIGTERM)
    output, _ = run.communicate(timeout=300)
    assert "Will exit after finishing currently running jobs" in output
    built = set(simulations.glob("*.nc"))
    assert built and len(built) < 6, sorted(p.name for p in built)
    assert temporaries(results) == []
    assert_results_are_complete_or_absent(results)

    # 2. a plain rerun picks up; SIGKILL it (with its jobs) while a result is being written
    run = start(workdir)
    wait_until(lambda: temporaries(simulations) or new_results(built)(), run, "a simulation being written")
    os.killpg(run.pid, signal.SIGKILL)
    output, _ = run.communicate(timeout=300)
    assert "localrule simulate" in output  # it had resumed work before the kill
    assert_results_are_complete_or_absent(results)
    assert all(p.name.startswith(".") for p in temporaries(results))
    locked = subprocess.run(snakemake_command(workdir, *TARGETS), cwd=REPO, capture_output=True, text=True,
                            timeout=300)
    assert locked.returncode != 0 and "--unlock" in locked.stdout + locked.stderr  # what README says

    # 3. what README tells the user: unlock, rerun the incomplete jobs
    unlock = subprocess.run(snakemake_command(workdir, "--unlock", *TARGETS), cwd=REPO, capture_output=True,
                            text=True, timeout=300)
    assert unlock.returncode == 0, unlock.stderr[-3000:]
    resumed = subprocess.run(snakemake_command(workdir, "--rerun-incomplete", *TARGETS), cwd=REPO,
                             capture_output=True, text=True, timeout=600)
    assert resumed.returncode == 0, (resumed.stdout + resumed.stderr)[-4000:]
    assert all((workdir / target).is_file() for target in TARGETS)
    assert temporaries(results) == [] and temporaries(workdir / "logs") == []
    datasets = {path.stem: open_result(path) for path in result_files(simulations)}
    assert len(datasets) == 6

    # the diverged run finished as a result, with the convergence check the rule passes on
    tlam = datasets["fig05_tlam_wf3p5"]
    assert tlam.attrs["diverged"] == 1 and 0.0 < tlam.attrs["diverged_at_s"] < 6.0
    assert "diverged at t" in tlam.attrs["warnings"] and tlam.attrs["validity"] == "diverged"
    assert datasets["fig05_foam_wf3p5"].attrs["diverged"] == 0
    checked = tiny_config()["numerics"]["convergence_check"]
    for ds in datasets.values():
        assert json.loads(ds.attrs["convergence_check"]) == checked
        assert math.isfinite(ds.attrs["convergence_modes_diff_m"])
    # ... and Fig. 5 (built from it by the workflow above) draws it up to the divergence, marked
    with styled():
        fig05_runs = {case: ds for case, ds in datasets.items() if case.startswith("fig05_")}
        fig = PAPER_PRODUCTS["fig05"].resolve()(fig05_runs)
    texts = [text.get_text() for text in fig.findobj(matplotlib.text.Text)]
    assert f"TLAM diverged at t = {tlam.attrs['diverged_at_s']:.2f} s" in texts


# ---------------------------------------------------------------------------------------------
# determinism and provenance

DETERMINISM_CASE = {"name": "determinism", "model": "CFOAM", "modes": 2, "t_end": 3.0,
                    "maneuver": {"kind": "torque", "tau_max": 200.0, "tf": 2.0},
                    "tip_mass": {"mass": 0.1, "position": 6.0}}
SIMULATE_IN_A_PROCESS = textwrap.dedent("""
    import json, sys
    from hubbeam.results.io import write_netcdf
    from hubbeam.model.parameters import BeamParameters
    from hubbeam.simulation.simulate import simulate

    case, beam, numerics, path = json.loads(sys.argv[1]), json.loads(sys.argv[2]), json.loads(sys.argv[3]), sys.argv[4]
    ds = simulate(case, BeamParameters.from_config({"beam": beam}), numerics,
                  convergence_check=numerics["convergence_check"])
    write_netcdf(ds, path)
""")


def test_a_case_gives_identical_results_in_one_process_and_in_two(setup, tmp_path, monkeypatch):
    params, numerics, config = setup
    epoch = "1237766400"
    monkeypatch.setenv("SOURCE_DATE_EPOCH", epoch)  # the one volatile attribute: history's time
    first = simulate(DETERMINISM_CASE, params, numerics, convergence_check=numerics["convergence_check"])
    second = simulate(DETERMINISM_CASE, params, numerics, convergence_check=numerics["convergence_check"])
    xr.testing.assert_identical(first, second)

    environment = dict(os.environ, SOURCE_DATE_EPOCH=epoch)
    arguments = [json.dumps(DETERMINISM_CASE), json.dumps(config["beam"]), json.dumps(numerics)]
    processes = [subprocess.Popen([sys.executable, "-c", SIMULATE_IN_A_PROCESS, *arguments,
                                   str(tmp_path / f"run{k}.nc")], env=environment) for k in (1, 2)]
    assert [process.wait(timeout=600) for process in processes] == [0, 0]
    one, two = (open_result(tmp_path / f"run{k}.nc") for k in (1, 2))
    xr.testing.assert_identical(one, two)
    xr.testing.assert_identical(one.drop_attrs(deep=False), first.drop_attrs(deep=False))
    assert one.attrs["warnings"] == first.attrs["warnings"]
    assert one.attrs["convergence_modes_diff_m"] == first.attrs["convergence_modes_diff_m"]


def test_the_attributes_of_a_dataset_alone_rebuild_and_reproduce_it(setup, tmp_path, monkeypatch):
    """From a file written by the simulation rule's script (matrices: the leading blocks of a
    file with more modes, as in the workflow) and from one of the Python API."""
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1237766400")
    params, numerics, config = setup
    case = case_of(config, "fig10_tlam_mt0p1", modes=2, t_end=4.0)
    tip = case.tip_mass
    matrices = write_netcdf(to_dataset(assemble(params, tip, 4, numerics["quadrature_points"]), params, tip),
                            tmp_path / "matrices.nc")
    written = tmp_path / "simulations" / "case.nc"
    run_script("hubbeam.pipeline.jobs.simulation:simulate", input={"matrices": str(matrices)},
               output={"nc": str(written)}, params=simulation_params(config, case, convergence_check=True),
               log=str(tmp_path / "case.log"))
    from_rule = open_result(written)
    inputs = simulation_inputs(from_rule.attrs)
    assert inputs["case"] == case.to_dict() and inputs["params"] == params
    assert inputs["convergence_check"] == numerics["convergence_check"]
    for key in ("rtol", "atol", "output_step", "max_steps", "step_warning", "divergence_limit"):
        assert inputs["numerics"][key] == numerics[key]
    rebuilt = simulate(**inputs)
    # the provenance to compare with before rerunning is recorded: versions and commit
    for key in ("hubbeam_version", "git_commit", "numpy_version", "numba_version", "scipy_version"):
        assert rebuilt.attrs[key] == from_rule.attrs[key]
    # Assembled for 2 modes instead of cut from 4, the matrices differ by round-off (the same Gauss
    # nodes: attribute quadrature_points); the run then agrees to well within the integrator's rtol.
    for name, variable in from_rule.data_vars.items():
        scale = float(np.nanmax(np.abs(variable.values))) or 1.0
        np.testing.assert_allclose(rebuilt[name].values, variable.values, rtol=0,
                                   atol=numerics["rtol"] * scale, err_msg=name)
    # from the Python API (matrices assembled by simulate itself) the rebuild is exact
    direct = open_result(write_netcdf(simulate(case, params, numerics), tmp_path / "direct.nc"))
    xr.testing.assert_identical(simulate(**simulation_inputs(direct.attrs)), direct)


def test_a_dataset_without_the_rerun_attributes_is_named(setup):
    params, numerics, config = setup
    ds = simulate(case_of(config, "fig05_foam_wf2p8", t_end=0.1), params, numerics)
    del ds.attrs["quadrature_points"]
    with pytest.raises(DatasetError, match="dataset attribute 'quadrature_points' is missing"):
        simulation_inputs(ds.attrs)


# ---------------------------------------------------------------------------------------------
# the convergence check


def tip_difference(a: xr.Dataset, b: xr.Dataset) -> float:
    """Largest |tip deflection difference| over the times where both runs have values."""
    difference = np.abs(a["tip_transverse"].values - b["tip_transverse"].values)
    return float(np.max(difference[np.isfinite(difference)]))


def test_under_resolved_runs_are_flagged_and_a_converged_run_is_not(setup):
    params, numerics, config = setup
    check = numerics["convergence_check"]
    threshold = check["threshold_m"]

    one_mode = case_of(config, "fig06_foam_n1")  # 1 mode, wf = 5 rad/s (Fig. 6)
    ds = simulate(one_mode, params, numerics, convergence_check=check)
    three = simulate(one_mode.with_modes(1 + check["extra_modes"]), params, numerics)
    assert ds.attrs["convergence_modes"] == 3
    assert ds.attrs["convergence_modes_diff_m"] == tip_difference(ds, three) > threshold
    assert ds.attrs["convergence_tolerance_diff_m"] < threshold
    assert "not converged in the modes" in ds.attrs["warnings"]
    assert "not converged in the tolerance" not in ds.attrs["warnings"]

    loose = dict(numerics, rtol=1e-2, atol=1e-4)  # 1 % per step
    ds = simulate(case_of(config, "fig06_foam_n5"), params, loose, convergence_check=check)
    tight = simulate(case_of(config, "fig06_foam_n5"), params,
                     dict(loose, rtol=1e-2 * check["tolerance_factor"], atol=1e-4 * check["tolerance_factor"]))
    assert ds.attrs["convergence_rtol"] == pytest.approx(1e-2 * check["tolerance_factor"])
    assert ds.attrs["convergence_tolerance_diff_m"] == tip_difference(ds, tight) > threshold
    assert "not converged in the tolerance" in ds.attrs["warnings"]

    ds = simulate(case_of(config, "fig06_foam_n5"), params, numerics, convergence_check=check)
    assert ds.attrs["convergence_modes_diff_m"] < threshold and ds.attrs["convergence_tolerance_diff_m"] < threshold
    assert ds.attrs["warnings"] == ""


def test_convergence_of_a_diverged_run_is_measured_before_the_divergence(setup):
    params, numerics, config = setup
    check = numerics["convergence_check"]
    case = case_of(config, "fig05_tlam_wf3p5", modes=2)
    ds = simulate(case, params, numerics, convergence_check=check)
    assert ds.attrs["diverged"] == 1
    more = simulate(case.with_modes(4), params, numerics)
    assert more.attrs["diverged"] == 1
    assert math.isfinite(ds.attrs["convergence_modes_diff_m"])
    assert ds.attrs["convergence_modes_diff_m"] == tip_difference(ds, more)


def test_a_case_with_the_most_modes_records_that_modes_were_not_checked(setup):
    params, numerics, config = setup
    case = case_of(config, "fig05_foam_wf2p8", modes=20, t_end=0.5)
    ds = simulate(case, params, numerics, convergence_check=numerics["convergence_check"])
    assert ds.attrs["convergence_modes"] == 20 and math.isnan(ds.attrs["convergence_modes_diff_m"])
    assert "convergence in the modes not checked" in ds.attrs["warnings"]
    assert math.isfinite(ds.attrs["convergence_tolerance_diff_m"])
