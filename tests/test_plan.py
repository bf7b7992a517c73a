"""The workflow's plan (hubbeam.pipeline): built from small configurations, without Snakemake.

* the targets of `all` for the paper and for a study: every product in every format, the runs,
  matrices, linear models, maps, readings and validation they need, in the configuration's own
  folder, each written by a job of the plan;
* the inputs and params of a few rules (a case's matrices and kernel, the modes of a matrices file,
  a figure's runs, the claims, the reproduction report, a reading, a sweep's chunks), checked
  against the configuration and the registry, not against the plan's own output;
* a bad configuration refused with one error listing every problem of every kind, and nothing
  written;
* a step's jobs evaluated like Snakemake (wildcards in paths and string params, params functions,
  `threads`), the jobs of `all` ordered after their inputs' writers, a name the configuration does
  not define refused naming what is allowed;
* the one script of workflow/scripts is a shim running the job its step names through the runner,
  and every rule's code inputs are what its job runs (a figure's module is no input of a simulation);
* the families of steps: one module each, every step declared once, no pipeline module over 400 lines;
* the runner writes a job's log, with its traceback when it fails, and leaves logging as it found it;
* the study report's figures by the section their products name.
"""

from __future__ import annotations

import ast
import dataclasses
import logging
import math
import shutil
from pathlib import Path

import pytest
import yaml
from synthetic_results import CONFIG_FILE, REPO, SCRIPTS, small_study

from hubbeam.configuration.grids import expand_case_grids
from hubbeam.model.beam import beam_from_config
from hubbeam.model.eigen import table2
from hubbeam.model.frozen import FrozenMap
from hubbeam.model.matrices import configuration_name
from hubbeam.model.models import FAMILIES, MODELS
from hubbeam.model.parameters import TipMass
from hubbeam.pipeline.jobs.eigen import eigen_table2
from hubbeam.pipeline.plan import NotPlanned, PlanError, build_plan
from hubbeam.pipeline.runner import Job, job_function, run_job
from hubbeam.pipeline.steps import Step, file_paths, fill
from hubbeam.reporting.products import GENERAL_PRODUCTS, PAPER_PRODUCTS, product_cases
from hubbeam.results.io import ResultFileError
from hubbeam.study import MARKER

STUDY_FILE = REPO / "studies" / "controller_trust.yaml"


def paper_config() -> dict:
    return yaml.safe_load(CONFIG_FILE.read_text())


@pytest.fixture(scope="module")
def paper():
    """The plan of config/config.yaml (the paper's folders are shared: nothing is claimed)."""
    return build_plan(paper_config(), [CONFIG_FILE], REPO)


@pytest.fixture
def in_tmp(tmp_path, monkeypatch):
    """A working directory of its own (a study claims its folder there)."""
    monkeypatch.chdir(tmp_path)
    return tmp_path


def study_plan(directory: Path, config: dict, name: str = "study.yaml"):
    """The plan of ``config``, written to ``directory/<name>`` (the file that owns its folder)."""
    path = directory / name
    path.write_text(yaml.safe_dump(config, sort_keys=False))
    return build_plan(yaml.safe_load(path.read_text()), [path], REPO)


# --- targets ---------------------------------------------------------------------------------------

