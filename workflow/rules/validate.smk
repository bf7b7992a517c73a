"""Independent validation (docs/validation.md); helpers in common.smk.

Builds in RESULTS/validation/ (results/validation/ for the paper, results/<name>/validation/ for
a study):
* published_comparison.csv, tip_mass_comparison.csv, rotating_eigen.nc, rotating_frequencies.pdf/png:
  the constant-speed linearisation of FOAM against published rotating-cantilever frequencies
  (rule `validate_published`, seconds, no Exudyn; the paper only: part of `all` and of the
  reproduction report);
* exudyn_<case>.nc, exudyn_comparison.csv, exudyn_comparison.pdf/png: FOAM, CFOAM and TLAM tip
  deflections against the Exudyn ANCF reference (runs/ holds the separate runs);
* exudyn_mode_study.csv: the model-reference differences against the number of assumed modes;
* exudyn_convergence.csv, exudyn_convergence.nc: convergence of the reference;
* nonuniform_ritz_fe.csv, nonuniform_pybmodes.csv: frequencies of a non-uniform beam (the
  config's own when it has sections, else the tapered version of its uniform beam) from the Ritz
  model, our finite elements and pyBModes (`hubbeam.validation.nonuniform`);
and RESULTS/report/validation_exudyn.md/.html, the report of these checks. Everything but the
published check is built only by the `validate` target (`snakemake validate`, not part of `all`);
it needs the optional dependencies (`pip install -e .[validation]`) and without them stops before
running anything, saying so. The Exudyn part needs the config's `validation` section.
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
        f"{VALIDATION_LOGS}/published.log",
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
        f"{VALIDATION_LOGS}/exudyn_{{vcase}}.log",
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
        f"{VALIDATION_LOGS}/models_{{vcase}}.log",
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
        f"{VALIDATION_LOGS}/case_{{vcase}}.log",
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
        f"{VALIDATION_LOGS}/comparison.log",
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
        f"{VALIDATION_LOGS}/modes.log",
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
        f"{VALIDATION_LOGS}/convergence.log",
    script:
        "../scripts/validate_convergence.py"


rule validate_nonuniform:
    input:
        code=script_code("validate_nonuniform.py"),
    output:
        **{name: ensure(path, non_empty=True) for name, path in nonuniform_results().items()},
    params:
        beam=config["beam"],
        n_quad=config["numerics"]["quadrature_points"],
    log:
        f"{VALIDATION_LOGS}/nonuniform.log",
    script:
        "../scripts/validate_nonuniform.py"


rule validation_report:
    localrule: True
    input:
        **exudyn_report_inputs(),
        **nonuniform_results(),
        code=script_code("report_validation.py"),
    output:
        markdown=ensure(f"{RESULTS}/report/validation_exudyn.md", non_empty=True),
        html=report(
            ensure(f"{RESULTS}/report/validation_exudyn.html", non_empty=True),
            caption="../report/validation_exudyn.rst",
            category="Validation",
        ),
    log:
        f"{LOGS}/report/validation_exudyn.log",
    script:
        "../scripts/report_validation.py"
