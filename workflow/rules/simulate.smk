"""Time simulation of every configured case: `<RESULTS>/simulations/<case>.nc` (Radau IIA kernel),
where RESULTS (common.smk) is results/ for the paper and results/<name>/ for a study.

The system matrices come from `<RESULTS>/matrices/<configuration>.nc` (their leading `modes` blocks);
the beam parameters, the resolved case, the integrator settings and the optional convergence check
(`numerics.convergence_check`, None when absent) come through `params:`, so that editing a case
reruns exactly that case (helpers `simulation_matrices` and `simulation_numerics` in common.smk). The package sources a simulation runs are inputs, so that editing a kernel reruns
every simulation. `simulation_kernel` compiles the jitted kernel once into numba's on-disk cache
before the (parallel) simulations load it.
"""



rule simulation_kernel:
    input:
        code=script_code("compile_simulation_kernel.py"),
    output:
        "logs/simulations/kernel.done",
    log:
        "logs/simulations/kernel.log",
    script:
        "../scripts/compile_simulation_kernel.py"


rule simulate:
    input:
        matrices=simulation_matrices,
        kernel="logs/simulations/kernel.done",
        code=script_code("simulate_case.py"),
    output:
        ensure(f"{RESULTS}/simulations/{{case}}.nc", non_empty=True),
    params:
        beam=config["beam"],
        case=case_params,
        numerics=simulation_numerics(),
        convergence_check=config["numerics"].get("convergence_check"),
    log:
        f"{LOGS}/simulations/{{case}}.log",
    script:
        "../scripts/simulate_case.py"
