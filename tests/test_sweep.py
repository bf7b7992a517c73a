"""Parameter sweeps (``hubbeam.simulation.sweep``, ``hubbeam.core.sweep``) against individual simulations.

* a sweep point reproduces ``simulate`` of the same case (peak tip deflection, its time and the
  residual amplitude), with and without a tip mass, to the sweep's accuracy target;
* the grid, the coordinates and the point order follow the config; the dataset is
  self-describing and survives a netCDF round trip;
* a diverged run (TLAM beyond its critical speed) is flagged, with NaN extrema, not an error, and
  TLAM diverges exactly where the final speed exceeds the eigen-analysis' critical speed;
* the threaded kernel gives the same numbers on any number of threads; a map gathered from its
  chunks (through their files) is identical to the map run in one go;
* the extremum of the cubic Hermite interpolant and the output grid are exact;
* config validation names the key of an inconsistent sweep; both figure kinds are drawn, and the
  slices of a map over three axes.
"""

import copy
import dataclasses
import json
import math

import numpy as np
import pytest
import xarray as xr

from hubbeam.configuration.load import ConfigError, check_schema
from hubbeam.configuration.settings import Grid, from_config
from hubbeam.core import radau
from hubbeam.core.inputs import ModelTraits
from hubbeam.core.sweep import hermite_abs_max, output_grid
from hubbeam.model import validity
from hubbeam.model.frozen import FrozenMap
from hubbeam.model.parameters import BeamParameters
from hubbeam.results.io import open_result, write_netcdf
from hubbeam.simulation.simulate import simulate
from hubbeam.simulation.sweep import (
    _points,
    axis_values,
    gather_chunks,
    n_chunks,
    run_chunk,
    run_sweep,
)

#: relative accuracy of the peak tip deflection that the maps are meant to have
MAP_ACCURACY = 1e-4


@pytest.fixture(scope="module")
def params(_study_config):
    return BeamParameters.from_config(_study_config)


def small_sweep(config, name, **grid):
    """The configured sweep ``name`` on a reduced grid ``{parameter: values}`` (3 modes)."""
    sweep = from_config(config).sweeps[name]
    reduced = {key: Grid(float(values[0]), float(values[-1]), len(values)) for key, values in grid.items()}
    return dataclasses.replace(sweep, modes=3, grid=FrozenMap({**sweep.grid, **reduced}))


@pytest.fixture(scope="module")
def spinup(_study_config, params):
    sweep = small_sweep(_study_config, "spinup_peak", wf=[1.5, 4.0], tf=[8.0, 20.0])
    return sweep, run_sweep(sweep, params)


@pytest.fixture(scope="module")
def with_tip_mass(_study_config, params):
    sweep = dataclasses.replace(small_sweep(_study_config, "tlam_vs_foam", wf=[1.0, 1.5], tip_mass=[0.0, 0.5]),
                                t_after=5.0)
    return sweep, run_sweep(sweep, params)


def simulated_extrema(sweep, params, numerics, model, maneuver, tip_mass):
    """``simulate`` on a fine output grid: (peak, time, |v(L)|), residual amplitude."""
    case = {"name": "sweep_point", "model": model, "modes": sweep.modes,
            "maneuver": {"kind": sweep.maneuver["kind"], **maneuver},
            "t_end": maneuver["tf"] + sweep.t_after, "tip_mass": tip_mass}
    ds = simulate(case, params, dict(numerics, rtol=1e-10, atol=1e-12, output_step=2e-3))
    assert ds.attrs["diverged"] == 0
    tip = abs(ds.tip_transverse)
    return float(tip.max()), tip, float(tip.where(ds.time >= maneuver["tf"]).max())


@pytest.mark.parametrize("model", ["FOAM", "TLAM"])
def test_sweep_point_equals_a_simulation_of_the_same_case(spinup, params, _study_config, model):
    sweep, ds = spinup
    point = ds.sel(model=model, wf=1.5, tf=8.0)
    assert int(point.diverged) == 0
    peak, tip, residual = simulated_extrema(
        sweep, params, _study_config["numerics"], model, {"wf": 1.5, "tf": 8.0},
        {"mass": sweep.tip_mass.mass, "position": sweep.tip_mass.position})
    assert float(point.peak_tip_deflection) == pytest.approx(peak, rel=MAP_ACCURACY)
    # the simulation reaches the peak at the sweep's peak time
    at_peak_time = np.interp(float(point.peak_time), tip.time.values, tip.values)
    assert at_peak_time == pytest.approx(peak, rel=MAP_ACCURACY)
    assert float(point.residual_amplitude) == pytest.approx(residual, abs=MAP_ACCURACY * peak)