def test_the_paper_builds_its_products_and_what_they_read(paper):
    targets = set(paper.targets)
    assert len(targets) == len(paper.targets) and paper.targets[-1] == "results/hubbeam-results.tar.gz"
    raw = paper_config()
    figures = [key for key, product in PAPER_PRODUCTS.items() if product.is_figure]
    figures += ["linear_campbell", "linear_mode_shapes", "linear_poles_zeros", "linear_bode"]
    figures += [f"{key}_tip" for key in figures[-4:]]  # the paper's linear grid has a second tip mass
    figures += [f"sweep_{name}" for name, sweep in raw["sweeps"]["maps"].items() if sweep.get("in_all", True)]
    expected = {f"results/figures/{key}.{ext}" for key in figures for ext in ("pdf", "png")}
    expected |= {f"results/tables/table{i}.{ext}" for i in (1, 2, 3) for ext in ("csv", "md", "tex")}
    expected |= {f"results/report/{name}" for name in ("claims.csv", "reproduction.md", "reproduction.html")}
    expected |= {f"results/simulations/{case}.nc" for case in raw["cases"]}
    # the paper's tip masses: none, 0.1 kg and 0.5 kg at the tip
    expected |= {"results/matrices/mt0.nc", "results/matrices/mt0p1_l8.nc", "results/matrices/mt0p5_l8.nc"}
    expected |= {f"results/linear/models/{model}_{hub}_tip{k}.{ext}" for model in MODELS
                 for hub in ("free", "prescribed") for k in range(len(raw["linear"]["tip_masses"]))
                 for ext in ("nc", "mat")}
    expected |= {f"results/sweeps/{name}.nc" for name in ("spinup_peak", "tlam_vs_foam")}
    expected |= {"results/readings/readings.csv", "results/readings/readings.nc"}
    expected |= {f"results/validation/{name}" for name in (
        "published_comparison.csv", "tip_mass_comparison.csv", "rotating_eigen.nc", "rotating_frequencies.pdf",
        "rotating_frequencies.png")}
    expected |= {f"results/eigen/{name}.nc" for name in ("k22", "critical_speeds", "campbell")}
    expected |= {f"results/linear/{name}.nc" for name in ("campbell", "mode_shapes", "poles_zeros", "bode")}
    expected |= {"results/tables/critical_speeds.csv", "results/hubbeam-results.tar.gz"}
    assert targets == expected
    assert set(paper.target_rules["large_sweeps"]) == {"results/sweeps/tlam_vs_foam_3d.nc",
                                                       "results/figures/sweep_tlam_vs_foam_3d.pdf",
                                                       "results/figures/sweep_tlam_vs_foam_3d.png"}
    assert paper.target_rules["readings"] == ("results/readings/readings.csv", "results/readings/readings.nc")
    assert list(paper.readings) == list(raw["readings"])


def test_every_target_is_written_by_a_job_after_the_jobs_writing_its_inputs(paper):
    jobs = paper.jobs()
    written = {path: index for index, planned in enumerate(jobs) for path in file_paths(planned.job.output)}
    assert set(paper.targets) <= set(written)
    for index, planned in enumerate(jobs):
        for path in file_paths(planned.job.input):
            assert written.get(path, -1) < index, (planned.rule, path)
    counts = {rule: sum(planned.rule == rule for planned in jobs) for rule in paper.steps}
    raw = paper_config()
    assert counts["simulate"] == len(raw["cases"]) and counts["matrices"] == 3
    assert counts["simulation_kernel"] == len(FAMILIES) and counts["reading"] == len(raw["readings"])
    assert counts["validate_exudyn"] == 0 and counts["study_report"] == 0  # `validate` only; no study


def test_a_study_builds_only_in_its_own_folder(in_tmp):
    study = yaml.safe_load(STUDY_FILE.read_text())
    plan = study_plan(in_tmp, study)
    name = study["study"]["name"]
    assert (in_tmp / "results" / name / MARKER).read_text() == "study.yaml\n"  # claimed
    assert all(target.startswith(f"results/{name}/") for target in plan.targets)
    figures = {f"case_{case}" for case in plan.settings.cases}
    assert len(figures) == 30  # the study's grid
    figures |= {f"compare_{comparison}" for comparison in study["study"]["comparisons"]}
    figures |= {"beam_properties", "controller_trust"}
    figures |= {f"plant_{product}_{plant}" for plant in plan.settings.plants
                for product in ("campbell", "mode_shapes", "poles_zeros", "bode")}
    for figure in figures:
        assert f"results/{name}/figures/{figure}.png" in plan.targets, figure
    report = {f"results/{name}/report/{leaf}" for leaf in ("report.md", "report.html", "summary.csv")}
    assert report <= set(plan.targets)
    assert not [target for target in plan.targets if "claims" in target or "table" in target or "readings" in target]
    assert plan.targets[-1] == f"results/{name}/{name}-results.tar.gz"


# --- the inputs and params of rules --------------------------------------------------------------------

def test_a_body_on_the_loaded_modes_and_on_the_clamped_free_ones_have_matrices_of_their_own(in_tmp):
    """The link study's payload on two sets of transverse functions: two matrices files, each
    assembled with its functions and read by its own case."""
    study = yaml.safe_load((REPO / "studies" / "deluca_link.yaml").read_text())
    plan = study_plan(in_tmp, study)
    loaded, plain = "mt0p1_l0p5_J0p0005_tip_body", "mt0p1_l0p5_J0p0005"
    for case, name in (("payload", loaded), ("payload_clamped_free", plain), ("point_payload", "mt0p1_l0p5")):
        assert plan.steps["simulate"].job({"case": case}).input["matrices"].endswith(f"/matrices/{name}.nc")
    functions = {name: plan.steps["matrices"].job({"config_name": name}).params["configuration"]["functions"]
                 for name in (loaded, plain)}
    assert functions == {loaded: "tip_body", plain: "clamped_free"}


