"""Helpers shared by every rule file; the Snakefile includes this file first.

Rules reach the experiment through these helpers: case names for wildcards, the resolved case for
`params:` (so that editing a case reruns exactly that case), and the package sources a rule's
script imports, as inputs (Snakemake watches a script's own mtime, not the modules it imports).
Every path comes from `PATHS` (hubbeam.results.paths: results/ and logs/ for the paper, results/<name>/
and logs/<name>/ for a study; `SHARED` for the compiled kernels' markers), every figure and table
from `PRODUCTS`, the configuration's products (hubbeam.reporting.products.products_for).
"""

import os
from pathlib import Path

from snakemake.exceptions import WorkflowError

from hubbeam.model.models import FAMILIES, model, wildcard_pattern
from hubbeam.results.paths import FIGURE_FORMATS, SHARED, TABLE_FORMATS, study_paths
from hubbeam.reporting.products import (CASE_FIGURE, COMPARISON_FIGURE, DESIGNS_FIGURE, EIGEN_FIGURE, PAPER,
                                        PAPER_PRODUCTS, SIMULATION_FIGURE, TABLE, designed_cases, of_kind,
                                        product_cases, product_sets, products_for)
from hubbeam.reporting.sourcedeps import script_dependencies

PACKAGE_DIR = Path(workflow.basedir, "src", "hubbeam")
SCRIPTS_DIR = Path(workflow.basedir, "workflow", "scripts")
#: where this configuration's results and logs go
PATHS = study_paths(config)
#: the checked configuration as objects (the Snakefile's `SETTINGS`): what the jobs take
#: the figures and tables of this configuration
PRODUCTS = products_for(config)
#: the paper's own products (Tables 1-3, Figs. 3-10, claims, reproduction report) are asked for
WITH_PAPER = PAPER in product_sets(config)
#: the kernel families, each compiled once (hubbeam.model.models)
FAMILY_PATTERN = wildcard_pattern(FAMILIES)


def cases():
    """Names of all configured cases, sorted."""
    return list(SETTINGS.cases)


def case_params(wildcards):
    """`params:` function: the resolved case of the job's `{case}` wildcard (a `Case`)."""
    return SETTINGS.case(wildcards.case)


def fingerprint(*values):
    """A `params:` entry that makes Snakemake rerun a job when the settings objects it takes
    change: Snakemake compares only built-in values, so the objects' `repr` (complete: every field,
    floats written exactly) stands for them."""
    return lambda wildcards: repr(tuple(value(wildcards) if callable(value) else value for value in values))


def script_code(script, *modules):
    """The package sources workflow/scripts/`script` runs, as inputs relative to the working
    directory: every hubbeam module it imports, transitively, with the package data those modules
    declare (`hubbeam.reporting.sourcedeps`), and the `modules` it imports by a name computed at run time
    (e.g. "hubbeam.plotting.fig05")."""
    try:
        files = script_dependencies(SCRIPTS_DIR / script, PACKAGE_DIR, modules)
    except (OSError, ImportError, SyntaxError, ValueError) as error:
        raise WorkflowError(f"script_code({script!r}): {error}") from error
    return [os.path.relpath(path) for path in files]


#: the marker of a family's compiled kernel (shared by every configuration)
KERNEL_DONE = SHARED.log("simulations", "kernel_{family}.done")


def simulation_kernel_done(wildcards):
    """Input function of `simulate`: the marker of the compiled kernel of the case's family."""
    return KERNEL_DONE.format(family=model(case_params(wildcards).model).family)


def simulation_kernels_done(wildcards):
    """Input function of jobs that simulate any model: the markers of every family's kernel."""
    return expand(KERNEL_DONE, family=FAMILIES)


def simulation_results():
    """One netCDF file per configured case."""
    return [PATHS.simulation(case) for case in cases()]


def all_targets():
    """The inputs of the `all` rule: every product of the configuration and its archive."""
    return archive_inputs(None) + [PATHS.archive()]


