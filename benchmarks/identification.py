"""The identification's fits against what a user would write with scipy (and python-control):
a frequency-response fit (``identification.csv``) and a time-series fit
(``identification_time_series.csv``).

The frequency-response problem: the synthetic rig of :mod:`hubbeam.identification.synthetic`
(CFOAM, three modes, root spring, SRV02 drive), a frequency response from the voltage to the
deflection angle at 500 frequencies from 0.5 to 60 Hz computed at the true parameters, coherence
0.98 over 4 averages, and the five parameters of the shipped study (``studies/identification_rig/study.yaml``)
started at their nominal values.

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

The time-series problem (:func:`time_series_rows`): the same rig with the factors on ``EI`` and on
the motor constants set to their true values (:data:`SERIES_HELD`, known, not fitted), driven by a
voltage doublet of 0.1 V (0.2 s each way from 0.1 s, :data:`DOUBLET`) and recorded for 10 s at
1 kHz (10 001 samples; the test runs a shorter, coarser record): the hub angle and the deflection
angle of the true plant, simulated by hubbeam, plus seeded Gaussian noise of 1e-5 rad and 2e-6 rad
(about 1/1500 and 1/1800 of their peaks of 0.015 rad and 0.0036 rad), unit gain, no offset, no
quantisation (:data:`SERIES_SENSORS`: synthetic sensors far finer than the rig's 4096-count
encoder, which would see 10 counts of this motion). Three parameters are free, each started at
its nominal value within the bounds of the frequency-response problem (:data:`SERIES_BOUNDS`):
the root spring's stiffness (the first mode), the modal damping ratio of the bending modes and
the drive's viscous friction (the hub's decay).

* ``hubbeam``: :func:`~hubbeam.identification.fit.fit` from one start on the
  :class:`~hubbeam.identification.experiments.TimeSeries`. Each evaluation integrates the
  NONLINEAR CFOAM with the drive and the compliant root (:meth:`CasePlant.simulate`, hubbeam's
  jitted Radau IIA at the rig's ``rtol = 1e-7``, ``atol = 1e-10``, the voltage linear between the
  samples), the same model that made the record. Its time includes what the fit does after the
  minimum: one more residual evaluation and a central-difference Jacobian (``1 + 2 x 3`` of its
  evaluations) and the identifiability analysis on that Jacobian.
* ``scipy``: ``scipy.optimize.least_squares`` with hubbeam's fit's options (:data:`FIT_OPTIONS`,
  the parameters scaled to their bounds) around ``scipy.integrate.solve_ivp`` on the LINEAR
  equations about rest, ``M z'' + E z' + K z = b V`` of
  :meth:`~hubbeam.identification.plant.CasePlant.equations` (the drive's back-EMF and viscous
  friction on the hub row; the SRV02 model has no Coulomb friction and the 10 V limit is not
  reached), ``LSODA`` with ``rtol = 1e-10``, ``atol = 1e-13`` and the constant Jacobian
  (:data:`ODE`, :func:`linear_readings`), the same signal rows and sensor model, the same
  weighted residuals.

The two routes do not integrate the same equations: the linearisation drops the terms of second
order in the motion (the centrifugal stiffening by ``theta'^2``, the foreshortening), which is why
the doublet is small. Measured at the truth on the 10 s record when this benchmark was written: the
linear readings differ from the nonlinear ones by at most 1.9e-6 (hub angle) and 1.2e-5 (deflection
angle) of their peaks, 0.003 and 0.022 of the noise's standard deviation (at 1.5 V, the amplitude
of the rig's own doublet, the deflection angle is 2.8e-3 of its peak off, 75 times this record's
noise); the integrators' own errors are 5e-10 of the peak (hubbeam, against its run at ``rtol =
1e-12``) and 9e-10 (LSODA, against the exact discretisation of the linear equations with the input
linear between the samples, ``scipy.signal.lsim``); and the fitted values of the two routes differ
by less than a tenth of hubbeam's standard errors (3.4e-5 relative at most). The table gives each
route's wall time, residual evaluations, the largest relative error of its fitted values against
the truth (noise-limited: the truth is not the least-squares minimum of noisy data), the largest
relative difference of its fitted values to hubbeam's, and the ratio of its wall time to hubbeam's.
"""

from __future__ import annotations

import numpy as np
import scipy.optimize
from scipy.integrate import solve_ivp

