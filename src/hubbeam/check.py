"""The one check of a configuration, before anything runs.

:func:`check_configuration` takes a configuration as Snakemake read it (the merged mapping of its
config files) and returns a :class:`CheckedConfiguration`, or raises one
:class:`~hubbeam.configuration.load.ConfigError` listing every problem found, each naming its key,
the value and what is allowed:

1. the tables given as ``file:`` are read relative to the last config file
   (:func:`hubbeam.configuration.tabular.resolve_files`), then the schema and the physical checks
   run and the defaults are filled in (:mod:`hubbeam.configuration.load`);
2. the configuration becomes its records (:func:`hubbeam.configuration.settings.from_config`),
   and what needs each case's matrices is resolved once (designs, sampled controllers, shapers:
   :func:`hubbeam.control.cases.case_problems`) with the ``control`` section
   (:func:`hubbeam.control.analyses.control_problems`);
3. the product sets and the cases their products read (:mod:`hubbeam.reporting.products`), and,
   with the paper's products, the alternative readings with the runs they generate
   (:func:`hubbeam.paper.readings.reading_runs`);
4. a study's ``identify`` section: its experiment files (read relative to the last config file),
   parameters and lists (:func:`hubbeam.identification.section.identify_problems`), then what needs
   the cases (:func:`hubbeam.identification.section.case_problems`). The fit itself runs later,
   once (:mod:`hubbeam.calibration`).

The workflow's plan (:func:`hubbeam.pipeline.plan.build_plan`) and the Python API
(:func:`hubbeam.api.load`) both call it, so that a configuration one accepts the other accepts
too. The checks that need the records run once the schema accepts the configuration, so a design
problem can show up once the schema's problems are fixed.
"""

from __future__ import annotations

import copy
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hubbeam.configuration.load import ConfigError, check_schema
from hubbeam.configuration.settings import Settings, from_config
from hubbeam.configuration.tabular import resolve_files
from hubbeam.control.analyses import control_problems
from hubbeam.control.cases import case_problems
from hubbeam.identification import section as identification
from hubbeam.model.frozen import FrozenMap
from hubbeam.paper.readings import ReadingError, ReadingRuns, reading_runs
from hubbeam.reporting.products import PAPER, Product, ProductError, product_case_problems, products_for


@dataclass(frozen=True)
class CheckedConfiguration:
    """A configuration that passed :func:`check_configuration`.

    ``config``: the completed configuration as plain values (tables inlined, defaults filled in),
    what a results archive records; ``settings``: its records, one per section; ``products``: its
    figures and tables by key; ``readings``: the runs of every alternative reading (with the
    paper's products only); ``files``: the config files it was read from.
    """

    config: Mapping[str, Any]
    settings: Settings
    products: Mapping[str, Product]
    readings: Mapping[str, ReadingRuns]
    files: tuple[str, ...]

    @property
    def base_dir(self) -> Path:
        """The folder the configuration's relative files (tables, experiments) are read from: the
        last config file's."""
        return Path(self.files[-1]).parent

    @property
    def with_paper(self) -> bool:
        """Whether the configuration asks for the paper's products (``products: [paper]``)."""
        return PAPER in self.settings.products


def check_configuration(config: Mapping, config_files: Sequence[os.PathLike | str]) -> CheckedConfiguration:
    """The :class:`CheckedConfiguration` of ``config`` as read from ``config_files`` (the last of
    which locates the tables given as ``file:``), or one ``ConfigError`` with every problem (module
    docstring). ``config`` itself is not changed."""
    files = tuple(str(path) for path in config_files)
    if not files:
        raise ValueError("check_configuration: no config file given; allowed: the config files the "
                         "configuration was read from")
    cfg = copy.deepcopy(dict(config))
    problems: list = []
    try:
        cfg.update(resolve_files(cfg, Path(files[-1]).parent))
        check_schema(cfg, files=files)
    except ConfigError as error:
        problems += error.problems
    settings = None if problems else from_config(cfg)
    if settings is not None:
        problems += case_problems(settings) + control_problems(settings)
    try:
        products = products_for(cfg)
    except ProductError as error:
        problems.append(str(error))
        products = {}
    cases = cfg.get("cases")
    problems += product_case_problems(products, cases if isinstance(cases, Mapping) else {})
    readings = {}
    if settings is not None and PAPER in settings.products:  # the readings recompute the paper's claims
        for name, reading in settings.readings.items():
            try:
                readings[name] = reading_runs(settings, reading)
            except ReadingError as error:
                problems.append(str(error))
            except ConfigError as error:
                problems += error.problems
    if isinstance(cfg.get("identify"), Mapping):
        problems += _identify_problems(cfg, settings, Path(files[-1]).parent)
    if problems:
        error = ConfigError(problems, files)
        error.config = cfg  # the configuration as far as the check completed it, to say where a problem is
        raise error
    return CheckedConfiguration(config=cfg, settings=settings, products=products, readings=FrozenMap(readings),
                                files=files)


def _identify_problems(cfg: Mapping, settings: Settings | None, base_dir: Path) -> list[str]:
    """The problems of the ``identify`` section (module docstring, step 4)."""
    cases = cfg.get("cases") if isinstance(cfg.get("cases"), Mapping) else {}
    names = list(settings.cases) if settings is not None else list(cases)
    problems = identification.identify_problems(cfg["identify"], names, base_dir)
    if problems or settings is None:
        return problems
    return identification.case_problems(cfg["identify"], settings, base_dir, cases)
