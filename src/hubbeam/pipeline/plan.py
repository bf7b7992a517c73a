"""The workflow's plan: a configuration, checked once, as everything the rules need.

:func:`build_plan` takes the configuration Snakemake read and its config files and returns the
:class:`Plan`, or raises one :class:`PlanError` listing every problem it found: those of the one
check of the configuration (:func:`hubbeam.check.check_configuration`) and the study's folder
(:func:`hubbeam.study.check_folder`: another config file may own it already). A configuration with
any problem writes nothing; only then does a study claim its folder, and fit its ``identify``
section (:func:`hubbeam.calibration.calibrated`: the cases of ``apply_to`` are planned on the
fitted plant).

The plan holds the checked configuration, its folders (:class:`hubbeam.results.paths.StudyPaths`),
the steps of every family (:mod:`hubbeam.pipeline.families`: each declares its own), the targets of
``all`` and the target rules of the families (``readings``, ``large_sweeps``, ``validate``). The
rule files define one rule per step and per target rule (``workflow/rules/``), and
:meth:`Plan.jobs` lists, without Snakemake, the jobs that build a set of targets in an order where
each comes after the jobs writing its inputs.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple

from hubbeam.calibration import calibrated
from hubbeam.check import CheckedConfiguration, check_configuration
from hubbeam.configuration.load import ConfigError
from hubbeam.configuration.schema import CASE_NAME_PATTERN
from hubbeam.model.frozen import FrozenMap
from hubbeam.pipeline.context import NotPlanned, PlanContext
from hubbeam.pipeline.families import FAMILIES
from hubbeam.pipeline.runner import Job
from hubbeam.pipeline.steps import Step, file_paths
from hubbeam.results.paths import StudyPaths, study_paths
from hubbeam.study import StudyError, check_folder, claim_folder

__all__ = ["NotPlanned", "Plan", "PlanError", "PlannedJob", "build_plan"]


class PlanError(ConfigError):
    """The configuration is refused: ``problems`` lists every problem found, those of the
    configuration's check (:class:`~hubbeam.configuration.schema.Problem`) and the plan's own
    (messages that name their key), in one message."""


class PlannedJob(NamedTuple):
    """One job of a rule: the rule's name, the job's wildcards and the job as its function receives it."""

    rule: str
    wildcards: Mapping[str, str]
    job: Job


@dataclass(frozen=True)
class Plan:
    """A checked configuration as the workflow runs it (module docstring).

    ``checked``: the configuration as the one check returned it (its records, products, readings
    and the completed mapping the archive records); ``steps`` the :class:`~hubbeam.pipeline.steps.Step`
    of every rule that runs a job, by rule name; ``targets`` the inputs of ``all``: every product of
    the configuration and its archive; ``target_rules`` the families' other target rules by name
    (their files, or a function giving them when the rule runs).
    """

    checked: CheckedConfiguration
    paths: StudyPaths
    steps: Mapping[str, Step]
    targets: tuple[str, ...]
    target_rules: Mapping[str, tuple[str, ...] | Callable]

    @property
    def settings(self):
        """The configuration's records (:class:`~hubbeam.configuration.settings.Settings`)."""
        return self.checked.settings

    @property
    def config(self) -> Mapping:
        """The completed configuration as plain values (what the archive records)."""
        return self.checked.config

    @property
    def products(self):
        return self.checked.products

    @property
    def readings(self):
        return self.checked.readings

    @property
    def cases(self) -> tuple[str, ...]:
        """The names of the configured cases, sorted."""
        return tuple(self.settings.cases)

    @property
    def case_pattern(self) -> str:
        """The wildcard constraint of a case's (and a comparison's) name."""
        return CASE_NAME_PATTERN

    def jobs(self, targets: Iterable[str] | None = None) -> list[PlannedJob]:
        """The jobs that build ``targets`` (default: those of ``all``) from the files no rule
        writes, each after the jobs that write its inputs; what Snakemake would run in a folder
        without results, found from the steps alone."""
        writers = {path: (rule, wildcards) for rule, step in self.steps.items() for wildcards in step.wildcards
                   for path in step.output_paths(wildcards)}
        ordered: dict[tuple[str, Mapping[str, str]], PlannedJob] = {}
        visiting: set[tuple[str, Mapping[str, str]]] = set()

        def visit(path: str) -> None:
            if path not in writers:
                return
            key = writers[path]
            if key in ordered:
                return
            if key in visiting:
                raise ValueError(f"rule {key[0]} needs its own output {path}")
            visiting.add(key)
            rule, wildcards = key
            job = self.steps[rule].job(wildcards)
            for needed in file_paths(job.input):
                visit(needed)
            visiting.discard(key)
            ordered[key] = PlannedJob(rule, wildcards, job)

        for target in self.targets if targets is None else targets:
            visit(target)
        return list(ordered.values())


def build_plan(config: Mapping, config_files: Sequence[os.PathLike | str], workflow_root: os.PathLike | str) -> Plan:
    """The :class:`Plan` of ``config`` (as Snakemake read it from ``config_files``, the last of
    which locates the tables given as ``file:`` and owns a study's folder), for the workflow in
    ``workflow_root`` (the repository); a :class:`PlanError` listing every problem otherwise
    (module docstring). ``config`` itself is not changed."""
    files = [str(path) for path in config_files]
    if not files:
        raise ValueError("build_plan: no config file given; allowed: the config files the configuration was read from")
    problems: list = []
    try:
        checked = check_configuration(config, files)
    except ConfigError as error:
        checked, problems = None, list(error.problems)
    paths = study_paths(checked.settings.study.name if checked and checked.settings.study else _study_name(config))
    try:
        (check_folder if problems else claim_folder)(paths, files[-1])
    except StudyError as error:
        problems.append(str(error))
    if problems:
        raise PlanError(problems, files)
    try:
        checked = calibrated(checked, paths)
    except ConfigError as error:
        raise PlanError([f"identify: the fitted plant is refused: {problem}" for problem in error.problems],
                        files) from None
    return plan_of(PlanContext(checked, paths, Path(workflow_root)))


def plan_of(ctx: PlanContext) -> Plan:
    """The plan of the families of :data:`~hubbeam.pipeline.families.FAMILIES` on ``ctx``."""
    targets = sorted({path for family in FAMILIES for path in family.targets(ctx)})
    ctx.archived = tuple(targets)
    steps: dict[str, Step] = {}
    target_rules: dict[str, tuple[str, ...] | Callable] = {}
    for family in FAMILIES:
        for name, step in family.steps(ctx).items():
            if name in steps:
                raise ValueError(f"rule {name} is declared by two families; allowed: one step per rule name")
            steps[name] = step
        for name, files in getattr(family, "target_rules", lambda ctx: {})(ctx).items():
            target_rules[name] = files if callable(files) else tuple(files)
    return Plan(checked=ctx.checked, paths=ctx.paths, steps=FrozenMap(steps),
                targets=(*targets, ctx.paths.archive()), target_rules=FrozenMap(target_rules))


def _study_name(config: Mapping) -> str | None:
    """The study's name of a configuration the check refused, when it has one that names a folder."""
    study = config.get("study")
    name = study.get("name") if isinstance(study, Mapping) else None
    return name if isinstance(name, str) else None
