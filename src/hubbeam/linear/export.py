"""Linear models over a grid of hub speeds as a CF netCDF dataset and as a MATLAB ``.mat`` file.

The dataset (:func:`to_dataset`) stacks the ``A, B, C, D`` of a plant's linear models
(:func:`hubbeam.linear.plant_models.plant_linear`: its tip body, root spring, drive and damping, the
input the rig drives) over the dimension ``speed``; the names of the states, inputs and outputs are string coordinates
(``state`` for the rows of ``A`` and ``B`` and the columns of ``C``, ``state_j`` for the columns of
``A``, ``input``, ``output``), with their units. ``growth_rate`` (the largest real part of the
poles) says where a plant is unstable (TLAM above its critical speed): it is not an error. The
``.mat`` file (:func:`write_mat`) holds the same arrays with the speed last (``A(:, :, k)`` in
MATLAB), the speed vector and the names as cell arrays. Both are written atomically
(``hubbeam.results.io``); ``docs/linear-models.md`` shows how to load each.

A plant with a drive (``hubbeam.model.drive.DcMotor``) gives the free hub's models with the drive's
voltage as input (``hubbeam.linear.voltage``), with the operating-point voltage of each speed; a
plant with a compliant root gives the hub angle ``phi`` as a state and its spring in the attributes.
Optional, absent by default: ``sample_time`` (s) gives the zero-order-hold models with the input
delayed by ``delay`` samples (``hubbeam.linear.discrete``, attributes ``sample_time_s`` and
``input_delay_samples``; the delayed inputs are states in the input's unit; ``growth_rate`` is
then ``ln(max |z|) / Ts``, the continuous rate the largest discrete pole stands for).
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import xarray as xr

from hubbeam.linear.discrete import check_sampling, discretise
from hubbeam.linear.plant_models import plant_damping, plant_linear
from hubbeam.linear.statespace import INPUT_UNITS, OUTPUTS, ROOT_OUTPUTS, check_request, check_speeds
from hubbeam.linear.voltage import check_motor
from hubbeam.model.beam import beam_attributes
from hubbeam.model.plant import Plant, plant_matrices
from hubbeam.model.root import HUB_COORDINATE
from hubbeam.results.io import staged, write_netcdf
from hubbeam.results.provenance import global_attributes


def state_units(name: str, inputs=()) -> str:
    """The unit of a state: rad for the hub angle, kg1/2 m for a modal coordinate, s-1 more for a
    rate (``*_dot``), the input's for a delayed input (``<input>_lag<j>`` of ``inputs``)."""
    for input_name in inputs:
        if name.startswith(f"{input_name}_lag"):
            return INPUT_UNITS[input_name]
    coordinate = "rad" if name.startswith(("theta", HUB_COORDINATE)) else "kg1/2 m"
    return coordinate + (" s-1" if name.endswith("_dot") else "")


def _growth_rate(lm) -> float:
    """The largest real part of the poles; for a discrete model ``ln(max |z|) / Ts``."""
    poles = np.linalg.eigvals(lm.A)
    if getattr(lm, "Ts", None) is None:
        return float(np.max(poles.real))
    with np.errstate(divide="ignore"):
        return float(np.log(np.max(np.abs(poles))) / lm.Ts)


