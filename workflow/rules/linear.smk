"""Linear models about a steady spin for control design (hubbeam.linear, docs/linear-models.md),
from the `linear` section of the configuration (defaults in hubbeam.configuration.defaults): the state-space
models of every model, free and prescribed hub, over the speed grid as CF netCDF and MATLAB files
(`linear_models`), and the datasets the linear-model figures of the registry read: the tracked,
damped Campbell diagram, the mode shapes along the span, the poles and zeros over speed and the
Bode diagrams. Built for every configuration, the paper's included."""


def linear_params():
    """The `params:` every linear-model rule reads: the beam, the tip masses, the grid, the
    damping and the discretisation."""
    linear = config["linear"]
    return dict(beam=config["beam"], tip_masses=linear["tip_masses"], speeds=linear["speeds"],
                damping=linear.get("damping"), n_modes=config["numerics"]["modes"],
                n_quad=config["numerics"]["quadrature_points"])


rule linear_models:
    input:
        code=script_code("linear_models.py"),
    output:
        [ensure(path, non_empty=True) for path in linear_model_files()],
    params:
        **linear_params(),
        files=linear_model_exports(),
    log:
        PATHS.log("linear", "models.log"),
    script:
        "../scripts/linear_models.py"


rule linear_campbell:
    input:
        code=script_code("linear_dataset.py"),
    output:
        ensure(PATHS.linear("campbell"), non_empty=True),
    params:
        **linear_params(),
        product="campbell",
    log:
        PATHS.log("linear", "campbell.log"),
    script:
        "../scripts/linear_dataset.py"


rule linear_poles_zeros:
    input:
        code=script_code("linear_dataset.py"),
    output:
        ensure(PATHS.linear("poles_zeros"), non_empty=True),
    params:
        **linear_params(),
        product="poles_zeros",
    log:
        PATHS.log("linear", "poles_zeros.log"),
    script:
        "../scripts/linear_dataset.py"


rule linear_bode:
    input:
        code=script_code("linear_dataset.py"),
    output:
        ensure(PATHS.linear("bode"), non_empty=True),
    params:
        **linear_params(),
        product="bode",
        bode_speeds=config["linear"]["bode_speeds"],
        frequencies=config["linear"]["frequencies"],
    log:
        PATHS.log("linear", "bode.log"),
    script:
        "../scripts/linear_dataset.py"


rule linear_mode_shapes:
    input:
        campbell=PATHS.linear("campbell"),
        code=script_code("linear_mode_shapes.py"),
    output:
        ensure(PATHS.linear("mode_shapes"), non_empty=True),
    params:
        beam=config["beam"],
        # no more than the vibration modes every model has (SFOAM: numerics.modes)
        shapes=min(config["linear"]["shapes"], config["numerics"]["modes"]),
    log:
        PATHS.log("linear", "mode_shapes.log"),
    script:
        "../scripts/linear_mode_shapes.py"