# --- figures, tables, claims and report (rules in figures.smk, study.smk and report.smk) --------

FIGURE_STYLE = os.path.relpath(PACKAGE_DIR / "plotting" / "hubbeam.mplstyle")
#: the caption file of every product in `snakemake --report`: it prints `params.caption`
PRODUCT_CAPTION = "../report/product.rst"


def product(key):
    """The paper's product `key` (`hubbeam.reporting.products.PAPER_PRODUCTS`)."""
    return PAPER_PRODUCTS[key]


def product_datasets(key):
    """The result files of the cases product `key` reads."""
    return [PATHS.simulation(case) for case in product(key).cases]


def product_files(product):
    """{keyword: path} of the result files `product` reads, in this configuration's folder."""
    return {name: PATHS.result(path) for name, path in product.files.items()}


def study_comparisons():
    """{comparison name: [case, ...]} of `study.comparisons` (none without it)."""
    return dict(config.get("study", {}).get("comparisons", {}))


def designed_results(wildcards=None):
    """Input function: the simulations whose state feedback is designed, by case name."""
    return {case: PATHS.simulation(case) for case in designed_cases(config)}


def figure_names(key, product):
    """The figure names of `product`: its key, or one `<key>_<name>` per case or comparison."""
    names = {CASE_FIGURE: cases(), COMPARISON_FIGURE: sorted(study_comparisons())}.get(product.kind)
    return [key] if names is None else [f"{key}_{name}" for name in names]


def figures(ext):
    """{name: path} of every figure of the configuration in the format `ext`."""
    return {name: PATHS.figure(name, ext) for key, product in PRODUCTS.items() if product.is_figure
            for name in figure_names(key, product)}


def figure_targets():
    """PDF and PNG of every figure of the configuration."""
    return sorted(path for ext in FIGURE_FORMATS for path in figures(ext).values())


def table_keys():
    """Keys of the tables of the configuration (`table1`, ...)."""
    return sorted(of_kind(PRODUCTS, TABLE))


def table_targets():
    """csv, Markdown and LaTeX of every table (table2.csv itself comes from the eigen rule)."""
    return [PATHS.table(key, ext) for key in table_keys() for ext in TABLE_FORMATS]


def claim_cases():
    """The runs the claims read: every case of the paper's products."""
    return product_cases(PAPER_PRODUCTS)


#: the tables of the eigen-analysis the claims read besides the runs, by input name
CLAIM_TABLES = {"table2": PATHS.table("table2", "csv"),
                "critical_speeds": PATHS.table("critical_speeds", "csv")}
#: the files of the study report (rules in study.smk), by output name
STUDY_REPORT = {"markdown": PATHS.report("report.md"), "html": PATHS.report("report.html"),
                "summary": PATHS.report("summary.csv")}


def report_targets():
    """The reports the configuration asks for: the claims and the reproduction report with the
    paper's products, the study report with a `study` section (its title, description and
    comparisons)."""
    paper = [PATHS.report(name) for name in ("claims.csv", "reproduction.md", "reproduction.html")]
    return (paper if WITH_PAPER else []) + (list(STUDY_REPORT.values()) if "study" in config else [])


def linear_model_exports():
    """One `[tip-mass index, model, hub, netCDF, MATLAB]` per exported set of linear models (rule
    in linear.smk): every model and hub condition at every tip mass of `linear.tip_masses`."""
    from hubbeam.linear.statespace import HUBS
    from hubbeam.model.models import MODELS

    return [[k, model, hub, *(PATHS.linear(f"models/{model}_{hub}_tip{k}", ext) for ext in ("nc", "mat"))]
            for k in range(len(config["linear"]["tip_masses"])) for model in MODELS for hub in HUBS]


def linear_model_files():
    """The files of the exported linear models (netCDF and MATLAB)."""
    return [path for entry in linear_model_exports() for path in entry[3:]]