def test_a_simulation_reads_the_matrices_of_its_tip_mass_and_its_family_s_kernel(paper):
    job = paper.steps["simulate"].job({"case": "fig10_foam_mt0p5"})
    assert job.input["matrices"] == "results/matrices/mt0p5_l8.nc"
    assert job.input["kernel"] == "logs/simulations/kernel_foam.done"
    assert paper.steps["simulate"].job({"case": "fig04_cfoam"}).input["kernel"] == "logs/simulations/kernel_cfoam.done"
    assert job.output == {"nc": "results/simulations/fig10_foam_mt0p5.nc"}
    assert job.log == "logs/simulations/fig10_foam_mt0p5.log"
    case = job.params["case"]
    assert case.name == "fig10_foam_mt0p5" and case.tip_mass == TipMass(0.5, 8.0)
    assert job.params["numerics"].modes is None  # the matrices carry the discretisation
    assert repr(case) in job.params["fingerprint"]  # editing the case reruns it


def test_a_matrices_file_has_the_modes_of_the_most_demanding_case_using_it(paper):
    raw = paper_config()
    default = raw["numerics"]["modes"]
    for name in ("mt0", "mt0p5_l8"):
        users = [case for case in raw["cases"].values()
                 if configuration_name(TipMass(**case.get("tip_mass", {"mass": 0.0, "position": 8.0}))) == name]
        configuration = paper.steps["matrices"].job({"config_name": name}).params["configuration"]
        assert configuration["modes"] == max(case.get("modes", default) for case in users)
    with pytest.raises(NotPlanned, match="unknown configuration 'mt9'; allowed: mt0, mt0p1_l8, mt0p5_l8"):
        paper.steps["matrices"].job({"config_name": "mt9"})


def test_figures_claims_and_reports_read_what_the_registry_and_the_configuration_name(paper):
    fig05 = paper.steps["figure_fig05"].job()
    assert fig05.params["cases"] == list(PAPER_PRODUCTS["fig05"].cases)
    assert fig05.input["datasets"] == tuple(f"results/simulations/{case}.nc" for case in PAPER_PRODUCTS["fig05"].cases)
    assert "src/hubbeam/plotting/fig05.py" in {Path(path).as_posix()[-len("src/hubbeam/plotting/fig05.py"):]
                                               for path in fig05.input["code"]}
    claims = paper.steps["claims"].job()
    assert claims.params["cases"] == product_cases(PAPER_PRODUCTS)
    assert claims.input["table2"] == "results/tables/table2.csv"
    report = paper.steps["reproduction_report"].job()
    assert {"published", "tip_mass", "curves", "published_figure", "readings"} <= set(report.input)
    assert {f"results/figures/{key}.png" for key, product in PAPER_PRODUCTS.items() if product.is_figure} <= set(
        report.input["figures"])
    without = paper_config()
    del without["readings"], without["validation"]["published"]
    lean = build_plan(without, [CONFIG_FILE], REPO).steps["reproduction_report"].job()
    assert not {"published", "readings"} & set(lean.input)


def test_a_reading_reads_the_runs_of_its_claims_and_a_sweep_its_chunks(paper):
    reading = paper.steps["reading"].job({"reading": "eq43_as_printed"})
    runs = reading.params["runs"]
    assert runs.name == "eq43_as_printed" and reading.params["cases"] == sorted(runs.bases)
    assert reading.input["datasets"] == tuple(f"results/simulations/{case}.nc" for case in sorted(runs.bases))
    assert reading.input["claims"] == "results/report/claims.csv"
    with pytest.raises(NotPlanned, match="unknown reading 'nope'; allowed: eq43_as_printed, "):
        paper.steps["reading"].job({"reading": "nope"})
    raw = paper_config()["sweeps"]
    spec = raw["maps"]["spinup_peak"]
    chunks = math.ceil(len(spec["models"]) * math.prod(grid["num"] for grid in spec["grid"].values())
                       / raw["chunk_size"])
    gather = paper.steps["sweep"].job({"sweep": "spinup_peak"})
    assert gather.input["chunks"] == tuple(f"results/sweeps/chunks/spinup_peak/{i}.nc" for i in range(chunks))
    assert gather.params["sweep"] is paper.settings.sweeps["spinup_peak"]
    assert gather.params["sweep_config"] == paper.settings.sweeps["spinup_peak"].to_dict()
    chunk = paper.steps["sweep_chunk"].job({"sweep": "spinup_peak", "chunk": "1"}, threads=2)
    assert chunk.params["chunk"] == "1" and chunk.params["threads"] == 2
    with pytest.raises(NotPlanned, match="unknown sweep 'map'; allowed: spinup_peak, tlam_vs_foam, tlam_vs_foam_3d"):
        paper.steps["sweep"].job({"sweep": "map"})