from benchmarks.timing import median_time
from hubbeam.configuration.settings import case_plant
from hubbeam.identification.experiments import FrequencyResponse, TimeSeries
from hubbeam.identification.fit import fit
from hubbeam.identification.parameters import Parameter, apply
from hubbeam.identification.plant import CasePlant
from hubbeam.identification.predictions import Prediction, first_order_lag, weighted_residuals
from hubbeam.identification.synthetic import TRUTH, doublet, measured, rig_plant
from hubbeam.linear.plant_models import plant_linear
from hubbeam.linear.statespace import output_rows
from hubbeam.model.maneuvers import SensorSpec

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


#: the time-series problem's free parameters: key -> (lower, upper, start = the nominal rig's value)
SERIES_BOUNDS = {"root_spring.stiffness": (10.0, 60.0, 30.0), "damping.transverse": (0.001, 0.1, 0.02),
                 "drive.viscous_friction": (0.0, 0.05, 0.015)}
#: the other parameters of :data:`TRUTH`, applied to the rig at their true values before either fit
SERIES_HELD = {key: value for key, value in TRUTH.items() if key not in SERIES_BOUNDS}
#: the voltage doublet: amplitude (V), duration of each half (s) and start (s)
DOUBLET = {"amplitude": 0.1, "width": 0.2, "start": 0.1}
#: the benchmark's record: duration (s) and sample rate (Hz), 10 001 samples
SERIES_DURATION, SERIES_RATE = 10.0, 1000.0
#: the sensors of the record: unit gain, no offset, no quantisation, white noise (rad)
SERIES_SENSORS = {"hub_angle": SensorSpec("hub_angle", noise=1.0e-5),
                  "deflection_angle": SensorSpec("deflection_angle", noise=2.0e-6)}
#: the seed of the record's noise
SERIES_SEED = 20250101
#: ``solve_ivp``'s method and tolerances for the linear equations
ODE = {"method": "LSODA", "rtol": 1e-10, "atol": 1e-13}
#: the options of :func:`hubbeam.identification.fit.fit` with a time series, given to the scipy route as well
FIT_OPTIONS = {"method": "trf", "x_scale": 1.0, "diff_step": 1e-4, "max_nfev": 200, "xtol": 1e-10, "ftol": 1e-12,
               "gtol": 1e-10}


def series_plant() -> CasePlant:
    """The synthetic rig (:func:`rig_plant`) with :data:`SERIES_HELD` applied: the plant both routes fit."""
    rig = rig_plant()
    return CasePlant(*apply(rig.case, rig.beam, SERIES_HELD), rig.numerics)


def series_experiment(plant: CasePlant, duration: float = SERIES_DURATION, rate: float = SERIES_RATE) -> TimeSeries:
    """The doublet's record of ``duration`` s at ``rate`` Hz: the true plant simulated by hubbeam
    (nonlinear CFOAM) and read by :data:`SERIES_SENSORS`, the noise seeded by :data:`SERIES_SEED`."""
    t, command = doublet(duration, 1.0 / rate, **DOUBLET)
    truth = {key: TRUTH[key] for key in SERIES_BOUNDS}
    return measured(plant, truth, "doublet", t, list(SERIES_SENSORS), np.random.default_rng(SERIES_SEED),
                    command=command, sensors=SERIES_SENSORS)


def series_parameters() -> tuple[Parameter, ...]:
    return tuple(Parameter(key, low, high, start) for key, (low, high, start) in SERIES_BOUNDS.items())


