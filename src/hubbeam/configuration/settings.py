"""The configuration as frozen, typed objects, checked once.

:func:`from_config` turns a validated configuration (:func:`hubbeam.configuration.load.check_schema`)
into :class:`Settings`: the study, the beam (:func:`hubbeam.model.beam.beam_from_config`), the
numerics, the eigen grids, the cases, each :class:`Case` with its defaults filled in and its
maneuver and damping as the records of their kinds (:mod:`hubbeam.model.maneuvers`,
:mod:`hubbeam.model.damping`), and the parameter sweeps, each :class:`Sweep` with its defaults
filled in (run by :mod:`hubbeam.simulation.sweep`). The workflow builds them once, before any job, and hands them to its
jobs; nothing downstream checks them again or turns them back into mappings (``to_dict()`` gives
only the plain mapping a dataset records, ``case_config``).

The Python API also takes the bare mapping of a case and of the integrator settings:
:func:`simulation_settings` checks those by the same path as a configuration file (the schema's
``cases`` and ``numerics`` sections and :mod:`hubbeam.configuration.checks`, every problem in one
:class:`~hubbeam.configuration.load.ConfigError`) and builds the same objects.
"""

from __future__ import annotations

import copy
import dataclasses
import functools
from collections.abc import Mapping
from dataclasses import dataclass, field, fields

import numpy as np

from hubbeam.configuration.load import ConfigError, validate_parts
from hubbeam.configuration.schema import SCHEMA, Problem
from hubbeam.configuration.sections import Control, Grid, Identify, Linear, Reading, Validation
from hubbeam.model.beam import BeamSections, beam_from_config
from hubbeam.model.damping import ModalDamping, RayleighDamping, damping_from_dict, damping_to_dict
from hubbeam.model.drive import DcMotor
from hubbeam.model.frozen import FrozenMap, freeze
from hubbeam.model.limits import MEMORY_BUDGET_MB, SMALL_DEFLECTION_LIMIT
from hubbeam.model.maneuvers import Maneuver, maneuver_from_dict
from hubbeam.model.modes import CLAMPED_FREE
from hubbeam.model.parameters import TipMass, UniformBeam
from hubbeam.model.plant import Plant
from hubbeam.model.root import RootSpring
from hubbeam.model.shapers import ShaperSpec


@dataclass(frozen=True)
class InitialState:
    """The operating point a case starts from (schema ``case.initial``): a steady spin at
    ``hub_speed`` with ``q1`` at its centrifugal stretch, plus the modal coordinates and rates
    given (None: not given, zeros). ``hubbeam.simulation.simulate.initial_state`` builds the state."""

    hub_speed: float | None = None
    q1: tuple[float, ...] | None = None
    q2: tuple[float, ...] | None = None
    q1_dot: tuple[float, ...] | None = None
    q2_dot: tuple[float, ...] | None = None

    @classmethod
    def from_dict(cls, entry: Mapping) -> InitialState:
        return cls(**{key: float(value) if key == "hub_speed" else tuple(map(float, value))
                      for key, value in entry.items()})

    def modal(self, key: str, modes: int) -> np.ndarray:
        """The modal values ``key`` (``q1``, ``q2``, ``q1_dot``, ``q2_dot``) for ``modes`` modes:
        zeros where not given, the given values padded with zeros for a case rerun with more modes."""
        given = getattr(self, key) or ()
        return np.concatenate([np.asarray(given, dtype=float), np.zeros(modes - len(given))])

    def to_dict(self) -> dict:
        """The keys given, as written in a configuration."""
        return {item.name: list(value) if isinstance(value, tuple) else value
                for item in fields(self) if (value := getattr(self, item.name)) is not None}


