"""Alternative readings of the paper: one changed interpretation each, and the claims it moves.

A reading (config ``readings``) names ONE change of how the paper is read, as data:

* ``case``: a partial case merged into every affected run (``{modes: 3}``, ``{maneuver: {tf:
  20.0}}``); ``where`` restricts it to runs whose ``model`` or maneuver ``kind`` match;
* ``maneuver``: a maneuver generated from each run's own one (:data:`MANEUVER_READINGS`): the
  spin-up of Eq. (43) as printed, other periods or shapes of the torque pulse of Eq. (44);
* ``beam``: Table 1 values replacing the configured ones (every run and the eigen tables);
* ``tip_mass``: ``{position}`` or ``{replace, mass}`` (mass ``replace`` becomes ``mass``) for
  every run with a tip mass and for the critical speeds;
* ``measure``: how a claim is measured (:data:`MEASURES`), on the default runs.

:func:`reading_case` maps (reading, base case) to the generated case ``reading-<reading>--<case>``
(None when the reading leaves the case alone, so that the default run is reused);
:func:`evaluate_reading` evaluates the reading's claims with the functions of
:mod:`hubbeam.paper.claims` on those runs. Readings never touch the default results.
"""

from __future__ import annotations

import copy
import dataclasses
import json
import math
from collections.abc import Mapping

import numpy as np
import xarray as xr

from hubbeam.configuration.load import ConfigError
from hubbeam.configuration.schema import Problem
from hubbeam.configuration.sections import Reading
from hubbeam.configuration.settings import Case, Eigen, Numerics, Settings, simulation_settings
from hubbeam.model.beam import CONFIG_FIELDS
from hubbeam.model.eigen import critical_speed
from hubbeam.model.eigen import table2 as eigen_table2
from hubbeam.model.frozen import thaw
from hubbeam.model.parameters import TipMass
from hubbeam.paper import claims as claim_defs
from hubbeam.paper import tables
from hubbeam.paper.tables import read_csv_rows
from hubbeam.reporting.products import PAPER_PRODUCTS
from hubbeam.results import measures
from hubbeam.results.reader import maneuver_value, variable
from hubbeam.simulation.simulate import simulate

CHANGE_KINDS = ("case", "maneuver", "beam", "tip_mass", "measure")
#: samples per second of the tables that carry a generated maneuver
TABLE_RATE = 20.0


class ReadingError(ValueError):
    """A reading is malformed (names the key, the value and what is allowed)."""


# --- generated maneuvers ------------------------------------------------------------------------

def _eq43_as_printed(maneuver):
    """Eq. (43) exactly as printed, ``wf/tf - (wf/2 pi) sin(2 pi t/tf)`` up to ``tf`` and ``wf``
    after (note 1), as a speed table; the run starts from rest, so the rate rises to ``wf/tf``
    within the first sample interval."""
    wf, tf = maneuver["wf"], maneuver["tf"]
    t = np.linspace(0.0, tf, int(round(tf * TABLE_RATE)) + 1)
    speed = wf / tf - wf / (2 * math.pi) * np.sin(2 * math.pi * t / tf)
    speed[0] = 0.0
    return {"kind": "speed_table", "time": [*t.tolist(), tf + 1.0 / TABLE_RATE],
            "speed": [*speed.tolist(), wf]}


def _torque_table(maneuver, shape):
    tf = maneuver["tf"]
    t = np.linspace(0.0, tf, int(round(tf * TABLE_RATE)) + 1)
    torque = maneuver["tau_max"] * shape(t / tf)
    torque[-1] = 0.0
    return {"kind": "torque_table", "time": [*t.tolist(), tf + 1.0 / TABLE_RATE],
            "torque": [*torque.tolist(), 0.0]}


#: name -> (maneuver kind it applies to, function of that maneuver -> new maneuver)
MANEUVER_READINGS = {
    "eq43_as_printed": ("prescribed", _eq43_as_printed),
    # Eq. (44) with T = 2 tf: a half sine, net angular impulse 2 tau_m tf / pi (note 8)
    "torque_half_sine": ("torque", lambda m: _torque_table(m, lambda s: np.sin(math.pi * s))),
    # a versine pulse tau_m (1 - cos(2 pi t/tf)) / 2: smooth at both ends, one-signed (note 8)
    "torque_versine": ("torque", lambda m: _torque_table(
        m, lambda s: 0.5 * (1.0 - np.cos(2 * math.pi * s)))),
}


# --- measure variants -----------------------------------------------------------------------------

def _axial_with_foreshortening(results):
    case, ds = results.run("fig06", model="FOAM")
    axial = variable(case, ds, "tip_axial").values + variable(case, ds, "tip_foreshortening").values
    return measures.peak(variable(case, ds, "tip_transverse").values) / measures.peak(axial)