def test_sweep_point_with_a_tip_mass_equals_a_simulation(with_tip_mass, params, _study_config):
    sweep, ds = with_tip_mass
    for mass in (0.0, 0.5):
        point = ds.sel(model="TLAM", wf=1.5, tip_mass=mass)
        peak, _, residual = simulated_extrema(
            sweep, params, _study_config["numerics"], "TLAM", {"wf": 1.5, "tf": 30.0},
            {"mass": mass, "position": sweep.tip_mass.position})
        assert float(point.peak_tip_deflection) == pytest.approx(peak, rel=MAP_ACCURACY)
        assert float(point.residual_amplitude) == pytest.approx(residual, abs=MAP_ACCURACY * peak)
    # the tip mass changes the answer (the matrix sets are not mixed up)
    assert (float(ds.peak_tip_deflection.sel(model="TLAM", wf=1.5, tip_mass=0.5))
            > 1.1 * float(ds.peak_tip_deflection.sel(model="TLAM", wf=1.5, tip_mass=0.0)))


def test_diverged_run_is_flagged_not_raised(spinup, params):
    sweep, ds = spinup
    tlam = ds.sel(model="TLAM", wf=4.0)  # above TLAM's critical speed (2.9 rad/s)
    assert (tlam.diverged == 1).all()
    assert (tlam.status == radau.LEFT_RANGE).all()  # stopped at |v(L)| > divergence_limit * L
    assert (tlam.validity == validity.DIVERGED).all()  # beyond the critical speed: not left_range
    assert np.isnan(tlam.peak_tip_deflection).all()
    assert (tlam.stopped_at < tlam.tf + sweep.t_after).all()
    assert float(ds.critical_speed.sel(eigen_model="TLAM")) < 4.0
    foam = ds.sel(model="FOAM", wf=4.0)
    assert (foam.diverged == 0).all() and np.isfinite(foam.peak_tip_deflection).all()
    assert ds.attrs["n_diverged"] == int(ds.diverged.sum()) == 2
    # the runs that complete: large_deflection exactly where the peak exceeds 0.1 L
    done = ds.status == radau.SUCCESS
    expected = xr.where(ds.peak_tip_deflection > 0.1 * params.L, validity.LARGE_DEFLECTION, validity.VALID)
    np.testing.assert_array_equal(ds.validity.where(done, drop=True), expected.where(done, drop=True))


def test_tlam_diverges_exactly_above_its_critical_speed(_study_config, params):
    """The sweep's divergence (time integration) agrees with the eigen-analysis: TLAM diverges
    once the final speed exceeds Omega_c(m_t) (K22 singular) and stays bounded below it."""
    from hubbeam.model.eigen import critical_speed
    from hubbeam.model.parameters import TipMass

    masses = (0.0, 0.6)
    critical = [critical_speed("TLAM", params, TipMass(m, params.L), 3, 20.0) for m in masses]
    margin = 0.15  # rad/s: growth sqrt(wf^2 - Omega_c^2) >= 0.9 s-1 reaches the limit in time
    sweep = small_sweep(_study_config, "tlam_vs_foam",
                        wf=np.linspace(min(critical) - margin, max(critical) + margin, 2 + round(
                            (max(critical) - min(critical) + 2 * margin) / 0.1)),
                        tip_mass=list(masses))
    sweep = dataclasses.replace(sweep, models=("TLAM",), figure=FrozenMap({"kind": "peak"}))
    ds = run_sweep(sweep, params)
    np.testing.assert_allclose(ds.critical_speed.sel(eigen_model="TLAM").values, critical)
    for mass, speed in zip(masses, critical):
        stopped = ds.status.sel(model="TLAM", tip_mass=mass) == radau.LEFT_RANGE
        away = abs(ds.wf - speed) >= margin
        np.testing.assert_array_equal(stopped.where(away, drop=True).values,
                                      (ds.wf > speed).where(away, drop=True).values)
        np.testing.assert_array_equal(ds.diverged.sel(model="TLAM", tip_mass=mass).values, stopped.values)


