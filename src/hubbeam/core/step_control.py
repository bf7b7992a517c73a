"""Step-size bounds of the Radau IIA integrator (:mod:`hubbeam.core.radau`), importable without
numba, so that the startup checks can derive the smallest usable step budget from them.

The integrator starts with the step ``INITIAL_STEP_FRACTION * span`` (``span = t_end - t0``) and
grows it by at most ``MAX_FACTOR`` per accepted step; rejected steps, Newton failures and the
stops it may not cross only shorten it. It interpolates the output times inside its steps, so
the output grid does not bound the number of steps.
"""

import math

#: first step, as a fraction of the integrated span (when no first step is given)
INITIAL_STEP_FRACTION = 1e-6
#: the most and the least a step may grow or shrink from one attempt to the next
MIN_FACTOR = 0.2
MAX_FACTOR = 8.0


def fewest_steps() -> int:
    """The fewest attempted steps that can cover any span: the smallest ``k`` with
    ``INITIAL_STEP_FRACTION * (1 + MAX_FACTOR + ... + MAX_FACTOR**(k - 1)) >= 1``.

    A step budget (``max_steps``) below this stops every run before its end, whatever the
    equations; a budget above it is necessary, not sufficient."""
    growth = 1.0 + (MAX_FACTOR - 1.0) / INITIAL_STEP_FRACTION
    return math.ceil(math.log(growth) / math.log(MAX_FACTOR) - 1e-12)
