"""Eigen-analysis at constant hub speed: K22 eigenvalues (Fig. 9), critical speeds (Sections 4.2,
4.4), Campbell diagram and Table 2, of the configuration's beam (uniform or in sections). Every
physical parameter reaches the scripts via `params:`. The products and the claims that read these
files decide which are built (`eigen_results` in common.smk)."""

#: the transverse mode shapes of the beam's data (eigen/beam.nc, the mode-shape figure)
BEAM_MODE_SHAPES = 3

rule eigen_k22:
    input:
        code=script_code("eigen_k22.py"),
    output:
        ensure(PATHS.eigen("k22"), non_empty=True),
    params:
        beam=config["beam"],
        tip_masses=config["eigen"]["tip_masses"],
        positions=config["eigen"]["positions"],
        speeds=config["eigen"]["speeds"],
        n_modes=config["numerics"]["modes"],
        n_quad=config["numerics"]["quadrature_points"],
    log:
        PATHS.log("eigen", "k22.log"),
    script:
        "../scripts/eigen_k22.py"


rule eigen_critical_speeds:
    input:
        code=script_code("eigen_critical_speeds.py"),
    output:
        ensure(PATHS.eigen("critical_speeds"), non_empty=True),
    params:
        beam=config["beam"],
        tip_masses=config["eigen"]["tip_masses"],
        positions=config["eigen"]["positions"],
        search_max=config["eigen"]["critical_speed_search_max"],
        n_modes=config["numerics"]["modes"],
        n_quad=config["numerics"]["quadrature_points"],
    log:
        PATHS.log("eigen", "critical_speeds.log"),
    script:
        "../scripts/eigen_critical_speeds.py"


rule eigen_critical_speed_table:
    input:
        code=script_code("eigen_critical_speed_table.py"),
    output:
        ensure(CLAIM_TABLES["critical_speeds"], non_empty=True),
    params:
        beam=config["beam"],
        tip_masses=config["eigen"]["tip_masses"],
        search_max=config["eigen"]["critical_speed_search_max"],
        n_modes=config["numerics"]["modes"],
        n_quad=config["numerics"]["quadrature_points"],
    log:
        PATHS.log("eigen", "critical_speed_table.log"),
    script:
        "../scripts/eigen_critical_speed_table.py"


rule eigen_campbell:
    input:
        code=script_code("eigen_campbell.py"),
    output:
        ensure(PATHS.eigen("campbell"), non_empty=True),
    params:
        beam=config["beam"],
        tip_masses=config["eigen"]["tip_masses"],
        speeds=config["eigen"]["speeds"],
        n_modes=config["numerics"]["modes"],
        n_quad=config["numerics"]["quadrature_points"],
    log:
        PATHS.log("eigen", "campbell.log"),
    script:
        "../scripts/eigen_campbell.py"


rule eigen_beam:
    input:
        code=script_code("eigen_beam.py"),
    output:
        beam=ensure(PATHS.eigen("beam"), non_empty=True),
    params:
        beam=config["beam"],
        tips={name: case.tip_mass for name, case in SETTINGS.cases.items()},
        speeds=[0.0, config["eigen"]["speeds"]["stop"]],
        tip_masses=config["eigen"]["tip_masses"],
        n_shapes=BEAM_MODE_SHAPES,
        n_modes=config["numerics"]["modes"],
        n_quad=config["numerics"]["quadrature_points"],
    log:
        PATHS.log("eigen", "beam.log"),
    script:
        "../scripts/eigen_beam.py"


rule eigen_table2:
    input:
        code=script_code("eigen_table2.py"),
    output:
        ensure(CLAIM_TABLES["table2"], non_empty=True),
    params:
        beam=config["beam"],
        # only the paper's configuration has it; read when the job runs
        speed=lambda wildcards: config["eigen"]["table2_speed"],
        n_modes=config["numerics"]["modes"],
        n_quad=config["numerics"]["quadrature_points"],
    log:
        PATHS.log("eigen", "table2.log"),
    script:
        "../scripts/eigen_table2.py"
