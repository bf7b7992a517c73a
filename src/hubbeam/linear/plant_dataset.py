"""What a study's plant is, as a dataset: its natural frequencies and how far they are converged,
its free hub's frequencies, the critical speed of each model, and what it holds.

* ``held_frequency``: the natural frequencies (Hz) with the hub held, at rest
  (:func:`hubbeam.linear.plant_models.plant_frequencies`, what ``hubbeam.api`` gives);
* ``more_modes_frequency`` and ``relative_change``: the same with :data:`EXTRA_MODES` more assumed
  functions, and the relative change; a mode is ``converged`` when the change is below
  :data:`CONVERGED` (the top modes of an assumed-modes model are too stiff: they are marked so, not
  listed as if they were the beam's);
* ``free_frequency``: the frequencies of the undamped free hub at rest (hub torque input), the
  rigid-body mode left out: every one of them is a flexible mode, whatever coordinate dominates it;
* ``critical_speed``: where the hub-held stiffness of each model's linearisation stops being
  positive definite (NaN: none up to the search's top).
"""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import xarray as xr

from hubbeam.linear.axes import plant_axis
from hubbeam.linear.plant_models import plant_critical_speed, plant_frequencies, plant_linear
from hubbeam.model.limits import MAX_MODES
from hubbeam.model.models import MODELS
from hubbeam.model.plant import Plant

#: the assumed functions added for the convergence of the frequencies
EXTRA_MODES = 3
#: the relative change of a frequency below which it counts as converged
CONVERGED = 1e-3
#: ``|lambda|`` (rad s-1) below which a pole of the free hub is its rigid-body mode
RIGID = 1e-6


def free_frequencies(plant: Plant) -> np.ndarray:
    """The frequencies (Hz, ascending) of ``plant``'s undamped free hub at rest, the rigid-body mode
    (its two zero poles) left out; FOAM's model (the frequencies at rest are every model's)."""
    undamped = dataclasses.replace(plant, damping=None)
    poles = np.linalg.eigvals(plant_linear(undamped, "FOAM", 0.0, "free", ("hub_angle",), through_drive=False).A)
    flexible = poles[np.abs(poles) > RIGID * max(1.0, np.abs(poles).max())]
    return np.sort(np.abs(flexible[flexible.imag > 0].imag)) / (2.0 * np.pi)


def plant_dataset(plant: Plant, cases, search_max: float) -> xr.Dataset:
    """The dataset of ``plant`` (module docstring), run by the ``cases`` named; the critical speeds
    searched up to ``search_max`` (rad s-1)."""
    held = plant_frequencies(plant)
    more = min(plant.modes + EXTRA_MODES, MAX_MODES)
    finer = plant_frequencies(dataclasses.replace(plant, modes=more)) if more > plant.modes else held
    change = np.abs(held - finer[:held.size]) / finer[:held.size]
    free = free_frequencies(plant)
    critical = [plant_critical_speed(plant, model, search_max) for model in MODELS]
    mode = {"units": "1", "long_name": "mode, by frequency"}
    return xr.Dataset(
        {
            "held_frequency": ("mode", held, {"units": "Hz", "long_name": "natural frequency, hub held, at rest"}),
            "more_modes_frequency": ("mode", finer[:held.size],
                                     {"units": "Hz", "long_name": f"the same with {more} assumed functions"}),
            "relative_change": ("mode", change, {"units": "1", "long_name": "relative change of the natural "
                                                 "frequency with more assumed functions"}),
            "converged": ("mode", (change < CONVERGED).astype(np.int8),
                          {"long_name": f"relative change below {CONVERGED:g}",
                           "flag_values": np.array([0, 1], dtype=np.int8), "flag_meanings": "no yes"}),
            "free_frequency": ("flexible_mode", free,
                               {"units": "Hz", "long_name": "frequency of a flexible mode of the undamped free hub at "
                                                            "rest (the rigid-body mode left out)"}),
            "critical_speed": ("model", np.array(critical, dtype=float),
                               {"units": "rad s-1", "long_name": "critical speed of the hub-held stiffness of the "
                                "model's linearisation (NaN: none up to the search's top)"}),
        },
        coords={"mode": ("mode", np.arange(1, held.size + 1), mode),
                "flexible_mode": ("flexible_mode", np.arange(1, free.size + 1),
                                  {"units": "1", "long_name": "flexible mode of the free hub, by frequency"}),
                "model": ("model", list(MODELS), {"long_name": "model (Section 3)"})},
        attrs={"title": f"plant {plant.name}", **plant_axis(plant).attributes, "cases": json.dumps(list(cases)),
               "more_modes": more, "converged_below": CONVERGED, "critical_speed_search_max": float(search_max)},
    )
