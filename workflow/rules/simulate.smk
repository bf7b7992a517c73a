"""Time simulation of every configured case: `simulations/<case>.nc` of the results folder
(Radau IIA kernel; results/ for the paper, results/<name>/ for a study).

The system matrices come from `matrices/<configuration>.nc` (their leading `modes` blocks); the
beam, the resolved case, the integrator settings and the optional convergence check
(`numerics.convergence_check`, None when absent) come through `params:` as the objects of the one
check of the configuration, with their fingerprint, so that editing a case reruns exactly that
case. The package sources a simulation runs are inputs, so that editing a kernel reruns every
simulation. `simulation_kernel` compiles the jitted kernel of one family of models (`foam`: TLAM,
FOAM, SFOAM; `cfoam`: CFOAM) into numba's on-disk cache, or its sampled-controller kernel
(`foam_sampled`, `cfoam_sampled`: only for a configuration with a sampled controller); the kernels
compile in parallel jobs, and a simulation waits only for its own kernel, so that FOAM-type runs
start while CFOAM's kernel still compiles. Inputs and params: hubbeam.pipeline.plan (`simulation_steps`).
"""


rule simulation_kernel:
    input:
        **STEPS["simulation_kernel"].input,
    output:
        done=STEPS["simulation_kernel"].output["done"],
    params:
        **STEPS["simulation_kernel"].params,
    wildcard_constraints:
        kernel=PLAN.kernel_pattern,
    # first on the cores of a cold run: every simulation waits for its family's kernel
    priority: 100
    log:
        STEPS["simulation_kernel"].log,
    script:
        "../scripts/compile_simulation_kernel.py"


rule simulate:
    input:
        **STEPS["simulate"].input,
    output:
        nc=ensure(STEPS["simulate"].output["nc"], non_empty=True),
    params:
        **STEPS["simulate"].params,
    log:
        STEPS["simulate"].log,
    script:
        "../scripts/simulate_case.py"
