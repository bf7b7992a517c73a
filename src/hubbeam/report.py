"""The paper's quantitative claims checked against our results, and the reproduction report.

Every computed value comes from a result file (simulation datasets, ``table2.csv``,
``critical_speeds.csv``); every printed value comes from :mod:`hubbeam.paper`. A claim agrees
when ``|computed - paper| / |paper|`` is within its tolerance (or, for claims that two curves
coincide, when the largest difference relative to the peak is within an absolute tolerance).

Tolerance rule, fixed before any comparison: the precision the paper prints, i.e. half a unit
in the last printed digit relative to the value (2.60 rad/s -> 0.19 %, "about 100" -> 50 %),
never below 0.1 % (Table 1 gives the parameters to five significant figures, so computed
numbers carry ~1e-4 relative uncertainty before any modelling choice).

Measures (documented in the report):
- peak: ``max |x(t)|`` over the run, NaN samples after a divergence ignored;
- residual vibration: the tip deflection for ``t > t_f`` (after the maneuver or torque pulse);
  its amplitude is ``max |v(L, t)|`` over ``t > t_f``;
- phase and amplitude of a residual vibration: least-squares fit of
  ``c + A cos(omega (t - t_f) + phi)``; ``omega`` starts at the peak of the Hann-windowed,
  zero-padded spectrum and is refined by minimising the fit residual within one spectral bin;
  ``phi`` is the phase at ``t = t_f``. A positive ``phi_SFOAM - phi_FOAM`` (wrapped to (-pi, pi])
  means SFOAM leads.
"""

from __future__ import annotations

import base64
import csv
import html
import math
import os
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.optimize
import xarray as xr

from hubbeam import __version__, paper
from hubbeam.io import open_result
from hubbeam.plotting.figures import (cases_for, diverged_at, maneuver, maneuver_value, model,
                                      n_modes, select, tip_mass, variable)
from hubbeam.tables import read_csv_rows, table3_rows

CLAIM_COLUMNS = ("id", "claim", "unit", "paper", "computed", "rel_diff", "tolerance", "verdict",
                 "source")


class ClaimInputError(LookupError):
    """A claim needs a result that the given files do not contain (names what is missing)."""


# --- measures -----------------------------------------------------------------------------------

def peak(values) -> float:
    """``max |x|`` ignoring NaN (samples after a divergence)."""
    return float(np.nanmax(np.abs(np.asarray(values, dtype=float))))


def residual(case: str, ds: xr.Dataset, name: str = "tip_transverse") -> tuple[np.ndarray, np.ndarray]:
    """Times and values of ``name`` after the maneuver (``t > t_f``), finite samples only."""
    tf = maneuver_value(case, ds, "tf")
    t = ds["time"].values
    y = variable(case, ds, name).values
    keep = (t > tf) & np.isfinite(y)
    if keep.sum() < 4:
        t_div = diverged_at(case, ds)
        why = f"the run diverged at t = {t_div:g} s" if t_div is not None else "the run ends too early"
        raise ClaimInputError(f"case {case!r}: fewer than 4 samples of {name} after t_f = {tf} s ({why})")
    return t[keep], y[keep]


def residual_amplitude(case: str, ds: xr.Dataset, name: str = "tip_transverse") -> float:
    """Residual vibration amplitude: ``max |x(t)|`` over ``t > t_f``."""
    return peak(residual(case, ds, name)[1])


@dataclass(frozen=True)
class SinusoidFit:
    """``offset + amplitude * cos(omega * (t - t0) + phase)``."""

    amplitude: float
    omega: float
    phase: float
    offset: float
    t0: float


def _linear_fit(s, y, omega):
    basis = np.column_stack([np.ones_like(s), np.cos(omega * s), np.sin(omega * s)])
    coef, *_ = np.linalg.lstsq(basis, y, rcond=None)
    return coef, float(np.sum((basis @ coef - y) ** 2))


