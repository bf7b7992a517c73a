"""The linear products as labelled datasets: tracked Campbell diagrams, poles and zeros over speed,
frequency responses and mode shapes along the span.

Each function takes the plants it spans (a :class:`~hubbeam.linear.axes.PlantAxis`: the paper's grid
of point masses at the tip, ``tip_mass_axis``, or one plant of a study, ``plant_axis``) and the hub
speeds (rad s-1), and returns an :class:`xarray.Dataset` with CF units and long names over the
models of :data:`hubbeam.model.models.MODELS`; a workflow job adds the provenance attributes
(``hubbeam.results.provenance.global_attributes``) and writes it with ``hubbeam.results.io.write_netcdf``.
Every plant's linear models come from :mod:`hubbeam.linear.plant_models` (its tip body, root spring, drive
and damping). Models without a mode or a root where others have one (SFOAM keeps no axial
coordinates) are padded with NaN (``kind`` and ``stable`` -1, ``none``).

The hub conditions (:func:`hubbeam.linear.plant_models.hub_conditions`): held (speed prescribed, input its
acceleration), free (input the hub torque) and, for a plant with a drive, driven (the free hub
through the drive: input the voltage, the back-EMF's damping on the hub; NaN at the speeds the drive
cannot hold within its voltage limit). The frequency responses, poles and zeros are those of the
rig's input: the voltage with a drive, the hub torque without.

* :func:`campbell`: every mode of every model in every hub condition, tracked over the speeds by
  :mod:`hubbeam.linear.tracking`: frequency, damping ratio, growth rate, kind (vibration,
  divergent, rigid), stability, label, and the mode's shape (its position components);
* :func:`mode_shapes`: from a Campbell dataset, the transverse shapes ``v(x) = f2(x) q2`` of the
  first vibration modes at the lowest and the highest speed (and a tip body's rotation);
* :func:`poles_zeros`: poles in every hub condition and transmission zeros from the rig's input to
  the hub angle, the tip deflection and the tip's arc position (:mod:`hubbeam.linear.frequency`),
  with the collocated alternation and the right-half-plane zeros;
* :func:`bode`: magnitude and phase from the rig's input to those outputs.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

import numpy as np
import xarray as xr

from hubbeam.linear import frequency, tracking
from hubbeam.linear.axes import PlantAxis, axis_of
from hubbeam.linear.plant_models import condition_model, hub_conditions, plant_critical_speed, reaches
from hubbeam.linear.statespace import HUBS, INPUT_UNITS, OUTPUTS, check_speeds, linear_model, spin_equations
from hubbeam.model.matrices import functions_load
from hubbeam.model.models import MODELS
from hubbeam.model.models import model as model_traits
from hubbeam.model.modes import transverse_modes
from hubbeam.model.plant import plant_matrices
from hubbeam.model.root import HUB_COORDINATE
from hubbeam.model.shapes import unit_peak
from hubbeam.results.provenance import without_provenance

#: the outputs of the transfer functions from the rig's input (free hub)
TRANSFER_OUTPUTS = ("hub_angle", "tip_deflection", "tip_arc")
#: mode kinds stored in ``kind`` (flag values; ``none``: no such mode in this model)
KINDS = {"none": -1, "vibration": 0, "divergent": 1, "rigid": 2}
#: hub conditions in the datasets of the paper's grid: held = prescribed hub speed, free = torque input
HUB_NAMES = {"held": "prescribed", "free": "free"}
#: what each hub condition is, in the ``hub`` coordinate's long name
HUB_MEANINGS = {"held": "held (speed prescribed)", "free": "free (torque input)",
                "driven": "driven (the free hub through its drive, voltage input)"}
HZ = 1.0 / (2.0 * np.pi)


def _checked(plants, speeds, outputs=()):
    """The axis of ``plants``, the speeds as an array and each plant's matrices, every argument checked."""
    axis = axis_of(plants)
    speeds = check_speeds(speeds)
    unknown = [name for name in outputs if name not in OUTPUTS]
    if unknown:
        raise ValueError(f"outputs = {list(outputs)!r}; allowed: names among {', '.join(OUTPUTS)}")
    return axis, speeds, [plant_matrices(plant) for plant in axis.plants]


