"""Generated studies (tests/generated_studies.py) through the one check, the plan and Snakemake.

For every seed's study:

* the one check accepts it (a refusal is a generator bug; many seeds, no workflow);
* (a) the Snakemake dry run lists exactly the jobs of the plan;
* (b) the whole workflow completes: every target of the plan exists, each case's validity in the
  report's table is its dataset's, and a run the integrator stopped is never "valid";
* (c) each case's held-hub frequencies at rest in its plant's ``plant.nc`` are the API's;
* (d) on the free hub, exactly one rigid-body mode (``hub``, at 0 Hz at rest) and the bending modes
  numbered from the first flexible one by frequency;
* (e) no ``nan`` in the report's text or tables;
* (f) every panel of every figure has finite data or is hidden: the figure jobs of the plan run
  again in the process, each figure inspected when it is saved.

``make test`` runs the fixed :data:`SEEDS`; ``make test-studies`` runs ``HUBBEAM_STUDIES`` seeds
from 0 (or the listed ones).
"""

from __future__ import annotations

import csv
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import matplotlib
import numpy as np
import pytest
import xarray as xr
import yaml
from generated_studies import generate_study
from synthetic_results import REPO
from test_rules import dry_run_jobs

from hubbeam.api import load
from hubbeam.check import check_configuration
from hubbeam.model.validity import describe
from hubbeam.pipeline.plan import build_plan
from hubbeam.pipeline.runner import Job, job_function, run_job
from hubbeam.pipeline.steps import file_paths

matplotlib.use("Agg")
from matplotlib.figure import Figure  # noqa: E402

#: the seed of ``make test``, the most the suite's time allows: a voltage-driven CFOAM arm on a root
#: spring, a payload body inward of the tip, under a sampled LQR (``make test-studies`` runs more;
#: seed 22, a FOAM arm with a body inward of the tip on a root spring, Rayleigh damping and a torque
#: table, by ``HUBBEAM_STUDIES=22,246``)
SEEDS = (246,)


def study_seeds(text: str | None) -> tuple[int, ...]:
    """The seeds ``HUBBEAM_STUDIES`` names: a count ``N`` (seeds 0 to N-1) or a list ``4,17,58``;
    unset, :data:`SEEDS`."""
    if not text:
        return SEEDS
    return tuple(int(seed) for seed in text.split(",")) if "," in text else tuple(range(int(text)))


#: the seeds of this run (``make test-studies`` sets ``HUBBEAM_STUDIES``)
STUDY_SEEDS = study_seeds(os.environ.get("HUBBEAM_STUDIES"))
#: the validities a case's run may have (hubbeam.model.validity)
VALIDITIES = {"valid", "large_deflection", "left_range", "diverged", "stopped"}
SNAKEMAKE = [sys.executable, "-m", "snakemake", "--snakefile", str(REPO / "Snakefile")]


def write_study(directory: Path, seed: int) -> Path:
    path = directory / f"generated_{seed}.yaml"
    path.write_text(yaml.safe_dump(generate_study(seed), sort_keys=False))
    return path


def test_every_generated_study_passes_the_one_check(tmp_path):
    for seed in range(120):
        path = write_study(tmp_path, seed)
        check_configuration(yaml.safe_load(path.read_text()), [path])


def test_the_generator_is_seeded_and_spans_the_schema():
    assert generate_study(5) == generate_study(5) and generate_study(5) != generate_study(6)
    seen: set[str] = set()
    for seed in range(120):
        config = generate_study(seed)
        beam = config["beam"]
        seen.add("sections" if "sections" in beam else "factors" if "density" in beam else "products")
        seen |= {f"control.{key}" for key in config.get("control", {})}
        seen |= {"case_grids"} if "case_grids" in config else set()
        for case in config["cases"].values():
            maneuver = case["maneuver"]
            seen |= {maneuver["kind"], case["model"]} | {key for key in case if key not in ("model", "maneuver")}
            tip = case.get("tip_mass", {})
            seen |= {"inward"} if tip.get("position", beam["length"]) < beam["length"] else set()
            sampling = maneuver.get("sampling", {})
            seen |= {f"estimator.{sampling.get('estimator', {}).get('kind', 'exact')}"} if sampling else set()
            seen |= {"reduce"} if sampling.get("reduce") else set()
    expected = {"products", "factors", "sections", "control.sample_time", "control.robustness", "case_grids",
                "prescribed", "torque", "speed_table", "torque_table", "voltage_table", "pd", "state_feedback",
                "TLAM", "FOAM", "SFOAM", "CFOAM", "tip_mass", "inward", "root_spring", "drive", "damping",
                "shaper", "initial", "modes", "estimator.exact", "estimator.kalman", "reduce"}
    assert expected <= seen, expected - seen


