"""Validity flags (hubbeam.model.validity): runs beyond the small-deflection range the models assume are
flagged, a stop at |v(L)| > divergence_limit * L is "left_range" unless the run went beyond the
critical speed of its linearisation ("diverged"), and figures and reports say so."""

from __future__ import annotations

import math

import matplotlib
import pytest
from synthetic_results import case_of

from hubbeam.core import radau
from hubbeam.model import validity
from hubbeam.model.parameters import BeamParameters
from hubbeam.simulation.simulate import simulate

matplotlib.use("Agg")


@pytest.fixture(scope="module")
def paper(_study_config):
    return _study_config, BeamParameters.from_config(_study_config)


def run(paper, name, numerics=None, **changes):
    cfg, params = paper
    case = case_of(cfg, name).to_dict() | changes
    return simulate(case, params, dict(cfg["numerics"], **(numerics or {})))


@pytest.mark.parametrize("name", ["fig05_tlam_wf3p5", "fig10_tlam_mt0p5"])
def test_tlam_beyond_its_critical_speed_diverged(paper, name):
    """TLAM's critical speed is 2.91 rad/s without tip mass (Table 2, Section 4.2) and below
    2 rad/s with 0.5 kg at the tip: K22 of Eq. 31 is indefinite at the final speed."""
    ds = run(paper, name)
    assert ds.attrs["integrator_status"] == "left_range"  # stopped at |v(L)| > L ...
    assert ds.attrs["validity"] == "diverged" and ds.attrs["diverged"] == 1  # ... by unbounded growth
    assert ds.attrs["left_range"] == 0 and ds.attrs["diverged_at_s"] == ds.attrs["stopped_at_s"]
    assert "diverged at t" in ds.attrs["warnings"] and "K22" in ds.attrs["warnings"]


def test_foam_with_a_heavy_tip_mass_is_bounded_but_flagged(paper):
    """FOAM with 10 kg at the tip of the 8 m beam, spun up to 3 rad/s: a bounded response whose
    tip deflection (about 4.3 m) is far outside the small-deflection range."""
    ds = run(paper, "fig04_foam", tip_mass={"mass": 10.0, "position": 8.0})
    assert ds.attrs["integrator_status"] == "success" and ds.attrs["diverged"] == 0
    assert ds.attrs["validity"] == "large_deflection" and ds.attrs["large_deflection"] == 1
    assert 0.4 < ds.attrs["max_deflection_ratio"] < 0.7
    assert "large deflection: max |v(L)|" in ds.attrs["warnings"]


def test_a_bounded_run_stopped_at_the_limit_left_the_range_and_did_not_diverge(paper):
    ds = run(paper, "fig04_foam", numerics={"divergence_limit": 0.3}, tip_mass={"mass": 10.0, "position": 8.0})
    assert ds.attrs["integrator_status"] == "left_range"
    assert ds.attrs["validity"] == "left_range" and ds.attrs["left_range"] == 1
    assert ds.attrs["diverged"] == 0 and math.isnan(ds.attrs["diverged_at_s"])
    assert "left the range of the models" in ds.attrs["warnings"]


@pytest.mark.parametrize("name, low, high", [("tab3_foam_tau400", 0.2, 0.3), ("tab3_foam_tau200", 0.11, 0.16)])
def test_the_papers_large_torque_runs_are_flagged(paper, name, low, high):
    """The torque pulses of Table 3 reach about 2.0 m (400 N m) and 1.1 m (200 N m) on L = 8 m."""
    ds = run(paper, name)
    assert ds.attrs["validity"] == "large_deflection"
    assert low < ds.attrs["max_deflection_ratio"] < high


def test_the_papers_foam_run_at_2p8_is_not_flagged_unless_the_limit_is_tighter(paper):
    ds = run(paper, "fig05_foam_wf2p8")  # peak about 0.22 m (Fig. 5): 0.03 L
    assert ds.attrs["validity"] == "valid" and ds.attrs["large_deflection"] == 0
    assert ds.attrs["small_deflection_limit"] == 0.1 and "deflection" not in ds.attrs["warnings"]
    tight = run(paper, "fig05_foam_wf2p8", numerics={"small_deflection_limit": 0.01})
    assert tight.attrs["validity"] == "large_deflection"
    assert tight.attrs["max_deflection_ratio"] == ds.attrs["max_deflection_ratio"]


def test_a_blown_up_state_is_diverged_whatever_the_deflection():
    for status in (radau.NON_FINITE, radau.STEP_UNDERFLOW):
        assert validity.classify(status, False, 0.0, 0.1) == validity.DIVERGED
    assert validity.classify(radau.TOO_MANY_STEPS, False, 0.05, 0.1) == validity.VALID


def test_figures_and_reports_name_a_flagged_run(paper):
    from hubbeam.paper.report import runs_markdown
    from hubbeam.plotting import case_figure
    from hubbeam.plotting.figures import plot_series
    from hubbeam.study.summary import case_summary

    ds = run(paper, "tab3_foam_tau400")
    fig = case_figure.plot("tau400", ds)
    assert "[large deflection: max |v(L)| = 0.2" in fig.axes[0].get_title()
    line = plot_series(fig.axes[1], "tau400", ds, "tip_transverse")
    assert "(large deflection, max |v(L)| = 0.2" in line.get_label()
    assert "| large deflection (0.2" in runs_markdown({"tau400": ds})
    assert case_summary("tau400", ds)["validity"].startswith("large deflection (0.2")