def fit_sinusoid(t, y, t0: float) -> SinusoidFit:
    """Least-squares sinusoid at the dominant frequency of ``y(t)`` (uniform ``t``), phase at ``t0``."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    dt = np.diff(t)
    if len(t) < 8 or not np.allclose(dt, dt[0], rtol=1e-6, atol=0):
        raise ValueError("fit_sinusoid needs at least 8 samples on a uniform time grid")
    s = t - t0
    pad = 8 * len(y)
    spectrum = np.abs(np.fft.rfft((y - y.mean()) * np.hanning(len(y)), pad))
    frequencies = np.fft.rfftfreq(pad, dt[0])
    omega0 = 2 * np.pi * frequencies[1 + np.argmax(spectrum[1:])]
    half_width = 2 * np.pi / (len(y) * dt[0])  # one bin of the unpadded spectrum
    best = scipy.optimize.minimize_scalar(
        lambda w: _linear_fit(s, y, w)[1], method="bounded",
        bounds=(max(omega0 - half_width, 1e-12), omega0 + half_width), options={"xatol": 1e-12})
    (c, a, b), _ = _linear_fit(s, y, best.x)
    # a cos + b sin = R cos(w s + phi) with R = hypot(a, b), phi = atan2(-b, a)
    return SinusoidFit(float(np.hypot(a, b)), float(best.x), float(np.arctan2(-b, a)), float(c), t0)


def wrap_phase(angle: float) -> float:
    """Angle in (-pi, pi]."""
    wrapped = math.remainder(angle, 2 * math.pi)
    return math.pi if wrapped == -math.pi else wrapped


def residual_fit(case: str, ds: xr.Dataset) -> SinusoidFit:
    """Sinusoid fitted to the residual tip deflection, phase referred to ``t = t_f``."""
    t, y = residual(case, ds)
    return fit_sinusoid(t, y, maneuver_value(case, ds, "tf"))


def max_relative_difference(a: tuple[str, xr.Dataset], b: tuple[str, xr.Dataset],
                            name: str = "tip_transverse") -> float:
    """``max |x_a - x_b| / max |x_b|`` on the time grid of ``b`` (``a`` interpolated)."""
    (case_a, ds_a), (case_b, ds_b) = a, b
    xa = variable(case_a, ds_a, name).interp(time=ds_b["time"]).values
    xb = variable(case_b, ds_b, name).values
    return peak(xa - xb) / peak(xb)


# --- inputs -------------------------------------------------------------------------------------

class Results:
    """The result files the claims read: simulation datasets by case name, and the eigen tables."""

    def __init__(self, simulations: Mapping[str, str | Path], table2_csv=None, critical_speeds_csv=None):
        self.paths = {case: Path(path) for case, path in simulations.items()}
        self.table2_csv = table2_csv
        self.critical_speeds_csv = critical_speeds_csv
        self._open: dict[str, xr.Dataset] = {}

    def dataset(self, case: str) -> xr.Dataset:
        if case not in self._open:
            self._open[case] = open_result(self.paths[case])
        return self._open[case]

    def group(self, key: str) -> dict[str, xr.Dataset]:
        return {case: self.dataset(case) for case in cases_for(key, self.paths)}

    def run(self, key: str, **criteria) -> tuple[str, xr.Dataset]:
        """The run of figure ``key`` matching ``criteria`` (the one with most modes if several)."""
        matches = select(self.group(key), **criteria)
        if not matches:
            raise ClaimInputError(f"no {key} case with {criteria}; cases: {cases_for(key, self.paths)}")
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
                                   "Hz", value, f"{value:.4f}", compute, "results/tables/table2.csv"))
    return claims


def _critical_claims():
    claims = []
    for mass, value in paper.CRITICAL_SPEEDS_TLAM.items():
        where = "without tip mass" if mass == 0 else f"with m_t = {mass:g} kg at the tip"
        claims.append(_numeric(
            f"critical_speed_tlam_mt{mass:g}".replace(".", "p"), f"TLAM critical angular velocity {where}",
            "rad s-1", value, f"{value:.2f}", lambda r, m=mass: r.critical_speed("TLAM", m),
            "results/tables/critical_speeds.csv"))

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
                 lambda r: peak(variable(*tlam28(r), "tip_transverse")), "fig05 TLAM 2.8 rad/s"),
        _numeric("peak_tip_foam_wf2p8", "Peak tip deflection of FOAM at w_f = 2.8 rad/s", "m",
                 p.PEAK_TIP_DEFLECTION_WF2P8["FOAM"], "0.22",
                 lambda r: peak(variable(*foam28(r), "tip_transverse")), "fig05 FOAM 2.8 rad/s"),
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
    tf = maneuver_value(case, ds, "tf")
    values = variable(case, ds, name)
    late = values.where(ds["time"] > tf)
    return peak(late.values) / peak(values.values)


def _ratio_of_peaks(case, ds, numerator, denominator):
    return peak(variable(case, ds, numerator).values) / peak(variable(case, ds, denominator).values)


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
    return wrap_phase(sfoam.phase - foam.phase)


def _amplitude_reduction(results, tau):
    sfoam, foam = _residual_fits(results, tau)
    return 100.0 * (1.0 - sfoam.amplitude / foam.amplitude)


def claims() -> list[Claim]:
    """Every quantitative claim of Section 4, in the order of the paper's tables and figures."""
    return _table2_claims() + _critical_claims() + _simulation_claims()


