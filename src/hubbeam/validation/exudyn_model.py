"""Independent reference: the hub-beam in Exudyn with geometrically exact 2D ANCF cable elements.

Exudyn (https://github.com/jgerstmayr/EXUDYN, an optional dependency: ``pip install -e
.[validation]``) models the beam in the inertial frame with ``ObjectANCFCable2D`` elements: every
node carries a position and a slope vector, the axial strain is ``|r'| - 1`` and the curvature the
exact one, so large rotations, stretch and foreshortening come out of the kinematics instead of
being truncated as in the assumed-mode models. Nothing of hubbeam's discretisation is shared.

Model (:func:`build_model`)
    * hub: a 2D rigid body whose position is held at the origin and whose rotation coordinate is
      driven by a ``CoordinateConstraint`` with ``offsetUserFunction = theta(t)`` of Eq. (43)
      (corrected, note 1; the project's kernel ``hubbeam.core.maneuver.hub_motion``);
    * clamp: a ``GenericJoint`` between a rigid marker at ``(rA, 0)`` on the hub and a
      ``MarkerNodeRigid`` on the first cable node, locking both translations and the rotation
      about the axis, so the root position and the root slope follow the hub;
    * beam: ``elements`` equal cable elements from ``rA`` to ``rA + L``, ``EA``, ``EI``,
      ``rho A`` of Table 1, no damping, full-order Gauss integration;
    * tip mass (optional): a point mass node tied to the position of the node at ``rA + l``
      (``l`` must be a node position) by two coordinate constraints.

Time integration: generalised-alpha (index-3 constraints need a spectral radius below 1) with a
fixed step (adaptive step reduction off: a failed Newton iteration is an error, never a silently
smaller step). Newton's convergence test uses the *increment* (``residualMode = 1``): the stiff
axial direction (EA / (rho A L^2) ~ 3e5 s^-2 here) leaves a round-off residual in the equations of
motion that a residual-based test at tight tolerance cannot meet, and the solver then cuts the
step size towards its minimum (measured: 1e-6 s within the first 0.13 s, see docs/validation.md).

Output (:func:`spin_up`): the tip's transverse deflection in the hub frame, ``v = -sin(theta) X +
cos(theta) Y`` (the projection of the tip position onto the rotating y-axis; the clamp lies on
the rotating x-axis), on the uniform time grid of ``output_step``.
"""

from __future__ import annotations

import importlib.util
import math
import time
from dataclasses import asdict, dataclass

import numpy as np
import xarray as xr

from hubbeam.configuration.checks import is_multiple
from hubbeam.core.maneuver import hub_motion
from hubbeam.model.beam import BeamSections

INSTALL_HINT = "pip install -e .[validation]"


class ExudynNotInstalled(ImportError):
    """Exudyn, the optional dependency of the validation, is not importable."""


def exudyn_available() -> bool:
    """True if the optional dependency exudyn can be imported (without importing it)."""
    return importlib.util.find_spec("exudyn") is not None


def require_exudyn():
    """Import and return the ``exudyn`` module, or raise :class:`ExudynNotInstalled`."""
    try:
        import exudyn
    except ImportError as error:
        raise ExudynNotInstalled(
            "the Exudyn validation needs the optional dependency exudyn, which is not "
            f"installed: install the extra with `{INSTALL_HINT}` ({error})"
        ) from error
    return exudyn


