"""The paper is one study: every path from hubbeam.results.paths, every file named there or in the
registry of products, one registry of products for the paper and every study, and one set of rules
that every configuration runs."""

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from hubbeam.configuration.load import ConfigError, check_schema
from hubbeam.pipeline.plan import build_plan
from hubbeam.reporting.products import (
    CAMPBELL,
    DESIGNS_FIGURE,
    GENERAL_PRODUCTS,
    PAPER_PRODUCTS,
    SHAPING_FIGURE,
    SIMULATION_FIGURE,
    Product,
    ProductError,
    merged,
    of_kind,
    product_sets,
    products_for,
)
from hubbeam.results.paths import IN_RESULTS, SHARED, study_paths

REPO = Path(__file__).resolve().parents[1]
PAPER_CONFIG = REPO / "config" / "config.yaml"
STUDY_CONFIG = REPO / "studies" / "spinup10m.yaml"

#: a string literal that starts with the results or logs folder ("results/...", f'logs/...')
PATH_LITERAL = re.compile(r"""(?<![\w/.])[rbfuRBFU]{0,2}["'](results|logs)/""")
#: a string literal that names a file of a results folder by its extension ("claims.csv", f"{x}.nc")
RESULT_FILE_LITERAL = re.compile(r"""["'][^"'\s]+\.(nc|csv|md|html|tex|pdf|png|mat|done|tar\.gz)["']""")


def paper() -> dict:
    return yaml.safe_load(PAPER_CONFIG.read_text())


def study() -> dict:
    return yaml.safe_load(STUDY_CONFIG.read_text())


# --- paths -------------------------------------------------------------------------------------

@pytest.mark.parametrize("line, found", [
    ('x = "results/figures/fig05.pdf"', True), ("f'logs/{name}.log'", True), ('{"results": data}', False),
    ('rf"results/{x}"', True), ('"my_results/x"', False), ('"tests/results/x"', False),
    ("the results/ folder", False), ('"results_dir"', False),
])
def test_the_path_literal_pattern_finds_what_it_should(line, found):
    assert bool(PATH_LITERAL.search(line)) == found


def test_no_results_or_logs_path_is_spelled_outside_the_paths_module():
    paths_module = REPO / "src" / "hubbeam" / "results" / "paths.py"
    files = [REPO / "Snakefile", *(REPO / "src").rglob("*.py"), *(REPO / "workflow").rglob("*.smk"),
             *(REPO / "workflow").rglob("*.py")]
    found = [f"{path.relative_to(REPO)}:{number}: {line.strip()}"
             for path in files if path != paths_module
             for number, line in enumerate(path.read_text().splitlines(), start=1)
             if PATH_LITERAL.search(line)]
    assert found == []


@pytest.mark.parametrize("line, found", [
    ('"claims.csv"', True), ("f'exudyn_{case}.nc'", True), ('"runs/models_x.nc"', True), ('"kernel.done"', True),
    ('"../report/claims.rst"', False), ('("nc", "mat")', False), ("``simulations/{case}.nc``", False),
    ('with_suffix(".png")', False),
])
def test_the_result_file_pattern_finds_what_it_should(line, found):
    assert bool(RESULT_FILE_LITERAL.search(line)) == found


def test_only_the_paths_module_and_the_registry_name_result_files():
    """The rule files, the Snakefile and the workflow's plan and jobs take every file name from
    hubbeam.results.paths or the registry of products, where each is stated once."""
    files = [REPO / "Snakefile", *(REPO / "workflow" / "rules").glob("*.smk"),
             *(REPO / "src" / "hubbeam" / "pipeline").rglob("*.py")]
    found = [f"{path.relative_to(REPO)}:{number}: {line.strip()}"
             for path in files for number, line in enumerate(path.read_text().splitlines(), start=1)
             if RESULT_FILE_LITERAL.search(line)]
    assert found == []


def test_the_paper_writes_directly_under_results_and_logs():
    paths = study_paths(None)
    assert paths == SHARED and not paths.owned
    assert paths.simulation("fig04_foam") == "results/simulations/fig04_foam.nc"
    assert paths.figure("fig05", "png") == "results/figures/fig05.png"
    assert paths.log("eigen", "k22.log") == "logs/eigen/k22.log"
    assert paths.archive() == "results/hubbeam-results.tar.gz" and paths.archive_root == "."


def test_a_study_writes_under_its_own_folders():
    paths = study_paths(study()["study"]["name"])
    assert paths.owned
    assert paths.simulation("{case}") == "results/spinup10m/simulations/{case}.nc"
    assert paths.eigen("campbell") == "results/spinup10m/eigen/campbell.nc"
    assert paths.log("simulations", "{case}.log") == "logs/spinup10m/simulations/{case}.log"
    assert paths.archive() == "results/spinup10m/spinup10m-results.tar.gz"
    assert paths.archive_root == paths.results == "results/spinup10m"


def test_products_name_their_files_relative_to_the_results_folder():
    assert IN_RESULTS.eigen("k22") == "eigen/k22.nc"
    for product in (*GENERAL_PRODUCTS.values(), *PAPER_PRODUCTS.values()):
        for path in product.files.values():
            assert not path.startswith(("results", "/")), (product.key, path)
            assert study_paths(study()["study"]["name"]).result(path).startswith("results/spinup10m/")


# --- the registry --------------------------------------------------------------------------------

#: the linear-model figures every configuration gets, and with a second tip mass their ``_tip`` variants
LINEAR = ["linear_campbell", "linear_mode_shapes", "linear_poles_zeros", "linear_bode"]
LINEAR_TIP = [product for key in LINEAR for product in (key, f"{key}_tip")]


