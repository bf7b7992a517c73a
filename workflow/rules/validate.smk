"""Optional independent validation (issue 8, docs/validation.md): `snakemake validate`.

Not part of `rule all`. Builds in results/validation/:
* published_comparison.csv, tip_mass_comparison.csv, rotating_eigen.nc, rotating_frequencies.pdf/png:
  the constant-speed linearisation of FOAM against published rotating-cantilever frequencies;
* exudyn_<case>.nc, exudyn_comparison.csv, exudyn_comparison.pdf/png: FOAM, CFOAM and TLAM tip
  deflections against the Exudyn ANCF reference (runs/ holds the separate runs);
* exudyn_mode_study.csv: the model-reference differences against the number of assumed modes;
* exudyn_convergence.csv, exudyn_convergence.nc: convergence of the reference.
The Exudyn part needs the optional dependency (`pip install -e .[validation]`); without it
`snakemake validate` stops before running anything, saying so.
"""

import importlib.util

VALIDATION_DIR = "results/validation"


def validation_config():
    """The `validation` section of the config, or a WorkflowError saying it is missing."""
    if "validation" not in config:
        raise WorkflowError(
            "`snakemake validate` needs the `validation` section of config/config.yaml "
            "(see docs/validation.md); the configuration in use has none"
        )
    return config["validation"]


def validation_cases():
    """Names of the validation cases, sorted."""
    return sorted(validation_config()["cases"])


def named_validation_case(name, key="validation.cases"):
    """The validation case `name`, or a WorkflowError naming the key and the defined cases."""
    cases = validation_config()["cases"]
    if name not in cases:
        raise WorkflowError(
            f"{key}: validation case {name!r} is not defined; defined: {', '.join(sorted(cases))}"
        )
    return cases[name]


def validation_case(wildcards):
    """`params:` function: the validation case of the job's `{vcase}` wildcard."""
    return named_validation_case(wildcards.vcase)


def validation_case_files(wildcards):
    """Input function: the comparison file of every validation case."""
    return expand(f"{VALIDATION_DIR}/exudyn_{{vcase}}.nc", vcase=validation_cases())


def validation_reference_files(wildcards):
    """Input function: the Exudyn run of every validation case."""
    return expand(f"{VALIDATION_DIR}/runs/exudyn_{{vcase}}.nc", vcase=validation_cases())


def validation_section(key):
    """`params:` function returning `validation.<key>` (evaluated only for validation jobs)."""
    return lambda wildcards: validation_config()[key]


def convergence_case(wildcards):
    """`params:` function: the case the Exudyn convergence study runs."""
    return named_validation_case(validation_config()["convergence"]["case"],
                                 key="validation.convergence.case")


def validation_targets(wildcards):
    """Inputs of `validate`; stops with an install hint when Exudyn is not importable."""
    if importlib.util.find_spec("exudyn") is None:
        raise WorkflowError(
            "`snakemake validate` needs the optional dependency exudyn, which is not installed "
            "in this environment: install the extra with `pip install -e .[validation]` (from "
            "the repository root), then rerun `snakemake validate`"
        )
    return [
        f"{VALIDATION_DIR}/published_comparison.csv",
        f"{VALIDATION_DIR}/tip_mass_comparison.csv",
        f"{VALIDATION_DIR}/rotating_eigen.nc",
        f"{VALIDATION_DIR}/rotating_frequencies.pdf",
        f"{VALIDATION_DIR}/exudyn_comparison.csv",
        f"{VALIDATION_DIR}/exudyn_comparison.pdf",
        f"{VALIDATION_DIR}/exudyn_convergence.csv",
        f"{VALIDATION_DIR}/exudyn_convergence.nc",
        f"{VALIDATION_DIR}/exudyn_mode_study.csv",
    ] + validation_case_files(wildcards)


EXUDYN_CODE = hubbeam_sources("validation/exudyn_model.py", "core/maneuver.py", "core/jit.py",
                              "parameters.py")


rule validate:
    localrule: True
    input:
        validation_targets,


