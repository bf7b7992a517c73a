"""Python API of a simulation: validate a case, run the jitted kernel, label the result.

:func:`simulate` turns a resolved case (``hubbeam.configuration.load.case_settings``), the beam parameters
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

import numpy as np
import xarray as xr
from scipy.integrate import cumulative_simpson

from hubbeam.configuration.settings import Case, ConvergenceCheck, Numerics, simulation_settings
from hubbeam.core import radau
from hubbeam.core.inputs import IDENTITY_SHAPER, NO_DRIVE, IntegratorSettings, SimulationInputs, State
from hubbeam.core.integrate import n_output_columns, output_columns, simulate_kernel
from hubbeam.model import linearised, validity
from hubbeam.model.beam import beam_attributes
from hubbeam.model.damping import damping_matrices
from hubbeam.model.limits import (
    MAX_MODES,
    MAX_QUADRATURE_POINTS,
    MIN_QUADRATURE_POINTS,
    MIN_RTOL,
)
from hubbeam.model.maneuvers import FeedbackLaw, Maneuver, SpinUp
from hubbeam.model.matrices import SystemMatrices, assemble
from hubbeam.model.models import FAMILIES, family_model, model
from hubbeam.model.parameters import BeamParameters, TipMass
from hubbeam.model.root import RootSpring, checked_spring, joint_inputs
from hubbeam.model.shapers import Shaper, shaped_stops
from hubbeam.results.provenance import global_attributes
from hubbeam.results.variables import (
    CUMULATIVE_VARIABLES,
    JOINT_WORK,
    dataset_variables,
    output_count,
)

LOG = logging.getLogger(__name__)

INTEGRATOR = "Radau IIA order 5 (hubbeam.core.radau), dense output by quintic Hermite interpolation"


class SimulationError(ValueError):
    """A case or the numerics cannot be simulated; the message names key, value and allowed."""


def initial_state(case: Case, sm: SystemMatrices, joint: bool = False) -> State:
    """The state ``(y, y')`` of ``y = (theta, q1, q2)`` at ``t = 0`` of a checked case (the
    configuration's checks, ``hubbeam.configuration.checks``), from its optional ``initial``
    state (:class:`~hubbeam.configuration.settings.InitialState`; default: rest); with a
    compliant root (``joint``, ``hubbeam.model.root``) of ``(theta, q1, q2, phi)``, the hub angle
    ``phi = 0`` turning with the root (the spring relaxed):

    * ``hub_speed`` (rad s-1, default 0): a steady spin, ``theta = 0``, ``theta' = hub_speed``,
      with ``q1`` at its centrifugal stretch ``q1s`` for that speed
      (:func:`hubbeam.model.linearised.axial_stretch`; zero for a model that keeps no ``q1``) and
      ``q2 = 0``; for a prescribed maneuver it must be the maneuver's speed at ``t = 0``;
    * ``q1``, ``q2``, ``q1_dot``, ``q2_dot`` (one value per mode, default zeros): added to the
      modal coordinates and rates of that state.
    """
    n = case.modes
    spec = case.initial
    if spec is None:
        size = 2 + 2 * n if joint else 1 + 2 * n
        return State(np.zeros(size), np.zeros(size))
    speed = spec.hub_speed or 0.0
    q1s = linearised.axial_stretch(sm, speed) if model(case.model).keeps_axial else np.zeros(n)
    hub = [0.0] if joint else []
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
    """The system matrices of ``case``: ``matrices`` (checked) or assembled from ``params``."""
    n = case.modes
    if matrices is None:
        if numerics.quadrature_points is None:
            raise SimulationError(f"numerics.quadrature_points: missing (required when no matrices are "
                                  f"given); allowed: an integer in {MIN_QUADRATURE_POINTS}..{MAX_QUADRATURE_POINTS}")
        matrices = assemble(params, case.tip_mass, n, numerics.quadrature_points)
    if np.shape(matrices.K1) != (n, n):
        raise SimulationError(f"cases.{case.label}.modes = {n}, but the matrices given have "
                              f"{np.shape(matrices.K1)[0]} modes; allowed: matrices assembled with the case's "
                              "number of modes")
    return kernel_matrices(matrices)


def simulate(case: Case | Mapping, params: BeamParameters, numerics: Numerics | Mapping,
             matrices: SystemMatrices | None = None, *,
             convergence_check: ConvergenceCheck | Mapping | None = None, feedback=None,
             shaper: Shaper | None = None, root_spring: RootSpring | None = None) -> xr.Dataset:
    """Simulate one case from its initial state and return the labelled simulation dataset.

    Parameters
    ----------
    case : a :class:`~hubbeam.configuration.settings.Case` (its ``maneuver`` and ``damping`` the
        records of :mod:`hubbeam.model.maneuvers` and :mod:`hubbeam.model.damping`, its optional
        ``initial`` state, :func:`initial_state`), or the mapping of a resolved case.
    params : the beam (Table 1 parameters, or any beam of :mod:`hubbeam.model.beam`).
    numerics : :class:`~hubbeam.configuration.settings.Numerics` or the ``numerics`` mapping of a
        configuration (``quadrature_points`` is needed when ``matrices`` is not given).
    matrices : the case's :class:`~hubbeam.model.matrices.SystemMatrices` (assembled if None).
    convergence_check : ``numerics.convergence_check`` (``tolerance_factor``, ``extra_modes``,
        ``threshold_m``); if given, the case is rerun at a tighter tolerance and with more modes and
        the differences are recorded (:func:`convergence`).
    feedback : for a ``state_feedback`` maneuver, the function ``(case, sm) -> (law,
        attributes)`` that resolves its :class:`~hubbeam.model.maneuvers.FeedbackLaw` for the case's
        matrices (every rerun its own) and the dataset attributes that record it
        (``hubbeam.control.feedback.simulate_case`` passes it).
    shaper : a command shaper (:class:`hubbeam.model.shapers.Shaper`) convolved with the
        maneuver's command (``hubbeam.core.shaping``: the hub motion, the torque, or a
        controller's reference); None leaves it unshaped. Recorded as the attribute ``shaper``
        (JSON), present only when given.
    root_spring : a compliant root (:class:`hubbeam.model.root.RootSpring`: a torsional spring and
        damper between the hub and the beam's root, ``docs/compliant-root.md``); None, the
        default, clamps the beam to the hub. With one ``theta`` is the beam's root angle, the
        maneuver drives the hub (a prescribed maneuver prescribes the hub angle, a controller reads
        and drives it; a state feedback's gains act on ``(theta, q1, q2, phi)`` and their rates),
        and the dataset adds ``hub_angle``, ``hub_speed``, ``hub_acceleration``, ``spring_torque``
        and the spring's attributes (:meth:`~hubbeam.model.root.RootSpring.attributes`).

    Objects are used as they are (the workflow's jobs get them from the one check of the
    configuration); mappings are checked once, by the same schema and checks
    (:func:`hubbeam.configuration.settings.simulation_settings`, ``ConfigError``). The attribute
    ``quadrature_points`` records the Gauss-Legendre nodes of the matrices used, so that
    :func:`hubbeam.results.reader.simulation_inputs` can rebuild them.
    """
    if shaper is not None and not isinstance(shaper, Shaper):
        raise SimulationError(f"shaper = {shaper!r}; allowed: a hubbeam.model.shapers.Shaper, or None")
    root_spring = checked_spring(root_spring)
    case, numerics = simulation_settings(case, numerics, params.L, convergence_check)
    sm = case_matrices(case, params, numerics, matrices)
    ds = build_dataset(case, params, numerics, sm,
                       *_integrate(case, params, numerics, sm, feedback, shaper=shaper, root_spring=root_spring),
                       root_spring=root_spring)
    ds.attrs["quadrature_points"] = quadrature_points(sm)
    if case.maneuver.needs_law:
        ds.attrs.update(feedback(case, sm)[1])
    if shaper is not None:
        ds.attrs["shaper"] = json.dumps(shaper.to_dict())
    if numerics.convergence_check is not None:
        found = convergence(ds, case, params, numerics, sm, feedback, shaper, root_spring)
        notes = found.pop("warnings")
        ds.attrs.update(found)
        ds.attrs["warnings"] = "; ".join(filter(None, [ds.attrs["warnings"], *notes]))
    return ds


def quadrature_points(sm: SystemMatrices) -> int:
    """Gauss-Legendre nodes of the beam integrals of ``sm`` (its point cloud less the tip)."""
    return int(np.size(sm.x) - 1)


def _feedback_law(case: Case, sm: SystemMatrices, feedback, joint: bool = False) -> FeedbackLaw | None:
    """The resolved law of a maneuver that needs one (``feedback`` as in :func:`simulate`; with a
    compliant root, ``joint``, its gains on ``(theta, q1, q2, phi)`` and their rates)."""
    if not case.maneuver.needs_law:
        return None
    if feedback is None:
        raise SimulationError(f"cases.{case.label}.maneuver.kind = {case.maneuver.kind!r}; allowed here only "
                              "with its feedback (run it with hubbeam.control.feedback.simulate_case)")
    law = feedback(case, sm)[0]
    states = 2 * (2 + 2 * case.modes if joint else 1 + 2 * case.modes)
    if np.size(law.gains) != states:
        raise SimulationError(f"cases.{case.label}.maneuver: {np.size(law.gains)} feedback gains; allowed: "
                              f"{states}, one per state of {case.modes} modes"
                              + (" with the root spring's hub angle (theta, q1, q2, phi and their rates)"
                                 if joint else ""))
    return law


def _integrate(case: Case, params: BeamParameters, numerics: Numerics, sm: SystemMatrices, feedback=None,
               drive: np.ndarray = NO_DRIVE, shaper: Shaper | None = None, root_spring: RootSpring | None = None):
    """Run the kernel once: ``(t, out, status, t_stop, integrator)`` for :func:`build_dataset`
    (``feedback``, ``shaper`` and ``root_spring`` as in :func:`simulate`; ``drive``: the hub's
    packed drive, ``hubbeam.core.drive``)."""
    joint = root_spring is not None
    kind, mp = case.maneuver.kernel_parameters(_feedback_law(case, sm, feedback, joint))
    t = output_times(case.t_end, numerics.output_step)
    out = np.empty((t.size, n_output_columns(case.modes, joint)))
    stats = np.zeros(len(radau.STAT_NAMES), dtype=np.int64)
    start = time.perf_counter()
    link, root = joint_inputs(sm, root_spring)
    inputs = SimulationInputs(model(case.model).traits, kind, mp, damping_matrices(case.damping, sm), link, drive,
                              IDENTITY_SHAPER if shaper is None else shaper.kernel_array(), root)
    status, t_stop = simulate_kernel(inputs, initial_state(case, sm, joint), t, step_stops(case.maneuver, t, shaper),
                                     integrator_settings(numerics, params.L), out, stats)
    wall = time.perf_counter() - start
    LOG.info("case %s (%s, %d modes): %s at t = %g s, %.3f s wall, %d steps (%d rejected), "
             "%d rhs calls, %d Jacobians, %d LU", case.label, case.model, case.modes, radau.STATUS_NAMES[status],
             t_stop, wall, stats[radau.ACCEPTED], stats[radau.REJECTED], stats[radau.RHS_CALLS],
             stats[radau.JACOBIANS], stats[radau.FACTORIZATIONS])
    integrator = {"integrator": INTEGRATOR, "rtol": float(numerics.rtol), "atol": float(numerics.atol),
                  **{name: int(value) for name, value in zip(radau.STAT_NAMES, stats)}}
    return t, out, status, t_stop, integrator


def integrator_settings(numerics: Numerics, length: float) -> IntegratorSettings:
    """The kernel's :class:`~hubbeam.core.inputs.IntegratorSettings` from checked ``numerics``
    for a beam of length ``length`` (the tip limit is ``divergence_limit * length``)."""
    return IntegratorSettings(float(numerics.rtol), float(numerics.atol), float(numerics.divergence_limit) * length,
                              int(numerics.max_steps))


def convergence(ds: xr.Dataset, case: Case, params: BeamParameters, numerics: Numerics,
                sm: SystemMatrices, feedback=None, shaper: Shaper | None = None,
                root_spring: RootSpring | None = None) -> dict:
    """Check the run ``ds`` of ``case`` (made with matrices ``sm``, ``shaper`` and ``root_spring``)
    against two reruns, with the settings ``numerics.convergence_check``.

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
        _, out, status, rerun_stop, _ = _integrate(rerun_case, params, rerun_numerics, rerun_sm, feedback,
                                                   shaper=shaper, root_spring=root_spring)
        rerun_tip = out[:, output_columns(rerun_case.modes)["tip_transverse"]]
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


def build_dataset(case: Case, params: BeamParameters, numerics: Numerics, sm: SystemMatrices,
                  t: np.ndarray, out: np.ndarray, status: int, t_stop: float,
                  integrator: Mapping, root_spring: RootSpring | None = None) -> xr.Dataset:
    """The simulation dataset of ``docs/architecture.md`` from the kernel's output array.

    ``sm`` are the case's matrices (their ``K22`` of Eq. 31 tells a divergence from a run that
    left the range of the models, :mod:`hubbeam.model.validity`); ``status`` and ``t_stop`` are the
    kernel's return values; ``integrator`` holds the integrator attributes (name, tolerances and
    statistics, including ``n_steps``); ``root_spring`` the run's compliant root (None: rigid),
    whose variables and attributes join (:func:`simulate`), the work then the hub torque's on the
    hub's rate.
    """
    n = case.modes
    joint = root_spring is not None
    columns = output_columns(n, joint)
    variables = dataset_variables(case.model, joint)
    data_vars = {name: (dims, np.ascontiguousarray(out[:, columns[name]]),
                        {"units": units, "long_name": long_name})
                 for name, (dims, units, long_name) in variables.items()}
    for name, (factors, units, long_name) in CUMULATIVE_VARIABLES.items():
        if joint and factors == CUMULATIVE_VARIABLES["work"][0]:
            factors = JOINT_WORK
        integrand = np.prod([out[:, columns[factor]] for factor in factors], axis=0)
        data_vars[name] = ("time", cumulative_integral(integrand, t),
                           {"units": units, "long_name": long_name})
    coords = {
        "time": ("time", t, {"units": "s", "long_name": "time since the start of the maneuver",
                             "standard_name": "time"}),
        "mode": ("mode", np.arange(1, n + 1), {"units": "1", "long_name": "mode number"}),
    }
    found = validity.run_attributes(status, t_stop, case.model, sm, out[:, columns["theta_dot"]],
                                    out[:, columns["tip_transverse"]], params.L, float(numerics.small_deflection_limit))
    warnings = []
    if integrator.get("n_steps", 0) > numerics.step_warning:
        warnings.append(f"{integrator['n_steps']} accepted steps exceed numerics.step_warning = "
                        f"{numerics.step_warning}")
    if status == radau.TOO_MANY_STEPS:
        warnings.append(f"step budget numerics.max_steps = {numerics.max_steps} exhausted at "
                        f"t = {t_stop:.6g} s; outputs after it are NaN")
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
        **beam_attributes(params),
        **(root_spring.attributes() if joint else {}),
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
    maneuver = json.dumps(recorded["maneuver"], sort_keys=True)  # as in case_config
    title = f"hubbeam simulation {case.name or ''}: {case.model}, {maneuver}"
    attrs = global_attributes(title, case_config=recorded, extra=attributes)
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


def compile_kernels(family: str | None = None) -> float:
    """Compile (or load from numba's cache) the simulation kernel of ``family`` (a key of
    :data:`hubbeam.core.integrate.FAMILY_KERNELS`; default: every family); return the seconds it
    took.

    One kernel per family serves every model of it, maneuver and mode count, so a workflow calls
    this once per family before it starts parallel simulations (they then all load the cached
    machine code); the families compile independently, in parallel processes if wanted.
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
        _integrate(case, params, numerics, case_matrices(case, params, numerics))
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

