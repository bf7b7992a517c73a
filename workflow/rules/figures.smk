"""Figures (Figs. 3-10 and beyond) and Tables 1-3, drawn from the result files only.

A simulation figure takes the cases whose names start with its prefixes
(`hubbeam.plotting.figures.FIGURE_CASE_PREFIXES`): naming a case `fig05_...` in the config puts it
on Fig. 5. One rule per figure (defined in a loop) so that each figure has its own caption.
"""

for _key, _module in SIMULATION_FIGURES.items():

    rule:
        name:
            f"figure_{_key}"
        input:
            datasets=figure_datasets(_key),
            style=FIGURE_STYLE,
            code=script_code("figure_simulation.py", f"hubbeam.plotting.{_module}"),
        output:
            pdf=ensure(f"results/figures/{_key}.pdf", non_empty=True),
            png=report(
                ensure(f"results/figures/{_key}.png", non_empty=True),
                caption=f"../report/{_key}.rst",
                category=figure_category(_key),
            ),
        params:
            figure=_key,
            cases=figure_cases(_key),
        log:
            f"logs/figures/{_key}.log",
        script:
            "../scripts/figure_simulation.py"


for _key, (_module, _inputs) in EIGEN_FIGURES.items():

    rule:
        name:
            f"figure_{_key}"
        input:
            **_inputs,
            style=FIGURE_STYLE,
            code=script_code("figure_eigen.py", f"hubbeam.plotting.{_module}"),
        output:
            pdf=ensure(f"results/figures/{_key}.pdf", non_empty=True),
            png=report(
                ensure(f"results/figures/{_key}.png", non_empty=True),
                caption=f"../report/{_key}.rst",
                category=figure_category(_key),
            ),
        params:
            module=_module,
        log:
            f"logs/figures/{_key}.log",
        script:
            "../scripts/figure_eigen.py"


rule table1:
    input:
        code=script_code("table_1.py"),
    output:
        csv=report("results/tables/table1.csv", caption="../report/table.rst", category="Tables"),
        md="results/tables/table1.md",
        tex="results/tables/table1.tex",
    params:
        beam=config["beam"],
        tip_masses=used_tip_masses(),
    log:
        "logs/tables/table1.log",
    script:
        "../scripts/table_1.py"


rule table2_render:
    input:
        csv="results/tables/table2.csv",
        code=script_code("table_2.py"),
    output:
        md=report("results/tables/table2.md", caption="../report/table.rst", category="Tables"),
        tex="results/tables/table2.tex",
    params:
        speed=config["eigen"]["table2_speed"],
    log:
        "logs/tables/table2.log",
    script:
        "../scripts/table_2.py"


rule table3:
    input:
        datasets=figure_datasets("table3"),
        code=script_code("table_3.py"),
    output:
        csv=report("results/tables/table3.csv", caption="../report/table.rst", category="Tables"),
        md="results/tables/table3.md",
        tex="results/tables/table3.tex",
    params:
        cases=figure_cases("table3"),
    log:
        "logs/tables/table3.log",
    script:
        "../scripts/table_3.py"
