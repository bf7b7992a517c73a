"""Helpers shared by every rule file; the Snakefile includes this file first.

Rules reach the experiment through these helpers: case names for wildcards, the resolved case for
`params:` (so that editing a case reruns exactly that case), and the package sources a rule's
script imports, as inputs (Snakemake watches a script's own mtime, not the modules it imports).
"""

import os
from pathlib import Path

from snakemake.exceptions import WorkflowError

from hubbeam.config import case_names, case_settings
from hubbeam.models import FAMILIES, model, wildcard_pattern
from hubbeam.sourcedeps import script_dependencies
from hubbeam.study import is_study, logs_dir, results_dir

PACKAGE_DIR = Path(workflow.basedir, "src", "hubbeam")
SCRIPTS_DIR = Path(workflow.basedir, "workflow", "scripts")
#: where the generic rules (matrices, simulations) write: results/ and logs/ for the paper,
#: results/<name>/ and logs/<name>/ for a study
RESULTS = results_dir(config)
LOGS = logs_dir(config)


def cases():
    """Names of all configured cases, sorted."""
    return case_names(config)


def case_config(name):
    """The validated case `name` with the `numerics` defaults filled in (a plain dict)."""
    return case_settings(config, name)


def case_params(wildcards):
    """`params:` function: the resolved case of the job's `{case}` wildcard."""
    return case_config(wildcards.case)


def script_code(script, *modules):
    """The package sources workflow/scripts/`script` runs, as inputs relative to the working
    directory: every hubbeam module it imports, transitively, with the package data those modules
    declare (`hubbeam.sourcedeps`), and the `modules` it imports by a name computed at run time
    (e.g. "hubbeam.plotting.fig05")."""
    try:
        files = script_dependencies(SCRIPTS_DIR / script, PACKAGE_DIR, modules)
    except (OSError, ImportError, SyntaxError, ValueError) as error:
        raise WorkflowError(f"script_code({script!r}): {error}") from error
    return [os.path.relpath(path) for path in files]


def simulation_kernel_done(wildcards):
    """Input function of `simulate`: the marker of the compiled kernel of the case's family."""
    family = model(case_config(wildcards.case)["model"]).family
    return f"logs/simulations/kernel_{family}.done"


def simulation_kernels_done(wildcards):
    """Input function of jobs that simulate any model: the markers of every family's kernel."""
    return expand("logs/simulations/kernel_{family}.done", family=FAMILIES)


def simulation_results():
    """One netCDF file per configured case."""
    return expand(f"{RESULTS}/simulations/{{case}}.nc", case=cases())


def final_targets():
    """Every final product of the study, the inputs of the `all` rule (extend as rules are added)."""
    return (
        simulation_results()
        + figure_targets()
        + table_targets()
        + report_targets()
        + sweep_targets()
        + published_validation_results()
        + reading_targets()
        + ["results/hubbeam-results.tar.gz"]
    )


# --- figures, tables, claims and report (rules in figures.smk and report.smk) -------------------

from hubbeam.products import (EIGEN_FIGURE, PAPER_PRODUCTS, SIMULATION_FIGURE, TABLE, of_kind,
                              product_cases)

FIGURE_STYLE = os.path.relpath(PACKAGE_DIR / "plotting" / "hubbeam.mplstyle")
#: the caption file of every product in `snakemake --report`: it prints `params.caption`
PRODUCT_CAPTION = "../report/product.rst"


def product(key):
    """The product `key` of the registry (`hubbeam.products.PAPER_PRODUCTS`)."""
    return PAPER_PRODUCTS[key]


def product_datasets(key):
    """The result files of the cases product `key` reads."""
    return expand("results/simulations/{case}.nc", case=product(key).cases)


def figure_targets():
    """PDF and PNG of every figure of the registry."""
    keys = sorted(of_kind(PAPER_PRODUCTS, SIMULATION_FIGURE, EIGEN_FIGURE))
    return expand("results/figures/{key}.{ext}", key=keys, ext=("pdf", "png"))