def evaluate(results: Results, selected: list[Claim] | None = None) -> list[dict]:
    """One row per claim; a claim whose input is missing raises (no empty computed value)."""
    rows = []
    for claim in selected or claims():
        computed = float(claim.compute(results))
        if not math.isfinite(computed):
            raise ClaimInputError(f"claim {claim.id}: computed value is {computed} ({claim.source})")
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
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)

    def cell(value):
        if value is None or (isinstance(value, float) and math.isnan(value)):
            return ""
        return repr(value) if isinstance(value, float) else str(value)

    with path.open("w", newline="") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(CLAIM_COLUMNS)
        for row in rows:
            writer.writerow([cell(row[c]) for c in CLAIM_COLUMNS])
    return path


NUMERIC_CLAIM_COLUMNS = ("paper", "computed", "rel_diff", "tolerance")


def read_claims(path) -> list[dict]:
    """Rows of ``claims.csv`` with the numeric columns as floats (empty: NaN), the rest as text."""
    return read_csv_rows(path, NUMERIC_CLAIM_COLUMNS)


# --- the reproduction report --------------------------------------------------------------------

@dataclass(frozen=True)
class FigureText:
    """What the paper shows in a figure, and what ours shows (own words)."""

    title: str
    paper: str
    ours: str
    claims: tuple[str, ...] = ()  # claim ids discussed with the figure


