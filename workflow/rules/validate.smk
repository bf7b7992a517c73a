"""Independent validation (docs/validation.md); helpers in common.smk.

Builds in validation/ of the results folder (results/validation/ for the paper,
results/<name>/validation/ for a study):
* published_comparison.csv, tip_mass_comparison.csv, rotating_eigen.nc, rotating_frequencies.pdf/png:
  the constant-speed linearisation of FOAM against published rotating-cantilever frequencies
  (rule `validate_published`, seconds, no Exudyn; with the paper's products and
  `validation.published`: part of `all` and of the reproduction report);
* exudyn_<case>.nc, exudyn_comparison.csv, exudyn_comparison.pdf/png: FOAM, CFOAM and TLAM tip
  deflections against the Exudyn ANCF reference (runs/ holds the separate runs);
* exudyn_mode_study.csv: the model-reference differences against the number of assumed modes;
* exudyn_convergence.csv, exudyn_convergence.nc: convergence of the reference;
* nonuniform_ritz_fe.csv, nonuniform_pybmodes.csv: frequencies of a non-uniform beam (the
  config's own when it has sections, else the tapered version of its uniform beam) from the Ritz
  model, our finite elements and pyBModes (`hubbeam.validation.nonuniform`);
and report/validation_exudyn.md/.html, the report of these checks. Everything but the
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
        table=ensure(PATHS.validation("published_comparison.csv"), non_empty=True),
        tip_mass=ensure(PATHS.validation("tip_mass_comparison.csv"), non_empty=True),
        curves=ensure(PATHS.validation("rotating_eigen.nc"), non_empty=True),
        pdf=ensure(PATHS.validation("rotating_frequencies.pdf"), non_empty=True),
        png=report(
            ensure(PATHS.validation("rotating_frequencies.png"), non_empty=True),
            caption="../report/rotating_frequencies.rst",
            category="Validation",
        ),
    params:
        published=validation_section("published"),
        n_quad=config["numerics"]["quadrature_points"],
    log:
        PATHS.log("validation", "published.log"),
    script:
        "../scripts/validate_published.py"


rule validate_exudyn:
    input:
        code=script_code("validate_exudyn.py"),
    output:
        ensure(PATHS.validation("runs/exudyn_{vcase}.nc"), non_empty=True),
    wildcard_constraints:
        vcase=CASE_NAME_PATTERN,
    params:
        beam=config["beam"],
        case=validation_case,
        exudyn=validation_section("exudyn"),
        output_step=config["numerics"]["output_step"],
    log:
        PATHS.log("validation", "exudyn_{vcase}.log"),
    script:
        "../scripts/validate_exudyn.py"


rule validate_models:
    input:
        code=script_code("validate_models.py"),
    output:
        ensure(PATHS.validation("runs/models_{vcase}.nc"), non_empty=True),
    wildcard_constraints:
        vcase=CASE_NAME_PATTERN,
    params:
        beam=config["beam"],
        case=validation_case,
        models=validation_section("models"),
        numerics=config["numerics"],
    log:
        PATHS.log("validation", "models_{vcase}.log"),
    script:
        "../scripts/validate_models.py"


rule validate_case:
    input:
        reference=PATHS.validation("runs/exudyn_{vcase}.nc"),
        models=PATHS.validation("runs/models_{vcase}.nc"),
        code=script_code("validate_case.py"),
    output:
        ensure(PATHS.validation("exudyn_{vcase}.nc"), non_empty=True),
    wildcard_constraints:
        vcase=CASE_NAME_PATTERN,
    log:
        PATHS.log("validation", "case_{vcase}.log"),
    script:
        "../scripts/validate_case.py"


rule validate_comparison:
    input:
        cases=validation_case_files,
        code=script_code("validate_comparison.py"),
        style=FIGURE_STYLE,
    output:
        table=ensure(PATHS.validation("exudyn_comparison.csv"), non_empty=True),
        pdf=ensure(PATHS.validation("exudyn_comparison.pdf"), non_empty=True),
        png=report(
            ensure(PATHS.validation("exudyn_comparison.png"), non_empty=True),
            caption="../report/exudyn_comparison.rst",
            category="Validation",
        ),
    log:
        PATHS.log("validation", "comparison.log"),
    script:
        "../scripts/validate_comparison.py"


rule validate_modes:
    input:
        references=validation_reference_files,
        code=script_code("validate_modes.py"),
    output:
        ensure(PATHS.validation("exudyn_mode_study.csv"), non_empty=True),
    params:
        beam=config["beam"],
        cases=validation_section("cases"),
        models=validation_section("models"),
        modes=validation_section("mode_study"),
        numerics=config["numerics"],
    log:
        PATHS.log("validation", "modes.log"),
    script:
        "../scripts/validate_modes.py"


rule validate_convergence:
    input:
        code=script_code("validate_convergence.py"),
    output:
        table=ensure(PATHS.validation("exudyn_convergence.csv"), non_empty=True),
        runs=ensure(PATHS.validation("exudyn_convergence.nc"), non_empty=True),
    params:
        beam=config["beam"],
        case=convergence_case,
        exudyn=validation_section("exudyn"),
        convergence=validation_section("convergence"),
        output_step=config["numerics"]["output_step"],
    log:
        PATHS.log("validation", "convergence.log"),
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
        PATHS.log("validation", "nonuniform.log"),
    script:
        "../scripts/validate_nonuniform.py"


rule validation_report:
    localrule: True
    input:
        **exudyn_report_inputs(),
        **nonuniform_results(),
        code=script_code("report_validation.py"),
    output:
        markdown=ensure(PATHS.report("validation_exudyn.md"), non_empty=True),
        html=report(
            ensure(PATHS.report("validation_exudyn.html"), non_empty=True),
            caption="../report/validation_exudyn.rst",
            category="Validation",
        ),
    log:
        PATHS.log("report", "validation_exudyn.log"),
    script:
        "../scripts/report_validation.py"
