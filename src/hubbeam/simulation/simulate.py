"""Python API of a simulation: validate a case, run the jitted kernel, label the result.

:func:`simulate` turns a resolved case (``hubbeam.configuration.settings.Case.to_dict``), the beam parameters
(Table 1) and the ``numerics`` section of the config into the simulation dataset of
``docs/architecture.md``. The hub-beam starts at rest and undeformed (``theta = 0``, ``q = 0``,
all rates zero), or at the operating point of the case's optional ``initial`` mapping
(:func:`initial_state`: a steady spin with ``q1`` at its centrifugal stretch, plus given modal
coordinates and rates). The whole time integration runs in :func:`hubbeam.core.integrate.simulate_kernel`
(Radau IIA of order 5, :mod:`hubbeam.core.radau`). A run stopped early is a result with NaN
outputs after ``stopped_at_s``: stopped at a tip deflection beyond ``numerics.divergence_limit * L``
it has ``left_range = 1``, or ``diverged = 1`` when it went beyond its critical speed (or its state
blew up); a completed run beyond ``numerics.small_deflection_limit * L`` has
``large_deflection = 1`` (:mod:`hubbeam.model.validity`, attribute ``validity``).

Guard rails written into the dataset's ``warnings`` attribute: more accepted steps than
``numerics.step_warning``, an exhausted step budget, a large deflection, a run that left the range
of the models or diverged, and, when the optional
convergence check (``numerics.convergence_check``) is given, a tip deflection that changes by more
than its threshold when the case is rerun at a tighter tolerance or with more modes.
:func:`hubbeam.results.reader.simulation_inputs` turns the attributes of a dataset back into the
arguments that reproduce it.
"""

from __future__ import annotations

import dataclasses
import json
import logging
import math
import time
from collections.abc import Mapping
from typing import NamedTuple

import numpy as np
import xarray as xr
from scipy.integrate import cumulative_simpson

from hubbeam.configuration.settings import Case, ConvergenceCheck, Numerics, case_plant, simulation_settings
from hubbeam.core import maneuver as kernel_maneuvers
from hubbeam.core import radau
from hubbeam.core.eom import free_coordinates
from hubbeam.core.inputs import IDENTITY_SHAPER, NO_DRIVE, IntegratorSettings, SampleRecords, SimulationInputs, State
from hubbeam.core.integrate import n_output_columns, output_columns, simulate_kernel
from hubbeam.core.sampled import simulate_sampled_kernel
from hubbeam.model import linearised, validity
from hubbeam.model.beam import beam_attributes
from hubbeam.model.damping import damping_matrices
from hubbeam.model.limits import (
    MAX_MODES,
    MAX_QUADRATURE_POINTS,
    MIN_QUADRATURE_POINTS,
    MIN_RTOL,
)
from hubbeam.model.maneuvers import FeedbackLaw, Maneuver, PdControl, SensorSpec, SpinUp, Tracking
from hubbeam.model.matrices import SystemMatrices
from hubbeam.model.models import FAMILIES, family_model, model
from hubbeam.model.parameters import BeamParameters, TipMass
from hubbeam.model.plant import plant_matrices, with_drive
from hubbeam.model.root import joint_inputs
from hubbeam.model.shapers import Shaper, shaped_stops
from hubbeam.results.provenance import global_attributes
from hubbeam.results.variables import (
    CUMULATIVE_VARIABLES,
    JOINT_WORK,
    SAMPLE_VARIABLES,
    dataset_variables,
    output_count,
)
from hubbeam.simulation.errors import SimulationError
from hubbeam.simulation.sampled import SampledLoop, held_table, loop_arrays, reference_array, sensor_unit

LOG = logging.getLogger(__name__)

INTEGRATOR = "Radau IIA order 5 (hubbeam.core.radau), dense output by quintic Hermite interpolation"


