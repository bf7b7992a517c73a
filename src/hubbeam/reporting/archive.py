"""The results archive: a configuration's results in one ``.tar.gz`` with a SHA-256 manifest and a
Workflow Run RO-Crate (rule ``archive``, :func:`hubbeam.pipeline.jobs.reports.archive`).

The archive holds, under one top directory (``hubbeam-results/`` for the paper, ``<name>-results/``
for a study, ``archive_top`` of :class:`hubbeam.results.paths.StudyPaths`): every file given
(netCDF results, figures, tables, report), the workflow that made them (``Snakefile`` and every file under
``workflow/``), the configuration the workflow ran with (``config/config.used.yaml``),
``ro-crate-metadata.json`` (``hubbeam.reporting.crate``: what each file is, the software versions, the run)
and ``MANIFEST.sha256``, one ``<sha256>  <path>`` line per file in the format of ``sha256sum``, so
``tar xzf hubbeam-results.tar.gz && cd hubbeam-results && sha256sum -c MANIFEST.sha256`` checks
it. The archive is written under a temporary name beside the target and renamed when complete.
"""

import io
import os
import tarfile
from collections.abc import Iterable, Mapping
from pathlib import Path

import yaml

from hubbeam.reporting.crate import MAIN_WORKFLOW, METADATA_NAME, WORKFLOW_DIR, Member, crate_metadata, sha256
from hubbeam.results.io import staged
from hubbeam.results.paths import SHARED

#: the top folder of the paper's archive (a study's is named after it)
TOP = SHARED.archive_top
MANIFEST = "MANIFEST.sha256"
CONFIG_NAME = "config/config.used.yaml"


def _member(name: str, data: bytes, mtime: float, top: str) -> tuple[tarfile.TarInfo, io.BytesIO]:
    info = tarfile.TarInfo(f"{top}/{name}")
    info.size, info.mtime, info.mode = len(data), int(mtime), 0o644
    info.uid = info.gid = 0
    info.uname = info.gname = ""
    return info, io.BytesIO(data)


def workflow_files(workflow_root: os.PathLike | str) -> list[str]:
    """The workflow in ``workflow_root`` (the repository): ``Snakefile`` and every file under
    ``workflow/``, without hidden files and Python caches; paths relative to ``workflow_root``."""
    workflow_root = Path(workflow_root)
    parts = [path.relative_to(workflow_root).as_posix()
             for path in (workflow_root / WORKFLOW_DIR).rglob("*") if path.is_file()]
    return [MAIN_WORKFLOW] + sorted(name for name in parts if not any(
        part.startswith(".") or part == "__pycache__" for part in name.split("/")))


def _read(root: Path, names: Iterable[str], what: str) -> list[Member]:
    members = []
    for name in names:
        path = root / name
        if not path.is_file():
            raise FileNotFoundError(f"{what} {path} does not exist")
        members.append(Member(name, path.read_bytes(), path.stat().st_mtime))
    return members


def build_archive(files: Iterable[os.PathLike | str], config: Mapping, output: os.PathLike | str,
                  workflow_root: os.PathLike | str, root: os.PathLike | str = ".",
                  top: str = TOP) -> Path:
    """Write ``output`` (.tar.gz) with ``files`` (paths relative to ``root``), the workflow in
    ``workflow_root``, the config, the crate and the manifest, all under the directory ``top``;
    atomic (``hubbeam.results.io.staged``: temporary file + rename). Raises FileNotFoundError naming a missing file."""
    root, output = Path(root), Path(output)
    names = sorted({Path(os.path.relpath(Path(root, f), root)).as_posix() for f in files})
    workflow = workflow_files(workflow_root)
    reserved = sorted(({CONFIG_NAME, MANIFEST, METADATA_NAME} | set(workflow)) & set(names))
    if reserved:
        raise ValueError(f"{reserved} are written by the archive itself; allowed: other result paths")
    results = _read(root, names, "archive input")
    newest = max((m.mtime for m in results), default=0.0)
    config_text = yaml.safe_dump(_plain(config), sort_keys=True).encode()
    members = [*results, *_read(Path(workflow_root), workflow, "workflow file"),
               Member(CONFIG_NAME, config_text, newest)]
    members.append(Member(METADATA_NAME, crate_metadata(members, CONFIG_NAME).encode(), newest))
    members.sort()
    manifest = "".join(f"{sha256(data)}  {name}\n" for name, data, _ in members).encode()
    with staged(output) as (temporary,):
        with tarfile.open(temporary, "w:gz", format=tarfile.PAX_FORMAT) as tar:
            for name, data, mtime in [(MANIFEST, manifest, newest), *members]:
                tar.addfile(*_member(name, data, mtime, top))
    return output


def _plain(value):
    """Snakemake's config is a dict subclass with nested wrappers; YAML wants plain types."""
    if isinstance(value, Mapping):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


def verify_archive(path: os.PathLike | str, top: str = TOP) -> list[str]:
    """Problems found in the archive (empty list: every file matches the manifest and every file
    is listed)."""
    with tarfile.open(path, "r:gz") as tar:
        contents = {m.name.removeprefix(f"{top}/"): tar.extractfile(m).read()
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
