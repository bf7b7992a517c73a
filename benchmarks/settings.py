"""The benchmark's settings: ``benchmarks/config.yaml`` (the ``benchmark`` section, schema
``benchmarks/schema.yaml``) validated together with the study config it runs on."""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

from hubbeam.configuration.load import Section, load_config
from hubbeam.configuration.schema import Problem, read_schema
from hubbeam.model import limits

HERE = Path(__file__).resolve().parent
BENCHMARK_CONFIG = HERE / "config.yaml"
STUDY_CONFIG = HERE.parent / "config" / "config.yaml"
#: a reference tolerance tighter than this is below what double precision can resolve
MIN_REFERENCE_RTOL = 100 * 2.0**-52


def cross_checks(cfg: dict) -> list[Problem]:
    """What the schema cannot express: the case references name benchmark cases, the cases fit
    the beam and the comparison grid, and the reference tolerance is resolvable."""
    benchmark, length = cfg["benchmark"], cfg["beam"]["length"]
    cases, scipy_cases = benchmark["cases"], benchmark["scipy_cases"]
    problems = []
    references = [("python_rhs_case", benchmark["python_rhs_case"]),
                  ("scaling.case", benchmark["scaling"]["case"])]
    references += [(f"scipy_cases[{i}]", name) for i, name in enumerate(scipy_cases)]
    for key, name in references:
        if name not in cases:
            problems.append(Problem(f"benchmark.{key}", f"got {name!r}; allowed: a name of "
                                    f"benchmark.cases ({', '.join(sorted(cases))})"))
    if benchmark["python_rhs_case"] not in scipy_cases:
        problems.append(Problem("benchmark.python_rhs_case", f"got {benchmark['python_rhs_case']!r}; "
                                "allowed: one of benchmark.scipy_cases"))
    step = benchmark["output_step"]
    for name, case in cases.items():
        if case["t_end"] < step:
            problems.append(Problem(f"benchmark.cases.{name}.t_end",
                                    f"got {case['t_end']}; allowed: t_end >= benchmark.output_step = {step}"))
        position = case.get("tip_mass", {}).get("position")
        if position is not None and position > length:
            problems.append(Problem(f"benchmark.cases.{name}.tip_mass.position",
                                    f"got {position}; allowed: 0 <= position <= beam.length = {length}"))
    if benchmark["reference_rtol"] < MIN_REFERENCE_RTOL:
        problems.append(Problem("benchmark.reference_rtol", f"got {benchmark['reference_rtol']}; allowed: "
                                f"at least 100 machine epsilons ({MIN_REFERENCE_RTOL:.3g})"))
    return problems


_RTOL_BOUND = {"minimum": limits.MIN_RTOL}
#: the rtol bound of :mod:`hubbeam.model.limits`, filled into the benchmark schema as into the config's
SCHEMA_LIMITS = {
    ("properties", "tolerances", "items"): _RTOL_BOUND,
    ("properties", "reference_rtol"): _RTOL_BOUND,
    ("properties", "sweep_check", "properties", "rtol"): _RTOL_BOUND,
}
SECTION = Section("benchmark", read_schema(HERE / "schema.yaml", SCHEMA_LIMITS), cross_checks)


def load_settings(study_files: Sequence[os.PathLike | str], benchmark_file: os.PathLike | str) -> dict:
    """The study config of ``study_files`` merged with ``benchmark_file``, validated together
    (raises :class:`hubbeam.configuration.load.ConfigError` naming every problem)."""
    return load_config([*study_files, benchmark_file], section=SECTION)