def initial_state(case: Case, sm: SystemMatrices) -> State:
    """The state ``(y, y')`` of ``y = (theta, q1, q2)`` at ``t = 0`` of a checked case (the
    configuration's checks, ``hubbeam.configuration.checks``), from its optional ``initial``
    state (:class:`~hubbeam.configuration.settings.InitialState`; default: rest); with a
    compliant root (``case.root_spring``, ``hubbeam.model.root``) of ``(theta, q1, q2, phi)``, the
    hub angle ``phi = 0`` turning with the root (the spring relaxed):

    * ``hub_speed`` (rad s-1, default 0): a steady spin, ``theta = 0``, ``theta' = hub_speed``,
      with ``q1`` at its centrifugal stretch ``q1s`` for that speed
      (:func:`hubbeam.model.linearised.axial_stretch`; zero for a model that keeps no ``q1``) and
      ``q2 = 0``; for a prescribed maneuver it must be the maneuver's speed at ``t = 0``;
    * ``q1``, ``q2``, ``q1_dot``, ``q2_dot`` (one value per mode, default zeros): added to the
      modal coordinates and rates of that state.
    """
    n = case.modes
    spec = case.initial
    hub = [] if case.root_spring is None else [0.0]
    if spec is None:
        size = 1 + 2 * n + len(hub)
        return State(np.zeros(size), np.zeros(size))
    speed = spec.hub_speed or 0.0
    q1s = linearised.axial_stretch(sm, speed) if model(case.model).keeps_axial else np.zeros(n)
    return State(np.concatenate([[0.0], q1s + spec.modal("q1", n), spec.modal("q2", n), hub]),
                 np.concatenate([[speed], spec.modal("q1_dot", n), spec.modal("q2_dot", n), [speed] * len(hub)]))


def output_times(t_end: float, output_step: float) -> np.ndarray:
    """The uniform output grid ``0, dt, 2 dt, ...`` up to the last multiple of ``dt`` <= t_end."""
    return np.arange(output_count(t_end, output_step)) * output_step


def kernel_matrices(sm: SystemMatrices) -> SystemMatrices:
    """``sm`` with C-contiguous float64 arrays and float scalars (one compiled kernel for all)."""
    return SystemMatrices(*(np.ascontiguousarray(value, dtype=np.float64) if np.ndim(value)
                            else float(value) for value in sm))


def case_matrices(case: Case, params: BeamParameters, numerics: Numerics,
                  matrices: SystemMatrices | None = None) -> SystemMatrices:
    """The system matrices of ``case``: those of its plant (``hubbeam.model.plant.plant_matrices``:
    ``params`` with the case's tip body, modes and transverse functions, the reflected inertia of the
    case's drive rotor in the hub's), or ``matrices`` given (checked; the rotor added,
    :func:`hubbeam.model.plant.with_drive`)."""
    n = case.modes
    if matrices is None:
        if numerics.quadrature_points is None:
            raise SimulationError(f"numerics.quadrature_points: missing (required when no matrices are "
                                  f"given); allowed: an integer in {MIN_QUADRATURE_POINTS}..{MAX_QUADRATURE_POINTS}")
        return kernel_matrices(plant_matrices(case_plant(case, params, numerics)))
    if np.shape(matrices.K1) != (n, n):
        raise SimulationError(f"cases.{case.label}.modes = {n}, but the matrices given have "
                              f"{np.shape(matrices.K1)[0]} modes; allowed: matrices assembled with the case's "
                              "number of modes")
    return with_drive(kernel_matrices(matrices), case.drive)


class Resolved(NamedTuple):
    """What a case needs besides its settings, resolved for the matrices of one run: the feedback
    law of a state feedback (``law``), the sampled digital controller (``loop``, which replaces the
    law), the command shaper (``shaper``) and the dataset attributes that record them. ``resolve``
    (:func:`simulate`) gives it; ``hubbeam.control.cases`` resolves every kind of case."""

    law: FeedbackLaw | None = None
    loop: SampledLoop | None = None
    shaper: Shaper | None = None
    attributes: Mapping | None = None


#: the resolution of a case that needs none
UNRESOLVED = Resolved()


def needs_resolving(case: Case) -> bool:
    """Whether ``case`` needs a resolver: a law to design or resolve, a sampled controller, a shaper."""
    return case.maneuver.needs_law or case.shaper is not None


class Run(NamedTuple):
    """One integration: the output grid ``t``, the output array ``out`` (columns
    ``hubbeam.core.integrate.output_columns``), radau5's ``status`` and ``t_stop``, the integrator's
    attributes, and under a sampled controller its :class:`~hubbeam.core.inputs.SampleRecords`
    ``records`` (NaN after the stop) and the sensor noise it drew (else None)."""

    t: np.ndarray
    out: np.ndarray
    status: int
    t_stop: float
    integrator: dict
    records: SampleRecords | None = None
    noise: np.ndarray | None = None


