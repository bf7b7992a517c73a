"""A configuration, checked once, for a notebook or a script.

:func:`load` reads a study's configuration (or the paper's, or a small file changing a setting of
the paper's) exactly as the workflow does: ``file:`` tables inlined, the schema, the physical
checks and the checks that need each case's matrices in one pass, every problem in one
:class:`~hubbeam.configuration.load.ConfigError`. The :class:`Configuration` it returns holds the
checked objects (:class:`~hubbeam.configuration.settings.Settings`) and answers in one call what the
workflow's jobs compute from them::

    from hubbeam.api import load

    study = load("studies/first_study.yaml")
    ds = study.simulate("spinup")                  # the case's run, an xarray Dataset
    plant = study.plant("spinup", speed=6.0)       # python-control StateSpace about the steady spin
    print(float(abs(ds.tip_transverse).max()), plant.poles()[:4])

Paths are read relative to the working directory, as Snakemake reads them: run from the
repository's root (a file without a ``study`` section is merged onto ``config/config.yaml``).

A study with an ``identify`` section (docs/identification.md) loads as the workflow plans it: the
cases of ``identify.apply_to`` run on the fitted plant, the fit read from the study's
``identification/fit.nc`` when it was made from the same inputs, else run and written there
(:func:`hubbeam.calibration.calibrated`); ``load(path, identified=False)`` gives the rig as drawn,
and :meth:`Configuration.identify` runs the fit itself and returns it::

    rig = load("studies/identification_rig/study.yaml", identified=False)
    result, fit = rig.identify()                  # FitResult, and the fit as an xarray Dataset
    print(result.values, fit.lower_95.values, fit.upper_95.values)
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path

import xarray as xr

from hubbeam.calibration import calibrated
from hubbeam.check import check_configuration
from hubbeam.configuration.load import ConfigError, merge_configs, read_config_file
from hubbeam.configuration.schema import Problem
from hubbeam.configuration.settings import Case, Settings
from hubbeam.control.cases import resolve, sampled_controller, sampling_of, simulate_case
from hubbeam.control.feedback import design_plant
from hubbeam.control.implementation import write_implementation
from hubbeam.identification.dataset import fit_dataset
from hubbeam.identification.fit import FitResult
from hubbeam.identification.plant import CasePlant
from hubbeam.identification.section import identify
from hubbeam.linear.plant_models import plant_frequencies, plant_linear
from hubbeam.model.frozen import FrozenMap
from hubbeam.model.plant import Plant, plant_matrices
from hubbeam.results.paths import study_paths
from hubbeam.study import base_config_files


def load(paths: os.PathLike | str | Iterable[os.PathLike | str], identified: bool = True) -> Configuration:
    """The checked :class:`Configuration` of one config file or several (later ones override
    earlier ones), merged onto ``config/config.yaml`` unless they hold a ``study`` section, as
    ``snakemake --configfile ...`` reads them; a :class:`~hubbeam.configuration.load.ConfigError`
    listing every problem otherwise. With an ``identify`` section and ``identified``, the cases of
    ``identify.apply_to`` run on the fitted plant, as in the workflow (module docstring)."""
    given = [Path(paths)] if isinstance(paths, (str, os.PathLike)) else [Path(path) for path in paths]
    if not given:
        raise ValueError("load: no config file given; allowed: one path or a list of paths")
    merged = merge_configs(*(read_config_file(path) for path in given))
    files = [Path(path) for path in base_config_files(merged)] + given
    checked = check_configuration(merge_configs(*(read_config_file(path) for path in files)), files)
    if identified and checked.settings.identify is not None:
        study = checked.settings.study
        checked = calibrated(checked, study_paths(study.name if study is not None else None))
    return Configuration(checked.settings, checked.files, checked.config)


@dataclass(frozen=True)
class Configuration:
    """The checked objects of a configuration (``settings``) and the files they were read from.

    Each method takes a case's name and gives what the workflow computes for it, from the same
    functions: its run, its linear model, its feedback design and sampled controller."""

    settings: Settings
    files: tuple[str, ...] = ()
    #: the completed configuration as plain values (what the workflow's archive records)
    config: Mapping = FrozenMap()

    @property
    def beam(self):
        """The beam (``BeamParameters``, ``BeamProducts`` or ``BeamSections``)."""
        return self.settings.beam

    @property
    def case_names(self) -> tuple[str, ...]:
        """The names of the cases, sorted."""
        return tuple(self.settings.cases)

    def case(self, name: str) -> Case:
        """The :class:`~hubbeam.configuration.settings.Case` ``name``; a ``ConfigError`` naming the cases."""
        return self.settings.case(name)

    def plant_of(self, name: str) -> Plant:
        """The plant case ``name`` runs (``hubbeam.model.plant.Plant``: its beam, modes and functions,
        tip body, root spring, drive and damping), named as the workflow's products name it."""
        return self.settings.plant_of(name)

    def matrices(self, name: str):
        """The system matrices of case ``name``'s plant (its modes and tip body,
        ``numerics.quadrature_points`` Gauss nodes, a drive's rotor in the hub inertia)."""
        return plant_matrices(self.plant_of(name))

    def natural_frequencies(self, name: str):
        """The natural frequencies (Hz, ascending) of case ``name``'s plant with the hub held, at rest:
        its tip body, modes, transverse functions and root spring
        (``hubbeam.linear.plant_models.plant_frequencies``), as a frequency equation gives them; what the
        workflow's products of the plant give."""
        return plant_frequencies(self.plant_of(name))

    def simulate(self, name: str, modes: int | None = None):
        """The run of case ``name`` as the workflow writes it (``simulations/<name>.nc``), with
        ``modes`` modes instead of the case's if given (a convergence check of one's own)."""
        case = self.case(name)
        if modes is not None:
            case = case.with_modes(modes)
        return simulate_case(case, self.beam, self.settings.numerics,
                             convergence_check=self.settings.numerics.convergence_check)

    def linear(self, name: str, speed: float | None = None, hub: str = "free", outputs=None):
        """The linear model of case ``name``'s model, modes, tip body, damping and root about the steady spin
        at ``speed`` (rad s-1; default the maneuver's final speed): the voltage as input for a free
        hub with a drive (``hubbeam.linear.voltage``), the hub torque (free) or acceleration
        (``hub="prescribed"``) otherwise; ``outputs`` as ``hubbeam.linear.statespace.linear_model``
        (``hubbeam.linear.plant_models.plant_linear`` on its plant, as the workflow's exports)."""
        case = self.case(name)
        speed = case.maneuver.final_speed if speed is None else speed
        return plant_linear(self.plant_of(name), case.model, speed, hub, outputs)

    def plant(self, name: str, speed: float | None = None, hub: str = "free", outputs=None):
        """:meth:`linear` as a python-control ``StateSpace`` with named states, inputs and outputs."""
        return self.linear(name, speed, hub, outputs).to_control()

    def design_plant(self, name: str):
        """The continuous linear model case ``name``'s LQR is designed on (its ``design``)."""
        return design_plant(self._feedback_case(name), self.beam, self.matrices(name))

    def resolve(self, name: str):
        """What case ``name`` needs for its run (``hubbeam.control.cases.resolve``): its feedback
        law, its sampled loop, its shaper and the attributes that record them."""
        return resolve(self.case(name), self.matrices(name), self.beam)

    def controller(self, name: str):
        """The sampled controller of case ``name`` (``hubbeam.control.sampled.SampledController``)."""
        case = self._feedback_case(name)
        if sampling_of(case) is None:
            raise ValueError(f"cases.{name}.maneuver.sampling: absent; allowed: a case whose state feedback "
                             "runs as a sampled controller")
        return sampled_controller(case, self.beam, self.matrices(name))

    def export_controller(self, name: str, path: os.PathLike | str) -> tuple[Path, Path]:
        """Write case ``name``'s sampled controller and its discrete plant as ``<path>.mat`` and
        ``<path>.json`` (``hubbeam.control.implementation``); the two paths."""
        return write_implementation(self.controller(name), path)

    def identify(self) -> tuple[FitResult, xr.Dataset]:
        """The fit the ``identify`` section asks for, run now on the case as configured (its
        experiment files read relative to the last config file): the
        :class:`~hubbeam.identification.fit.FitResult` and its dataset, as the workflow writes it
        to ``identification/fit.nc`` (:func:`hubbeam.identification.dataset.fit_dataset`)."""
        entry = self.config.get("identify")
        if entry is None:
            raise ConfigError([Problem("identify", "missing; allowed: a configuration with an identify section "
                                                   "(docs/identification.md)")], self.files)
        plant = CasePlant.from_configuration(self, entry["case"])
        result, experiments = identify(entry, plant, Path(self.files[-1]).parent)
        return result, fit_dataset(result, experiments)

    def _feedback_case(self, name: str) -> Case:
        case = self.case(name)
        if getattr(case.maneuver, "design", None) is None:
            raise ValueError(f"cases.{name}.maneuver: kind {case.maneuver.kind!r} without a design; allowed: "
                             "a state_feedback case with a design")
        return case


__all__ = ["ConfigError", "Configuration", "load"]