@dataclass(frozen=True)
class ExudynNumerics:
    """Discretisation and solver settings of the Exudyn reference.

    ``elements`` ANCF cable elements; ``time_step`` fixed step (s); ``spectral_radius`` of the
    generalised-alpha method (< 1); ``newton_tolerance`` on the Newton increment (relative and
    absolute, as Exudyn requires for ``residualMode = 1``); ``output_step`` (s), a multiple of
    ``time_step``.
    """

    elements: int = 16
    time_step: float = 1.0e-3
    spectral_radius: float = 0.9
    newton_tolerance: float = 1.0e-10
    output_step: float = 0.01

    def __post_init__(self):
        problems = []
        if not (isinstance(self.elements, int) and self.elements >= 1):
            problems.append(f"elements = {self.elements!r}: expected an integer >= 1")
        for name in ("time_step", "newton_tolerance", "output_step"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
                problems.append(f"{name} = {value!r}: expected a finite number > 0")
        if not (isinstance(self.spectral_radius, (int, float))
                and 0.0 <= self.spectral_radius < 1.0):
            problems.append(f"spectral_radius = {self.spectral_radius!r}: expected 0 <= value < 1 "
                            "(index-3 constraints of the generalised-alpha method)")
        if not problems and not is_multiple(self.output_step, self.time_step):
            problems.append(f"output_step = {self.output_step!r}: expected an integer multiple "
                            f"of time_step = {self.time_step!r}")
        if problems:
            raise ValueError("invalid Exudyn numerics: " + "; ".join(problems))


@dataclass(frozen=True)
class HubBeamModel:
    """An assembled Exudyn system of the hub-beam and the items needed to read it.

    The system container must stay alive as long as ``mbs`` is used.
    """

    system_container: object
    mbs: object
    hub_node: object
    cable_nodes: list
    tip_sensor: object
    hub_sensor: object


def build_model(params, tip=None, maneuver=None, elements: int = 16) -> HubBeamModel:
    """Assemble the Exudyn hub-beam (module docstring).

    ``params`` :class:`hubbeam.model.parameters.BeamParameters`; ``tip`` :class:`TipMass` or None;
    ``maneuver`` ``(wf, tf)`` of Eq. (43), or None for a hub held at ``theta = 0``.
    """
    if isinstance(params, BeamSections):
        raise ValueError("beam.sections: the Exudyn reference models a uniform beam (one "
                         "ObjectANCFCable2D cross-section); allowed with a `validation` section: "
                         "a uniform beam (its factors or its products)")
    exu = require_exudyn()
    from exudyn.itemInterface import (
        CoordinateConstraint,
        GenericJoint,
        MarkerBodyRigid,
        MarkerNodeCoordinate,
        MarkerNodeRigid,
        MassPoint2D,
        NodePoint2D,
        NodePoint2DSlope1,
        NodePointGround,
        NodeRigidBody2D,
        ObjectANCFCable2D,
        ObjectGround,
        ObjectRigidBody2D,
        SensorNode,
    )

    length = params.L / elements
    tip_node_index = None
    if tip is not None and tip.mass > 0.0:
        if not is_multiple(tip.position, length):
            raise ValueError(f"tip_mass.position = {tip.position!r}: the Exudyn model needs the "
                             f"tip mass at a node, a multiple of L / elements = {length!r} m")
        tip_node_index = int(round(tip.position / length))

    system_container = exu.SystemContainer()
    mbs = system_container.AddSystem()
    mbs.AddObject(ObjectGround())
    ground = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mbs.AddNode(NodePointGround()),
                                                coordinate=0))

    # hub: a rigid body at the origin whose angle is prescribed (the mass does not matter)
    hub_node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0.0, 0.0, 0.0]))
    hub = mbs.AddObject(ObjectRigidBody2D(mass=1.0, inertia=1.0, nodeNumber=hub_node))
    for coordinate in (0, 1):
        mbs.AddObject(CoordinateConstraint(markerNumbers=[
            ground, mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=hub_node,
                                                       coordinate=coordinate))]))
    angle_constraint = {}
    if maneuver is not None:
        motion_parameters = np.array([float(maneuver[0]), float(maneuver[1])])

        def hub_angle(mbs, t, item, offset):  # noqa: ARG001 (Exudyn's signature)
            return hub_motion(t, motion_parameters)[0]

        angle_constraint["offsetUserFunction"] = hub_angle
    mbs.AddObject(CoordinateConstraint(markerNumbers=[
        ground, mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=hub_node, coordinate=2))],
        **angle_constraint))

    # beam: straight cable elements along the hub's x-axis from the clamp at rA
    cable_nodes = [mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[params.rA + k * length,
                                                                       0.0, 1.0, 0.0]))
                   for k in range(elements + 1)]
    for k in range(elements):
        mbs.AddObject(ObjectANCFCable2D(
            nodeNumbers=[cable_nodes[k], cable_nodes[k + 1]], length=length,
            massPerLength=params.rhoA, bendingStiffness=params.EI,
            axialStiffness=params.EA, useReducedOrderIntegration=0))

    # clamp: root position and slope direction locked to the hub
    mbs.AddObject(GenericJoint(
        markerNumbers=[mbs.AddMarker(MarkerNodeRigid(nodeNumber=cable_nodes[0])),
                       mbs.AddMarker(MarkerBodyRigid(bodyNumber=hub,
                                                     localPosition=[params.rA, 0.0, 0.0]))],
        constrainedAxes=[1, 1, 0, 0, 0, 1]))

    if tip_node_index is not None:
        mass_node = mbs.AddNode(NodePoint2D(referenceCoordinates=[params.rA + tip.position, 0.0]))
        mbs.AddObject(MassPoint2D(mass=tip.mass, nodeNumber=mass_node))
        for coordinate in (0, 1):
            mbs.AddObject(CoordinateConstraint(markerNumbers=[
                mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=cable_nodes[tip_node_index],
                                                   coordinate=coordinate)),
                mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mass_node,
                                                   coordinate=coordinate))]))

    tip_sensor = mbs.AddSensor(SensorNode(nodeNumber=cable_nodes[-1], storeInternal=True,
                                          writeToFile=False,
                                          outputVariableType=exu.OutputVariableType.Position))
    hub_sensor = mbs.AddSensor(SensorNode(nodeNumber=hub_node, storeInternal=True,
                                          writeToFile=False,
                                          outputVariableType=exu.OutputVariableType.Coordinates))
    mbs.Assemble()
    return HubBeamModel(system_container, mbs, hub_node, cable_nodes, tip_sensor, hub_sensor)