def simulate(case: Case | Mapping, params: BeamParameters, numerics: Numerics | Mapping,
             matrices: SystemMatrices | None = None, *,
             convergence_check: ConvergenceCheck | Mapping | None = None, resolve=None) -> xr.Dataset:
    """Simulate one case from its initial state and return the labelled simulation dataset.

    Parameters
    ----------
    case : a :class:`~hubbeam.configuration.settings.Case` (its ``maneuver`` and ``damping`` the
        records of :mod:`hubbeam.model.maneuvers` and :mod:`hubbeam.model.damping`, its optional
        ``initial`` state, :func:`initial_state`, ``drive`` and ``shaper``), or the mapping of a
        resolved case.
    params : the beam (Table 1 parameters, or any beam of :mod:`hubbeam.model.beam`).
    numerics : :class:`~hubbeam.configuration.settings.Numerics` or the ``numerics`` mapping of a
        configuration (``quadrature_points`` is needed when ``matrices`` is not given).
    matrices : the case's :class:`~hubbeam.model.matrices.SystemMatrices` (assembled if None).
    convergence_check : ``numerics.convergence_check`` (``tolerance_factor``, ``extra_modes``,
        ``threshold_m``); if given, the case is rerun at a tighter tolerance and with more modes and
        the differences are recorded (:func:`convergence`).
    resolve : the function ``(case, sm) ->`` :class:`Resolved` for the case's matrices (every rerun
        its own), required for a case that needs it (:func:`needs_resolving`);
        ``hubbeam.control.cases.simulate_case`` passes it.

    A drive (``case.drive``) turns the hub's command into volts, its rotor joins the hub inertia and
    the dataset gains ``hub_voltage`` and ``motor_torque``; a sampled controller (``Resolved.loop``)
    runs in the kernel between the samples, and the dataset holds its records per sample. Objects
    are used as they are (the workflow's jobs get them from the one check of the configuration);
    mappings are checked once, by the same schema and checks
    (:func:`hubbeam.configuration.settings.simulation_settings`, ``ConfigError``). The attribute
    ``quadrature_points`` records the Gauss-Legendre nodes of the matrices used, so that
    :func:`hubbeam.results.reader.simulation_inputs` can rebuild them.
    """
    case, numerics = simulation_settings(case, numerics, params.L, convergence_check)
    sm = case_matrices(case, params, numerics, matrices)
    resolved = _resolved(case, sm, resolve)
    ds = build_dataset(case, params, numerics, sm, run(case, params, numerics, sm, resolved), resolved)
    ds.attrs["quadrature_points"] = quadrature_points(sm)
    if numerics.convergence_check is not None:
        found = convergence(ds, case, params, numerics, sm, resolve)
        notes = found.pop("warnings")
        ds.attrs.update(found)
        ds.attrs["warnings"] = "; ".join(filter(None, [ds.attrs["warnings"], *notes]))
    return ds


def quadrature_points(sm: SystemMatrices) -> int:
    """Gauss-Legendre nodes of the beam integrals of ``sm`` (its point cloud less the tip)."""
    return int(np.size(sm.x) - 1)


def _resolved(case: Case, sm: SystemMatrices, resolve) -> Resolved:
    """What ``case`` needs for the run on ``sm`` (``resolve`` as in :func:`simulate`; given, it is
    asked for every case)."""
    if resolve is None and not needs_resolving(case):
        return UNRESOLVED
    if resolve is None:
        raise SimulationError(f"cases.{case.label}: a {case.maneuver.kind} maneuver"
                              f"{' with a shaper' if case.shaper is not None else ''}; allowed here only with its "
                              "resolver (run it with hubbeam.control.cases.simulate_case)")
    return resolve(case, sm)