@dataclass(frozen=True)
class Case:
    """A resolved case (schema ``cases.<name>``; defaults filled in: ``modes`` from
    ``numerics.modes``, no tip mass is mass 0 at the tip, a tip mass without position sits at the
    tip). ``name`` is None for a case given to the API without one."""

    name: str | None
    model: str
    maneuver: Maneuver
    t_end: float
    modes: int
    tip_mass: TipMass
    damping: ModalDamping | RayleighDamping | None = None
    #: the operating point at t = 0 (None: rest)
    initial: InitialState | None = None
    #: the hub's DC drive (None: an ideal torque actuator)
    drive: DcMotor | None = None
    #: the command shaper (None: unshaped)
    shaper: ShaperSpec | None = None
    #: a compliant root between the hub and the beam (None: clamped to the hub)
    root_spring: RootSpring | None = None
    #: the assumed transverse functions (``hubbeam.model.modes``): the clamped-free beam's modes or
    #: the modes of the beam loaded by the tip body (``"tip_body"``)
    transverse_functions: str = CLAMPED_FREE

    @property
    def label(self) -> str:
        """The case's name in messages."""
        return UNNAMED if self.name is None else self.name

    def with_modes(self, modes: int) -> Case:
        """The case with ``modes`` modes (a convergence rerun; added initial values are zero)."""
        return dataclasses.replace(self, modes=modes)

    def to_dict(self) -> dict:
        """The resolved case as a plain mapping, as a dataset records it (``case_config``)."""
        settings = {} if self.name is None else {"name": self.name}
        settings |= {"model": self.model, "maneuver": self.maneuver.to_dict(),
                     "t_end": self.t_end, "modes": self.modes,
                     "tip_mass": tip_mass_to_dict(self.tip_mass)}
        if self.damping is not None:
            settings["damping"] = damping_to_dict(self.damping)
        if self.initial is not None:
            settings["initial"] = self.initial.to_dict()
        if self.drive is not None:
            settings["drive"] = self.drive.to_dict()
        if self.shaper is not None:
            settings["shaper"] = self.shaper.to_dict()
        if self.root_spring is not None:
            settings["root_spring"] = self.root_spring.to_dict()
        if self.transverse_functions != CLAMPED_FREE:
            settings["transverse_functions"] = self.transverse_functions
        return settings


def tip_mass_to_dict(tip: TipMass) -> dict:
    """``{mass, position}`` of a tip mass as a configuration writes it, with ``inertia`` and
    ``offset`` for a body (left out for a point mass, which a dataset records as before)."""
    plain = {"mass": tip.mass, "position": tip.position}
    return plain if tip.is_point else plain | {"inertia": tip.inertia, "offset": tip.offset}


@dataclass(frozen=True)
class ConvergenceCheck:
    """``numerics.convergence_check``: the reruns at tighter tolerances and with more modes."""

    tolerance_factor: float
    extra_modes: int
    threshold_m: float

    def to_dict(self) -> dict:
        return {item.name: getattr(self, item.name) for item in fields(self)}


@dataclass(frozen=True)
class Numerics:
    """Integrator and discretisation settings (schema ``numerics``). ``modes`` and
    ``quadrature_points`` are None in the settings of a simulation that is given its matrices."""

    rtol: float
    atol: float
    output_step: float
    max_steps: int
    step_warning: int
    divergence_limit: float
    small_deflection_limit: float = SMALL_DEFLECTION_LIMIT
    memory_budget_mb: float = MEMORY_BUDGET_MB
    modes: int | None = None
    quadrature_points: int | None = None
    convergence_check: ConvergenceCheck | None = None

    @classmethod
    def from_mapping(cls, numerics: Mapping) -> Numerics:
        given = {item.name: numerics[item.name] for item in fields(cls) if item.name in numerics}
        if "convergence_check" in given:
            given["convergence_check"] = ConvergenceCheck(**given["convergence_check"])
        return cls(**given)

    def to_dict(self) -> dict:
        """The settings as a plain mapping, without the ones not given (None)."""
        plain = {item.name: getattr(self, item.name) for item in fields(self)}
        if self.convergence_check is not None:
            plain["convergence_check"] = self.convergence_check.to_dict()
        return {key: value for key, value in plain.items() if value is not None}

    def simulation(self) -> Numerics:
        """The settings a simulation reads: without the discretisation (the matrices carry it),
        the memory budget and the convergence check (given to each job on its own), so that
        changing any of those reruns no simulation."""
        return dataclasses.replace(self, modes=None, quadrature_points=None, convergence_check=None,
                                   memory_budget_mb=MEMORY_BUDGET_MB)


@dataclass(frozen=True)
class Eigen:
    """The grids of the eigenvalue studies (schema ``eigen``)."""

    speeds: Grid
    positions: Grid
    tip_masses: tuple[float, ...]
    critical_speed_search_max: float
    table2_speed: float | None = None


@dataclass(frozen=True)
class Study:
    """The ``study`` section: a study of its own, not the paper."""

    name: str
    title: str = ""
    description: str = ""
    comparisons: FrozenMap = field(default_factory=FrozenMap)


