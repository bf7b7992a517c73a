"""One compilation measurement in a fresh process, printed as a JSON line (run by
:mod:`benchmarks.compilation` with its own ``NUMBA_CACHE_DIR``)::

    python -m benchmarks.fresh_process first-call CONFIG_FILES_JSON CASE_JSON
    python -m benchmarks.fresh_process {radau5,rhs,rhs+jacobian} CONFIG_FILES_JSON CASE_JSON

``first-call``: the import of hubbeam and the first and second ``simulate`` call of the case;
a kernel name: the compile time of that kernel alone. hubbeam is imported inside the functions,
so that ``first-call`` times the import too.
"""

from __future__ import annotations

import json
import sys
import time
from collections.abc import Sequence

KERNELS = ("radau5", "rhs", "rhs+jacobian")


def first_call(config_files: list[str], case: dict) -> dict:
    """Seconds to import hubbeam, of the first ``simulate`` call and of the second; numba's
    cache misses and hits of the simulation kernels (``FAMILY_KERNELS``)."""
    start = time.perf_counter()
    from hubbeam.configuration.load import load_config
    from hubbeam.configuration.settings import Numerics, case_from_config
    from hubbeam.core.integrate import FAMILY_KERNELS
    from hubbeam.model.parameters import BeamParameters
    from hubbeam.simulation.simulate import simulate

    cfg = load_config(config_files)
    resolved = case_from_config({**cfg, "cases": {"c": case}}, "c")
    params = BeamParameters.from_config(cfg)
    imported = time.perf_counter()
    simulate(resolved, params, Numerics.from_mapping(cfg["numerics"]))
    first = time.perf_counter()
    simulate(resolved, params, Numerics.from_mapping(cfg["numerics"]))
    second = time.perf_counter()
    return {"import_s": imported - start, "first_call_s": first - imported,
            "second_call_s": second - first,
            "cache_misses": sum(sum(kernel.stats.cache_misses.values())
                                for kernel in FAMILY_KERNELS.values()),
            "cache_hits": sum(sum(kernel.stats.cache_hits.values())
                              for kernel in FAMILY_KERNELS.values())}


def compile_kernel(kernel: str, config_files: list[str], case: dict) -> dict:
    """Seconds of the first call of ``kernel`` (one of :data:`KERNELS`): its compilation."""
    import numpy as np

    from benchmarks.cases import prepare_case, run_hubbeam
    from hubbeam.configuration.load import load_config
    from hubbeam.configuration.settings import case_from_config
    from hubbeam.core.first_order import first_order_jacobian, first_order_rhs
    from hubbeam.model.parameters import BeamParameters

    cfg = load_config(config_files)
    resolved = case_from_config({**cfg, "cases": {"c": case}}, "c")
    bench = prepare_case("c", resolved, BeamParameters.from_config(cfg), cfg["numerics"], 0.01)
    z = np.zeros(2 * bench.free.size)
    start = time.perf_counter()
    if kernel == "radau5":
        run_hubbeam(bench, 1e-6, 1e-8)
    else:
        first_order_rhs(0.0, z, bench.problem)
        if kernel == "rhs+jacobian":
            first_order_jacobian(0.0, z, bench.problem)
    return {"compile_s": time.perf_counter() - start}


def main(argv: Sequence[str]) -> int:
    measurement, config_files, case = argv[0], json.loads(argv[1]), json.loads(argv[2])
    if measurement == "first-call":
        result = first_call(config_files, case)
    elif measurement in KERNELS:
        result = compile_kernel(measurement, config_files, case)
    else:
        raise SystemExit(f"measurement: got {measurement!r}; allowed: first-call, {', '.join(KERNELS)}")
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
