"""Time simulation of every configured case: `simulations/<case>.nc` of the results folder
(Radau IIA kernel; `PATHS` in common.smk: results/ for the paper, results/<name>/ for a study).

The system matrices come from `matrices/<configuration>.nc` (their leading `modes` blocks);
the beam, the resolved case, the integrator settings and the optional convergence check
(`numerics.convergence_check`, None when absent) come through `params:` as the objects of the one
check of the configuration (`SETTINGS`), with their fingerprint, so that editing a case reruns
exactly that case (helpers `simulation_matrices` and `fingerprint` in common.smk). The package sources a simulation runs are inputs, so that editing a kernel reruns
every simulation. `simulation_kernel` compiles the jitted kernel of one family of models (`foam`:
TLAM, FOAM, SFOAM; `cfoam`: CFOAM) into numba's on-disk cache; the two families compile in
parallel jobs, and a simulation waits only for its own family's kernel (`simulation_kernel_done`
in common.smk), so that FOAM-type runs start while CFOAM's kernel still compiles.
"""



rule simulation_kernel:
    input:
        code=script_code("compile_simulation_kernel.py"),
    output:
        KERNEL_DONE,
    params:
        family="{family}",
    wildcard_constraints:
        family=FAMILY_PATTERN,
    # first on the cores of a cold run: every simulation waits for its family's kernel
    priority: 100
    log:
        SHARED.log("simulations", "kernel_{family}.log"),
    script:
        "../scripts/compile_simulation_kernel.py"


rule simulate:
    input:
        matrices=simulation_matrices,
        kernel=simulation_kernel_done,
        code=script_code("simulate_case.py"),
    output:
        ensure(PATHS.simulation("{case}"), non_empty=True),
    params:
        beam=SETTINGS.beam,
        case=case_params,
        numerics=SETTINGS.numerics.simulation(),
        convergence_check=SETTINGS.numerics.convergence_check,
        settings=fingerprint(SETTINGS.beam, case_params, SETTINGS.numerics.simulation(),
                             SETTINGS.numerics.convergence_check),
    log:
        PATHS.log("simulations", "{case}.log"),
    script:
        "../scripts/simulate_case.py"
