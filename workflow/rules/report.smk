"""The claims of the paper against our results and the reproduction report (with the paper's
products), and the archive of every configuration's results. Inputs and params:
hubbeam.pipeline.plan (`report_steps`)."""


report: "../report/workflow.rst"


rule claims:
    localrule: True
    input:
        **STEPS["claims"].input,
    output:
        claims=report(ensure(STEPS["claims"].output["claims"], non_empty=True), caption="../report/claims.rst",
                      category="Report"),
    params:
        **STEPS["claims"].params,
    log:
        STEPS["claims"].log,
    script:
        "../scripts/report_claims.py"


rule reproduction_report:
    localrule: True
    input:
        **STEPS["reproduction_report"].input,
    output:
        markdown=ensure(STEPS["reproduction_report"].output["markdown"], non_empty=True),
        html=report(ensure(STEPS["reproduction_report"].output["html"], non_empty=True),
                    caption="../report/reproduction.rst", category="Report"),
    params:
        **STEPS["reproduction_report"].params,
    log:
        STEPS["reproduction_report"].log,
    script:
        "../scripts/report_reproduction.py"


rule archive:
    localrule: True
    input:
        **STEPS["archive"].input,
    output:
        archive=ensure(STEPS["archive"].output["archive"], non_empty=True),
    params:
        **STEPS["archive"].params,
    log:
        STEPS["archive"].log,
    script:
        "../scripts/archive.py"