# --- the workflow of each seed's study --------------------------------------------------------------

def snakemake(workdir: Path, config: Path, *args: str) -> subprocess.CompletedProcess:
    command = [*SNAKEMAKE, "--directory", str(workdir), "--cores", "2", "--configfile", str(config), *args]
    return subprocess.run(command, cwd=workdir, capture_output=True, text=True, timeout=1200, check=False)


@pytest.fixture(scope="module", params=STUDY_SEEDS, ids=lambda seed: f"seed{seed}")
def study(request):
    """The study of one seed: its config file in a folder of its own, the plan, the dry run's output
    and the run's process."""
    seed = request.param
    with tempfile.TemporaryDirectory(prefix=f"generated_{seed}_") as folder:
        workdir = Path(folder)
        path = write_study(workdir, seed)
        config = yaml.safe_load(path.read_text())
        before = Path.cwd()
        os.chdir(workdir)
        try:
            plan = build_plan(config, [path.name], REPO)
        finally:
            os.chdir(before)
        dry = snakemake(workdir, path, "--dry-run")
        run = snakemake(workdir, path)
        yield {"seed": seed, "workdir": workdir, "path": path, "config": config, "plan": plan,
               "dry": dry.stdout + dry.stderr, "run": run}


def test_a_dry_run_lists_the_jobs_of_the_plan(study):
    assert "This was a dry-run" in study["dry"], study["dry"][-3000:]
    planned = {(job.rule, frozenset(file_paths(job.job.output))) for job in study["plan"].jobs()}
    assert dry_run_jobs(study["dry"]) == planned | {("all", frozenset())}


def summary_rows(study) -> dict[str, dict]:
    name = study["config"]["study"]["name"]
    with open(study["workdir"] / "results" / name / "report" / "summary.csv", newline="") as table:
        return {row["case"]: row for row in csv.DictReader(table)}


def test_the_workflow_completes_and_reports_each_run_as_it_ended(study):
    run = study["run"]
    assert run.returncode == 0, (run.stdout + run.stderr)[-4000:]
    missing = [target for target in study["plan"].targets if not (study["workdir"] / target).is_file()]
    assert not missing
    rows = summary_rows(study)
    cases = study["plan"].checked.settings.cases
    assert set(rows) == set(cases)
    for case in cases:
        folder = study["workdir"] / "results" / study["config"]["study"]["name"] / "simulations"
        with xr.open_dataset(folder / f"{case}.nc") as run:
            validity, status, cell = run.attrs["validity"], run.attrs["integrator_status"], describe(run.attrs)
        assert validity in VALIDITIES and rows[case]["validity"] == cell, (case, validity, rows[case]["validity"])
        if status != "success":
            assert validity != "valid", (case, status)


def plant_folders(study) -> dict[str, Path]:
    """The plant folder of each case."""
    configuration = load(study["path"])
    root = study["workdir"] / "results" / study["config"]["study"]["name"] / "plants"
    return {case: root / configuration.plant_of(case).name for case in configuration.case_names}


def test_the_held_frequencies_of_each_case_s_plant_are_the_api_s(study):
    configuration = load(study["path"])
    for case, folder in plant_folders(study).items():
        with xr.open_dataset(folder / "plant.nc") as plant:
            held = plant["held_frequency"].values
        expected = np.asarray(configuration.natural_frequencies(case))
        np.testing.assert_allclose(held, expected[:held.size], rtol=1e-9, err_msg=case)
        assert held.size == expected.size


