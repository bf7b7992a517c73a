"""Every case resolved for its run, and checked before any job: its law, its sampled controller, its shaper.

What a case needs besides its configuration depends on the matrices of the run (its modes, its tip
body, the drive's rotor), so it is resolved for each run (:func:`resolve`, the ``resolve`` of
:func:`hubbeam.simulation.simulate.simulate`, a convergence rerun its own):

* a ``state_feedback`` maneuver run continuously: its :class:`~hubbeam.model.maneuvers.FeedbackLaw`
  (:func:`hubbeam.control.feedback.feedback_law`);
* run as a sampled digital controller (``maneuver.sampling``): the design's continuous linear model
  (:func:`hubbeam.control.feedback.design_plant`) sampled with its zero-order hold and delay
  (:func:`hubbeam.linear.discrete.discretise`), the gain (discrete LQR, or the continuous LQR gain
  through the hold, :mod:`hubbeam.control.dlqr`), the estimator (the exact states, the courseware's
  filtered differences, or a steady-state Kalman filter, :mod:`hubbeam.control.kalman`), as the
  matrices of the compiled loop (:func:`sampled_controller`, :mod:`hubbeam.control.sampled`) with
  the sensors of the simulated model (:func:`sampled_loop`);
* a ``shaper``: its impulses, tuned on given frequencies or on the linear model's modes
  (:mod:`hubbeam.control.shaping`), rounded to the samples of a sampled controller, which must
  sample its modes (:func:`case_shaper`).

:func:`case_problems` resolves every case of a configuration on its own matrices before any job
runs, and reports what would stop one as a problem naming its key (the workflow refuses the
configuration with all of them, ``hubbeam.check.check_configuration``). :func:`simulate_case` runs any case.
"""

from __future__ import annotations

import dataclasses
import functools
import math

from hubbeam.configuration.schema import Problem
from hubbeam.configuration.settings import Case, Settings, simulation_settings
from hubbeam.control.dlqr import continuous_lqr, discrete_lqr
from hubbeam.control.feedback import FeedbackError, design_plant, feedback_law, rigid_inertia
from hubbeam.control.kalman import kalman_filter
from hubbeam.control.sampled import (
    SampledController,
    filtered_difference_controller,
    kalman_controller,
    rigid_feedforward,
    state_controller,
)
from hubbeam.control.sampling import sensor_unit
from hubbeam.control.shaping import ShapingMode, case_shaping_mode
from hubbeam.linear.discrete import discretise
from hubbeam.linear.export import state_units
from hubbeam.linear.lumped import LUMPED_SIGNALS
from hubbeam.linear.reduction import MODAL_PREFIX, reduce_for_sampling
from hubbeam.linear.statespace import OUTPUTS, linear_model
from hubbeam.model.eigen import critical_speed
from hubbeam.model.maneuvers import StateFeedback
from hubbeam.model.shapers import Shaper, check_sampling, rounded
from hubbeam.results.reader import simulation_inputs
from hubbeam.simulation.errors import SimulationError
from hubbeam.simulation.sampled import SampledLoop
from hubbeam.simulation.simulate import Resolved, case_matrices, needs_resolving, simulate


def sampling_of(case: Case):
    """The case's sampled controller settings (``maneuver.sampling``), or None."""
    return case.maneuver.sampling if isinstance(case.maneuver, StateFeedback) else None


