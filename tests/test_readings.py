"""Alternative readings (hubbeam.paper.readings) and the conclusions drawn from them (hubbeam.paper.explain).

Each reading must change exactly what it names; a claim the reading does not touch must keep its
default value; the conclusion logic must identify a planted explanation. Expected values come from
the printed formulas (Eqs. 43, 44) or from independent computations, never from our own outputs.
"""

from __future__ import annotations

import copy
import dataclasses
import math
import subprocess
import sys

import numpy as np
import pytest

from hubbeam.configuration.load import load_config
from hubbeam.configuration.sections import Reading
from hubbeam.configuration.settings import from_config
from hubbeam.model.beam import CONFIG_FIELDS
from hubbeam.model.eigen import critical_speed_table, table2
from hubbeam.paper import claims as claim_defs
from hubbeam.paper import explain
from hubbeam.paper.readings import (
    VERDICT_FLAGS,
    ReadingError,
    check_reading,
    evaluate_reading,
    generated_name,
    matrix,
    reading_beam,
    reading_case,
    reading_cases,
    reading_runs,
)
from hubbeam.results.io import write_netcdf
from hubbeam.results.reader import maneuver
from hubbeam.simulation.simulate import simulate


@pytest.fixture(scope="module")
def cfg(repo_root):
    return load_config([repo_root / "config" / "config.yaml"])


@pytest.fixture(scope="module")
def settings(cfg):
    return from_config(cfg)


def _differing_keys(a, b):
    return {key for key in set(a) | set(b) if a.get(key) != b.get(key)}


#: the case keys each change kind may touch (besides the name)
ALLOWED = {"maneuver": {"maneuver"}, "tip_mass": {"tip_mass"}, "beam": set()}


def test_each_reading_changes_exactly_what_it_names(cfg, settings):
    for name, reading in cfg["readings"].items():
        kind, value = next(iter(reading["change"].items()))
        for case, base_case in settings.cases.items():
            new_case = reading_case(Reading.from_dict(name, reading), base_case, settings)
            if kind == "measure":
                assert new_case is None, (name, case)
                continue
            if new_case is None:
                continue
            base, new = base_case.to_dict(), new_case.to_dict()
            assert new["name"] == generated_name(name, case) == f"reading-{name}--{case}"
            changed = _differing_keys(new, base) - {"name"}
            allowed = set(value) if kind == "case" else ALLOWED[kind]
            assert changed <= allowed, (name, case, changed)
            if kind == "case":
                where = reading.get("where", {})
                assert base["model"] == where.get("model", base["model"])
                assert base["maneuver"]["kind"] == where.get("kind", base["maneuver"]["kind"])
                for key, part in value.items():
                    if isinstance(part, dict):  # a partial mapping: only its keys change
                        assert _differing_keys(new[key], base[key]) <= set(part)


def test_beam_reading_replaces_only_its_keys(cfg, settings):
    reading = cfg["readings"]["table1_3sf"]
    beam = reading_beam(Reading.from_dict("table1_3sf", reading), settings.beam)
    changed = {field for field in CONFIG_FIELDS.values() if getattr(beam, field) != getattr(settings.beam, field)}
    assert changed == {CONFIG_FIELDS[key] for key in reading["change"]["beam"]}
    other = cfg["readings"]["modes_3"]
    assert reading_beam(Reading.from_dict("modes_3", other), settings.beam) == settings.beam


def test_case_reading_respects_where(cfg, settings):
    reading = {"change": {"case": {"modes": 1}}, "where": {"model": "SFOAM"}, "claims": ["table3_tau50"],
               "notes": [20], "why": "test"}
    assert reading_case(Reading.from_dict("x", reading), settings.cases["tab3_foam_tau50"], settings) is None
    new = reading_case(Reading.from_dict("x", reading), settings.cases["fig08_sfoam_tau200"], settings)
    assert new.modes == 1 and new.model == "SFOAM"


def test_eq43_as_printed_samples_the_printed_formula(cfg, settings):
    base = settings.cases["fig05_tlam_wf2p8"]
    wf, tf = base.maneuver.wf, base.maneuver.tf
    new = reading_case(Reading.from_dict("eq43_as_printed", cfg["readings"]["eq43_as_printed"]), base, settings)
    table = new.maneuver.to_dict()
    assert table["kind"] == "speed_table"
    t, speed = np.array(table["time"]), np.array(table["speed"])
    inside = (t > 0) & (t <= tf)
    np.testing.assert_allclose(speed[inside], wf / tf - wf / (2 * math.pi) * np.sin(2 * math.pi * t[inside] / tf),
                               rtol=0, atol=1e-12)
    assert speed[0] == 0.0 and speed[-1] == wf and t[-1] > tf


