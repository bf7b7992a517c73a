"""The claims of the paper against our results and the reproduction report (with the paper's
products), and the archive of every configuration's results."""


report: "../report/workflow.rst"


rule claims:
    localrule: True
    input:
        datasets=[PATHS.simulation(case) for case in claim_cases()],
        **CLAIM_TABLES,
        code=script_code("report_claims.py"),
    output:
        report(
            ensure(PATHS.report("claims.csv"), non_empty=True),
            caption="../report/claims.rst",
            category="Report",
        ),
    params:
        cases=claim_cases(),
    log:
        PATHS.log("report", "claims.log"),
    script:
        "../scripts/report_claims.py"


rule reproduction_report:
    localrule: True
    input:
        claims=PATHS.report("claims.csv"),
        figures=list(figures("png").values()),
        tables=[PATHS.table(key, "md") for key in table_keys()],
        datasets=simulation_results(),
        # the published-table validation (none when the config has no `validation` section)
        **published_validation_inputs(),
        # the claims under alternative readings (none when the config has no `readings` section)
        **reading_inputs(),
        code=script_code("report_reproduction.py"),
    output:
        markdown=ensure(PATHS.report("reproduction.md"), non_empty=True),
        html=report(
            ensure(PATHS.report("reproduction.html"), non_empty=True),
            caption="../report/reproduction.rst",
            category="Report",
        ),
    params:
        cases=cases(),
        numerics=config["numerics"],
        readings=config.get("readings", {}),
    log:
        PATHS.log("report", "reproduction.log"),
    script:
        "../scripts/report_reproduction.py"


rule archive:
    localrule: True
    input:
        archive_inputs,
    output:
        ensure(PATHS.archive(), non_empty=True),
    params:
        config=config,
        top=PATHS.archive_top,
        root=PATHS.archive_root,
        workflow_root=workflow.basedir,
    log:
        PATHS.log("report", "archive.log"),
    script:
        "../scripts/archive.py"