def table_keys():
    """Keys of the tables of the registry (`table1`, ...)."""
    return sorted(of_kind(PAPER_PRODUCTS, TABLE))


def table_targets():
    """csv, Markdown and LaTeX of every table (table2.csv itself comes from the eigen rule)."""
    return expand("results/tables/{key}.{ext}", key=table_keys(), ext=("csv", "md", "tex"))


def claim_cases():
    """The runs the claims read: every case of the paper's products."""
    return product_cases(PAPER_PRODUCTS)


def report_targets():
    return [
        "results/report/claims.csv",
        "results/report/reproduction.md",
        "results/report/reproduction.html",
    ]


def archive_inputs(wildcards):
    """Everything the archive bundles: netCDF results (simulations, matrices, eigen-analysis,
    sweeps), figures, tables, the report and the published-table validation (the optional Exudyn
    validation is not bundled)."""
    results = simulation_results() + matrices_results() + eigen_results() + sweep_targets()
    products = (figure_targets() + table_targets() + report_targets() + published_validation_results()
                + reading_targets())
    return sorted(set(results + products))


# --- simulations (rule in simulate.smk) -----------------------------------------------------------


def simulation_matrices(wildcards):
    """The matrices file of the job's case: its tip-mass configuration (rule in matrices.smk)."""
    from hubbeam.matrices import configuration_name
    from hubbeam.parameters import TipMass

    tip = TipMass(**case_config(wildcards.case)["tip_mass"])
    return f"{RESULTS}/matrices/{configuration_name(tip)}.nc"


def simulation_numerics():
    """The `numerics` settings a simulation reads (changing any other one does not rerun it)."""
    from hubbeam.simulate import NUMERICS_KEYS, OPTIONAL_NUMERICS

    return {key: config["numerics"].get(key, default) for key, default in
            {**dict.fromkeys(NUMERICS_KEYS), **OPTIONAL_NUMERICS}.items()}


# --- system matrices (rule in matrices.smk) ------------------------------------------------------


def matrices_configurations():
    """{name: {"mass", "position", "modes"}} over the tip masses of the configured cases."""
    from hubbeam.matrices import configuration_name
    from hubbeam.parameters import TipMass

    configurations = {}
    for case in cases():
        settings = case_config(case)
        tip = TipMass(**settings["tip_mass"])
        if tip.mass == 0.0:
            tip = TipMass(mass=0.0, position=config["beam"]["length"])
        entry = configurations.setdefault(
            configuration_name(tip),
            {"mass": tip.mass, "position": tip.position, "modes": settings["modes"]},
        )
        entry["modes"] = max(entry["modes"], settings["modes"])
    return configurations


def matrices_configuration(wildcards):
    """`params:` function: the tip mass and mode count of the job's `{config_name}`."""
    configurations = matrices_configurations()
    if wildcards.config_name not in configurations:
        raise WorkflowError(
            f"{RESULTS}/matrices/{wildcards.config_name}.nc: unknown configuration "
            f"{wildcards.config_name!r}; allowed: {', '.join(sorted(configurations))}"
        )
    return configurations[wildcards.config_name]


def matrices_results():
    """One netCDF file of system matrices per tip-mass configuration."""
    return expand(f"{RESULTS}/matrices/{{config_name}}.nc", config_name=sorted(matrices_configurations()))


# --- eigen-analysis (rules in eigen.smk) ----------------------------------------------------------


def eigen_results():
    """Every product of the eigen-analysis (netCDF and csv)."""
    return [
        "results/eigen/k22.nc",
        "results/eigen/critical_speeds.nc",
        "results/eigen/campbell.nc",
        "results/tables/critical_speeds.csv",
        "results/tables/table2.csv",
    ]


