"""Limits of the numerical inputs, each defined once.

The startup checks (:mod:`hubbeam.configuration.load`, which fills them into the JSON schema when it loads
it, see ``config_schema.SCHEMA_LIMITS``), the Python API (:mod:`hubbeam.simulation.simulate`) and the modules that
build the matrices (:mod:`hubbeam.model.modes`, :mod:`hubbeam.model.quadrature`) all read them here. The
run status codes live with the integrator that returns them (:mod:`hubbeam.core.radau`), as the
jitted core imports nothing of the rest of the package. Importing this module is cheap (no numba).
"""

import numpy as np

from hubbeam.core.step_control import fewest_steps

#: the fewest and the most assumed modes per coordinate set (Eqs. 7-8); above 20 the clamped-free
#: modes' exponent-safe evaluation has not been checked
MIN_MODES = 1
MAX_MODES = 20
#: the smallest relative tolerance of the Radau IIA integrator: 100 machine epsilons
#: (``hubbeam.core.radau.UROUND``); its Newton test divides by ``rtol``
MIN_RTOL = 100 * float(np.finfo(np.float64).eps)
#: Gauss-Legendre nodes on [0, L]: below this many the rule is never used, whatever is asked for
MIN_QUADRATURE_POINTS = 8
#: above this many nodes numpy's Legendre rule is no longer accurate to double precision
MAX_QUADRATURE_POINTS = 1000
#: the smallest step budget (``numerics.max_steps``): the Radau IIA integrator starts with a step of
#: 1e-6 of the span and grows it at most eightfold per step, so no run ends in fewer attempts
#: (``hubbeam.core.step_control.fewest_steps``)
MIN_STEPS = fewest_steps()
#: default memory budget of one run's outputs or one sweep, MiB (``numerics.memory_budget_mb``):
#: a run holds about twice its outputs while its dataset is built, so the default keeps one
#: simulation below about 4 GiB
MEMORY_BUDGET_MB = 2048.0
#: default small-deflection limit, as a fraction of L (``numerics.small_deflection_limit``); the
#: models linearise the strain in the elastic deformation (docs/reliability.md)
SMALL_DEFLECTION_LIMIT = 0.1
