"""The linear products as labelled datasets: tracked Campbell diagrams, poles and zeros over speed,
frequency responses and mode shapes along the span.

Each function takes the beam, the tip masses (kg, at the beam tip ``l = L``; 0 for none), the hub
speeds (rad s-1) and the discretisation, and returns an :class:`xarray.Dataset` with CF units and
long names over the models of :data:`hubbeam.model.models.MODELS`; a workflow script adds the provenance
attributes (``hubbeam.results.provenance.global_attributes``) and writes it with
``hubbeam.results.io.write_netcdf``. ``damping`` is a damping record or its mapping (``hubbeam.model.damping``) or
None. Models without a mode or a root where others have one (SFOAM keeps no axial coordinates)
are padded with NaN (``kind`` and ``stable`` -1, ``none``).

* :func:`campbell`: every mode of every model, held (prescribed) and free hub, tracked over the
  speeds by :mod:`hubbeam.linear.tracking`: frequency, damping ratio, growth rate, kind
  (vibration, divergent, rigid), stability, label, and the mode's shape (its position components);
* :func:`mode_shapes`: from a Campbell dataset, the transverse shapes ``v(x) = f2(x) q2`` of the
  first vibration modes at the lowest and the highest speed;
* :func:`poles_zeros`: poles of the free hub and transmission zeros from the hub torque to the
  hub angle, the tip deflection and the tip's arc position (:mod:`hubbeam.linear.frequency`), with
  the collocated alternation and the right-half-plane zeros;
* :func:`bode`: magnitude and phase from the hub torque to those outputs.
"""

from __future__ import annotations

import json
import re
from collections.abc import Sequence

import numpy as np
import xarray as xr

from hubbeam.configuration.settings import damping_settings
from hubbeam.linear import frequency, tracking
from hubbeam.linear.statespace import HUBS, INPUT_UNITS, OUTPUTS, check_speeds, linear_model, spin_equations
from hubbeam.model.beam import beam_attributes
from hubbeam.model.damping import damping_matrices, damping_to_dict
from hubbeam.model.eigen import critical_speed
from hubbeam.model.matrices import MODE_NORMALISATION, assemble
from hubbeam.model.models import MODELS
from hubbeam.model.models import model as model_traits
from hubbeam.model.modes import transverse_modes
from hubbeam.model.parameters import TipMass
from hubbeam.model.shapes import unit_peak
from hubbeam.results.provenance import without_provenance

#: the outputs of the transfer functions from the hub torque (free hub)
TRANSFER_OUTPUTS = ("hub_angle", "tip_deflection", "tip_arc")
#: mode kinds stored in ``kind`` (flag values; ``none``: no such mode in this model)
KINDS = {"none": -1, "vibration": 0, "divergent": 1, "rigid": 2}
#: hub conditions in the datasets: held = prescribed hub speed, free = torque input
HUB_NAMES = {"held": "prescribed", "free": "free"}
HZ = 1.0 / (2.0 * np.pi)


def _systems(beam, tip_masses, n_modes, n_quad):
    """``[(mass, SystemMatrices)]`` with the tip mass at the beam tip (none for 0 kg)."""
    masses = np.atleast_1d(np.asarray(tip_masses, dtype=float))
    if masses.ndim != 1 or masses.size == 0 or not np.all(np.isfinite(masses) & (masses >= 0.0)):
        raise ValueError(f"tip_masses = {tip_masses!r}; allowed: a non-empty list of masses >= 0 kg")
    return [(float(m), assemble(beam, TipMass(mass=float(m), position=float(beam.L)) if m > 0
                                else None, n_modes, n_quad)) for m in masses]


def _damping(damping, sm):
    return None if damping is None else damping_matrices(damping, sm)


def _checked(beam, tip_masses, speeds, n_modes, n_quad, damping, outputs=()):
    """Every argument checked, then the speeds as an array and the systems (:func:`_systems`)."""
    damping_settings(damping)  # a mapping checked here (a record as it is)
    speeds = check_speeds(speeds)
    unknown = [name for name in outputs if name not in OUTPUTS]
    if unknown:
        raise ValueError(f"outputs = {list(outputs)!r}; allowed: names among {', '.join(OUTPUTS)}")
    return speeds, _systems(beam, tip_masses, n_modes, n_quad)


def _attributes(beam, n_modes, n_quad, damping, title) -> dict:
    return {"title": title, "n_modes": int(n_modes), "n_quad_requested": int(n_quad),
            "mode_normalisation": MODE_NORMALISATION, "tip_position_m": float(beam.L),
            "damping": json.dumps(damping_to_dict(damping_settings(damping)), sort_keys=True)} | beam_attributes(beam)


