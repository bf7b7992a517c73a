"""Studies: any hub-beam experiment in a results folder of its own.

A study is one config file with a top-level ``study`` section (``name``, optional ``title``,
``description``, ``comparisons``); ``snakemake --configfile studies/<name>.yaml`` runs it and
writes only under ``results/<name>/`` (:func:`hubbeam.results.paths.study_paths`). A config without
``study`` is the paper (Bai et al. 2009), whose products stay directly under ``results/``. Two
config files that claim the same folder are rejected: the first run writes the marker
``results/<name>/.study`` with the path of the config file that owns the folder.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

from hubbeam.results.paths import DEFAULT_CONFIG_FILE, StudyPaths

#: the file in a study's folder that records the config file owning it
MARKER = ".study"


class StudyError(ValueError):
    """A study cannot run as configured (the message names the folder and the config files)."""


def base_config_files(cfg: Mapping) -> tuple[str, ...]:
    """The config files ``cfg`` (the config files given to Snakemake) is merged onto: none for a
    study, which stands alone; config/config.yaml for any other (a small file changing a setting
    of the paper's)."""
    return () if "study" in cfg else (DEFAULT_CONFIG_FILE,)


def claim_results_dir(folder: os.PathLike | str, config_file: os.PathLike | str) -> Path:
    """Record ``config_file`` as the owner of ``folder`` (its ``.study`` marker), or raise
    :class:`StudyError` when another config file owns it already (:func:`check_results_dir`)."""
    marker = check_results_dir(folder, config_file)
    if not marker.is_file():
        marker.parent.mkdir(parents=True, exist_ok=True)
        marker.write_text(_owner(config_file) + "\n", encoding="utf-8")
    return marker


def check_results_dir(folder: os.PathLike | str, config_file: os.PathLike | str) -> Path:
    """The ``.study`` marker of ``folder``; :class:`StudyError` when it names a config file other
    than ``config_file``. Writes nothing. Paths are compared as given relative to the working
    directory, so a moved checkout keeps its claims."""
    marker = Path(folder, MARKER)
    owner = _owner(config_file)
    if marker.is_file():
        recorded = marker.read_text(encoding="utf-8").strip()
        if recorded != owner:
            raise StudyError(
                f"study.name: the folder {folder} belongs to the study of {recorded} (recorded in "
                f"{marker}), not to {owner}; allowed: a study name no other config file uses "
                f"(rename the study, or delete {folder} to give it to {owner})")
    return marker


def _owner(config_file: os.PathLike | str) -> str:
    return Path(os.path.relpath(config_file)).as_posix()


def claim_folder(paths: StudyPaths, config_file: os.PathLike | str) -> Path | None:
    """:func:`claim_results_dir` for a configuration's folders when they are its own (a study's);
    the default folders are shared by config/config.yaml and the files extending it."""
    return claim_results_dir(paths.results, config_file) if paths.owned else None


def check_folder(paths: StudyPaths, config_file: os.PathLike | str) -> None:
    """:func:`check_results_dir` for a configuration's own folders (a study's); writes nothing."""
    if paths.owned:
        check_results_dir(paths.results, config_file)
