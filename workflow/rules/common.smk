"""What the rule files take from the workflow's plan; the Snakefile includes this file first.

`PLAN` (the Snakefile builds it: hubbeam.pipeline.plan.build_plan) is the checked configuration
with everything the rules need. Each rule that runs a script takes its step, `STEPS["<rule>"]`
(hubbeam.pipeline.steps.Step): its input files, params and log as they are, its outputs by name
wrapped in Snakemake's flags (`ensure`, `temp`, `report`). The Snakefile checks, once every rule
file is read, that each rule runs the script its step names. Every path comes from the plan
(hubbeam.results.paths), every figure and table from the configuration's products
(`PLAN.products`, hubbeam.reporting.products).
"""

from hubbeam.reporting.products import (CASE_FIGURE, COMPARISON_FIGURE, DESIGNS_FIGURE, FILES_FIGURE,
                                        SHAPING_FIGURE, SIMULATION_FIGURE, of_kind)

#: the step of every rule that runs a script, by rule name
STEPS = PLAN.steps
#: the caption file of every product in `snakemake --report`: it prints `params.caption`
PRODUCT_CAPTION = "../report/product.rst"
