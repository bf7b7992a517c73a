"""How far the plant may stray from the one a sampled controller was designed for: linear stability maps.

A sampled case's controller (:func:`hubbeam.control.cases.sampled_controller`: its design, gain,
estimator and sensors) is built once, for the case's nominal plant. Its loop is then closed with
*another* truth: the case's linear model (:func:`hubbeam.control.sample_time.truth_model`: its
model, modes, damping, drive and root spring, the voltage as input) with one plant parameter moved
within a stated range, the others nominal. The parameters (:data:`PARAMETERS`) are the payload (a
point mass at the link's tip, kg), the link's bending stiffness (a factor on ``EI``), the hub's
viscous friction ``Beq`` (N m s/rad), the motor constants ``kt = km`` together (a factor: one
physical constant in SI units) and the armature resistance ``Rm`` (a factor). The sensors read the
moved plant through its own output rows (:func:`hubbeam.control.sampled.sensor_rows`): a strain
gauge reads the deflection of the moved link, an exact reading of a modal coordinate reads the
moved model's coordinate.

At every point the loop of :func:`hubbeam.control.sample_time.loop_matrix` is stable exactly when
its spectral radius is below 1 (Franklin, Powell and Workman, *Digital Control of Dynamic Systems*,
1998, Ch. 4); :func:`robustness_map` evaluates it on a uniform grid of each parameter and
:func:`stability_margin` finds, by Brent's method, the first value on each side of the nominal one
where it reaches 1 (none within the range: NaN). At the nominal point the loop is the case's own
(a test compares it with the design's closed-loop poles where the design model is the truth's).
The maps are linear algebra on the models: no integration.

:func:`confirm_margins` checks every margin that lies inside its swept range by two nonlinear runs
of the compiled sampled loop on the moved plant, just inside and just outside the margin, from a
small tip deflection with the reference at rest and the sensors without noise and quantisation
(so that the envelope's rate is the loop's): the growth rate of the applied command's envelope
against the linear ``ln(rho) / Ts``.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import scipy.optimize
import xarray as xr

from hubbeam.configuration.settings import Case
from hubbeam.control.cases import sampled_controller
from hubbeam.control.sample_time import at_rest, loop_radius, nonlinear_rate, plant_modes, truth_model
from hubbeam.control.sampled import sensor_rows
from hubbeam.model.beam import scaled_bending_stiffness
from hubbeam.model.parameters import TipMass
from hubbeam.results.provenance import global_attributes
from hubbeam.simulation.simulate import case_matrices

#: the plant parameters a map may move: name -> (unit, what the value is)
PARAMETERS = {
    "tip_mass": ("kg", "payload: a point mass at the link's tip"),
    "EI_factor": ("1", "factor on the link's bending stiffness EI"),
    "viscous_friction": ("N m s rad-1", "hub viscous friction Beq"),
    "motor_constant_factor": ("1", "factor on the motor's torque and back-EMF constants kt = km"),
    "resistance_factor": ("1", "factor on the armature resistance Rm"),
}
#: relative tolerance of Brent's method on a margin
MARGIN_XTOL = 1e-6
#: the confirmation runs lie this fraction of a margin's value inside and outside it
CONFIRM_STEP = 0.05
#: a confirmation run lasts long enough for this many e-folds of the slower linear rate, within the bounds (s)
CONFIRM_EFOLDS, CONFIRM_T_END = 3.0, (2.0, 20.0)


def _check_parameter(name: str, case: Case) -> None:
    if name not in PARAMETERS:
        raise ValueError(f"parameter = {name!r}; allowed: one of {', '.join(PARAMETERS)}")
    if name not in ("tip_mass", "EI_factor") and case.drive is None:
        raise ValueError(f"parameter = {name!r} for case {case.label!r} without a drive; allowed: tip_mass, "
                         "EI_factor")


def nominal_value(case: Case, name: str) -> float:
    """The nominal value of the parameter ``name`` of :data:`PARAMETERS` for ``case``."""
    _check_parameter(name, case)
    if name == "tip_mass":
        return float(case.tip_mass.mass)
    if name == "viscous_friction":
        return float(case.drive.viscous_friction)
    return 1.0


def moved_plant(case: Case, beam, numerics, name: str, value: float):
    """``(case, beam, sm)`` with the parameter ``name`` at ``value`` (module docstring); the tip mass
    is a point mass at the link's tip."""
    _check_parameter(name, case)
    if not math.isfinite(value) or value < 0.0 or (name.endswith("_factor") and value == 0.0):
        raise ValueError(f"{name} = {value!r}; allowed: a finite value >= 0 (a factor > 0)")
    if name == "tip_mass":
        case = dataclasses.replace(case, tip_mass=TipMass(mass=float(value), position=float(beam.L)))
    elif name == "EI_factor":
        beam = scaled_bending_stiffness(beam, value)
    else:
        drive = case.drive
        changes = {"viscous_friction": {"viscous_friction": value},
                   "motor_constant_factor": {"torque_constant": drive.torque_constant * value,
                                             "back_emf_constant": drive.back_emf_constant * value},
                   "resistance_factor": {"resistance": drive.resistance * value}}[name]
        case = dataclasses.replace(case, drive=dataclasses.replace(drive, **changes))
    return case, beam, case_matrices(case, beam, numerics)