def test_grid_and_coordinates_follow_the_config(_study_config):
    sweeps = from_config(_study_config).sweeps
    assert list(sweeps) == sorted(_study_config["sweeps"]["maps"])
    for name, sweep in sweeps.items():
        spec = _study_config["sweeps"]["maps"][name]
        assert sweep.axes == tuple(spec["grid"])
        for key, values in axis_values(sweep).items():
            grid = spec["grid"][key]
            np.testing.assert_array_equal(values, np.linspace(grid["start"], grid["stop"],
                                                              grid["num"]))
        models, mp, index, t_end, t_mark, tips = _points(sweep)
        shape = (len(spec["models"]),) + tuple(g["num"] for g in spec["grid"].values())
        assert len(models) == math.prod(shape) >= 10_000
        assert models.shape[1:] == (len(ModelTraits._fields),)
        # C order (model, axis 1, axis 2): the swept values vary along their own axis only
        grids = np.meshgrid(*axis_values(sweep).values(), indexing="ij")
        for key, grid in zip(sweep.axes, grids):
            if key in ("wf", "tf", "tau_max"):
                column = ("wf", "tf") if sweep.maneuver["kind"] == "prescribed" else (
                    "tau_max", "tf")
                swept = mp[:, column.index(key)].reshape(shape)
            elif key == "tip_mass":
                swept = np.array([tips[i].mass for i in index]).reshape(shape)
            else:
                swept = np.array([tips[i].position for i in index]).reshape(shape)
            np.testing.assert_array_equal(swept, np.broadcast_to(grid, shape))
        np.testing.assert_allclose(t_end - t_mark, sweep.t_after)


def test_dataset_is_self_describing_and_round_trips(with_tip_mass, tmp_path):
    sweep, ds = with_tip_mass
    assert ds.peak_tip_deflection.dims == ("model", "wf", "tip_mass")
    for name, variable in ds.variables.items():
        assert "long_name" in variable.attrs, name
        if name not in ("model", "eigen_model"):
            assert "units" in variable.attrs, name
    assert ds.diverged.attrs["flag_meanings"] == "bounded diverged"
    assert ds.validity.attrs["flag_meanings"] == "valid large_deflection left_range diverged"
    for key in ("rtol", "atol", "output_step", "max_steps", "divergence_limit", "integrator",
                "Conventions", "git_commit"):
        assert key in ds.attrs
    assert json.loads(ds.attrs["sweep_config"]) == json.loads(json.dumps(sweep.to_dict()))
    back = open_result(write_netcdf(ds, tmp_path / "sweep.nc"))
    np.testing.assert_array_equal(back.peak_tip_deflection.values, ds.peak_tip_deflection.values)
    np.testing.assert_array_equal(back.diverged.values, ds.diverged.values)
    assert back.attrs["sweep_config"] == ds.attrs["sweep_config"]
    # TLAM's critical speed falls with the tip mass; FOAM has none
    critical = back.critical_speed.sel(eigen_model="TLAM").values
    assert critical[1] < critical[0]
    assert np.isnan(back.critical_speed.sel(eigen_model="FOAM")).all()


def test_thread_count_does_not_change_the_numbers(with_tip_mass, params):
    sweep, ds = with_tip_mass
    for threads in (1, 3):
        again = run_sweep(sweep, params, threads=threads)
        for name in ("peak_tip_deflection", "residual_amplitude", "status", "n_rhs"):
            np.testing.assert_array_equal(again[name].values, ds[name].values)


@pytest.fixture(scope="module")
def cube(_study_config, params):
    """The three-axis map on a 3 x 2 x 2 grid, in one go."""
    sweep = small_sweep(_study_config, "tlam_vs_foam_3d", wf=[1.0, 2.0, 3.0], tf=[4.0, 8.0],
                        tip_mass=[0.0, 0.5])
    sweep = dataclasses.replace(sweep, t_after=3.0, chunk_size=5)
    return sweep, run_sweep(sweep, params)


def test_a_map_gathered_from_chunk_files_equals_the_single_run(cube, params, tmp_path):
    sweep, whole = cube
    assert n_chunks(sweep) == 5  # 24 simulations: four chunks of 5, one of 4
    files = [write_netcdf(run_chunk(sweep, params, index, threads=1), tmp_path / f"{index}.nc")
             for index in range(n_chunks(sweep))]
    chunks = [open_result(path) for path in reversed(files)]  # any order
    gathered = gather_chunks(sweep, params, chunks)
    xr.testing.assert_identical(gathered.drop_attrs(deep=False), whole.drop_attrs(deep=False))
    assert {k: v for k, v in gathered.attrs.items() if k != "history"} == {
        k: v for k, v in whole.attrs.items() if k != "history"}
    assert whole.peak_tip_deflection.dims == ("model", "wf", "tf", "tip_mass")
    with pytest.raises(ValueError, match=r"chunks \[0, 1, 2, 3\]; allowed: each of 0 to 4 once"):
        gather_chunks(sweep, params, chunks[1:])
    with pytest.raises(ValueError, match="chunk 0 was run with other sweep settings"):
        gather_chunks(dataclasses.replace(sweep, t_after=4.0), params, chunks)
    with pytest.raises(IndexError, match="chunk 5; allowed: 0 to 4"):
        run_chunk(sweep, params, 5)


