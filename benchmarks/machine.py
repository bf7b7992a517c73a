"""``machine.json``: where the benchmark ran (CPU, load, library versions, source state)."""

from __future__ import annotations

import os
import platform
from importlib import metadata
from pathlib import Path

from hubbeam import __version__
from hubbeam.results.provenance import RECORDED_VERSIONS, git_commit
from hubbeam.simulation.sweep import default_threads


def load_average() -> list[float] | None:
    """The 1, 5 and 15 minute load averages, None where the platform has none."""
    return list(os.getloadavg()) if hasattr(os, "getloadavg") else None


def machine_info() -> dict:
    """CPU model, cores, load, library versions and the source state of this benchmark."""
    cpu = "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        cpu = platform.processor() or "unknown"
    return {
        "cpu_model": cpu,
        "logical_cpus": os.cpu_count(),
        "usable_cpus": default_threads(),
        "load_average_1_5_15": load_average(),
        "platform": platform.platform(),
        "python": platform.python_version(),
        **{name.lower(): metadata.version(name) for name in RECORDED_VERSIONS},
        "hubbeam": __version__,
        "git_commit": git_commit(),
        "numba_cache_dir": os.environ.get("NUMBA_CACHE_DIR"),
    }
