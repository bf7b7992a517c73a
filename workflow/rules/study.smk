"""The study report and its figures per case, per comparison and of the feedback designs
(products of kinds "figure per case", "figure per comparison" and "figure of the feedback
designs" of the registry, `PRODUCTS` in common.smk): built for a configuration with a `study` section (docs/studies.md), under its results folder results/<name>/.

The study report (Markdown, HTML, summary.csv) shows a figure per case, the comparison figures of
`study.comparisons` and every eigen-analysis figure of the configuration's products (the Campbell
diagram, the critical speeds), each drawn by the rules of figures.smk; the simulations, matrices,
eigen-analysis and archive come from the rules every configuration shares.
"""


wildcard_constraints:
    comparison=CASE_NAME_PATTERN,


def comparison_inputs(wildcards):
    """Input function: the simulations a comparison overlays, by case name."""
    comparisons = study_comparisons()
    if wildcards.comparison not in comparisons:
        raise WorkflowError(
            f"{PATHS.figure(f'compare_{wildcards.comparison}', 'pdf')}: unknown comparison "
            f"{wildcards.comparison!r}; defined in study.comparisons: {', '.join(sorted(comparisons))}"
        )
    return {case: PATHS.simulation(case) for case in comparisons[wildcards.comparison]}


for _key, _product in of_kind(PRODUCTS, CASE_FIGURE).items():

    rule:
        name:
            f"figure_{_key}"
        localrule: True
        input:
            simulation=PATHS.simulation("{case}"),
            code=script_code("study_figure.py", _product.module),
        output:
            pdf=ensure(PATHS.figure(f"{_key}_{{case}}", "pdf"), non_empty=True),
            png=report(
                ensure(PATHS.figure(f"{_key}_{{case}}", "png"), non_empty=True),
                caption=PRODUCT_CAPTION,
                category=_product.category,
            ),
        params:
            function=_product.function,
            caption=_product.caption(),
            per_case=True,
            name=lambda wildcards: wildcards.case,
        log:
            PATHS.log("figures", f"{_key}_{{case}}.log"),
        script:
            "../scripts/study_figure.py"


for _key, _product in of_kind(PRODUCTS, COMPARISON_FIGURE).items():

    rule:
        name:
            f"figure_{_key}"
        localrule: True
        input:
            unpack(comparison_inputs),
            code=script_code("study_figure.py", _product.module),
        output:
            pdf=ensure(PATHS.figure(f"{_key}_{{comparison}}", "pdf"), non_empty=True),
            png=report(
                ensure(PATHS.figure(f"{_key}_{{comparison}}", "png"), non_empty=True),
                caption=PRODUCT_CAPTION,
                category=_product.category,
            ),
        params:
            function=_product.function,
            caption=_product.caption(),
            per_case=False,
            name=lambda wildcards: wildcards.comparison,
        log:
            PATHS.log("figures", f"{_key}_{{comparison}}.log"),
        script:
            "../scripts/study_figure.py"


for _key, _product in of_kind(PRODUCTS, DESIGNS_FIGURE).items():

    rule:
        name:
            f"figure_{_key}"
        localrule: True
        input:
            unpack(designed_results),
            code=script_code("study_figure.py", _product.module),
        output:
            pdf=ensure(PATHS.figure(_key, "pdf"), non_empty=True),
            png=report(
                ensure(PATHS.figure(_key, "png"), non_empty=True),
                caption=PRODUCT_CAPTION,
                category=_product.category,
            ),
        params:
            function=_product.function,
            caption=_product.caption(),
            per_case=False,
            name=config.get("study", {}).get("name", _key),
        log:
            PATHS.log("figures", f"{_key}.log"),
        script:
            "../scripts/study_figure.py"


rule study_report:
    localrule: True
    input:
        simulations=simulation_results(),
        figures=list(figures("png").values()),
        code=script_code("study_report.py"),
    output:
        **STUDY_REPORT,
    params:
        # only a study's configuration has it; read when the job runs
        study=lambda wildcards: config["study"],
        beam=config["beam"],
        cases=cases(),
        figures=figures("png"),
    log:
        PATHS.log("report", "report.log"),
    script:
        "../scripts/study_report.py"