@dataclass(frozen=True, eq=False)
class RobustnessMap:
    """One case's map: per parameter its ``values`` grid, the loop's spectral ``radius`` there and the
    truth's ``mode`` that carries it; the ``nominal`` value and the ``margins`` (lowest and highest
    value of the range that keeps the loop stable around the nominal one; the range's end when it
    stays stable up to there, NaN when the nominal loop is not stable)."""

    case: str
    values: Mapping[str, np.ndarray]
    radius: Mapping[str, np.ndarray]
    mode: Mapping[str, np.ndarray]
    nominal: Mapping[str, float]
    margins: Mapping[str, tuple[float, float]]
    nominal_radius: float


def _radius_at(case, beam, numerics, controller, name, value):
    moved_case, moved_beam, sm = moved_plant(case, beam, numerics, name, value)
    truth = truth_model(moved_case, moved_beam, numerics, sm)
    return loop_radius(truth, controller, plant_modes(truth), sensor_rows(truth, controller.sensors))


def stability_margin(case: Case, beam, numerics, controller, name: str, values: np.ndarray, radius: np.ndarray,
                     nominal: float) -> tuple[float, float]:
    """The lowest and highest value of the grid ``values`` (increasing) between which the loop stays
    stable around ``nominal``: from the grid's last stable point next to an unstable one, refined by
    Brent's method; the grid's end when every point on that side is stable; NaN, NaN when the loop
    at ``nominal`` is not."""
    if not _radius_at(case, beam, numerics, controller, name, nominal).radius < 1.0:
        return math.nan, math.nan

    def excess(value):
        return _radius_at(case, beam, numerics, controller, name, value).radius - 1.0

    found = []
    for side in (np.flatnonzero(values < nominal)[::-1], np.flatnonzero(values > nominal)):
        edge, inner = (float(values[side[-1]]) if side.size else nominal), nominal
        for k in side:
            if not radius[k] < 1.0:
                edge = float(scipy.optimize.brentq(excess, inner, values[k], xtol=MARGIN_XTOL * max(abs(nominal), 1.0)))
                break
            inner = float(values[k])
        found.append(edge)
    return found[0], found[1]


def robustness_map(case: Case, beam, numerics, ranges: Mapping[str, Sequence[float]], points: int) -> RobustnessMap:
    """The :class:`RobustnessMap` of the sampled ``case`` (its controller built for the nominal plant)
    over ``points`` uniform values of each parameter's ``[low, high]`` of ``ranges``."""
    if not (isinstance(points, int) and points >= 2):
        raise ValueError(f"points = {points!r}; allowed: an integer >= 2")
    controller = sampled_controller(case, beam, case_matrices(case, beam, numerics))
    values, radius, mode, nominal, margins = {}, {}, {}, {}, {}
    for name, (low, high) in ranges.items():
        if not (math.isfinite(low) and math.isfinite(high) and 0.0 <= low < high):
            raise ValueError(f"ranges[{name!r}] = {[low, high]!r}; allowed: [low, high] with 0 <= low < high")
        grid = np.linspace(low, high, points)
        found = [_radius_at(case, beam, numerics, controller, name, float(value)) for value in grid]
        values[name], nominal[name] = grid, nominal_value(case, name)
        radius[name] = np.array([point.radius for point in found])
        mode[name] = np.array([point.mode for point in found], dtype=object)
        margins[name] = stability_margin(case, beam, numerics, controller, name, grid, radius[name], nominal[name])
    at_nominal = loop_radius(truth_model(case, beam, numerics, case_matrices(case, beam, numerics)), controller).radius
    return RobustnessMap(case=case.label, values=values, radius=radius, mode=mode, nominal=nominal,
                         margins=margins, nominal_radius=at_nominal)


@dataclass(frozen=True)
class MarginRun:
    """A nonlinear run of a case's nominal controller on the plant with ``parameter`` at ``value``,
    ``where`` (inside or outside) its ``side`` (lowest or highest) margin: the loop's linear spectral
    ``radius`` and ``predicted_rate`` ``ln radius / Ts`` (s-1), the ``measured_rate`` of the applied
    command's envelope and the integrator's ``status``."""

    case: str
    parameter: str
    side: str
    where: str
    value: float
    radius: float
    predicted_rate: float
    measured_rate: float
    status: str


