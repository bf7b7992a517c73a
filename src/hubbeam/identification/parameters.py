"""The free parameters of a fit, named by the configuration keys of a case, and how they are applied.

A parameter is a key of the case's configuration (``root_spring.stiffness``) or of the beam
(``beam.hub_inertia``), with bounds and a start; the rest of the case stays as configured. Keys
(:data:`PARAMETERS`; units SI):

* ``beam.EI_factor``: a factor on the link's bending stiffness ``EI`` (the products' ``EI``, the
  factors' ``second_moment``, every station of ``sections``): a factor, so that one key serves
  every form of beam and a non-uniform link keeps its shape; ``beam.hub_inertia``;
* ``root_spring.stiffness``, ``root_spring.damping``, ``root_spring.clamp_inertia`` (a case with a
  compliant root);
* ``damping.transverse`` (every transverse mode) and ``damping.transverse_modes.<k>`` (the ratio
  of transverse mode ``k = 1, 2, ...`` alone, ``hubbeam.model.damping``), ``damping.axial``: modal
  damping (a case without damping gets ``{kind: modal, axial: 0, transverse: 0}`` to start from);
* ``tip_mass.mass``, ``tip_mass.inertia``, ``tip_mass.position``, ``tip_mass.offset``;
* ``drive.viscous_friction``, ``drive.coulomb_friction``, ``drive.motor_constant_factor`` (a factor
  on the torque and back-EMF constants together, ``kt = km`` in SI units), ``drive.resistance``
  (a case with a drive);
* ``sensors.<signal>.gain``, ``sensors.<signal>.offset``: a rig's sensor of a measured signal
  (every time series that measures it; the sensor is the rig's, not the case's, and stays out of
  the configuration fragment).

:func:`apply` gives the case and the beam as the configuration would build them with the values
(the same records: ``ModalDamping``, ``RootSpring``, ``TipMass``, ``DcMotor``, the beam's class),
and :func:`fragment` the configuration mapping that says so, for a study to merge. A key that is
not a parameter, bounds that are not finite or not increasing, a start outside its bounds, a
value outside the physical range of the key or a key the case cannot take (a root spring's on a
case without one) is refused with a :class:`ParameterError` naming the key, the value and what is
allowed.
"""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from hubbeam.configuration.settings import Case, tip_mass_to_dict
from hubbeam.identification.experiments import SIGNALS
from hubbeam.model.beam import scaled_bending_stiffness
from hubbeam.model.damping import ModalDamping, RayleighDamping, damping_to_dict
from hubbeam.model.limits import MAX_MODES
from hubbeam.model.parameters import BeamParameters, BeamProducts, TipMass


class ParameterError(ValueError):
    """A free parameter is refused: the message names its key, the value and what is allowed."""


@dataclass(frozen=True)
class Kind:
    """What a key is: its ``unit`` and ``long_name``, the physical range ``[low, high]`` (an end
    excluded when ``open_low`` / ``open_high``), the part of the case it needs (``needs``:
    ``root_spring``, ``drive``) and whether it is a sensor's (not the plant's)."""

    unit: str
    long_name: str
    low: float = 0.0
    high: float = math.inf
    open_low: bool = False
    open_high: bool = False
    needs: str | None = None

    def allows(self, value: float) -> bool:
        above = value > self.low if self.open_low else value >= self.low
        below = value < self.high if self.open_high else value <= self.high
        return math.isfinite(value) and above and below

    def allowed(self) -> str:
        low = f"{'>' if self.open_low else '>='} {self.low:g}"
        high = "" if math.isinf(self.high) else f" and {'<' if self.open_high else '<='} {self.high:g}"
        return f"a finite value {low}{high} {self.unit}".rstrip()


