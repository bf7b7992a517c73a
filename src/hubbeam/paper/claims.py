"""The paper's quantitative claims, evaluated against our results, and the claims.csv file.

Every computed value comes from a result file (simulation datasets, ``table2.csv``,
``critical_speeds.csv``); every printed value comes from :mod:`hubbeam.model.printed`. The runs of a claim
are those of the paper's product (figure or table) it belongs to (:data:`hubbeam.reporting.products.PAPER_PRODUCTS`);
the measures (peak, residual amplitude, fitted sinusoid, phase lead) are those of :mod:`hubbeam.results.measures`.
A claim agrees when ``|computed - paper| / |paper|`` is within its tolerance (or, for claims that two
curves coincide, when the largest difference relative to the peak is within an absolute tolerance).

Tolerance rule, fixed before any comparison: the precision the paper prints, i.e. half a unit
in the last printed digit relative to the value (2.60 rad/s -> 0.19 %, "about 100" -> 50 %),
never below 0.1 % (Table 1 gives the parameters to five significant figures, so computed
numbers carry ~1e-4 relative uncertainty before any modelling choice).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr

from hubbeam.model import printed as paper
from hubbeam.paper.tables import read_csv_rows, table3_rows, write_rows
from hubbeam.reporting.products import PAPER_PRODUCTS, Product
from hubbeam.results import measures
from hubbeam.results.io import open_result
from hubbeam.results.paths import SHARED
from hubbeam.results.reader import diverged_at, maneuver_value, n_modes, select, times, variable

CLAIM_COLUMNS = ("id", "claim", "unit", "paper", "computed", "rel_diff", "tolerance", "verdict",
                 "source")


class ClaimInputError(LookupError):
    """A claim needs a result that the given files do not contain (names what is missing)."""

# --- measures of a run -------------------------------------------------------------------------

def residual(case: str, ds: xr.Dataset, name: str = "tip_transverse") -> tuple[np.ndarray, np.ndarray]:
    """Times and values of ``name`` after the maneuver (``t > t_f``), finite samples only."""
    tf = maneuver_value(case, ds, "tf")
    t, y = measures.after(times(ds), variable(case, ds, name).values, tf)
    if len(t) < 4:
        t_div = diverged_at(case, ds)
        why = f"the run diverged at t = {t_div:g} s" if t_div is not None else "the run ends too early"
        raise ClaimInputError(f"case {case!r}: fewer than 4 samples of {name} after t_f = {tf} s ({why})")
    return t, y


def residual_amplitude(case: str, ds: xr.Dataset, name: str = "tip_transverse") -> float:
    """Residual vibration amplitude: ``max |x(t)|`` over ``t > t_f``."""
    return measures.peak(residual(case, ds, name)[1])


def residual_fit(case: str, ds: xr.Dataset) -> measures.SinusoidFit:
    """Sinusoid fitted to the residual tip deflection, phase referred to ``t = t_f``."""
    t, y = residual(case, ds)
    return measures.fit_sinusoid(t, y, maneuver_value(case, ds, "tf"))


def max_relative_difference(a: tuple[str, xr.Dataset], b: tuple[str, xr.Dataset],
                            name: str = "tip_transverse") -> float:
    """``max |x_a - x_b| / max |x_b|`` on the time grid of ``b`` (``a`` interpolated)."""
    (case_a, ds_a), (case_b, ds_b) = a, b
    xa = variable(case_a, ds_a, name).interp(time=ds_b["time"]).values
    return measures.relative_difference(xa, variable(case_b, ds_b, name).values)


# --- inputs -------------------------------------------------------------------------------------

class Results:
    """The result files the claims read: simulation datasets by case name, and the eigen tables.

    ``products`` give the runs of each figure or table a claim refers to (default: the paper's).
    """

    def __init__(self, simulations: Mapping[str, str | Path], table2_csv=None, critical_speeds_csv=None,
                 products: Mapping[str, Product] = PAPER_PRODUCTS):
        self.paths = {case: Path(path) for case, path in simulations.items()}
        self.table2_csv = table2_csv
        self.critical_speeds_csv = critical_speeds_csv
        self.products = products
        self._open: dict[str, xr.Dataset] = {}

    def dataset(self, case: str) -> xr.Dataset:
        if case not in self._open:
            self._open[case] = open_result(self.paths[case])
        return self._open[case]

    def group(self, key: str) -> dict[str, xr.Dataset]:
        """The runs of product ``key``, by case name (every one must be given)."""
        cases = self.products[key].cases
        missing = [case for case in cases if case not in self.paths]
        if missing:
            raise ClaimInputError(f"the claims of {key} need the run(s) {', '.join(missing)}; "
                                  f"given: {', '.join(sorted(self.paths)) or 'none'}")
        return {case: self.dataset(case) for case in cases}

    def run(self, key: str, **criteria) -> tuple[str, xr.Dataset]:
        """The run of product ``key`` matching ``criteria`` (the one with most modes if several)."""
        matches = select(self.group(key), **criteria)
        if not matches:
            raise ClaimInputError(f"no {key} case with {criteria}; "
                                  f"cases: {', '.join(self.products[key].cases)}")
        return max(matches.items(), key=lambda item: n_modes(*item))

    def table2(self) -> list[dict]:
        return read_csv_rows(self._require(self.table2_csv, "table2.csv"))

    def critical_speed(self, model_name: str, mass: float) -> float:
        """Critical speed (rad/s) of ``model_name`` with ``mass`` at the beam tip, from the csv."""
        rows = read_csv_rows(self._require(self.critical_speeds_csv, "critical_speeds.csv"))
        for row in rows:
            if row["model"] == model_name and math.isclose(row["tip_mass_kg"], mass, abs_tol=1e-12):
                return row["critical_speed_rad_s"]
        raise ClaimInputError(f"{self.critical_speeds_csv}: no row for model {model_name}, tip mass {mass} kg")

    @staticmethod
    def _require(path, name):
        if path is None:
            raise ClaimInputError(f"the claims need {name}; pass its path")
        return path


# --- claims -------------------------------------------------------------------------------------

def printed_tolerance(printed: str, floor: float = 1e-3) -> float:
    """Half a unit in the last printed digit of ``printed``, relative to its value (>= ``floor``)."""
    text = printed.strip().lower()
    mantissa, _, exponent = text.partition("e")
    if "." in mantissa:
        unit = 10.0 ** -len(mantissa.split(".")[1])
    else:  # trailing zeros of an integer are not significant ("100" -> unit 100)
        digits = mantissa.lstrip("-")
        unit = 10.0 ** (len(digits) - len(digits.rstrip("0")))
    unit *= 10.0 ** int(exponent or 0)
    return max(0.5 * unit / abs(float(text)), floor)


@dataclass(frozen=True)
class Claim:
    """A statement of the paper and how to compute it from the results.

    ``kind``: "relative" (|rel_diff| <= tolerance), "absolute" (|computed - paper| <= tolerance,
    for 'the curves coincide': paper = 0) or "qualitative" (no verdict; the number is shown).
    """

    id: str
    claim: str
    unit: str
    paper: float | None
    tolerance: float | None
    kind: str
    compute: Callable[[Results], float]
    source: str


def _numeric(cid, text, unit, value, printed, compute, source, floor=1e-3):
    tol = printed_tolerance(printed, floor)
    return Claim(cid, f"{text} [agrees within {100 * tol:.2g} %]", unit, value, tol, "relative",
                 compute, source)


def _coincide(cid, text, compute, source, tol=0.01):
    return Claim(cid, f"{text} [max |difference| / peak; agrees if <= {tol:g}]", "1", 0.0, tol,
                 "absolute", compute, source)


def _qualitative(cid, text, unit, compute, source, value=None):
    return Claim(cid, text, unit, value, None, "qualitative", compute, source)


def _table2_claims():
    claims = []
    speed = paper.TABLE2_SPEED
    for row, values in paper.TABLE2.items():
        label = "natural" if row == "natural" else f"{row} at {speed:g} rad/s"
        for i, value in enumerate(values, start=1):
            def compute(results, row=row, i=i):
                line = next((r for r in results.table2() if int(r["mode"]) == i), None)
                if line is None:
                    raise ClaimInputError(f"{results.table2_csv}: no row for mode {i}")
                return line[row]
            claims.append(_numeric(f"table2_{row.lower()}_f{i}", f"Table 2: {label} frequency of mode {i}",
                                   "Hz", value, f"{value:.4f}", compute, SHARED.table("table2", "csv")))
    return claims


def _critical_claims():
    claims = []
    for mass, value in paper.CRITICAL_SPEEDS_TLAM.items():
        where = "without tip mass" if mass == 0 else f"with m_t = {mass:g} kg at the tip"
        claims.append(_numeric(
            f"critical_speed_tlam_mt{mass:g}".replace(".", "p"), f"TLAM critical angular velocity {where}",
            "rad s-1", value, f"{value:.2f}", lambda r, m=mass: r.critical_speed("TLAM", m),
            SHARED.table("critical_speeds", "csv")))

    def ratio(results):
        natural = next(r for r in results.table2() if int(r["mode"]) == 1)["natural"]
        return results.critical_speed("TLAM", 0.0) / (2 * math.pi * natural)

    claims.append(Claim("critical_speed_equals_omega1",
                        "TLAM critical speed (no tip mass) equals the first natural circular frequency: "
                        "ratio [agrees within 0.1 %]", "1", 1.0, 1e-3, "relative", ratio,
                        "critical_speeds.csv, table2.csv"))

    def decreasing(results):
        speeds = [results.critical_speed("TLAM", m) for m in sorted(paper.CRITICAL_SPEEDS_TLAM)]
        return float(all(a > b for a, b in zip(speeds, speeds[1:])))

    claims.append(_qualitative("tip_mass_lowers_tlam_critical_speed",
                               "TLAM critical speed decreases as the tip mass grows (1 = yes)", "1",
                               decreasing, "critical_speeds.csv", 1.0))

    def foam_has_none(results):
        masses = sorted(paper.CRITICAL_SPEEDS_TLAM)
        return float(sum(math.isfinite(results.critical_speed("FOAM", m)) for m in masses))

    claims.append(_qualitative("foam_no_critical_speed",
                               "FOAM's K_q2q2 stays positive definite: number of tip masses with a FOAM "
                               "critical speed in the search range (paper: K_q2q2 can be made positive definite)",
                               "1", foam_has_none, "critical_speeds.csv", 0.0))

    def ordering(results):
        rows = results.table2()[:5]
        return float(all(r["TLAM"] < r["natural"] < r["FOAM"] for r in rows))

    claims.append(_qualitative("table2_tlam_softens_foam_stiffens",
                               "Table 2: TLAM < natural < FOAM frequency for every mode (1 = yes)", "1",
                               ordering, "table2.csv", 1.0))
    return claims


def _simulation_claims():
    p = paper
    tlam28 = lambda r: r.run("fig05", model="TLAM", wf=2.8)  # noqa: E731
    foam28 = lambda r: r.run("fig05", model="FOAM", wf=2.8)  # noqa: E731
    claims = [
        _qualitative("tlam_diverges_wf3p5", "TLAM diverges above 3 rad/s: diverged flag of the "
                     "TLAM run at w_f = 3.5 rad/s (1 = diverged)", "1",
                     lambda r: float(diverged_at(*r.run("fig05", model="TLAM", wf=3.5)) is not None),
                     "fig05 TLAM 3.5 rad/s", 1.0),
        _qualitative("foam_bounded_wf3p5", "FOAM stays bounded at w_f = 3.5 rad/s: diverged flag "
                     "(0 = bounded)", "1",
                     lambda r: float(diverged_at(*r.run("fig05", model="FOAM", wf=3.5)) is not None),
                     "fig05 FOAM 3.5 rad/s", 0.0),
        _numeric("peak_tip_tlam_wf2p8", "Peak tip deflection of TLAM at w_f = 2.8 rad/s", "m",
                 p.PEAK_TIP_DEFLECTION_WF2P8["TLAM"], "0.49",
                 lambda r: measures.peak(variable(*tlam28(r), "tip_transverse")), "fig05 TLAM 2.8 rad/s"),
        _numeric("peak_tip_foam_wf2p8", "Peak tip deflection of FOAM at w_f = 2.8 rad/s", "m",
                 p.PEAK_TIP_DEFLECTION_WF2P8["FOAM"], "0.22",
                 lambda r: measures.peak(variable(*foam28(r), "tip_transverse")), "fig05 FOAM 2.8 rad/s"),
        _numeric("residual_ratio_tlam_foam_wf2p8", "Residual vibration amplitude (t > t_f) TLAM / FOAM "
                 "at w_f = 2.8 rad/s", "1", p.RESIDUAL_RATIO_TLAM_FOAM_WF2P8, "100",
                 lambda r: residual_amplitude(*tlam28(r)) / residual_amplitude(*foam28(r)),
                 "fig05 2.8 rad/s"),
        _coincide("cfoam_foam_coincide_wf3", "CFOAM and FOAM tip deflections coincide at w_f = 3 rad/s",
                  lambda r: max_relative_difference(r.run("fig04", model="CFOAM"), r.run("fig04", model="FOAM")),
                  "fig04"),
        _qualitative("cfoam_terms_small_after_tf", "Fig. 3: the high-order transverse force dQ_q2 is small "
                     "after t_f: max |dQ_q2| for t > t_f / max |dQ_q2| overall", "1",
                     lambda r: _late_share(*r.run("fig03", model="CFOAM"), "dQ_q2"), "fig03"),
        _numeric("transverse_axial_ratio_wf5", "FOAM at w_f = 5 rad/s: peak transverse / peak axial (w1) "
                 "tip response", "1", p.TRANSVERSE_AXIAL_PEAK_RATIO_WF5, "1500",
                 lambda r: _ratio_of_peaks(*r.run("fig06", model="FOAM"), "tip_transverse", "tip_axial"),
                 "fig06 n = 5"),
        _qualitative("first_two_modes_dominate_wf5", "FOAM at w_f = 5 rad/s: share of modes 1-2 in the sum "
                     "of the peak modal amplitudes max |q2_i| (unit modal mass)", "1",
                     lambda r: _leading_share(*r.run("fig06", model="FOAM"), 2), "fig06 n = 5"),
        _coincide("axial_same_for_n1_n5", "Fig. 6b: axial tip response w1(L) with the fewest modes (n = 1) "
                  "equals that with the most (n = 5)",
                  lambda r: max_relative_difference(*_fewest_and_most(r, "fig06"), "tip_axial"), "fig06"),
        _numeric("q_theta_percent_of_tau400", "max |Q_theta| / tau_m at tau_m = 400 N m (the text says "
                 "'about 6.5 %')", "%", p.Q_THETA_PERCENT_OF_TAU_MAX_400, "6.5",
                 lambda r: _table3_value(r, 400.0, "percent_of_tau_max"), "table3"),
    ]
    for tau, value in sorted(p.TABLE3.items()):
        claims.append(_numeric(f"table3_tau{tau:g}", f"Table 3: max |Q_theta| (FOAM) for tau_m = {tau:g} N m",
                               "N m", value, f"{value:.2e}", lambda r, t=tau: _table3_value(r, t, "max_abs_Q_theta"),
                               "table3"))
    claims += [
        _qualitative("sfoam_foam_close_tau50", "SFOAM and FOAM tip deflections almost coincide at "
                     "tau_m = 50 N m: max |difference| / peak", "1",
                     lambda r: max_relative_difference(r.run("fig08", model="SFOAM", tau_max=50.0),
                                                       r.run("fig08", model="FOAM", tau_max=50.0)), "fig08"),
        _numeric("sfoam_phase_lead_tau200", "Residual vibration (t > t_f) at tau_m = 200 N m: phase lead "
                 "of SFOAM over FOAM (least-squares sinusoid, phase at t_f)", "rad",
                 p.SFOAM_PHASE_LEAD_RAD_TAU200, "0.45", lambda r: _phase_lead(r, 200.0), "fig08"),
        _numeric("sfoam_amplitude_reduction_tau200", "Residual vibration at tau_m = 200 N m: SFOAM amplitude "
                 "smaller than FOAM's by (fitted amplitudes)", "%",
                 p.SFOAM_AMPLITUDE_REDUCTION_PERCENT_TAU200, "24", lambda r: _amplitude_reduction(r, 200.0),
                 "fig08"),
        _coincide("sfoam_n1_equals_n5_tau200", "SFOAM with 1 mode reproduces SFOAM with 5 modes at "
                  "tau_m = 200 N m", lambda r: max_relative_difference(
                      r.run("fig08", model="SFOAM", tau_max=200.0, n_modes=1),
                      r.run("fig08", model="SFOAM", tau_max=200.0)), "fig08"),
        _qualitative("tlam_fails_mt0p5_wf2", "TLAM with m_t = 0.5 kg fails at 2 rad/s: diverged flag "
                     "(1 = diverged)", "1",
                     lambda r: float(diverged_at(*r.run("fig10", model="TLAM", tip_mass=0.5)) is not None),
                     "fig10", 1.0),
        _qualitative("tlam_foam_close_mt0_wf2", "Without tip mass TLAM and FOAM almost agree at 2 rad/s: "
                     "max |difference| / peak", "1",
                     lambda r: max_relative_difference(r.run("fig10", model="TLAM", tip_mass=0.0),
                                                       r.run("fig10", model="FOAM", tip_mass=0.0)), "fig10"),
    ]
    return claims


def _fewest_and_most(results, key):
    ordered = sorted(results.group(key).items(), key=lambda item: n_modes(*item))
    return ordered[0], ordered[-1]


def _late_share(case, ds, name):
    return measures.late_share(times(ds), variable(case, ds, name).values,
                               maneuver_value(case, ds, "tf"))


def _ratio_of_peaks(case, ds, numerator, denominator):
    return (measures.peak(variable(case, ds, numerator).values)
            / measures.peak(variable(case, ds, denominator).values))


def _leading_share(case, ds, count):
    peaks = np.nanmax(np.abs(variable(case, ds, "q2").values), axis=0)
    return float(peaks[:count].sum() / peaks.sum())


def _table3_value(results, tau, column):
    rows = table3_rows(results.group("table3"))
    row = next((row for row in rows if math.isclose(row["tau_max"], tau)), None)
    if row is None:
        raise ClaimInputError(f"Table 3 has no FOAM run at tau_max = {tau:g} N m")
    return row[column]


def _residual_fits(results, tau):
    sfoam = residual_fit(*results.run("fig08", model="SFOAM", tau_max=tau))
    foam = residual_fit(*results.run("fig08", model="FOAM", tau_max=tau))
    return sfoam, foam


def _phase_lead(results, tau):
    sfoam, foam = _residual_fits(results, tau)
    return measures.phase_lead(sfoam, foam)


def _amplitude_reduction(results, tau):
    sfoam, foam = _residual_fits(results, tau)
    return 100.0 * (1.0 - sfoam.amplitude / foam.amplitude)


def claims() -> list[Claim]:
    """Every quantitative claim of Section 4, in the order of the paper's tables and figures."""
    return _table2_claims() + _critical_claims() + _simulation_claims()


#: verdict of a claim whose value the runs cannot give (only with ``strict=False``)
NOT_COMPUTABLE = "not computable"


def evaluate(results: Results, selected: list[Claim] | None = None, strict: bool = True) -> list[dict]:
    """One row per claim; a claim whose input is missing, or whose value is not finite, raises
    :class:`ClaimInputError` (no empty computed value), or with ``strict=False`` gets the computed
    value NaN and the verdict :data:`NOT_COMPUTABLE` (an alternative reading whose runs end too
    early for a measure, say)."""
    rows = []
    for claim in selected or claims():
        try:
            computed = float(claim.compute(results))
            if not math.isfinite(computed):
                raise ClaimInputError(f"claim {claim.id}: computed value is {computed} ({claim.source})")
        except ClaimInputError:
            if strict:
                raise
            rows.append({"id": claim.id, "claim": claim.claim, "unit": claim.unit, "paper": claim.paper,
                         "computed": math.nan, "rel_diff": math.nan, "tolerance": claim.tolerance,
                         "verdict": NOT_COMPUTABLE, "source": claim.source})
            continue
        rel = (computed - claim.paper) / abs(claim.paper) if claim.paper else math.nan
        if claim.kind == "relative":
            verdict = "agrees" if abs(rel) <= claim.tolerance else "differs"
        elif claim.kind == "absolute":
            verdict = "agrees" if abs(computed - claim.paper) <= claim.tolerance else "differs"
        else:
            verdict = "qualitative"
        rows.append({"id": claim.id, "claim": claim.claim, "unit": claim.unit, "paper": claim.paper,
                     "computed": computed, "rel_diff": rel if claim.kind == "relative" else math.nan,
                     "tolerance": claim.tolerance, "verdict": verdict, "source": claim.source})
    return rows


def write_claims(rows: list[dict], path) -> Path:
    return write_rows(rows, path, CLAIM_COLUMNS)


NUMERIC_CLAIM_COLUMNS = ("paper", "computed", "rel_diff", "tolerance")


def read_claims(path) -> list[dict]:
    """Rows of ``claims.csv`` with the numeric columns as floats (empty: NaN), the rest as text."""
    return read_csv_rows(path, NUMERIC_CLAIM_COLUMNS)