def _coords(masses, speeds, **extra):
    coords = {
        "model": ("model", list(MODELS), {"long_name": "model (Section 3)"}),
        "tip_mass": ("tip_mass", np.asarray(masses, float),
                     {"units": "kg", "long_name": "tip mass m_t at the beam tip"}),
        "speed": ("speed", np.asarray(speeds, float),
                  {"units": "rad s-1", "long_name": "hub speed Omega of the steady spin"}),
    }
    return coords | extra


def _coordinate_names(n_modes):
    """Position coordinates of the models that keep every one (theta, q1, q2)."""
    return ["theta"] + [f"q{b}_{i}" for b in (1, 2) for i in range(1, n_modes + 1)]


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
    A = np.stack([lm.A for lm in models])
    names = models[0].states[:A.shape[1] // 2]
    modes = tracking.track(tracking.state_modes(A, mode_weights(sm, model, root_spring)))
    return modes, names


def campbell(beam, tip_masses, speeds, n_modes, n_quad=64, damping=None) -> xr.Dataset:
    """Tracked, damped Campbell diagram of every model, held and free hub (module docstring).

    Mode ``k`` is one tracked mode (numbered by frequency at the first speed); ``mode_label`` its
    group there (numbered by frequency within the group), ``label`` its group at each speed,
    numbered by frequency within the group at that speed (``bending 2`` is the second bending mode
    by frequency, also on a light free hub where every bending mode's dominant coordinate is the
    first: :func:`hubbeam.linear.tracking.numbered_by_frequency`). ``unstable_from`` is the lowest
    grid speed with an unstable mode; ``critical_speed`` that of ``K22`` (Eq. 31, hub held) of the
    model's linearisation
    (:func:`hubbeam.model.eigen.critical_speed`), NaN where none up to the last speed.
    """
    speeds, systems = _checked(beam, tip_masses, speeds, n_modes, n_quad, damping)
    coordinates = _coordinate_names(n_modes)
    m = len(coordinates)  # modes of the models that keep every coordinate: one per coordinate
    shape = (len(MODELS), len(systems), len(HUB_NAMES), speeds.size, m)
    out = {name: np.full(shape, np.nan) for name in ("frequency", "damping_ratio", "growth_rate")}
    kind = np.full(shape, -1, dtype=np.int8)
    stable = np.full(shape, -1, dtype=np.int8)
    label = np.full(shape, "", dtype=object)
    components = np.full(shape + (m,), np.nan + 0j)
    critical = np.full((len(MODELS), len(systems)), np.nan)
    for i, model in enumerate(MODELS):
        for j, (mass, sm) in enumerate(systems):
            tip = TipMass(mass=mass, position=float(beam.L)) if mass > 0 else None
            # search up to the last speed (a grid of rest alone: the smallest positive speed)
            critical[i, j] = critical_speed(model_traits(model).linearisation, beam, tip, n_modes,
                                            max(float(speeds[-1]), np.finfo(float).tiny), n_quad)
            for h, hub in enumerate(HUB_NAMES.values()):
                modes, names = tracked_modes(beam, sm, model, hub, speeds, _damping(damping, sm))
                k = modes.eigenvalue.shape[1]
                where = [coordinates.index(name) for name in names]
                out["frequency"][i, j, h, :, :k] = modes.frequency * HZ
                out["damping_ratio"][i, j, h, :, :k] = modes.damping_ratio
                out["growth_rate"][i, j, h, :, :k] = modes.eigenvalue.real
                kind[i, j, h, :, :k] = np.where(modes.rigid, KINDS["rigid"],
                                                np.where(modes.divergent, KINDS["divergent"],
                                                         KINDS["vibration"]))
                stable[i, j, h, :, :k] = modes.stable
                label[i, j, h, :, :k] = tracking.numbered_by_frequency(
                    tracking.dominant_content(modes.shape, names, modes.weights)[0], modes.frequency)
                components[i, j, h, :, :k][..., where] = modes.shape
    growing = (stable == 0).any(axis=-1)  # (model, tip_mass, hub, speed)
    unstable_from = np.where(growing.any(axis=-1), speeds[np.argmax(growing, axis=-1)], np.nan)
    dims = ("model", "tip_mass", "hub", "speed", "mode")
    flags = {"flag_values": np.array(list(KINDS.values()), dtype=np.int8),
             "flag_meanings": " ".join(KINDS)}
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
            "unstable_from": (("model", "tip_mass", "hub"), unstable_from,
                              {"units": "rad s-1", "long_name": "lowest speed of the grid with a "
                                                                "growing mode (NaN: none)"}),
            "critical_speed": (("model", "tip_mass"), critical,
                               {"units": "rad s-1", "long_name": "critical speed of K22 (Eq. 31, hub "
                                "held) of the model's linearisation; NaN: none up to the last "
                                "speed"}),
        },
        coords=_coords([mass for mass, _ in systems], speeds,
                       hub=("hub", list(HUB_NAMES), {"long_name": "hub condition: held (speed "
                                                     "prescribed) or free (torque input)"}),
                       mode=("mode", np.arange(1, m + 1),
                             {"units": "1", "long_name": "tracked mode, numbered by frequency at "
                                                         "the first speed"}),
                       coordinate=("coordinate", coordinates,
                                   {"long_name": "position coordinate of the mode shape"})),
        attrs=_attributes(beam, n_modes, n_quad, damping, "tracked damped Campbell diagram"),
    )
    return ds


