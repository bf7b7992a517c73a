"""Benchmark hubbeam's jitted integrator against what a user would otherwise run.

    python -m benchmarks [--configfile FILE ...] [--benchmark-config FILE] [--output DIR]
                         [--repeats 5] [--run-cap 20] [--timing-budget 10]
                         [--skip-compilation] [--skip-extras]

from the repository root (``make benchmark`` runs it in the project environment). The settings
are the ``benchmark`` section of ``benchmarks/config.yaml`` (schema ``benchmarks/schema.yaml``),
run on the study config (``config/config.yaml``: beam, numerics, eigen grid, sweeps). Not part
of the test suite or of the workflow: timings depend on the machine, which is recorded beside
them.

Integrators (``integrators.csv``). For every case of ``benchmark.cases`` the transverse
tip deflection ``v(L)`` on the output grid is compared with a converged reference (hubbeam's Radau
IIA at ``benchmark.reference_rtol``; ``references.csv`` gives its own error estimates: the change
to a ten times looser tolerance, and the difference to scipy's Radau at that looser tolerance).
Each method searches the tolerance ladder ``benchmark.tolerances`` from the loosest rung and
stops at the first ``rtol`` (``atol = benchmark.atol_ratio * rtol`` on every free position and
velocity) that reaches ``max |v(L) - reference| <= benchmark.error_target``; its wall time is the
median of warm runs (compiled beforehand). The methods:

* ``hubbeam radau5``: hubbeam's Radau IIA kernel with dense output of the states
  (:func:`hubbeam.core.integrate.integrate_free`), and ``hubbeam simulate_kernel``: the same
  integration plus every output of a simulation dataset, at the tolerance found for the former
  (``outputs_ratio``: its wall time over the former's);
* ``scipy <method>``: ``scipy.integrate.solve_ivp`` with the same equations, the jitted
  first-order right-hand side (:mod:`hubbeam.core.first_order`) as ``fun`` (a fast RHS with
  scipy's stepping) and, for ``benchmark.jacobian_methods``, the jitted forward-difference
  Jacobian as ``jac`` (otherwise scipy's own finite differences); the run is split at the end of
  the maneuver as hubbeam's is. ``benchmark.scipy_cases`` get every method of
  ``benchmark.methods``, the other cases only ``benchmark.jacobian_methods`` (the fastest);
  the ``jacobian_methods`` run a second time with the jitted Jacobian;
* one row with a plain-Python right-hand side (every jitted function replaced by its Python
  source, :func:`hubbeam.simulation.reference.pure_python`, in :func:`benchmarks.cases.python_rhs`) for
  ``benchmark.python_rhs_case``, with the fastest scipy method that needs no jitted Jacobian.

A scipy run that exceeds ``--run-cap`` seconds is aborted (its row records the cap as a lower
bound, ``passed = False``), and no tighter rung is tried: a tighter tolerance never costs less.
Slow methods get fewer repetitions (``repeats`` column) so that the whole benchmark takes minutes.

Also written: ``compilation.csv`` (a fresh process's first ``simulate`` call with numba's cache
cold and warm, and the cold compile time of each kernel), ``scaling.csv`` (``simulate`` against
the number of modes and the simulated time), ``eigen.csv`` (``K22`` eigen-analyses per second),
``linear_modes.csv`` (a tracked, damped Campbell diagram over 200 speeds with 10 + 10 modes,
:mod:`benchmarks.linear_modes`), ``rig.csv`` (a sampled LQG loop on a servo rig against a Python
loop over the samples and against continuous feedback, :mod:`benchmarks.rig`), ``identification.csv``
(a frequency-response fit of five parameters to 500 frequencies against scipy's least_squares around
python-control, :mod:`benchmarks.identification`), ``identification_time_series.csv`` (a fit of three
parameters to a 10 s record of two signals at 1 kHz: hubbeam's fit, integrating the nonlinear model,
against scipy's least_squares around solve_ivp on its linearisation, the motion kept small enough
for the two to agree; the same module),
``sweeps.csv`` (throughput and accuracy of the parameter-sweep kernel) and ``machine.json``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import time
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
import pandas as pd

from benchmarks.cases import HUBBEAM, HUBBEAM_FULL, prepare_case, run_hubbeam
from benchmarks.compilation import compilation_rows
from benchmarks.extras import eigen_rows, scaling_rows, sweep_rows
from benchmarks.identification import identification_rows, time_series_rows
from benchmarks.linear import linear_rows
from benchmarks.linear_modes import campbell_rows
from benchmarks.machine import load_average, machine_info
from benchmarks.rig import rig_rows
from benchmarks.search import benchmark_case, case_methods, python_rhs_row
from benchmarks.settings import BENCHMARK_CONFIG, STUDY_CONFIG, load_settings
from hubbeam.configuration.settings import case_from_config
from hubbeam.core.first_order import first_order_jacobian
from hubbeam.model.parameters import BeamParameters
from hubbeam.results.paths import SHARED


def run(config_files: Sequence[str], benchmark_file: os.PathLike | str, output: Path,
        repeats: int, cap: float, budget: float, compilation: bool = True, extras: bool = True,
        log=print) -> dict[str, Path]:
    """Run the whole benchmark on the study config ``config_files`` with the settings of
    ``benchmark_file``; return the files written."""
    started = time.perf_counter()
    cfg = load_settings(config_files, benchmark_file)
    settings = cfg["benchmark"]
    params = BeamParameters.from_config(cfg)
    output.mkdir(parents=True, exist_ok=True)
    machine = machine_info()
    log(json.dumps(machine))
    resolved = {name: case_from_config({**cfg, "cases": settings["cases"]}, name)
                for name in sorted(settings["cases"])}
    benches = {name: prepare_case(name, case, params, cfg["numerics"], settings["output_step"])
               for name, case in resolved.items()}
    # compile every kernel once (not timed here: compilation.csv measures it)
    any_bench = next(iter(benches.values()))
    run_hubbeam(any_bench, 1e-3, 1e-5)
    run_hubbeam(any_bench, 1e-3, 1e-5, full=True)
    first_order_jacobian(0.0, np.zeros(2 * any_bench.free.size), any_bench.problem)
    rows, references = [], []
    for name, bench in benches.items():
        case_rows, info, reference = benchmark_case(bench, case_methods(settings, name), settings,
                                                    repeats, cap, budget, log)
        rows += case_rows
        references.append(info)
        if name == settings["python_rhs_case"]:
            rows.append(python_rhs_row(bench, case_rows, reference, settings, cap, log))
    written = {}
    columns = ["method", "settings", "wall_s", "compile_s", "rhs_calls", "max_err_m", "case",
               "model", "modes", "t_end_s", "rtol", "repeats", "passed", "outputs_ratio", "note",
               "ladder"]
    compile_rows = []
    if compilation:
        compile_rows = compilation_rows(config_files, resolved[settings["python_rhs_case"]])
        written["compilation"] = _write_csv(compile_rows, output / "compilation.csv")
    compile_s = {row["measurement"].removeprefix("cold compile: "): row.get("compile_s")
                 for row in compile_rows if row["measurement"].startswith("cold compile")}
    first_calls = {row["cache"]: row["first_call_s"] for row in compile_rows
                   if "first_call_s" in row}
    if first_calls:  # simulate_kernel's compile time: cold minus warm first simulate() call
        compile_s[HUBBEAM_FULL] = first_calls["cold"] - first_calls["warm"]
    for row in rows:
        if row["method"] == HUBBEAM_FULL:
            row["compile_s"] = compile_s.get(HUBBEAM_FULL, math.nan)
        elif row["method"] == HUBBEAM:
            row["compile_s"] = compile_s.get("radau5", math.nan)
        elif "plain-Python" in row["method"]:
            row["compile_s"] = 0.0
        else:
            row["compile_s"] = compile_s.get("rhs+jacobian" if "Jacobian" in row["method"]
                                             else "rhs", math.nan)
    written["integrators"] = _write_csv(rows, output / "integrators.csv", columns)
    written["references"] = _write_csv(references, output / "references.csv")
    if extras:
        written["scaling"] = _write_csv(scaling_rows(cfg, params, settings, repeats, budget),
                                        output / "scaling.csv")
        written["eigen"] = _write_csv(eigen_rows(cfg, params, repeats, budget),
                                      output / "eigen.csv")
        written["linear"] = _write_csv(linear_rows(cfg, params, repeats, budget),
                                       output / "linear.csv")
        written["linear_modes"] = _write_csv(campbell_rows(cfg, params, repeats, budget),
                                             output / "linear_modes.csv")
        written["rig"] = _write_csv(rig_rows(repeats, budget, log), output / "rig.csv")
        written["identification"] = _write_csv(identification_rows(repeats, budget), output / "identification.csv")
        written["identification_time_series"] = _write_csv(time_series_rows(repeats, budget),
                                                           output / "identification_time_series.csv")
        if "sweeps" in cfg:
            check = settings["sweep_check"]
            written["sweeps"] = _write_csv(sweep_rows(cfg, params, check["points"], check["rtol"]),
                                           output / "sweeps.csv")
    machine["load_average_at_end"] = load_average()
    machine["benchmark_wall_s"] = time.perf_counter() - started
    machine["settings"] = {"repeats": repeats, "run_cap_s": cap, "timing_budget_s": budget,
                           "config_files": [str(path) for path in config_files],
                           "benchmark_config": str(benchmark_file)}
    path = output / "machine.json"
    path.write_text(json.dumps(machine, indent=2) + "\n")
    written["machine"] = path
    return written


def _write_csv(rows: Sequence[Mapping], path: Path, columns: Sequence[str] | None = None) -> Path:
    frame = pd.DataFrame(list(rows))
    if columns is not None:
        frame = frame[[column for column in columns if column in frame]]
    frame.to_csv(path, index=False)
    return path


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m benchmarks",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--configfile", nargs="+", default=[str(STUDY_CONFIG)],
                        help="study config file(s), merged left to right (default: %(default)s)")
    parser.add_argument("--benchmark-config", default=str(BENCHMARK_CONFIG),
                        help="the benchmark's settings (default: %(default)s)")
    parser.add_argument("--output", type=Path, default=Path(SHARED.benchmarks()),
                        help="directory of the CSV files and machine.json (default: %(default)s)")
    parser.add_argument("--repeats", type=int, default=5,
                        help="warm runs per timing, median reported (default: %(default)s)")
    parser.add_argument("--run-cap", type=float, default=20.0,
                        help="seconds after which a scipy run is aborted (default: %(default)s)")
    parser.add_argument("--timing-budget", type=float, default=10.0,
                        help="seconds of repeated runs per row; slower methods get fewer "
                             "repeats, at least one (default: %(default)s)")
    parser.add_argument("--skip-compilation", action="store_true",
                        help="do not time cold and warm compilation in fresh processes")
    parser.add_argument("--skip-extras", action="store_true",
                        help="skip the scaling, eigen, linear-modes, rig, identification and sweep tables")
    args = parser.parse_args(argv)
    if args.repeats < 1 or args.run_cap <= 0 or args.timing_budget <= 0:
        parser.error(f"--repeats = {args.repeats}, --run-cap = {args.run_cap}, --timing-budget "
                     f"= {args.timing_budget}; allowed: repeats >= 1, cap and budget > 0")
    written = run(args.configfile, args.benchmark_config, args.output, args.repeats, args.run_cap,
                  args.timing_budget, compilation=not args.skip_compilation, extras=not args.skip_extras)
    for label, path in written.items():
        print(f"{label}: {path}")
    return 0