def test_half_sine_pulse_has_the_analytic_impulse(cfg, settings):
    base = settings.cases["tab3_foam_tau200"]
    tau, tf = base.maneuver.tau_max, base.maneuver.tf
    new = reading_case(Reading.from_dict("torque_half_sine", cfg["readings"]["torque_half_sine"]), base, settings)
    t, torque = np.array(new.maneuver.time), np.array(new.maneuver.torque)
    # Eq. (44) with T = 2 tf: the impulse of tau sin(pi t / tf) over [0, tf] is 2 tau tf / pi;
    # the linear table's trapezoid error is below 1e-3 relative at 20 samples per second
    assert np.trapezoid(torque, t) == pytest.approx(2 * tau * tf / math.pi, rel=1e-3)
    assert torque[-1] == 0.0 and np.all(torque[t >= tf] == 0.0)


def test_a_bad_reading_names_the_key(cfg):
    with pytest.raises(ReadingError, match=r"readings\.bad\.change: got 'scale'"):
        check_reading(Reading("bad", change="scale", value=2.0, claims=("table3_tau50",)))
    with pytest.raises(ReadingError, match=r"readings\.bad\.claims"):
        check_reading(Reading.from_dict("bad", {"change": {"case": {"modes": 1}}, "claims": ["no_such_claim"]}))
    with pytest.raises(ReadingError, match=r"readings\.bad\.change\.maneuver: got 'wiggle'"):
        check_reading(Reading.from_dict("bad", {"change": {"maneuver": "wiggle"}, "claims": ["table3_tau50"]}))


@pytest.fixture(scope="module")
def default_files(cfg, settings, tmp_path_factory):
    """Default runs of Fig. 5 and the eigen tables, computed here, and their claim rows."""
    folder = tmp_path_factory.mktemp("defaults")
    params = settings.beam
    sims = {}
    for case in ("fig05_tlam_wf2p8", "fig05_foam_wf2p8", "fig05_tlam_wf3p5", "fig05_foam_wf3p5"):
        sims[case] = write_netcdf(simulate(settings.cases[case], params, settings.numerics), folder / f"{case}.nc")
    modes, quad = cfg["numerics"]["modes"], cfg["numerics"]["quadrature_points"]
    table2(params, cfg["eigen"]["table2_speed"], modes, quad).to_csv(folder / "table2.csv", index=False)
    critical_speed_table(params, cfg["eigen"]["tip_masses"], modes, cfg["eigen"]["critical_speed_search_max"],
                         quad).to_csv(folder / "critical.csv", index=False)
    return sims, folder / "table2.csv", folder / "critical.csv"


def _default_rows(default_files, ids):
    sims, t2, crit = default_files
    results = claim_defs.Results(sims, t2, crit)
    return {row["id"]: row for row in claim_defs.evaluate(results, [c for c in claim_defs.claims() if c.id in ids])}


def test_a_reading_that_leaves_a_claim_alone_gives_its_default_value(cfg, default_files):
    ids = ["peak_tip_tlam_wf2p8", "residual_ratio_tlam_foam_wf2p8", "critical_speed_tlam_mt0p1"]
    cfg = copy.deepcopy(cfg)
    # SFOAM runs only: Fig. 5 is untouched; the 0.5 kg mass only: the 0.1 kg critical speed is untouched
    cfg["readings"] = {
        "sfoam_only": {"change": {"case": {"modes": 1}}, "where": {"model": "SFOAM"}, "claims": ids[:2],
                       "notes": [20], "why": "test"},
        "other_mass": {"change": {"tip_mass": {"replace": 0.5, "mass": 0.05}}, "claims": ids[2:],
                       "notes": [22], "why": "test"},
    }
    settings = from_config(cfg)
    assert all(case is None for case in reading_cases(settings, settings.readings["sfoam_only"]).values())
    default = _default_rows(default_files, ids)
    for reading in settings.readings.values():
        rows, runs = evaluate_reading(reading_runs(settings, reading), *default_files)
        assert runs == {}
        for row in rows:
            assert row["computed"] == pytest.approx(default[row["id"]]["computed"], rel=1e-12)


def test_a_reading_that_changes_a_run_moves_its_claim(cfg, default_files):
    cfg = copy.deepcopy(cfg)
    cfg["readings"] = {"short": {"change": {"case": {"maneuver": {"tf": 20.0}}}, "where": {"kind": "prescribed"},
                                 "claims": ["peak_tip_foam_wf2p8"], "notes": [12], "why": "test"}}
    settings = from_config(cfg)
    (row,), runs = evaluate_reading(reading_runs(settings, settings.readings["short"]), *default_files)
    assert set(runs) == {f"reading-short--{c}" for c in ("fig05_tlam_wf2p8", "fig05_foam_wf2p8",
                                                            "fig05_tlam_wf3p5", "fig05_foam_wf3p5")}
    assert all(maneuver("run", ds)["tf"] == 20.0 for ds in runs.values())
    default = _default_rows(default_files, ["peak_tip_foam_wf2p8"])["peak_tip_foam_wf2p8"]
    # a faster spin-up excites the beam more (the peak grows as tf shrinks toward the first period)
    assert row["computed"] > 1.05 * default["computed"]


# --- the conclusion logic on synthetic numbers ----------------------------------------------------

