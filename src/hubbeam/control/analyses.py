"""The configuration's ``control`` section: the sample-time sweep and the robustness maps of its sampled cases.

:func:`control_problems` checks what the schema cannot (every listed case exists and runs a
sampled controller with an LQR design; a drive parameter is moved only for cases with a drive);
:func:`sample_time_analysis` and :func:`robustness_analysis` compute the section's datasets from the
checked settings (:mod:`hubbeam.control.sample_time`, :mod:`hubbeam.control.robustness`), and
:func:`sampled_cases` names the cases whose controllers are exported
(:func:`hubbeam.control.implementation.write_implementation`).
"""

from __future__ import annotations

import math

from hubbeam.configuration.schema import Problem
from hubbeam.configuration.sections import RobustnessAnalysis, SampleTimeAnalysis
from hubbeam.configuration.settings import Settings
from hubbeam.control.cases import sampling_of
from hubbeam.control.robustness import PARAMETERS, confirm_margins, robustness_dataset, robustness_map
from hubbeam.control.sample_time import (
    REDUCED,
    confirm_boundary,
    plant_modes,
    sample_time_sweep,
    sweep_dataset,
    truth_model,
)
from hubbeam.simulation.simulate import case_matrices

#: the parameters of :data:`hubbeam.control.robustness.PARAMETERS` that belong to the drive
DRIVE_PARAMETERS = tuple(name for name in PARAMETERS if name not in ("tip_mass", "EI_factor"))


def sampled_cases(settings: Settings) -> list[str]:
    """The cases of ``settings`` that run a sampled controller, sorted."""
    return sorted(name for name, case in settings.cases.items() if sampling_of(case) is not None)


def control_problems(settings: Settings) -> list[Problem]:
    """The problems of the ``control`` section of ``settings`` (module docstring), one per key."""
    control = settings.control
    if control is None:
        return []
    sampled = set(sampled_cases(settings))
    problems = []
    for part, spec in control.analyses.items():
        for k, name in enumerate(spec.cases):
            if name not in sampled:
                problems.append(Problem(f"control.{part}.cases[{k}]", f"got {name!r}; allowed: a case with "
                                        f"maneuver.sampling ({', '.join(sorted(sampled)) or 'none in cases'})"))
            elif part == "sample_time" and sampling_of(settings.cases[name]).reduce:
                problems.append(Problem(f"control.sample_time.cases[{k}]", f"{name!r} {REDUCED}"))
            elif part == "robustness" and settings.cases[name].drive is None:
                moved = [key for key in spec.ranges if key in DRIVE_PARAMETERS]
                if moved:
                    problems.append(Problem(f"control.robustness.ranges.{moved[0]}", f"moves the drive of case "
                                            f"{name!r}, which has none; allowed: tip_mass, EI_factor"))
    times = control.sample_time.sample_times if control.sample_time is not None else None
    if times is not None and not times.start < times.stop:
        problems.append(Problem("control.sample_time.sample_times", f"got start {times.start!r} >= stop "
                                f"{times.stop!r}; allowed: start < stop"))
    for name, (low, high) in (control.robustness.ranges if control.robustness is not None else {}).items():
        if not low < high or (name.endswith("_factor") and low == 0.0):
            problems.append(Problem(f"control.robustness.ranges.{name}", f"got [{low!r}, {high!r}]; allowed: "
                                    "low < high (a factor's low > 0)"))
    return problems


def sample_time_analysis(settings: Settings, spec: SampleTimeAnalysis, confirm: bool = True):
    """The sample-time sweep of ``control.sample_time`` as a dataset
    (:func:`hubbeam.control.sample_time.sweep_dataset`); with ``confirm``, the first case's boundary
    with the continuous gain and no delay confirmed by two nonlinear runs just inside and outside it
    (:func:`hubbeam.control.sample_time.confirm_boundary`; none when that loop is stable over the
    whole grid)."""
    grid, delays = spec.sample_times.values, spec.delays
    sweeps, truth = [], None
    for name in spec.cases:
        case = settings.cases[name]
        sm = case_matrices(case, settings.beam, settings.numerics)
        sweeps.append(sample_time_sweep(case, settings.beam, settings.numerics, sm, grid, delays))
        truth = truth or plant_modes(truth_model(case, settings.beam, settings.numerics, sm))
    confirmation = None
    first = sweeps[0]
    boundary = float(first.boundary[first.gains.index("continuous"), 0]) if 0.0 in delays else math.nan
    if confirm and math.isfinite(boundary):
        case = settings.cases[spec.cases[0]]
        sm = case_matrices(case, settings.beam, settings.numerics)
        runs = confirm_boundary(case, settings.beam, settings.numerics, sm, boundary, 0.0, "continuous")
        confirmation = {"case": case.label, "gain": "continuous", "delay": 0.0, "boundary": boundary, "runs": runs}
    return sweep_dataset(sweeps, truth, confirmation)


def robustness_analysis(settings: Settings, spec: RobustnessAnalysis, confirm: bool = True):
    """The robustness maps of ``control.robustness`` as a dataset
    (:func:`hubbeam.control.robustness.robustness_dataset`); with ``confirm``, every margin inside
    its swept range confirmed by nonlinear runs (:func:`hubbeam.control.robustness.confirm_margins`)."""
    maps, runs = [], []
    for name in spec.cases:
        case = settings.cases[name]
        maps.append(robustness_map(case, settings.beam, settings.numerics, dict(spec.ranges), spec.points))
        if confirm:
            runs += confirm_margins(case, settings.beam, settings.numerics, maps[-1])
    return robustness_dataset(maps, runs)


__all__ = ["DRIVE_PARAMETERS", "control_problems", "robustness_analysis", "sample_time_analysis", "sampled_cases"]
