"""A plant's linear models and frequencies: the one route from a :class:`~hubbeam.model.plant.Plant`
to what the eigen-analysis, the linear products, their exports and ``hubbeam.api`` give.

* :func:`plant_linear`: the linear model of a model of the plant about a steady spin, with the
  input the rig drives: the drive's voltage on a free hub with a drive (``hubbeam.linear.voltage``,
  the back-EMF's damping on the hub), the hub torque on a free hub without one, the hub's angular
  acceleration with the hub held (``hub="prescribed"``); its root spring, tip body and damping
  always (``hubbeam.linear.statespace``);
* :func:`plant_frequencies`: its natural frequencies with the hub held, at rest (Hz), as a frequency
  equation gives them (``hubbeam.model.eigen.natural_frequencies``);
* :func:`plant_critical_speed`: where the hub-held stiffness of a model's linearisation stops being
  positive definite (``hubbeam.model.eigen.critical_speed_of``).
"""

from __future__ import annotations

import math

import numpy as np

from hubbeam.linear.statespace import LinearModel, linear_model
from hubbeam.linear.voltage import voltage_model
from hubbeam.model.damping import damping_matrices
from hubbeam.model.eigen import critical_speed_of, natural_frequencies
from hubbeam.model.models import model as model_traits
from hubbeam.model.plant import Plant, plant_matrices

#: the hub conditions of a plant's linear products: name -> (the linear model's hub, through its drive)
HUB_CONDITIONS = {"held": ("prescribed", False), "free": ("free", False), "driven": ("free", True)}


def hub_conditions(plants) -> tuple[str, ...]:
    """The hub conditions of the linear products of ``plants``: held and free, and driven (the free
    hub through the drive, its input the voltage) when one of them has a drive."""
    return ("held", "free") + (("driven",) if any(plant.drive is not None for plant in plants) else ())


def plant_damping(plant: Plant, sm):
    """The damping matrices of ``plant`` on its matrices ``sm`` (None: undamped)."""
    return None if plant.damping is None else damping_matrices(plant.damping, sm)


def plant_linear(plant: Plant, model: str, speed: float = 0.0, hub: str = "free", outputs=None,
                 through_drive: bool = True, sm=None) -> LinearModel:
    """The linear model of ``model`` for ``plant`` about the steady spin at ``speed`` (rad s-1; module
    docstring): ``hub`` ``"free"`` or ``"prescribed"``; a free hub with a drive takes the voltage
    unless ``through_drive`` is false (the hub torque, without the drive's damping); ``outputs`` as
    :func:`hubbeam.linear.statespace.linear_model`; ``sm`` the plant's matrices when they are at
    hand (:func:`hubbeam.model.plant.plant_matrices`)."""
    sm = plant_matrices(plant) if sm is None else sm
    damping = plant_damping(plant, sm)
    if hub == "free" and through_drive and plant.drive is not None:
        return voltage_model(plant.beam, sm, model, plant.drive, speed, damping, outputs, plant.root_spring)
    return linear_model(plant.beam, sm, model, speed, hub, damping, outputs, plant.root_spring)


def reaches(plant: Plant, condition: str, speed: float) -> bool:
    """Whether the hub condition ``condition`` of ``plant`` exists at ``speed``: a driven hub only
    where the drive can hold the steady spin (its voltage within the amplifier's limit)."""
    if condition != "driven" or plant.drive is None:
        return condition != "driven"
    return abs(plant.drive.voltage(0.0, float(speed))) <= plant.drive.voltage_limit


def condition_model(plant: Plant, model: str, speed: float, condition: str, outputs=None, sm=None) -> LinearModel:
    """:func:`plant_linear` for a hub condition of :data:`HUB_CONDITIONS` (held, free, driven)."""
    hub, through_drive = HUB_CONDITIONS[condition]
    return plant_linear(plant, model, speed, hub, outputs, through_drive, sm)


def plant_frequencies(plant: Plant, sm=None) -> np.ndarray:
    """The natural frequencies (Hz, ascending) of ``plant`` with the hub held, at rest."""
    sm = plant_matrices(plant) if sm is None else sm
    return natural_frequencies(sm, plant.root_spring) / (2.0 * math.pi)


def plant_critical_speed(plant: Plant, model: str, search_max: float, sm=None) -> float:
    """The critical speed (rad s-1) of ``model``'s linearisation (TLAM's or FOAM's) of ``plant``
    with the hub held; NaN when none up to ``search_max``."""
    sm = plant_matrices(plant) if sm is None else sm
    return critical_speed_of(sm, model_traits(model).linearisation, search_max, plant.root_spring)


__all__ = ["HUB_CONDITIONS", "condition_model", "reaches", "hub_conditions", "plant_critical_speed", "plant_damping",
           "plant_frequencies", "plant_linear"]
