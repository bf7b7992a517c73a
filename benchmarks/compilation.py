"""``compilation.csv``: compile and first-call times in fresh processes
(:mod:`benchmarks.fresh_process`), with numba's cache cold and warm."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from collections.abc import Mapping, Sequence
from pathlib import Path

from benchmarks.fresh_process import KERNELS

#: the directory holding the ``benchmarks`` package, put on the fresh process's path
ROOT = Path(__file__).resolve().parents[1]


def fresh_process(measurement: str, config_files: Sequence[str], case: Mapping,
                  cache_dir: str) -> dict:
    """Run one measurement of :mod:`benchmarks.fresh_process` with numba's cache in ``cache_dir``."""
    env = dict(os.environ, NUMBA_CACHE_DIR=cache_dir)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT), env.get("PYTHONPATH")]))
    env.pop("HUBBEAM_NO_JIT_CACHE", None)
    done = subprocess.run([sys.executable, "-m", "benchmarks.fresh_process", measurement,
                           json.dumps([str(path) for path in config_files]), json.dumps(case)],
                          env=env, capture_output=True, text=True, check=True)
    return json.loads(done.stdout.strip().splitlines()[-1])


def compilation_rows(config_files: Sequence[str], case: Mapping) -> list[dict]:
    """Fresh processes with an empty numba cache (cold) and with the cache they left (warm)."""
    rows = []
    with tempfile.TemporaryDirectory(prefix="hubbeam-numba-") as cache:
        for state in ("cold", "warm"):
            rows.append({"measurement": "fresh process, first simulate() call", "cache": state,
                         **fresh_process("first-call", config_files, case, cache)})
    for kernel in KERNELS:
        with tempfile.TemporaryDirectory(prefix="hubbeam-numba-") as cache:
            rows.append({"measurement": f"cold compile: {kernel}", "cache": "cold",
                         **fresh_process(kernel, config_files, case, cache)})
    return rows
