"""The figures and tables of the configuration's products (the registry, :mod:`hubbeam.reporting.products`):
one step per figure (or per figure of a case, of a comparison), drawn from the result files only,
and Tables 1-3 of the paper. Each figure's PNG is shown in ``snakemake --report`` with its caption."""

from __future__ import annotations

from hubbeam.model.beam import beam_config
from hubbeam.pipeline.context import NotPlanned, PlanContext
from hubbeam.pipeline.steps import Step
from hubbeam.reporting.products import (
    CASE_FIGURE,
    COMPARISON_FIGURE,
    FILES_FIGURE,
    PAPER_PRODUCTS,
    PLANT_FIGURE,
    SHAPING_FIGURE,
    SIMULATION_FIGURE,
    TABLE,
    Product,
    designed_cases,
)
from hubbeam.results.paths import FIGURE_FORMATS, TABLE_FORMATS

FIGURES, TABLES = "hubbeam.pipeline.jobs.figures", "hubbeam.pipeline.jobs.tables"
#: the caption file of every product in ``snakemake --report`` (relative to the rule files): it
#: prints ``params.caption``
PRODUCT_CAPTION = "../report/product.rst"


def targets(ctx: PlanContext) -> list[str]:
    """The PDF and PNG of every figure, the csv, Markdown and LaTeX of every table."""
    return sorted(path for ext in FIGURE_FORMATS for path in ctx.figure_files(ext).values()) + [
        ctx.paths.table(key, ext) for key in ctx.table_keys() for ext in TABLE_FORMATS]


def steps(ctx: PlanContext) -> dict[str, Step]:
    figures = {f"figure_{key}": figure_step(ctx, key, product) for key, product in ctx.products.items()
               if product.kind != TABLE}
    return figures | table_steps(ctx)


def figure_step(ctx: PlanContext, key: str, product: Product) -> Step:
    """The step of the figure(s) of ``product``."""
    common = {"function": product.function, "caption": product.caption()}
    flags = {"local": True, "reported": {"png": (PRODUCT_CAPTION, product.category)}, "modules": (product.module,)}
    log = ctx.paths.log("figures", f"{key}.log")
    if product.kind == SIMULATION_FIGURE:
        return ctx.step(f"{FIGURES}:simulation_figure", output=ctx.figure(key), log=log,
                        input={"datasets": ctx.simulations(product.cases), "style": ctx.style},
                        params={**common, "cases": list(product.cases)}, **flags)
    if product.kind == FILES_FIGURE:
        files = {name: ctx.result(path) for name, path in product.files.items()}
        return ctx.step(f"{FIGURES}:files_figure", output=ctx.figure(key), log=log, input={**files, "style": ctx.style},
                        params={**common, "options": dict(product.options)}, **flags)
    if product.kind == CASE_FIGURE:
        return ctx.step(f"{FIGURES}:study_figure", output=ctx.figure(f"{key}_{{case}}"),
                        log=ctx.paths.log("figures", f"{key}_{{case}}.log"),
                        input={"simulations": [ctx.paths.simulation("{case}")]},
                        params={**common, "per_case": True, "cases": ["{case}"], "name": "{case}"},
                        wildcards=[{"case": case} for case in ctx.cases], **flags)
    if product.kind == COMPARISON_FIGURE:
        def comparison(wildcards) -> list[str]:
            """The cases of a job's ``{comparison}`` (``study.comparisons``)."""
            if wildcards.comparison not in ctx.comparisons:
                raise NotPlanned(f"unknown comparison {wildcards.comparison!r}; defined in study.comparisons: "
                                 f"{', '.join(sorted(ctx.comparisons)) or 'none'}")
            return list(ctx.comparisons[wildcards.comparison])

        return ctx.step(f"{FIGURES}:study_figure", output=ctx.figure(f"{key}_{{comparison}}"),
                        log=ctx.paths.log("figures", f"{key}_{{comparison}}.log"),
                        input={"simulations": lambda wildcards: ctx.simulations(comparison(wildcards))},
                        params={**common, "per_case": False, "cases": comparison, "name": "{comparison}"},
                        wildcards=[{"comparison": name} for name in sorted(ctx.comparisons)], **flags)
    if product.kind == PLANT_FIGURE:
        files = {name: ctx.result(path) for name, path in product.files.items()}
        return ctx.step(f"{FIGURES}:files_figure", output=ctx.figure(f"{key}_{{plant}}"),
                        log=ctx.paths.log("figures", f"{key}_{{plant}}.log"), input={**files, "style": ctx.style},
                        params={**common, "options": dict(product.options)},
                        wildcards=[{"plant": plant} for plant in ctx.settings.plants], **flags)
    name = ctx.settings.study.name if ctx.settings.study is not None else key
    cases = list(ctx.cases) if product.kind == SHAPING_FIGURE else designed_cases(ctx.checked.config)
    return ctx.step(f"{FIGURES}:study_figure", output=ctx.figure(key), log=log,
                    input={"simulations": ctx.simulations(cases)},
                    params={**common, "per_case": False, "cases": cases, "name": name}, **flags)


def table_steps(ctx: PlanContext) -> dict[str, Step]:
    """Tables 1-3 of the paper (csv, Markdown, LaTeX; Table 2's csv comes from the eigen-analysis)."""
    def step(key: str, job: str, formats=TABLE_FORMATS, **arguments) -> Step:
        reported = "csv" if "csv" in formats else "md"
        return ctx.step(f"{TABLES}:{job}", output={ext: ctx.paths.table(key, ext) for ext in formats},
                        log=ctx.paths.log("tables", f"{key}.log"), local=True,
                        reported={reported: (PRODUCT_CAPTION, "Tables")}, **arguments)

    table2, table3 = PAPER_PRODUCTS["table2"], PAPER_PRODUCTS["table3"]
    return {
        "table1": step("table1", "table1", params={"beam": beam_config(ctx.settings.beam),
                                                  "caption": PAPER_PRODUCTS["table1"].caption()}),
        "table2_render": step("table2", "table2_render", ("md", "tex"),
                              input={name: ctx.result(path) for name, path in table2.files.items()},
                              params={"speed": ctx.settings.eigen.table2_speed, "caption": table2.caption()}),
        "table3": step("table3", "table3", input={"datasets": ctx.simulations(table3.cases)},
                       params={"cases": list(table3.cases), "caption": table3.caption()}),
    }
