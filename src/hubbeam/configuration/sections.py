"""The records of the configuration's sections beside the cases: grids, the linear models, the
independent validation, the analyses of the sampled controllers and the alternative readings.

Each section of a checked configuration becomes one frozen record with its defaults resolved
(:func:`hubbeam.configuration.settings.from_config` builds them, once, in the one check of the
configuration); the workflow's plan and its jobs take these records and never read the mapping
again. ``to_dict()`` gives back the plain mapping where a dataset records one.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, fields

import numpy as np

from hubbeam.model.damping import ModalDamping, RayleighDamping, damping_from_dict
from hubbeam.model.frozen import FrozenMap, freeze, thaw
from hubbeam.model.maneuvers import SpinUp, maneuver_from_dict
from hubbeam.model.parameters import TipMass


@dataclass(frozen=True)
class Grid:
    """``num`` equally spaced values from ``start`` to ``stop`` (schema ``$defs.grid``)."""

    start: float
    stop: float
    num: int

    @property
    def values(self) -> np.ndarray:
        return np.linspace(self.start, self.stop, self.num)

    @classmethod
    def from_dict(cls, entry: Mapping) -> Grid:
        return cls(entry["start"], entry["stop"], entry["num"])

    def to_dict(self) -> dict:
        return {"start": self.start, "stop": self.stop, "num": self.num}


@dataclass(frozen=True)
class LogGrid(Grid):
    """``num`` logarithmically spaced values from ``start`` to ``stop`` (both > 0)."""

    @property
    def values(self) -> np.ndarray:
        return np.geomspace(self.start, self.stop, self.num)


@dataclass(frozen=True)
class Linear:
    """The ``linear`` section with its defaults filled in (``hubbeam.configuration.defaults``): the
    speeds of the steady spins, the point masses at the tip of the paper's linear models, the
    speeds and frequencies (rad s-1) of the Bode diagrams, the mode shapes drawn and the damping."""

    speeds: Grid
    tip_masses: tuple[float, ...]
    bode_speeds: tuple[float, ...]
    frequencies: LogGrid
    shapes: int
    damping: ModalDamping | RayleighDamping | None = None

    @classmethod
    def from_dict(cls, entry: Mapping) -> Linear:
        return cls(speeds=Grid.from_dict(entry["speeds"]), tip_masses=tuple(entry["tip_masses"]),
                   bode_speeds=tuple(entry["bode_speeds"]), frequencies=LogGrid.from_dict(entry["frequencies"]),
                   shapes=int(entry["shapes"]), damping=damping_from_dict(entry.get("damping")))


@dataclass(frozen=True)
class Published:
    """``validation.published``: the mode counts of the published-table check (the last the
    result) and the grid of dimensionless speeds of its frequency curves."""

    modes: tuple[int, ...]
    gammas: Grid


@dataclass(frozen=True)
class ExudynSettings:
    """``validation.exudyn``: the production settings of the Exudyn ANCF reference."""

    elements: int
    time_step: float
    spectral_radius: float
    newton_tolerance: float

    def to_dict(self) -> dict:
        return {item.name: getattr(self, item.name) for item in fields(self)}


@dataclass(frozen=True)
class ValidationCase:
    """A prescribed spin-up of ``validation.cases`` (Eq. 43), with an optional point mass at a node."""

    name: str
    maneuver: SpinUp
    t_end: float
    tip_mass: TipMass | None = None

    def to_dict(self) -> dict:
        """The case as written in the configuration (what its datasets record)."""
        plain = {"maneuver": self.maneuver.to_dict(), "t_end": self.t_end}
        if self.tip_mass is not None:
            plain["tip_mass"] = {"mass": self.tip_mass.mass, "position": self.tip_mass.position}
        return plain


@dataclass(frozen=True)
class ReferenceConvergence:
    """``validation.convergence``: the case and the settings the reference's convergence study varies."""

    case: str
    elements: tuple[int, ...]
    time_steps: tuple[float, ...]
    newton_tolerances: tuple[float, ...]


@dataclass(frozen=True)
class Validation:
    """The ``validation`` section (docs/validation.md): the published-table check (None without
    ``published``), the Exudyn reference's settings, the models compared, the mode counts of the
    mode study, the validation cases by name and the reference's convergence study."""

    exudyn: ExudynSettings
    models: tuple[str, ...]
    mode_study: tuple[int, ...]
    cases: FrozenMap
    convergence: ReferenceConvergence
    published: Published | None = None

    @classmethod
    def from_dict(cls, entry: Mapping) -> Validation:
        published = entry.get("published")
        return cls(
            exudyn=ExudynSettings(**entry["exudyn"]), models=tuple(entry["models"]),
            mode_study=tuple(int(n) for n in entry["mode_study"]),
            cases=FrozenMap({name: _validation_case(name, case) for name, case in sorted(entry["cases"].items())}),
            convergence=ReferenceConvergence(case=entry["convergence"]["case"],
                                             **{key: tuple(entry["convergence"][key])
                                                for key in ("elements", "time_steps", "newton_tolerances")}),
            published=None if published is None else Published(tuple(int(n) for n in published["modes"]),
                                                               Grid.from_dict(published["gammas"])))


