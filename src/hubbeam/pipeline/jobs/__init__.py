"""The job functions of the workflow's rules, one per rule (named after it) or per family of rules.

A job function takes a :class:`hubbeam.pipeline.runner.Job` (the rule's files by name, its params,
its log file), does the work with the package's functions, writes every output atomically
(:mod:`hubbeam.results.io`) and logs what it did. The rule's script, a shim in
``workflow/scripts/``, runs it through :func:`hubbeam.pipeline.runner.run`.

The jobs are grouped in modules by what they import, not only by topic: the package sources a
script imports are the code inputs of its rule (:mod:`hubbeam.reporting.sourcedeps`), so a costly
job (a simulation, a sweep chunk, an Exudyn run) sits in a module that imports only what it needs,
and editing a figure's module reruns no simulation.
"""