def confirm_margins(case: Case, beam, numerics, found: RobustnessMap, deflection: float = 1e-3) -> list[MarginRun]:
    """The :class:`MarginRun` pairs of every margin of ``found`` (the map of ``case``) that lies inside
    its swept range (module docstring), :data:`CONFIRM_STEP` of its value inside and outside."""
    controller = sampled_controller(case, beam, case_matrices(case, beam, numerics))
    sampling = case.maneuver.sampling
    quiet = tuple(dataclasses.replace(sensor, noise=0.0, quantum=0.0) for sensor in sampling.sensors)
    runs = []
    for name, (low, high) in found.margins.items():
        grid, nominal = found.values[name], found.nominal[name]
        for side, edge, end in (("lowest", low, grid[0]), ("highest", high, grid[-1])):
            if not math.isfinite(edge) or math.isclose(edge, end):
                continue
            inward = 1.0 if side == "lowest" else -1.0
            points = {"inside": edge + inward * min(CONFIRM_STEP * edge, 0.5 * abs(nominal - edge)),
                      "outside": edge - inward * CONFIRM_STEP * edge}
            linear = {}
            for where, value in points.items():
                moved_case, moved_beam, sm = moved_plant(case, beam, numerics, name, value)
                truth = truth_model(moved_case, moved_beam, numerics, sm)
                rows = sensor_rows(truth, controller.sensors)
                radius = loop_radius(truth, controller, plant_modes(truth), rows).radius
                linear[where] = (moved_case, moved_beam, sm, dataclasses.replace(controller, sensor_rows=rows), radius)
            slowest = min(abs(math.log(item[4])) for item in linear.values()) / controller.Ts
            t_end = min(max(CONFIRM_EFOLDS / max(slowest, 1e-12), CONFIRM_T_END[0]), CONFIRM_T_END[1])
            for where, (moved_case, moved_beam, sm, moved, radius) in linear.items():
                rest = at_rest(moved_case, deflection, sm, t_end)
                run = dataclasses.replace(rest, maneuver=dataclasses.replace(
                    rest.maneuver, sampling=dataclasses.replace(sampling, sensors=quiet)))
                rate, status = nonlinear_rate(run, moved_beam, numerics, sm, moved)
                runs.append(MarginRun(case.label, name, side, where, float(points[where]), radius,
                                      math.log(radius) / controller.Ts, rate, status))
    return runs


def robustness_dataset(maps: Sequence[RobustnessMap], confirmations: Sequence[MarginRun] = ()) -> xr.Dataset:
    """The maps of several cases (the same parameters and points) as one CF dataset: per parameter
    ``<name>`` (its grid, a coordinate ``<name>_value`` over ``<name>_point``), ``radius_<name>`` and
    ``mode_<name>`` over ``(case, <name>_point)``, ``nominal_<name>``, ``lowest_<name>`` and
    ``highest_<name>`` over ``case``; ``nominal_radius`` over ``case``; the ``confirmations``
    (:class:`MarginRun`) as ``confirmation_<field>`` over ``confirmation``."""
    first = maps[0]
    data, coords = {}, {"case": ("case", [m.case for m in maps], {"long_name": "sampled case"})}
    for name, grid in first.values.items():
        unit, what = PARAMETERS[name]
        point = f"{name}_point"
        coords[f"{name}_value"] = (point, grid, {"units": unit, "long_name": what})
        data[f"radius_{name}"] = (("case", point), np.stack([m.radius[name] for m in maps]),
                                  {"units": "1", "long_name": f"spectral radius of the sampled loop against {what}"})
        data[f"mode_{name}"] = (("case", point), np.stack([m.mode[name] for m in maps]).astype(str),
                                {"long_name": "the truth's mode that carries the pole of largest modulus"})
        data[f"nominal_{name}"] = ("case", [m.nominal[name] for m in maps], {"units": unit})
        for k, side in enumerate(("lowest", "highest")):
            data[f"{side}_{name}"] = ("case", [m.margins[name][k] for m in maps], {
                "units": unit, "long_name": f"{side} {what} of the range that keeps the loop stable (the range's "
                                            "end if stable up to there; NaN: the nominal loop is not stable)"})
    data["nominal_radius"] = ("case", [m.nominal_radius for m in maps], {"units": "1"})
    for field in dataclasses.fields(MarginRun):
        data[f"confirmation_{field.name}"] = ("confirmation", [getattr(run, field.name) for run in confirmations], {
            "long_name": {"predicted_rate": "ln(spectral radius) / Ts of the linear loop, s-1",
                          "measured_rate": "growth rate of the applied command's envelope in the nonlinear run, s-1"
                          }.get(field.name, field.name.replace("_", " "))})
    title = "hubbeam robustness maps: spectral radius of sampled loops over plant parameters"
    attrs = global_attributes(title, extra={"parameters": ", ".join(first.values)})
    return xr.Dataset(data, coords=coords, attrs=attrs)


__all__ = ["PARAMETERS", "MarginRun", "RobustnessMap", "confirm_margins", "moved_plant", "nominal_value",
           "robustness_dataset", "robustness_map", "stability_margin"]
