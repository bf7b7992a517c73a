"""Products of a study (a config with a `study` section, docs/studies.md), all under RESULTS =
results/<name>/: the simulations and matrices (generic rules, simulate.smk and matrices.smk), a
figure per case, the comparison figures of `study.comparisons`, the eigen-analysis of the study's
beam (Campbell diagram, critical speeds over tip mass and position), the beam itself (its properties
along the span and its first mode shapes), the study report (Markdown, HTML, summary.csv) and the
archive <name>-results.tar.gz with its SHA-256 manifest.
"""

STUDY_NAME = config["study"]["name"]
#: the drawing modules study_figure.py imports by name
STUDY_FIGURE_MODULES = ("hubbeam.plotting.case_figure", "hubbeam.plotting.comparison")
#: eigen figure -> (plotting module, {plot() keyword: eigen result})
STUDY_EIGEN_FIGURES = {
    "campbell": ("campbell", {"campbell": f"{RESULTS}/eigen/campbell.nc",
                              "critical": f"{RESULTS}/eigen/critical_speeds.nc"}),
    "critical_speeds": ("study_critical", {"critical": f"{RESULTS}/eigen/critical_speeds.nc"}),
    "beam_properties": ("beam_properties", {"beam": f"{RESULTS}/eigen/beam.nc"}),
    "mode_shapes": ("mode_shapes", {"beam": f"{RESULTS}/eigen/beam.nc"}),
}
#: transverse mode shapes the study report shows
STUDY_MODE_SHAPES = 3
STUDY_EIGEN_MODULES = tuple(f"hubbeam.plotting.{module}" for module, _ in STUDY_EIGEN_FIGURES.values())


def study_comparisons():
    """{comparison name: [case, ...]} of `study.comparisons` (none by default)."""
    return dict(config["study"].get("comparisons", {}))


def comparison_inputs(wildcards):
    """Input function: the simulations a comparison overlays, by case name."""
    comparisons = study_comparisons()
    if wildcards.comparison not in comparisons:
        raise WorkflowError(
            f"{RESULTS}/figures/compare_{wildcards.comparison}.pdf: unknown comparison "
            f"{wildcards.comparison!r}; defined in study.comparisons: {', '.join(sorted(comparisons))}"
        )
    return {case: f"{RESULTS}/simulations/{case}.nc" for case in comparisons[wildcards.comparison]}


def study_figures(ext):
    """{name: path} of every study figure with extension `ext`: per case, per comparison, eigen."""
    figures = {f"case_{case}": f"{RESULTS}/figures/case_{case}.{ext}" for case in cases()}
    figures |= {f"compare_{name}": f"{RESULTS}/figures/compare_{name}.{ext}" for name in study_comparisons()}
    return figures | {key: f"{RESULTS}/figures/{key}.{ext}" for key in STUDY_EIGEN_FIGURES}


def study_eigen_results():
    return [f"{RESULTS}/eigen/campbell.nc", f"{RESULTS}/eigen/critical_speeds.nc", f"{RESULTS}/eigen/beam.nc"]


def study_report_results():
    return [f"{RESULTS}/report/{name}" for name in ("report.md", "report.html", "summary.csv")]


def study_products():
    """Everything the study builds except its archive."""
    figures = [*study_figures("pdf").values(), *study_figures("png").values()]
    return sorted(simulation_results() + matrices_results() + study_eigen_results() + figures
                  + study_report_results())


def study_targets():
    """The inputs of `all` for a study: every product and the archive."""
    return study_products() + [f"{RESULTS}/{STUDY_NAME}-results.tar.gz"]


wildcard_constraints:
    comparison=CASE_NAME_PATTERN,
    eigen_figure="|".join(STUDY_EIGEN_FIGURES),


