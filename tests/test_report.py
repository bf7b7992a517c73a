"""Tables, claims and the reproduction report, on contract datasets with known content."""

from __future__ import annotations

import csv
import dataclasses
import functools
import math
import re
from pathlib import Path

import numpy as np
import pytest
from synthetic_results import run_script, write_eigen, write_simulations, write_validation

from hubbeam.api import load
from hubbeam.model import printed as paper
from hubbeam.paper.claims import (
    CLAIM_COLUMNS,
    ClaimInputError,
    Results,
    claims,
    evaluate,
    printed_tolerance,
    read_claims,
    write_claims,
)
from hubbeam.paper.report import reproduction_markdown
from hubbeam.paper.tables import Column, Table, table1, table2, table3, to_latex, to_markdown, write_table
from hubbeam.reporting.document import markdown_to_html
from hubbeam.reporting.products import PAPER_PRODUCTS
from hubbeam.results.io import ResultFileError, open_result
from hubbeam.validation.report import ValidationInputError, published_section, validation_markdown


@functools.cache
def paper_settings():
    """The paper's checked settings (their numerics are what the reproduction report prints)."""
    return load("config/config.yaml").settings

#: residual vibration after the torque pulse: FOAM (amplitude, omega, phase at t_f) and an SFOAM
#: that leads it by 0.45 rad with a 24 % smaller amplitude (the paper's statement, as input)
FOAM_RESIDUAL = (0.05, 2.6, 0.3)
SFOAM_RESIDUAL = (0.05 * 0.76, 2.6, 0.3 + 0.45)


@pytest.fixture(scope="module")
def results_dir(tmp_path_factory):
    root = tmp_path_factory.mktemp("results")
    sims = write_simulations(root / "simulations", dt=0.05, overrides={
        "tab3_foam_tau200": {"residual": FOAM_RESIDUAL},
        "fig08_sfoam_tau200": {"residual": SFOAM_RESIDUAL},
        "fig05_tlam_wf2p8": {"residual": (0.30, 2.9, 0.0)},
        "fig05_foam_wf2p8": {"residual": (0.003, 2.9, 0.0)},
    })
    eigen = write_eigen(root, n_modes=5, n_quad=24)
    return root, sims, eigen


@pytest.fixture(scope="module")
def results(results_dir):
    _, sims, eigen = results_dir
    return Results(sims, eigen["table2"], eigen["critical_speeds_csv"])


@pytest.fixture(scope="module")
def claim_rows(results):
    return evaluate(results)


def by_id(rows):
    return {row["id"]: row for row in rows}


# --- tolerances ------------------------------------------------------------------------------------

@pytest.mark.parametrize("printed, tolerance", [("2.60", 0.005 / 2.6), ("1.91", 0.005 / 1.91),
                                                ("100", 0.5), ("1500", 50 / 1500), ("0.45", 0.005 / 0.45),
                                                ("0.4635", 1e-3), ("6.24e-03", 1e-3), ("2.62e+00", 0.005 / 2.62)])
def test_tolerance_is_the_printed_precision(printed, tolerance):
    assert printed_tolerance(printed) == pytest.approx(tolerance)


# --- claims --------------------------------------------------------------------------------------

def test_claims_csv_has_every_claim_and_no_empty_computed_value(claim_rows, tmp_path):
    path = write_claims(claim_rows, tmp_path / "claims.csv")
    with path.open(newline="") as handle:
        reader = csv.DictReader(handle)
        assert tuple(reader.fieldnames) == CLAIM_COLUMNS
        rows = list(reader)
    assert [row["id"] for row in rows] == [claim.id for claim in claims()]
    assert len({row["id"] for row in rows}) == len(rows)
    for row in rows:
        assert row["computed"] != "" and math.isfinite(float(row["computed"])), row["id"]
        assert row["verdict"] in ("agrees", "differs", "qualitative")
        if row["verdict"] != "qualitative":
            assert row["tolerance"] != "" and row["paper"] != ""


def test_every_printed_number_has_a_claim(claim_rows):
    papers = {row["paper"] for row in claim_rows}
    printed = [*paper.TABLE3.values(), *paper.CRITICAL_SPEEDS_TLAM.values(),
               *[v for values in paper.TABLE2.values() for v in values],
               *paper.PEAK_TIP_DEFLECTION_WF2P8.values(), paper.RESIDUAL_RATIO_TLAM_FOAM_WF2P8,
               paper.TRANSVERSE_AXIAL_PEAK_RATIO_WF5, paper.SFOAM_PHASE_LEAD_RAD_TAU200,
               paper.SFOAM_AMPLITUDE_REDUCTION_PERCENT_TAU200, paper.Q_THETA_PERCENT_OF_TAU_MAX_400]
    assert set(printed) <= papers


