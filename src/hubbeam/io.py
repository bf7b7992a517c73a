"""Writing result files atomically and reading them back with a clear error.

Results are netCDF-4 files written by xarray with the netcdf4 engine. Float variables are
compressed losslessly (zlib + shuffle); nothing is packed into integers. A file is first written
under a temporary name in the destination directory and then renamed over the destination
(``os.replace``, atomic on POSIX), so a crash or error never leaves a partial result where
Snakemake or a figure would take it for a finished one, and an existing file stays intact.
"""

from __future__ import annotations

import os
import secrets
from pathlib import Path

import numpy as np
import xarray as xr

#: Lossless compression of every floating-point variable.
FLOAT_ENCODING = {"zlib": True, "shuffle": True, "complevel": 4}


class ResultFileError(OSError):
    """A result file is missing, truncated or otherwise unreadable."""


def write_netcdf(ds: xr.Dataset, path: os.PathLike | str) -> Path:
    """Write ``ds`` to ``path`` (NETCDF4) atomically; return the path.

    Encodings carried by ``ds`` (for example from a file it was read from) are replaced: float
    variables get :data:`FLOAT_ENCODING`, all others the defaults.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    encoding = {name: dict(FLOAT_ENCODING) if np.issubdtype(variable.dtype, np.floating) else {}
                for name, variable in ds.variables.items()}
    temporary = path.with_name(f".{path.name}.{secrets.token_hex(6)}.tmp")
    try:
        ds.to_netcdf(temporary, mode="w", engine="netcdf4", format="NETCDF4", encoding=encoding)
        with open(temporary, "rb") as written:
            os.fsync(written.fileno())
        os.replace(temporary, path)
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise
    return path


def open_result(path: os.PathLike | str) -> xr.Dataset:
    """Read a result file completely into memory (the file is closed on return).

    Raises :class:`ResultFileError` naming the file if it is missing or cannot be decoded.
    """
    path = Path(path)
    if not path.is_file():
        raise ResultFileError(f"result file {path} does not exist; build it with `snakemake {path}`")
    try:
        with xr.open_dataset(path, engine="netcdf4", decode_timedelta=False) as ds:
            return ds.load()
    except Exception as error:
        raise ResultFileError(
            f"result file {path} cannot be read, it is corrupted or truncated "
            f"({type(error).__name__}: {error}); delete it and rebuild it with `snakemake {path}`"
        ) from error