def _attributes(axis: PlantAxis, title: str, **extra) -> dict:
    return {"title": title, **axis.attributes, **extra}


def _coords(axis: PlantAxis, speeds, **extra):
    coords = {
        "model": ("model", list(MODELS), {"long_name": "model (Section 3)"}),
        axis.name: axis.coordinate(),
        "speed": ("speed", np.asarray(speeds, float),
                  {"units": "rad s-1", "long_name": "hub speed Omega of the steady spin"}),
    }
    return coords | extra


def _coordinate_names(n_modes, root_spring: bool = False):
    """Position coordinates of the models that keep every one (theta, q1, q2; the hub angle phi
    with a compliant root)."""
    return (["theta"] + [f"q{b}_{i}" for b in (1, 2) for i in range(1, n_modes + 1)]
            + ([HUB_COORDINATE] if root_spring else []))


def _rig_condition(conditions) -> str:
    """The hub condition of the rig's input: driven with a drive, free without."""
    return "driven" if "driven" in conditions else "free"


def mode_weights(sm, model: str, root_spring=None) -> np.ndarray:
    """Square roots of the diagonal of the model's mass matrix at rest (``theta``, ``q1``, ``q2``;
    with a compliant root ``root_spring`` the hub angle ``phi`` too): the MAC and label weights of
    :mod:`hubbeam.linear.tracking`."""
    return np.sqrt(np.diag(spin_equations(sm, model_traits(model), 0.0, root_spring=root_spring)[0]))


def tracked_modes(beam, sm, model: str, hub: str, speeds, damping=None, root_spring=None):
    """The modes of ``model`` with hub condition ``hub`` over ``speeds``, tracked, with the
    position state names: ``(Modes, names)`` (with a compliant root ``root_spring``, its states,
    ``hubbeam.linear.statespace.linear_model``)."""
    models = [linear_model(beam, sm, model, float(speed), hub, damping, outputs=("hub_angle",),
                           root_spring=root_spring) for speed in speeds]
    return _tracked(models, sm, model, root_spring)


def plant_modes(plant, sm, model: str, condition: str, speeds):
    """:func:`tracked_modes` of ``plant`` (matrices ``sm``) in a hub condition (held, free, driven)."""
    models = [condition_model(plant, model, float(speed), condition, ("hub_angle",), sm) for speed in speeds]
    return _tracked(models, sm, model, plant.root_spring)