# --- independent validation (rules in validate.smk, docs/validation.md) --------------------------
# The published-table check (paper only: it validates the paper's beam model against literature
# tables) is part of `all` whenever the config has `validation.published`, and of the reproduction
# report. The optional target `validate` builds, under RESULTS/validation/, the Exudyn comparison
# (when the config has a `validation` section) and the non-uniform checks (always), with their
# report RESULTS/report/validation_exudyn.md/.html.

VALIDATION_DIR = f"{RESULTS}/validation"
VALIDATION_LOGS = f"{LOGS}/validation"
#: the optional modules `validate` imports: pyBModes always, Exudyn for the `validation` section
VALIDATION_MODULES = ("pybmodes", "exudyn")


def validation_config():
    """The `validation` section of the config, or a WorkflowError saying it is missing."""
    if "validation" not in config:
        raise WorkflowError(
            "the Exudyn comparison needs the `validation` section of the config (see "
            "docs/validation.md); the configuration in use has none"
        )
    return config["validation"]


def published_validation_inputs():
    """The products of `validate_published` the reproduction report reads, by input name (none
    for a study or when the config has no `validation.published`)."""
    if is_study(config) or "published" not in config.get("validation", {}):
        return {}
    return {
        "published": f"{VALIDATION_DIR}/published_comparison.csv",
        "tip_mass": f"{VALIDATION_DIR}/tip_mass_comparison.csv",
        "curves": f"{VALIDATION_DIR}/rotating_eigen.nc",
        "published_figure": f"{VALIDATION_DIR}/rotating_frequencies.png",
    }


def published_validation_results():
    """Every product of `validate_published` (none without `validation.published`)."""
    inputs = published_validation_inputs()
    return sorted(inputs.values()) + ([f"{VALIDATION_DIR}/rotating_frequencies.pdf"] if inputs else [])


def validation_cases():
    """Names of the validation cases, sorted."""
    return sorted(validation_config()["cases"])


def named_validation_case(name, key="validation.cases"):
    """The validation case `name`, or a WorkflowError naming the key and the defined cases."""
    cases = validation_config()["cases"]
    if name not in cases:
        raise WorkflowError(
            f"{key}: validation case {name!r} is not defined; defined: {', '.join(sorted(cases))}"
        )
    return cases[name]


def validation_case(wildcards):
    """`params:` function: the validation case of the job's `{vcase}` wildcard."""
    return named_validation_case(wildcards.vcase)


def validation_case_files(wildcards):
    """Input function: the comparison file of every validation case."""
    return expand(f"{VALIDATION_DIR}/exudyn_{{vcase}}.nc", vcase=validation_cases())


def validation_reference_files(wildcards):
    """Input function: the Exudyn run of every validation case."""
    return expand(f"{VALIDATION_DIR}/runs/exudyn_{{vcase}}.nc", vcase=validation_cases())


def validation_section(key):
    """`params:` function returning `validation.<key>` (evaluated only for validation jobs)."""
    return lambda wildcards: validation_config()[key]


def convergence_case(wildcards):
    """`params:` function: the case the Exudyn convergence study runs."""
    return named_validation_case(
        validation_config()["convergence"]["case"], key="validation.convergence.case"
    )


def nonuniform_results():
    """The tables of the non-uniform checks (rule validate_nonuniform) by input name: Ritz
    against our finite elements always, pyBModes for a beam off the hub axis (it needs rA > 0)."""
    results = {"ritz_fe": f"{VALIDATION_DIR}/nonuniform_ritz_fe.csv"}
    if config["beam"]["hub_radius"] > 0.0:
        results["pybmodes"] = f"{VALIDATION_DIR}/nonuniform_pybmodes.csv"
    return results


def exudyn_report_inputs():
    """The Exudyn products the validation report reads, by input name (none without a
    `validation` section)."""
    if "validation" not in config:
        return {}
    return {
        "comparison": f"{VALIDATION_DIR}/exudyn_comparison.csv",
        "figure": f"{VALIDATION_DIR}/exudyn_comparison.png",
        "mode_study": f"{VALIDATION_DIR}/exudyn_mode_study.csv",
        "convergence": f"{VALIDATION_DIR}/exudyn_convergence.csv",
    }


