"""Figures (Figs. 3-10 and beyond: the figures of the eigen-analysis and of the linear models of
every configuration) and Tables 1-3, drawn from the result files only.

Every figure and table is a product of the registry (hubbeam.reporting.products;
`PLAN.products` holds the configuration's), which names the cases or result files it reads, the
function that draws it and its caption. One rule per figure (defined in a loop over the products
of a kind) so that each figure has its own caption in `snakemake --report`; its step is
`STEPS["figure_<key>"]`. The figures per case and per comparison are in study.smk. Inputs and
params: hubbeam.pipeline.plan (`figure_steps`, `table_steps`).
"""

for _key, _product in of_kind(PLAN.products, SIMULATION_FIGURE).items():
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
            "../scripts/figure_simulation.py"


for _key, _product in of_kind(PLAN.products, FILES_FIGURE).items():
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
            "../scripts/figure_files.py"


rule table1:
    localrule: True
    input:
        **STEPS["table1"].input,
    output:
        csv=report(STEPS["table1"].output["csv"], caption=PRODUCT_CAPTION, category="Tables"),
        md=STEPS["table1"].output["md"],
        tex=STEPS["table1"].output["tex"],
    params:
        **STEPS["table1"].params,
    log:
        STEPS["table1"].log,
    script:
        "../scripts/table_1.py"


rule table2_render:
    localrule: True
    input:
        **STEPS["table2_render"].input,
    output:
        md=report(STEPS["table2_render"].output["md"], caption=PRODUCT_CAPTION, category="Tables"),
        tex=STEPS["table2_render"].output["tex"],
    params:
        **STEPS["table2_render"].params,
    log:
        STEPS["table2_render"].log,
    script:
        "../scripts/table_2.py"


rule table3:
    localrule: True
    input:
        **STEPS["table3"].input,
    output:
        csv=report(STEPS["table3"].output["csv"], caption=PRODUCT_CAPTION, category="Tables"),
        md=STEPS["table3"].output["md"],
        tex=STEPS["table3"].output["tex"],
    params:
        **STEPS["table3"].params,
    log:
        STEPS["table3"].log,
    script:
        "../scripts/table_3.py"
