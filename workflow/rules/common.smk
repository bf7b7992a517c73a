"""Helpers shared by every rule file; the Snakefile includes this file first.

Rules reach the experiment through these helpers: case names for wildcards, the resolved case for
`params:` (so that editing a case reruns exactly that case), and the package sources a rule runs,
as inputs (Snakemake watches a script's own mtime, not the modules it imports).
"""

import os
from pathlib import Path

from snakemake.exceptions import WorkflowError

from hubbeam.config import case_names, case_settings

PACKAGE_DIR = Path(workflow.basedir, "src", "hubbeam")


def cases():
    """Names of all configured cases, sorted."""
    return case_names(config)


def case_config(name):
    """The validated case `name` with the `numerics` defaults filled in (a plain dict)."""
    return case_settings(config, name)


def case_params(wildcards):
    """`params:` function: the resolved case of the job's `{case}` wildcard."""
    return case_config(wildcards.case)


def hubbeam_sources(*parts):
    """The `.py` files of the package a rule runs, as inputs relative to the working directory.

    `parts` are modules or subpackages under src/hubbeam (e.g. "core", "simulate.py"); no part
    means the whole package.
    """
    roots = [PACKAGE_DIR / part for part in parts] or [PACKAGE_DIR]
    files = set()
    for root in roots:
        if root.is_dir():
            files.update(root.rglob("*.py"))
        elif root.is_file():
            files.add(root)
        else:
            raise WorkflowError(f"hubbeam_sources: {root} does not exist")
    return sorted(os.path.relpath(path) for path in files)


def simulation_results():
    """One netCDF file per configured case."""
    return expand("results/simulations/{case}.nc", case=cases())


def final_targets():
    """Every final product of the study, the inputs of the `all` rule (extend as rules are added)."""
    return (
        simulation_results()
        + figure_targets()
        + table_targets()
        + report_targets()
        + ["results/hubbeam-results.tar.gz"]
    )


# --- figures, tables, claims and report (rules in figures.smk and report.smk) -------------------

from hubbeam.plotting import SIMULATION_FIGURES
from hubbeam.plotting.figures import cases_for

FIGURE_STYLE = os.path.relpath(PACKAGE_DIR / "plotting" / "hubbeam.mplstyle")
CRITICAL_SPEEDS_NC = "results/eigen/critical_speeds.nc"
#: figures of the eigen-analysis: key -> (plotting module, {plot() keyword: result file})
EIGEN_FIGURES = {
    "fig09": ("fig09", {"k22": "results/eigen/k22.nc", "critical": CRITICAL_SPEEDS_NC}),
    "campbell": ("campbell", {"campbell": "results/eigen/campbell.nc", "critical": CRITICAL_SPEEDS_NC}),
    "critical_map": ("critical_map", {"critical": CRITICAL_SPEEDS_NC}),
}
PAPER_FIGURES = ("fig03", "fig04", "fig05", "fig06", "fig07", "fig08", "fig09", "fig10")
#: figure and table groups whose runs the claims read
CLAIM_GROUPS = ("fig03", "fig04", "fig05", "fig06", "fig08", "fig10", "table3")


def figure_cases(key):
    """Case names drawn on figure (or table) `key`: the configured cases named with its prefix
    (`hubbeam.plotting.figures.FIGURE_CASE_PREFIXES`)."""
    return cases_for(key, cases())


def figure_datasets(key):
    return expand("results/simulations/{case}.nc", case=figure_cases(key))


def figure_code(module, *extra):
    """The package sources a figure's drawing depends on (inputs, so that edits rerun it)."""
    base = ("plotting/__init__.py", "plotting/figures.py", "plotting/style.py", "io.py")
    return hubbeam_sources(*base, f"plotting/{module}.py", *extra)


def figure_category(key):
    return "Figures of the paper" if key in PAPER_FIGURES else "Beyond the paper"


def figure_targets():
    """PDF and PNG of every figure."""
    keys = sorted(SIMULATION_FIGURES) + sorted(EIGEN_FIGURES)
    return expand("results/figures/{key}.{ext}", key=keys, ext=("pdf", "png"))


def table_targets():
    """csv, Markdown and LaTeX of Tables 1-3 (table2.csv itself comes from the eigen rule)."""
    return expand("results/tables/table{i}.{ext}", i=(1, 2, 3), ext=("csv", "md", "tex"))


def used_tip_masses():
    return sorted({case_config(case)["tip_mass"]["mass"] for case in cases()})


def claim_cases():
    return sorted({case for key in CLAIM_GROUPS for case in figure_cases(key)})


def report_targets():
    return [
        "results/report/claims.csv",
        "results/report/reproduction.md",
        "results/report/reproduction.html",
    ]


def archive_inputs(wildcards):
    """Everything the archive bundles: netCDF results, figures, tables and the report."""
    netcdf = simulation_results() + matrices_results()
    netcdf += [path for path in eigen_results() if path.endswith(".nc")]
    return sorted(set(netcdf + figure_targets() + table_targets() + report_targets()))


# --- simulations (rule in simulate.smk) -----------------------------------------------------------


def simulation_matrices(wildcards):
    """The matrices file of the job's case: its tip-mass configuration (rule in matrices.smk)."""
    from hubbeam.matrices import configuration_name
    from hubbeam.parameters import TipMass

    tip = TipMass(**case_config(wildcards.case)["tip_mass"])
    return f"results/matrices/{configuration_name(tip)}.nc"


def simulation_numerics():
    """The `numerics` settings a simulation reads (changing any other one does not rerun it)."""
    from hubbeam.simulate import NUMERICS_KEYS

    return {key: config["numerics"][key] for key in NUMERICS_KEYS}
