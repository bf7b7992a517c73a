"""How slowly a sampled LQR design may be sampled: the spectral radius of its loop with the truth plant.

A sampled case (``maneuver.design`` with ``maneuver.sampling``) designs its gain on a design model
(the courseware's lumped model, or an assumed-modes model with few modes) and runs on its own
simulated model, the *truth*. Here the truth is linear: the free-hub model of the case's model
(its modes, tip body, damping and drive, the voltage as input; :func:`truth_model`) about the
design speed, sampled with the case's zero-order hold and delay
(:func:`hubbeam.linear.discrete.discretise`). For a sample time ``Ts`` and a delay ``D`` the
controller is the design's state feedback on exact readings of the design's states taken from the
truth (:func:`hubbeam.control.sampled.state_controller`: the hub angle, the deflection angle and
their rates for the lumped model, the modal coordinates for an assumed-modes design), with

* the **continuous gain** through the hold (``ct.lqr`` on the continuous design model, what the
  Quanser courseware does: :func:`hubbeam.control.dlqr.continuous_lqr`), or
* the **discrete gain** redesigned at each ``Ts`` (``ct.dlqr`` on the sampled design model with the
  delay, :func:`hubbeam.control.dlqr.discrete_lqr`),

and the sampled loop ``[[Ad - Bd K F Cm, -Bd K E], [Bc Cm - Bu K F Cm, Ac - Bu K E]]``
(:func:`hubbeam.control.sampled.closed_loop_matrix`, :func:`loop_matrix`) is stable exactly when
its spectral radius ``max |z|`` is below 1 (Franklin, Powell and Workman, *Digital Control of
Dynamic Systems*, 1998, Ch. 4). :func:`sample_time_sweep` evaluates it over a grid of sample
times and names the truth's mode that sets it (:func:`plant_modes`, :meth:`PlantModes.name_of`:
the largest share of the eigenvector's plant part in the truth's modal coordinates); the first
crossing of 1 is refined by Brent's method (:func:`stability_boundary`). A vibration mode of
frequency ``f`` aliases from ``Ts = 1 / (2 f)`` on (:func:`aliasing_sample_times`). As ``Ts -> 0``
the loop's eigenvalues tend to ``exp(lambda Ts)`` of the continuous loop ``A - B K`` on the truth
(a test). Everything is linear algebra on the models: no integration.

:func:`confirm_boundary` runs the nonlinear sampled loop (the compiled kernel, on the case's own
model) just inside and just outside a boundary, from a small tip deflection with the reference at
rest, and compares the growth rate of the applied command's envelope
(:func:`hubbeam.results.measures.envelope_growth_rate`) with the loop's ``ln rho / Ts``.
"""

from __future__ import annotations

import dataclasses
import json
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import scipy.optimize
import xarray as xr

from hubbeam.configuration.schema import MEASURED_SIGNALS
from hubbeam.configuration.settings import Case, InitialState, case_plant
from hubbeam.control.cases import sampled_loop
from hubbeam.control.dlqr import continuous_lqr, discrete_lqr
from hubbeam.control.feedback import design_plant
from hubbeam.control.sampled import closed_loop_matrix, kernel_layout, state_controller
from hubbeam.control.sampling import zero_tolerance
from hubbeam.linear.discrete import discretise
from hubbeam.linear.plant_models import plant_linear
from hubbeam.model.maneuvers import AngleTable, Estimator
from hubbeam.results import measures
from hubbeam.results.provenance import global_attributes
from hubbeam.simulation.simulate import Resolved, simulate

#: the two ways a sampled loop gets its gain (``sampling.gain``)
GAINS = ("continuous", "discrete")
#: the name of a real, non-zero mode of the truth (the hub's rate, damped by the drive and the friction)
REAL_MODE = "hub (real)"
#: the name of a closed-loop mode that lives in the controller's states (its plant part negligible)
CONTROLLER_MODE = "controller"
#: a closed-loop eigenvector whose plant part is below this share of its norm is the controller's
CONTROLLER_SHARE = 1e-6
#: the boundary's mode of a sweep in which no sample time has a design
NO_DESIGN = "no design at any sample time"
#: why a design reduced to the modes its sample time resolves (``sampling.reduce``) has no sweep: the
#: sweep reads the design's states exactly, and a reduced model's states (modal coordinates of the
#: truncated model) are not the truth's
REDUCED = ("reduces its design to the modes each sample time resolves (sampling.reduce: true), whose modal "
           "states the sweep's exact readings cannot read; allowed: a case with sampling.reduce false")