def _validation_case(name: str, entry: Mapping) -> ValidationCase:
    tip = entry.get("tip_mass")
    return ValidationCase(name=name, maneuver=maneuver_from_dict(entry["maneuver"]), t_end=float(entry["t_end"]),
                          tip_mass=None if tip is None else TipMass(float(tip["mass"]), float(tip["position"])))


#: the command delays of the sample-time sweep without ``control.sample_time.delays``, samples
DEFAULT_DELAYS = (0.0, 1.0)
#: the points of each range of a robustness map without ``control.robustness.points``
DEFAULT_POINTS = 21


@dataclass(frozen=True)
class SampleTimeAnalysis:
    """``control.sample_time``: the sampled cases swept, the sample times (s, logarithmically
    spaced) and the command delays (samples)."""

    cases: tuple[str, ...]
    sample_times: LogGrid
    delays: tuple[float, ...] = DEFAULT_DELAYS


@dataclass(frozen=True)
class RobustnessAnalysis:
    """``control.robustness``: the sampled cases, ``(low, high)`` of each plant parameter moved,
    and the points of each range."""

    cases: tuple[str, ...]
    ranges: FrozenMap
    points: int = DEFAULT_POINTS


@dataclass(frozen=True)
class Control:
    """The ``control`` section: its analyses, each None when not asked for."""

    sample_time: SampleTimeAnalysis | None = None
    robustness: RobustnessAnalysis | None = None

    @classmethod
    def from_dict(cls, entry: Mapping) -> Control:
        sweep, robust = entry.get("sample_time"), entry.get("robustness")
        return cls(
            sample_time=None if sweep is None else SampleTimeAnalysis(
                cases=tuple(sweep["cases"]), sample_times=LogGrid.from_dict(sweep["sample_times"]),
                delays=tuple(float(d) for d in sweep.get("delays", DEFAULT_DELAYS))),
            robustness=None if robust is None else RobustnessAnalysis(
                cases=tuple(robust["cases"]),
                ranges=FrozenMap({name: (float(low), float(high)) for name, (low, high) in robust["ranges"].items()}),
                points=int(robust.get("points", DEFAULT_POINTS))))

    @property
    def analyses(self) -> dict:
        """The analyses asked for, by name (``sample_time``, ``robustness``)."""
        return {name: getattr(self, name) for name in ("sample_time", "robustness")
                if getattr(self, name) is not None}


@dataclass(frozen=True)
class Identify:
    """The ``identify`` section as the workflow plans it (``hubbeam.identification.section`` reads
    and fits the rest): the identified ``case``, the ``experiments``' kinds by name, the names of
    those ``fitted`` and ``held_out``, and the cases that run on the fitted plant (``apply_to``)."""

    case: str
    experiments: FrozenMap
    fitted: tuple[str, ...]
    held_out: tuple[str, ...]
    apply_to: tuple[str, ...] = ()

    @classmethod
    def from_dict(cls, entry: Mapping) -> Identify:
        held_out = tuple(entry.get("validate", ()))
        fitted = tuple(entry.get("fit", [name for name in entry["experiments"] if name not in held_out]))
        kinds = {name: experiment["kind"] for name, experiment in entry["experiments"].items()}
        return cls(case=entry["case"], experiments=FrozenMap(kinds),
                   fitted=fitted, held_out=held_out, apply_to=tuple(entry.get("apply_to", ())))


@dataclass(frozen=True)
class Reading:
    """One alternative reading of the paper (``readings.<name>``, :mod:`hubbeam.paper.readings`):
    its one change (``change`` the kind: case, maneuver, beam, tip_mass or measure; ``value`` what
    it changes to), the runs a case change applies to (``where``), the claims it can move, the
    reproduction notes behind it and why it is plausible."""

    name: str
    change: str
    value: object
    claims: tuple[str, ...]
    notes: tuple[int, ...] = ()
    why: str = ""
    where: FrozenMap = field(default_factory=FrozenMap)

    @classmethod
    def from_dict(cls, name: str, entry: Mapping) -> Reading:
        (change, value), = entry["change"].items()
        return cls(name=name, change=change, value=freeze(value), claims=tuple(entry["claims"]),
                   notes=tuple(entry.get("notes", ())), why=entry.get("why", ""),
                   where=freeze(entry.get("where", {})))

    def to_dict(self) -> dict:
        """The reading as written in the configuration."""
        plain = {"change": {self.change: thaw(self.value)}, "claims": list(self.claims), "notes": list(self.notes),
                 "why": self.why}
        return plain | ({"where": thaw(self.where)} if self.where else {})
