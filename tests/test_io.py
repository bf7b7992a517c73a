"""Result files: atomic, lossless netCDF writing; clear errors for damaged files; provenance
attributes; the numba cache directory keyed by the package sources."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from importlib import metadata

import netCDF4
import numpy as np
import pytest
import xarray as xr

import hubbeam
from hubbeam.results import provenance
from hubbeam.results.io import FILE_TIME_ATTRS, FLOAT_ENCODING, ResultFileError, open_result, write_netcdf


def result_dataset(scale: float = 1.0) -> xr.Dataset:
    time = np.arange(0.0, 2.0, 0.01)
    mode = np.arange(1, 4)
    rng = np.random.default_rng(7)
    return xr.Dataset(
        {
            "theta": ("time", scale * np.sin(time), {"units": "rad", "long_name": "hub angle"}),
            "q2": (("time", "mode"), scale * rng.standard_normal((time.size, mode.size)) * 1e-3,
                   {"units": "kg1/2 m", "long_name": "transverse modal coordinates"}),
            "n_steps": ((), np.int64(123)),
        },
        coords={"time": ("time", time, {"units": "s", "long_name": "time"}),
                "mode": ("mode", mode, {"long_name": "mode number"})},
        # a fixed history: datasets built a second apart must compare equal
        attrs={**provenance.global_attributes("test result", {"model": "FOAM", "t_end": 2.0}),
               "history": "2026-01-01T00:00:00Z created by the test suite"},
    )


def files_in(directory) -> list[str]:
    return sorted(os.listdir(directory))


# ---------------------------------------------------------------------------------------------
# writing


def test_round_trip_is_lossless_and_compressed(tmp_path):
    ds = result_dataset()
    path = write_netcdf(ds, tmp_path / "sub" / "case.nc")
    assert files_in(tmp_path / "sub") == ["case.nc"]
    back = open_result(path)
    xr.testing.assert_identical(back, ds)
    with netCDF4.Dataset(path) as nc:
        assert nc.data_model == "NETCDF4"
        for name in ("theta", "q2", "time"):
            filters = nc[name].filters()
            assert filters["zlib"] and filters["shuffle"] and filters["complevel"] == FLOAT_ENCODING["complevel"]
            assert nc[name].dtype == np.float64
            assert not {"scale_factor", "add_offset"} & set(nc[name].ncattrs())
        assert not nc["mode"].filters()["zlib"]


def test_packing_carried_by_the_dataset_is_not_written(tmp_path):
    """An encoding inherited from elsewhere (here int16 packing) must not make the file lossy."""
    ds = result_dataset()
    ds["theta"].encoding.update(dtype="int16", scale_factor=1e-3, add_offset=0.0)
    back = open_result(write_netcdf(ds, tmp_path / "case.nc"))
    np.testing.assert_array_equal(back["theta"].values, ds["theta"].values)


class DiskFull(OSError):
    pass


def failing_to_netcdf(monkeypatch, exception):
    """Make writing fail after part of the file is on disk, like a full disk or a kill."""
    real = xr.Dataset.to_netcdf

    def write_then_fail(self, path, *args, **kwargs):
        real(self, path, *args, **kwargs)
        with open(path, "r+b") as partial:
            partial.truncate(os.path.getsize(path) // 2)
        raise exception

    monkeypatch.setattr(xr.Dataset, "to_netcdf", write_then_fail)


@pytest.mark.parametrize("exception", [DiskFull("No space left on device"), KeyboardInterrupt()])
def test_failed_write_leaves_no_file(tmp_path, monkeypatch, exception):
    failing_to_netcdf(monkeypatch, exception)
    with pytest.raises(type(exception)):
        write_netcdf(result_dataset(), tmp_path / "case.nc")
    assert files_in(tmp_path) == []


def test_failed_overwrite_keeps_the_old_file(tmp_path, monkeypatch):
    original = result_dataset()
    path = write_netcdf(original, tmp_path / "case.nc")
    before = path.read_bytes()
    failing_to_netcdf(monkeypatch, DiskFull("No space left on device"))
    with pytest.raises(DiskFull):
        write_netcdf(result_dataset(scale=2.0), path)
    assert files_in(tmp_path) == ["case.nc"]
    assert path.read_bytes() == before
    xr.testing.assert_identical(open_result(path), original)


def test_failed_rename_leaves_no_temporary_file(tmp_path, monkeypatch):
    original = result_dataset()
    path = write_netcdf(original, tmp_path / "case.nc")

    def refuse(*_args):
        raise PermissionError("rename refused")

    monkeypatch.setattr(os, "replace", refuse)
    with pytest.raises(PermissionError):
        write_netcdf(result_dataset(scale=2.0), path)
    assert files_in(tmp_path) == ["case.nc"]
    xr.testing.assert_identical(open_result(path), original)


def test_overwrite_replaces_content(tmp_path):
    path = write_netcdf(result_dataset(), tmp_path / "case.nc")
    write_netcdf(result_dataset(scale=2.0), path)
    xr.testing.assert_identical(open_result(path), result_dataset(scale=2.0))
    assert files_in(tmp_path) == ["case.nc"]


def test_result_read_back_can_be_rewritten_in_place(tmp_path):
    path = write_netcdf(result_dataset(), tmp_path / "case.nc")
    ds = open_result(path)
    ds.attrs["note"] = "edited"
    write_netcdf(ds, path)
    assert open_result(path).attrs["note"] == "edited"


def test_coordinates_carry_no_fill_value(tmp_path):
    """CF 2.5.1: a coordinate variable may not have missing values, hence no _FillValue; data
    variables keep theirs (NaN marks the output after a diverged run's stop)."""
    ds = result_dataset().assign_coords(speed=("speed", [0.0, 1.5], {"units": "rad s-1"}))
    with netCDF4.Dataset(write_netcdf(ds, tmp_path / "case.nc")) as nc:
        for name in ("time", "mode", "speed"):
            assert "_FillValue" not in nc[name].ncattrs(), name
        assert np.isnan(nc["theta"].getncattr("_FillValue"))


def test_time_is_stored_with_a_reference_and_read_back_in_seconds(tmp_path):
    """CF 4.4: the time coordinate's units name a reference time (the nominal epoch); hubbeam and
    ``decode_times=False`` read the seconds unchanged, plain xarray the epoch plus the seconds."""
    ds = result_dataset()
    path = write_netcdf(ds, tmp_path / "case.nc")
    with netCDF4.Dataset(path) as nc:
        assert {name: nc["time"].getncattr(name) for name in FILE_TIME_ATTRS} == FILE_TIME_ATTRS
        assert nc["time"].long_name == "time" and nc["time"].dtype == np.float64
    assert FILE_TIME_ATTRS["units"].startswith("seconds since ")
    back = open_result(path)
    assert back["time"].attrs == ds["time"].attrs  # units "s" again, nothing added
    np.testing.assert_array_equal(back["time"].values, ds["time"].values)
    with xr.open_dataset(path, decode_times=False) as raw:
        np.testing.assert_array_equal(raw["time"].values, ds["time"].values)
    with xr.open_dataset(path) as decoded:
        elapsed = (decoded["time"].values - np.datetime64("1970-01-01T00:00:00")) / np.timedelta64(1, "s")
        np.testing.assert_allclose(elapsed, ds["time"].values, rtol=0, atol=1e-9)


def test_a_time_coordinate_not_in_seconds_is_written_as_it_is(tmp_path):
    ds = result_dataset()
    ds["time"].attrs["units"] = "days since 2009-03-23"
    with netCDF4.Dataset(write_netcdf(ds, tmp_path / "case.nc")) as nc:
        assert nc["time"].units == "days since 2009-03-23" and "comment" not in nc["time"].ncattrs()


# ---------------------------------------------------------------------------------------------
# reading damaged files


@pytest.mark.parametrize("damage", ["truncated_half", "truncated_end", "empty", "garbage"])
def test_damaged_file_raises_a_clear_error(tmp_path, damage):
    path = write_netcdf(result_dataset(), tmp_path / "case.nc")
    data = path.read_bytes()
    path.write_bytes({"truncated_half": data[: len(data) // 2], "truncated_end": data[:-64], "empty": b"",
                      "garbage": b"not a netCDF file" * 50}[damage])
    with pytest.raises(ResultFileError) as caught:
        open_result(path)
    message = str(caught.value)
    assert str(path) in message and "corrupted or truncated" in message
    assert f"snakemake {path}" in message
    assert isinstance(caught.value, OSError)


def test_missing_file_raises_a_clear_error(tmp_path):
    path = tmp_path / "absent.nc"
    with pytest.raises(ResultFileError, match=f"result file {path} does not exist"):
        open_result(path)


# ---------------------------------------------------------------------------------------------
# provenance


def test_global_attributes(monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1237766400")  # 2009-03-23, the paper's publication day
    case = {"model": "FOAM", "maneuver": {"kind": "torque", "tau_max": 50.0, "tf": 10.0}}
    attrs = provenance.global_attributes("FOAM, torque pulse", case, {"diverged": False, "maneuver": case["maneuver"]})
    assert attrs["Conventions"] == "CF-1.11"
    assert attrs["title"] == "FOAM, torque pulse"
    assert attrs["institution"]
    assert attrs["history"] == f"2009-03-23T00:00:00Z created by hubbeam {hubbeam.__version__}"
    assert "Sensors & Transducers" in attrs["references"] and "2009" in attrs["references"]
    assert attrs["hubbeam_version"] == hubbeam.__version__
    assert attrs["source"] == f"hubbeam {hubbeam.__version__} (git commit {attrs['git_commit']})"
    for name in ("numpy", "numba", "scipy", "xarray"):
        assert attrs[f"{name}_version"] == metadata.version(name)
    assert json.loads(attrs["case_config"]) == case
    assert attrs["diverged"] == 0 and json.loads(attrs["maneuver"]) == case["maneuver"]
    assert "case_config" not in provenance.global_attributes("no case")


def test_extra_attributes_may_not_replace_provenance():
    with pytest.raises(ValueError, match="git_commit"):
        provenance.global_attributes("x", extra={"git_commit": "abc"})


def test_git_commit_is_unknown_without_git(monkeypatch):
    def no_git(*_args, **_kwargs):
        raise FileNotFoundError("git")

    provenance.git_commit.cache_clear()
    monkeypatch.setattr(subprocess, "run", no_git)
    try:
        assert provenance.git_commit() == "unknown"
    finally:
        provenance.git_commit.cache_clear()


def test_git_commit_in_the_repository(repo_root):
    if shutil.which("git") is None or subprocess.run(["git", "rev-parse", "HEAD"], cwd=repo_root,
                                                     capture_output=True).returncode != 0:
        pytest.skip("not a git checkout with commits")
    head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=repo_root, capture_output=True, text=True).stdout.strip()
    provenance.git_commit.cache_clear()
    assert provenance.git_commit().removesuffix("-dirty") == head


# ---------------------------------------------------------------------------------------------
# numba cache directory


def cache_dir_after_import(environment: dict) -> str:
    code = "import hubbeam, numba; print(numba.config.CACHE_DIR)"
    return subprocess.run([sys.executable, "-c", code], env=environment, capture_output=True, text=True,
                          check=True).stdout.strip()


def test_numba_cache_dir_is_keyed_by_the_sources(tmp_path):
    environment = {key: value for key, value in os.environ.items() if key != "NUMBA_CACHE_DIR"}
    environment["XDG_CACHE_HOME"] = str(tmp_path)
    expected = tmp_path / "hubbeam" / f"numba-{hubbeam.source_hash()}"
    assert cache_dir_after_import(environment) == str(expected)
    environment["NUMBA_CACHE_DIR"] = str(tmp_path / "mine")
    assert cache_dir_after_import(environment) == str(tmp_path / "mine")


def test_source_hash_changes_with_any_source_file(tmp_path):
    package = tmp_path / "pkg"
    (package / "core").mkdir(parents=True)
    (package / "__init__.py").write_text("")
    kernel = package / "core" / "kernel.py"
    kernel.write_text("X = 1\n")
    before = hubbeam.source_hash(package)
    assert hubbeam.source_hash(package) == before
    kernel.write_text("X = 2\n")
    after_edit = hubbeam.source_hash(package)
    assert after_edit != before
    (package / "core" / "__pycache__").mkdir()
    (package / "core" / "__pycache__" / "kernel.nbi").write_bytes(b"compiled")  # not a source
    assert hubbeam.source_hash(package) == after_edit
    kernel.rename(package / "core" / "renamed.py")
    assert hubbeam.source_hash(package) != after_edit