#: relative tolerance of Brent's method on a stability boundary's sample time
BOUNDARY_XTOL = 1e-6


def truth_model(case: Case, beam, numerics, sm):
    """The truth's continuous linear model of the sampled ``case`` (module docstring): the linear
    model of its plant (``beam``, ``numerics``: :func:`hubbeam.configuration.settings.case_plant`)
    and its model on the matrices ``sm`` about its design speed, free hub, its damping and root
    spring, the voltage of its drive as the input (or the hub torque without one), the measured
    signals as outputs (:func:`hubbeam.linear.plant_models.plant_linear`)."""
    return plant_linear(case_plant(case, beam, numerics), case.model, case.maneuver.design.speed, "free",
                        list(MEASURED_SIGNALS), sm=sm)


@dataclass(frozen=True, eq=False)
class PlantModes:
    """The modes of a continuous linear model: its eigenvalues ``values`` (s-1) with unit-length
    right eigenvectors ``vectors`` (columns), the ``name`` of each eigenvalue's mode (``rigid body``;
    ``hub (real)``, a real mode: the hub's rate damped by the drive's back-EMF and the friction;
    ``bending k`` and ``axial k`` by frequency within their kind, by where the eigenvector's positions
    lie) and each distinct name's damped ``frequency`` in Hz (``names``, ``frequencies``; 0 for a real mode)."""

    values: np.ndarray
    vectors: np.ndarray
    labels: tuple[str, ...]
    names: tuple[str, ...]
    frequencies: np.ndarray

    def name_of(self, x: np.ndarray) -> str:
        """The mode that carries the largest share of the state ``x`` (complex, the model's states):
        ``x`` in modal coordinates ``eta = V^-1 x``, each mode's share ``sum |eta_j|`` over its
        eigenvalues (the eigenvectors have unit length)."""
        eta = np.linalg.lstsq(self.vectors, x, rcond=None)[0]
        shares = {name: 0.0 for name in self.names}
        for label, value in zip(self.labels, np.abs(eta)):
            shares[label] += float(value)
        return max(shares, key=shares.get)


def plant_modes(model) -> PlantModes:
    """The :class:`PlantModes` of a continuous linear model (its ``A`` and state names; positions are
    the states whose names do not end in ``_dot``, axial those that start with ``q1_``)."""
    A = np.asarray(model.A, dtype=float)
    values, vectors = np.linalg.eig(A)
    vectors = vectors / np.linalg.norm(vectors, axis=0)
    tol = zero_tolerance(A)
    positions = [k for k, name in enumerate(model.states) if not name.endswith("_dot")]
    axial = [k for k in positions if model.states[k].startswith("q1_")]
    kinds = []
    for value, vector in zip(values, vectors.T):
        if abs(value) <= tol:
            kinds.append("rigid body")
        elif abs(value.imag) <= tol:
            kinds.append(REAL_MODE)
        else:
            share = np.linalg.norm(vector[axial]) / np.linalg.norm(vector[positions]) if axial else 0.0
            kinds.append("axial" if share > math.sqrt(0.5) else "bending")
    labels, frequencies = [""] * len(values), {}
    for kind in ("bending", "axial"):
        members = [k for k, found in enumerate(kinds) if found == kind]
        distinct = sorted({round(abs(values[k].imag), 9) for k in members})
        for k in members:
            rank = distinct.index(round(abs(values[k].imag), 9)) + 1
            labels[k] = f"{kind} {rank}"
            frequencies[labels[k]] = abs(values[k].imag) / (2.0 * math.pi)
    for k, kind in enumerate(kinds):
        if kind in ("rigid body", REAL_MODE):
            labels[k] = kind
            frequencies[kind] = 0.0
    order = sorted(frequencies, key=lambda name: (frequencies[name], name))
    return PlantModes(values=values, vectors=vectors, labels=tuple(labels), names=tuple(order),
                      frequencies=np.array([frequencies[name] for name in order]))


def aliasing_sample_times(modes: PlantModes) -> dict[str, float]:
    """``Ts = 1 / (2 f)`` of every vibration mode of ``modes`` (s): from there on the mode lies above
    half the sampling frequency and aliases."""
    return {name: 0.5 / f for name, f in zip(modes.names, modes.frequencies) if f > 0.0}