#: simulations per chunk job of a sweep unless ``sweeps.chunk_size`` or the map's ``chunk_size``
#: says otherwise: about a minute on one core at the default sweep numerics (docs/performance.md)
DEFAULT_CHUNK_SIZE = 32_000


@dataclass(frozen=True)
class SweepNumerics:
    """The integrator settings of every run of a sweep (schema ``sweeps.numerics``), as given."""

    rtol: float
    atol: float
    output_step: float
    max_steps: int


@dataclass(frozen=True)
class Sweep:
    """A parameter sweep (schema ``sweeps.maps.<name>``) with its defaults filled in: ``modes`` from
    ``numerics.modes``; no tip mass is mass 0 at the tip, a tip mass without position sits at the
    tip (unless a tip parameter is swept); ``chunk_size`` from ``sweeps.chunk_size``, else
    :data:`DEFAULT_CHUNK_SIZE`; ``in_all`` true. The integrator settings are ``sweeps.numerics``;
    the divergence and small-deflection limits and the quadrature come from ``numerics``, the
    critical-speed search from ``eigen``.

    ``maneuver`` holds the kind and the fixed parameters of the maneuver, ``grid`` the swept
    parameters (the map's axes, in their order) with their :class:`Grid`.
    """

    name: str
    models: tuple[str, ...]
    maneuver: FrozenMap
    grid: FrozenMap
    t_after: float
    modes: int
    tip_mass: TipMass
    outputs: tuple[str, ...]
    figure: FrozenMap
    in_all: bool
    chunk_size: int
    numerics: SweepNumerics
    divergence_limit: float
    small_deflection_limit: float
    quadrature_points: int
    critical_speed_search_max: float

    @property
    def axes(self) -> tuple[str, ...]:
        """The swept parameters, in the order of the map's axes."""
        return tuple(self.grid)

    def to_dict(self) -> dict:
        """The sweep as a plain mapping (JSON-serialisable), as its datasets record it (``sweep_config``)."""
        return {
            "name": self.name, "models": list(self.models), "maneuver": dict(self.maneuver),
            "axes": list(self.axes),
            "grid": {key: {"start": grid.start, "stop": grid.stop, "num": grid.num} for key, grid in self.grid.items()},
            "t_after": self.t_after, "modes": self.modes,
            "tip_mass": {"mass": self.tip_mass.mass, "position": self.tip_mass.position},
            "outputs": list(self.outputs), "figure": dict(self.figure), "in_all": self.in_all,
            "chunk_size": self.chunk_size,
            "numerics": {item.name: getattr(self.numerics, item.name) for item in fields(self.numerics)},
            "divergence_limit": self.divergence_limit, "small_deflection_limit": self.small_deflection_limit,
            "quadrature_points": self.quadrature_points, "critical_speed_search_max": self.critical_speed_search_max,
        }


@dataclass(frozen=True)
class Settings:
    """A whole configuration, one record per section: ``study`` is None for the paper; ``sweeps``
    by name (none without a ``sweeps`` section); ``linear`` with its defaults filled in; the
    optional ``validation``, ``control`` and ``identify`` sections (None when absent,
    :mod:`hubbeam.configuration.sections`); the ``readings`` by name; the product sets asked for."""

    beam: UniformBeam | BeamSections
    numerics: Numerics
    eigen: Eigen
    cases: FrozenMap
    study: Study | None = None
    sweeps: FrozenMap = field(default_factory=FrozenMap)
    linear: Linear | None = None
    #: the independent validation (None without a ``validation`` section)
    validation: Validation | None = None
    #: the analyses of the sampled controllers (None without a ``control`` section)
    control: Control | None = None
    #: the alternative readings of the paper by name (:class:`~hubbeam.configuration.sections.Reading`)
    readings: FrozenMap = field(default_factory=FrozenMap)
    #: the product sets asked for (``products``)
    products: tuple[str, ...] = ()
    #: the calibration to a rig's experiments (None without an ``identify`` section)
    identify: Identify | None = None

    def case(self, name: str) -> Case:
        """The case ``name``; a :class:`ConfigError` names the defined ones."""
        if name not in self.cases:
            raise ConfigError([Problem(f"cases.{name}", f"unknown case; defined: {', '.join(self.cases)}")])
        return self.cases[name]

    @functools.cached_property
    def plant_cases(self) -> FrozenMap:
        """The plants of the cases (:func:`case_plant`) by name, each with the names of the cases
        that run it: ``{name: (plant, cases)}``. A plant is named after the first case (by name)
        that runs it; cases that run the same arm (equal plants) share one."""
        found: list[tuple[Plant, list[str]]] = []
        for name, case in self.cases.items():
            plant = case_plant(case, self.beam, self.numerics)
            entry = next((entry for entry in found if entry[0] == plant), None)
            if entry is None:
                found.append((dataclasses.replace(plant, name=name), [name]))
            else:
                entry[1].append(name)
        return FrozenMap({plant.name: (plant, tuple(cases)) for plant, cases in found})

    @property
    def plants(self) -> FrozenMap:
        """The plants of the cases by name (:attr:`plant_cases`)."""
        return FrozenMap({name: plant for name, (plant, _) in self.plant_cases.items()})

    def plant_of(self, case: str) -> Plant:
        """The plant case ``case`` runs, with its name."""
        self.case(case)
        return next(plant for plant, cases in self.plant_cases.values() if case in cases)


