"""Beams with sectional properties given at stations, and the beam of a config's ``beam`` section.

A non-uniform beam is described by its mass per unit length ``rho A(x)``, bending stiffness
``E I(x)`` and axial stiffness ``E A(x)`` at stations ``0 = x_0 < x_1 < ... < x_m = L``; between
stations each property is linear in ``x`` (a piecewise-linear table). Every integral of Eqs.
(13)-(20) is then taken with these functions inside, ``K1 = int EA f1'^T f1' dx``, ``K2 = int EI
f2''^T f2'' dx`` and the mass integrals with ``rho A(x)`` (``hubbeam.model.matrices``); the quadrature
breaks at the stations, where the tables have kinks (``hubbeam.model.quadrature.beam_rule``).

The admissible functions stay the clamped-free modes of a uniform beam of the same length, used
as a Ritz basis; they are normalised to unit modal mass of the uniform beam of the same total mass,
``rho A_ref = m_beam / L`` (``BeamSections.rhoA_ref``), so ``M2`` and ``K2`` are no longer diagonal.

A uniform beam is a :class:`hubbeam.model.parameters.UniformBeam`: by the factors of Table 1
(:class:`~hubbeam.model.parameters.BeamParameters`) or by its products
(:class:`~hubbeam.model.parameters.BeamProducts`). All offer the same interface (``L``, ``Jh``,
``rA``, ``beam_mass``, ``rhoA_ref``, ``stations``, ``rhoA_at``, ``EI_at``, ``EA_at``,
``outboard_moment``), which is all :func:`hubbeam.model.matrices.assemble` uses.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from hubbeam.model.parameters import CONFIG_KEYS, PRODUCT_KEYS, BeamParameters, BeamProducts, UniformBeam

#: the properties tabulated at the stations, in the order of the config's ``sections``
SECTION_PROPERTIES = ("rhoA", "EI", "EA")
#: unit of each sectional property
SECTION_UNITS = {"rhoA": "kg m-1", "EI": "N m2", "EA": "N"}
#: keys of a ``beam`` section with ``sections`` (besides ``sections`` itself)
SECTIONS_BEAM_KEYS = ("length", "hub_inertia", "hub_radius")
#: config key -> field name
CONFIG_FIELDS = {key: name for name, key in CONFIG_KEYS.items()}
#: the uniform beam classes -> their field -> config key
UNIFORM_KEYS = {BeamParameters: CONFIG_KEYS, BeamProducts: PRODUCT_KEYS}

# two-point Gauss-Legendre rule on [-1, 1]: exact for the cubic rho A(s) (rA + s) on a segment
_GAUSS2 = np.array([-1.0, 1.0]) / math.sqrt(3.0)


def _check_scalar(name, value, allowed, ok):
    if not (isinstance(value, (int, float, np.integer, np.floating))
            and not isinstance(value, bool) and ok(float(value))):
        raise ValueError(f"beam.{name} = {value!r}: expected {allowed}")
    return float(value)


def _as_table(name, values):
    try:
        table = tuple(float(v) for v in values)
    except (TypeError, ValueError):
        raise ValueError(
            f"beam.sections.{name} = {values!r}: expected a list of numbers, one per station"
        ) from None
    return table


@dataclass(frozen=True)
class BeamSections:
    """Beam with piecewise-linear sectional properties, clamped radially to a rigid hub.

    ``L`` length (m), ``Jh`` hub inertia (kg m2), ``rA`` hub radius (m); at the stations ``x`` (m,
    strictly increasing, ``x[0] = 0``, ``x[-1] = L``, at least two): ``rhoA`` (kg m-1), ``EI``
    (N m2), ``EA`` (N), each finite and > 0. The tables are stored as tuples of floats; a bad
    value raises ``ValueError`` naming the field, the index and the value.
    """

    L: float
    Jh: float
    rA: float
    x: tuple
    rhoA: tuple
    EI: tuple
    EA: tuple

    def __post_init__(self) -> None:
        L = _check_scalar("length", self.L, "a finite length > 0 m",
                          lambda v: math.isfinite(v) and v > 0.0)
        Jh = _check_scalar("hub_inertia", self.Jh, "a finite hub inertia >= 0 kg m2",
                           lambda v: math.isfinite(v) and v >= 0.0)
        rA = _check_scalar("hub_radius", self.rA, "a finite hub radius >= 0 m",
                           lambda v: math.isfinite(v) and v >= 0.0)
        tables = {name: _as_table(name, getattr(self, name)) for name in ("x",) + SECTION_PROPERTIES}
        x = tables["x"]
        if len(x) < 2:
            raise ValueError(f"beam.sections.x = {list(x)}: expected at least 2 stations "
                             "(the root x = 0 and the tip x = length)")
        for name in SECTION_PROPERTIES:
            if len(tables[name]) != len(x):
                raise ValueError(
                    f"beam.sections.{name} has {len(tables[name])} values: expected one per "
                    f"station, {len(x)} like beam.sections.x"
                )
        if x[0] != 0.0:
            raise ValueError(f"beam.sections.x[0] = {x[0]!r}: expected 0 (the clamped root)")
        if x[-1] != L:
            raise ValueError(f"beam.sections.x[{len(x) - 1}] = {x[-1]!r}: expected the beam "
                             f"length {L} (the last station is the tip)")
        for i in range(1, len(x)):
            if not (math.isfinite(x[i]) and x[i] > x[i - 1]):
                raise ValueError(f"beam.sections.x[{i}] = {x[i]!r}: expected a finite station "
                                 f"> x[{i - 1}] = {x[i - 1]} (strictly increasing)")
        for name in SECTION_PROPERTIES:
            for i, value in enumerate(tables[name]):
                if not (math.isfinite(value) and value > 0.0):
                    raise ValueError(f"beam.sections.{name}[{i}] = {value!r}: expected a finite "
                                     f"value > 0 {SECTION_UNITS[name]}")
        for name, value in (("L", L), ("Jh", Jh), ("rA", rA), *tables.items()):
            object.__setattr__(self, name, value)

    # -- the interface shared with BeamParameters ------------------------------------------

    @property
    def stations(self) -> tuple:
        """Station abscissae (m): the properties are linear between consecutive ones."""
        return self.x

    @property
    def beam_mass(self) -> float:
        """Mass of the beam (kg), exact for the piecewise-linear ``rho A``."""
        x, m = np.asarray(self.x), np.asarray(self.rhoA)
        return float(np.sum(0.5 * (m[1:] + m[:-1]) * np.diff(x)))

    @property
    def rhoA_ref(self) -> float:
        """``m_beam / L`` (kg m-1): the admissible functions have unit modal mass of the uniform
        beam of this mass per unit length (``hubbeam.model.modes``)."""
        return self.beam_mass / self.L

    def rhoA_at(self, x):
        """Mass per unit length (kg m-1) at ``x``, linear between stations."""
        return np.interp(x, self.x, self.rhoA)

    def EI_at(self, x):
        """Bending stiffness (N m2) at ``x``, linear between stations."""
        return np.interp(x, self.x, self.EI)

    def EA_at(self, x):
        """Axial stiffness (N) at ``x``, linear between stations."""
        return np.interp(x, self.x, self.EA)

    def outboard_moment(self, x):
        """``int_x^L rho A(s) (rA + s) ds`` (kg m) at ``0 <= x <= L``: the centrifugal tension per
        ``Omega^2`` and the weight of ``D`` (Eq. 18) with the order of integration swapped.

        Exact: on each segment the integrand is a cubic, integrated by a two-point Gauss rule
        (whole segments outboard of ``x``, summed from the tip, plus the part of ``x``'s own).
        """
        x = np.asarray(x, dtype=float)
        stations = np.asarray(self.x)
        whole = self._moment(stations[:-1], stations[1:])
        outboard = np.append(np.cumsum(whole[::-1])[::-1], 0.0)  # int_{x_k}^L, k = 0..m
        k = np.clip(np.searchsorted(stations, x, side="right"), 1, stations.size - 1)
        return outboard[k] + self._moment(x, stations[k])

    def _moment(self, a, b):
        """``int_a^b rho A(s) (rA + s) ds`` for ``a, b`` within one segment (arrays)."""
        half = 0.5 * (np.asarray(b) - np.asarray(a))
        s = (np.asarray(a) + half)[..., None] + half[..., None] * _GAUSS2
        return half * np.sum(self.rhoA_at(s) * (self.rA + s), axis=-1)


def scaled_bending_stiffness(beam: UniformBeam | BeamSections, factor: float) -> UniformBeam | BeamSections:
    """``beam`` with its bending stiffness ``E I`` (at every station) times ``factor``, in the field its
    form has: ``EI`` of the products or of the sections, ``I`` of the factors of Table 1."""
    if isinstance(beam, BeamParameters):
        return dataclasses.replace(beam, I=beam.I * factor)
    if isinstance(beam, BeamSections):
        return dataclasses.replace(beam, EI=tuple(value * factor for value in beam.EI))
    return dataclasses.replace(beam, EI=beam.EI * factor)


def beam_from_config(beam: Mapping) -> UniformBeam | BeamSections:
    """The beam of a config's ``beam`` section, in the form its keys select (schema ``beam``).

    Uniform by the factors ``length, density, area, youngs_modulus, second_moment, hub_inertia,
    hub_radius`` (:class:`BeamParameters`) or by the products ``length, rhoA, EI, EA,
    hub_inertia, hub_radius`` (:class:`BeamProducts`). Non-uniform: ``length, hub_inertia,
    hub_radius`` and ``sections: {x: [...], rhoA: [...], EI: [...], EA: [...]}`` as inline lists
    (:class:`BeamSections`); a ``sections: {file: ...}`` must have been read into such lists before.
    """
    if isinstance(beam.get("beam"), Mapping):
        raise ValueError(f"beam_from_config takes the beam section, not a whole configuration (keys "
                         f"{', '.join(sorted(beam))}); allowed: beam_from_config(cfg['beam'])")
    if "sections" not in beam:
        cls = BeamProducts if "rhoA" in beam else BeamParameters
        keys = UNIFORM_KEYS[cls]
        missing = [key for key in keys.values() if key not in beam]
        if missing:
            raise ValueError(f"beam is missing {', '.join(missing)}: a uniform beam needs "
                             f"{', '.join(keys.values())} (or give sections)")
        return cls(**{name: beam[key] for name, key in keys.items()})
    extra = sorted(set(beam) - set(SECTIONS_BEAM_KEYS) - {"sections"})
    if extra:
        raise ValueError(f"beam.{extra[0]} = {beam[extra[0]]!r}: not allowed with sections; "
                         f"allowed: {', '.join(SECTIONS_BEAM_KEYS)}, sections")
    missing = [key for key in SECTIONS_BEAM_KEYS if key not in beam]
    if missing:
        raise ValueError(f"beam is missing {', '.join(missing)}: a beam with sections needs "
                         f"{', '.join(SECTIONS_BEAM_KEYS)}")
    sections = beam["sections"]
    expected = ("x",) + SECTION_PROPERTIES
    if not isinstance(sections, Mapping) or sorted(sections) != sorted(expected):
        shown = sorted(sections) if isinstance(sections, Mapping) else sections
        raise ValueError(f"beam.sections = {shown!r}: expected inline lists "
                         f"{', '.join(expected)} (a sections file must be read first)")
    return BeamSections(L=beam["length"], Jh=beam["hub_inertia"], rA=beam["hub_radius"],
                        **{name: sections[name] for name in expected})


def beam_attributes(params: UniformBeam | BeamSections) -> dict:
    """Dataset attributes describing a beam, under its config keys (``beam`` section).

    Uniform: the keys of its form (:data:`hubbeam.model.parameters.CONFIG_KEYS` or
    :data:`~hubbeam.model.parameters.PRODUCT_KEYS`) as floats. With sections: ``length``,
    ``hub_inertia``, ``hub_radius`` and the tables as float arrays ``sections_x``,
    ``sections_rhoA``, ``sections_EI``, ``sections_EA``. :func:`beam_from_attributes` inverts it.
    """
    if isinstance(params, UniformBeam):
        return {key: float(getattr(params, name)) for name, key in UNIFORM_KEYS[type(params)].items()}
    return ({key: float(getattr(params, CONFIG_FIELDS[key])) for key in SECTIONS_BEAM_KEYS}
            | {f"sections_{name}": np.asarray(getattr(params, name), dtype=float)
               for name in ("x",) + SECTION_PROPERTIES})


def beam_config(params: UniformBeam | BeamSections) -> dict:
    """The beam as a configuration's ``beam`` section writes it (the inverse of
    :func:`beam_from_config`): the keys of its uniform form, or the three scalars and inline
    ``sections`` lists."""
    attributes = beam_attributes(params)
    if isinstance(params, UniformBeam):
        return attributes
    return ({key: attributes[key] for key in SECTIONS_BEAM_KEYS}
            | {"sections": {name: attributes[f"sections_{name}"].tolist() for name in ("x",) + SECTION_PROPERTIES}})


def beam_from_attributes(attrs: Mapping) -> UniformBeam | BeamSections:
    """The beam described by :func:`beam_attributes` (e.g. a dataset's attributes)."""
    if "sections_x" not in attrs:
        return beam_from_config(attrs)
    beam = {key: attrs[key] for key in SECTIONS_BEAM_KEYS if key in attrs}
    beam["sections"] = {name: np.atleast_1d(attrs[f"sections_{name}"]).tolist()
                        for name in ("x",) + SECTION_PROPERTIES}
    return beam_from_config(beam)
