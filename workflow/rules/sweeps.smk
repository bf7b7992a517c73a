"""Parameter sweeps beyond the paper (`sweeps` of the config): maps of the peak tip deflection.

One job per map runs every simulation of the map in one parallel numba kernel (hubbeam.sweep)
on all the cores Snakemake gives it, and writes `results/sweeps/<name>.nc`; `figure_sweep`
draws `results/figures/sweep_<name>.pdf/.png` from that file only. `sweep_kernel` compiles the
kernel into numba's on-disk cache once, after `simulation_kernel` has cached the integrator it
shares, so that no two jobs compile the same code at the same time. Helpers (`sweeps`,
`sweep_params`, `sweep_targets`) are in common.smk.
"""



rule sweep_kernel:
    input:
        code=script_code("sweep_compile.py"),
        simulation_kernel="logs/simulations/kernel.done",
    output:
        "logs/sweeps/kernel.done",
    log:
        "logs/sweeps/kernel.log",
    script:
        "../scripts/sweep_compile.py"


rule sweep:
    input:
        kernel="logs/sweeps/kernel.done",
        code=script_code("sweep_run.py"),
    output:
        ensure("results/sweeps/{sweep}.nc", non_empty=True),
    params:
        beam=config["beam"],
        sweep=sweep_params,
    wildcard_constraints:
        sweep="|".join(sweeps()) or "no-sweeps",
    threads: workflow.cores
    log:
        "logs/sweeps/{sweep}.log",
    script:
        "../scripts/sweep_run.py"


rule figure_sweep:
    input:
        sweep="results/sweeps/{sweep}.nc",
        style=FIGURE_STYLE,
        code=script_code("figure_sweep.py"),
    output:
        pdf=ensure("results/figures/sweep_{sweep}.pdf", non_empty=True),
        png=report(
            ensure("results/figures/sweep_{sweep}.png", non_empty=True),
            caption="../report/sweep.rst",
            category="Beyond the paper",
        ),
    wildcard_constraints:
        sweep="|".join(sweeps()) or "no-sweeps",
    log:
        "logs/figures/sweep_{sweep}.log",
    script:
        "../scripts/figure_sweep.py"
