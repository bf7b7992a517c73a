"""The identification's frequency-response fit against what a user would write with scipy and
python-control (``identification.csv``).

The problem: the synthetic rig of :mod:`hubbeam.identification.synthetic` (CFOAM, three modes, root
spring, SRV02 drive), a frequency response from the voltage to the deflection angle at 500
frequencies from 0.5 to 60 Hz computed at the true parameters, coherence 0.98 over 4 averages, and
the five parameters of ``studies/identification_rig/identify.yaml`` started at their nominal values.

* ``hubbeam``: :func:`hubbeam.identification.fit.fit` from one start (its residuals from one
  batched solve of ``(s^2 M + s E + K) z = b`` over the frequencies, the matrices assembled once,
  :class:`hubbeam.identification.plant.CasePlant`);
* ``scipy + python-control``: ``scipy.optimize.least_squares`` on the same weighted residuals
  (:func:`hubbeam.identification.predictions.weighted_residuals`), each evaluation rebuilding the
  case with the parameters (:func:`hubbeam.identification.parameters.apply`), its voltage-input
  state-space model (:func:`hubbeam.linear.plant_models.plant_linear`) and its response by
  ``control.frequency_response``: what a user writes around hubbeam's public models.

Both fits start from the same point with the same bounds and tolerances; the table gives each wall
time (:func:`benchmarks.timing.median_time`), the residual evaluations (the finite-difference
Jacobians' included), the largest relative error of the fitted values against the truth, and the
ratio to hubbeam's.
"""

from __future__ import annotations

import numpy as np
import scipy.optimize

from benchmarks.timing import median_time
from hubbeam.configuration.settings import case_plant
from hubbeam.identification.experiments import FrequencyResponse
from hubbeam.identification.fit import fit
from hubbeam.identification.parameters import Parameter, apply
from hubbeam.identification.predictions import Prediction, weighted_residuals
from hubbeam.identification.synthetic import TRUTH, rig_plant
from hubbeam.linear.plant_models import plant_linear

#: the free parameters: key -> (lower, upper, start = the nominal rig's value)
BOUNDS = {"root_spring.stiffness": (10.0, 60.0, 30.0), "beam.EI_factor": (0.7, 1.3, 1.0),
          "damping.transverse": (0.001, 0.1, 0.02), "drive.motor_constant_factor": (0.7, 1.3, 1.0),
          "drive.viscous_friction": (0.0, 0.05, 0.015)}
FREQUENCIES = np.geomspace(0.5, 60.0, 500)
TOLERANCES = {"xtol": 1e-10, "ftol": 1e-10, "gtol": 1e-10}


def experiment(plant) -> FrequencyResponse:
    """The measured response: the truth's, with a coherence of 0.98 over 4 averages."""
    response = plant.frequency_response(TRUTH, "voltage", "deflection_angle", FREQUENCIES)
    return FrequencyResponse("frf", "voltage", "deflection_angle", FREQUENCIES, response,
                             coherence=np.full(FREQUENCIES.size, 0.98), averages=4.0)


def parameters() -> tuple[Parameter, ...]:
    return tuple(Parameter(key, low, high, start) for key, (low, high, start) in BOUNDS.items())


def python_control_fit(plant, measured: FrequencyResponse, found: tuple[Parameter, ...]) -> tuple[np.ndarray, int]:
    """``least_squares`` around python-control's frequency response of the rebuilt plant: the
    fitted values and the residual evaluations."""
    import control as ct

    omega = 2.0 * np.pi * measured.frequency
    evaluations = 0

    def residual(x):
        nonlocal evaluations
        evaluations += 1
        values = {parameter.key: float(v) for parameter, v in zip(found, x)}
        case, beam = apply(plant.case, plant.beam, values)
        model = plant_linear(case_plant(case, beam, plant.numerics), case.model, 0.0, "free", ("deflection_angle",))
        response = ct.frequency_response(model.to_control(), omega, squeeze=True).complex
        return weighted_residuals(measured, Prediction(measured.name, {"response": np.asarray(response)}))

    best = scipy.optimize.least_squares(residual, [p.start for p in found], bounds=(
        [p.lower for p in found], [p.upper for p in found]), **TOLERANCES)
    return best.x, evaluations


def identification_rows(repeats: int, budget: float) -> list[dict]:
    """One row per route (module docstring), timed within ``budget`` seconds each."""
    plant = rig_plant()
    measured, found = experiment(plant), parameters()
    truth = np.array([TRUTH[p.key] for p in found])
    ours = fit(plant, [measured], found, starts=1, seed=0)
    theirs, evaluations = python_control_fit(plant, measured, found)
    routes = (("hubbeam fit (batched solve)", lambda: fit(plant, [measured], found, starts=1, seed=0),
               ours.evaluations, ours.value),
              ("scipy least_squares + python-control", lambda: python_control_fit(plant, measured, found),
               evaluations, theirs))
    rows = []
    for route, call, count, values in routes:
        seconds, runs = median_time(call, repeats, budget)
        rows.append({"route": route, "seconds": seconds, "repeats": runs, "evaluations": count,
                     "max_relative_error": float(np.max(np.abs(values / truth - 1.0))),
                     "parameters": len(found), "frequencies": FREQUENCIES.size})
    for row in rows:
        row["ratio_to_hubbeam"] = row["seconds"] / rows[0]["seconds"]
    return rows
