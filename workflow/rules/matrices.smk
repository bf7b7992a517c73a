"""System matrices (Eqs. 13-20, Appendix) of every tip-mass configuration of the simulation cases.

One file per configuration, `matrices/<name>.nc` of the results folder (`PATHS` in common.smk:
results/ for the paper, results/<name>/ for a study), named by
`hubbeam.model.matrices.configuration_name` (`mt0`, `mt0p1_l8`, ...), with as many modes as the most
demanding case that uses it (the matrices of fewer modes are its leading blocks). The helpers
(`matrices_configurations`, `matrices_configuration`, `matrices_results`) are in common.smk.
"""

rule matrices:
    input:
        code=script_code("assemble_matrices.py"),
    output:
        ensure(PATHS.matrices("{config_name}"), non_empty=True),
    params:
        beam=config["beam"],
        configuration=matrices_configuration,
        n_quad=config["numerics"]["quadrature_points"],
    wildcard_constraints:
        config_name=r"mt[0-9a-z_]+",
    log:
        PATHS.log("matrices", "{config_name}.log"),
    script:
        "../scripts/assemble_matrices.py"