def test_the_free_hub_has_one_rigid_mode_and_its_bending_modes_are_numbered_from_the_first(study):
    for case, folder in plant_folders(study).items():
        with xr.open_dataset(folder / "campbell.nc") as campbell:
            free = campbell.sel(hub="free").isel(plant=0)
            for model in free["model"].values:
                labels = [str(label) for label in free["mode_label"].sel(model=model).values]
                frequency = free["frequency"].sel(model=model).isel(speed=0).values
                kind = free["kind"].sel(model=model).isel(speed=0).values
                assert labels.count("hub") == 1, (case, model, labels)
                hub = labels.index("hub")
                assert kind[hub] == 2 and abs(frequency[hub]) < 1e-6 * max(1.0, np.nanmax(frequency)), (case, model)
                flexible = [k for k, label in enumerate(labels) if label and label != "hub"]
                # a flexible mode vibrates (a positive frequency) or, overdamped by the damping, is a
                # decaying real pair (kind 1, frequency 0, damping ratio 1)
                damping = free["damping_ratio"].sel(model=model).isel(speed=0).values
                assert all(frequency[k] > 0 if kind[k] == 0 else kind[k] == 1 and damping[k] >= 1.0 - 1e-9
                           for k in flexible), (case, model, labels, kind, damping)
                bending = sorted((frequency[k], labels[k]) for k in flexible if labels[k].startswith("bending"))
                assert [label for _, label in bending] == [f"bending {n}" for n in range(1, len(bending) + 1)]
                assert bending, (case, model, labels)


def test_no_report_text_or_table_prints_nan(study):
    folder = study["workdir"] / "results" / study["config"]["study"]["name"] / "report"
    for path in [*folder.glob("*.md"), *folder.glob("*.html")]:
        text = re.sub(r"data:[^\"')\s]*", "data:", path.read_text())  # the embedded figures' bytes
        found = re.findall(r".{0,80}\bnan\b.{0,40}", text, re.I)
        assert not found, (path.name, found[:5])


def panel_problems(figure: Figure) -> list[str]:
    """The visible axes of ``figure`` that draw no finite data: no line, collection, image or patch
    with a finite point (an empty panel a reader would take for a result)."""
    problems = []
    for axes in figure.get_axes():
        if not axes.get_visible() or not axes.axison and not axes.has_data():
            continue
        finite = any(np.isfinite(np.asarray(line.get_xydata(), dtype=float)).all(axis=-1).any()
                     for line in axes.get_lines() if len(line.get_xydata()))
        for collection in axes.collections:
            offsets = np.asarray(collection.get_offsets(), dtype=float)
            paths = [np.asarray(path.vertices, dtype=float) for path in collection.get_paths()]
            finite |= any(np.isfinite(points).all(axis=-1).any() for points in [offsets, *paths] if points.size)
        finite |= bool(axes.images) or any(np.isfinite(patch.get_path().vertices).all() for patch in axes.patches)
        if not finite:
            problems.append(f"{axes.get_title() or axes.get_ylabel() or 'untitled'}")
    return problems


def test_every_figure_panel_drawn_has_data(study, tmp_path, monkeypatch):
    """The figure jobs of the plan run again in this process on the workflow's datasets; each
    figure is inspected as it is saved (the PNGs are not parsed)."""
    assert study["run"].returncode == 0
    monkeypatch.chdir(study["workdir"])
    inspected: dict[str, list[str]] = {}
    save = Figure.savefig

    def inspecting(figure, name, *args, **kwargs):
        inspected[Path(str(name)).name] = panel_problems(figure)
        return save(figure, name, *args, **kwargs)

    monkeypatch.setattr(Figure, "savefig", inspecting)
    figures = [planned for planned in study["plan"].jobs() if planned.rule.startswith("figure")]
    assert figures
    for planned in figures:
        job = planned.job
        output = {key: str(tmp_path / Path(value).name) if isinstance(value, str)
                  else tuple(str(tmp_path / Path(v).name) for v in value) for key, value in job.output.items()}
        run_job(job_function(job.params["job"]), Job(input=job.input, output=output, params=job.params,
                                                    log=str(tmp_path / f"{planned.rule}.log")))
    assert inspected
    empty = {name: problems for name, problems in inspected.items() if problems}
    assert not empty
