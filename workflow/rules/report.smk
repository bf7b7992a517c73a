"""The claims of the paper against our results, the reproduction report and the results archive."""


report: "../report/workflow.rst"


rule claims:
    localrule: True
    input:
        datasets=expand("results/simulations/{case}.nc", case=claim_cases()),
        table2="results/tables/table2.csv",
        critical_speeds="results/tables/critical_speeds.csv",
        code=script_code("report_claims.py"),
    output:
        report(
            ensure("results/report/claims.csv", non_empty=True),
            caption="../report/claims.rst",
            category="Report",
        ),
    params:
        cases=claim_cases(),
    log:
        "logs/report/claims.log",
    script:
        "../scripts/report_claims.py"


rule reproduction_report:
    localrule: True
    input:
        claims="results/report/claims.csv",
        figures=[path for path in figure_targets() if path.endswith(".png")],
        tables=expand("results/tables/{key}.md", key=table_keys()),
        datasets=simulation_results(),
        # the published-table validation (none when the config has no `validation` section)
        **published_validation_inputs(),
        # the claims under alternative readings (none when the config has no `readings` section)
        **reading_inputs(),
        code=script_code("report_reproduction.py"),
    output:
        markdown=ensure("results/report/reproduction.md", non_empty=True),
        html=report(
            ensure("results/report/reproduction.html", non_empty=True),
            caption="../report/reproduction.rst",
            category="Report",
        ),
    params:
        cases=cases(),
        numerics=config["numerics"],
    log:
        "logs/report/reproduction.log",
    script:
        "../scripts/report_reproduction.py"


rule archive:
    localrule: True
    input:
        archive_inputs,
    output:
        ensure("results/hubbeam-results.tar.gz", non_empty=True),
    params:
        config=config,
        workflow_root=workflow.basedir,
    log:
        "logs/report/archive.log",
    script:
        "../scripts/archive.py"