def archive_inputs(wildcards):
    """Everything the archive bundles: netCDF results (simulations, matrices, eigen-analysis,
    sweeps), figures, tables, the reports and the published-table validation (the optional Exudyn
    validation is not bundled)."""
    results = (simulation_results() + matrices_results() + eigen_results() + sweep_targets()
               + linear_model_files())
    products = (figure_targets() + table_targets() + report_targets() + published_validation_results()
                + reading_targets())
    return sorted(set(results + products))


# --- simulations (rule in simulate.smk) -----------------------------------------------------------


def simulation_matrices(wildcards):
    """The matrices file of the job's case: its tip-mass configuration (rule in matrices.smk)."""
    from hubbeam.model.matrices import configuration_name

    return PATHS.matrices(configuration_name(case_params(wildcards).tip_mass))


# --- system matrices (rule in matrices.smk) ------------------------------------------------------


def matrices_configurations():
    """{name: {"mass", "position", "inertia", "offset", "modes"}} over the tip masses (or bodies) of the
    configured cases."""
    from hubbeam.model.matrices import configuration_name
    from hubbeam.model.parameters import TipMass

    configurations = {}
    for case in SETTINGS.cases.values():
        tip = case.tip_mass
        if tip.mass == 0.0 and tip.is_point:
            tip = TipMass(mass=0.0, position=config["beam"]["length"])
        entry = configurations.setdefault(
            configuration_name(tip),
            {"mass": tip.mass, "position": tip.position, "inertia": tip.inertia, "offset": tip.offset,
             "modes": case.modes},
        )
        entry["modes"] = max(entry["modes"], case.modes)
    return configurations


def matrices_configuration(wildcards):
    """`params:` function: the tip mass and mode count of the job's `{config_name}`."""
    configurations = matrices_configurations()
    if wildcards.config_name not in configurations:
        raise WorkflowError(
            f"{PATHS.matrices(wildcards.config_name)}: unknown configuration "
            f"{wildcards.config_name!r}; allowed: {', '.join(sorted(configurations))}"
        )
    return configurations[wildcards.config_name]


def matrices_results():
    """One netCDF file of system matrices per tip-mass configuration."""
    return [PATHS.matrices(name) for name in sorted(matrices_configurations())]


# --- eigen-analysis (rules in eigen.smk) ----------------------------------------------------------


def eigen_results():
    """The results of the eigen-analysis (netCDF and csv) the products and the claims read."""
    read = {path for product in PRODUCTS.values() for path in product_files(product).values()}
    return sorted(read | (set(CLAIM_TABLES.values()) if WITH_PAPER else set()))


# --- independent validation (rules in validate.smk, docs/validation.md) --------------------------
# The published-table check (it validates the beam model against literature tables of uniform
# cantilevers, not a study's beam) is one of the paper's products: with `validation.published`, part
# of `all` and of the reproduction report. The optional target `validate` builds, under validation/ of the results folder, the
# Exudyn comparison (when the config has a `validation` section) and the non-uniform checks
# (always), with their report report/validation_exudyn.md/.html.

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
    without the paper's products or without `validation.published`)."""
    if not WITH_PAPER or "published" not in config.get("validation", {}):
        return {}
    return {
        "published": PATHS.validation("published_comparison.csv"),
        "tip_mass": PATHS.validation("tip_mass_comparison.csv"),
        "curves": PATHS.validation("rotating_eigen.nc"),
        "published_figure": PATHS.validation("rotating_frequencies.png"),
    }


def published_validation_results():
    """Every product of `validate_published` (none without `validation.published`)."""
    inputs = published_validation_inputs()
    return sorted(inputs.values()) + ([PATHS.validation("rotating_frequencies.pdf")] if inputs else [])


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
    return [PATHS.validation(f"exudyn_{vcase}.nc") for vcase in validation_cases()]


