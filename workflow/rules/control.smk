"""Analyses of the sampled controllers (hubbeam.control.analyses, docs/quanser-study.md), from the
`control` section of the configuration: the sample-time sweep (`control_sample_time`), the
robustness maps (`control_robustness`) and the implementation files of every sampled case's
controller (`control_export`). Their figures are products of the registry (figures.smk). Inputs
and params: hubbeam.pipeline.plan (`control_steps`)."""


rule control_sample_time:
    input:
        **STEPS["control_sample_time"].input,
    output:
        nc=ensure(STEPS["control_sample_time"].output["nc"], non_empty=True),
    params:
        **STEPS["control_sample_time"].params,
    log:
        STEPS["control_sample_time"].log,
    script:
        "../scripts/control_sample_time.py"


rule control_robustness:
    input:
        **STEPS["control_robustness"].input,
    output:
        nc=ensure(STEPS["control_robustness"].output["nc"], non_empty=True),
    params:
        **STEPS["control_robustness"].params,
    log:
        STEPS["control_robustness"].log,
    script:
        "../scripts/control_robustness.py"


rule control_export:
    input:
        **STEPS["control_export"].input,
    output:
        mat=ensure(STEPS["control_export"].output["mat"], non_empty=True),
        json=ensure(STEPS["control_export"].output["json"], non_empty=True),
    params:
        **STEPS["control_export"].params,
    log:
        STEPS["control_export"].log,
    script:
        "../scripts/control_export.py"