def validation_report_results():
    return [f"{RESULTS}/report/validation_exudyn.md", f"{RESULTS}/report/validation_exudyn.html"]


def validation_targets(wildcards):
    """Inputs of `validate`; stops with an install hint when an optional module it needs is not
    importable."""
    import importlib.util

    needed = VALIDATION_MODULES if "validation" in config else VALIDATION_MODULES[:1]
    missing = [module for module in needed if importlib.util.find_spec(module) is None]
    if missing:
        raise WorkflowError(
            f"`snakemake validate` needs the optional dependencies {', '.join(needed)}; not "
            f"installed in this environment: {', '.join(missing)}. Install the extra with "
            "`pip install -e .[validation]` (from the repository root), then rerun "
            "`snakemake validate`"
        )
    exudyn = []
    if "validation" in config:
        exudyn = [
            f"{VALIDATION_DIR}/exudyn_comparison.pdf",
            f"{VALIDATION_DIR}/exudyn_convergence.nc",
            *exudyn_report_inputs().values(),
            *validation_case_files(wildcards),
        ]
    return (
        published_validation_results()
        + exudyn
        + list(nonuniform_results().values())
        + validation_report_results()
    )


# --- parameter sweeps (rules in sweeps.smk) ------------------------------------------------------


def sweeps():
    """Names of the configured parameter sweeps (`sweeps.maps`), sorted; none without `sweeps`."""
    from hubbeam.sweep import sweep_names

    return sweep_names(config)


def sweep_params(wildcards):
    """`params:` function: the resolved sweep of the job's `{sweep}` wildcard."""
    from hubbeam.sweep import sweep_settings

    return sweep_settings(config, wildcards.sweep)


def sweep_chunks(wildcards):
    """Input function of `sweep`: the chunk files of the job's `{sweep}` wildcard."""
    from hubbeam.sweep import n_chunks

    count = n_chunks(sweep_params(wildcards))
    return expand(f"results/sweeps/chunks/{wildcards.sweep}/{{chunk}}.nc", chunk=range(count))


def sweep_targets(in_all=True):
    """The netCDF result and the figure (PDF and PNG) of every sweep whose `in_all` is `in_all`
    (the maps of `all`, or the large ones of `large_sweeps`)."""
    from hubbeam.sweep import sweep_settings

    names = [name for name in sweeps() if sweep_settings(config, name)["in_all"] == in_all]
    return expand("results/sweeps/{sweep}.nc", sweep=names) + expand(
        "results/figures/sweep_{sweep}.{ext}", sweep=names, ext=("pdf", "png")
    )


# --- alternative readings (rules in readings.smk) ------------------------------------------------


def reading_names():
    """Names of the configured readings (`readings`), in config order; none without the section."""
    return list(config.get("readings", {}))


def reading_targets():
    """The claims x readings matrix (none without a `readings` section)."""
    return ["results/readings/readings.csv", "results/readings/readings.nc"] if reading_names() else []


def reading_inputs():
    """The matrix the reproduction report reads, by input name (none without `readings`)."""
    return {"readings": "results/readings/readings.csv"} if reading_names() else {}


def _reading_cases(name):
    from hubbeam.readings import ReadingError, reading_cases

    if name not in config.get("readings", {}):
        raise WorkflowError(f"results/readings/claims/{name}.csv: unknown reading {name!r}; "
                            f"allowed: {', '.join(reading_names()) or 'none configured'}")
    try:
        return reading_cases(config, name)
    except ReadingError as error:
        raise WorkflowError(str(error)) from error


def reading_base_cases(wildcards):
    """The default runs the job's reading reads (its claims' products), sorted."""
    return sorted(_reading_cases(wildcards.reading))


def reading_generated_cases(wildcards):
    """`params:` function: the generated cases of the job's reading (editing one reruns it)."""
    return {base: case for base, case in _reading_cases(wildcards.reading).items() if case is not None}