def test_phase_lead_and_amplitude_reduction_are_measured_from_the_residual(claim_rows):
    rows = by_id(claim_rows)
    assert rows["sfoam_phase_lead_tau200"]["computed"] == pytest.approx(0.45, abs=1e-6)
    assert rows["sfoam_amplitude_reduction_tau200"]["computed"] == pytest.approx(24.0, abs=1e-4)
    assert rows["sfoam_phase_lead_tau200"]["verdict"] == "agrees"
    assert rows["sfoam_amplitude_reduction_tau200"]["verdict"] == "agrees"


def test_residual_ratio_and_divergence_flags_come_from_the_datasets(claim_rows, results):
    rows = by_id(claim_rows)
    # residual amplitudes 0.30 and 0.003 (sampled at 0.05 s, so peaks within 1 % of them)
    assert rows["residual_ratio_tlam_foam_wf2p8"]["computed"] == pytest.approx(100.0, rel=0.02)
    assert rows["tlam_diverges_wf3p5"]["computed"] == 1.0
    assert rows["foam_bounded_wf3p5"]["computed"] == 0.0
    assert rows["tlam_fails_mt0p5_wf2"]["computed"] == 1.0


def test_table_claims_read_the_eigen_tables(claim_rows, results):
    rows = by_id(claim_rows)
    table2_rows = results.table2()
    assert rows["table2_foam_f3"]["computed"] == table2_rows[2]["FOAM"]
    assert rows["critical_speed_tlam_mt0p5"]["computed"] == results.critical_speed("TLAM", 0.5)
    assert rows["critical_speed_tlam_mt0p5"]["paper"] == paper.CRITICAL_SPEEDS_TLAM[0.5]


def test_verdict_follows_the_tolerance(claim_rows):
    for row in claim_rows:
        if row["verdict"] == "qualitative":
            continue
        if math.isnan(row["rel_diff"]):  # absolute claims: curves coincide
            within = abs(row["computed"] - row["paper"]) <= row["tolerance"]
        else:
            assert row["rel_diff"] == pytest.approx((row["computed"] - row["paper"]) / abs(row["paper"]))
            within = abs(row["rel_diff"]) <= row["tolerance"]
        assert row["verdict"] == ("agrees" if within else "differs"), row["id"]


def test_a_claim_without_its_run_fails_naming_what_is_missing(results_dir):
    _, sims, eigen = results_dir
    partial = {case: path for case, path in sims.items() if not case.startswith("fig08_sfoam_tau200")}
    results = Results(partial, eigen["table2"], eigen["critical_speeds_csv"])
    wanted = [c for c in claims() if c.id == "sfoam_phase_lead_tau200"]
    with pytest.raises(ClaimInputError, match="fig08 need the run.*fig08_sfoam_tau200, fig08_sfoam_tau200_n1"):
        evaluate(results, wanted)


# --- tables --------------------------------------------------------------------------------------

def test_table1_comes_from_the_config(study_config):
    table = table1(study_config["beam"])
    values = {row["symbol"]: row["value"] for row in table.rows}
    assert values["L"] == study_config["beam"]["length"]
    assert values["J_h"] == study_config["beam"]["hub_inertia"]
    assert values["m_t"] == paper.TABLE1_TIP_MASS
    assert "$J_h$" in to_latex(table)


def test_table3_is_the_largest_q_theta_of_each_foam_torque_run(results_dir):
    _, sims, _ = results_dir
    runs = {c: open_result(sims[c]) for c in PAPER_PRODUCTS["fig08"].cases}  # includes SFOAM runs
    table = table3(runs)
    assert [row["tau_max"] for row in table.rows] == sorted(paper.TABLE3)
    for row in table.rows:
        q = runs[row["case"]]["Q_theta"].values
        assert row["max_abs_Q_theta"] == np.nanmax(np.abs(q))
        assert row["paper"] == paper.TABLE3[row["tau_max"]]
        assert row["percent_of_tau_max"] == pytest.approx(100 * row["max_abs_Q_theta"] / row["tau_max"])