def validation_reference_files(wildcards):
    """Input function: the Exudyn run of every validation case."""
    return [PATHS.validation(f"runs/exudyn_{vcase}.nc") for vcase in validation_cases()]


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
    results = {"ritz_fe": PATHS.validation("nonuniform_ritz_fe.csv")}
    if config["beam"]["hub_radius"] > 0.0:
        results["pybmodes"] = PATHS.validation("nonuniform_pybmodes.csv")
    return results


def exudyn_report_inputs():
    """The Exudyn products the validation report reads, by input name (none without a
    `validation` section)."""
    if "validation" not in config:
        return {}
    return {
        "comparison": PATHS.validation("exudyn_comparison.csv"),
        "figure": PATHS.validation("exudyn_comparison.png"),
        "mode_study": PATHS.validation("exudyn_mode_study.csv"),
        "convergence": PATHS.validation("exudyn_convergence.csv"),
    }


def validation_report_results():
    return [PATHS.report("validation_exudyn.md"), PATHS.report("validation_exudyn.html")]


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
            PATHS.validation("exudyn_comparison.pdf"),
            PATHS.validation("exudyn_convergence.nc"),
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
    from hubbeam.simulation.sweep import sweep_names

    return sweep_names(config)


def sweep_params(wildcards):
    """`params:` function: the resolved sweep of the job's `{sweep}` wildcard."""
    from hubbeam.simulation.sweep import sweep_settings

    return sweep_settings(config, wildcards.sweep)


def sweep_chunks(wildcards):
    """Input function of `sweep`: the chunk files of the job's `{sweep}` wildcard."""
    from hubbeam.simulation.sweep import n_chunks

    count = n_chunks(sweep_params(wildcards))
    return [PATHS.sweep_chunk(wildcards.sweep, str(chunk)) for chunk in range(count)]


def sweep_targets(in_all=True):
    """The netCDF result and the figure (PDF and PNG) of every sweep whose `in_all` is `in_all`
    (the maps of `all`, or the large ones of `large_sweeps`)."""
    from hubbeam.simulation.sweep import sweep_settings

    names = [name for name in sweeps() if sweep_settings(config, name)["in_all"] == in_all]
    return [PATHS.sweep(name) for name in names] + [
        PATHS.figure(f"sweep_{name}", ext) for name in names for ext in FIGURE_FORMATS]


# --- alternative readings (rules in readings.smk) ------------------------------------------------


def reading_names():
    """Names of the configured readings (`readings`), in config order; none without the section
    or without the paper's products (a reading recomputes the paper's claims)."""
    return list(config.get("readings", {})) if WITH_PAPER else []


def reading_targets():
    """The claims x readings matrix (none without a `readings` section)."""
    return [PATHS.readings("csv"), PATHS.readings("nc")] if reading_names() else []


def reading_inputs():
    """The matrix the reproduction report reads, by input name (none without `readings`)."""
    return {"readings": PATHS.readings("csv")} if reading_names() else {}


def _reading_runs():
    """{reading: its runs (hubbeam.paper.readings.ReadingRuns)}, each reading checked and its
    generated cases built once, when the workflow is read."""
    from hubbeam.paper.readings import ReadingError, reading_runs

    try:
        return {name: reading_runs(SETTINGS, name, config["readings"][name]) for name in reading_names()}
    except (ReadingError, ConfigError) as error:
        raise WorkflowError(str(error)) from None


#: the runs of every reading
READING_RUNS = _reading_runs()


def reading_params(wildcards):
    """`params:` function: the runs of the job's reading (`ReadingRuns`)."""
    if wildcards.reading not in READING_RUNS:
        raise WorkflowError(f"{PATHS.reading(wildcards.reading)}: unknown reading {wildcards.reading!r}; "
                            f"allowed: {', '.join(reading_names()) or 'none configured'}")
    return READING_RUNS[wildcards.reading]


def reading_base_cases(wildcards):
    """The default runs the job's reading reads (its claims' products), sorted."""
    return sorted(reading_params(wildcards).bases)