def test_the_paper_asks_for_its_products_and_gets_none_of_the_study_report():
    products = products_for(paper())
    assert product_sets(paper()) == ["paper"]
    assert dict(products) == dict(PAPER_PRODUCTS) | {key: GENERAL_PRODUCTS[key] for key in LINEAR_TIP}
    assert products["campbell"] is CAMPBELL is GENERAL_PRODUCTS["campbell"]  # declared once


def test_the_linear_figures_of_a_tip_mass_need_one():
    cfg = paper()
    cfg["linear"]["tip_masses"] = [0.0]
    assert set(products_for(cfg)) == set(PAPER_PRODUCTS) | set(LINEAR)


def test_a_study_gets_the_general_products_and_none_of_the_paper():
    """A study's eigen-analysis and linear models are its plants' (no grid of tip masses)."""
    cfg = study()
    plants = ["plant_campbell", "plant_mode_shapes", "plant_poles_zeros", "plant_bode"]
    assert list(products_for(cfg)) == ["case", "compare", "beam_properties", *plants]
    del cfg["study"]["comparisons"]
    assert list(products_for(cfg)) == ["case", "beam_properties", *plants]
    assert not set(products_for(cfg)) & set(PAPER_PRODUCTS)
    del cfg["study"]
    assert "campbell" in products_for(cfg) and "plant_campbell" not in products_for(cfg)


def test_a_study_may_ask_for_the_paper_products_too():
    products = products_for(study() | {"products": ["paper"]})
    designs = set(of_kind(GENERAL_PRODUCTS, DESIGNS_FIGURE))  # the study designs no feedback
    control = {"sample_time_sweep", "robustness"}  # nor has a `control` section
    shaping = set(of_kind(GENERAL_PRODUCTS, SHAPING_FIGURE))  # and shapes no command
    grid = {key for key, product in GENERAL_PRODUCTS.items() if "study" in product.unless}  # its plants instead
    assert set(products) == set(PAPER_PRODUCTS) | set(GENERAL_PRODUCTS) - designs - control - shaping - grid


def test_the_figure_of_the_feedback_designs_needs_a_design_run_on_the_truth_or_its_own_model():
    cfg = study()
    assert not set(of_kind(products_for(cfg), DESIGNS_FIGURE))
    # a design run on a third model is neither the truth (CFOAM) nor the design's prediction
    designed = {"model": "FOAM", "maneuver": {"kind": "state_feedback", "design": {"model": "TLAM"}}}
    cfg["cases"]["designed"] = designed
    assert not set(of_kind(products_for(cfg), DESIGNS_FIGURE))
    for model in ("TLAM", "CFOAM"):
        cfg["cases"]["designed"] = designed | {"model": model}
        assert set(of_kind(products_for(cfg), DESIGNS_FIGURE)) == {"controller_trust"}


def test_an_unknown_product_set_is_named_with_what_is_allowed():
    with pytest.raises(ProductError, match=r"^products: got 'papr'; allowed: paper$"):
        products_for(paper() | {"products": ["papr"]})


def test_table2_speed_is_needed_by_the_paper_products_not_by_a_config_without_a_study():
    with pytest.raises(ConfigError, match=r"eigen.table2_speed: missing \(required for the paper's Table 2"):
        check_schema(study() | {"products": ["paper"]})
    cfg = paper()
    del cfg["products"], cfg["eigen"]["table2_speed"]
    check_schema(cfg)


def test_a_product_is_built_only_with_the_keys_it_needs():
    product = Product("x", SIMULATION_FIGURE, "m:f", "X", ours="x", needs=("study.comparisons",))
    assert product.is_built_for({"study": {"comparisons": {}}})
    assert not product.is_built_for({"study": {"name": "s"}})
    assert not product.is_built_for({"study": "not a section"})


def test_two_products_under_one_key_are_an_error():
    other = Product("campbell", SIMULATION_FIGURE, "m:f", "Another", ours="x")
    assert merged(GENERAL_PRODUCTS, PAPER_PRODUCTS)["campbell"] is CAMPBELL
    with pytest.raises(ProductError, match="product key 'campbell' is declared twice"):
        merged(GENERAL_PRODUCTS, {"campbell": other})


# --- one set of rules ----------------------------------------------------------------------------

def snakemake_rules(workdir: Path, *args: str) -> set[str]:
    command = [sys.executable, "-m", "snakemake", "--snakefile", str(REPO / "Snakefile"), "--directory",
               str(workdir), "--list-rules", *args]
    run = subprocess.run(command, cwd=workdir, capture_output=True, text=True, timeout=300, check=False)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    return {line.split()[0] for line in run.stdout.splitlines() if line and not line[0].isspace()}


def test_every_step_is_a_rule_for_the_paper_and_for_a_study(tmp_path):
    """The rules Snakemake knows are the plan's steps, its target rules and `all`, for the paper and
    for a study: the same rule files for both."""
    assert "is_study" not in (REPO / "Snakefile").read_text()
    (tmp_path / "config").mkdir()
    shutil.copy(PAPER_CONFIG, tmp_path / "config" / "config.yaml")
    shutil.copy(STUDY_CONFIG, tmp_path / "study.yaml")
    for args, files in (((), [tmp_path / "config" / "config.yaml"]),
                        (("--configfile", "study.yaml"), [tmp_path / "study.yaml"])):
        with pytest.MonkeyPatch.context() as patch:
            patch.chdir(tmp_path)
            plan = build_plan(yaml.safe_load(files[-1].read_text()), files, REPO)
        expected = {*plan.steps, *plan.target_rules, "all"}
        assert {"simulate", "eigen_campbell", "archive", "sweep"} <= expected
        assert snakemake_rules(tmp_path, *args) == expected, args