def _late_residual(case, ds, delay):
    """Largest ``|v(L)|`` over ``t > tf + delay``; NaN when the run ends before that."""
    t, y = claim_defs.residual(case, ds)
    return measures.residual_amplitude(t, y, maneuver_value(case, ds, "tf") + delay)


def _ratio_after_settling(results):
    tlam, foam = results.run("fig05", model="TLAM", wf=2.8), results.run("fig05", model="FOAM", wf=2.8)
    return _late_residual(*tlam, 10.0) / _late_residual(*foam, 10.0)


def _ratio_of_fits(results):
    tlam, foam = results.run("fig05", model="TLAM", wf=2.8), results.run("fig05", model="FOAM", wf=2.8)
    return claim_defs.residual_fit(*tlam).amplitude / claim_defs.residual_fit(*foam).amplitude


def _reduction_of_peaks(results):
    sfoam = claim_defs.residual_amplitude(*results.run("fig08", model="SFOAM", tau_max=200.0))
    foam = claim_defs.residual_amplitude(*results.run("fig08", model="FOAM", tau_max=200.0))
    return 100.0 * (1.0 - sfoam / foam)


#: name -> {claim id: function of the results replacing that claim's compute}
MEASURES = {
    "axial_with_foreshortening": {"transverse_axial_ratio_wf5": _axial_with_foreshortening},
    "residual_after_settling": {"residual_ratio_tlam_foam_wf2p8": _ratio_after_settling},
    "residual_fitted_amplitude": {"residual_ratio_tlam_foam_wf2p8": _ratio_of_fits},
    "residual_peak_amplitude": {"sfoam_amplitude_reduction_tau200": _reduction_of_peaks},
}


# --- readings as data ---------------------------------------------------------------------------

def check_reading(reading: Reading) -> None:
    """Raise :class:`ReadingError` unless ``reading`` has one known change and known claims."""
    where = f"readings.{reading.name}"
    if reading.change not in CHANGE_KINDS:
        raise ReadingError(f"{where}.change: got {reading.change!r}; allowed: a mapping with exactly one of "
                           f"{', '.join(CHANGE_KINDS)}")
    known = {claim.id for claim in claim_defs.claims()}
    if not reading.claims:
        raise ReadingError(f"{where}.claims: got []; allowed: a non-empty list of claim ids of claims.csv")
    unknown = [k for k, cid in enumerate(reading.claims) if cid not in known]
    if unknown:
        raise ReadingError(f"{where}.claims[{unknown[0]}]: got {reading.claims[unknown[0]]!r}; allowed: a claim id of "
                           "claims.csv")
    kind, value = change_of(reading)
    named = {"maneuver": MANEUVER_READINGS, "measure": MEASURES}.get(kind)
    if named is not None and value not in named:
        raise ReadingError(f"{where}.change.{kind}: got {value!r}; allowed: {', '.join(named)}")
    if kind == "measure":
        missing = [cid for cid in reading.claims if cid not in MEASURES[value]]
        if missing:
            raise ReadingError(f"{where}.claims: measure {value!r} does not define "
                               f"{', '.join(missing)}; allowed: {', '.join(MEASURES[value])}")


def change_of(reading: Reading) -> tuple[str, object]:
    """The kind of the reading's change and what it changes to."""
    return reading.change, reading.value


def _merge(base: dict, override: Mapping) -> dict:
    out = copy.deepcopy(base)
    for key, value in override.items():
        out[key] = _merge(out[key], value) if isinstance(value, Mapping) and isinstance(out.get(key), dict) \
            else copy.deepcopy(value)
    return out


def _matches(case: Case, where: Mapping) -> bool:
    fields = {"model": case.model, "kind": case.maneuver.kind, "modes": case.modes}
    return all(fields.get(key) == value for key, value in where.items())


def generated_name(reading: str, case: str) -> str:
    return f"reading-{reading}--{case}"


def reading_case(reading: Reading, base: Case, settings: Settings) -> Case | None:
    """The case of ``reading`` generated from the ``base`` case of ``settings``, or None when
    the reading leaves that run unchanged (the default run is then the reading's run). A generated
    case is checked as any case of a configuration (``ConfigError``)."""
    kind, value = change_of(reading)
    plain = base.to_dict()
    new = copy.deepcopy(plain)
    if kind == "case" and _matches(base, reading.where):
        new = _merge(new, thaw(value))
    elif kind == "maneuver":
        applies_to, generate = MANEUVER_READINGS[value]
        if base.maneuver.kind == applies_to:
            new["maneuver"] = generate(plain["maneuver"])
    elif kind == "tip_mass" and base.tip_mass.mass > 0.0:
        new["tip_mass"] = _tip(value, base.tip_mass.mass, base.tip_mass.position)
    if new == plain and kind != "beam":
        return None
    new["name"] = generated_name(reading.name, base.name)
    try:
        return simulation_settings(new, settings.numerics, settings.beam.L)[0]
    except ConfigError as error:  # a generated case's problem is the reading's change's
        generated = f"cases.{new['name']}"
        change = f"readings.{reading.name}.change.{kind}"
        raise ConfigError([Problem(problem.path.replace(generated, change, 1), problem.text)
                           if isinstance(problem, Problem) else problem for problem in error.problems]) from None