def to_dataset(plant: Plant, model: str, speeds, hub: str = "free", outputs=None, *, sample_time=None,
               delay=0.0) -> xr.Dataset:
    """The linear models of ``model`` for ``plant`` at every speed of ``speeds`` (rad s-1) as a dataset.

    ``hub``: ``"free"`` (the drive's voltage with a drive, else the hub torque) or ``"prescribed"``
    (the hub's acceleration); ``outputs`` as :func:`hubbeam.linear.linear_model`; ``sample_time``
    and ``delay`` as in the module docstring. The plant's tip body, root spring and drive are in the
    attributes. Every argument is checked before the first model is computed.
    """
    check_request(model, hub, outputs, plant.root_spring is not None)
    grid = check_speeds(speeds)
    motor = plant.drive if hub == "free" else None
    if motor is not None:
        check_motor(motor)
    if sample_time is not None:
        check_sampling(sample_time, delay)
    sm = plant_matrices(plant)

    def one(speed):
        lm = plant_linear(plant, model, speed, hub, outputs, sm=sm)
        return lm if sample_time is None else discretise(lm, sample_time, delay)

    models = [one(float(speed)) for speed in grid]
    first = models[0]
    stack = {name: np.stack([getattr(lm, name) for lm in models]) for name in "ABCD"}
    growth = np.array([_growth_rate(lm) for lm in models])
    coords = {
        "speed": ("speed", grid, {"units": "rad s-1", "long_name": "hub speed of the steady spin"}),
        "state": ("state", list(first.states), {"long_name": "state (row of A and B, column of C)"}),
        "state_j": ("state_j", list(first.states), {"long_name": "state (column of A)"}),
        "input": ("input", list(first.inputs), {"long_name": "input"}),
        "output": ("output", list(first.outputs), {"long_name": "output"}),
        "state_units": ("state", [state_units(name, first.inputs) for name in first.states],
                        {"long_name": "units of each state"}),
        "input_units": ("input", [INPUT_UNITS[name] for name in first.inputs],
                        {"long_name": "units of each input"}),
        "output_units": ("output", [({**OUTPUTS, **ROOT_OUTPUTS})[name][0] for name in first.outputs],
                         {"long_name": "units of each output"}),
    }
    data_vars = {
        "A": (("speed", "state", "state_j"), stack["A"], {"long_name": "state matrix A of x' = A x + B u",
                                                          "units": "1"}),
        "B": (("speed", "state", "input"), stack["B"], {"long_name": "input matrix B", "units": "1"}),
        "C": (("speed", "output", "state"), stack["C"], {"long_name": "output matrix C of y = C x + D u",
                                                         "units": "1"}),
        "D": (("speed", "output", "input"), stack["D"], {"long_name": "feedthrough matrix D",
                                                         "units": "1"}),
        "growth_rate": ("speed", growth, {"units": "s-1", "long_name": "largest real part of the "
                                          "poles (> 0: an unstable plant, e.g. TLAM above its "
                                          "critical speed; about 0 for a free hub's rigid mode)"}),
    }
    tip, damping = plant.tip, plant_damping(plant, sm)
    attrs = {
        "title": f"linear models of {first.model}, {hub} hub, about a steady spin",
        "model": first.model,
        "hub": hub,
        "tip_mass_kg": float(tip.mass),
        "tip_position_m": float(tip.position),
        "tip_inertia_kg_m2": float(tip.inertia),
        "tip_offset_m": float(tip.offset),
        "n_modes": int(sm.M2.shape[0]),
        "damped": int(damping is not None and bool(np.any(np.asarray(damping)))),
        "matrix_units": "A, B: the row state's units s-1 per the column state's or input's; C, "
                        "D: the output's units per the column state's or input's (state_units, "
                        "input_units, output_units)",
    }
    if plant.root_spring is not None:
        attrs |= {f"root_spring_{key}": value for key, value in plant.root_spring.to_dict().items()}
    if motor is not None:
        attrs |= {f"drive_{key}": value for key, value in motor.to_dict().items()}
        data_vars["operating_voltage"] = ("speed", np.array([getattr(lm, "continuous", lm).operating_voltage
                                                             for lm in models]),
                                          {"units": "V", "long_name": "voltage that holds the steady spin "
                                                                      "(the input is the deviation from it)"})
    if sample_time is not None:
        attrs |= {"title": attrs["title"] + f", sampled every {first.Ts:g} s (zero-order hold)",
                  "sample_time_s": first.Ts, "input_delay_samples": first.delay,
                  "matrix_units": "A, B: the row state's units per the column state's or input's (one "
                                  "sample); C, D: the output's units per the column state's or input's "
                                  "(state_units, input_units, output_units)"}
    return xr.Dataset(data_vars, coords=coords, attrs=attrs | beam_attributes(plant.beam))


def cell(names) -> np.ndarray:
    """``names`` as a column of strings that ``scipy.io.savemat`` writes as a MATLAB cell array."""
    array = np.empty((len(names), 1), dtype=object)
    array[:, 0] = [str(name) for name in names]
    return array


def write_dataset(ds: xr.Dataset, path: os.PathLike | str) -> Path:
    """Write the dataset of :func:`to_dataset` as CF netCDF with the provenance attributes."""
    ds = ds.copy()
    ds.attrs = global_attributes(ds.attrs.pop("title"), extra=ds.attrs)
    return write_netcdf(ds, path)


def write_mat(ds: xr.Dataset, path: os.PathLike | str) -> Path:
    """Write the dataset of :func:`to_dataset` as a MATLAB file (``scipy.io.savemat``): ``A, B, C,
    D`` with the speed as their last index, ``speed``, the names ``states, inputs, outputs`` as
    cell arrays, and ``model``, ``hub``, ``tip_mass_kg``, ``tip_position_m``, ``tip_inertia_kg_m2``,
    ``tip_offset_m``, ``n_modes`` (and, where present, ``sample_time_s``, ``input_delay_samples``,
    ``operating_voltage``, the root spring's ``root_spring_*`` and the drive's ``drive_*``)."""
    from scipy.io import savemat

    contents = {name: np.moveaxis(ds[name].values, 0, -1) for name in "ABCD"}
    contents |= {"speed": ds.speed.values, "growth_rate": ds.growth_rate.values,
                 "states": cell(ds.state.values), "inputs": cell(ds.input.values),
                 "outputs": cell(ds.output.values)}
    contents |= {key: value for key, value in ds.attrs.items()
                 if key in ("model", "hub", "tip_mass_kg", "tip_position_m", "tip_inertia_kg_m2", "tip_offset_m",
                            "n_modes", "sample_time_s", "input_delay_samples")
                 or key.startswith(("root_spring_", "drive_"))}
    if "operating_voltage" in ds:
        contents["operating_voltage"] = ds.operating_voltage.values
    path = Path(path)
    with staged(path) as (stand_in,):
        savemat(stand_in, contents, do_compression=True, oned_as="column")
    return path


__all__ = ["cell", "state_units", "to_dataset", "write_dataset", "write_mat"]