FIGURE_TEXT = {
    "fig03": FigureText(
        "Fig. 3: high-order terms of CFOAM",
        "The terms that distinguish CFOAM from FOAM, evaluated for a one-mode model during the spin-up "
        "to 3 rad/s; the paper finds them small and fading after the 30 s maneuver.",
        "Each panel is one difference CFOAM minus FOAM evaluated along the CFOAM trajectory (case "
        "fig03_cfoam_n1, 1 mode): the rotary inertia M_thth, the generalised force of the "
        "hub equation, and the generalised forces of the axial (q1) and transverse (q2) equations "
        "(note 5; derivation in docs/cfoam.md).",
        ("cfoam_terms_small_after_tf",)),
    "fig04": FigureText(
        "Fig. 4: CFOAM against FOAM",
        "Tip deflection of CFOAM and FOAM for the spin-up to 3 rad/s; the paper calls them identical.",
        "Panel (a) overlays both 5-mode runs, panel (b) shows their difference, so that 'identical' "
        "becomes a number (claim below).",
        ("cfoam_foam_coincide_wf3",)),
    "fig05": FigureText(
        "Fig. 5: TLAM against FOAM",
        "Transverse and axial tip response of TLAM and FOAM at 2.8 and 3.5 rad/s: TLAM diverges above "
        "about 3 rad/s and overshoots FOAM strongly at 2.8 rad/s (0.49 m against 0.22 m, residual "
        "vibration about 100 times larger).",
        "Columns are the two final speeds: panels (a), (b) the transverse tip deflection, (c), (d) "
        "the pure axial deformation w1(L) (note 11). A diverged run is drawn until it stops and "
        "labelled with its divergence time.",
        ("tlam_diverges_wf3p5", "foam_bounded_wf3p5", "peak_tip_tlam_wf2p8", "peak_tip_foam_wf2p8",
         "residual_ratio_tlam_foam_wf2p8")),
    "fig06": FigureText(
        "Fig. 6: modal responses and mode count (FOAM, 5 rad/s)",
        "The five transverse modal coordinates during the spin-up to 5 rad/s (the first two dominate) "
        "and the axial tip response for different numbers of modes (identical); the transverse peak is "
        "about 1500 times the axial one.",
        "Panel (a): q2_i of the 5-mode run, modes normalised to unit modal mass (note 7), so q2_i is in "
        "kg^1/2 m; panel (b): w1(L) for n = 1, 3, 5.",
        ("transverse_axial_ratio_wf5", "first_two_modes_dominate_wf5", "axial_same_for_n1_n5")),
    "fig07": FigureText(
        "Fig. 7: inertia torque Q_theta under the torque pulse",
        "Q_theta for a 400 N m torque pulse; its largest value, 2.62 N m, is called a small "
        "disturbance ('about 6.5 %' of the torque, note 9: the ratio is 0.65 %).",
        "Panel (a) is the paper's figure; panel (b) shows Q_theta relative to the torque amplitude for "
        "all four torque cases (the numbers behind Table 3).",
        ("table3_tau400", "q_theta_percent_of_tau400")),
    "fig08": FigureText(
        "Fig. 8: SFOAM against FOAM under the torque pulse",
        "Tip deflection of FOAM and SFOAM at 50 and 200 N m: nearly equal at 50 N m; at 200 N m the "
        "residual vibration of SFOAM leads FOAM's by 0.45 rad with a 24 % smaller amplitude, and "
        "SFOAM with one mode equals SFOAM with five.",
        "One panel per torque amplitude; FOAM solid, SFOAM dashed (5 modes) and dotted (1 mode). "
        "Residual vibration is the response after the pulse (t > t_f = 10 s).",
        ("sfoam_foam_close_tau50", "sfoam_phase_lead_tau200", "sfoam_amplitude_reduction_tau200",
         "sfoam_n1_equals_n5_tau200")),
    "fig09": FigureText(
        "Fig. 9: dominant eigenvalue of K22",
        "The sign of the lowest eigenvalue of TLAM's stiffness K22 against the tip-mass position, for "
        "0.1 and 0.5 kg; the critical speeds are 2.91 rad/s (mass on the hub), 2.60 and 1.91 rad/s "
        "(mass at the tip).",
        "The hub speed of the printed curves is not stated (note 10): we show the dominant eigenvalue "
        "over position and speed and mark where it crosses zero; eigenvalues depend on the unit modal "
        "mass normalisation (note 7).",
        ("critical_speed_tlam_mt0", "critical_speed_tlam_mt0p1", "critical_speed_tlam_mt0p5",
         "tip_mass_lowers_tlam_critical_speed", "foam_no_critical_speed")),
    "fig10": FigureText(
        "Fig. 10: TLAM with a tip mass at 2 rad/s",
        "TLAM tip deflection with 0.1 and 0.5 kg at the beam tip for a spin-up to 2 rad/s: with 0.5 kg "
        "(critical speed 1.91 rad/s) TLAM fails, while without tip mass TLAM and FOAM nearly agree.",
        "One panel per tip mass, each with TLAM and FOAM (note 12 for the settings).",
        ("tlam_fails_mt0p5_wf2", "tlam_foam_close_mt0_wf2")),
    "campbell": FigureText(
        "Beyond the paper: Campbell diagram",
        "Not in the paper; Table 2 is one vertical slice of it (1 rad/s).",
        "Frequencies of TLAM and FOAM against hub speed: TLAM's first frequency reaches zero at the "
        "critical speed, FOAM's rises with speed (dynamic stiffening).",
        ("table2_tlam_softens_foam_stiffens",)),
    "critical_map": FigureText(
        "Beyond the paper: critical speed over tip mass and position",
        "Not in the paper, which quotes three points of it.",
        "TLAM's critical speed for every tip mass and position of the eigen grid (FOAM has none).",
        ("critical_speed_equals_omega1",)),
    "convergence": FigureText(
        "Beyond the paper: convergence in the number of modes",
        "The paper uses five modes throughout and shows, for the axial response only, that fewer give "
        "the same result.",
        "Tip deflection and the dominant residual frequency of the FOAM spin-up to 5 rad/s with 1, 3 "
        "and 5 modes.",
        ()),
}