def case_plant(case: Case, beam, numerics: Numerics) -> Plant:
    """The plant ``case`` runs (:class:`hubbeam.model.plant.Plant`): ``beam`` with the case's modes,
    transverse functions, tip body, root spring, drive and damping, and the Gauss nodes of
    ``numerics``; unnamed."""
    return Plant(beam=beam, modes=case.modes, quadrature_points=numerics.quadrature_points, tip=case.tip_mass,
                 functions=case.transverse_functions, root_spring=case.root_spring, drive=case.drive,
                 damping=case.damping)


def from_config(cfg: Mapping) -> Settings:
    """The objects of a validated configuration (:func:`hubbeam.configuration.load.check_schema`)."""
    eigen = dict(cfg["eigen"])
    study = cfg.get("study")
    return Settings(
        beam=beam_from_config(cfg["beam"]), numerics=Numerics.from_mapping(cfg["numerics"]),
        eigen=Eigen(**{**eigen, "speeds": Grid(**eigen["speeds"]), "positions": Grid(**eigen["positions"]),
                       "tip_masses": tuple(eigen["tip_masses"])}),
        cases=FrozenMap({name: case_from_config(cfg, name) for name in sorted(cfg["cases"])}),
        study=None if study is None else Study(**{**study, "comparisons": freeze(study.get("comparisons", {}))}),
        sweeps=FrozenMap({name: sweep_from_config(cfg, name)
                          for name in sorted(cfg.get("sweeps", {}).get("maps", {}))}),
        linear=Linear.from_dict(cfg["linear"]) if "linear" in cfg else None,
        validation=None if "validation" not in cfg else Validation.from_dict(cfg["validation"]),
        control=None if "control" not in cfg else Control.from_dict(cfg["control"]),
        readings=FrozenMap({name: Reading.from_dict(name, entry) for name, entry in cfg.get("readings", {}).items()}),
        products=tuple(cfg.get("products", ())),
        identify=None if "identify" not in cfg else Identify.from_dict(cfg["identify"]),
    )


def sweep_from_config(cfg: Mapping, name: str) -> Sweep:
    """The :class:`Sweep` ``name`` of a validated configuration, its defaults filled in (class docstring)."""
    sweeps, numerics = cfg["sweeps"], cfg["numerics"]
    spec = sweeps["maps"][name]
    tip = spec.get("tip_mass", {})
    return Sweep(
        name=name, models=tuple(spec["models"]),
        maneuver=FrozenMap({key: value if key == "kind" else float(value) for key, value in spec["maneuver"].items()}),
        grid=FrozenMap({key: Grid(float(grid["start"]), float(grid["stop"]), int(grid["num"]))
                        for key, grid in spec["grid"].items()}),
        t_after=float(spec["t_after"]), modes=int(spec.get("modes", numerics["modes"])),
        tip_mass=TipMass(float(tip.get("mass", 0.0)), float(tip.get("position", cfg["beam"]["length"]))),
        outputs=tuple(spec["outputs"]), figure=FrozenMap(spec["figure"]), in_all=bool(spec.get("in_all", True)),
        chunk_size=int(spec.get("chunk_size", sweeps.get("chunk_size", DEFAULT_CHUNK_SIZE))),
        numerics=SweepNumerics(**{item.name: sweeps["numerics"][item.name] for item in fields(SweepNumerics)}),
        divergence_limit=float(numerics["divergence_limit"]),
        small_deflection_limit=float(numerics.get("small_deflection_limit", SMALL_DEFLECTION_LIMIT)),
        quadrature_points=int(numerics["quadrature_points"]),
        critical_speed_search_max=float(cfg["eigen"]["critical_speed_search_max"]))


