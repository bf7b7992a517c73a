"""Alternative readings of the paper (config `readings`, hubbeam.paper.readings and hubbeam.paper.explain).

Each reading is one job: it simulates the runs its change generates (`reading-<reading>--<case>`,
held in memory; unchanged runs are the default results) and evaluates its claims with the
functions of hubbeam.paper.claims -> readings/claims/<reading>.csv of the results folder.
`readings_matrix` collects them into the claims x readings matrix, readings/readings.csv and
readings.nc, which the
reproduction report reads. The default results never depend on these rules. Part of `all` (the
17 readings of config/config.yaml take about 1.5 minutes on two cores); `snakemake readings` builds
the matrix alone.
"""


rule reading:
    input:
        datasets=lambda wildcards: [PATHS.simulation(case) for case in reading_base_cases(wildcards)],
        **CLAIM_TABLES,
        claims=PATHS.report("claims.csv"),
        kernel=simulation_kernels_done,
        code=script_code("readings_reading.py"),
    output:
        ensure(PATHS.reading("{reading}"), non_empty=True),
    params:
        cases=reading_base_cases,
        runs=reading_params,
        settings=fingerprint(reading_params),
    wildcard_constraints:
        reading="[A-Za-z0-9_]+",
    log:
        PATHS.log("readings", "{reading}.log"),
    script:
        "../scripts/readings_reading.py"


rule readings_matrix:
    input:
        readings=[PATHS.reading(name) for name in reading_names()],
        code=script_code("readings_matrix.py"),
    output:
        csv=ensure(PATHS.readings("csv"), non_empty=True),
        nc=ensure(PATHS.readings("nc"), non_empty=True),
    params:
        readings=config.get("readings", {}),
    log:
        PATHS.log("readings", "matrix.log"),
    script:
        "../scripts/readings_matrix.py"


rule readings:
    """Target: the claims x readings matrix alone (`snakemake readings`)."""
    input:
        reading_targets(),