_POSITIVE = {"open_low": True}
#: the fixed keys of the free parameters and what each is (module docstring)
PARAMETERS = {
    "beam.EI_factor": Kind("1", "factor on the link's bending stiffness EI", **_POSITIVE),
    "beam.hub_inertia": Kind("kg m2", "hub inertia"),
    "root_spring.stiffness": Kind("N m rad-1", "stiffness of the compliant root", needs="root_spring"),
    "root_spring.damping": Kind("N m s rad-1", "damping of the compliant root", needs="root_spring"),
    "root_spring.clamp_inertia": Kind("kg m2", "rotary inertia of the clamp", needs="root_spring"),
    "damping.transverse": Kind("1", "damping ratio of the transverse modes", high=1.0, open_high=True),
    "damping.axial": Kind("1", "damping ratio of the axial modes", high=1.0, open_high=True),
    "tip_mass.mass": Kind("kg", "tip body's mass"),
    "tip_mass.inertia": Kind("kg m2", "tip body's rotary inertia about its centre"),
    "tip_mass.position": Kind("m", "tip body's attachment along the beam"),
    "tip_mass.offset": Kind("m", "tip body's centre beyond its attachment", low=-math.inf),
    "drive.viscous_friction": Kind("N m s rad-1", "hub viscous friction Beq", needs="drive"),
    "drive.coulomb_friction": Kind("N m", "hub Coulomb friction", needs="drive"),
    "drive.motor_constant_factor": Kind("1", "factor on the motor's torque and back-EMF constants kt = km",
                                        needs="drive", **_POSITIVE),
    "drive.resistance": Kind("ohm", "armature resistance", needs="drive", **_POSITIVE),
}
#: the per-mode damping ratio's key, ``damping.transverse_modes.<k>``
MODE_RATIO = re.compile(r"^damping\.transverse_modes\.([1-9][0-9]*)$")
#: a sensor's key, ``sensors.<signal>.gain`` or ``.offset``
SENSOR_KEY = re.compile(r"^sensors\.([a-z_]+)\.(gain|offset)$")


def kind_of(key: str) -> Kind:
    """The :class:`Kind` of ``key``; a :class:`ParameterError` naming the keys allowed."""
    if key in PARAMETERS:
        return PARAMETERS[key]
    mode = MODE_RATIO.match(key) if isinstance(key, str) else None
    if mode and int(mode.group(1)) <= MAX_MODES:
        return Kind("1", f"damping ratio of transverse mode {mode.group(1)}", high=1.0, open_high=True)
    sensor = SENSOR_KEY.match(key) if isinstance(key, str) else None
    if sensor and sensor.group(1) in SIGNALS:
        if sensor.group(2) == "gain":
            return Kind("1", f"gain of the {sensor.group(1)} sensor", **_POSITIVE)
        return Kind("sensor unit", f"offset of the {sensor.group(1)} sensor", low=-math.inf)
    raise ParameterError(f"{key!r}: not a parameter; allowed: {', '.join(PARAMETERS)}, "
                         f"damping.transverse_modes.<k> (k = 1..{MAX_MODES}), sensors.<signal>.gain, "
                         f"sensors.<signal>.offset (signal: {', '.join(SIGNALS)})")


def is_sensor(key: str) -> bool:
    """Whether ``key`` is a sensor's (``sensors.<signal>.<gain|offset>``)."""
    return SENSOR_KEY.match(key) is not None


def nominal_value(key: str, case: Case, beam) -> float:
    """The value ``key`` has in the case as configured (a factor 1, an ideal sensor's gain 1 and
    offset 0, a ratio of an undamped case 0); a :class:`ParameterError` when the case cannot take it."""
    kind = kind_of(key)
    if kind.needs is not None and getattr(case, kind.needs) is None:
        raise ParameterError(f"{key!r}: case {case.label!r} has no {kind.needs}; allowed: a case with a "
                             f"{kind.needs} section")
    if key.startswith("damping.") and isinstance(case.damping, RayleighDamping):
        raise ParameterError(f"{key!r}: case {case.label!r} has Rayleigh damping; allowed: a case with modal "
                             "damping or none")
    head, _, tail = key.partition(".")
    if key.endswith("_factor") or (head == "sensors" and tail.endswith("gain")):
        return 1.0
    if head == "sensors":
        return 0.0
    if head == "beam":
        return float(beam.Jh)
    if head == "damping":
        damping = case.damping
        if damping is None:
            return 0.0
        mode = MODE_RATIO.match(key)
        if mode:
            return float(damping.transverse_ratios(int(mode.group(1)))[-1])
        return float(getattr(damping, tail))
    return float(getattr(getattr(case, head), tail))