def state_feedback(case: Case, beam, sm, truth, Ts: float, delay: float, gain: str):
    """The sampled controller of ``case``'s design at the sample time ``Ts`` (s) and ``delay``
    (samples) with the ``gain`` of :data:`GAINS` (the continuous one not checked for stability), on
    exact readings of the design's states from the ``truth`` (module docstring)."""
    if gain not in GAINS:
        raise ValueError(f"gain = {gain!r}; allowed: one of {', '.join(GAINS)}")
    spec = case.maneuver.design
    dm = discretise(design_plant(case, beam, sm), Ts, delay)
    if gain == "discrete":
        lqr = discrete_lqr(dm, spec.weights, spec.input_weight)
    else:
        lqr = continuous_lqr(dm, spec.weights, spec.input_weight, check=False)
    u_max = math.inf if case.drive is None else case.drive.voltage_limit
    return state_controller(lqr, truth, u_max)


def loop_matrix(truth, controller, rows: np.ndarray | None = None) -> tuple[np.ndarray, int]:
    """The sampled loop of ``controller`` (a ``SampledController``) with the continuous ``truth`` sampled
    at its ``Ts`` and delay (state: the truth's, its delayed commands, the controller's), and the
    number of the truth's own states (the plant part of the loop's eigenvectors). ``rows``: the
    sensors' rows on the truth's kernel state (default the controller's own, of the model it was
    built for; :func:`hubbeam.control.sampled.sensor_rows` on another truth)."""
    dm = discretise(truth, controller.Ts, controller.D)
    layout = kernel_layout(truth)
    columns = [layout.index(name) for name in truth.states]
    rows = controller.sensor_rows if rows is None else rows
    gains = np.array([sensor.gain for sensor in controller.sensors])
    Cm = np.zeros((len(controller.sensors), dm.A.shape[0]))
    Cm[:, :len(columns)] = gains[:, None] * rows[:, columns]
    c = controller
    return closed_loop_matrix(dm, Cm, c.Ac, c.Bc, c.Bu, c.E, c.F, c.K), dm.plant_states


@dataclass(frozen=True)
class LoopRadius:
    """A sampled loop's spectral radius ``radius`` = ``|pole|``, its ``pole`` of largest modulus and
    the truth's ``mode`` that carries it (or :data:`CONTROLLER_MODE`)."""

    radius: float
    pole: complex
    mode: str


def loop_radius(truth, controller, modes: PlantModes | None = None, rows: np.ndarray | None = None) -> LoopRadius:
    """The :class:`LoopRadius` of ``controller`` on the ``truth`` (:func:`loop_matrix`, ``rows`` as there)."""
    A, n = loop_matrix(truth, controller, rows)
    values, vectors = np.linalg.eig(A)
    k = int(np.argmax(np.abs(values)))
    vector = vectors[:, k]
    modes = plant_modes(truth) if modes is None else modes
    plant = vector[:n]
    mode = (modes.name_of(plant) if np.linalg.norm(plant) > CONTROLLER_SHARE * np.linalg.norm(vector)
            else CONTROLLER_MODE)
    return LoopRadius(float(abs(values[k])), complex(values[k]), mode)


def _radius(case, beam, sm, truth, modes, Ts, delay, gain) -> LoopRadius:
    try:
        return loop_radius(truth, state_feedback(case, beam, sm, truth, Ts, delay, gain), modes)
    except ValueError as error:  # a discrete design refused at this sample time
        return LoopRadius(math.nan, complex(math.nan, math.nan), f"no design: {error}")