def _simulation_settings(exu, t_end, numerics):
    settings = exu.SimulationSettings()
    integration = settings.timeIntegration
    integration.endTime = float(t_end)
    integration.numberOfSteps = int(round(t_end / numerics.time_step))
    integration.adaptiveStep = False
    integration.verboseMode = 0
    integration.generalizedAlpha.spectralRadius = numerics.spectral_radius
    integration.generalizedAlpha.computeInitialAccelerations = True
    newton = integration.newton
    newton.residualMode = 1  # increment-based convergence test (module docstring)
    newton.relativeTolerance = numerics.newton_tolerance
    newton.absoluteTolerance = numerics.newton_tolerance
    newton.useModifiedNewton = False
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = numerics.output_step
    settings.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    return settings


def spin_up(params, tip, wf: float, tf: float, t_end: float,
            numerics: ExudynNumerics = ExudynNumerics()) -> xr.Dataset:
    """Simulate the spin-up of Eq. (43) to ``wf`` (rad s-1) in ``tf`` (s) until ``t_end`` (s).

    Returns a dataset on the uniform grid ``0, output_step, ..., t_end`` with ``tip_transverse``
    (m, the tip's deflection along the rotating y-axis), ``tip_axial`` (m, its displacement along
    the rotating x-axis from ``rA + L``, stretch plus foreshortening), ``theta`` (rad) and the
    solver's statistics as attributes. Raises ``RuntimeError`` if Exudyn's solver fails.
    """
    exu = require_exudyn()
    if not (math.isfinite(t_end) and t_end > 0 and is_multiple(t_end, numerics.output_step)):
        raise ValueError(f"t_end = {t_end!r}: expected a positive multiple of output_step = "
                         f"{numerics.output_step!r} s")
    model = build_model(params, tip, (wf, tf), numerics.elements)
    start = time.perf_counter()
    success = model.mbs.SolveDynamic(_simulation_settings(exu, t_end, numerics),
                                     solverType=exu.DynamicSolverType.GeneralizedAlpha)
    cpu_time = time.perf_counter() - start
    if not success:
        raise RuntimeError(f"Exudyn's generalised-alpha solver failed (wf = {wf}, elements = "
                           f"{numerics.elements}, time step = {numerics.time_step} s)")
    iterations = model.mbs.sys["dynamicSolver"].it
    tip_data = model.mbs.GetSensorStoredData(model.tip_sensor)
    hub_data = model.mbs.GetSensorStoredData(model.hub_sensor)
    grid = np.round(np.arange(int(round(t_end / numerics.output_step)) + 1)
                    * numerics.output_step, 12)
    if tip_data.shape[0] != grid.size or np.max(np.abs(tip_data[:, 0] - grid)) > 1e-6:
        raise RuntimeError("Exudyn's sensor times do not match the uniform output grid "
                           f"({tip_data.shape[0]} samples for {grid.size} grid points)")
    theta = hub_data[:, 3]
    x, y = tip_data[:, 1], tip_data[:, 2]
    transverse = -np.sin(theta) * x + np.cos(theta) * y
    axial = np.cos(theta) * x + np.sin(theta) * y - (params.rA + params.L)
    mass = 0.0 if tip is None else float(tip.mass)
    return xr.Dataset(
        {
            "tip_transverse": ("time", transverse, {
                "units": "m", "long_name": "tip deflection along the rotating y-axis (Exudyn "
                                           "ANCF reference)"}),
            "tip_axial": ("time", axial, {
                "units": "m", "long_name": "tip displacement along the rotating x-axis from "
                                           "rA + L (stretch plus foreshortening)"}),
            "theta": ("time", theta, {"units": "rad", "long_name": "hub angle (prescribed)"}),
        },
        coords={"time": ("time", grid, {"units": "s", "long_name": "time"})},
        attrs={
            "model": "Exudyn ObjectANCFCable2D (geometrically exact 2D cable), prescribed hub",
            "maneuver": f'{{"kind": "prescribed", "wf": {float(wf)}, "tf": {float(tf)}}}',
            "tip_mass_kg": mass,
            "tip_position_m": float(params.L if tip is None else tip.position),
            "t_end": float(t_end),
            **{f"exudyn_{name}": value for name, value in asdict(numerics).items()},
            "exudyn_solver": "GeneralizedAlpha, fixed step, Newton residualMode=1 (increment)",
            "exudyn_newton_iterations": int(iterations.newtonStepsCount),
            "exudyn_steps": int(iterations.currentStepIndex) - 1,
            "exudyn_cpu_time_s": float(cpu_time),
            "exudyn_version": str(exu.__version__),
            **{f"param_{key}": float(getattr(params, key))
               for key in ("L", "rho", "A", "E", "I", "Jh", "rA")},
        },
    )


def natural_frequencies(params, tip=None, elements: int = 16, count: int = 3) -> np.ndarray:
    """Lowest ``count`` circular natural frequencies (rad s-1) of the non-rotating clamped beam.

    Exudyn's ``ComputeODE2Eigenvalues`` projects mass and stiffness matrices on the null space of
    the constraint Jacobian (hub fixed, clamp, tip-mass ties) at the undeformed state; every
    remaining coordinate is elastic (no rigid-body mode), so the spectrum holds bending and axial
    modes only, ascending.
    """
    model = build_model(params, tip, None, elements)
    omega2, _ = model.mbs.ComputeODE2Eigenvalues(ignoreAlgebraicEquations=False,
                                                 useAbsoluteValues=True)
    return np.sqrt(np.sort(np.asarray(omega2, dtype=float))[:count])
