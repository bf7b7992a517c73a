"""Writing result files atomically and reading them back with a clear error.

Results are netCDF-4 files written by xarray with the netcdf4 engine. Float variables are
compressed losslessly (zlib + shuffle); nothing is packed into integers. The files follow CF-1.11:
coordinate variables carry no ``_FillValue`` (CF 2.5.1), and the time coordinate, seconds from the
start of the run in memory (units ``s``), is stored with a reference time as CF 4.4 requires
(:data:`FILE_TIME_ATTRS`: a nominal epoch, explained in the variable's ``comment``).
:func:`open_result` reads it back as plain seconds; so does
``xarray.open_dataset(path, decode_times=False)`` (the ``units`` then name the epoch), whereas a
plain ``xarray.open_dataset(path)`` decodes it to dates from 1970-01-01.

Every file a rule produces is written atomically: first under a temporary name in the
destination directory, then renamed over the destination (``os.replace``, atomic on POSIX). A
crash, an error or a kill therefore never leaves a partial file under the destination's name,
where Snakemake or a figure would take it for a finished one, and an existing file stays intact
until its replacement is complete. :func:`write_netcdf` writes a dataset this way;
:func:`staged` does it for any writer (figures, tables, reports, archives), and
:func:`write_text` for a text. Temporaries are hidden entries ``.<name>.<random>.tmp`` beside the
destination; one left behind by a writer killed without a chance to clean up (``SIGKILL``, power
loss) is removed by the next write of the same file. Two processes must not write the same file
at the same time (Snakemake never runs two jobs with the same output).
"""

from __future__ import annotations

import contextlib
import glob
import os
import secrets
import shutil
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import xarray as xr

#: Lossless compression of every floating-point variable.
FLOAT_ENCODING = {"zlib": True, "shuffle": True, "complevel": 4}


#: The time coordinate's name and its attributes on disk. A run's t = 0 (the start of the maneuver)
#: has no date, but CF 4.4 wants a reference time in a time coordinate's units; the epoch below is
#: nominal, and the comment says so to anyone reading a file without hubbeam.
TIME = "time"
FILE_TIME_ATTRS = {
    "units": "seconds since 1970-01-01 00:00:00",
    "calendar": "standard",
    "units_metadata": "leap_seconds: none",
    "comment": "seconds from the start of the run; the reference date in units is nominal (CF "
               "requires one), so read with decode_times=False to get seconds",
}


class ResultFileError(OSError):
    """A result file is missing, truncated or otherwise unreadable."""


def temporary_path(path: os.PathLike | str) -> Path:
    """A fresh hidden temporary name beside ``path``: ``.<name>.<random>.tmp``."""
    path = Path(path)
    return path.with_name(f".{path.name}.{secrets.token_hex(6)}.tmp")


def remove_stale_temporaries(path: os.PathLike | str) -> list[Path]:
    """Delete the temporaries (files or staging directories) an earlier, killed writer of
    ``path`` left beside it; return what was removed."""
    path = Path(path)
    stale = sorted(path.parent.glob(f".{glob.escape(path.name)}.*.tmp"))
    for entry in stale:
        if entry.is_dir() and not entry.is_symlink():
            shutil.rmtree(entry, ignore_errors=True)
        else:
            entry.unlink(missing_ok=True)
    return stale


def _fsync(path: Path) -> None:
    with open(path, "rb") as written:
        os.fsync(written.fileno())