#: how we filled each gap of the transcribed paper (REPRODUCTION_NOTES numbers), in our words
GAPS = (
    (1, "The maneuver law (Eq. 43) is printed without the linear term of the hub rate; we restore it, "
        "so the hub accelerates smoothly from rest and reaches w_f at t_f with zero acceleration."),
    (2, "Two coupling entries of the mass matrix (Eqs. 27, 28) are printed as one line; we take both "
        "from the kinetic energy (theta-q1 coupling -q2'R', theta-q2 coupling V2 + q1'R)."),
    (3, "The journal exchanged the captions of Tables 2 and 3; our tables are titled by their "
        "content (frequencies in Table 2, inertia torque in Table 3)."),
    (4, "The Appendix writes the beam length where the tip-mass position belongs; we use the position "
        "l throughout, which coincides with the paper for its tip mass at the beam end."),
    (5, "The CFOAM correction terms (Eqs. 35-39) cannot be read reliably; CFOAM is derived again from the "
        "exact kinetic energy and checked to reduce to FOAM when the cubic and quartic terms are "
        "dropped. Fig. 3 therefore plots differences CFOAM minus FOAM of our own derivation."),
    (6, "The assumed modes are not stated; the natural-frequency row of Table 2 identifies clamped-free "
        "beam eigenfunctions for the transverse and fixed-free rod modes for the axial deformation."),
    (7, "No mode normalisation is given; we scale every mode to unit modal mass. Only the modal "
        "coordinates (Fig. 6a) and the K22 eigenvalues (Fig. 9) depend on this choice."),
    (8, "The period T of the torque pulse (Eq. 44) is not defined; we take T = t_f = 10 s, one full sine "
        "period with zero net angular impulse (a rest-to-rest pulse), and no torque afterwards."),
    (9, "Table 3 is not monotonic in the torque and the text misstates 2.62/400 as 6.5 %; we print our "
        "values beside the printed ones and judge each separately."),
    (10, "Fig. 9 does not state the hub speed; we show the lowest K22 eigenvalue over speed and "
         "position and mark the critical speeds instead of guessing one speed."),
    (11, "'Transverse displacement' is the tip deflection v(L) in the rotating frame; the axial "
         "response we plot is the pure axial deformation w1(L), which fits the factor of about 1500."),
    (12, "Unstated run settings: spin-ups with t_f = 30 s over 50 s, torque pulses with t_f = 10 s "
         "over 20 s, five modes unless a case says otherwise, tip masses of 0.1 and 0.5 kg at the beam "
         "end for Fig. 10."),
)

#: our own choices where the paper is silent (beyond the notes)
OWN_CHOICES = (
    "Residual vibration means the response after the maneuver (t > t_f); its amplitude is the largest "
    "|v(L)| there. Phase and amplitude of the residual vibration come from a least-squares sinusoid at "
    "the dominant frequency (spectral peak refined by minimising the residual), with the phase taken at "
    "t = t_f.",
    "Agreement is judged at the precision the paper prints (half a unit in the last printed digit, at "
    "least 0.1 %); claims that two curves coincide use the largest difference relative to the peak "
    "and agree when it is at most 1 %.",
    "A run is stopped and flagged as diverged when the tip deflection exceeds the configured multiple "
    "of the beam length; its figures show it until then.",
    "Table 2 and the critical speeds are those of the transverse stiffness K22 of Eq. 31 at constant "
    "hub speed (see hubbeam.eigen).",
)


