"""The workflow's plan and its jobs: what Snakemake runs, in tested Python.

:mod:`~hubbeam.pipeline.plan` turns a configuration into the plan of the workflow (or refuses it,
listing every problem): its settings, folders, products, the targets of ``all`` and, per rule, a
:class:`~hubbeam.pipeline.steps.Step` (the script, the files, the params, the log, the jobs). The
rule files of ``workflow/rules/`` take everything from it. :mod:`~hubbeam.pipeline.jobs` holds the
job functions the rules' scripts run, each through :func:`hubbeam.pipeline.runner.run`. See
``docs/pipeline.md``.
"""
