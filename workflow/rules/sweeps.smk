"""Parameter sweeps beyond the paper (`sweeps` of the config): maps of the peak tip deflection.

A map is split into chunks of `chunk_size` simulations (hubbeam.simulation.sweep.chunk_points): one
`sweep_chunk` job per chunk runs them in the parallel numba kernel on its threads (one by default,
a chunk being sized for about a minute on one core) and writes the temporary
`sweeps/chunks/<name>/<i>.nc` of the results folder; `sweep` gathers the chunks into
`sweeps/<name>.nc` (bit-identical to a single run of the whole map); `figure_sweep` draws
`figures/sweep_<name>.pdf/.png` from that file only. Maps marked `in_all: false` (too
large for every run) are built by `large_sweeps`. `sweep_kernel` compiles the kernel into numba's
on-disk cache once, after `simulation_kernel` has cached the integrator it shares, so that no two
jobs compile the same code at the same time. Each job takes its map as the configuration's
`Sweep` object (hubbeam.configuration.settings), with its plain mapping for Snakemake's rerun
trigger. Inputs and params: hubbeam.pipeline.plan (`sweep_steps`).
"""


rule large_sweeps:
    input:
        PLAN.large_sweep_targets,
    localrule: True


rule sweep_kernel:
    input:
        **STEPS["sweep_kernel"].input,
    output:
        done=STEPS["sweep_kernel"].output["done"],
    params:
        **STEPS["sweep_kernel"].params,
    log:
        STEPS["sweep_kernel"].log,
    script:
        "../scripts/sweep_compile.py"


rule sweep_chunk:
    input:
        **STEPS["sweep_chunk"].input,
    output:
        nc=temp(ensure(STEPS["sweep_chunk"].output["nc"], non_empty=True)),
    params:
        **STEPS["sweep_chunk"].params,
    wildcard_constraints:
        sweep=PLAN.sweep_pattern,
        chunk=r"\d+",
    log:
        STEPS["sweep_chunk"].log,
    script:
        "../scripts/sweep_chunk.py"


rule sweep:
    input:
        **STEPS["sweep"].input,
    output:
        nc=ensure(STEPS["sweep"].output["nc"], non_empty=True),
    params:
        **STEPS["sweep"].params,
    wildcard_constraints:
        sweep=PLAN.sweep_pattern,
    localrule: True
    log:
        STEPS["sweep"].log,
    script:
        "../scripts/sweep_gather.py"


rule figure_sweep:
    localrule: True
    input:
        **STEPS["figure_sweep"].input,
    output:
        pdf=ensure(STEPS["figure_sweep"].output["pdf"], non_empty=True),
        png=report(ensure(STEPS["figure_sweep"].output["png"], non_empty=True), caption="../report/sweep.rst",
                   category="Beyond the paper"),
    params:
        **STEPS["figure_sweep"].params,
    wildcard_constraints:
        sweep=PLAN.sweep_pattern,
    log:
        STEPS["figure_sweep"].log,
    script:
        "../scripts/figure_sweep.py"