#: context for a claim that differs, shown only when it does (own words; notes by number)
DIFFERENCE_NOTES = {
    "q_theta_percent_of_tau400": "2.62 N m is 0.655 % of 400 N m, so the printed percentage cannot hold "
                                 "even for the paper's own torque value (note 9).",
    "table3_tau50": "As printed, Table 3 falls from 100 to 200 N m (note 9); with the exponent -1 instead "
                    "of -2 at 200 N m (0.372 N m) the column would rise with the torque, which suggests a "
                    "misprint there.",
    "critical_speed_tlam_mt0p5": "The critical-speed figure marks the exact value of the continuum "
                                 "cantilever with the same tip mass; compare it with the printed number.",
    "transverse_axial_ratio_wf5": "The ratio depends on which axial quantity is meant; we use the pure "
                                  "axial deformation w1(L) (note 11).",
    "sfoam_phase_lead_tau200": "Our SFOAM is FOAM without the axial coordinates and without Q_theta "
                               "(Eq. 40); its distance from FOAM measures how much those terms matter "
                               "under the torque pulse.",
}
for _key, _source in (("table3_tau100", "table3_tau50"), ("table3_tau200", "table3_tau50"),
                      ("table3_tau400", "table3_tau50"),
                      ("sfoam_amplitude_reduction_tau200", "sfoam_phase_lead_tau200")):
    DIFFERENCE_NOTES[_key] = DIFFERENCE_NOTES[_source]


def _format(value, digits=4) -> str:
    if value is None or value == "" or (isinstance(value, float) and math.isnan(value)):
        return "-"
    if isinstance(value, float):
        return f"{value:.{digits}g}"
    return str(value)


def _md_cell(text: str) -> str:
    return str(text).replace("|", "\\|")


def claims_markdown(rows: list[dict]) -> str:
    lines = ["| id | claim | unit | paper | computed | rel. diff. | verdict |",
             "|---|---|---|---:|---:|---:|---|"]
    for row in rows:
        rel = row.get("rel_diff")
        rel_text = "-" if rel in ("", None) or (isinstance(rel, float) and math.isnan(rel)) else f"{100 * rel:+.2f} %"
        lines.append(f"| `{row['id']}` | {_md_cell(row['claim'])} | {row['unit']} | {_format(row['paper'])} | "
                     f"{_format(row['computed'])} | {rel_text} | **{row['verdict']}** |")
    return "\n".join(lines)


def runs_markdown(datasets: Mapping[str, xr.Dataset]) -> str:
    """The settings of every simulation run, read from the datasets' attributes."""
    lines = ["| case | model | n | maneuver | t_end (s) | tip mass (kg) at l (m) | diverged at (s) | steps |",
             "|---|---|---:|---|---:|---|---:|---:|"]
    for case, ds in sorted(datasets.items()):
        man = maneuver(case, ds)
        law = ", ".join(f"{k} = {v:g}" if isinstance(v, (int, float)) else f"{k} = {v}" for k, v in man.items())
        t_div = diverged_at(case, ds)
        mass = tip_mass(case, ds)
        where = f"{mass:g} at {float(ds.attrs['tip_position_m']):g}" if mass else "none"
        lines.append(f"| {case} | {model(case, ds)} | {n_modes(case, ds)} | {law} | "
                     f"{float(ds['time'].values[-1]):g} | {where} | {'-' if t_div is None else f'{t_div:.2f}'} | "
                     f"{ds.attrs.get('n_steps', '-')} |")
    return "\n".join(lines)


#: the validation section when the config has no `validation` section (nothing was run)
NO_VALIDATION = ("## Validation\n\nThe configuration of this run has no `validation` section, so the "
                 "independent validation (`docs/validation.md`) was not run.\n")