def test_table_writers_round_trip_and_escape(tmp_path):
    table = Table("Table 9", "A caption with 50 % & an_underscore.",
                  (Column("x", "|x| (m)", "$|x|$ (m)", 3), Column("name", "Name", "Name", None)),
                  ({"x": 1.23456789e-7, "name": "a_b"}, {"x": float("nan"), "name": "c"}))
    csv_path, md_path, tex_path = write_table(table, tmp_path / "table9.csv")
    assert csv_path.read_text().splitlines() == ["x,name", "1.23456789e-07,a_b", ",c"]
    md = md_path.read_text()
    assert "| \\|x\\| (m) | Name |" in md and "| 1.23×10^-7 | a_b |" in md and "| - | c |" in md
    tex = tex_path.read_text()
    assert "50 \\% \\& an\\_underscore" in tex and "$1.23\\times10^{-7}$ & a\\_b \\\\" in tex
    assert to_markdown(table) == md and to_latex(table) == tex


def test_table2_renders_the_eigen_csv(results_dir, tmp_path):
    _, _, eigen = results_dir
    table = table2(eigen["table2"], 1.0)
    assert [row["mode"] for row in table.rows] == [1, 2, 3, 4, 5]
    assert "Table 3's caption" in table.caption
    assert "FOAM (1 rad/s), paper" in to_markdown(table)


# --- the report ----------------------------------------------------------------------------------

def test_report_scripts_write_claims_markdown_and_html(results_dir, tmp_path):
    root, sims, eigen = results_dir
    cases = sorted(sims)
    claims_csv = tmp_path / "report" / "claims.csv"
    run_script("hubbeam.pipeline.jobs.claims:claims", input={"datasets": [str(sims[c]) for c in cases],
                                          "table2": str(eigen["table2"]),
                                          "critical_speeds": str(eigen["critical_speeds_csv"])},
               output={"claims": str(claims_csv)}, params={"cases": cases})
    assert len(read_claims(claims_csv)) == len(claims())
    figures = []
    for key in ("fig04", "fig08"):
        pdf = tmp_path / "figures" / f"{key}.pdf"
        group = list(PAPER_PRODUCTS[key].cases)
        run_script("hubbeam.pipeline.jobs.figures:simulation_figure", input={"datasets": [str(sims[c]) for c in group]},
                   output={"pdf": str(pdf)}, params={"function": PAPER_PRODUCTS[key].function, "cases": group})
        figures.append(str(pdf.with_suffix(".png")))
    table_md = tmp_path / "tables" / "table2.md"
    write_table(table2(eigen["table2"], 1.0), table_md.with_suffix(".csv"), csv=False)
    out = {"markdown": str(tmp_path / "report" / "reproduction.md"),
           "html": str(tmp_path / "report" / "reproduction.html")}
    run_script("hubbeam.pipeline.jobs.reports:reproduction_report",
               input={"claims": str(claims_csv), "figures": figures, "tables": [str(table_md)],
                      "datasets": [str(sims[c]) for c in cases]},
               output=out, params={"cases": cases, "numerics": dataclasses.replace(
                   paper_settings().numerics, rtol=1e-9, atol=1e-11, output_step=0.05, quadrature_points=64)})
    md = (tmp_path / "report" / "reproduction.md").read_text()
    assert "![Fig. 4: CFOAM against FOAM](../figures/fig04.png)" in md
    assert all(f"\n{n}. " in md for n in range(1, 13))  # every note interpreted
    assert "**Table 2.**" in md and "fig05_tlam_wf3p5" in md
    page = (tmp_path / "report" / "reproduction.html").read_text()
    assert page.count('src="data:image/png;base64,') == 2
    assert all(claim.id in page for claim in claims())
    assert "<table>" in page and "<ol>" in page


def test_markdown_to_html_renders_the_markup_the_reports_use(tmp_path):
    md = ("# Title *x*\n\nSome **bold** `a|b` text\ncontinued.\n\n- one\n- two\n\n1. first\n2. second\n\n"
          "| a | b |\n|---|---:|\n| 1 \\| 2 | 3 |\n")
    page = markdown_to_html(md, tmp_path)
    assert "<h1>Title <em>x</em></h1>" in page
    assert "<p>Some <strong>bold</strong> <code>a|b</code> text\ncontinued.</p>" in page
    assert "<li>one</li>" in page and "<ol>\n<li>first</li>" in page
    assert '<td>1 | 2</td>\n<td style="text-align:right">3</td>' in page
    assert page.startswith("<!DOCTYPE html>") and "<style>" in page
    with pytest.raises(FileNotFoundError, match="missing.png"):
        markdown_to_html("![x](missing.png)\n", tmp_path)