def run(case: Case, params: BeamParameters, numerics: Numerics, sm: SystemMatrices, resolved: Resolved) -> Run:
    """Integrate ``case`` once on the matrices ``sm`` with what :func:`_resolved` gave: the
    continuous kernel (the maneuver's law, through the drive), or the sampled kernel (the loop's
    held command) (:mod:`hubbeam.core.integrate`, :mod:`hubbeam.core.sampled`)."""
    traits = model(case.model).traits
    n = case.modes
    joint = case.root_spring is not None
    N = 1 + 2 * n + (1 if joint else 0)  # theta, q1, q2 (and the hub angle phi)
    t = output_times(case.t_end, numerics.output_step)
    out = np.empty((t.size, n_output_columns(n, joint)))
    stats = np.zeros(len(radau.STAT_NAMES), dtype=np.int64)
    drive = NO_DRIVE if case.drive is None else case.drive.packed()
    shaper = IDENTITY_SHAPER if resolved.shaper is None else resolved.shaper.kernel_array()
    damping = damping_matrices(case.damping, sm)
    settings = integrator_settings(numerics, params.L)
    link, root = joint_inputs(sm, case.root_spring)
    start = time.perf_counter()
    loop = resolved.loop
    if loop is None:
        if resolved.law is not None and np.size(resolved.law.gains) != 2 * N:
            raise SimulationError(f"cases.{case.label}.maneuver: {np.size(resolved.law.gains)} feedback gains; "
                                  f"allowed: {2 * N}, one per state of {case.model} with {n} modes"
                                  + (" and the root spring's hub angle" if joint else ""))
        kind, mp = case.maneuver.kernel_parameters(resolved.law)
        inputs = SimulationInputs(traits, kind, mp, damping, link, drive, shaper, root)
        status, t_stop = simulate_kernel(inputs, initial_state(case, sm), t,
                                         step_stops(case.maneuver, t, resolved.shaper), settings, out, stats)
        records = noise = None
    else:
        if not isinstance(case.maneuver, Tracking):
            raise SimulationError(f"cases.{case.label}.maneuver.kind = {case.maneuver.kind!r} with a sampled loop; "
                                  "allowed: a maneuver that tracks a reference (the loop replaces its law)")
        if loop.rows.shape[1] != 2 * N:
            raise SimulationError(f"SampledLoop.rows: rows of length {loop.rows.shape[1]}; allowed: "
                                  f"2 N = {2 * N}, the state (y, y') of {case.model} with {n} modes"
                                  + (" and the root spring's hub angle" if joint else ""))
        inputs = SimulationInputs(traits, kernel_maneuvers.HELD, held_table(0, loop.u_init), damping, link, drive,
                                  IDENTITY_SHAPER, root)
        arrays, stops, noise = loop_arrays(loop, free_coordinates(inputs), t[-1], reference_array(case.maneuver),
                                           shaper)
        inputs = inputs._replace(mp=held_table(arrays.timing.sample_times.size, loop.u_init))
        status, t_stop = simulate_sampled_kernel(inputs, initial_state(case, sm), t, stops, settings, arrays, out,
                                                 stats)
        records = arrays.records
    wall = time.perf_counter() - start
    LOG.info("case %s (%s, %d modes%s): %s at t = %g s, %.3f s wall, %d steps (%d rejected), %d rhs calls, "
             "%d Jacobians, %d LU", case.label, case.model, n, "" if loop is None else f", sampled every {loop.Ts:g} s",
             radau.STATUS_NAMES[status], t_stop, wall, stats[radau.ACCEPTED], stats[radau.REJECTED],
             stats[radau.RHS_CALLS], stats[radau.JACOBIANS], stats[radau.FACTORIZATIONS])
    integrator = {"integrator": INTEGRATOR, "rtol": float(numerics.rtol), "atol": float(numerics.atol),
                  **{name: int(value) for name, value in zip(radau.STAT_NAMES, stats)}}
    return Run(t, out, status, t_stop, integrator, records, noise)


def integrator_settings(numerics: Numerics, length: float) -> IntegratorSettings:
    """The kernel's :class:`~hubbeam.core.inputs.IntegratorSettings` from checked ``numerics``
    for a beam of length ``length`` (the tip limit is ``divergence_limit * length``)."""
    return IntegratorSettings(float(numerics.rtol), float(numerics.atol), float(numerics.divergence_limit) * length,
                              int(numerics.max_steps))


