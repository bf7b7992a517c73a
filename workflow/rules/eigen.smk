"""Eigen-analysis at constant hub speed: K22 eigenvalues (Fig. 9), critical speeds (Sections 4.2,
4.4), Campbell diagram and Table 2. Every physical parameter reaches the scripts via `params:`."""

rule eigen_k22:
    input:
        code=script_code("eigen_k22.py"),
    output:
        ensure("results/eigen/k22.nc", non_empty=True),
    params:
        beam=config["beam"],
        tip_masses=config["eigen"]["tip_masses"],
        positions=config["eigen"]["positions"],
        speeds=config["eigen"]["speeds"],
        n_modes=config["numerics"]["modes"],
        n_quad=config["numerics"]["quadrature_points"],
    log:
        "logs/eigen/k22.log",
    script:
        "../scripts/eigen_k22.py"


rule eigen_critical_speeds:
    input:
        code=script_code("eigen_critical_speeds.py"),
    output:
        grid=ensure("results/eigen/critical_speeds.nc", non_empty=True),
        table=ensure("results/tables/critical_speeds.csv", non_empty=True),
    params:
        beam=config["beam"],
        tip_masses=config["eigen"]["tip_masses"],
        positions=config["eigen"]["positions"],
        search_max=config["eigen"]["critical_speed_search_max"],
        n_modes=config["numerics"]["modes"],
        n_quad=config["numerics"]["quadrature_points"],
    log:
        "logs/eigen/critical_speeds.log",
    script:
        "../scripts/eigen_critical_speeds.py"


rule eigen_campbell:
    input:
        code=script_code("eigen_campbell.py"),
    output:
        ensure("results/eigen/campbell.nc", non_empty=True),
    params:
        beam=config["beam"],
        tip_masses=config["eigen"]["tip_masses"],
        speeds=config["eigen"]["speeds"],
        n_modes=config["numerics"]["modes"],
        n_quad=config["numerics"]["quadrature_points"],
    log:
        "logs/eigen/campbell.log",
    script:
        "../scripts/eigen_campbell.py"


rule eigen_table2:
    input:
        code=script_code("eigen_table2.py"),
    output:
        ensure("results/tables/table2.csv", non_empty=True),
    params:
        beam=config["beam"],
        speed=config["eigen"]["table2_speed"],
        n_modes=config["numerics"]["modes"],
        n_quad=config["numerics"]["quadrature_points"],
    log:
        "logs/eigen/table2.log",
    script:
        "../scripts/eigen_table2.py"