@contextlib.contextmanager
def staged(*paths: os.PathLike | str) -> Iterator[list[Path]]:
    """Write the files ``paths`` atomically: yield stand-ins to write instead, rename when done.

    The stand-ins have the destinations' own file names, inside a hidden staging directory
    (``.<name of the first file>.<random>.tmp/``) beside each destination directory, so writers
    that derive sibling names (``fig05.pdf`` -> ``fig05.png``, ``table1.csv`` -> ``table1.md``)
    or pick a format by suffix work unchanged. When the block ends normally, every stand-in must
    exist; each is flushed to disk and renamed over its destination. When the block raises (or a
    stand-in is missing), no destination is touched and the staging directories are removed::

        with staged("figures/fig05.pdf", "figures/fig05.png") as (pdf, _png):
            save_figure(fig, pdf)  # writes pdf and the png beside it
    """
    destinations = [Path(path) for path in paths]
    if not destinations:
        raise ValueError("staged() needs at least one destination path")
    if len(set(destinations)) != len(destinations):
        raise ValueError(f"staged() got a destination twice: {[str(p) for p in destinations]}")
    for destination in destinations:
        remove_stale_temporaries(destination)
    staging: dict[Path, Path] = {}  # destination directory -> its staging directory
    try:
        for destination in destinations:
            if destination.parent not in staging:
                destination.parent.mkdir(parents=True, exist_ok=True)
                staging[destination.parent] = temporary_path(destination)
                staging[destination.parent].mkdir()
        stand_ins = [staging[destination.parent] / destination.name for destination in destinations]
        yield stand_ins
        missing = [str(destination) for destination, stand_in in zip(destinations, stand_ins)
                   if not stand_in.is_file()]
        if missing:
            raise FileNotFoundError(f"the writer did not produce {', '.join(missing)}")
        for stand_in in stand_ins:
            _fsync(stand_in)
        for destination, stand_in in zip(destinations, stand_ins):
            os.replace(stand_in, destination)
    finally:
        for directory in staging.values():
            shutil.rmtree(directory, ignore_errors=True)


def write_text(path: os.PathLike | str, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically; return the path."""
    path = Path(path)
    with staged(path) as (stand_in,):
        stand_in.write_text(text, encoding="utf-8")
    return path


def write_netcdf(ds: xr.Dataset, path: os.PathLike | str) -> Path:
    """Write ``ds`` to ``path`` (NETCDF4) atomically; return the path.

    Encodings carried by ``ds`` (for example from a file it was read from) are replaced: float
    variables get :data:`FLOAT_ENCODING`, all others the defaults, and no coordinate gets a
    ``_FillValue``. A time coordinate in seconds (units ``s``) is stored with
    :data:`FILE_TIME_ATTRS`. The temporary file's name does not end in ``.nc``, so no partial file
    ever looks like a result.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(path)
    ds = _time_for_file(ds)
    encoding = {name: _encoding(variable, is_coordinate=name in ds.coords)
                for name, variable in ds.variables.items()}
    temporary = temporary_path(path)
    try:
        ds.to_netcdf(temporary, mode="w", engine="netcdf4", format="NETCDF4", encoding=encoding)
        _fsync(temporary)
        os.replace(temporary, path)
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise
    return path


def _encoding(variable: xr.Variable, is_coordinate: bool) -> dict:
    encoding = dict(FLOAT_ENCODING) if np.issubdtype(variable.dtype, np.floating) else {}
    if is_coordinate:
        encoding["_FillValue"] = None  # CF 2.5.1: no missing values in coordinate variables
    return encoding


def _time_for_file(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with its time coordinate in seconds given :data:`FILE_TIME_ATTRS` (a shallow copy)."""
    if TIME not in ds.coords or ds[TIME].attrs.get("units") != "s":
        return ds
    return _with_time_attrs(ds, {**ds[TIME].attrs, **FILE_TIME_ATTRS})


def _time_from_file(ds: xr.Dataset) -> xr.Dataset:
    """Undo :func:`_time_for_file`: the time coordinate back in plain seconds (units ``s``)."""
    if TIME not in ds.coords or ds[TIME].attrs.get("units") != FILE_TIME_ATTRS["units"]:
        return ds
    attrs = {key: value for key, value in ds[TIME].attrs.items() if FILE_TIME_ATTRS.get(key) != value}
    return _with_time_attrs(ds, {**attrs, "units": "s"})


def _with_time_attrs(ds: xr.Dataset, attrs: dict) -> xr.Dataset:
    time = ds[TIME].copy(deep=False)
    time.attrs = attrs
    return ds.assign_coords({TIME: time})


def open_result(path: os.PathLike | str) -> xr.Dataset:
    """Read a result file completely into memory (the file is closed on return), with the time
    coordinate in seconds from the start of the run (units ``s``, as the dataset was built).

    Raises :class:`ResultFileError` naming the file if it is missing or cannot be decoded.
    """
    path = Path(path)
    if not path.is_file():
        raise ResultFileError(f"result file {path} does not exist; build it with `snakemake {path}`")
    try:
        with xr.open_dataset(path, engine="netcdf4", decode_times=False, decode_timedelta=False) as ds:
            return _time_from_file(ds.load())
    except Exception as error:
        raise ResultFileError(
            f"result file {path} cannot be read, it is corrupted or truncated "
            f"({type(error).__name__}: {error}); delete it and rebuild it with `snakemake {path}`"
        ) from error
