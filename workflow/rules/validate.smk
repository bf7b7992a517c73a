"""Independent validation (docs/validation.md).

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
and report/validation_exudyn.md/.html, the report of these checks (the names: hubbeam.results.paths).
Everything but the published check is built only by the `validate` target (`snakemake validate`,
not part of `all`); it needs the optional dependencies (`pip install -e .[validation]`) and
without them stops before running anything, saying so. The Exudyn part needs the config's
`validation` section. Inputs and params: hubbeam.pipeline.plan (`validation_steps`).
"""


rule validate:
    localrule: True
    input:
        PLAN.validation_targets,


rule validate_published:
    input:
        **STEPS["validate_published"].input,
    output:
        table=ensure(STEPS["validate_published"].output["table"], non_empty=True),
        tip_mass=ensure(STEPS["validate_published"].output["tip_mass"], non_empty=True),
        curves=ensure(STEPS["validate_published"].output["curves"], non_empty=True),
        pdf=ensure(STEPS["validate_published"].output["pdf"], non_empty=True),
        png=report(ensure(STEPS["validate_published"].output["png"], non_empty=True),
                   caption="../report/rotating_frequencies.rst", category="Validation"),
    params:
        **STEPS["validate_published"].params,
    log:
        STEPS["validate_published"].log,
    script:
        "../scripts/validate_published.py"


rule validate_exudyn:
    input:
        **STEPS["validate_exudyn"].input,
    output:
        nc=ensure(STEPS["validate_exudyn"].output["nc"], non_empty=True),
    wildcard_constraints:
        vcase=CASE_NAME_PATTERN,
    params:
        **STEPS["validate_exudyn"].params,
    log:
        STEPS["validate_exudyn"].log,
    script:
        "../scripts/validate_exudyn.py"


rule validate_models:
    input:
        **STEPS["validate_models"].input,
    output:
        nc=ensure(STEPS["validate_models"].output["nc"], non_empty=True),
    wildcard_constraints:
        vcase=CASE_NAME_PATTERN,
    params:
        **STEPS["validate_models"].params,
    log:
        STEPS["validate_models"].log,
    script:
        "../scripts/validate_models.py"


rule validate_case:
    input:
        **STEPS["validate_case"].input,
    output:
        nc=ensure(STEPS["validate_case"].output["nc"], non_empty=True),
    wildcard_constraints:
        vcase=CASE_NAME_PATTERN,
    params:
        **STEPS["validate_case"].params,
    log:
        STEPS["validate_case"].log,
    script:
        "../scripts/validate_case.py"


rule validate_comparison:
    input:
        **STEPS["validate_comparison"].input,
    output:
        table=ensure(STEPS["validate_comparison"].output["table"], non_empty=True),
        pdf=ensure(STEPS["validate_comparison"].output["pdf"], non_empty=True),
        png=report(ensure(STEPS["validate_comparison"].output["png"], non_empty=True),
                   caption="../report/exudyn_comparison.rst", category="Validation"),
    params:
        **STEPS["validate_comparison"].params,
    log:
        STEPS["validate_comparison"].log,
    script:
        "../scripts/validate_comparison.py"


rule validate_modes:
    input:
        **STEPS["validate_modes"].input,
    output:
        csv=ensure(STEPS["validate_modes"].output["csv"], non_empty=True),
    params:
        **STEPS["validate_modes"].params,
    log:
        STEPS["validate_modes"].log,
    script:
        "../scripts/validate_modes.py"


rule validate_convergence:
    input:
        **STEPS["validate_convergence"].input,
    output:
        table=ensure(STEPS["validate_convergence"].output["table"], non_empty=True),
        runs=ensure(STEPS["validate_convergence"].output["runs"], non_empty=True),
    params:
        **STEPS["validate_convergence"].params,
    log:
        STEPS["validate_convergence"].log,
    script:
        "../scripts/validate_convergence.py"


rule validate_nonuniform:
    input:
        **STEPS["validate_nonuniform"].input,
    output:
        **{name: ensure(path, non_empty=True) for name, path in STEPS["validate_nonuniform"].output.items()},
    params:
        **STEPS["validate_nonuniform"].params,
    log:
        STEPS["validate_nonuniform"].log,
    script:
        "../scripts/validate_nonuniform.py"


rule validation_report:
    localrule: True
    input:
        **STEPS["validation_report"].input,
    output:
        markdown=ensure(STEPS["validation_report"].output["markdown"], non_empty=True),
        html=report(ensure(STEPS["validation_report"].output["html"], non_empty=True),
                    caption="../report/validation_exudyn.rst", category="Validation"),
    params:
        **STEPS["validation_report"].params,
    log:
        STEPS["validation_report"].log,
    script:
        "../scripts/report_validation.py"