def stability_boundary(case: Case, beam, sm, truth, sample_times, radii, delay: float, gain: str,
                       modes: PlantModes | None = None) -> tuple[float, str]:
    """The first sample time of the grid's interval where the loop's spectral radius reaches 1,
    refined by Brent's method between the last stable and the first unstable grid point, and the
    truth's mode that crosses; ``(nan, "")`` when every grid point is stable, ``(nan,``
    :data:`NO_DESIGN` ``)`` when no sample time of the grid has a design, ``(sample_times[0], mode)``
    when the first already is not stable (a sample time without a design counts as neither)."""
    modes = plant_modes(truth) if modes is None else modes
    radii = np.asarray(radii)
    if not np.isfinite(radii).any():  # no design at any sample time: no boundary either
        return math.nan, NO_DESIGN
    unstable = np.flatnonzero(radii >= 1.0)
    if unstable.size == 0:
        return math.nan, ""
    i = int(unstable[0])
    if i == 0 or not np.isfinite(radii[i - 1]):  # nothing stable just below to refine from
        return float(sample_times[i]), _radius(case, beam, sm, truth, modes, sample_times[i], delay, gain).mode

    def excess(Ts):
        return _radius(case, beam, sm, truth, modes, Ts, delay, gain).radius - 1.0

    Ts = scipy.optimize.brentq(excess, sample_times[i - 1], sample_times[i], xtol=BOUNDARY_XTOL * sample_times[i])
    return float(Ts), _radius(case, beam, sm, truth, modes, Ts * (1.0 + BOUNDARY_XTOL), delay, gain).mode


@dataclass(frozen=True, eq=False)
class SampleTimeSweep:
    """One design's sweep: over ``gains`` x ``delays`` x ``sample_times`` the spectral ``radius``, the
    ``pole`` of largest modulus and its ``mode``; per gain and delay the ``boundary`` (s, NaN: none in
    the grid) and the mode that crosses there; the design model's vibration frequencies (Hz)."""

    design: str
    sample_times: np.ndarray
    gains: tuple[str, ...]
    delays: tuple[float, ...]
    radius: np.ndarray
    pole: np.ndarray
    mode: np.ndarray
    boundary: np.ndarray
    boundary_mode: np.ndarray
    design_frequencies: np.ndarray


def sample_time_sweep(case: Case, beam, numerics, sm, sample_times: Sequence[float],
                      delays: Sequence[float] = (0.0, 1.0), gains: Sequence[str] = GAINS) -> SampleTimeSweep:
    """The :class:`SampleTimeSweep` of the sampled ``case`` on the matrices ``sm`` of its own model
    (``numerics``: its plant's, :func:`truth_model`; module docstring)."""
    if case.maneuver.sampling.reduce:
        raise ValueError(f"case {case.label!r} {REDUCED}")
    sample_times = np.asarray(sample_times, dtype=float)
    if sample_times.ndim != 1 or sample_times.size < 2 or np.any(np.diff(sample_times) <= 0.0) or sample_times[0] <= 0:
        raise ValueError(f"sample_times = {sample_times!r}; allowed: at least two increasing sample times > 0 s")
    truth = truth_model(case, beam, numerics, sm)
    modes = plant_modes(truth)
    shape = (len(gains), len(delays), sample_times.size)
    radius, pole, mode = np.full(shape, np.nan), np.full(shape, np.nan, complex), np.full(shape, "", dtype=object)
    boundary, boundary_mode = np.full(shape[:2], np.nan), np.full(shape[:2], "", dtype=object)
    for g, gain in enumerate(gains):
        for d, delay in enumerate(delays):
            for k, Ts in enumerate(sample_times):
                found = _radius(case, beam, sm, truth, modes, Ts, delay, gain)
                radius[g, d, k], pole[g, d, k], mode[g, d, k] = found.radius, found.pole, found.mode
            boundary[g, d], boundary_mode[g, d] = stability_boundary(case, beam, sm, truth, sample_times,
                                                                     radius[g, d], delay, gain, modes)
    design = design_plant(case, beam, sm)
    frequencies = plant_modes(design).frequencies
    return SampleTimeSweep(design=case.label, sample_times=sample_times, gains=tuple(gains),
                           delays=tuple(float(d) for d in delays), radius=radius, pole=pole, mode=mode,
                           boundary=boundary, boundary_mode=boundary_mode,
                           design_frequencies=frequencies[frequencies > 0.0])


def at_rest(case: Case, deflection: float, sm, t_end: float) -> Case:
    """``case`` with its reference at rest (no feedforward) until ``t_end``, started from the tip
    deflection ``deflection`` (m) in its first mode (``sm``: its matrices)."""
    q2 = (deflection / float(np.asarray(sm.f2L)[0]),) + (0.0,) * (case.modes - 1)
    maneuver = dataclasses.replace(case.maneuver, reference=AngleTable(time=(0.0, t_end), angle=(0.0, 0.0)),
                                   feedforward=False)
    return dataclasses.replace(case, maneuver=maneuver, initial=InitialState(q2=q2), t_end=t_end)


