"""The study report and its figures per case, per comparison and of the feedback designs
(products of kinds "figure per case", "figure per comparison" and "figure of the feedback
designs" of the registry): built for a configuration with a `study` section (docs/studies.md),
under its results folder results/<name>/.

The study report (Markdown, HTML, summary.csv) shows each figure of the configuration in the
section of the report its product names (hubbeam.reporting.products: the beam, the cases, the
comparisons of `study.comparisons`, the feedback designs, the eigen-analysis, the linear models),
each drawn by its own rule; the simulations, matrices, eigen-analysis and archive come from the
rules every configuration shares. Inputs and params: hubbeam.pipeline.plan (`figure_steps`,
`report_steps`).
"""


wildcard_constraints:
    comparison=CASE_NAME_PATTERN,


for _key, _product in of_kind(PLAN.products, CASE_FIGURE, COMPARISON_FIGURE, DESIGNS_FIGURE, SHAPING_FIGURE).items():
    _step = STEPS[f"figure_{_key}"]

    rule:
        name:
            f"figure_{_key}"
        localrule: True
        input:
            **_step.input,
        output:
            pdf=ensure(_step.output["pdf"], non_empty=True),
            png=report(ensure(_step.output["png"], non_empty=True), caption=PRODUCT_CAPTION,
                       category=_product.category),
        params:
            **_step.params,
        log:
            _step.log,
        script:
            "../scripts/study_figure.py"


rule study_report:
    localrule: True
    input:
        **STEPS["study_report"].input,
    output:
        markdown=STEPS["study_report"].output["markdown"],
        html=STEPS["study_report"].output["html"],
        summary=STEPS["study_report"].output["summary"],
        **{key: path for key, path in STEPS["study_report"].output.items() if key == "shaping"},
    params:
        **STEPS["study_report"].params,
    log:
        STEPS["study_report"].log,
    script:
        "../scripts/study_report.py"
