"""What the rule files take from the workflow's plan; the Snakefile includes this file first.

`PLAN` (the Snakefile builds it: hubbeam.pipeline.plan.build_plan) is the checked configuration
with everything the rules need: a step per rule that runs a job (`STEPS`, hubbeam.pipeline.steps.Step:
its job function, input files, params, log, wildcards and Snakemake's flags), declared by the
families of hubbeam.pipeline.families, and the families' target rules.
"""

#: the step of every rule that runs a job, by rule name
STEPS = PLAN.steps

report: "../report/workflow.rst"
