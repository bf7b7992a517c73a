"""Bundle the study's results into one ``.tar.gz`` with a SHA-256 manifest (rule ``archive``).

The archive holds, under one top directory ``hubbeam-results/``: every file given (netCDF results,
figures, tables, report), the configuration the workflow ran with (``config/config.used.yaml``)
and ``MANIFEST.sha256``, one ``<sha256>  <path>`` line per file in the format of ``sha256sum``, so
``tar xzf hubbeam-results.tar.gz && cd hubbeam-results && sha256sum -c MANIFEST.sha256`` checks
it. The archive is written under a temporary name beside the target and renamed when complete.

Run by Snakemake (``snakemake`` global) or imported (``build_archive``, ``verify_archive``).
"""

import hashlib
import io
import os
import tarfile
from collections.abc import Iterable, Mapping
from pathlib import Path

import yaml

from hubbeam.io import staged

TOP = "hubbeam-results"
MANIFEST = "MANIFEST.sha256"
CONFIG_NAME = "config/config.used.yaml"


def sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def _member(name: str, data: bytes, mtime: float) -> tuple[tarfile.TarInfo, io.BytesIO]:
    info = tarfile.TarInfo(f"{TOP}/{name}")
    info.size, info.mtime, info.mode = len(data), int(mtime), 0o644
    info.uid = info.gid = 0
    info.uname = info.gname = ""
    return info, io.BytesIO(data)


def build_archive(files: Iterable[os.PathLike | str], config: Mapping, output: os.PathLike | str,
                  root: os.PathLike | str = ".") -> Path:
    """Write ``output`` (.tar.gz) with ``files`` (paths relative to ``root``), the config and the
    manifest; atomic (``hubbeam.io.staged``: temporary file + rename). Raises FileNotFoundError
    naming a missing file."""
    root, output = Path(root), Path(output)
    names = sorted({Path(os.path.relpath(Path(root, f), root)).as_posix() for f in files})
    if CONFIG_NAME in names or MANIFEST in names:
        raise ValueError(f"{CONFIG_NAME} and {MANIFEST} are written by the archive itself")
    members = []
    for name in names:
        path = root / name
        if not path.is_file():
            raise FileNotFoundError(f"archive input {path} does not exist")
        members.append((name, path.read_bytes(), path.stat().st_mtime))
    config_text = yaml.safe_dump(_plain(config), sort_keys=True).encode()
    newest = max((m for *_, m in members), default=0.0)
    members.append((CONFIG_NAME, config_text, newest))
    members.sort()
    manifest = "".join(f"{sha256(data)}  {name}\n" for name, data, _ in members).encode()
    with staged(output) as (temporary,):
        with tarfile.open(temporary, "w:gz", format=tarfile.PAX_FORMAT) as tar:
            for name, data, mtime in [(MANIFEST, manifest, newest), *members]:
                tar.addfile(*_member(name, data, mtime))
    return output


def _plain(value):
    """Snakemake's config is a dict subclass with nested wrappers; YAML wants plain types."""
    if isinstance(value, Mapping):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


def verify_archive(path: os.PathLike | str) -> list[str]:
    """Problems found in the archive (empty list: every file matches the manifest and every file
    is listed)."""
    with tarfile.open(path, "r:gz") as tar:
        contents = {m.name.removeprefix(f"{TOP}/"): tar.extractfile(m).read()
                    for m in tar.getmembers() if m.isfile()}
    if MANIFEST not in contents:
        return [f"{path}: no {MANIFEST}"]
    listed = {}
    for line in contents.pop(MANIFEST).decode().splitlines():
        digest, _, name = line.partition("  ")
        listed[name] = digest
    problems = [f"{name}: listed in {MANIFEST} but missing" for name in sorted(set(listed) - set(contents))]
    problems += [f"{name}: not listed in {MANIFEST}" for name in sorted(set(contents) - set(listed))]
    problems += [f"{name}: SHA-256 does not match {MANIFEST}" for name in sorted(set(listed) & set(contents))
                 if sha256(contents[name]) != listed[name]]
    return problems


if "snakemake" in globals():
    written = build_archive(snakemake.input, snakemake.params.config, snakemake.output[0])
    problems = verify_archive(written)
    with open(snakemake.log[0], "w") as log:
        print(f"{written}: {len(snakemake.input)} files + config + manifest; "
              f"verification: {problems or 'ok'}", file=log)
    if problems:
        raise RuntimeError(f"{written} does not verify: {problems}")
