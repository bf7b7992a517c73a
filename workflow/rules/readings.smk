"""Alternative readings of the paper (config `readings`, hubbeam.readings and hubbeam.explain).

Each reading is one job: it simulates the runs its change generates (`reading-<reading>--<case>`,
held in memory; unchanged runs are the default results) and evaluates its claims with the
functions of hubbeam.claims -> results/readings/claims/<reading>.csv. `readings_matrix` collects
them into the claims x readings matrix, results/readings/readings.csv and readings.nc, which the
reproduction report reads. The default results never depend on these rules. Part of `all` (the
17 readings of config/config.yaml take about 1.5 minutes on two cores); `snakemake readings` builds
the matrix alone.
"""


rule reading:
    input:
        datasets=lambda wildcards: expand("results/simulations/{case}.nc", case=reading_base_cases(wildcards)),
        table2="results/tables/table2.csv",
        critical_speeds="results/tables/critical_speeds.csv",
        claims="results/report/claims.csv",
        kernel=simulation_kernels_done,
        code=script_code("readings_reading.py"),
    output:
        ensure("results/readings/claims/{reading}.csv", non_empty=True),
    params:
        cases=reading_base_cases,
        generated=reading_generated_cases,
        reading=lambda wildcards: config["readings"][wildcards.reading],
        beam=config["beam"],
        numerics=config["numerics"],
        eigen=config["eigen"],
    wildcard_constraints:
        reading="[A-Za-z0-9_]+",
    log:
        "logs/readings/{reading}.log",
    script:
        "../scripts/readings_reading.py"


rule readings_matrix:
    input:
        readings=expand("results/readings/claims/{reading}.csv", reading=reading_names()),
        code=script_code("readings_matrix.py"),
    output:
        csv=ensure("results/readings/readings.csv", non_empty=True),
        nc=ensure("results/readings/readings.nc", non_empty=True),
    params:
        readings=config.get("readings", {}),
    log:
        "logs/readings/matrix.log",
    script:
        "../scripts/readings_matrix.py"


rule readings:
    """Target: the claims x readings matrix alone (`snakemake readings`)."""
    input:
        reading_targets(),