rule validate_published:
    input:
        code=hubbeam_sources("validation/published.py", "validation/rotating_eigen.py",
                             "validation/figures.py", "matrices.py", "modes.py", "quadrature.py",
                             "parameters.py"),
        style=FIGURE_STYLE,
    output:
        table=ensure(f"{VALIDATION_DIR}/published_comparison.csv", non_empty=True),
        tip_mass=ensure(f"{VALIDATION_DIR}/tip_mass_comparison.csv", non_empty=True),
        curves=ensure(f"{VALIDATION_DIR}/rotating_eigen.nc", non_empty=True),
        pdf=ensure(f"{VALIDATION_DIR}/rotating_frequencies.pdf", non_empty=True),
        png=ensure(f"{VALIDATION_DIR}/rotating_frequencies.png", non_empty=True),
    params:
        published=validation_section("published"),
        n_quad=config["numerics"]["quadrature_points"],
    log:
        "logs/validation/published.log",
    script:
        "../scripts/validate_published.py"


rule validate_exudyn:
    input:
        code=EXUDYN_CODE,
    output:
        ensure(f"{VALIDATION_DIR}/runs/exudyn_{{vcase}}.nc", non_empty=True),
    wildcard_constraints:
        vcase=CASE_NAME_PATTERN,
    params:
        beam=config["beam"],
        case=validation_case,
        exudyn=validation_section("exudyn"),
        output_step=config["numerics"]["output_step"],
    log:
        "logs/validation/exudyn_{vcase}.log",
    script:
        "../scripts/validate_exudyn.py"


rule validate_models:
    input:
        code=hubbeam_sources("core", "simulate.py", "matrices.py", "modes.py", "quadrature.py",
                             "parameters.py", "validation/comparison.py"),
    output:
        ensure(f"{VALIDATION_DIR}/runs/models_{{vcase}}.nc", non_empty=True),
    wildcard_constraints:
        vcase=CASE_NAME_PATTERN,
    params:
        beam=config["beam"],
        case=validation_case,
        models=validation_section("models"),
        numerics=config["numerics"],
    log:
        "logs/validation/models_{vcase}.log",
    script:
        "../scripts/validate_models.py"


rule validate_case:
    input:
        reference=f"{VALIDATION_DIR}/runs/exudyn_{{vcase}}.nc",
        models=f"{VALIDATION_DIR}/runs/models_{{vcase}}.nc",
        code=hubbeam_sources("validation/comparison.py"),
    output:
        ensure(f"{VALIDATION_DIR}/exudyn_{{vcase}}.nc", non_empty=True),
    wildcard_constraints:
        vcase=CASE_NAME_PATTERN,
    log:
        "logs/validation/case_{vcase}.log",
    script:
        "../scripts/validate_case.py"


rule validate_comparison:
    input:
        cases=validation_case_files,
        code=hubbeam_sources("validation/comparison.py", "validation/figures.py"),
        style=FIGURE_STYLE,
    output:
        table=ensure(f"{VALIDATION_DIR}/exudyn_comparison.csv", non_empty=True),
        pdf=ensure(f"{VALIDATION_DIR}/exudyn_comparison.pdf", non_empty=True),
        png=ensure(f"{VALIDATION_DIR}/exudyn_comparison.png", non_empty=True),
    log:
        "logs/validation/comparison.log",
    script:
        "../scripts/validate_comparison.py"


rule validate_modes:
    input:
        references=validation_reference_files,
        code=hubbeam_sources("core", "simulate.py", "matrices.py", "modes.py", "quadrature.py",
                             "parameters.py", "validation/comparison.py"),
    output:
        ensure(f"{VALIDATION_DIR}/exudyn_mode_study.csv", non_empty=True),
    params:
        beam=config["beam"],
        cases=validation_section("cases"),
        models=validation_section("models"),
        modes=validation_section("mode_study"),
        numerics=config["numerics"],
    log:
        "logs/validation/modes.log",
    script:
        "../scripts/validate_modes.py"


rule validate_convergence:
    input:
        code=EXUDYN_CODE + hubbeam_sources("validation/comparison.py"),
    output:
        table=ensure(f"{VALIDATION_DIR}/exudyn_convergence.csv", non_empty=True),
        runs=ensure(f"{VALIDATION_DIR}/exudyn_convergence.nc", non_empty=True),
    params:
        beam=config["beam"],
        case=convergence_case,
        exudyn=validation_section("exudyn"),
        convergence=validation_section("convergence"),
        output_step=config["numerics"]["output_step"],
    log:
        "logs/validation/convergence.log",
    script:
        "../scripts/validate_convergence.py"