def case_from_config(cfg: Mapping, name: str) -> Case:
    """The :class:`Case` ``name`` of a validated configuration, its defaults filled in (class
    docstring); a ``name`` of :data:`UNNAMED` gives a case without a name."""
    case = cfg["cases"][name]
    tip = case.get("tip_mass", {})
    return Case(name=None if name == UNNAMED else name, model=case["model"],
                maneuver=maneuver_from_dict(case["maneuver"]), t_end=float(case["t_end"]),
                modes=int(case.get("modes", cfg["numerics"]["modes"])),
                tip_mass=TipMass(float(tip.get("mass", 0.0)), float(tip.get("position", cfg["beam"]["length"])),
                                 float(tip.get("inertia", 0.0)), float(tip.get("offset", 0.0))),
                damping=damping_from_dict(case.get("damping")),
                initial=InitialState.from_dict(case["initial"]) if "initial" in case else None,
                drive=DcMotor(**case["drive"]) if "drive" in case else None,
                shaper=ShaperSpec.from_dict(case["shaper"]) if "shaper" in case else None,
                root_spring=RootSpring(**case["root_spring"]) if "root_spring" in case else None,
                transverse_functions=case.get("transverse_functions", CLAMPED_FREE))


#: the name a case given without one has in messages
UNNAMED = "<unnamed>"
#: the schema of a bare case and the integrator settings of a simulation (the API's mappings):
#: the configuration's sections, the case with its ``modes`` (resolved), ``numerics`` as in a
#: configuration (a key left out takes its default, ``hubbeam.configuration.defaults``)
SIMULATION_SCHEMA = {
    "type": "object",
    "properties": {
        "cases": {"type": "object", "additionalProperties": {
            "$ref": "#/$defs/case", "required": [*SCHEMA["$defs"]["case"]["required"], "modes"]}},
        "numerics": SCHEMA["properties"]["numerics"],
    },
    "$defs": SCHEMA["$defs"],
}


def simulation_settings(case: Case | Mapping, numerics: Numerics | Mapping, length: float,
                        convergence_check: ConvergenceCheck | Mapping | None = None) -> tuple[Case, Numerics]:
    """The arguments of a simulation as objects: ``case``, ``numerics`` with ``convergence_check``
    (the one of the arguments: None runs no check, whatever ``numerics`` holds). Objects are taken
    as they are; mappings (a resolved case, the integrator settings, the check) are checked in one
    pass (``ConfigError``) and converted by the builders of :func:`from_config`. ``length`` is the
    beam's, for the tip-mass position."""
    if isinstance(case, Case) and isinstance(numerics, Numerics) and not isinstance(convergence_check, Mapping):
        return case, dataclasses.replace(numerics, convergence_check=convergence_check)
    case = case.to_dict() if isinstance(case, Case) else dict(case)
    numerics = numerics.to_dict() if isinstance(numerics, Numerics) else dict(numerics)
    numerics.pop("convergence_check", None)
    if convergence_check is not None:
        numerics["convergence_check"] = (convergence_check.to_dict() if isinstance(convergence_check, ConvergenceCheck)
                                         else dict(convergence_check))
    where = case.pop("name", None) or UNNAMED
    cfg = copy.deepcopy({"beam": {"length": length}, "numerics": numerics, "cases": {where: case}})
    validate_parts(cfg, SIMULATION_SCHEMA)
    return case_from_config(cfg, where), Numerics.from_mapping(cfg["numerics"])


#: the schema of a bare damping mapping (the API's), the configuration's ``damping`` section
DAMPING_SCHEMA = {"type": "object", "properties": {"damping": {"$ref": "#/$defs/damping"}}, "$defs": SCHEMA["$defs"]}


def damping_settings(damping: ModalDamping | RayleighDamping | Mapping | None) -> ModalDamping | RayleighDamping | None:
    """A damping as a record (None: no damping). A record is taken as it is; a mapping is checked
    in the one pass of the configuration (``ConfigError`` naming ``damping.<key>``) and converted."""
    if damping is None or isinstance(damping, ModalDamping | RayleighDamping):
        return damping
    cfg = {"damping": copy.deepcopy(dict(damping))}
    validate_parts(cfg, DAMPING_SCHEMA)
    return damping_from_dict(cfg["damping"])
