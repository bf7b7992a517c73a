"""Timings of hubbeam against scipy (``make benchmark``); not part of the package or the workflow.

Modules: :mod:`~benchmarks.settings` (config and its checks), :mod:`~benchmarks.cases` (single
runs), :mod:`~benchmarks.search` (tolerance search, integrator rows), :mod:`~benchmarks.timing`,
:mod:`~benchmarks.compilation` with :mod:`~benchmarks.fresh_process`, :mod:`~benchmarks.extras`
(scaling, eigen, sweeps), :mod:`~benchmarks.rig` (a sampled controller on a servo rig),
:mod:`~benchmarks.machine` and :mod:`~benchmarks.run` (command line).
"""
