"""Figures (Figs. 3-10 and beyond, the eigen-analysis figures of every configuration) and Tables
1-3, drawn from the result files only.

Every figure and table is a product of the registry (`hubbeam.reporting.products`; `PRODUCTS` in common.smk
holds the configuration's), which names the cases or result files it reads, the function that
draws it and its caption. One rule per figure (defined in a loop) so that each figure has its own
caption in `snakemake --report`. The figures per case and per comparison are in study.smk.
"""

for _key, _product in of_kind(PRODUCTS, SIMULATION_FIGURE).items():

    rule:
        name:
            f"figure_{_key}"
        localrule: True
        input:
            datasets=product_datasets(_key),
            style=FIGURE_STYLE,
            code=script_code("figure_simulation.py", _product.module),
        output:
            pdf=ensure(PATHS.figure(_key, "pdf"), non_empty=True),
            png=report(
                ensure(PATHS.figure(_key, "png"), non_empty=True),
                caption=PRODUCT_CAPTION,
                category=_product.category,
            ),
        params:
            function=_product.function,
            cases=list(_product.cases),
            caption=_product.caption(),
        log:
            PATHS.log("figures", f"{_key}.log"),
        script:
            "../scripts/figure_simulation.py"


for _key, _product in of_kind(PRODUCTS, EIGEN_FIGURE).items():

    rule:
        name:
            f"figure_{_key}"
        localrule: True
        input:
            **product_files(_product),
            style=FIGURE_STYLE,
            code=script_code("figure_eigen.py", _product.module),
        output:
            pdf=ensure(PATHS.figure(_key, "pdf"), non_empty=True),
            png=report(
                ensure(PATHS.figure(_key, "png"), non_empty=True),
                caption=PRODUCT_CAPTION,
                category=_product.category,
            ),
        params:
            function=_product.function,
            options=dict(_product.options),
            caption=_product.caption(),
        log:
            PATHS.log("figures", f"{_key}.log"),
        script:
            "../scripts/figure_eigen.py"


rule table1:
    localrule: True
    input:
        code=script_code("table_1.py"),
    output:
        csv=report(PATHS.table("table1", "csv"), caption=PRODUCT_CAPTION, category="Tables"),
        md=PATHS.table("table1", "md"),
        tex=PATHS.table("table1", "tex"),
    params:
        beam=config["beam"],
        caption=product("table1").caption(),
    log:
        PATHS.log("tables", "table1.log"),
    script:
        "../scripts/table_1.py"


rule table2_render:
    localrule: True
    input:
        **product_files(product("table2")),
        code=script_code("table_2.py"),
    output:
        md=report(PATHS.table("table2", "md"), caption=PRODUCT_CAPTION, category="Tables"),
        tex=PATHS.table("table2", "tex"),
    params:
        # only the paper's configuration has it; read when the job runs
        speed=lambda wildcards: config["eigen"]["table2_speed"],
        caption=product("table2").caption(),
    log:
        PATHS.log("tables", "table2.log"),
    script:
        "../scripts/table_2.py"


rule table3:
    localrule: True
    input:
        datasets=product_datasets("table3"),
        code=script_code("table_3.py"),
    output:
        csv=report(PATHS.table("table3", "csv"), caption=PRODUCT_CAPTION, category="Tables"),
        md=PATHS.table("table3", "md"),
        tex=PATHS.table("table3", "tex"),
    params:
        cases=list(product("table3").cases),
        caption=product("table3").caption(),
    log:
        PATHS.log("tables", "table3.log"),
    script:
        "../scripts/table_3.py"