def reproduction_markdown(claim_rows: list[dict], figures: Mapping[str, str | Path],
                          tables: Mapping[str, str | Path], datasets: Mapping[str, xr.Dataset],
                          numerics: Mapping, report_dir, validation=None) -> str:
    """The reproduction report (Markdown), figures linked relative to ``report_dir``.

    ``validation`` is the :class:`hubbeam.validation.report.Section` of the published-table
    validation (its summary sentence joins the report's summary), or None when the configuration
    has no ``validation`` section.
    """
    report_dir = Path(report_dir)
    by_id = {row["id"]: row for row in claim_rows}
    counts = {v: sum(r["verdict"] == v for r in claim_rows) for v in ("agrees", "differs", "qualitative")}
    commits = sorted({str(ds.attrs.get("git_commit", "unknown")) for ds in datasets.values()})
    out = [
        "# Reproduction of Bai et al. (2009), *A Study on Dynamic Stiffening of a Rotating Beam with a Tip Mass*",
        "",
        f"Generated by hubbeam {__version__} from the result files only; simulations from git commit(s) "
        f"{', '.join(f'`{c}`' for c in commits)}. Integrator: Radau IIA, rtol = {numerics.get('rtol')}, "
        f"atol = {numerics.get('atol')}, output every {numerics.get('output_step')} s, "
        f"{numerics.get('quadrature_points')} Gauss points.",
        "",
        "## Summary",
        "",
        f"{len(claim_rows)} claims checked: **{counts['agrees']} agree**, **{counts['differs']} differ**, "
        f"{counts['qualitative']} are qualitative (the number is shown, no tolerance applies). "
        "Numbers that differ are reported as they are; the model is never adjusted toward the printed values.",
        "",
    ]
    if validation is not None:
        out += [validation.summary, ""]
    differing = [row for row in claim_rows if row["verdict"] == "differs"]
    if differing:
        out += ["Claims that differ:", ""]
        for row in differing:
            note = DIFFERENCE_NOTES.get(row["id"], "")
            unit = "" if row["unit"] == "1" else f" {row['unit']}"
            out.append(f"- `{row['id']}`: paper {_format(row['paper'])}{unit}, computed "
                       f"{_format(row['computed'])}{unit}. {note}".rstrip())
        out.append("")
    out += [
        "## Tables",
        "",
    ]
    for name in sorted(tables):
        out += [Path(tables[name]).read_text().strip(), ""]
    out += ["## Figures", ""]
    for key, text in FIGURE_TEXT.items():
        if key not in figures:
            continue
        link = Path(os.path.relpath(Path(figures[key]).resolve(), report_dir.resolve())).as_posix()
        out += [f"### {text.title}", "", f"**Paper.** {text.paper}", "", f"**This study.** {text.ours}", "",
                f"![{text.title}]({link})", ""]
        listed = [by_id[c] for c in text.claims if c in by_id]
        if listed:
            out += [claims_markdown(listed), ""]
    out += ["## All claims", "", claims_markdown(claim_rows), ""]
    out += [validation.markdown if validation is not None else NO_VALIDATION]
    out += ["## How the gaps of the paper were filled", "",
            "Numbers refer to the notes in REPRODUCTION_NOTES.md.", ""]
    out += [f"{number}. {text}" for number, text in GAPS]
    out += ["", "Further choices of this reproduction:", ""]
    out += [f"- {text}" for text in OWN_CHOICES]
    out += ["", "## Simulation runs", "", runs_markdown(datasets), ""]
    return "\n".join(out)


# --- Markdown to self-contained HTML (the subset the report uses) -------------------------------

_INLINE = (
    (re.compile(r"`([^`]+)`"), r"<code>\1</code>"),
    (re.compile(r"\*\*(.+?)\*\*"), r"<strong>\1</strong>"),
    (re.compile(r"(?<![\w*])\*(?!\s)(.+?)(?<!\s)\*(?![\w*])"), r"<em>\1</em>"),
    (re.compile(r"\[([^\]]+)\]\(([^)\s]+)\)"), r'<a href="\2">\1</a>'),
)
_IMAGE = re.compile(r"^!\[([^\]]*)\]\(([^)\s]+)\)$")
_CSS = ("body{font-family:sans-serif;max-width:60rem;margin:2rem auto;padding:0 1rem;line-height:1.45}"
        "table{border-collapse:collapse;margin:1rem 0;font-size:.9rem}"
        "th,td{border:1px solid #ccc;padding:.25rem .5rem;vertical-align:top}th{background:#f2f2f2}"
        "td.r{text-align:right}figure{margin:1rem 0}img{max-width:100%}"
        "figcaption{font-size:.9rem;color:#444}code{background:#f5f5f5;padding:0 .2rem}")