@dataclass(frozen=True)
class Parameter:
    """A free parameter: its configuration ``key``, its bounds and its start (module docstring)."""

    key: str
    lower: float
    upper: float
    start: float

    @property
    def kind(self) -> Kind:
        return kind_of(self.key)

    def scaled(self, value):
        """``value`` as the fraction of the bounds, ``(value - lower) / (upper - lower)``."""
        return (np.asarray(value, dtype=float) - self.lower) / (self.upper - self.lower)

    def unscaled(self, x):
        """The value at the fraction ``x`` of the bounds."""
        return self.lower + np.asarray(x, dtype=float) * (self.upper - self.lower)


def _number(where: str, value, allowed: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ParameterError(f"{where} = {value!r}; allowed: {allowed}")
    return float(value)


def free_parameters(entries: Mapping[str, Mapping], case: Case, beam, where: str = "parameters",
                    sensors: Sequence[str] = ()) -> tuple[Parameter, ...]:
    """The :class:`Parameter` of every ``key: {lower, upper[, start]}`` of ``entries``, checked for
    ``case`` (its records as configured) and ``beam``; ``start`` defaults to the case's value when
    it lies within the bounds, to their middle otherwise. ``sensors``: the signals the experiments
    measure (a sensor's key must name one). ``where`` prefixes the keys in messages."""
    if not isinstance(entries, Mapping) or not entries:
        raise ParameterError(f"{where} = {entries!r}; allowed: a mapping of at least one key to "
                             "{lower, upper, start}")
    found = []
    for key, entry in entries.items():
        at = f"{where}.{key}"
        try:
            kind = kind_of(key)
            nominal = nominal_value(key, case, beam)
        except ParameterError as error:
            raise ParameterError(f"{where}.{error}") from None
        sensor = SENSOR_KEY.match(key)
        if sensor and sensor.group(1) not in sensors:
            raise ParameterError(f"{at}: no experiment measures {sensor.group(1)}; allowed: the sensors of "
                                 f"{', '.join(sensors) or 'no signal (no time series)'}")
        if not isinstance(entry, Mapping) or not {"lower", "upper"} <= set(entry) or set(entry) - {
                "lower", "upper", "start"}:
            raise ParameterError(f"{at} = {entry!r}; allowed: {{lower, upper}} with an optional start")
        lower = _number(f"{at}.lower", entry["lower"], kind.allowed())
        upper = _number(f"{at}.upper", entry["upper"], kind.allowed())
        for name, value in (("lower", lower), ("upper", upper)):
            if not kind.allows(value):
                raise ParameterError(f"{at}.{name} = {value!r}; allowed: {kind.allowed()}")
        if not lower < upper:
            raise ParameterError(f"{at}: lower = {lower!r}, upper = {upper!r}; allowed: lower < upper")
        if key == "tip_mass.position" and upper > beam.L:
            raise ParameterError(f"{at}.upper = {upper!r}; allowed: a position on the beam, <= {beam.L:g} m")
        if "start" in entry:
            start = _number(f"{at}.start", entry["start"], f"a number in [{lower!r}, {upper!r}]")
            if not lower <= start <= upper:
                raise ParameterError(f"{at}.start = {start!r}; allowed: a start in [{lower!r}, {upper!r}]")
        else:
            start = nominal if lower <= nominal <= upper else 0.5 * (lower + upper)
        found.append(Parameter(key, lower, upper, start))
    return tuple(found)


def _damping(damping: ModalDamping | None, values: Mapping[str, float]) -> ModalDamping:
    damping = damping or ModalDamping(axial=0.0, transverse=0.0)
    damping = ModalDamping(axial=float(values.get("damping.axial", damping.axial)),
                           transverse=float(values.get("damping.transverse", damping.transverse)),
                           transverse_modes=damping.transverse_modes)
    modes = {int(MODE_RATIO.match(key).group(1)): value for key, value in values.items() if MODE_RATIO.match(key)}
    if not modes:
        return damping
    count = max(max(modes), len(damping.transverse_modes or ()))
    ratios = damping.transverse_ratios(count)
    return dataclasses.replace(damping, transverse_modes=tuple(float(modes.get(k + 1, ratios[k]))
                                                               for k in range(count)))


def apply(case: Case, beam, values: Mapping[str, float]):
    """``(case, beam)`` with the plant parameters ``values`` (key -> value; sensors' keys ignored):
    the records the configuration builds from :func:`fragment` (module docstring)."""
    plant = {key: float(value) for key, value in values.items() if not is_sensor(key)}
    for key, value in plant.items():
        kind = kind_of(key)
        if not kind.allows(value):
            raise ParameterError(f"{key} = {value!r}; allowed: {kind.allowed()}")
    changes = {}
    if "beam.EI_factor" in plant:
        beam = scaled_bending_stiffness(beam, plant["beam.EI_factor"])
    if "beam.hub_inertia" in plant:
        beam = dataclasses.replace(beam, Jh=plant["beam.hub_inertia"])
    root = {key.partition(".")[2]: value for key, value in plant.items() if key.startswith("root_spring.")}
    if root:
        changes["root_spring"] = dataclasses.replace(case.root_spring, **root)
    tip = {key.partition(".")[2]: value for key, value in plant.items() if key.startswith("tip_mass.")}
    if tip:
        changes["tip_mass"] = TipMass(**(dataclasses.asdict(case.tip_mass) | tip))
    damping = {key: value for key, value in plant.items() if key.startswith("damping.")}
    if damping:
        changes["damping"] = _damping(case.damping, damping)
    drive = {key.partition(".")[2]: value for key, value in plant.items() if key.startswith("drive.")}
    if drive:
        factor = drive.pop("motor_constant_factor", 1.0)
        motor = case.drive
        changes["drive"] = dataclasses.replace(motor, torque_constant=motor.torque_constant * factor,
                                               back_emf_constant=motor.back_emf_constant * factor, **drive)
    return (dataclasses.replace(case, **changes) if changes else case), beam


def fragment(case_name: str, values: Mapping[str, float], case: Case, beam) -> dict:
    """The configuration fragment that gives case ``case_name`` (configured as ``case`` on ``beam``)
    the plant parameters ``values``: ``{"beam": {...}, "cases": {case_name: {...}}}`` with only the
    sections the values change (a whole ``damping``, ``root_spring``, ``tip_mass`` or ``drive``
    section; the beam's keys in its own form, ``sections`` as inline lists). Merged onto the
    configuration, it gives the records :func:`apply` gives; sensors' values are left out."""
    new_case, new_beam = apply(case, beam, values)
    keys = {key.partition(".")[0] for key in values if not is_sensor(key)}
    found: dict = {}
    if "beam" in keys:
        section = {"hub_inertia": new_beam.Jh} if "beam.hub_inertia" in values else {}
        if "beam.EI_factor" in values:
            if isinstance(new_beam, BeamProducts):
                section["EI"] = new_beam.EI
            elif isinstance(new_beam, BeamParameters):
                section["second_moment"] = new_beam.I
            else:
                section["sections"] = {"x": list(new_beam.x), "rhoA": list(new_beam.rhoA), "EI": list(new_beam.EI),
                                       "EA": list(new_beam.EA)}
        found["beam"] = section
    entry = {}
    if "damping" in keys:
        entry["damping"] = damping_to_dict(new_case.damping)
    if "root_spring" in keys:
        entry["root_spring"] = new_case.root_spring.to_dict()
    if "tip_mass" in keys:
        entry["tip_mass"] = tip_mass_to_dict(new_case.tip_mass)
    if "drive" in keys:
        entry["drive"] = new_case.drive.to_dict()
    if entry:
        found["cases"] = {case_name: entry}
    return found


def sensor_values(values: Mapping[str, float]) -> dict[str, dict[str, float]]:
    """The sensors' values of ``values`` by signal: ``{signal: {"gain": ..., "offset": ...}}``."""
    found: dict[str, dict[str, float]] = {}
    for key, value in values.items():
        matched = SENSOR_KEY.match(key)
        if matched:
            found.setdefault(matched.group(1), {})[matched.group(2)] = float(value)
    return found


__all__ = ["PARAMETERS", "Kind", "Parameter", "ParameterError", "apply", "free_parameters", "fragment",
           "is_sensor", "kind_of", "nominal_value", "sensor_values"]