def linear_readings(plant: CasePlant, series: TimeSeries, values) -> dict[str, np.ndarray]:
    """The readings of ``series``'s sensors predicted by ``solve_ivp`` (:data:`ODE`) on the linear
    equations about rest ``M z'' + E z' + K z = b V`` of ``plant`` with the parameter ``values``
    (:meth:`CasePlant.equations` with the voltage as input), written as ``x' = A x + B V(t)``,
    ``x = (z, z')``, from rest; ``V(t)`` linear between the samples (``np.interp``), the integration
    restarted at every sample where the interpolated input has a kink (8 for a doublet: stepping
    across them from rest, LSODA's first steps can grow past the whole doublet unseen); the signals
    ``Cz z + Cv z' + Ca z''`` of :func:`hubbeam.linear.statespace.output_rows`, read as the sensor
    says (gain, offset, the analog low-pass, half a quantum below for an encoder counting edges)."""
    if series.loop is not None or series.hold != "linear":
        raise ValueError(f"experiment {series.name}: loop {series.loop}, hold {series.hold}; allowed: open loop, "
                         "linear hold")
    eq = plant.equations(values, input="voltage")
    N = eq.M.shape[0]
    b = np.zeros(N)
    b[eq.hub] = eq.gain
    Az, Av, Bu = np.split(np.linalg.solve(eq.M, np.column_stack([-eq.K, -eq.E, b])), [N, 2 * N], axis=1)
    A = np.block([[np.zeros((N, N)), np.eye(N)], [Az, Av]])
    B = np.concatenate([np.zeros(N), Bu[:, 0]])
    names = list(series.signals)
    Cz, Cv, Ca = output_rows(eq.beam, eq.sm, plant.traits, 0.0, eq.q1s, names, eq.case.root_spring)
    C, D = np.hstack([Cz + Ca @ Az, Cv + Ca @ Av]), (Ca @ Bu)[:, 0]
    t, u = series.time - series.time[0], series.command

    def rhs(time, x):
        return A @ x + B * np.interp(time, t, u)

    kinks = np.flatnonzero(np.diff(u, 2)) + 1
    edges = np.unique(np.concatenate([[0], kinks, [t.size - 1]]))
    states = np.empty((2 * N, t.size))
    x = np.zeros(2 * N)
    for first, last in zip(edges[:-1], edges[1:]):
        solution = solve_ivp(rhs, (t[first], t[last]), x, t_eval=t[first:last + 1], jac=lambda time, x: A, **ODE)
        if not solution.success:
            return {name: np.full(t.size, np.nan) for name in names}  # weighted_residuals: FAILED
        states[:, first:last + 1] = solution.y
        x = solution.y[:, -1]
    signals = C @ states + D[:, None] * u
    readings = {}
    for name, signal in zip(names, signals):
        spec = series.sensors[name]
        reading = spec.gain * signal + spec.offset
        if spec.lowpass > 0.0:
            reading = first_order_lag(reading, series.step, spec.lowpass)
        readings[name] = reading - (0.5 * spec.quantum if spec.mode == "edges" else 0.0)
    return readings


def solve_ivp_fit(plant: CasePlant, series: TimeSeries, found: tuple[Parameter, ...]) -> tuple[np.ndarray, int]:
    """``least_squares`` (:data:`FIT_OPTIONS`, the parameters scaled to their bounds as hubbeam's fit
    scales them) on the weighted residuals of :func:`linear_readings`: the fitted values and the
    residual evaluations."""
    evaluations = 0

    def residual(x):
        nonlocal evaluations
        evaluations += 1
        values = {p.key: float(p.unscaled(xi)) for p, xi in zip(found, x)}
        return weighted_residuals(series, Prediction(series.name, linear_readings(plant, series, values)))

    best = scipy.optimize.least_squares(residual, [p.scaled(p.start) for p in found], bounds=(0.0, 1.0),
                                        **FIT_OPTIONS)
    return np.array([p.unscaled(xi) for p, xi in zip(found, best.x)]), evaluations


def time_series_rows(repeats: int, budget: float, duration: float = SERIES_DURATION,
                     rate: float = SERIES_RATE) -> list[dict]:
    """One row per route of the time-series fit (module docstring) on a record of ``duration`` s at
    ``rate`` Hz, timed within ``budget`` seconds each (the fitted values from the first timed run)."""
    plant = series_plant()
    measured_series, found = series_experiment(plant, duration, rate), series_parameters()
    truth = np.array([TRUTH[p.key] for p in found])
    fitted = {}

    def ours():
        result = fit(plant, [measured_series], found, starts=1, seed=0)
        fitted.setdefault("hubbeam", (result.value, result.evaluations))

    def theirs():
        fitted.setdefault("scipy", solve_ivp_fit(plant, measured_series, found))

    routes = (("hubbeam fit (jitted nonlinear CFOAM)", "hubbeam", ours),
              ("scipy least_squares + solve_ivp (linear equations)", "scipy", theirs))
    rows = []
    for route, key, call in routes:
        seconds, runs = median_time(call, repeats, budget)
        values, count = fitted[key]
        rows.append({"route": route, "seconds": seconds, "repeats": runs, "evaluations": count,
                     "max_relative_error": float(np.max(np.abs(values / truth - 1.0))),
                     "max_relative_difference_to_hubbeam": float(np.max(np.abs(values / fitted["hubbeam"][0] - 1.0))),
                     "parameters": len(found), "samples": measured_series.time.size, "duration_s": duration,
                     "rate_hz": rate})
    for row in rows:
        row["ratio_to_hubbeam"] = row["seconds"] / rows[0]["seconds"]
    return rows