def _row(cid, paper, computed, tolerance=0.01, reading=None):
    rel = (computed - paper) / abs(paper)
    row = {"id": cid, "paper": paper, "computed": computed, "rel_diff": rel, "tolerance": tolerance,
           "verdict": "agrees" if abs(rel) <= tolerance else "differs"}
    return {**row, "reading": reading} if reading else row


def test_a_planted_reading_is_identified_as_the_explanation():
    default = [_row("a", 2.0, 2.5), _row("b", 10.0, 13.0), _row("c", 1.0, 1.0)]
    trials = [_row("a", 2.0, 2.01, reading="planted"), _row("a", 2.0, 2.3, reading="near"),
              _row("b", 10.0, 10.05, reading="planted"), _row("b", 10.0, 20.0, reading="near")]
    found = {c.claim: c for c in explain.conclusions(default, trials)}
    assert set(found) == {"a", "b"}  # "c" agrees already
    assert found["a"].verdict == explain.EXPLAINED and found["a"].closest == "planted"
    assert found["b"].explaining == ("planted",)
    assert explain.shared_explanations(found.values()) == {"planted": ["a", "b"]}
    effects = explain.side_effects({r["id"]: r for r in default}, trials)
    assert effects["near"] == {"closer": ["a"], "further": ["b"]}


def test_without_an_explaining_reading_the_closest_is_named():
    found = explain.conclude(_row("a", 2.0, 3.0), {"x": _row("a", 2.0, 2.5, reading="x"),
                                                   "y": _row("a", 2.0, 3.5, reading="y")})
    assert found.verdict == explain.UNEXPLAINED and found.closest == "x"
    assert "closest reading x" in found.text


@pytest.mark.parametrize(("printed", "computed", "what"), [
    (0.0372, 0.3721, "exponent off by one"),
    (0.00624, 0.006421, "digits swapped: 0.00642"),
    (4.61e-2, 4.16e-2, "digits swapped: 0.0416"),
])
def test_simple_misprints_are_recognised(printed, computed, what):
    found = explain.conclude(_row("a", printed, computed, tolerance=1e-3), {})
    assert found.verdict == explain.MISPRINT and what in found.text


def test_a_value_far_from_every_misprint_is_not_called_one():
    found = explain.conclude(_row("a", 1.91, 1.9366, tolerance=2.6e-3), {})
    assert found.verdict == explain.UNEXPLAINED


@pytest.mark.workflow
def test_dry_run_plans_every_reading_and_no_default_run_twice(tmp_path, repo_root, cfg):
    command = [sys.executable, "-m", "snakemake", "--snakefile", str(repo_root / "Snakefile"),
               "--directory", str(tmp_path), "--configfile", str(repo_root / "config" / "config.yaml"),
               "--dry-run", "readings"]
    run = subprocess.run(command, cwd=repo_root, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    counts = dict(line.split()[:2] for line in run.stdout.splitlines()
                  if line.strip() and line.split()[0] in ("reading", "simulate", "readings_matrix"))
    assert int(counts["reading"]) == len(cfg["readings"])
    assert int(counts["simulate"]) <= len(cfg["cases"])  # generated runs never go through simulate


def test_matrix_holds_each_reading_s_values_and_nothing_else():
    rows = [{**_row("table3_tau50", 6.24e-3, 6.42e-3, reading="a"), "unit": "N m", "default": 6.4e-3},
            {**_row("table3_tau400", 2.62, 2.0, reading="b"), "unit": "N m", "default": 1.95}]
    ds = matrix(rows, {name: Reading(name, "measure", "residual_after_settling", ("table3_tau50",), why=why)
                       for name, why in (("a", "first"), ("b", "second"))})
    assert list(ds["claim"].values) == ["table3_tau50", "table3_tau400"]
    assert ds["computed"].sel(claim="table3_tau50", reading="a") == 6.42e-3
    assert np.isnan(ds["computed"].sel(claim="table3_tau50", reading="b"))
    assert int(ds["verdict"].sel(claim="table3_tau50", reading="b")) == -1
    assert int(ds["verdict"].sel(claim="table3_tau400", reading="b")) == VERDICT_FLAGS.index("differs")
    assert list(ds["why"].values) == ["first", "second"]


def test_a_claim_the_runs_cannot_give_is_recorded_not_computable_only_when_asked():
    """Strict evaluation (the paper's claims) raises; a reading's evaluation records the claim
    with NaN and the verdict 'not computable' and goes on with the others."""
    def missing(_results):
        raise claim_defs.ClaimInputError("fewer than 4 samples after t_f")

    base = claim_defs.claims()[0]
    broken = dataclasses.replace(base, compute=missing)
    nan = dataclasses.replace(base, compute=lambda _results: math.nan)
    with pytest.raises(claim_defs.ClaimInputError):
        claim_defs.evaluate(None, [broken])
    with pytest.raises(claim_defs.ClaimInputError):
        claim_defs.evaluate(None, [nan])
    rows = claim_defs.evaluate(None, [broken, nan], strict=False)
    assert [row["verdict"] for row in rows] == [claim_defs.NOT_COMPUTABLE] * 2
    assert all(math.isnan(row["computed"]) for row in rows)
