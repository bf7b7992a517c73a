"""One rule per step of the plan (hubbeam.pipeline.families declares them, a family per module):
its input files, outputs with Snakemake's flags (non-empty, temporary, shown in `snakemake --report`
with their caption), params, log, wildcard constraints and priority come from its step as they are.
Every rule runs the one script, workflow/scripts/run_job.py, which runs the job function its step
names (`params.job`) through hubbeam.pipeline.runner."""

for _name, _step in STEPS.items():

    rule:
        name:
            _name
        localrule: _step.local
        priority: _step.priority
        wildcard_constraints:
            **_step.constraints,
        input:
            **_step.input,
        output:
            **_step.flagged_output(ensure, temp, report),
        params:
            **_step.params,
        log:
            _step.log,
        script:
            "../scripts/run_job.py"
