"""The measures and the verdict of the controller-trust study (``hubbeam.study.trust``), on
synthetic runs whose numbers are known in closed form."""

import json
import math

import matplotlib
import numpy as np
import xarray as xr

from hubbeam.plotting import controller_trust
from hubbeam.study.trust import SETTLING_BAND, closed_loop_measures, design_table, performance, verdicts

matplotlib.use("Agg")

TF = 2.0


def _run(design, model, speed, amplitude, status="success"):
    """v(L) = amplitude sin(pi t / TF) during the spin-up, then amplitude/2 exp(-(t - TF)) cos(10 (t - TF))."""
    t = np.linspace(0.0, 10.0, 10001)
    s = t - TF
    tip = np.where(t <= TF, amplitude * np.sin(np.pi * t / TF), 0.5 * amplitude * np.exp(-s) * np.cos(10 * s))
    maneuver = {"kind": "state_feedback", "reference": {"kind": "prescribed", "wf": speed, "tf": TF},
                "design": {"model": design, "speed": speed, "weights": {"tip_deflection": 1.0}}}
    return xr.Dataset({"tip_transverse": ("time", tip), "hub_torque": ("time", 3.0 * tip)},
                      coords={"time": t},
                      attrs={"maneuver": json.dumps(maneuver), "model": model, "integrator_status": status})


def test_the_measures_of_a_run_are_those_of_its_signal():
    m = closed_loop_measures("a", _run("FOAM", "CFOAM", 1.0, 0.4))
    np.testing.assert_allclose([m["peak_tip_deflection_m"], m["peak_torque_Nm"], m["residual_vibration_m"]],
                               [0.4, 1.2, 0.2 * math.exp(-1e-3) * math.cos(1e-2)], rtol=1e-12)  # first sample after TF
    # |v| leaves the band 0.05 * 0.4 for the last time near exp(-s) / 2 = SETTLING_BAND, a crest
    # of the cosine (every pi / 10 s)
    bound = math.log(0.5 / SETTLING_BAND)
    assert bound - math.pi / 10 <= m["settling_time_s"] <= bound
    assert m["stable"]


def test_a_design_is_good_enough_while_the_truth_stays_within_the_tolerance():
    runs = {"own1": _run("TLAM", "TLAM", 1.0, 0.4), "ref1": _run("TLAM", "CFOAM", 1.0, 0.42),
            "own2": _run("TLAM", "TLAM", 2.0, 0.4), "ref2": _run("TLAM", "CFOAM", 2.0, 0.6),
            "own3": _run("TLAM", "TLAM", 3.0, 0.4), "ref3": _run("TLAM", "CFOAM", 3.0, 0.4, "left_range")}
    table = design_table(runs)
    assert [row["good"] for row in table] == [True, False, False]
    np.testing.assert_allclose([row["gap"] for row in table[:2]], [0.05, 0.5])
    assert verdicts(table) == {"TLAM": "good enough up to 1 rad/s (largest gap 5 %); at 2 rad/s its "
                                       "CFOAM tip deflections differ by 50 % from its prediction; "
                                       "unstable on CFOAM from 3 rad/s"}


def test_a_poor_prediction_and_the_best_performance_are_stated_apart():
    """TLAM's design is 50 % off its prediction at 2 rad/s (not good enough) yet leaves the least
    residual on CFOAM there (residual half the amplitude of v(L) during the spin-up): prediction
    and performance are two statements with their numbers."""
    runs = {"t_own1": _run("TLAM", "TLAM", 1.0, 0.4), "t_ref1": _run("TLAM", "CFOAM", 1.0, 0.42),
            "t_own2": _run("TLAM", "TLAM", 2.0, 0.4), "t_ref2": _run("TLAM", "CFOAM", 2.0, 0.6),
            "f_own1": _run("FOAM", "FOAM", 1.0, 0.3), "f_ref1": _run("FOAM", "CFOAM", 1.0, 0.3),
            "f_own2": _run("FOAM", "FOAM", 2.0, 1.0), "f_ref2": _run("FOAM", "CFOAM", 2.0, 1.0),
            "s_ref2": _run("SFOAM", "CFOAM", 2.0, 0.8, "left_range")}
    table = design_table(runs)
    assert verdicts(table)["TLAM"].startswith("good enough up to 1 rad/s (largest gap 5 %); at 2 rad/s its CFOAM")
    # residuals: the first sample after TF, 0.5 * amplitude * exp(-1e-3) cos(1e-2), to two figures
    assert performance(table) == {
        "TLAM": "the least residual vibration on CFOAM of the designs at 2 rad/s (0.3 m against 0.5 m (FOAM)); "
                "more than another design at 1 rad/s (0.21 m against 0.15 m (FOAM))",
        "FOAM": "the least residual vibration on CFOAM of the designs at 1 rad/s (0.15 m against 0.21 m (TLAM)); "
                "more than another design at 2 rad/s (0.5 m against 0.3 m (TLAM))",
        "SFOAM": "unstable on CFOAM at 2 rad/s"}


def test_designs_within_the_tie_share_the_least_residual():
    """Two designs whose residuals differ by 0.5 % are both the least (TIE is 1 %)."""
    runs = {"f_ref": _run("FOAM", "CFOAM", 1.0, 0.4), "s_ref": _run("SFOAM", "CFOAM", 1.0, 0.402),
            "t_ref": _run("TLAM", "CFOAM", 1.0, 0.5)}
    found = performance(design_table(runs))
    assert found["FOAM"].startswith("the least residual") and found["SFOAM"].startswith("the least residual")
    assert found["TLAM"].startswith("more than another design at 1 rad/s")


def test_a_design_run_only_on_the_truth_is_not_judged_and_its_figure_draws_only_that_run():
    """One design, run on CFOAM but not on its own model: there is no prediction to compare, so no
    gap (no 'nan %') and no verdict 'not good enough'; the figure has one legend entry, for the run
    that exists, and an axis from rest rather than a sliver around the one design speed."""
    runs = {"only": _run("FOAM", "CFOAM", 1.5, 0.3)}
    (row,) = design_table(runs)
    assert row["own"] is None and row["good"] is None
    verdict = verdicts([row])["FOAM"]
    assert "not judged" in verdict and "nan" not in verdict.lower() and "not good enough" not in verdict
    figure = controller_trust.plot("one design", runs)
    labels = [text.get_text() for text in figure.get_axes()[0].get_legend().get_texts()]
    assert labels == ["designed on FOAM, run on CFOAM"]
    assert all(ax.get_xlim()[0] == 0.0 and ax.get_xlim()[1] > 1.5 for ax in figure.get_axes())