rule study_eigen:
    input:
        code=script_code("study_eigen.py"),
    output:
        campbell=ensure(f"{RESULTS}/eigen/campbell.nc", non_empty=True),
        critical=ensure(f"{RESULTS}/eigen/critical_speeds.nc", non_empty=True),
    params:
        beam=config["beam"],
        tip_masses=config["eigen"]["tip_masses"],
        positions=config["eigen"]["positions"],
        speeds=config["eigen"]["speeds"],
        search_max=config["eigen"]["critical_speed_search_max"],
        n_modes=config["numerics"]["modes"],
        n_quad=config["numerics"]["quadrature_points"],
    log:
        f"{LOGS}/eigen/study_eigen.log",
    script:
        "../scripts/study_eigen.py"


rule study_beam:
    input:
        code=script_code("study_beam.py"),
    output:
        beam=ensure(f"{RESULTS}/eigen/beam.nc", non_empty=True),
    params:
        beam=config["beam"],
        tips={case: case_config(case)["tip_mass"] for case in cases()},
        speeds=[0.0, config["eigen"]["speeds"]["stop"]],
        tip_masses=config["eigen"]["tip_masses"],
        n_shapes=STUDY_MODE_SHAPES,
        n_modes=config["numerics"]["modes"],
        n_quad=config["numerics"]["quadrature_points"],
    log:
        f"{LOGS}/eigen/study_beam.log",
    script:
        "../scripts/study_beam.py"


rule study_case_figure:
    localrule: True
    input:
        simulation=f"{RESULTS}/simulations/{{case}}.nc",
        code=script_code("study_figure.py", *STUDY_FIGURE_MODULES),
    output:
        pdf=f"{RESULTS}/figures/case_{{case}}.pdf",
        png=f"{RESULTS}/figures/case_{{case}}.png",
    params:
        module="case_figure",
        name=lambda wildcards: wildcards.case,
    log:
        f"{LOGS}/figures/case_{{case}}.log",
    script:
        "../scripts/study_figure.py"


rule study_comparison_figure:
    localrule: True
    input:
        unpack(comparison_inputs),
        code=script_code("study_figure.py", *STUDY_FIGURE_MODULES),
    output:
        pdf=f"{RESULTS}/figures/compare_{{comparison}}.pdf",
        png=f"{RESULTS}/figures/compare_{{comparison}}.png",
    params:
        module="comparison",
        name=lambda wildcards: wildcards.comparison,
    log:
        f"{LOGS}/figures/compare_{{comparison}}.log",
    script:
        "../scripts/study_figure.py"


rule study_eigen_figure:
    localrule: True
    input:
        unpack(lambda wildcards: STUDY_EIGEN_FIGURES[wildcards.eigen_figure][1]),
        code=script_code("figure_eigen.py", *STUDY_EIGEN_MODULES),
    output:
        pdf=f"{RESULTS}/figures/{{eigen_figure}}.pdf",
        png=f"{RESULTS}/figures/{{eigen_figure}}.png",
    params:
        function=lambda wildcards: f"hubbeam.plotting.{STUDY_EIGEN_FIGURES[wildcards.eigen_figure][0]}:plot",
    log:
        f"{LOGS}/figures/{{eigen_figure}}.log",
    script:
        "../scripts/figure_eigen.py"


rule study_report:
    localrule: True
    input:
        simulations=simulation_results(),
        figures=list(study_figures("png").values()),
        code=script_code("study_report.py"),
    output:
        markdown=f"{RESULTS}/report/report.md",
        html=f"{RESULTS}/report/report.html",
        summary=f"{RESULTS}/report/summary.csv",
    params:
        study=config["study"],
        beam=config["beam"],
        cases=cases(),
        figures=study_figures("png"),
    log:
        f"{LOGS}/report/report.log",
    script:
        "../scripts/study_report.py"


rule study_archive:
    localrule: True
    input:
        study_products(),
    output:
        ensure(f"{RESULTS}/{STUDY_NAME}-results.tar.gz", non_empty=True),
    params:
        config=config,
        top=f"{STUDY_NAME}-results",
        root=RESULTS,
        workflow_root=workflow.basedir,
    log:
        f"{LOGS}/report/archive.log",
    script:
        "../scripts/archive.py"