def test_the_validation_needs_its_section_only_when_its_jobs_run(in_tmp):
    config = yaml.safe_load((REPO / "studies" / "first_study.yaml").read_text())
    assert "validation" not in config and config["beam"]["hub_radius"] == 0.0  # no pyBModes on the axis
    plan = study_plan(in_tmp, config)
    assert plan.steps["validate_exudyn"].wildcards == ()
    with pytest.raises(NotPlanned, match="validation.convergence: missing from the configuration in use"):
        plan.steps["validate_convergence"].job()
    assert [Path(path).name for path in plan.target_rules["validate"]()] == [
        "nonuniform_ritz_fe.csv", "validation_exudyn.md", "validation_exudyn.html"]


# --- a refused configuration -----------------------------------------------------------------------

def problems(error: PlanError) -> list[str]:
    return [str(problem) for problem in error.problems]


def test_a_bad_configuration_is_refused_with_every_problem_listed(in_tmp):
    """Schema problems with the products' missing cases; then, in a configuration the schema
    accepts, a feedback design, a reading, the products' cases and a folder another configuration
    owns: every one in one message, and nothing written."""
    bad = paper_config()
    bad["beam"]["density"] = -1.0
    del bad["cases"]["fig03_cfoam_n1"]
    with pytest.raises(PlanError) as error:
        study_plan(in_tmp, bad)
    found = problems(error.value)
    assert any(p.startswith("beam.density: got -1.0") for p in found)
    assert "cases: product fig03 reads fig03_cfoam_n1, which the config `cases` does not define" in found
    assert f"{len(found)} problems:" in str(error.value) and str(error.value).count("\n  - ") == len(found)

    study = yaml.safe_load(STUDY_FILE.read_text())
    name = study["study"]["name"]
    owner = in_tmp / "results" / name / MARKER
    owner.parent.mkdir(parents=True)
    owner.write_text("other.yaml\n")
    study["products"] = ["paper"]  # reads the paper's cases, which the study lacks
    study.setdefault("eigen", {})["table2_speed"] = 1.0
    assert expand_case_grids(study) == []  # the grid's cases written out, to change one of them
    del study["case_grids"]
    design = study["cases"]["foam_on_cfoam_w1"]["maneuver"]["design"]
    design["speed"] = 2000.0  # no steady spin of FOAM's axial modes there
    reading = next(reading for reading in paper_config()["readings"].values() if "measure" in reading["change"])
    study["readings"] = {"wrong": reading | {"claims": ["no_such_claim"]}}
    with pytest.raises(PlanError) as error:
        study_plan(in_tmp, study)
    found = problems(error.value)
    expected = ["cases.foam_on_cfoam_w1.maneuver.design.speed: got 2000.0",
                "readings.wrong.claims", "cases: product fig03 reads fig03_cfoam_n1,",
                f"study.name: the folder results/{name} belongs to the study of other.yaml"]
    for start in expected:
        assert any(p.startswith(start) for p in found), (start, found)
    assert owner.read_text() == "other.yaml\n" and sorted(p.name for p in in_tmp.iterdir()) == ["results", "study.yaml"]


def test_a_refused_study_claims_no_folder(in_tmp):
    study = yaml.safe_load(STUDY_FILE.read_text())
    study["numerics"]["rtol"] = "fast"
    with pytest.raises(PlanError, match="numerics.rtol"):
        study_plan(in_tmp, study)
    assert not (in_tmp / "results").exists()


# --- steps and their jobs ------------------------------------------------------------------------