def test_reproduction_report_lists_each_figure_with_its_claims(claim_rows, results_dir, tmp_path):
    _, sims, _ = results_dir
    png = tmp_path / "figures" / "fig05.png"
    png.parent.mkdir()
    png.write_bytes(b"png")
    datasets = {c: open_result(p) for c, p in sims.items()}
    md = reproduction_markdown(claim_rows, {"fig05": png}, {}, datasets, paper_settings().numerics, tmp_path / "report")
    section = md.split("### Fig. 5")[1].split("###")[0]
    assert "../figures/fig05.png" in section
    assert re.search(r"`peak_tip_tlam_wf2p8` \| .* \| m \| 0\.49 \|", section)


# --- the validation sections ---------------------------------------------------------------------

@pytest.fixture(scope="module")
def validation_files(tmp_path_factory):
    return write_validation(tmp_path_factory.mktemp("validation"))


def published(files, report_dir):
    return published_section(files["published"], files["tip_mass"], files["curves"],
                             files["published_figure"], report_dir)


def test_validation_section_counts_verdicts_and_tests_both_readings_of_the_last_digit(
        validation_files):
    section = published(validation_files, validation_files["published"].parent / "report")
    md = section.markdown
    assert "**5 of 6**" in section.summary and "**2 of 2**" in section.summary
    assert md.startswith("## Validation\n")
    # the rounded table: truncation would fail two entries; the truncated one: rounding fails all three
    assert "Wright et al. (1982); Hodges and Rutkowski (1981): read as rounded 3 of 3 agree, read as " \
           "truncated 1 of 3; taken as **rounded**" in md
    assert "Hamza-Cherif and Houmat (2004): read as rounded 0 of 3 agree, read as truncated 2 of 3; " \
           "taken as **truncated**" in md
    assert "flapwise gamma = 6: ours 7.360374, printed 7.3603" in md
    assert "each printed value lying below ours" in md
    assert "rounding our value to the printed decimals reproduces 0, chopping it reproduces 2" in md
    assert "Ours, 7.360374, rounds to 7.3604 and chops to 7.3603." in md
    # the entry that is not reproduced is named, and marked in the table
    assert re.search(r"Entries that do not agree: .*chordwise gamma = 4: printed 3.888, ours 3.900000", md)
    assert re.search(r"\| chordwise \| 4 \| 70 \| 3.888 \| truncated \| 3.900000 \|.*\*\*differs\*\* \|", md)
    # the uncoupled chordwise value comes from rotating_eigen.nc at the row's gamma
    assert re.search(r"\| chordwise \| 8 \| 70 \| 4.6105 \| truncated \| 4.610587 \|"
                     r".*\| 4.6572 \| \*\*agrees\*\* \|", md)
    assert "at gamma = 8 would be 4.6572 against the printed 4.6105" in md
    assert "![Validation" in md and "(../rotating_frequencies.png)" in md
    sources = md.split("### Sources of the published values")[1]
    assert all(name in sources for name in ("Wright", "Hodges", "Hamza-Cherif", "point mass at its free end"))
    assert "snakemake validate" in md and "(validation_exudyn.html)" in md


def test_reproduction_report_carries_the_validation_section_or_says_it_was_not_run(
        claim_rows, results_dir, validation_files, tmp_path):
    _, sims, _ = results_dir
    datasets = {c: open_result(p) for c, p in list(sims.items())[:2]}
    report_dir = validation_files["published"].parent / "report"
    section = published(validation_files, report_dir)
    md = reproduction_markdown(claim_rows, {}, {}, datasets, paper_settings().numerics, report_dir, validation=section)
    summary = md.split("## Summary")[1].split("## Tables")[0]
    assert section.summary in summary
    assert md.index("## All claims") < md.index("## Validation") < md.index("## How the gaps")
    page = markdown_to_html(md, report_dir)
    assert page.count('src="data:image/png;base64,') == 1 and "<h2>Validation</h2>" in page
    without = reproduction_markdown(claim_rows, {}, {}, datasets, paper_settings().numerics, tmp_path)
    assert "## Validation\n\nThe configuration of this run has no `validation` section" in without