def test_the_million_run_map_is_chunked(_study_config):
    sweep = from_config(_study_config).sweeps["tlam_vs_foam_3d"]
    assert len(sweep.models) * math.prod(grid.num for grid in sweep.grid.values()) >= 10**6
    assert not sweep.in_all and n_chunks(sweep) > 1


def test_hermite_extremum_and_output_grid():
    rng = np.random.default_rng(7)
    s = np.linspace(0.0, 1.0, 200_001)
    for _ in range(20):
        p0, d0, p1, d1 = rng.normal(size=4)
        h = rng.uniform(0.01, 2.0)
        h00, h10 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s
        h01, h11 = -2 * s**3 + 3 * s**2, s**3 - s**2
        sampled = abs(h00 * p0 + h10 * h * d0 + h01 * p1 + h11 * h * d1)
        value, where = hermite_abs_max(p0, d0, p1, d1, h)
        assert value == pytest.approx(sampled.max(), rel=1e-9)
        assert where == pytest.approx(s[sampled.argmax()], abs=1e-4)
    grid = output_grid(10.0, 0.3, 4.0)
    assert grid[0] == 0.0 and grid[-1] == 10.0 and 4.0 in grid
    assert np.all(np.diff(grid) > 0) and np.diff(grid).max() <= 0.3 + 1e-12
    assert output_grid(6.0, 0.5, 3.0).tolist() == [0.5 * k for k in range(13)]


@pytest.mark.parametrize("change, key", [
    (lambda s: s["maneuver"].update(wf=2.0), "sweeps.maps.spinup_peak.maneuver.wf"),
    (lambda s: s["maneuver"].update(tau_max=50.0), "sweeps.maps.spinup_peak.maneuver.tau_max"),
    (lambda s: s["grid"].update(tau_max={"start": 1.0, "stop": 2.0, "num": 2}) or
     s["grid"].pop("tf"), "sweeps.maps.spinup_peak.grid.tau_max"),
    (lambda s: s["grid"]["wf"].update(start=0.0), "sweeps.maps.spinup_peak.grid.wf.start"),
    (lambda s: s["figure"].update(kind="departure", model="CFOAM", reference="FOAM",
                                  threshold=0.1), "sweeps.maps.spinup_peak.figure.model"),
])
def test_inconsistent_sweep_is_rejected_naming_the_key(_study_config, change, key):
    config = copy.deepcopy(_study_config)
    change(config["sweeps"]["maps"]["spinup_peak"])
    with pytest.raises(ConfigError) as error:
        check_schema(config)
    assert key in str(error.value)


def test_both_figure_kinds_are_drawn(spinup, with_tip_mass, cube, tmp_path):
    from hubbeam.plotting import draw
    from hubbeam.plotting.sweep_maps import plot, relative_departure

    for name, (_, ds) in {"peak": spinup, "departure": with_tip_mass}.items():
        pdf, png = draw(plot, tmp_path / f"{name}.pdf", ds)
        assert pdf.stat().st_size > 0 and png.stat().st_size > 0
    sweep, ds = cube
    for figure in (dict(sweep.figure), {"kind": "peak", "slices": 2}):
        ds = ds.assign_attrs(sweep_config=json.dumps(dict(sweep.to_dict(), figure=figure)))
        pdf, png = draw(plot, tmp_path / f"cube_{figure['kind']}.pdf", ds)
        assert pdf.stat().st_size > 0 and png.stat().st_size > 0
    _, ds = with_tip_mass
    departure = relative_departure(ds, "TLAM", "FOAM")
    peak = ds.peak_tip_deflection
    expected = abs(peak.sel(model="TLAM") / peak.sel(model="FOAM") - 1.0)
    np.testing.assert_allclose(departure.values, expected.values, rtol=1e-12)


def test_sweep_cells_tell_left_range_from_diverged(_study_config, params):
    """At 3 rad/s with a heavy tip mass and a tight limit, FOAM's bounded response is stopped
    (left_range: its linearisation has no critical speed), TLAM's, beyond its critical speed,
    diverged."""
    sweep = small_sweep(_study_config, "tlam_vs_foam", wf=[1.0, 3.0], tip_mass=[0.0, 10.0])
    sweep = dataclasses.replace(sweep, t_after=5.0, divergence_limit=0.3)
    ds = run_sweep(sweep, params)
    cell = ds.validity.sel(wf=3.0, tip_mass=10.0)
    assert int(cell.sel(model="FOAM")) == validity.LEFT_RANGE
    assert int(cell.sel(model="TLAM")) == validity.DIVERGED
    assert int(ds.validity.sel(model="FOAM", wf=1.0, tip_mass=0.0)) == validity.VALID
    assert ds.attrs["n_left_range"] == int((ds.validity == validity.LEFT_RANGE).sum()) >= 1