def sampled_controller(case: Case, beam, sm) -> SampledController:
    """The sampled controller of ``case`` (module docstring) for the run's matrices ``sm``."""
    maneuver, sampling = case.maneuver, case.maneuver.sampling
    spec = maneuver.design
    plant = design_plant(case, beam, sm)
    if sampling.reduce:
        plant, _ = reduce_for_sampling(plant, sampling.sample_time)
    dm = discretise(plant, sampling.sample_time, sampling.delay)
    design = discrete_lqr if sampling.gain == "discrete" else continuous_lqr
    lqr = design(dm, spec.weights, spec.input_weight)
    # the sensors' rows: the same at any speed
    simulated = linear_model(beam, sm, case.model, 0.0, "free", root_spring=case.root_spring)
    u_max = math.inf if case.drive is None else case.drive.voltage_limit
    feedforward = rigid_feedforward(rigid_inertia(case, sm), case.drive) if maneuver.feedforward else None
    estimator = sampling.estimator
    if estimator.kind == "exact":
        return state_controller(lqr, simulated, u_max, 0.0, feedforward)
    if estimator.kind == "filtered_differences":
        return filtered_difference_controller(lqr, sampling.sensors, estimator.cutoff, simulated, u_max, 0.0,
                                              feedforward)
    kf = kalman_filter(dm, sampling.sensors, estimator.input_noise or 0.0, dict(estimator.state_noise or {}),
                       form=estimator.form or "current")
    return kalman_controller(lqr, kf, simulated, u_max, 0.0, feedforward)


def reduction_error(case: Case, beam, sm):
    """The largest relative frequency-response error of the case's truncated design model up to half
    the sampling frequency (``hubbeam.linear.reduction.response_error``)."""
    return reduce_for_sampling(design_plant(case, beam, sm), case.maneuver.sampling.sample_time)[1]


def estimate_unit(name: str, inputs=()) -> str:
    """The unit of a state the controller estimates: a measured signal's (the lumped model's
    states), none for a modal coordinate of a truncated model (``mode_k``, a mixture of states), or a
    beam model's (``hubbeam.linear.export.state_units``)."""
    if name in LUMPED_SIGNALS:
        return OUTPUTS[LUMPED_SIGNALS[name]][0]
    return "1" if name.startswith(MODAL_PREFIX) else state_units(name, inputs)


def sampled_loop(case: Case, controller: SampledController) -> SampledLoop:
    """The compiled loop of ``controller`` with the sensors of ``case`` (their gains, offsets, noise,
    low-pass and quantisation: a run may read the controller's signals otherwise than its design
    assumed, e.g. without noise; the exact estimator's readings, which a case does not list, without
    any), each in its unit (:func:`hubbeam.control.sampling.sensor_unit`), the noise seeded by
    ``sampling.seed``."""
    sensors = case.maneuver.sampling.sensors or controller.sensors
    if [sensor.signal for sensor in sensors] != [sensor.signal for sensor in controller.sensors]:
        raise ValueError(f"case {case.label!r} reads {[sensor.signal for sensor in sensors]}; allowed: the "
                         f"controller's signals in its order, {[sensor.signal for sensor in controller.sensors]}")
    sensors = [dataclasses.replace(sensor, unit=sensor_unit(sensor)) for sensor in sensors]
    inputs = controller.design.inputs
    return SampledLoop(sensors, controller.sensor_rows, **controller.matrices, Ts=controller.Ts, D=controller.D,
                       u_max=controller.u_max, u_init=controller.u_init, seed=case.maneuver.sampling.seed,
                       estimate_states=controller.estimate_states,
                       estimate_units=tuple(estimate_unit(name, inputs) for name in controller.estimate_states))


def case_shaper(case: Case, beam, sm, sample_time: float | None = None) -> Shaper:
    """The command shaper of ``case`` (``case.shaper``): on its given frequencies, or tuned on the
    modes the command excites in the linearisation of its model (or the shaper's) at the shaper's
    speed (default the maneuver's final speed), designed at its ``frequency_ratio`` times their
    frequencies if it has one; with a ``sample_time``, checked against it and
    rounded to its samples (``hubbeam.model.shapers``)."""
    spec = case.shaper
    modes = spec.given_modes()
    if modes is None:
        speed = case.maneuver.final_speed if spec.speed is None else spec.speed
        found = [case_shaping_mode(case, beam, sm, speed, mode=number, model=spec.model) for number in spec.modes]
        modes = spec.design_modes([(mode.omega, mode.zeta) for mode in found])
    shaper = spec.shaper(modes)
    if sample_time is None:
        return shaper
    check_sampling(shaper, sample_time)
    return rounded(shaper, sample_time)