def _held_at_rest(case: Case, Ts: float, delay: float, gain: str, deflection: float, sm, t_end: float) -> Case:
    """:func:`at_rest` with the controller sampled every ``Ts`` with ``delay`` and ``gain`` on exact readings."""
    sampling = dataclasses.replace(case.maneuver.sampling, sample_time=Ts, delay=delay, gain=gain, reduce=False,
                                   estimator=Estimator("exact"), sensors=())
    rest = at_rest(case, deflection, sm, t_end)
    return dataclasses.replace(rest, maneuver=dataclasses.replace(rest.maneuver, sampling=sampling))


def nonlinear_rate(case: Case, beam, numerics, sm, controller) -> tuple[float, str]:
    """The growth rate (s-1) of the applied command's envelope in the nonlinear run of ``case`` (its
    own model, matrices ``sm``) under the sampled ``controller`` with ``case``'s sensors
    (:func:`hubbeam.results.measures.envelope_growth_rate` after the first sixth of the run, up to
    the drive's limit), and the integrator's status."""
    loop = sampled_loop(case, controller)
    ds = simulate(case, beam, numerics, sm, resolve=lambda _case, _sm: Resolved(loop=loop, attributes={}))
    u_max = math.inf if case.drive is None else case.drive.voltage_limit
    rate = measures.envelope_growth_rate(ds["sample_time"].values, ds["applied"].values, case.t_end / 6.0,
                                         limit=0.99 * u_max)
    return rate, str(ds.attrs["integrator_status"])


@dataclass(frozen=True)
class BoundaryRun:
    """A nonlinear run of a design at ``sample_time``: the loop's linear spectral ``radius`` and
    ``predicted_rate`` ``ln radius / Ts`` (s-1), the ``measured_rate`` of the applied command's
    envelope and the run's integrator ``status``."""

    sample_time: float
    radius: float
    predicted_rate: float
    measured_rate: float
    status: str

    @property
    def stable_linear(self) -> bool:
        return self.radius < 1.0

    @property
    def stable_nonlinear(self) -> bool:
        return self.measured_rate < 0.0


def confirm_boundary(case: Case, beam, numerics, sm, boundary: float, delay: float, gain: str,
                     margin: float = 0.05, deflection: float = 1e-3, t_end: float | None = None
                     ) -> tuple[BoundaryRun, BoundaryRun]:
    """Nonlinear runs of ``case``'s design (the compiled sampled loop on its own model, ``numerics``)
    at ``(1 - margin)`` and ``(1 + margin)`` times the ``boundary`` sample time, from a tip deflection
    of ``deflection`` m with the reference at rest, each against its linear prediction (module
    docstring); ``t_end`` default: 150 samples of the boundary."""
    if not (0.0 < margin < 0.5):
        raise ValueError(f"margin = {margin!r}; allowed: a fraction in (0, 0.5)")
    if not (math.isfinite(boundary) and boundary > 0.0):
        raise ValueError(f"boundary = {boundary!r}; allowed: a sample time > 0 s")
    truth = truth_model(case, beam, numerics, sm)
    t_end = 150.0 * boundary if t_end is None else float(t_end)
    runs = []
    for Ts in ((1.0 - margin) * boundary, (1.0 + margin) * boundary):
        controller = state_feedback(case, beam, sm, truth, Ts, delay, gain)
        radius = loop_radius(truth, controller).radius
        rate, status = nonlinear_rate(_held_at_rest(case, Ts, delay, gain, deflection, sm, t_end), beam, numerics, sm,
                                      controller)
        runs.append(BoundaryRun(float(Ts), radius, math.log(radius) / Ts, rate, status))
    return runs[0], runs[1]


