"""Eigen-analysis at constant hub speed: K22 eigenvalues (Fig. 9), critical speeds (Sections 4.2,
4.4), Campbell diagram, the beam as data and Table 2, of the configuration's beam (uniform or in
sections). Every physical parameter reaches the scripts via `params:`. The products and the claims
that read these files decide which are built. Inputs and params: hubbeam.pipeline.plan
(`eigen_steps`)."""


rule eigen_k22:
    input:
        **STEPS["eigen_k22"].input,
    output:
        nc=ensure(STEPS["eigen_k22"].output["nc"], non_empty=True),
    params:
        **STEPS["eigen_k22"].params,
    log:
        STEPS["eigen_k22"].log,
    script:
        "../scripts/eigen_k22.py"


rule eigen_critical_speeds:
    input:
        **STEPS["eigen_critical_speeds"].input,
    output:
        nc=ensure(STEPS["eigen_critical_speeds"].output["nc"], non_empty=True),
    params:
        **STEPS["eigen_critical_speeds"].params,
    log:
        STEPS["eigen_critical_speeds"].log,
    script:
        "../scripts/eigen_critical_speeds.py"


rule eigen_critical_speed_table:
    input:
        **STEPS["eigen_critical_speed_table"].input,
    output:
        csv=ensure(STEPS["eigen_critical_speed_table"].output["csv"], non_empty=True),
    params:
        **STEPS["eigen_critical_speed_table"].params,
    log:
        STEPS["eigen_critical_speed_table"].log,
    script:
        "../scripts/eigen_critical_speed_table.py"


rule eigen_campbell:
    input:
        **STEPS["eigen_campbell"].input,
    output:
        nc=ensure(STEPS["eigen_campbell"].output["nc"], non_empty=True),
    params:
        **STEPS["eigen_campbell"].params,
    log:
        STEPS["eigen_campbell"].log,
    script:
        "../scripts/eigen_campbell.py"


rule eigen_beam:
    input:
        **STEPS["eigen_beam"].input,
    output:
        nc=ensure(STEPS["eigen_beam"].output["nc"], non_empty=True),
    params:
        **STEPS["eigen_beam"].params,
    log:
        STEPS["eigen_beam"].log,
    script:
        "../scripts/eigen_beam.py"


rule eigen_table2:
    input:
        **STEPS["eigen_table2"].input,
    output:
        csv=ensure(STEPS["eigen_table2"].output["csv"], non_empty=True),
    params:
        **STEPS["eigen_table2"].params,
    log:
        STEPS["eigen_table2"].log,
    script:
        "../scripts/eigen_table2.py"