def _tracked(models, sm, model, root_spring):
    A = np.stack([lm.A for lm in models])
    names = models[0].states[:A.shape[1] // 2]
    modes = tracking.track(tracking.state_modes(A, mode_weights(sm, model, root_spring)))
    return modes, names


def campbell(plants, speeds) -> xr.Dataset:
    """Tracked, damped Campbell diagram of every model in every hub condition of ``plants`` (a
    :class:`~hubbeam.linear.axes.PlantAxis`; module docstring).

    Mode ``k`` is one tracked mode (numbered by frequency at the first speed); ``mode_label`` its
    group there (numbered by frequency within the group), ``label`` its group at each speed,
    numbered by frequency within the group at that speed (``bending 2`` is the second bending mode
    by frequency, also on a light free hub where every bending mode's dominant coordinate is the
    first: :func:`hubbeam.linear.tracking.numbered_by_frequency`). ``unstable_from`` is the lowest
    grid speed with an unstable mode; ``critical_speed`` that of the hub-held stiffness of the
    model's linearisation (``K22`` of Eq. 31 on a rigid root, :func:`hubbeam.linear.plant_models.plant_critical_speed`),
    NaN where none up to the last speed.
    """
    axis, speeds, systems = _checked(plants, speeds)
    conditions = hub_conditions(axis.plants)
    coordinates = _coordinate_names(axis.n_modes, axis.root_spring)
    m = len(coordinates)  # modes of the models that keep every coordinate: one per coordinate
    shape = (len(MODELS), len(systems), len(conditions), speeds.size, m)
    out = {name: np.full(shape, np.nan) for name in ("frequency", "damping_ratio", "growth_rate")}
    kind = np.full(shape, -1, dtype=np.int8)
    stable = np.full(shape, -1, dtype=np.int8)
    label = np.full(shape, "", dtype=object)
    components = np.full(shape + (m,), np.nan + 0j)
    critical = np.full((len(MODELS), len(systems)), np.nan)
    for i, model in enumerate(MODELS):
        for j, (plant, sm) in enumerate(zip(axis.plants, systems)):
            # search up to the last speed (a grid of rest alone: the smallest positive speed)
            critical[i, j] = plant_critical_speed(plant, model, max(float(speeds[-1]), np.finfo(float).tiny), sm)
            for h, condition in enumerate(conditions):
                held = np.array([reaches(plant, condition, speed) for speed in speeds])
                if not held.any():
                    continue
                s = int(np.argmin(held)) if not held.all() else speeds.size  # the speeds the condition reaches
                modes, names = plant_modes(plant, sm, model, condition, speeds[:s])
                k = modes.eigenvalue.shape[1]
                where = [coordinates.index(name) for name in names]
                out["frequency"][i, j, h, :s, :k] = modes.frequency * HZ
                out["damping_ratio"][i, j, h, :s, :k] = modes.damping_ratio
                out["growth_rate"][i, j, h, :s, :k] = modes.eigenvalue.real
                kind[i, j, h, :s, :k] = np.where(modes.rigid, KINDS["rigid"],
                                                 np.where(modes.divergent, KINDS["divergent"],
                                                          KINDS["vibration"]))
                stable[i, j, h, :s, :k] = modes.stable
                label[i, j, h, :s, :k] = tracking.numbered_by_frequency(
                    tracking.dominant_content(modes.shape, names, modes.weights, modes.rigid)[0], modes.frequency)
                components[i, j, h, :s, :k][..., where] = modes.shape
    growing = (stable == 0).any(axis=-1)  # (model, plant, hub, speed)
    unstable_from = np.where(growing.any(axis=-1), speeds[np.argmax(growing, axis=-1)], np.nan)
    dims = ("model", axis.name, "hub", "speed", "mode")
    flags = {"flag_values": np.array(list(KINDS.values()), dtype=np.int8),
             "flag_meanings": " ".join(KINDS)}
    hubs = ", ".join(HUB_MEANINGS[condition] for condition in conditions[:-1]) + " or " + HUB_MEANINGS[conditions[-1]]
    ds = xr.Dataset(
        {
            "frequency": (dims, out["frequency"],
                          {"units": "Hz", "long_name": "damped frequency |Im lambda| / 2 pi "
                                                      "(0: divergent or rigid mode)"}),
            "damping_ratio": (dims, out["damping_ratio"],
                              {"units": "1", "long_name": "damping ratio -Re lambda / |lambda| "
                                                          "(NaN: rigid mode)"}),
            "growth_rate": (dims, out["growth_rate"],
                            {"units": "s-1", "long_name": "Re lambda (> 0: growing)"}),
            "kind": (dims, kind, {"long_name": "kind of mode"} | flags),
            "stable": (dims, stable, {"long_name": "mode does not grow (1) or grows (0)",
                                      "flag_values": np.array([-1, 0, 1], dtype=np.int8),
                                      "flag_meanings": "none unstable stable"}),
            "label": (dims, label.astype(str),
                      {"long_name": "dominant content of the mode's shape at this speed, numbered by "
                                    "frequency within its group at this speed"}),
            "mode_label": (dims[:3] + ("mode",), tracking.numbered_by_frequency(label[..., 0, :]),
                           {"long_name": "dominant content of the mode's shape at the first speed, numbered "
                                         "by frequency within its group"}),
            "shape_real": (dims + ("coordinate",), components.real,
                           {"units": "1", "long_name": "real part of the mode shape (position "
                            "components, unit norm weighted by the square root of the mass "
                            "diagonal; theta in rad, q in kg1/2 m, relative)"}),
            "shape_imag": (dims + ("coordinate",), components.imag,
                           {"units": "1", "long_name": "imaginary part of the mode shape"}),
            "unstable_from": (("model", axis.name, "hub"), unstable_from,
                              {"units": "rad s-1", "long_name": "lowest speed of the grid with a "
                                                                "growing mode (NaN: none)"}),
            "critical_speed": (("model", axis.name), critical,
                               {"units": "rad s-1", "long_name": "critical speed of K22 (Eq. 31, hub "
                                "held) of the model's linearisation; NaN: none up to the last "
                                "speed"}),
        },
        coords=_coords(axis, speeds,
                       hub=("hub", list(conditions), {"long_name": f"hub condition: {hubs}"}),
                       mode=("mode", np.arange(1, m + 1),
                             {"units": "1", "long_name": "tracked mode, numbered by frequency at "
                                                         "the first speed"}),
                       coordinate=("coordinate", coordinates,
                                   {"long_name": "position coordinate of the mode shape"})),
        attrs=_attributes(axis, "tracked damped Campbell diagram"),
    )
    return ds


def mode_shapes(campbell_ds: xr.Dataset, plants, count: int = 4, stations: int = 101) -> xr.Dataset:
    """Transverse shapes ``v(x) = f2(x) q2`` of the first ``count`` vibration modes (by frequency at
    the first speed) at the first and the last speed of a :func:`campbell` dataset of ``plants``
    (its axis; the transverse functions of the plants').

    Each shape is scaled to ``max |v| = 1`` with that point real and positive; ``shape`` holds
    its real part, ``shape_imag`` the imaginary part (a gyroscopic mode's phase along the span).
    For the plants of a study, ``body_rotation`` is the rotation of the tip body in the mode, on
    the same scale (``theta + f2'(l) q2``, per metre of the shape's peak): what turns the payload.
    """
    if not (isinstance(count, (int, np.integer)) and count >= 1):
        raise ValueError(f"count = {count!r}; allowed: an integer >= 1")
    axis = axis_of(plants)
    plant, beam = axis.plants[0], axis.beam
    n = int(campbell_ds.attrs["n_modes"])
    x = np.linspace(0.0, float(beam.L), stations)
    load = functions_load(beam, plant_matrices(plant)) if axis.name == "plant" else None
    f2 = transverse_modes(x, n, beam, load=load)  # (stations, n)
    ends = campbell_ds.isel(speed=[0, -1])
    q2 = [f"q2_{i}" for i in range(1, n + 1)]
    vibration = (ends["kind"].isel(speed=0) == KINDS["vibration"]).values
    if count > vibration.sum(axis=-1).min():
        raise ValueError(f"count = {count!r}; allowed: at most {vibration.sum(axis=-1).min()}, the "
                         "vibration modes every model has at the first speed")
    first = np.argsort(np.where(vibration, ends["mode"].values, np.iinfo(int).max), axis=-1,
                       kind="stable")[..., :count]
    whole = (ends["shape_real"] + 1j * ends["shape_imag"]).values
    parts = (ends["shape_real"] + 1j * ends["shape_imag"]).sel(coordinate=q2).values
    parts = np.take_along_axis(parts, first[..., None, :, None], axis=-2)
    v = np.einsum("xk,...k->...x", f2, parts)
    scaled = unit_peak(v)
    labels = np.take_along_axis(ends["mode_label"].values, first, axis=-1)
    dims = ("model", axis.name, "hub", "speed", "rank", "x")
    data = {
        "shape": (dims, scaled.real, {"units": "1", "long_name": "transverse mode shape v(x), "
                                                                "real part, max |v| = 1"}),
        "shape_imag": (dims, scaled.imag, {"units": "1", "long_name": "imaginary part of v(x)"}),
        "mode_label": (dims[:3] + ("rank",), labels, {"long_name": "dominant content at the first speed"}),
        "tracked_mode": (dims[:3] + ("rank",), ends["mode"].values[first],
                         {"units": "1", "long_name": "mode index of the Campbell dataset"}),
    }
    if axis.name == "plant":
        slope = transverse_modes(np.array([plant.tip.position]), n, beam, derivative=1, load=load)[0]
        theta = np.take_along_axis(whole[..., list(ends["coordinate"].values).index("theta")],
                                   first[..., None, :], axis=-1)
        peak = np.take_along_axis(v, np.argmax(np.abs(v), axis=-1)[..., None], axis=-1)[..., 0]
        with np.errstate(invalid="ignore", divide="ignore"):
            rotation = (theta + np.einsum("k,...k->...", slope, parts)) / peak
        data["body_rotation"] = (dims[:-1], rotation.real,
                                 {"units": "m-1", "long_name": "rotation of the tip body theta + f2'(l) q2 in the "
                                  "mode, per metre of the shape's peak (real part)"})
    return xr.Dataset(
        data,
        coords={"model": ends["model"], axis.name: ends[axis.name], "hub": ends["hub"],
                "speed": ends["speed"],
                "rank": ("rank", np.arange(1, count + 1),
                         {"units": "1", "long_name": "vibration mode, by frequency at rest"}),
                "x": ("x", x, {"units": "m", "long_name": "distance from the clamp"})},
        attrs=without_provenance(campbell_ds.attrs) | {"title": "mode shapes along the span"},
    )
def per_unit_input(units: str, input_units: str) -> str:
    """UDUNITS of an output per unit input: ``("rad", "N m")`` -> ``"rad N-1 m-1"``."""
    def inverse(token):
        name, power = re.fullmatch(r"([A-Za-z]+)(-?\d*)", token).groups()
        exponent = -int(power or 1)
        return name if exponent == 1 else f"{name}{exponent}"
    return " ".join([units] + [inverse(token) for token in input_units.split()])


def _padded(arrays, width):
    out = np.full((len(arrays), width), np.nan + 0j)
    for k, values in enumerate(arrays):
        out[k, :values.size] = values
    return out


def _input_words(axis: PlantAxis, conditions) -> tuple[str, str]:
    """The rig's input of the axis's transfer functions: its name and how the long names say it."""
    name = "voltage" if _rig_condition(conditions) == "driven" else HUBS["free"]
    return name, {"voltage": "drive voltage", "hub_torque": "hub torque"}[name]


def poles_zeros(plants, speeds, outputs: Sequence[str] = TRANSFER_OUTPUTS) -> xr.Dataset:
    """Poles (every hub condition) and transmission zeros from the rig's input over speed.

    ``alternates``: the collocated poles and zeros (hub angle) alternate on the imaginary axis
    (:func:`hubbeam.linear.frequency.alternates`); ``rhp_zero_count`` and ``lowest_rhp_zero``: the
    zeros in the right half-plane of each output and the smallest magnitude among them.
    """
    outputs = tuple(outputs)
    axis, speeds, systems = _checked(plants, speeds, outputs)
    conditions = hub_conditions(axis.plants)
    rig = _rig_condition(conditions)
    _, words = _input_words(axis, conditions)
    N = 2 * len(_coordinate_names(axis.n_modes, axis.root_spring))
    size = (len(MODELS), len(systems), speeds.size)
    pole = {condition: np.full(size + (N,), np.nan + 0j) for condition in conditions}
    zero = np.full(size[:2] + (len(outputs),) + size[2:] + (N,), np.nan + 0j)
    alternating = np.zeros(size, dtype=np.int8)
    rhp_count = np.zeros(size[:2] + (len(outputs),) + size[2:], dtype=np.int32)
    lowest = np.full(rhp_count.shape, np.nan)
    for i, model in enumerate(MODELS):
        for j, (plant, sm) in enumerate(zip(axis.plants, systems)):
            for k, speed in enumerate(speeds):
                lms = {condition: condition_model(plant, model, float(speed), condition, outputs, sm)
                       for condition in conditions if reaches(plant, condition, speed)}
                if rig not in lms:  # beyond the drive's reach: no rig at this speed
                    continue
                for name, lm in lms.items():
                    pole[name][i, j, k] = _padded([frequency.poles(lm)], N)[0]
                roots = [frequency.zeros(lms[rig], output) for output in outputs]
                zero[i, j, :, k] = _padded(roots, N)
                if "hub_angle" in outputs:
                    alternating[i, j, k] = frequency.alternates(
                        pole[rig][i, j, k][np.isfinite(pole[rig][i, j, k])], roots[outputs.index("hub_angle")])
                for o, values in enumerate(roots):
                    rhp = frequency.right_half_plane(values)
                    rhp_count[i, j, o, k] = rhp.size
                    lowest[i, j, o, k] = np.abs(rhp[0]) if rhp.size else np.nan
    rate = {"units": "s-1"}
    data = {}
    for name, values in pole.items():
        what = f"pole, {name} hub"
        data[f"{name}_pole_real"] = (("model", axis.name, "speed", "root"), values.real,
                                     rate | {"long_name": f"real part of a {what}"})
        data[f"{name}_pole_imag"] = (("model", axis.name, "speed", "root"), values.imag,
                                     rate | {"long_name": f"imaginary part of a {what}"})
    zdims = ("model", axis.name, "output", "speed", "root")
    source = f"from the {words}" + (" (free hub)" if rig == "free" else " (driven hub)")
    data |= {
        "zero_real": (zdims, zero.real, rate | {"long_name": f"real part of a transmission zero {source}"}),
        "zero_imag": (zdims, zero.imag, rate | {"long_name": "imaginary part of a transmission "
                                                             f"zero from the {words}"}),
        "alternates": (("model", axis.name, "speed"), alternating,
                       {"long_name": f"collocated poles and zeros ({words} to hub angle) "
                                     "alternate on the imaginary axis",
                        "flag_values": np.array([0, 1], dtype=np.int8), "flag_meanings": "no yes"}),
        "rhp_zero_count": (zdims[:-1], rhp_count,
                           {"units": "1", "long_name": "zeros in the right half-plane "
                                                      "(non-minimum phase)"}),
        "lowest_rhp_zero": (zdims[:-1], lowest,
                            rate | {"long_name": "smallest |z| of the right-half-plane zeros "
                                                 "(NaN: none)"}),
    }
    return xr.Dataset(
        data,
        coords=_coords(axis, speeds,
                       output=("output", list(outputs), {"long_name": "output of the transfer "
                                                         f"function from the {words}"}),
                       root=("root", np.arange(1, N + 1),
                             {"units": "1", "long_name": "root index, by |Im| then Re (NaN: "
                                                         "fewer roots)"})),
        attrs=_attributes(axis, "poles and zeros over hub speed"),
    )


def bode(plants, speeds, omega, outputs: Sequence[str] = TRANSFER_OUTPUTS) -> xr.Dataset:
    """Frequency responses from the rig's input (the free hub's torque, or the drive's voltage) to
    ``outputs`` at the circular frequencies ``omega`` (rad s-1): ``<output>_magnitude`` and
    ``<output>_phase`` (degree), and whether the plant is stable at each speed (a TLAM beyond its
    critical speed is not: its frequency response is that of the transfer function, not a
    measurable steady state)."""
    outputs = tuple(outputs)
    omega = frequency.check_omega(omega)
    axis, speeds, systems = _checked(plants, speeds, outputs)
    conditions = hub_conditions(axis.plants)
    rig = _rig_condition(conditions)
    name, words = _input_words(axis, conditions)
    size = (len(MODELS), len(systems), speeds.size)
    magnitude = np.zeros(size + (len(outputs), omega.size))
    phase = np.zeros_like(magnitude)
    stable = np.zeros(size, dtype=np.int8)
    for i, model in enumerate(MODELS):
        for j, (plant, sm) in enumerate(zip(axis.plants, systems)):
            for k, speed in enumerate(speeds):
                if not reaches(plant, rig, speed):  # beyond the drive's reach: no rig at this speed
                    magnitude[i, j, k] = phase[i, j, k] = np.nan
                    continue
                lm = condition_model(plant, model, float(speed), rig, outputs, sm)
                magnitude[i, j, k], phase[i, j, k] = frequency.frequency_response(lm, outputs, omega)
                stable[i, j, k] = bool(np.all(tracking.state_modes(lm.A[None]).stable))
    data = {}
    per_input = INPUT_UNITS[name]
    for o, output in enumerate(outputs):
        units, what = OUTPUTS[output]
        data[f"{output}_magnitude"] = (
            ("model", axis.name, "speed", "frequency"), magnitude[..., o, :],
            {"units": per_unit_input(units, per_input),
             "long_name": f"magnitude of the response of the {what} to the {words}"})
        data[f"{output}_phase"] = (
            ("model", axis.name, "speed", "frequency"), phase[..., o, :],
            {"units": "degree", "long_name": f"phase of the response of the {output} to the {words}"})
    data["stable"] = (("model", axis.name, "speed"), stable,
                      {"long_name": f"every mode of the {rig}-hub plant stable",
                       "flag_values": np.array([0, 1], dtype=np.int8), "flag_meanings": "no yes"})
    return xr.Dataset(
        data,
        coords=_coords(axis, speeds,
                       frequency=("frequency", omega,
                                  {"units": "rad s-1", "long_name": "circular frequency"})),
        attrs=_attributes(axis, f"frequency responses from the {words}"),
    )