def convergence(ds: xr.Dataset, case: Case, params: BeamParameters, numerics: Numerics,
                sm: SystemMatrices, resolve=None) -> dict:
    """Check the run ``ds`` of ``case`` (made with matrices ``sm``) against two reruns, each with
    what ``resolve`` (as in :func:`simulate`) gives for its own matrices, with the settings
    ``numerics.convergence_check``.

    The reruns change one setting each: the tolerances ``rtol`` and ``atol`` multiplied by
    ``tolerance_factor`` (``rtol`` not below :data:`MIN_RTOL`), and the number of modes raised by
    ``extra_modes`` (at most :data:`MAX_MODES`; the extra-mode matrices are assembled with at
    least the Gauss nodes of ``sm``). Each difference is the largest ``|tip_transverse -
    tip_transverse_rerun|`` in m over the output times where both runs have values, i.e. excluding
    what follows a divergence or an exhausted step budget.

    Returns the attributes ``convergence_check`` (the settings), ``convergence_rtol``,
    ``convergence_atol``, ``convergence_modes``, ``convergence_tolerance_diff_m``,
    ``convergence_modes_diff_m`` (NaN when the case already has :data:`MAX_MODES` modes) and
    ``warnings``, a list of texts: a difference above ``threshold_m``, a mode check that could not
    be made, a rerun that stopped on its step budget before the run did.
    """
    settings = numerics.convergence_check
    threshold = float(settings.threshold_m)
    tip = ds["tip_transverse"].values
    t_stop = float(ds.attrs["stopped_at_s"])
    n = case.modes
    joint = case.root_spring is not None
    tight = dataclasses.replace(numerics, rtol=max(float(numerics.rtol) * settings.tolerance_factor, MIN_RTOL),
                                atol=float(numerics.atol) * settings.tolerance_factor)
    more = min(n + int(settings.extra_modes), MAX_MODES)
    found = {"convergence_check": json.dumps(settings.to_dict(), sort_keys=True),
             "convergence_rtol": tight.rtol, "convergence_atol": tight.atol, "convergence_modes": more}
    warnings = []
    reruns = {"tolerance": (case, tight, sm, f"a rerun at rtol = {tight.rtol:.3g}, atol = {tight.atol:.3g}")}
    if more > n:
        more_case = case.with_modes(more)
        nodes = dataclasses.replace(numerics, quadrature_points=quadrature_points(sm))
        more_sm = case_matrices(more_case, params, nodes)
        reruns["modes"] = (more_case, numerics, more_sm, f"a rerun with {more} modes")
    else:
        found["convergence_modes_diff_m"] = math.nan
        warnings.append(f"convergence in the modes not checked: the case already has the "
                        f"maximum of {MAX_MODES} modes")
    for label, (rerun_case, rerun_numerics, rerun_sm, what) in reruns.items():
        rerun = run(rerun_case, params, rerun_numerics, rerun_sm, _resolved(rerun_case, rerun_sm, resolve))
        status, rerun_stop = rerun.status, rerun.t_stop
        rerun_tip = rerun.out[:, output_columns(rerun_case.modes, joint)["tip_transverse"]]
        both = np.isfinite(tip) & np.isfinite(rerun_tip)
        difference = float(np.max(np.abs(tip - rerun_tip)[both])) if both.any() else math.nan
        found[f"convergence_{label}_diff_m"] = difference
        LOG.info("case %s: max |tip deflection difference| to %s: %.3g m", case.label, what, difference)
        if difference > threshold:
            warnings.append(f"not converged in the {label}: the tip deflection differs by up to "
                            f"{difference:.3g} m from {what} (convergence_{label}_diff_m > "
                            f"numerics.convergence_check.threshold_m = {threshold:g} m)")
        elif math.isnan(difference):
            warnings.append(f"convergence in the {label} not checked: no output time where both "
                            f"the run and {what} have values")
        if status == radau.TOO_MANY_STEPS and rerun_stop < t_stop:
            warnings.append(f"convergence check against {what} covers t <= {rerun_stop:.6g} s "
                            "only (its step budget numerics.max_steps ran out)")
    found["warnings"] = warnings
    return found