def _tip(change: Mapping, mass: float, position: float) -> dict:
    """Tip mass under a ``tip_mass`` change: ``position`` moves every tip mass, ``mass`` replaces
    the mass ``replace``."""
    if "mass" in change and math.isclose(mass, change["replace"]):
        mass = change["mass"]
    return {"mass": float(mass), "position": float(change.get("position", position))}


def reading_beam(reading: Reading, beam):
    """The beam under the reading (changed only by a ``beam`` change of Table 1 values, given by
    their configuration keys)."""
    kind, value = change_of(reading)
    if kind != "beam":
        return beam
    return dataclasses.replace(beam, **{CONFIG_FIELDS[key]: float(number) for key, number in value.items()})


def claim_products(claim_ids) -> list[str]:
    """The paper products (figure or table keys) whose runs the claims read."""
    by_id = {claim.id: claim for claim in claim_defs.claims()}
    keys = {by_id[cid].source.split()[0] for cid in claim_ids}
    return sorted(key for key in keys if key in PAPER_PRODUCTS)


def reading_cases(settings: Settings, reading: Reading) -> dict[str, Case | None]:
    """``{base case: generated case or None}`` over the runs the claims of ``reading`` read (the
    reading is checked first, :func:`check_reading`)."""
    check_reading(reading)
    bases = sorted({case for key in claim_products(reading.claims)
                    for case in PAPER_PRODUCTS[key].cases})
    return {case: reading_case(reading, settings.case(case), settings) for case in bases}


# --- evaluation ---------------------------------------------------------------------------------

class ReadingResults(claim_defs.Results):
    """The default results, with the reading's runs and eigen tables in place of the defaults."""

    def __init__(self, simulations, table2_csv, critical_speeds_csv, runs, eigen=None):
        super().__init__(simulations, table2_csv, critical_speeds_csv)
        self._open.update(runs)
        self.paths.update({case: None for case in runs})
        self.eigen = eigen  # None: the default tables; else dict(params, tip, n_modes, ...)

    def table2(self):
        if self.eigen is None:
            return super().table2()
        e = self.eigen
        return eigen_table2(e["params"], e["speed"], e["n_modes"], e["n_quad"]).to_dict("records")

    def critical_speed(self, model_name, mass):
        if self.eigen is None:
            return super().critical_speed(model_name, mass)
        e = self.eigen
        tip = TipMass(**_tip(e["tip_mass"], float(mass), e["params"].L))
        return critical_speed(model_name, e["params"], tip, e["n_modes"], e["search_max"], e["n_quad"])


def as_base(ds, base: Case):
    """``ds`` labelled as the run it stands for: the ``base`` case's maneuver and tip mass attributes
    (which the claims select runs by), the reading's own under ``reading_maneuver`` and
    ``reading_tip_mass_kg``."""
    out = ds.copy()
    out.attrs.update(reading_maneuver=ds.attrs["maneuver"], reading_tip_mass_kg=ds.attrs["tip_mass_kg"],
                     maneuver=json.dumps(base.maneuver.to_dict()), tip_mass_kg=base.tip_mass.mass)
    return out


def _eigen_settings(reading: Reading, beam, numerics: Numerics, eigen: Eigen) -> dict | None:
    kind, value = change_of(reading)
    modes = value.get("modes") if kind == "case" and "model" not in reading.where else None
    if kind not in ("beam", "tip_mass") and modes is None:
        return None
    return {"params": reading_beam(reading, beam), "tip_mass": value if kind == "tip_mass" else {},
            "n_modes": modes or numerics.modes, "n_quad": numerics.quadrature_points,
            "speed": eigen.table2_speed, "search_max": eigen.critical_speed_search_max}


@dataclasses.dataclass(frozen=True)
class ReadingRuns:
    """What a reading's job needs besides the files: the reading, its base cases and the cases it
    generates from them (None: the base run is reused), the beam and the numerics and eigen
    settings of the configuration (:func:`reading_runs`)."""

    name: str
    reading: Reading
    bases: Mapping[str, Case]
    generated: Mapping[str, Case | None]
    beam: object
    numerics: Numerics
    eigen: Eigen


