"""Parameter sweeps beyond the paper (`sweeps` of the config): maps of the peak tip deflection.

A map is split into chunks of `chunk_size` simulations (hubbeam.simulation.sweep.chunk_points): one
`sweep_chunk` job per chunk runs them in the parallel numba kernel on its threads (one by default,
a chunk being sized for about a minute on one core) and writes the temporary
`sweeps/chunks/<name>/<i>.nc` of the results folder; `sweep` gathers the chunks into
`sweeps/<name>.nc` (bit-identical to a single run of the whole map); `figure_sweep` draws
`figures/sweep_<name>.pdf/.png` from that file only. Maps marked `in_all: false` (too
large for every run) are built by `large_sweeps`. `sweep_kernel` compiles the kernel into numba's
on-disk cache once, after `simulation_kernel` has cached the integrator it shares, so that no two
jobs compile the same code at the same time. Helpers (`sweeps`, `sweep_params`, `sweep_chunks`,
`sweep_targets`) are in common.smk.
"""


rule large_sweeps:
    input:
        sweep_targets(in_all=False),
    localrule: True


rule sweep_kernel:
    input:
        code=script_code("sweep_compile.py"),
        simulation_kernels=simulation_kernels_done,
    output:
        SHARED.log("sweeps", "kernel.done"),
    log:
        SHARED.log("sweeps", "kernel.log"),
    script:
        "../scripts/sweep_compile.py"


rule sweep_chunk:
    input:
        kernel=SHARED.log("sweeps", "kernel.done"),
        code=script_code("sweep_chunk.py"),
    output:
        temp(ensure(PATHS.sweep_chunk("{sweep}", "{chunk}"), non_empty=True)),
    params:
        beam=config["beam"],
        sweep=sweep_params,
    wildcard_constraints:
        sweep="|".join(sweeps()) or "no-sweeps",
        chunk=r"\d+",
    log:
        PATHS.log("sweeps", "chunks", "{sweep}", "{chunk}.log"),
    script:
        "../scripts/sweep_chunk.py"


rule sweep:
    input:
        chunks=sweep_chunks,
        code=script_code("sweep_gather.py"),
    output:
        ensure(PATHS.sweep("{sweep}"), non_empty=True),
    params:
        beam=config["beam"],
        sweep=sweep_params,
    wildcard_constraints:
        sweep="|".join(sweeps()) or "no-sweeps",
    localrule: True
    log:
        PATHS.log("sweeps", "{sweep}.log"),
    script:
        "../scripts/sweep_gather.py"


rule figure_sweep:
    localrule: True
    input:
        sweep=PATHS.sweep("{sweep}"),
        style=FIGURE_STYLE,
        code=script_code("figure_sweep.py"),
    output:
        pdf=ensure(PATHS.figure("sweep_{sweep}", "pdf"), non_empty=True),
        png=report(
            ensure(PATHS.figure("sweep_{sweep}", "png"), non_empty=True),
            caption="../report/sweep.rst",
            category="Beyond the paper",
        ),
    wildcard_constraints:
        sweep="|".join(sweeps()) or "no-sweeps",
    log:
        PATHS.log("figures", "sweep_{sweep}.log"),
    script:
        "../scripts/figure_sweep.py"
