"""Independent validation (issue 8, docs/validation.md); helpers in common.smk.

Builds in results/validation/:
* published_comparison.csv, tip_mass_comparison.csv, rotating_eigen.nc, rotating_frequencies.pdf/png:
  the constant-speed linearisation of FOAM against published rotating-cantilever frequencies
  (rule `validate_published`, seconds, no Exudyn: part of `all` and of the reproduction report);
* exudyn_<case>.nc, exudyn_comparison.csv, exudyn_comparison.pdf/png: FOAM, CFOAM and TLAM tip
  deflections against the Exudyn ANCF reference (runs/ holds the separate runs);
* exudyn_mode_study.csv: the model-reference differences against the number of assumed modes;
* exudyn_convergence.csv, exudyn_convergence.nc: convergence of the reference;
and results/report/validation_exudyn.md/.html, the report of the Exudyn comparison.
Everything Exudyn is built only by the `validate` target (`snakemake validate`, not part of
`all`); it needs the optional dependency (`pip install -e .[validation]`) and without it stops
before running anything, saying so.
"""



rule validate:
    localrule: True
    input:
        validation_targets,


rule validate_published:
    input:
        code=script_code("validate_published.py"),
        style=FIGURE_STYLE,
    output:
        table=ensure(f"{VALIDATION_DIR}/published_comparison.csv", non_empty=True),
        tip_mass=ensure(f"{VALIDATION_DIR}/tip_mass_comparison.csv", non_empty=True),
        curves=ensure(f"{VALIDATION_DIR}/rotating_eigen.nc", non_empty=True),
        pdf=ensure(f"{VALIDATION_DIR}/rotating_frequencies.pdf", non_empty=True),
        png=report(
            ensure(f"{VALIDATION_DIR}/rotating_frequencies.png", non_empty=True),
            caption="../report/rotating_frequencies.rst",
            category="Validation",
        ),
    params:
        published=validation_section("published"),
        n_quad=config["numerics"]["quadrature_points"],
    log:
        "logs/validation/published.log",
    script:
        "../scripts/validate_published.py"


rule validate_exudyn:
    input:
        code=script_code("validate_exudyn.py"),
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
        code=script_code("validate_models.py"),
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
        code=script_code("validate_case.py"),
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
        code=script_code("validate_comparison.py"),
        style=FIGURE_STYLE,
    output:
        table=ensure(f"{VALIDATION_DIR}/exudyn_comparison.csv", non_empty=True),
        pdf=ensure(f"{VALIDATION_DIR}/exudyn_comparison.pdf", non_empty=True),
        png=report(
            ensure(f"{VALIDATION_DIR}/exudyn_comparison.png", non_empty=True),
            caption="../report/exudyn_comparison.rst",
            category="Validation",
        ),
    log:
        "logs/validation/comparison.log",
    script:
        "../scripts/validate_comparison.py"


rule validate_modes:
    input:
        references=validation_reference_files,
        code=script_code("validate_modes.py"),
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
        code=script_code("validate_convergence.py"),
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


rule validation_report:
    localrule: True
    input:
        comparison=f"{VALIDATION_DIR}/exudyn_comparison.csv",
        figure=f"{VALIDATION_DIR}/exudyn_comparison.png",
        mode_study=f"{VALIDATION_DIR}/exudyn_mode_study.csv",
        convergence=f"{VALIDATION_DIR}/exudyn_convergence.csv",
        code=script_code("report_validation.py"),
    output:
        markdown=ensure("results/report/validation_exudyn.md", non_empty=True),
        html=report(
            ensure("results/report/validation_exudyn.html", non_empty=True),
            caption="../report/validation_exudyn.rst",
            category="Validation",
        ),
    log:
        "logs/report/validation_exudyn.log",
    script:
        "../scripts/report_validation.py"