def reading_runs(settings: Settings, reading: Reading) -> ReadingRuns:
    """The :class:`ReadingRuns` of ``reading`` of ``settings`` (checked: :func:`reading_cases`)."""
    generated = reading_cases(settings, reading)
    return ReadingRuns(reading.name, reading, {base: settings.case(base) for base in generated}, generated,
                       settings.beam, settings.numerics, settings.eigen)


def evaluate_reading(runs_of: ReadingRuns, simulations: Mapping, table2_csv,
                     critical_speeds_csv) -> tuple[list[dict], dict]:
    """Claim rows of the reading (:func:`hubbeam.paper.claims.evaluate` on its runs) and its runs
    ``{generated name: dataset}``; ``simulations`` are the default runs by case name."""
    reading = runs_of.reading
    params = reading_beam(reading, runs_of.beam)
    numerics = dataclasses.replace(runs_of.numerics, convergence_check=None)
    runs, by_base = {}, {}
    for base, case in runs_of.generated.items():
        if case is not None:
            runs[case.name] = simulate(case, params, numerics)
            by_base[base] = as_base(runs[case.name], runs_of.bases[base])
    results = ReadingResults(simulations, table2_csv, critical_speeds_csv, by_base,
                             _eigen_settings(reading, runs_of.beam, runs_of.numerics, runs_of.eigen))
    selected = [claim for claim in claim_defs.claims() if claim.id in reading.claims]
    kind, value = change_of(reading)
    if kind == "measure":
        selected = [dataclasses.replace(claim, compute=MEASURES[value][claim.id]) for claim in selected]
    return claim_defs.evaluate(results, selected, strict=False), runs


# --- the matrix claim x reading -------------------------------------------------------------------

READING_COLUMNS = ("reading", "id", "unit", "paper", "default", "computed", "rel_diff", "tolerance",
                   "verdict")


def reading_rows(name: str, rows: list[dict], default_rows: Mapping[str, Mapping]) -> list[dict]:
    """Claim rows of reading ``name`` with the reading's name and the default computed value."""
    return [{"reading": name, "default": default_rows[row["id"]]["computed"],
             **{key: row[key] for key in READING_COLUMNS if key in row}} for row in rows]


def write_rows(rows: list[dict], path) -> None:
    """The rows as csv (empty cell for NaN or None)."""
    tables.write_rows(rows, path, READING_COLUMNS)


def read_rows(path) -> list[dict]:
    return read_csv_rows(path, ("paper", "default", "computed", "rel_diff", "tolerance"))


def matrix(rows: list[dict], readings: Mapping[str, Reading]) -> xr.Dataset:
    """The claims x readings matrix (CF attributes): computed value, relative difference to the
    print and verdict flag of each claim under each reading that recomputes it (NaN / -1 where the
    reading does not)."""
    claim_ids = [claim.id for claim in claim_defs.claims() if any(r["id"] == claim.id for r in rows)]
    names = list(readings)
    shape = (len(claim_ids), len(names))
    computed, rel, flag = np.full(shape, np.nan), np.full(shape, np.nan), np.full(shape, -1, np.int8)
    paper, default = np.full(len(claim_ids), np.nan), np.full(len(claim_ids), np.nan)
    units = [""] * len(claim_ids)
    for row in rows:
        i, j = claim_ids.index(row["id"]), names.index(row["reading"])
        computed[i, j], rel[i, j] = row["computed"], row["rel_diff"]
        flag[i, j] = VERDICT_FLAGS.index(row["verdict"])
        paper[i], default[i], units[i] = row["paper"], row["default"], row["unit"]
    dims = ("claim", "reading")
    flags = {"flag_values": np.arange(len(VERDICT_FLAGS), dtype=np.int8),
             "flag_meanings": " ".join(flag.replace(" ", "_") for flag in VERDICT_FLAGS), "_FillValue": np.int8(-1)}
    return xr.Dataset(
        {"computed": (dims, computed, {"long_name": "claim value computed under the reading"}),
         "rel_diff": (dims, rel, {"long_name": "(computed - paper) / |paper|", "units": "1"}),
         "verdict": (dims, flag, {"long_name": "verdict of the claim under the reading", **flags}),
         "paper": ("claim", paper, {"long_name": "value printed in the paper"}),
         "default": ("claim", default, {"long_name": "claim value under the default reading"})},
        coords={"claim": ("claim", claim_ids, {"long_name": "claim id of claims.csv"}),
                "unit": ("claim", units, {"long_name": "unit of the claim's values (paper, default, computed)"}),
                "reading": ("reading", names, {"long_name": "alternative reading (config readings)"}),
                "why": ("reading", [readings[n].why for n in names],
                        {"long_name": "the changed interpretation"})},
    )


#: verdict flags of the matrix (index = flag value)
VERDICT_FLAGS = ("agrees", "differs", "qualitative", claim_defs.NOT_COMPUTABLE)
