"""The reader of the simulation dataset (hubbeam.results.reader) against its writer (hubbeam.simulation.simulate)."""

from __future__ import annotations

import ast
import json
import math
from pathlib import Path

import numpy as np
import pytest
from synthetic_results import paper_cases, simulation_dataset

import hubbeam
from hubbeam.model.parameters import BeamParameters
from hubbeam.results import reader as results
from hubbeam.results.io import open_result, write_netcdf
from hubbeam.results.variables import CUMULATIVE_VARIABLES, HIGH_ORDER_VARIABLES, VARIABLES


@pytest.fixture(scope="module")
def written(_study_config, tmp_path_factory):
    """A short CFOAM spin-up (every variable the writer knows) written to netCDF and read back."""
    from hubbeam.simulation.simulate import simulate

    case = {"name": "short_cfoam", "model": "CFOAM", "modes": 2, "t_end": 1.0,
            "maneuver": {"kind": "prescribed", "wf": 1.0, "tf": 0.5},
            "tip_mass": {"mass": 0.1, "position": 7.0}}
    numerics = dict(_study_config["numerics"], quadrature_points=16)
    ds = simulate(case, BeamParameters.from_config(_study_config), numerics)
    path = write_netcdf(ds, tmp_path_factory.mktemp("results") / "short_cfoam.nc")
    return case, ds, open_result(path)


def test_every_variable_the_writer_knows_is_read_back_with_its_units(written):
    case, ds, back = written
    tables = VARIABLES | CUMULATIVE_VARIABLES | HIGH_ORDER_VARIABLES
    assert set(back.data_vars) == set(tables)
    for name, entry in tables.items():
        assert results.units("short_cfoam", back, name) == entry[-2] == results.UNITS[name]
        np.testing.assert_array_equal(results.variable("short_cfoam", back, name).values, ds[name].values)
    np.testing.assert_array_equal(results.times(back), ds["time"].values)


def test_the_case_settings_are_read_from_the_attributes(written):
    case, _, back = written
    assert results.model("c", back) == "CFOAM"
    assert results.n_modes("c", back) == 2
    assert results.tip_mass("c", back) == 0.1 and results.tip_position("c", back) == 7.0
    assert results.maneuver("c", back) == case["maneuver"]
    assert results.maneuver_value("c", back, "wf") == 1.0
    assert results.maneuver_end(results.maneuver("c", back)) == 0.5
    assert results.diverged_at("c", back) is None and results.left_range_at("c", back) is None
    assert results.convergence_result(back.attrs) == "not checked"


def test_the_inputs_read_from_a_dataset_rerun_it(written):
    from hubbeam.simulation.simulate import simulate

    _, ds, back = written
    rerun = simulate(**results.simulation_inputs(back.attrs))
    np.testing.assert_array_equal(rerun["tip_transverse"].values, ds["tip_transverse"].values)
    attrs = dict(back.attrs)
    del attrs["rtol"]
    with pytest.raises(results.DatasetError, match="dataset attribute 'rtol' is missing"):
        results.simulation_inputs(attrs)


def _datasets():
    cases = paper_cases()
    names = ("fig05_tlam_wf2p8", "fig05_foam_wf2p8", "fig05_tlam_wf3p5", "fig06_foam_n1",
             "tab3_foam_tau200")
    return {name: simulation_dataset(name, cases[name], dt=0.5,
                                     diverge_at=41.3 if name == "fig05_tlam_wf3p5" else None)
            for name in names}


def test_select_and_distinct_compare_settings_and_maneuver_numbers():
    datasets = _datasets()
    assert sorted(results.select(datasets, model="TLAM")) == ["fig05_tlam_wf2p8", "fig05_tlam_wf3p5"]
    assert sorted(results.select(datasets, model="FOAM", wf=2.8)) == ["fig05_foam_wf2p8"]
    assert sorted(results.select(datasets, n_modes=1)) == ["fig06_foam_n1"]
    assert sorted(results.select(datasets, kind="torque")) == ["tab3_foam_tau200"]
    assert results.select(datasets, wf=2.8 + 1e-6) == {}
    spun_up = {c: d for c, d in datasets.items() if c.startswith("fig05")}
    assert results.distinct(spun_up, "wf") == [2.8, 3.5]
    assert results.distinct(datasets, "tip_mass") == [0.0]


def test_a_diverged_run_reports_its_time_or_its_last_finite_sample():
    ds = _datasets()["fig05_tlam_wf3p5"]
    assert results.diverged_at("c", ds) == 41.3
    ds.attrs["diverged_at_s"] = math.nan
    last = float(ds["time"].values[np.isfinite(ds["tip_transverse"].values)][-1])
    assert results.diverged_at("c", ds) == last < 41.3


def test_missing_items_are_named_with_the_case():
    ds = _datasets()["fig05_foam_wf2p8"]
    with pytest.raises(results.DatasetError, match=r"case 'c' has no variable 'dQ_q2' \(has: .*energy"):
        results.variable("c", ds, "dQ_q2")
    with pytest.raises(results.DatasetError, match="case 'c': maneuver has no 'tau_max'"):
        results.maneuver_value("c", ds, "tau_max")
    with pytest.raises(results.DatasetError, match="case 'c' has no attribute 'model'"):
        results.model("c", ds.drop_attrs())
    broken = ds.assign_attrs(maneuver="{kind")
    with pytest.raises(results.DatasetError, match="attribute 'maneuver' is not JSON"):
        results.maneuver("c", broken)
    with pytest.raises(results.DatasetError, match=r"maneuver \{'kind': 'speed'\} is not a maneuver hubbeam knows"):
        results.maneuver_end({"kind": "speed"})
    pd = '{"kind": "pd", "kp": 1.0, "kd": 1.0, "reference": {"kind": "prescribed", "wf": 1.0, "tf": 4.0}}'
    assert results.maneuver_end(json.loads(pd)) == 4.0


def test_only_drawing_modules_import_the_plotting_package():
    """Results are read through hubbeam.results.reader: outside the plotting package only the
    validation figures and the workflow's drawing jobs (which draw) import it."""
    package = Path(hubbeam.__file__).parent
    importers = set()
    for path in package.rglob("*.py"):
        if "plotting" in path.relative_to(package).parts:
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            names = ([alias.name for alias in node.names] if isinstance(node, ast.Import)
                     else [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
            if any(name.startswith("hubbeam.plotting") for name in names):
                importers.add(path.relative_to(package).as_posix())
    assert importers == {"validation/figures.py", "pipeline/jobs/figures.py", "pipeline/jobs/comparisons.py",
                         "pipeline/jobs/identification.py"}