def test_a_step_evaluates_its_job_as_snakemake_would(tmp_path):
    def files_of(wildcards):
        return [f"in/{wildcards.case}_{k}.nc" for k in range(2)]

    def with_threads(wildcards, threads):
        return threads

    step = Step(script="x.py", output={"nc": "out/{case}.nc"}, log="logs/{case}.log",
                input={"runs": files_of, "style": "style.mplstyle", "both": ["a/{case}.nc", "b.nc"]},
                params={"name": "{case}", "cases": ["{case}", 1], "threads": with_threads, "kept": ("{case}",)},
                wildcards=[{"case": "a1"}])
    [(wildcards, job)] = step.jobs()
    assert wildcards == {"case": "a1"}
    assert job.input == {"runs": ("in/a1_0.nc", "in/a1_1.nc"), "style": "style.mplstyle", "both": ("a/a1.nc", "b.nc")}
    assert job.output == {"nc": "out/a1.nc"} and job.log == "logs/a1.log"
    # strings and lists of strings are filled in, as Snakemake does; a tuple is a value
    assert job.params == {"name": "a1", "cases": ["a1", 1], "threads": 1, "kept": ("{case}",)}
    assert step.job({"case": "b"}, threads=3).params["threads"] == 3
    with pytest.raises(KeyError, match=r"out/\{case\}.nc: wildcard \{case\} has no value; given: none"):
        step.job()
    assert fill("x/{sweep}/{chunk,\\d+}.nc", {"sweep": "s", "chunk": 2}) == "x/s/2.nc"


def test_every_rule_runs_the_one_shim_on_the_job_its_step_names(paper, in_tmp):
    shutil.copy(STUDY_FILE, in_tmp / "study.yaml")
    study = build_plan(yaml.safe_load(STUDY_FILE.read_text()), [in_tmp / "study.yaml"], REPO)
    assert [path.name for path in SCRIPTS.glob("*")] == ["run_job.py"]
    tree = ast.parse((SCRIPTS / "run_job.py").read_text())
    docstring, runner_import, call = tree.body
    assert ast.get_docstring(tree).startswith("Snakemake shim")
    assert runner_import.module == "hubbeam.pipeline.runner" and runner_import.names[0].name == "run"
    assert ast.unparse(call) == "run(snakemake)"
    for plan in (paper, study):
        for rule, step in plan.steps.items():
            module, _, function = step.params["job"].partition(":")
            assert module.startswith("hubbeam.pipeline.jobs.") and callable(job_function(step.params["job"])), rule
            if "code" in step.input:
                source = module.replace(".", "/") + ".py"
                assert any(Path(file).as_posix().endswith(source) for file in step.input["code"]), rule


def test_each_family_declares_its_own_steps_in_a_small_module(paper):
    """The plan's steps are the union of the families' (each rule declared once), and no module of
    the pipeline package is longer than 400 lines."""
    from hubbeam.pipeline.families import FAMILIES
    from hubbeam.pipeline.plan import plan_of

    assert len({family.__name__ for family in FAMILIES}) == len(FAMILIES) >= 9
    assert set(plan_of.__globals__["FAMILIES"]) == set(FAMILIES)
    package = REPO / "src" / "hubbeam" / "pipeline"
    lengths = {path.relative_to(package).as_posix(): len(path.read_text().splitlines())
               for path in package.rglob("*.py")}
    assert max(lengths.values()) <= 400, {name: n for name, n in lengths.items() if n > 400}
    assert "cfg[" not in "".join(path.read_text() for path in package.rglob("*.py"))


def test_a_costly_job_s_code_inputs_hold_no_drawing_code(paper):
    """Editing a figure reruns no simulation, sweep or validation run: the code inputs of a rule are
    the modules its job imports (hubbeam.pipeline.jobs is grouped by imports)."""
    for rule in ("simulate", "matrices", "sweep_chunk", "reading", "validate_exudyn", "validate_models",
                 "validate_modes", "validate_convergence"):
        code = [Path(path).as_posix() for path in paper.steps[rule].input["code"]]
        assert not [path for path in code if "/plotting/" in path or "/pipeline/jobs/figures" in path], rule
        assert any(path.endswith("pipeline/runner.py") for path in code), rule
    exudyn = [Path(path).as_posix() for path in paper.steps["validate_exudyn"].input["code"]]
    assert not [path for path in exudyn if path.endswith(("fe_beam.py", "simulation/simulate.py"))]


