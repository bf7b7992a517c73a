"""Alternative readings of the paper (config `readings`, hubbeam.paper.readings and hubbeam.paper.explain).

Each reading is one job: it simulates the runs its change generates (`reading-<reading>--<case>`,
held in memory; unchanged runs are the default results) and evaluates its claims with the
functions of hubbeam.paper.claims -> readings/claims/<reading>.csv of the results folder.
`readings_matrix` collects them into the claims x readings matrix, readings/readings.csv and
readings.nc, which the reproduction report reads. The default results never depend on these
rules. Part of `all` (the 17 readings of config/config.yaml take about 1.5 minutes on two cores);
`snakemake readings` builds the matrix alone. Every reading is checked, and its generated cases
built, once with the plan. Inputs and params: hubbeam.pipeline.plan (`reading_steps`).
"""


rule reading:
    input:
        **STEPS["reading"].input,
    output:
        csv=ensure(STEPS["reading"].output["csv"], non_empty=True),
    params:
        **STEPS["reading"].params,
    wildcard_constraints:
        reading="[A-Za-z0-9_]+",
    log:
        STEPS["reading"].log,
    script:
        "../scripts/readings_reading.py"


rule readings_matrix:
    input:
        **STEPS["readings_matrix"].input,
    output:
        csv=ensure(STEPS["readings_matrix"].output["csv"], non_empty=True),
        nc=ensure(STEPS["readings_matrix"].output["nc"], non_empty=True),
    params:
        **STEPS["readings_matrix"].params,
    log:
        STEPS["readings_matrix"].log,
    script:
        "../scripts/readings_matrix.py"


rule readings:
    """Target: the claims x readings matrix alone (`snakemake readings`)."""
    input:
        PLAN.reading_targets,
