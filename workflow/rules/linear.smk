"""Linear models about a steady spin for control design (hubbeam.linear, docs/linear-models.md),
from the `linear` section of the configuration (defaults in hubbeam.configuration.defaults): the
state-space models of every model, free and prescribed hub, over the speed grid as CF netCDF and
MATLAB files (`linear_models`), and the datasets the linear-model figures of the registry read:
the tracked, damped Campbell diagram, the mode shapes along the span, the poles and zeros over
speed and the Bode diagrams. Built for every configuration, the paper's included. Inputs and
params: hubbeam.pipeline.plan (`linear_steps`)."""


rule linear_models:
    input:
        **STEPS["linear_models"].input,
    output:
        files=[ensure(path, non_empty=True) for path in STEPS["linear_models"].output["files"]],
    params:
        **STEPS["linear_models"].params,
    log:
        STEPS["linear_models"].log,
    script:
        "../scripts/linear_models.py"


rule linear_campbell:
    input:
        **STEPS["linear_campbell"].input,
    output:
        nc=ensure(STEPS["linear_campbell"].output["nc"], non_empty=True),
    params:
        **STEPS["linear_campbell"].params,
    log:
        STEPS["linear_campbell"].log,
    script:
        "../scripts/linear_dataset.py"


rule linear_poles_zeros:
    input:
        **STEPS["linear_poles_zeros"].input,
    output:
        nc=ensure(STEPS["linear_poles_zeros"].output["nc"], non_empty=True),
    params:
        **STEPS["linear_poles_zeros"].params,
    log:
        STEPS["linear_poles_zeros"].log,
    script:
        "../scripts/linear_dataset.py"


rule linear_bode:
    input:
        **STEPS["linear_bode"].input,
    output:
        nc=ensure(STEPS["linear_bode"].output["nc"], non_empty=True),
    params:
        **STEPS["linear_bode"].params,
    log:
        STEPS["linear_bode"].log,
    script:
        "../scripts/linear_dataset.py"


rule linear_mode_shapes:
    input:
        **STEPS["linear_mode_shapes"].input,
    output:
        nc=ensure(STEPS["linear_mode_shapes"].output["nc"], non_empty=True),
    params:
        **STEPS["linear_mode_shapes"].params,
    log:
        STEPS["linear_mode_shapes"].log,
    script:
        "../scripts/linear_mode_shapes.py"