def _inline(text: str) -> str:
    text = html.escape(text, quote=False)
    # code spans first, protected from the other patterns
    codes = []

    def stash(match):
        codes.append(f"<code>{match.group(1)}</code>")
        return f"\0{len(codes) - 1}\0"

    text = _INLINE[0][0].sub(stash, text)
    for pattern, replacement in _INLINE[1:]:
        text = pattern.sub(replacement, text)
    return re.sub(r"\0(\d+)\0", lambda m: codes[int(m.group(1))], text)


def _split_row(line: str) -> list[str]:
    cells = re.split(r"(?<!\\)\|", line.strip().strip("|"))
    return [cell.strip().replace("\\|", "|") for cell in cells]


def _image_html(alt: str, src: str, base: Path) -> str:
    path = (base / src).resolve()
    if not path.is_file():
        raise FileNotFoundError(f"report image {path} (linked as {src!r}) does not exist")
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    mime = "image/png" if path.suffix.lower() == ".png" else "image/svg+xml"
    return (f'<figure><img alt="{html.escape(alt)}" src="data:{mime};base64,{data}">'
            f"<figcaption>{_inline(alt)}</figcaption></figure>")


def markdown_to_html(markdown: str, base_dir, title: str = "hubbeam reproduction report") -> str:
    """Self-contained HTML of ``markdown``: headings, paragraphs, lists, pipe tables and images
    (embedded as base64, paths relative to ``base_dir``)."""
    base = Path(base_dir)
    body: list[str] = []
    lines = markdown.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i].rstrip()
        if not line:
            i += 1
        elif line.startswith("#"):
            level = len(line) - len(line.lstrip("#"))
            body.append(f"<h{level}>{_inline(line[level:].strip())}</h{level}>")
            i += 1
        elif _IMAGE.match(line):
            body.append(_image_html(*_IMAGE.match(line).groups(), base))
            i += 1
        elif line.startswith("|"):
            block = []
            while i < len(lines) and lines[i].startswith("|"):
                block.append(lines[i])
                i += 1
            header, rule, rows = _split_row(block[0]), _split_row(block[1]), block[2:]
            right = [cell.endswith(":") for cell in rule]
            cells = "".join(f"<th>{_inline(c)}</th>" for c in header)
            out = [f"<table><thead><tr>{cells}</tr></thead><tbody>"]
            for row in rows:
                tds = "".join(f'<td{" class=r" if right[k] else ""}>{_inline(c)}</td>'
                              for k, c in enumerate(_split_row(row)))
                out.append(f"<tr>{tds}</tr>")
            body.append("".join(out) + "</tbody></table>")
        elif re.match(r"^(- |\d+\. )", line):
            ordered = not line.startswith("- ")
            items = []
            while i < len(lines) and re.match(r"^(- |\d+\. )", lines[i]):
                items.append(re.sub(r"^(- |\d+\. )", "", lines[i]))
                i += 1
            tag = "ol" if ordered else "ul"
            body.append(f"<{tag}>" + "".join(f"<li>{_inline(it)}</li>" for it in items) + f"</{tag}>")
        else:
            paragraph = [line.strip()]
            i += 1
            while i < len(lines) and lines[i].strip() and not re.match(r"^(#|\||- |\d+\. |!\[)", lines[i]):
                paragraph.append(lines[i].strip())
                i += 1
            body.append(f"<p>{_inline(' '.join(paragraph))}</p>")
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>{html.escape(title)}</title><style>{_CSS}</style></head><body>\n"
            + "\n".join(body) + "\n</body></html>\n")
