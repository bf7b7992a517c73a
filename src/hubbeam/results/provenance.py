"""Provenance of every result file: CF-1.11 global attributes, versions and the git commit."""

from __future__ import annotations

import datetime
import json
import os
import platform
import subprocess
import time
from collections.abc import Iterable, Mapping
from functools import lru_cache
from importlib import metadata
from pathlib import Path
from typing import Any

from hubbeam import __version__

CONVENTIONS = "CF-1.11"
INSTITUTION = "hubbeam project: independent reproduction, not affiliated with the paper's authors"
REFERENCES = (
    "Bai, S., Ben-Tzvi, P., Zhou, Q., Huang, X.: A Study on Dynamic Stiffening of a Rotating Beam "
    "with a Tip Mass. Sensors & Transducers Journal, Vol. 5, Special Issue, March 2009, pp. 53-68."
)
#: Distributions whose versions are recorded as ``<name>_version`` attributes.
RECORDED_VERSIONS = ("numpy", "numba", "llvmlite", "scipy", "xarray", "netCDF4")
#: Distributions the results archive lists as the workflow's software: those above, the workflow
#: engine, what draws the figures and tables, and what writes the archive's description.
WORKFLOW_DISTRIBUTIONS = (*RECORDED_VERSIONS, "snakemake", "matplotlib", "pandas", "PyYAML",
                          "jsonschema", "rocrate")


@lru_cache(maxsize=1)
def git_commit() -> str:
    """HEAD commit of the source tree ('-dirty' appended if tracked files differ), else 'unknown'."""
    source_dir = Path(__file__).resolve().parents[1]

    def git(*args: str) -> str:
        return subprocess.run(["git", *args], cwd=source_dir, capture_output=True, text=True,
                              check=True, timeout=30).stdout.strip()

    try:
        commit = git("rev-parse", "--verify", "HEAD")
        dirty = git("status", "--porcelain", "--untracked-files=no")
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return f"{commit}-dirty" if dirty else commit


def versions(distributions: Iterable[str]) -> dict[str, str]:
    """Installed version of each distribution (name as given -> version)."""
    return {name: metadata.version(name) for name in distributions}


def iso_utc(seconds: float) -> str:
    """POSIX time ``seconds`` in ISO 8601, UTC, to the second: ``2009-03-23T00:00:00+00:00``."""
    return datetime.datetime.fromtimestamp(int(seconds), tz=datetime.UTC).isoformat()


def timestamp() -> str:
    """Current UTC time in ISO 8601 (``...Z``), or ``SOURCE_DATE_EPOCH`` when set (reproducible
    builds)."""
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    return iso_utc(int(epoch) if epoch else time.time()).replace("+00:00", "Z")


def global_attributes(title: str, case_config: Mapping | None = None,
                      extra: Mapping[str, Any] | None = None) -> dict:
    """Global attributes of a result file.

    ``case_config`` (the resolved case, see ``hubbeam.configuration.settings.Case.to_dict``) is stored as a JSON
    string. ``extra`` adds attributes; mappings become JSON strings and booleans 0/1, as netCDF has
    neither. An ``extra`` key may not replace one of the provenance attributes.
    """
    commit = git_commit()
    attributes = {
        "Conventions": CONVENTIONS,
        "title": title,
        "institution": INSTITUTION,
        "source": f"hubbeam {__version__} (git commit {commit})",
        "history": f"{timestamp()} created by hubbeam {__version__}",
        "references": REFERENCES,
        "hubbeam_version": __version__,
        "git_commit": commit,
        "python_version": platform.python_version(),
        **{f"{name.lower()}_version": version for name, version in versions(RECORDED_VERSIONS).items()},
    }
    if case_config is not None:
        attributes["case_config"] = json.dumps(case_config, sort_keys=True)
    clashes = sorted(set(extra or {}) & set(attributes))
    if clashes:
        raise ValueError(f"extra attributes {clashes} would replace provenance attributes; "
                         "allowed: new attribute names")
    for name, value in (extra or {}).items():
        attributes[name] = _netcdf_value(value)
    return attributes


#: the attributes :func:`global_attributes` writes besides the versions (``<name>_version``)
PROVENANCE_ATTRIBUTES = ("Conventions", "title", "institution", "source", "history", "references",
                         "git_commit", "case_config")


def without_provenance(attrs: Mapping[str, Any]) -> dict:
    """``attrs`` of a result read back, less what :func:`global_attributes` wrote: the attributes
    a product derived from it carries on."""
    return {key: value for key, value in attrs.items()
            if key not in PROVENANCE_ATTRIBUTES and not key.endswith("_version")}


def _netcdf_value(value: Any) -> Any:
    if isinstance(value, Mapping):
        return json.dumps(value, sort_keys=True)
    if isinstance(value, bool):
        return int(value)
    return value