def build_dataset(case: Case, params: BeamParameters, numerics: Numerics, sm: SystemMatrices, result: Run,
                  resolved: Resolved = UNRESOLVED) -> xr.Dataset:
    """The simulation dataset of ``docs/architecture.md`` from a :class:`Run`.

    ``sm`` are the case's matrices (their ``K22`` of Eq. 31 tells a divergence from a run that
    left the range of the models, :mod:`hubbeam.model.validity`); ``result`` the kernel's outputs,
    status, stop time and integrator attributes (name, tolerances and statistics, including
    ``n_steps``), and a sampled controller's records, which become the variables of the ``sample``
    dimension (:data:`hubbeam.results.variables.SAMPLE_VARIABLES`); ``resolved`` what the run was
    resolved with, recorded in the attributes.
    """
    t, out, status, t_stop, integrator = result[:5]
    n = case.modes
    joint = case.root_spring is not None
    columns = output_columns(n, joint)
    variables = dataset_variables(case.model, driven=case.drive is not None, joint=joint)
    data_vars = {name: (dims, np.ascontiguousarray(out[:, columns[name]]),
                        {"units": units, "long_name": long_name})
                 for name, (dims, units, long_name) in variables.items()}
    for name, (factors, units, long_name) in CUMULATIVE_VARIABLES.items():
        if joint and factors == CUMULATIVE_VARIABLES["work"][0]:
            factors = JOINT_WORK  # the hub torque works on the hub's rate, across the spring
        integrand = np.prod([out[:, columns[factor]] for factor in factors], axis=0)
        data_vars[name] = ("time", cumulative_integral(integrand, t),
                           {"units": units, "long_name": long_name})
    coords = {
        "time": ("time", t, {"units": "s", "long_name": "time since the start of the maneuver",
                             "standard_name": "time"}),
        "mode": ("mode", np.arange(1, n + 1), {"units": "1", "long_name": "mode number"}),
    }
    found = validity.run_attributes(status, t_stop, case.model, sm, out[:, columns["theta_dot"]],
                                    out[:, columns["tip_transverse"]], params.L, float(numerics.small_deflection_limit),
                                    case.t_end, numerics.max_steps)
    warnings = []
    if integrator.get("n_steps", 0) > numerics.step_warning:
        warnings.append(f"{integrator['n_steps']} accepted steps exceed numerics.step_warning = "
                        f"{numerics.step_warning}")
    warning = found.pop("warning")
    if warning:
        warnings.append(warning)
    recorded = case.to_dict()
    attributes = {
        "model": case.model,
        "maneuver": recorded["maneuver"],
        "damping": recorded.get("damping", {}),
        "initial": recorded.get("initial", {}),
        "tip_mass_kg": case.tip_mass.mass,
        "tip_position_m": case.tip_mass.position,
        **({} if case.tip_mass.is_point else {"tip_inertia_kg_m2": case.tip_mass.inertia,
                                               "tip_offset_m": case.tip_mass.offset}),
        "n_modes": int(n),
        **({} if case.drive is None else {"drive": case.drive.to_dict()}),
        **beam_attributes(params),
        **({} if case.root_spring is None else case.root_spring.attributes()),
        **found,
        "integrator_status": radau.STATUS_NAMES[status],
        "stopped_at_s": float(t_stop),
        "output_step": float(numerics.output_step),
        "divergence_limit": float(numerics.divergence_limit),
        "max_steps": int(numerics.max_steps),
        "step_warning": int(numerics.step_warning),
        **integrator,
        "warnings": "; ".join(warnings),
    }
    attributes |= dict(resolved.attributes or {})
    if resolved.shaper is not None:
        attributes["shaper"] = resolved.shaper.to_dict()
    if result.records is not None:
        loop = resolved.loop
        attributes |= loop.attributes()
        data_vars |= sample_variables(result.records, loop)
        coords |= {"sample_time": ("sample", result.records.t, {"units": "s", "long_name": "sample time t_k"}),
                   "sensor": ("sensor", [sensor.signal for sensor in loop.sensors], {"long_name": "sensor"}),
                   "estimate_state": ("estimate_state", list(loop.estimate_states),
                                      {"long_name": "state of the design model the controller estimates"})}
    maneuver = json.dumps(recorded["maneuver"], sort_keys=True)  # as in case_config
    title = f"hubbeam simulation {case.name or ''}: {case.model}, {maneuver}"
    attrs = global_attributes(title, case_config=recorded, extra=attributes)
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