def dataset_shaping_mode(ds, model: str, speed: float | None = None) -> ShapingMode:
    """The mode :func:`case_shaper` would tune the case of the simulation dataset ``ds`` to
    (:func:`~hubbeam.control.shaping.case_shaping_mode`, its first mode) on ``model``'s
    linearisation at ``speed`` (default the maneuver's final speed): the case, beam and matrices
    rebuilt from the dataset's attributes (:func:`hubbeam.results.reader.simulation_inputs`). A
    study finds the mode a shaper should have been tuned to on the model it ran on this way."""
    inputs = simulation_inputs(ds.attrs)
    beam = inputs["params"]
    case, numerics = simulation_settings(inputs["case"], inputs["numerics"], beam.L)
    sm = case_matrices(case, beam, numerics)
    return case_shaping_mode(case, beam, sm, case.maneuver.final_speed if speed is None else speed, model=model)


def dataset_critical_speed(ds, model: str = "TLAM", search_max: float = 100.0) -> float:
    """``model``'s critical speed (rad s-1; NaN when none up to ``search_max``) for the beam, tip
    mass and modes of the simulation dataset ``ds`` (:func:`hubbeam.model.eigen.critical_speed`)."""
    inputs = simulation_inputs(ds.attrs)
    beam = inputs["params"]
    case, numerics = simulation_settings(inputs["case"], inputs["numerics"], beam.L)
    return critical_speed(model, beam, case.tip_mass, case.modes, search_max, numerics.quadrature_points)


def resolve(case: Case, sm, beam) -> Resolved:
    """What ``case`` needs for a run on the matrices ``sm`` of ``beam`` (module docstring), with the
    dataset attributes that record it; a :class:`~hubbeam.control.feedback.FeedbackError` naming the
    key of what cannot be resolved."""
    where = f"cases.{case.label}"
    sampling = sampling_of(case)
    law, loop, attributes = None, None, {}
    if sampling is not None:
        try:
            controller = sampled_controller(case, beam, sm)
            loop = sampled_loop(case, controller)
        except (ValueError, SimulationError) as error:
            if isinstance(error, FeedbackError):
                raise
            raise FeedbackError(f"{where}.maneuver.sampling", str(error)) from None
        # netCDF attributes are one-dimensional: the predicted poles as their real and imaginary parts
        attributes = {"controller_kind": controller.kind,
                      "controller_poles_real": controller.poles.real.tolist(),
                      "controller_poles_imag": controller.poles.imag.tolist()}
        if sampling.reduce:
            error = reduction_error(case, beam, sm)
            attributes |= {"design_reduced_states": controller.design.plant_states,
                           "design_reduction_error": error.value, "design_reduction_error_output": error.output,
                           "design_reduction_error_hz": error.frequency}
    elif case.maneuver.needs_law:
        law, attributes = feedback_law(case, sm, beam)
    shaper = None
    if case.shaper is not None:
        try:
            shaper = case_shaper(case, beam, sm, None if sampling is None else sampling.sample_time)
        except ValueError as error:
            raise FeedbackError(f"{where}.shaper", str(error)) from None
    return Resolved(law, loop, shaper, attributes)


def case_problems(settings: Settings) -> list[Problem]:
    """What would stop a case of ``settings`` once its matrices are known (module docstring), found by
    resolving it on its own matrices (``numerics.quadrature_points`` Gauss nodes), one problem per
    case."""
    problems = []
    for case in settings.cases.values():
        if not needs_resolving(case):
            continue
        sm = case_matrices(case, settings.beam, settings.numerics)
        try:
            resolve(case, sm, settings.beam)
        except FeedbackError as error:
            problems.append(error.problem)
    return problems


def simulate_case(case, params, numerics, matrices=None, **options):
    """:func:`hubbeam.simulation.simulate.simulate` of any case, resolved (:func:`resolve`) for the
    matrices of every run."""
    return simulate(case, params, numerics, matrices, resolve=functools.partial(resolve, beam=params), **options)