def test_a_missing_or_incomplete_validation_file_is_a_clear_error(validation_files, tmp_path):
    files = dict(validation_files, published=tmp_path / "results" / "published_comparison.csv")
    with pytest.raises(ResultFileError, match=r"published_comparison.csv does not exist; build it with "
                                              r"`snakemake .*published_comparison.csv`"):
        published(files, tmp_path)
    broken = tmp_path / "tip_mass_comparison.csv"
    broken.write_text("\n".join(line.rsplit(",", 1)[0] for line in
                                validation_files["tip_mass"].read_text().splitlines()) + "\n")
    with pytest.raises(ValidationInputError, match=r"tip_mass_comparison.csv: missing column\(s\) agrees"):
        published(dict(validation_files, tip_mass=broken), tmp_path)
    with pytest.raises(ResultFileError, match=r"exudyn_comparison.csv does not exist.*snakemake validate"):
        validation_markdown(tmp_path, validation_files["ritz_fe"], exudyn={
            "comparison": tmp_path / "exudyn_comparison.csv", "mode_study": validation_files["mode_study"],
            "convergence": validation_files["convergence"], "figure": validation_files["exudyn_figure"]})
    with pytest.raises(ResultFileError, match=r"nonuniform_ritz_fe.csv does not exist.*snakemake validate"):
        validation_markdown(tmp_path, tmp_path / "nonuniform_ritz_fe.csv")


def test_exudyn_report_states_the_key_findings_computed_from_the_tables(validation_files, tmp_path):
    out = {"markdown": str(tmp_path / "report" / "validation_exudyn.md"),
           "html": str(tmp_path / "report" / "validation_exudyn.html")}
    (tmp_path / "report").mkdir()
    run_script("hubbeam.pipeline.jobs.reports:validation_report", input={
        "comparison": str(validation_files["comparison"]), "figure": str(validation_files["exudyn_figure"]),
        "mode_study": str(validation_files["mode_study"]), "convergence": str(validation_files["convergence"]),
        "ritz_fe": str(validation_files["ritz_fe"]), "pybmodes": str(validation_files["pybmodes"])},
        output=out)
    md = Path(out["markdown"]).read_text()
    # FOAM: 2e-5 / 0.15 and 1e-4 / 0.30 of the peak; residual ratios 1.001 and 0.998
    assert "**FOAM** stays within 0.033 % of the reference's peak tip deflection in all 2 bounded cases" in md
    assert "residual vibration amplitude is within 0.2 % of the reference's" in md
    # CFOAM: 5e-5 / 2e-5 and 3e-4 / 1e-4
    assert "is 2.5 to 3 times FOAM's (2 cases), at most 0.1 % of the peak" in md
    assert "in every case further from the geometrically exact beam than FOAM" in md
    assert ("at w_f = 2 rad/s its peak is 1.20 times the reference's and its residual amplitude 3.7 times; "
            "diverges at w_f = 3 rad/s, m_t = 0.5 kg (t = 27.6 s)") in md
    assert "from 5 to 10 modes the largest difference from the reference changes by FOAM 5.3 % to 9.1 % (2 cases)" in md
    assert "at most 8e-07 m, 25 times below FOAM's smallest difference" in md
    assert re.search(r"\| spin_b \| TLAM \| - \| - \| - \| 0.3 \| - \| 0.002 \| 27.60 \|", md)
    assert "| 16 | yes | 1e-07 |" in md
    page = Path(out["html"]).read_text()
    assert "<title>hubbeam validation against independent models</title>" in page
    assert 'src="data:image/png;base64,' in page
    # the non-uniform checks: the largest |ritz / fe - 1| per case and mode count, pyBModes's bounds
    assert "| bare | 0 | 0.004 | 2e-05 |" in md and "| tip_mass | 4.5 | 0.01 | 0.0003 |" in md
    assert "with 20 modes at most 0.0003" in md
    assert "(observed orders 1.9 to 1.99;" in md
    assert "within 2e-06 and with our finite elements within 5e-07 (relative, 2 frequencies" in md


def test_validation_report_without_exudyn_or_pybmodes_has_the_ritz_check_only(validation_files, tmp_path):
    md = validation_markdown(tmp_path, validation_files["ritz_fe"])
    assert "Geometrically exact reference" not in md and "exudyn_comparison.csv" not in md
    assert "## Non-uniform beam" in md and "| bare | 0 | 0.004 | 2e-05 |" in md
    assert "**pyBModes** is not run: the beam is clamped on the hub axis" in md