def test_a_job_function_runs_on_its_step_s_job(paper, tmp_path):
    """Table 2's job, called directly with the job of its step (the output moved aside), writes
    the table hubbeam.model.eigen.table2 gives for the configuration's own beam, speed, modes and
    quadrature: the params reach the function under the right names."""
    job = dataclasses.replace(paper.steps["eigen_table2"].job(), output=FrozenMap({"csv": str(tmp_path / "t.csv")}),
                              log=str(tmp_path / "t.log"))
    run_job(job_function(job.params["job"]), job)
    assert job_function(job.params["job"]) is eigen_table2
    raw = paper_config()
    expected = table2(beam_from_config(raw["beam"]), float(raw["eigen"]["table2_speed"]), raw["numerics"]["modes"],
                      raw["numerics"]["quadrature_points"])
    assert (tmp_path / "t.csv").read_text() == expected.to_csv(index=False)
    assert "Table 2:" in (tmp_path / "t.log").read_text()


# --- the runner -------------------------------------------------------------------------------

def test_a_failing_job_leaves_its_traceback_in_its_log(tmp_path):
    def broken(job):
        logging.getLogger("hubbeam.test").info("reading %s", job.input["runs"])
        raise ValueError(f"{job.input['runs']}: not a run")

    root = logging.getLogger()
    handlers, level = list(root.handlers), root.level
    job = Job(input=FrozenMap({"runs": "x.nc"}), output=FrozenMap(), params=FrozenMap(),
              log=str(tmp_path / "logs" / "broken.log"))
    with pytest.raises(ValueError, match="x.nc: not a run"):
        run_job(broken, job)
    log = Path(job.log).read_text()
    assert "hubbeam.test INFO reading x.nc" in log
    assert "job test_a_failing_job_leaves_its_traceback_in_its_log.<locals>.broken failed" in log
    assert "Traceback (most recent call last)" in log and 'in broken\n    raise ValueError' in log
    assert log.rstrip().endswith("ValueError: x.nc: not a run")
    assert root.handlers == handlers and root.level == level  # logging as it was

    run_job(lambda job: logging.getLogger("hubbeam.test").warning("only this"), job)
    log = Path(job.log).read_text()  # written afresh
    assert "hubbeam.test WARNING only this" in log and "Traceback" not in log


def test_a_script_s_failure_reaches_its_log_through_the_shim(tmp_path):
    from synthetic_results import run_script

    log = tmp_path / "table.log"
    with pytest.raises(ResultFileError, match="missing.nc does not exist"):
        run_script("hubbeam.pipeline.jobs.tables:table3", input={"datasets": [str(tmp_path / "missing.nc")]},
                   output={ext: str(tmp_path / f"t.{ext}") for ext in ("csv", "md", "tex")},
                   params={"cases": ["tab3_foam_tau50"]}, log=str(log))
    text = log.read_text()
    assert "job table3 failed" in text and "Traceback" in text and "missing.nc" in text


# --- the study report's sections ------------------------------------------------------------------

def test_the_study_report_shows_each_figure_in_the_section_its_product_names(in_tmp):
    study = yaml.safe_load(STUDY_FILE.read_text())
    name = study["study"]["name"]
    plan = study_plan(in_tmp, study)
    figures = plan.steps["study_report"].job().params["figures"]
    assert figures["cases"] == {case: f"results/{name}/figures/case_{case}.png" for case in plan.cases}
    assert set(figures["comparisons"]) == set(study["study"]["comparisons"])
    assert set(figures["beam"]) == {"beam_properties"} and set(figures["designs"]) == {"controller_trust"}
    assert "eigen" not in figures and "linear" not in figures  # the plants' products instead
    (plant,) = plan.settings.plants
    assert set(figures["plants"]) == {f"{plant}/{key}" for key in GENERAL_PRODUCTS if key.startswith("plant_")}
    assert "paper" not in figures


def test_the_small_study_runs_every_rule_but_the_optional_validation(in_tmp):
    """The configuration whose every job tests/test_reliability.py runs without Snakemake: its
    `all` needs every rule that runs a script, but those of `snakemake validate`."""
    plan = study_plan(in_tmp, small_study())
    validation_only = {"validate_exudyn", "validate_models", "validate_case", "validate_comparison",
                       "validate_modes", "validate_convergence", "validate_nonuniform", "validation_report"}
    # the analyses of sampled controllers need a `control` section (tests/test_quanser_plan.py)
    control_only = {"control_sample_time", "control_robustness", "control_export"}
    assert {planned.rule for planned in plan.jobs()} == set(plan.steps) - validation_only - control_only
