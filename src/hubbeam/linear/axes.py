"""The plants a linear product spans, and how its dataset names them.

A linear product (``hubbeam.linear.datasets``) is computed over a :class:`PlantAxis`: the plants and
the coordinate that names them in the dataset, with the dataset's attributes.

* :func:`tip_mass_axis`: the paper's grid, point masses at the beam's tip (kg; 0 for none) on the
  configuration's beam, modes, quadrature and ``linear.damping``, named by a ``tip_mass``
  coordinate;
* :func:`plant_axis`: one plant of a study (the arm as its cases run it: tip body, root spring,
  drive, damping), named by a ``plant`` coordinate, what it holds in the attributes.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from hubbeam.configuration.settings import damping_settings
from hubbeam.model.beam import beam_attributes
from hubbeam.model.damping import damping_to_dict
from hubbeam.model.matrices import MODE_NORMALISATION
from hubbeam.model.parameters import TipMass
from hubbeam.model.plant import Plant


class PlantAxis(NamedTuple):
    """The plants of a linear product (module docstring): the coordinate's ``name``, ``values``
    and ``attrs``, the ``plants`` in its order and the dataset's ``attributes`` besides its title."""

    name: str
    values: tuple
    attrs: dict
    plants: tuple[Plant, ...]
    attributes: dict

    @property
    def beam(self):
        return self.plants[0].beam

    @property
    def n_modes(self) -> int:
        return self.plants[0].modes

    @property
    def root_spring(self) -> bool:
        """Whether a plant of the axis has a compliant root (its hub angle is a coordinate more)."""
        return any(plant.root_spring is not None for plant in self.plants)

    def coordinate(self) -> tuple:
        """The dataset coordinate: ``(name, values, attrs)``."""
        values = np.asarray(self.values, float) if self.name == "tip_mass" else list(self.values)
        return self.name, values, self.attrs


def tip_mass_axis(beam, tip_masses, n_modes: int, n_quad: int = 64, damping=None) -> PlantAxis:
    """The paper's grid of point masses at the tip of ``beam`` (module docstring), each checked
    (a non-empty list of masses >= 0 kg; a damping record or its mapping, or None)."""
    masses = np.atleast_1d(np.asarray(tip_masses, dtype=float))
    if masses.ndim != 1 or masses.size == 0 or not np.all(np.isfinite(masses) & (masses >= 0.0)):
        raise ValueError(f"tip_masses = {tip_masses!r}; allowed: a non-empty list of masses >= 0 kg")
    damping = damping_settings(damping)
    plants = tuple(Plant(beam=beam, modes=int(n_modes), quadrature_points=int(n_quad),
                         tip=TipMass(mass=float(m), position=float(beam.L)), damping=damping) for m in masses)
    attributes = {"n_modes": int(n_modes), "n_quad_requested": int(n_quad), "mode_normalisation": MODE_NORMALISATION,
                  "tip_position_m": float(beam.L), "damping": json.dumps(damping_to_dict(damping), sort_keys=True)}
    return PlantAxis("tip_mass", tuple(float(m) for m in masses),
                     {"units": "kg", "long_name": "tip mass m_t at the beam tip"}, plants,
                     attributes | beam_attributes(beam))


def plant_axis(plant: Plant) -> PlantAxis:
    """One plant of a study (module docstring), named by its ``name``."""
    described = plant.describe()
    attributes = {"n_modes": plant.modes, "n_quad_requested": plant.quadrature_points,
                  "mode_normalisation": MODE_NORMALISATION, "plant": plant.name,
                  "tip_position_m": plant.tip.position, "damping": json.dumps(described["damping"], sort_keys=True),
                  "plant_config": json.dumps(described, sort_keys=True)}
    return PlantAxis("plant", (plant.name,), {"long_name": "plant: the arm as its cases run it (hubbeam.model.plant)"},
                     (plant,), attributes | beam_attributes(plant.beam))


def axis_of(plants: Sequence[Plant] | PlantAxis) -> PlantAxis:
    """``plants`` as an axis: a :class:`PlantAxis` as it is, a single plant as :func:`plant_axis`."""
    if isinstance(plants, PlantAxis):
        return plants
    if isinstance(plants, Plant):
        return plant_axis(plants)
    raise ValueError(f"plants = {plants!r}; allowed: a PlantAxis (tip_mass_axis, plant_axis) or a Plant")
