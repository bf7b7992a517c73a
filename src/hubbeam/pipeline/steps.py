"""A step of the workflow: what one rule runs, with its files and parameters, and its jobs.

A :class:`Step` is what a rule of ``workflow/rules/*.smk`` takes from the plan
(:mod:`hubbeam.pipeline.plan`): the script it runs, its input and output files by name, its params
by name, its log file, and the wildcards of every job of it the configuration defines. Paths may
hold Snakemake wildcards (a simulation is ``simulations/{case}.nc`` of a results folder); an input
or a param that depends on them is a function of the job's wildcards, called as Snakemake calls an
input or params function: with an object that has one attribute per wildcard (and the job's ``threads`` when the
function takes that argument). :meth:`Step.job` evaluates all of it for given wildcards into the
:class:`~hubbeam.pipeline.runner.Job` its job function receives, without Snakemake.
"""

from __future__ import annotations

import inspect
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import Any

from hubbeam.model.frozen import FrozenMap
from hubbeam.pipeline.runner import Job

#: a wildcard in a path or a string param (``{case}``, ``{chunk,\\d+}``), as Snakemake reads it
WILDCARD = re.compile(r"\{\s*(\w+)\s*(?:,[^{}]*)?\}")


def fill(pattern: str, wildcards: Mapping[str, str]) -> str:
    """``pattern`` with its wildcards replaced by their values; a wildcard without a value is an
    error naming it."""
    def value(match: re.Match) -> str:
        name = match.group(1)
        if name not in wildcards:
            raise KeyError(f"{pattern}: wildcard {{{name}}} has no value; given: {', '.join(wildcards) or 'none'}")
        return str(wildcards[name])

    return WILDCARD.sub(value, pattern)


def file_paths(files: Mapping[str, Any]) -> list[str]:
    """The paths of named files (each a path or a tuple of paths), in order."""
    return [path for value in files.values() for path in ((value,) if isinstance(value, str) else value)]


def fingerprint(*values) -> Callable:
    """A params function that stands for ``values`` (settings objects, or functions of the
    wildcards giving them) in Snakemake's rerun trigger: Snakemake compares only built-in param
    values, so the ``repr`` of the objects (complete: every field, floats written exactly) is
    passed as a string; editing a setting reruns exactly the jobs that take it."""
    def of(wildcards) -> str:
        return repr(tuple(value(wildcards) if callable(value) else value for value in values))

    return of


@dataclass(frozen=True)
class Step:
    """The files, params and log of one rule, the wildcards of its jobs and Snakemake's flags.

    ``script``: the file name of its script in ``workflow/scripts/``; ``input``, ``output``,
    ``params``: by name (a path, a tuple of paths, a value, or a function of the wildcards, see
    the module docstring); ``log``: the log file; ``wildcards``: one mapping per job the
    configuration defines (one empty mapping for a rule without wildcards, none for a rule whose
    jobs need a section the configuration lacks).

    The flags of the rule: ``local`` (run on the host that runs Snakemake, not on a cluster's
    node), ``priority``, the wildcards' ``constraints`` (regular expressions), the outputs that are
    ``temporary`` (deleted once every job reading them is done), the ``markers`` (outputs that
    may be empty; every other output must not be), and the outputs shown in ``snakemake --report``
    (``reported``: output name -> ``(caption file, category)``).
    """

    script: str
    output: Mapping[str, Any]
    log: str
    input: Mapping[str, Any] = field(default_factory=FrozenMap)
    params: Mapping[str, Any] = field(default_factory=FrozenMap)
    wildcards: tuple[Mapping[str, str], ...] = (FrozenMap(),)
    local: bool = False
    priority: int = 0
    constraints: Mapping[str, str] = field(default_factory=FrozenMap)
    temporary: tuple[str, ...] = ()
    markers: tuple[str, ...] = ()
    reported: Mapping[str, tuple[str, str]] = field(default_factory=FrozenMap)

    def __post_init__(self):
        for name in ("output", "input", "params", "constraints", "reported"):
            object.__setattr__(self, name, FrozenMap(getattr(self, name)))
        object.__setattr__(self, "wildcards", tuple(FrozenMap(values) for values in self.wildcards))
        unknown = sorted({*self.temporary, *self.markers, *self.reported} - set(self.output))
        if unknown:
            raise ValueError(f"step {self.script}: flags name outputs it does not have: {', '.join(unknown)}; "
                             f"allowed: {', '.join(self.output)}")

    def flagged_output(self, ensure: Callable, temp: Callable, report: Callable) -> dict[str, Any]:
        """The outputs with Snakemake's flags applied (the rule files pass Snakemake's ``ensure``,
        ``temp`` and ``report``): every output ensured non-empty but the markers, the temporary
        ones marked so, the reported ones with their caption and category."""
        def flagged(name: str, path: str):
            if name not in self.markers:
                path = ensure(path, non_empty=True)
            if name in self.temporary:
                path = temp(path)
            if name in self.reported:
                caption, category = self.reported[name]
                path = report(path, caption=caption, category=category)
            return path

        return {name: flagged(name, value) if isinstance(value, str) else [flagged(name, path) for path in value]
                for name, value in self.output.items()}

    def job(self, wildcards: Mapping[str, str] | None = None, threads: int = 1) -> Job:
        """The job of ``wildcards`` as its job function receives it: paths and string params with
        the wildcards filled in, functions called (those that take ``threads`` with ``threads``)."""
        wildcards = dict(wildcards or {})
        given = SimpleNamespace(**wildcards)

        def evaluate(value, files: bool):
            if callable(value):
                takes = inspect.signature(value).parameters
                value = value(given, threads=threads) if "threads" in takes else value(given)
                return _as_files(value) if files else value
            if isinstance(value, str):
                return fill(value, wildcards)
            if files:
                return tuple(fill(path, wildcards) for path in value)
            if isinstance(value, list):  # as Snakemake: the strings of a list param are filled in too
                return [fill(item, wildcards) if isinstance(item, str) else item for item in value]
            return value

        output = FrozenMap({name: evaluate(value, True) for name, value in self.output.items()})
        inputs = FrozenMap({name: evaluate(value, True) for name, value in self.input.items()})
        params = FrozenMap({name: evaluate(value, False) for name, value in self.params.items()})
        return Job(input=inputs, output=output, params=params, log=fill(self.log, wildcards))

    def jobs(self) -> list[tuple[Mapping[str, str], Job]]:
        """Every job of the step the configuration defines, with its wildcards."""
        return [(wildcards, self.job(wildcards)) for wildcards in self.wildcards]

    def output_paths(self, wildcards: Mapping[str, str]) -> list[str]:
        """The paths the job of ``wildcards`` writes (its inputs and params not evaluated)."""
        return [fill(path, wildcards) for path in file_paths(self.output)]


def _as_files(value) -> str | tuple[str, ...]:
    """What an input function returned, as a job receives its files: a path, or a tuple of paths."""
    return value if isinstance(value, str) else tuple(value)
