"""``linear.csv``: the cost of a linear model (both routes) and of its Bode data, 10 + 10 modes."""

from __future__ import annotations

from collections.abc import Mapping
from functools import partial

import control as ct
import numpy as np

from benchmarks.timing import median_time
from hubbeam.linear import linear_model
from hubbeam.linear.jacobian import jacobian_model
from hubbeam.model.matrices import assemble
from hubbeam.model.parameters import BeamParameters

#: the measured size: 10 axial and 10 bending modes, 500 frequencies (rad s-1), FOAM at 2 rad s-1
MODES = 10
FREQUENCIES = np.logspace(-1, 4, 500)
MODEL, SPEED = "FOAM", 2.0


def _bode(beam, sm):
    system = linear_model(beam, sm, MODEL, SPEED).to_control()
    return ct.frequency_response(system, FREQUENCIES)


def linear_rows(cfg: Mapping, params: BeamParameters, repeats: int, budget: float) -> list[dict]:
    """Median warm wall times of the assembled model, the Jacobian model, and the assembled model
    with the frequency response of all its outputs to the hub torque at :data:`FREQUENCIES`
    (what a Bode plot of each output needs)."""
    sm = assemble(params, None, MODES, cfg["numerics"]["quadrature_points"])
    calls = {"linear_model (assembled)": partial(linear_model, params, sm, MODEL, SPEED),
             "jacobian_model (central differences)": partial(jacobian_model, params, sm, MODEL,
                                                             SPEED),
             f"linear_model + frequency response at {FREQUENCIES.size} frequencies":
                 partial(_bode, params, sm)}
    rows = []
    for label, call in calls.items():
        call()  # the kernels' compilation or cache loading is not timed
        wall, count = median_time(call, repeats, budget)
        rows.append({"measurement": label, "model": MODEL, "speed_rad_s": SPEED,
                     "modes": MODES, "states": 2 * (1 + 2 * MODES), "wall_s": wall,
                     "repeats": count})
    return rows
