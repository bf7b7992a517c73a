"""The configuration as frozen, typed objects, checked once.

:func:`from_config` turns a validated configuration (:func:`hubbeam.configuration.load.validate_config`) into
:class:`Settings`: the study, the beam (:func:`hubbeam.model.beam.beam_from_config`), the numerics, the
eigen grids and the resolved cases. The Python API (:func:`hubbeam.simulation.simulate.simulate`) takes a
:class:`Case` and :class:`Numerics`, or the bare mappings of a case and of the integrator settings,
which :func:`simulation_settings` checks by the same path as a configuration file (the schema's
``cases`` and ``numerics`` sections and :mod:`hubbeam.configuration.checks`, every problem in one
:class:`~hubbeam.configuration.load.ConfigError`) and converts with the same builders. Nothing downstream
checks them again. ``to_dict()`` gives the plain mapping a dataset records (``case_config``).
"""

from __future__ import annotations

import copy
import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from types import MappingProxyType
from typing import Any

from hubbeam.configuration.load import case_settings, validate_parts
from hubbeam.configuration.schema import SCHEMA
from hubbeam.model.beam import BeamSections, beam_from_config
from hubbeam.model.limits import MEMORY_BUDGET_MB, SMALL_DEFLECTION_LIMIT
from hubbeam.model.parameters import TipMass, UniformBeam


def _frozen(value: Any) -> Any:
    """A number as float, a list as a tuple of such, a mapping (a pd reference, the gains of a
    state feedback) as a :class:`Maneuver` (kind None without a ``kind``)."""
    if isinstance(value, Mapping):
        return Maneuver.from_mapping(value)
    if isinstance(value, (list, tuple)):
        return tuple(_frozen(item) for item in value)
    return value if isinstance(value, (str, bool)) else float(value)


def _plain(value: Any) -> Any:
    if isinstance(value, Maneuver):
        return value.to_dict()
    return [_plain(item) for item in value] if isinstance(value, tuple) else value


@dataclass(frozen=True)
class Maneuver:
    """A hub maneuver (or a pd reference motion, or a damping): its ``kind`` and its parameters
    ``(key, value)`` in the order given, numbers as floats, tables as tuples (schema ``maneuver``,
    ``reference``, ``damping``: the keys of each kind)."""

    kind: str | None
    parameters: tuple[tuple[str, Any], ...]

    @classmethod
    def from_mapping(cls, entry: Mapping) -> Maneuver:
        return cls(entry.get("kind"), tuple((key, _frozen(value)) for key, value in entry.items() if key != "kind"))

    def __getitem__(self, key: str) -> Any:
        return self.kind if key == "kind" else dict(self.parameters)[key]

    def to_dict(self) -> dict:
        """``{"kind": ..., key: value, ...}`` with lists for tables, as written in a configuration."""
        kind = {} if self.kind is None else {"kind": self.kind}
        return kind | {key: _plain(value) for key, value in self.parameters}


#: a damping has the same shape: a kind and its parameters
Damping = Maneuver


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
    damping: Damping | None = None
    #: ``(key, value)`` of the optional ``initial`` state (``hubbeam.simulation.simulate.initial_state``);
    #: empty: the run starts at rest
    initial: tuple[tuple[str, Any], ...] = ()

    def to_dict(self) -> dict:
        """The resolved case as a plain mapping (``hubbeam.configuration.load.case_settings``)."""
        settings = {} if self.name is None else {"name": self.name}
        settings |= {"model": self.model, "maneuver": self.maneuver.to_dict(),
                    "t_end": self.t_end, "modes": self.modes,
                    "tip_mass": {"mass": self.tip_mass.mass, "position": self.tip_mass.position}}
        if self.damping is not None:
            settings["damping"] = self.damping.to_dict()
        if self.initial:
            settings["initial"] = {key: _plain(value) for key, value in self.initial}
        return settings


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


@dataclass(frozen=True)
class Grid:
    """``num`` equally spaced values from ``start`` to ``stop`` (schema ``$defs.grid``)."""

    start: float
    stop: float
    num: int


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
    comparisons: Mapping[str, tuple[str, ...]] = field(default_factory=lambda: MappingProxyType({}))


@dataclass(frozen=True)
class Settings:
    """A whole configuration: ``study`` is None for the paper."""

    beam: UniformBeam | BeamSections
    numerics: Numerics
    eigen: Eigen
    cases: Mapping[str, Case]
    study: Study | None = None


def from_config(cfg: Mapping) -> Settings:
    """The objects of a validated configuration (:func:`hubbeam.configuration.load.validate_config`)."""
    beam = beam_from_config(cfg["beam"])
    numerics = Numerics.from_mapping(cfg["numerics"])
    eigen = dict(cfg["eigen"])
    study = cfg.get("study")
    return Settings(
        beam=beam, numerics=numerics,
        eigen=Eigen(**{**eigen, "speeds": Grid(**eigen["speeds"]), "positions": Grid(**eigen["positions"]),
                       "tip_masses": tuple(eigen["tip_masses"])}),
        cases=MappingProxyType({name: _case(case_settings(cfg, name)) for name in sorted(cfg["cases"])}),
        study=None if study is None else Study(**{**study, "comparisons": MappingProxyType(
            {name: tuple(members) for name, members in study.get("comparisons", {}).items()})}),
    )


def _case(resolved: Mapping) -> Case:
    """The :class:`Case` of a resolved case (:func:`hubbeam.configuration.load.case_settings`, which fills the
    defaults); a name :data:`UNNAMED` is None."""
    return Case(name=None if resolved["name"] == UNNAMED else resolved["name"], model=resolved["model"],
                maneuver=Maneuver.from_mapping(resolved["maneuver"]), t_end=resolved["t_end"],
                modes=resolved["modes"], tip_mass=TipMass(**resolved["tip_mass"]),
                damping=Maneuver.from_mapping(resolved["damping"]) if "damping" in resolved else None,
                initial=tuple((key, _frozen(value)) for key, value in resolved.get("initial", {}).items()))


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
                                         else convergence_check)
    name = case.pop("name", None)
    where = UNNAMED if name is None else name
    cfg = copy.deepcopy({"beam": {"length": length}, "numerics": numerics, "cases": {where: case}})
    validate_parts(cfg, SIMULATION_SCHEMA)
    return _case(case_settings(cfg, where)), Numerics.from_mapping(cfg["numerics"])


#: the schema of a bare damping mapping (the API's), the configuration's ``damping`` section
DAMPING_SCHEMA = {"type": "object", "properties": {"damping": {"$ref": "#/$defs/damping"}}, "$defs": SCHEMA["$defs"]}


def damping_settings(damping: Damping | Mapping | None) -> Damping | None:
    """A damping as an object (None: no damping). An object is taken as it is; a mapping is checked
    in the one pass of the configuration (``ConfigError`` naming ``damping.<key>``) and converted."""
    if damping is None or isinstance(damping, Maneuver):
        return damping
    cfg = {"damping": copy.deepcopy(dict(damping))}
    validate_parts(cfg, DAMPING_SCHEMA)
    return Maneuver.from_mapping(cfg["damping"])
