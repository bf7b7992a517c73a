"""The beam of a study as data: its sectional properties along the span, the tip masses of its
cases, and its first transverse mode shapes at rest and at speed (:func:`beam_dataset`; its
properties drawn by :mod:`hubbeam.plotting.beam_properties`, the plants' damped shapes by
:mod:`hubbeam.plotting.linear_mode_shapes`).

At a constant hub speed ``Omega`` the free transverse vibrations obey ``K22(Omega) v = omega^2 M2 v``
(Eq. 31, :mod:`hubbeam.model.eigen`; ``M2`` with a tip body's rotary inertia); mode ``i`` has the
shape ``w_i(x) = f2(x) v_i`` (Eq. 8), scaled by :func:`unit_peak` (its largest deflection is +1), as
the damped modes' shapes of the linear models are (``hubbeam.linear.datasets.mode_shapes``). A direction in
which ``K22`` is not positive definite (TLAM beyond its critical speed) has no vibration: its
frequency and shape are NaN.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import scipy.linalg
import xarray as xr

from hubbeam.core.system_matrices import transverse_mass
from hubbeam.model.beam import SECTION_UNITS, beam_attributes
from hubbeam.model.eigen import K22, LINEARISATIONS
from hubbeam.model.matrices import assemble
from hubbeam.model.modes import transverse_modes
from hubbeam.model.parameters import TipMass

#: points along the span at which properties and shapes are stored (plus the stations)
SPAN_POINTS = 201
#: long name of each sectional property
LONG_NAMES = {"rhoA": "mass per unit length", "EI": "bending stiffness", "EA": "axial stiffness"}


def span(params) -> np.ndarray:
    """Abscissae from root to tip (m): :data:`SPAN_POINTS` evenly spaced and every station."""
    return np.union1d(np.linspace(0.0, params.L, SPAN_POINTS), params.stations)


def unit_peak(v):
    """Shapes ``v`` (real or complex, along the last axis) divided by their value of largest
    magnitude: ``max |v| = 1``, that point real and positive. The one normalisation of every mode
    shape hubbeam stores; an all-zero shape gives NaN."""
    v = np.asarray(v)
    peak = np.take_along_axis(v, np.argmax(np.abs(v), axis=-1)[..., None], axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return v / peak


def mode_shapes(params, tip: TipMass, speeds, n_shapes: int, n_modes: int, n_quad: int = 64):
    """Frequencies (Hz), shape ``(model, speed, mode)``, and shapes ``w(x)``, shape ``(model,
    speed, mode, x)`` on :func:`span`, of the first ``n_shapes`` transverse modes."""
    sm = assemble(params, tip, n_modes, n_quad)
    shapes_x = transverse_modes(span(params), n_modes, params)
    frequencies = np.full((len(LINEARISATIONS), len(speeds), n_shapes), np.nan)
    shapes = np.full(frequencies.shape + shapes_x.shape[:1], np.nan)
    for m, model in enumerate(LINEARISATIONS):
        for s, speed in enumerate(speeds):
            omega2, vectors = scipy.linalg.eigh(K22(sm, model, speed), transverse_mass(sm))
            for i in np.flatnonzero(omega2[:n_shapes] > 0.0):
                shapes[m, s, i] = unit_peak(shapes_x @ vectors[:, i])
                frequencies[m, s, i] = np.sqrt(omega2[i]) / (2.0 * np.pi)
    return frequencies, shapes


def beam_dataset(params, tips: Mapping[str, TipMass], speeds, shape_tips, n_shapes: int,
                 n_modes: int, n_quad: int = 64) -> xr.Dataset:
    """The study's beam: ``rhoA``, ``EI``, ``EA`` on :func:`span` and at the stations, the tip
    mass of every case (``tips``: case name -> tip mass), and the first ``n_shapes`` transverse
    mode shapes of TLAM and FOAM at ``speeds`` (rad s-1) with each tip mass of ``shape_tips``
    (kg) at the tip."""
    x = span(params)
    stations = np.asarray(params.stations, dtype=float)
    speeds = np.asarray(speeds, dtype=float)
    shape_tips = np.asarray(shape_tips, dtype=float)
    results = [mode_shapes(params, TipMass(mass=mass, position=params.L), speeds, n_shapes, n_modes, n_quad)
               for mass in shape_tips]
    frequency = np.stack([f for f, _ in results], axis=1)
    shape = np.stack([w for _, w in results], axis=1)
    names = list(tips)
    properties = {}
    for name, long_name in LONG_NAMES.items():
        at, unit = getattr(params, f"{name}_at"), SECTION_UNITS[name]
        properties[name] = ("x", at(x), {"units": unit, "long_name": long_name})
        properties[f"station_{name}"] = ("station", at(stations),
                                         {"units": unit, "long_name": f"{long_name} at the stations"})
    dims = ("model", "tip_mass", "speed", "mode")
    return xr.Dataset(
        properties | {
            "case_tip_mass": ("case", [tips[name].mass for name in names],
                              {"units": "kg", "long_name": "tip mass of the case"}),
            "case_tip_position": ("case", [tips[name].position for name in names],
                                  {"units": "m", "long_name": "tip-mass position of the case"}),
            "frequency": (dims, frequency, {"units": "Hz", "long_name": "transverse vibration frequency "
                                            "(NaN: K22 not positive definite)"}),
            "shape": (dims + ("x",), shape, {"units": "1", "long_name": "transverse mode shape f2(x) v, "
                                             "largest |deflection| 1, tip deflection >= 0"}),
        },
        coords={
            "x": ("x", x, {"units": "m", "long_name": "distance from the clamped root"}),
            "station": ("station", stations, {"units": "m", "long_name": "station of the sectional properties"}),
            "case": ("case", names),
            "model": ("model", list(LINEARISATIONS)),
            "tip_mass": ("tip_mass", shape_tips, {"units": "kg", "long_name": "tip mass at the tip"}),
            "speed": ("speed", speeds, {"units": "rad s-1", "long_name": "hub angular velocity"}),
            "mode": ("mode", np.arange(1, n_shapes + 1), {"units": "1", "long_name": "mode number"}),
        },
        attrs=beam_attributes(params) | {"title": "the study's beam: properties and transverse mode shapes",
                                          "n_modes": int(n_modes), "n_quad": int(n_quad)},
    )
