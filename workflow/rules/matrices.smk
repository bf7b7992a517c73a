"""System matrices (Eqs. 13-20, Appendix) of every tip-mass configuration of the simulation cases.

One file per configuration, `matrices/<name>.nc` of the results folder, named by
`hubbeam.model.matrices.configuration_name` (`mt0`, `mt0p1_l8`, ...), with as many modes as the
most demanding case that uses it (the matrices of fewer modes are its leading blocks). Inputs and
params: hubbeam.pipeline.plan (`simulation_steps`).
"""


rule matrices:
    input:
        **STEPS["matrices"].input,
    output:
        nc=ensure(STEPS["matrices"].output["nc"], non_empty=True),
    params:
        **STEPS["matrices"].params,
    wildcard_constraints:
        config_name=r"mt[0-9A-Za-z_]+",
    log:
        STEPS["matrices"].log,
    script:
        "../scripts/assemble_matrices.py"