def sample_variables(records: SampleRecords, loop: SampledLoop) -> dict:
    """The records of a sampled controller as the dataset's variables of the ``sample`` dimension
    (:data:`hubbeam.results.variables.SAMPLE_VARIABLES`), with the units of its sensors, states and
    command."""
    units = {"measured": ("sensor_units", [sensor_unit(sensor) for sensor in loop.sensors]),
             "sensed": ("sensor_units", [sensor_unit(sensor) for sensor in loop.sensors]),
             "estimate": ("state_units", list(loop.estimate_units))}
    found = {}
    for name, (dims, unit, long_name) in SAMPLE_VARIABLES.items():
        attrs = {"units": unit, "long_name": long_name}
        if name in units:
            attrs[units[name][0]] = json.dumps(units[name][1])
        found[name] = (dims, np.ascontiguousarray(getattr(records, name)), attrs)
    return found


def compile_kernels(family: str | None = None, sampled: bool = False) -> float:
    """Compile (or load from numba's cache) the simulation kernel of ``family`` (a key of
    :data:`hubbeam.core.integrate.FAMILY_KERNELS`; default: every family), or with ``sampled`` its
    sampled-controller kernel (:mod:`hubbeam.core.sampled`) instead; return the seconds it took.

    One kernel per family (and one sampled kernel) serves every model of it, maneuver and mode
    count, so a workflow calls this once per kernel before it starts parallel simulations (they
    then all load the cached machine code); the kernels compile independently, in parallel
    processes if wanted.
    """
    if family is not None and family not in FAMILIES:
        raise ValueError(f"family: got {family!r}; allowed: {', '.join(FAMILIES)}")
    params = BeamParameters(L=1.0, rho=1.0, A=1.0, E=1.0, I=1.0, Jh=1.0, rA=0.1)
    numerics = Numerics(rtol=1e-6, atol=1e-8, output_step=0.05, max_steps=1000, step_warning=1000,
                        divergence_limit=1.0, quadrature_points=8)
    start = time.perf_counter()
    for name in [family] if family else FAMILIES:
        case = Case(name="compile_kernels", model=family_model(name).name, maneuver=SpinUp(wf=0.1, tf=0.05),
                    t_end=0.1, modes=1, tip_mass=TipMass(0.0, 1.0))
        sm = case_matrices(case, params, numerics)
        if not sampled:
            run(case, params, numerics, sm, UNRESOLVED)
            continue
        tracking = dataclasses.replace(case, maneuver=PdControl(kp=1.0, kd=1.0, reference=case.maneuver))
        N = 1 + 2 * case.modes
        loop = SampledLoop([SensorSpec("hub_angle")], np.eye(2 * N)[:1], np.zeros((0, 0)), np.zeros((0, 1)),
                           np.zeros(0), np.zeros((1, 0)), np.ones((1, 1)), np.ones(1), np.zeros((1, 3)),
                           np.zeros(3), np.zeros(0), Ts=0.02)
        run(tracking, params, numerics, sm, Resolved(loop=loop))
    return time.perf_counter() - start


def step_stops(maneuver: Maneuver, t: np.ndarray, shaper: Shaper | None = None) -> np.ndarray:
    """Times no step may cross: where the maneuver is not smooth (the end of Eq. 43/44, where they
    are only C^1 or C^3; table rows), each shifted by every impulse of the ``shaper`` (and the
    shifted starts, :func:`hubbeam.model.shapers.shaped_stops`), inside the output span."""
    stops = maneuver.stops()
    if shaper is not None:
        stops = shaped_stops(stops, shaper)
    return np.ascontiguousarray(stops[(stops > 0.0) & (stops < t[-1])])


def cumulative_integral(rate: np.ndarray, t: np.ndarray) -> np.ndarray:
    """``int_0^t rate dt`` on the output grid by the composite Simpson rule
    (``scipy.integrate.cumulative_simpson``; error ``O(output_step^4)`` where ``rate`` is smooth,
    ``O(output_step^2)`` over an output interval with a kink); NaN after the first NaN."""
    result = np.full(t.size, np.nan)
    finite = np.isfinite(rate)
    count = t.size if finite.all() else int(np.argmin(finite))
    if count >= 2:
        result[:count] = cumulative_simpson(rate[:count], x=t[:count], initial=0.0)
    elif count == 1:
        result[0] = 0.0
    return result