def sweep_dataset(sweeps: Sequence[SampleTimeSweep], truth_modes: PlantModes,
                  confirmation: dict | None = None) -> xr.Dataset:
    """The sample-time sweeps of several designs (same sample times, gains and delays, the same truth)
    as one CF dataset: ``spectral_radius``, ``pole_real``, ``pole_imag``, ``mode`` over ``(design,
    gain, delay, sample_time)``; ``boundary``, ``boundary_mode`` over ``(design, gain, delay)``; the
    truth's modes (``truth_frequency``, ``aliasing_sample_time``) and each design model's vibration
    frequencies; ``confirmation`` (the settings and the two :class:`BoundaryRun`) over ``run``."""
    first = sweeps[0]
    dims = ("design", "gain", "delay", "sample_time")
    stack = {name: np.stack([getattr(sweep, name) for sweep in sweeps]) for name in ("radius", "pole", "mode")}
    width = max((sweep.design_frequencies.size for sweep in sweeps), default=0)
    design_frequencies = np.full((len(sweeps), width), np.nan)
    for k, sweep in enumerate(sweeps):
        design_frequencies[k, :sweep.design_frequencies.size] = sweep.design_frequencies
    aliasing = aliasing_sample_times(truth_modes)
    data = {
        "spectral_radius": (dims, stack["radius"], {"units": "1", "long_name": "spectral radius max |z| of the "
                                                    "sampled loop with the truth plant"}),
        "pole_real": (dims, stack["pole"].real, {"units": "1", "long_name": "real part of the loop's pole of "
                                                 "largest modulus"}),
        "pole_imag": (dims, stack["pole"].imag, {"units": "1", "long_name": "imaginary part of that pole"}),
        "mode": (dims, stack["mode"].astype(str), {"long_name": "the truth's mode that carries that pole"}),
        "boundary": (dims[:3], np.stack([sweep.boundary for sweep in sweeps]),
                     {"units": "s", "long_name": "first sample time of the grid where the loop loses stability "
                      "(Brent's method); NaN: stable over the whole grid"}),
        "boundary_mode": (dims[:3], np.stack([sweep.boundary_mode for sweep in sweeps]).astype(str),
                          {"long_name": "the truth's mode that crosses the unit circle there"}),
        "truth_frequency": ("truth_mode", truth_modes.frequencies,
                            {"units": "Hz", "long_name": "damped frequency of the truth's mode (0: real)"}),
        "aliasing_sample_time": ("truth_mode", np.array([aliasing.get(name, np.nan) for name in truth_modes.names]),
                                 {"units": "s", "long_name": "1 / (2 f): the sample time from which the mode "
                                  "aliases"}),
        "design_frequency": (("design", "design_mode"), design_frequencies,
                             {"units": "Hz", "long_name": "vibration frequencies of the design model"}),
    }
    coords = {"design": ("design", [sweep.design for sweep in sweeps], {"long_name": "sampled case"}),
              "gain": ("gain", list(first.gains), {"long_name": "continuous: the continuous LQR gain through the "
                                                   "hold; discrete: LQR redesigned at each sample time"}),
              "delay": ("delay", np.asarray(first.delays), {"units": "1", "long_name": "command delay in samples"}),
              "sample_time": ("sample_time", first.sample_times, {"units": "s", "long_name": "sample time Ts"}),
              "truth_mode": ("truth_mode", list(truth_modes.names), {"long_name": "mode of the truth plant"})}
    attrs = {}
    if confirmation is not None:
        runs = confirmation["runs"]
        data |= {
            "confirmation_sample_time": ("run", [run.sample_time for run in runs], {"units": "s"}),
            "confirmation_radius": ("run", [run.radius for run in runs], {"units": "1"}),
            "confirmation_predicted_rate": ("run", [run.predicted_rate for run in runs], {
                "units": "s-1", "long_name": "ln(spectral radius) / Ts of the linear loop"}),
            "confirmation_measured_rate": ("run", [run.measured_rate for run in runs], {
                "units": "s-1", "long_name": "growth rate of the applied command's envelope in the nonlinear run"}),
            "confirmation_status": ("run", [run.status for run in runs], {"long_name": "integrator status"}),
        }
        coords["run"] = ("run", ["inside", "outside"], {"long_name": "just inside / outside the boundary"})
        attrs["confirmation"] = json.dumps({key: value for key, value in confirmation.items() if key != "runs"},
                                           sort_keys=True)
    title = "hubbeam sample-time sweep: spectral radius of sampled LQR loops on the truth plant"
    return xr.Dataset(data, coords=coords, attrs=global_attributes(title, extra=attrs))


__all__ = ["CONTROLLER_MODE", "GAINS", "REAL_MODE", "BoundaryRun", "LoopRadius", "PlantModes", "SampleTimeSweep",
           "aliasing_sample_times", "at_rest", "confirm_boundary", "loop_matrix", "loop_radius", "nonlinear_rate",
           "plant_modes", "sample_time_sweep", "stability_boundary", "state_feedback", "sweep_dataset", "truth_model"]
