"""The one way a rule's script runs its job: logging into the rule's log file, the traceback kept.

Every rule runs the one script ``workflow/scripts/run_job.py``, a shim, ``run(snakemake)``: :func:`run`
turns the ``snakemake`` object Snakemake hands a script into a :class:`Job` (the rule's files by
name, its params, its log file) and :func:`run_job` runs on it the job function the rule's step
names (``params.job``, ``"module:function"`` of :mod:`hubbeam.pipeline.jobs`). While the job
runs, every log record of the package (``logging``, level INFO and up) goes to the log file,
written afresh, and Python's warnings with them; warnings also reach the console (standard
error). When the job raises, its traceback is written into the log file before the exception
goes on to Snakemake, so that the log of a failed job says where it failed.

This module imports nothing of the package but the frozen mapping: the script imports it, so
each of its imports would be a code input of every rule (:mod:`hubbeam.reporting.sourcedeps`); the
job's module is imported by its name, and its sources are the code inputs of its rule.
"""

from __future__ import annotations

import importlib
import logging
import sys
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hubbeam.model.frozen import FrozenMap

LOG = logging.getLogger(__name__)
#: how a log record is written in a job's log file
LOG_FORMAT = "%(asctime)s %(name)s %(levelname)s %(message)s"


@dataclass(frozen=True)
class Job:
    """What a job function receives: the rule's input and output files by name (a path, or a
    tuple of paths for a list), its params by name, and the path of its log file."""

    input: Mapping[str, Any]
    output: Mapping[str, Any]
    params: Mapping[str, Any]
    log: str


def _files(named) -> FrozenMap:
    """The named files of a Snakemake input or output list: a path as ``str``, a list as a tuple."""
    return FrozenMap({name: str(value) if isinstance(value, str) else tuple(map(str, value))
                      for name, value in named.items()})


def job_function(name: str) -> Callable[[Job], None]:
    """The job function named ``"module:function"`` (imported now)."""
    module, _, function = name.partition(":")
    return getattr(importlib.import_module(module), function)


def run(snakemake) -> None:
    """Run the job function its rule names (``params.job``) on the job of the ``snakemake`` object
    Snakemake hands the rule's script (:func:`run_job`). The files and params a rule does not name
    are not passed on."""
    params = FrozenMap(snakemake.params.items())
    run_job(job_function(params["job"]), Job(input=_files(snakemake.input), output=_files(snakemake.output),
                                              params=params, log=str(snakemake.log[0])))


def run_job(function: Callable[[Job], None], job: Job) -> None:
    """Run ``function(job)`` with the package's log records written into ``job.log`` (created
    afresh, its folder made if missing) and its warnings also on standard error; on an exception,
    write its traceback into the log, then raise it again."""
    Path(job.log).parent.mkdir(parents=True, exist_ok=True)
    to_file = logging.FileHandler(job.log, mode="w", encoding="utf-8")
    to_file.setFormatter(logging.Formatter(LOG_FORMAT))
    to_console = logging.StreamHandler(sys.stderr)
    to_console.setFormatter(logging.Formatter("%(levelname)s: %(message)s"))
    to_console.addFilter(lambda record: record.levelno == logging.WARNING)
    root = logging.getLogger()
    level = root.level
    root.addHandler(to_file)
    root.addHandler(to_console)
    root.setLevel(logging.INFO)
    logging.captureWarnings(True)
    name = getattr(function, "__qualname__", repr(function))
    start = time.perf_counter()
    try:
        function(job)
    except BaseException:
        LOG.exception("job %s failed after %.1f s", name, time.perf_counter() - start)
        raise
    else:
        LOG.info("job %s done in %.1f s", name, time.perf_counter() - start)
    finally:
        logging.captureWarnings(False)
        root.setLevel(level)
        for handler in (to_file, to_console):
            root.removeHandler(handler)
            handler.close()
