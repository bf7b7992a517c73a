"""``linear_modes.csv``: a tracked, damped Campbell diagram over 200 hub speeds with 10 + 10 modes.

For each model, free hub, modal damping: the 200 linear models (``hubbeam.linear.linear_model``,
state size ``2 (1 + 2n)``, 42 for TLAM, FOAM, CFOAM), their modes (``tracking.state_modes``: the
stacked eigendecomposition and the choice of one eigenvalue per pair) and the tracking with the
labels (``tracking.track``, ``tracking.dominant_content``), each timed on its own, and the whole
Campbell dataset of every model with held and free hub (``hubbeam.linear.datasets.campbell``).
"""

from __future__ import annotations

import time
from collections.abc import Mapping

import numpy as np

from benchmarks.timing import median_time
from hubbeam.linear import datasets, linear_model, tracking
from hubbeam.linear.axes import tip_mass_axis
from hubbeam.model.damping import damping_matrices
from hubbeam.model.matrices import assemble
from hubbeam.model.models import MODELS

#: the benchmark's grid: speeds from rest to the top of the config's eigen grid, modes per block
SPEEDS = 200
MODES = 10
DAMPING = {"kind": "modal", "axial": 0.01, "transverse": 0.02}


def _build(params, sm, model, speeds, C):
    return [linear_model(params, sm, model, float(speed), "free", C, outputs=("hub_angle",))
            for speed in speeds]


def campbell_rows(cfg: Mapping, params, repeats: int, budget: float) -> list[dict]:
    """One row per model (free hub; its phases timed once each, after a warm-up) and one for the
    whole Campbell dataset (median of ``repeats`` within ``budget`` seconds)."""
    speeds = np.linspace(cfg["eigen"]["speeds"]["start"], cfg["eigen"]["speeds"]["stop"], SPEEDS)
    n_quad = cfg["numerics"]["quadrature_points"]
    sm = assemble(params, None, MODES, n_quad)
    C = damping_matrices(DAMPING, sm)
    rows = []
    for model in MODELS:
        weights = datasets.mode_weights(sm, model)
        _build(params, sm, model, speeds, C)  # warm-up
        start = time.perf_counter()
        models = _build(params, sm, model, speeds, C)
        built = time.perf_counter()
        A = np.stack([lm.A for lm in models])
        modes = tracking.state_modes(A, weights)
        found = time.perf_counter()
        tracked = tracking.track(modes)
        tracking.dominant_content(tracked.shape, models[0].states[:A.shape[1] // 2], weights, tracked.rigid)
        done = time.perf_counter()
        rows.append({"product": "tracked Campbell, free hub", "model": model, "speeds": SPEEDS,
                     "modes_per_block": MODES, "states": A.shape[1],
                     "modes_tracked": tracked.eigenvalue.shape[1], "build_s": built - start,
                     "modes_s": found - built, "track_s": done - found, "wall_s": done - start,
                     "repeats": 1})
    wall, count = median_time(lambda: datasets.campbell(
        tip_mass_axis(params, [0.0], MODES, n_quad, DAMPING), speeds), repeats, budget)
    rows.append({"product": "Campbell dataset, every model, held and free hub", "model": "all",
                 "speeds": SPEEDS, "modes_per_block": MODES, "wall_s": wall, "repeats": count})
    return rows