def mode_shapes(campbell_ds: xr.Dataset, beam, count: int = 4, stations: int = 101) -> xr.Dataset:
    """Transverse shapes ``v(x) = f2(x) q2`` of the first ``count`` vibration modes (by frequency at
    the first speed) at the first and the last speed of a :func:`campbell` dataset.

    Each shape is scaled to ``max |v| = 1`` with that point real and positive; ``shape`` holds
    its real part, ``shape_imag`` the imaginary part (a gyroscopic mode's phase along the span).
    """
    if not (isinstance(count, (int, np.integer)) and count >= 1):
        raise ValueError(f"count = {count!r}; allowed: an integer >= 1")
    n = int(campbell_ds.attrs["n_modes"])
    x = np.linspace(0.0, float(beam.L), stations)
    f2 = transverse_modes(x, n, beam)  # (stations, n)
    ends = campbell_ds.isel(speed=[0, -1])
    q2 = [f"q2_{i}" for i in range(1, n + 1)]
    vibration = (ends["kind"].isel(speed=0) == KINDS["vibration"]).values
    if count > vibration.sum(axis=-1).min():
        raise ValueError(f"count = {count!r}; allowed: at most {vibration.sum(axis=-1).min()}, the "
                         "vibration modes every model has at the first speed")
    first = np.argsort(np.where(vibration, ends["mode"].values, np.iinfo(int).max), axis=-1,
                       kind="stable")[..., :count]
    parts = (ends["shape_real"] + 1j * ends["shape_imag"]).sel(coordinate=q2).values
    parts = np.take_along_axis(parts, first[..., None, :, None], axis=-2)
    v = unit_peak(np.einsum("xk,...k->...x", f2, parts))
    labels = np.take_along_axis(ends["mode_label"].values, first, axis=-1)
    dims = ("model", "tip_mass", "hub", "speed", "rank", "x")
    return xr.Dataset(
        {
            "shape": (dims, v.real, {"units": "1", "long_name": "transverse mode shape v(x), "
                                                                "real part, max |v| = 1"}),
            "shape_imag": (dims, v.imag, {"units": "1", "long_name": "imaginary part of v(x)"}),
            "mode_label": (dims[:3] + ("rank",), labels,
                           {"long_name": "dominant content at the first speed"}),
            "tracked_mode": (dims[:3] + ("rank",), ends["mode"].values[first],
                             {"units": "1", "long_name": "mode index of the Campbell dataset"}),
        },
        coords={"model": ends["model"], "tip_mass": ends["tip_mass"], "hub": ends["hub"],
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


def poles_zeros(beam, tip_masses, speeds, n_modes, n_quad=64, damping=None,
                outputs: Sequence[str] = TRANSFER_OUTPUTS) -> xr.Dataset:
    """Poles (free and held hub) and transmission zeros from the hub torque over speed.

    ``alternates``: the collocated poles and zeros (hub angle) alternate on the imaginary axis
    (:func:`hubbeam.linear.frequency.alternates`); ``rhp_zero_count`` and ``lowest_rhp_zero``: the
    zeros in the right half-plane of each output and the smallest magnitude among them.
    """
    outputs = tuple(outputs)
    speeds, systems = _checked(beam, tip_masses, speeds, n_modes, n_quad, damping, outputs)
    N = 2 * (1 + 2 * n_modes)
    size = (len(MODELS), len(systems), speeds.size)
    pole = {hub: np.full(size + (N,), np.nan + 0j) for hub in HUB_NAMES}
    zero = np.full(size[:2] + (len(outputs),) + size[2:] + (N,), np.nan + 0j)
    alternating = np.zeros(size, dtype=np.int8)
    rhp_count = np.zeros(size[:2] + (len(outputs),) + size[2:], dtype=np.int32)
    lowest = np.full(rhp_count.shape, np.nan)
    for i, model in enumerate(MODELS):
        for j, (_, sm) in enumerate(systems):
            C = _damping(damping, sm)
            for k, speed in enumerate(speeds):
                lms = {name: linear_model(beam, sm, model, float(speed), hub, C, outputs=outputs)
                       for name, hub in HUB_NAMES.items()}
                for name, lm in lms.items():
                    pole[name][i, j, k] = _padded([frequency.poles(lm)], N)[0]
                roots = [frequency.zeros(lms["free"], output) for output in outputs]
                zero[i, j, :, k] = _padded(roots, N)
                if "hub_angle" in outputs:
                    alternating[i, j, k] = frequency.alternates(
                        pole["free"][i, j, k][np.isfinite(pole["free"][i, j, k])],
                        roots[outputs.index("hub_angle")])
                for o, values in enumerate(roots):
                    rhp = frequency.right_half_plane(values)
                    rhp_count[i, j, o, k] = rhp.size
                    lowest[i, j, o, k] = np.abs(rhp[0]) if rhp.size else np.nan
    rate = {"units": "s-1"}
    data = {}
    for name, values in pole.items():
        what = f"pole, {name} hub"
        data[f"{name}_pole_real"] = (("model", "tip_mass", "speed", "root"), values.real,
                                     rate | {"long_name": f"real part of a {what}"})
        data[f"{name}_pole_imag"] = (("model", "tip_mass", "speed", "root"), values.imag,
                                     rate | {"long_name": f"imaginary part of a {what}"})
    zdims = ("model", "tip_mass", "output", "speed", "root")
    data |= {
        "zero_real": (zdims, zero.real, rate | {"long_name": "real part of a transmission zero "
                                                             "from the hub torque (free hub)"}),
        "zero_imag": (zdims, zero.imag, rate | {"long_name": "imaginary part of a transmission "
                                                             "zero from the hub torque"}),
        "alternates": (("model", "tip_mass", "speed"), alternating,
                       {"long_name": "collocated poles and zeros (hub torque to hub angle) "
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
        coords=_coords([mass for mass, _ in systems], speeds,
                       output=("output", list(outputs), {"long_name": "output of the transfer "
                                                         "function from the hub torque"}),
                       root=("root", np.arange(1, N + 1),
                             {"units": "1", "long_name": "root index, by |Im| then Re (NaN: "
                                                         "fewer roots)"})),
        attrs=_attributes(beam, n_modes, n_quad, damping, "poles and zeros over hub speed"),
    )


def bode(beam, tip_masses, speeds, omega, n_modes, n_quad=64, damping=None,
         outputs: Sequence[str] = TRANSFER_OUTPUTS) -> xr.Dataset:
    """Frequency responses from the hub torque (free hub) to ``outputs`` at the circular
    frequencies ``omega`` (rad s-1): ``<output>_magnitude`` and ``<output>_phase`` (degree), and
    whether the plant is stable at each speed (a TLAM beyond its critical speed is not: its
    frequency response is that of the transfer function, not a measurable steady state)."""
    outputs = tuple(outputs)
    omega = frequency.check_omega(omega)
    speeds, systems = _checked(beam, tip_masses, speeds, n_modes, n_quad, damping, outputs)
    size = (len(MODELS), len(systems), speeds.size)
    magnitude = np.zeros(size + (len(outputs), omega.size))
    phase = np.zeros_like(magnitude)
    stable = np.zeros(size, dtype=np.int8)
    for i, model in enumerate(MODELS):
        for j, (_, sm) in enumerate(systems):
            C = _damping(damping, sm)
            for k, speed in enumerate(speeds):
                lm = linear_model(beam, sm, model, float(speed), "free", C, outputs=outputs)
                magnitude[i, j, k], phase[i, j, k] = frequency.frequency_response(lm, outputs,
                                                                                  omega)
                stable[i, j, k] = bool(np.all(tracking.state_modes(lm.A[None]).stable))
    data = {}
    per_input = INPUT_UNITS[HUBS["free"]]
    for o, output in enumerate(outputs):
        units, what = OUTPUTS[output]
        data[f"{output}_magnitude"] = (
            ("model", "tip_mass", "speed", "frequency"), magnitude[..., o, :],
            {"units": per_unit_input(units, per_input),
             "long_name": f"magnitude of the response of the {what} to the hub torque"})
        data[f"{output}_phase"] = (
            ("model", "tip_mass", "speed", "frequency"), phase[..., o, :],
            {"units": "degree", "long_name": f"phase of the response of the {output} to the hub "
                                             "torque"})
    data["stable"] = (("model", "tip_mass", "speed"), stable,
                      {"long_name": "every mode of the free-hub plant stable",
                       "flag_values": np.array([0, 1], dtype=np.int8), "flag_meanings": "no yes"})
    return xr.Dataset(
        data,
        coords=_coords([mass for mass, _ in systems], speeds,
                       frequency=("frequency", omega,
                                  {"units": "rad s-1", "long_name": "circular frequency"})),
        attrs=_attributes(beam, n_modes, n_quad, damping,
                          "frequency responses from the hub torque"),
    )
