"""The workflow's plan: a configuration, checked once, as everything the rules need.

:func:`build_plan` takes the configuration Snakemake read and its config files and returns the
:class:`Plan`, or raises one :class:`PlanError` listing every problem it found: the schema and the
physical checks (:func:`hubbeam.configuration.load.validate_config`, after the tables given as
``file:`` are read) and what needs each case's matrices (designs, sampled controllers, shapers:
:func:`hubbeam.control.cases.case_problems`), all three in :func:`checked_configuration`, then
the alternative readings (:func:`hubbeam.paper.readings.reading_runs`), the product sets and the
cases the products read (:mod:`hubbeam.reporting.products`) and the study's folder
(:func:`hubbeam.study.check_folder`). The checks that need the configuration's objects run once the
schema accepts it; a configuration with any problem writes nothing, and only then does a study
claim its folder.

The plan holds the settings (:class:`hubbeam.configuration.settings.Settings`), the folders
(:class:`hubbeam.results.paths.StudyPaths`), the products, the cases, the readings' runs, the
targets of ``all``, ``readings`` and ``large_sweeps`` and, per rule that runs a script, its
:class:`~hubbeam.pipeline.steps.Step`: the rule files read everything from it
(``workflow/rules/common.smk``), and :meth:`Plan.jobs` lists, without Snakemake, the jobs that
build a set of targets in an order where each comes after the jobs writing its inputs.

Params are the configuration's plain values where they are plain (Snakemake compares only built-in
params to decide what to rerun) and its objects otherwise, each then with a param standing for it
(:func:`hubbeam.pipeline.steps.fingerprint`, or a sweep's plain mapping).
"""

from __future__ import annotations

import copy
import importlib.util
import os
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, NamedTuple

from hubbeam.configuration.load import ConfigError, validate_config
from hubbeam.configuration.settings import Settings, from_config
from hubbeam.configuration.tabular import resolve_files
from hubbeam.control.analyses import control_problems, sampled_cases
from hubbeam.control.cases import case_problems, sampling_of
from hubbeam.linear.statespace import HUBS
from hubbeam.model.frozen import FrozenMap
from hubbeam.model.matrices import configuration_name
from hubbeam.model.models import FAMILIES, MODELS, model, wildcard_pattern
from hubbeam.model.parameters import TipMass
from hubbeam.paper.readings import ReadingError, ReadingRuns, reading_runs
from hubbeam.pipeline.jobs.linear import LinearExport
from hubbeam.pipeline.runner import Job
from hubbeam.pipeline.steps import Step, file_paths, fingerprint
from hubbeam.reporting.products import (
    BEAM_NC,
    CAMPBELL_NC,
    CASE_FIGURE,
    COMPARISON_FIGURE,
    CONTROL_FOLDER,
    CONTROL_NC,
    CRITICAL_SPEEDS_CSV,
    CRITICAL_SPEEDS_NC,
    DESIGNS_FIGURE,
    FILES_FIGURE,
    K22_NC,
    LINEAR_NC,
    PAPER,
    PAPER_PRODUCTS,
    SHAPING_FIGURE,
    SIMULATION_FIGURE,
    TABLE,
    TABLE2_CSV,
    Product,
    ProductError,
    designed_cases,
    product_case_problems,
    product_cases,
    product_sets,
    products_for,
    shaped_cases,
)
from hubbeam.reporting.sourcedeps import script_dependencies
from hubbeam.results.paths import FIGURE_FORMATS, SHARED, TABLE_FORMATS, StudyPaths, study_paths
from hubbeam.simulation.sweep import n_chunks
from hubbeam.study import StudyError, check_folder, claim_folder

#: the compiled simulation kernels a workflow prepares, by name (their marker's): (family, sampled)
KERNELS = {**{family: (family, False) for family in FAMILIES},
           **{f"{family}_sampled": (family, True) for family in FAMILIES}}


def kernel_name(family: str, sampled: bool) -> str:
    """The name in :data:`KERNELS` of ``family``'s simulation kernel, or of its sampled-controller kernel."""
    return next(name for name, kernel in KERNELS.items() if kernel == (family, sampled))


def _kernel_family(wildcards) -> str:
    return KERNELS[wildcards.kernel][0]


def _kernel_sampled(wildcards) -> bool:
    return KERNELS[wildcards.kernel][1]


#: the transverse mode shapes of the beam's data (eigen/beam.nc, the mode-shape figure)
BEAM_MODE_SHAPES = 3
#: the optional modules ``snakemake validate`` imports: pyBModes always, Exudyn for a ``validation`` section
VALIDATION_MODULES = ("pybmodes", "exudyn")


class PlanError(ConfigError):
    """The configuration is refused: ``problems`` lists every problem found, those of the
    configuration's checks (:class:`~hubbeam.configuration.schema.Problem`) and the plan's own
    (messages that name their key), in one message."""


class NotPlanned(ValueError):
    """A job asks for something the configuration does not define (the message names it and what
    is allowed)."""


class PlannedJob(NamedTuple):
    """One job of a rule: the rule's name, the job's wildcards and the job as its function receives it."""

    rule: str
    wildcards: Mapping[str, str]
    job: Job


@dataclass(frozen=True)
class Plan:
    """A checked configuration as the workflow runs it (module docstring).

    ``config`` is the completed configuration (tables inlined, defaults filled in) as plain values,
    which the archive records; ``steps`` the :class:`~hubbeam.pipeline.steps.Step` of every rule
    that runs a script, by rule name; ``targets`` the inputs of ``all``: every product of the
    configuration and its archive.
    """

    config: Mapping[str, Any]
    settings: Settings
    paths: StudyPaths
    products: Mapping[str, Product]
    readings: Mapping[str, ReadingRuns]
    steps: Mapping[str, Step]
    targets: tuple[str, ...]
    reading_targets: tuple[str, ...]
    large_sweep_targets: tuple[str, ...]
    #: what ``snakemake validate`` builds, and the optional modules it needs
    validation_files: tuple[str, ...]
    validation_modules: tuple[str, ...]

    @property
    def cases(self) -> tuple[str, ...]:
        """The names of the configured cases, sorted."""
        return tuple(self.settings.cases)

    @property
    def kernel_pattern(self) -> str:
        """The wildcard constraint of a compiled kernel's name (:data:`KERNELS`)."""
        return wildcard_pattern(KERNELS)

    @property
    def sweep_pattern(self) -> str:
        """The wildcard constraint of a sweep's name: the configured sweeps (a name no file has
        without any)."""
        return "|".join(self.settings.sweeps) or "no-sweeps"

    def validation_targets(self, wildcards=None) -> list[str]:
        """The files of ``snakemake validate``; :class:`NotPlanned` with the command that installs
        them when an optional module it needs is not importable. An input function of the rule
        (``wildcards`` unused): evaluated only when ``validate`` is asked for."""
        missing = [name for name in self.validation_modules if importlib.util.find_spec(name) is None]
        if missing:
            raise NotPlanned(
                f"`snakemake validate` needs the optional dependencies {', '.join(self.validation_modules)}; not "
                f"installed in this environment: {', '.join(missing)}. Install the extra with "
                "`pip install -e .[validation]` (from the repository root), then rerun `snakemake validate`")
        return list(self.validation_files)

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

    def check_scripts(self, scripts: Mapping[str, str | None]) -> None:
        """Check the rules against the steps: ``scripts`` gives each rule's script (its path as the
        rule file writes it, None for a rule without one). Every rule that runs a script must have
        the step of its name, with that script, and every step a rule; a ValueError lists what
        does not match."""
        ran = {rule: Path(script).name for rule, script in scripts.items() if script}
        problems = [f"rule {rule} runs {script} but its step names {self.steps[rule].script}"
                    for rule, script in ran.items() if rule in self.steps and self.steps[rule].script != script]
        problems += [f"rule {rule} runs {ran[rule]} and has no step in the plan" for rule in ran
                     if rule not in self.steps]
        problems += [f"step {name} has no rule that runs its script" for name in self.steps if name not in ran]
        if problems:
            raise ValueError("the rule files and the plan (hubbeam.pipeline.plan) disagree:\n"
                             + "\n".join(f"  - {problem}" for problem in problems))


def checked_configuration(config: Mapping,
                          config_files: Sequence[os.PathLike | str]) -> tuple[dict, Settings | None, list]:
    """The one check of a configuration (as read from ``config_files``, the last of which locates the
    tables given as ``file:``): a copy of ``config`` with its tables inlined, its
    :class:`~hubbeam.configuration.settings.Settings` (None when the schema or the physical checks
    refuse it) and every problem of the schema, the physical checks and what needs each case's
    matrices (:func:`hubbeam.control.cases.case_problems`). ``config`` itself is not changed."""
    files = [str(path) for path in config_files]
    cfg = copy.deepcopy(dict(config))
    problems: list = []
    try:
        cfg.update(resolve_files(cfg, Path(files[-1]).parent))
        validate_config(cfg, files=files)
    except ConfigError as error:
        problems += error.problems
    settings = None if problems else from_config(cfg)
    if settings is not None:
        problems += case_problems(settings) + control_problems(cfg, settings)
    return cfg, settings, problems


def build_plan(config: Mapping, config_files: Sequence[os.PathLike | str], workflow_root: os.PathLike | str) -> Plan:
    """The :class:`Plan` of ``config`` (as Snakemake read it from ``config_files``, the last of
    which locates the tables given as ``file:`` and owns a study's folder), for the workflow in
    ``workflow_root`` (the repository); a :class:`PlanError` listing every problem otherwise
    (module docstring). ``config`` itself is not changed."""
    files = [str(path) for path in config_files]
    if not files:
        raise ValueError("build_plan: no config file given; allowed: the config files the configuration was read from")
    cfg, settings, problems = checked_configuration(config, files)
    try:
        with_paper = PAPER in product_sets(cfg)
        products = products_for(cfg)
    except ProductError as error:
        problems.append(str(error))
        with_paper, products = False, {}
    cases = cfg.get("cases")
    problems += product_case_problems(products, cases if isinstance(cases, Mapping) else {})
    readings = {}
    if settings is not None:
        for name, reading in cfg.get("readings", {}).items() if with_paper else ():  # they recompute the paper's claims
            try:
                readings[name] = reading_runs(settings, name, reading)
            except ReadingError as error:
                problems.append(str(error))
            except ConfigError as error:
                problems += error.problems
    paths = study_paths(cfg if isinstance(cfg.get("study", {}), Mapping) else {})
    try:
        (check_folder if problems else claim_folder)(paths, files[-1])
    except StudyError as error:
        problems.append(str(error))
    if problems:
        raise PlanError(problems, files)
    return _Planner(cfg, settings, paths, products, readings, Path(workflow_root)).plan()


class _Planner:
    """Builds the steps and targets of a checked configuration (:func:`build_plan`)."""

    def __init__(self, cfg: dict, settings: Settings, paths: StudyPaths, products: Mapping[str, Product],
                 readings: Mapping[str, ReadingRuns], root: Path):
        self.cfg, self.settings, self.paths, self.products = cfg, settings, paths, products
        self.readings = FrozenMap(readings)
        self.root = root
        self.package_dir = root / "src" / "hubbeam"
        self.with_paper = PAPER in product_sets(cfg)
        self.cases = tuple(settings.cases)
        self.style = os.path.relpath(self.package_dir / "plotting" / "hubbeam.mplstyle")
        self.validation = cfg.get("validation")
        self.comparisons = dict(settings.study.comparisons) if settings.study is not None else {}
        self.matrices_configurations = self._matrices_configurations()

    def plan(self) -> Plan:
        steps = {**self.simulation_steps(), **self.eigen_steps(), **self.figure_steps(), **self.table_steps(),
                 **self.linear_steps(), **self.reading_steps(), **self.report_steps(), **self.sweep_steps(),
                 **self.validation_steps(), **self.control_steps()}
        return Plan(config=self.cfg, settings=self.settings, paths=self.paths, products=self.products,
                    readings=self.readings, steps=FrozenMap(steps),
                    targets=(*self.archived(), self.paths.archive()),
                    reading_targets=tuple(self.reading_matrix()),
                    large_sweep_targets=tuple(self.sweep_files(in_all=False)),
                    validation_files=tuple(self.validation_files()),
                    validation_modules=VALIDATION_MODULES if self.validation is not None else VALIDATION_MODULES[:1])

    # --- helpers ------------------------------------------------------------------------------

    def step(self, script: str, output: Mapping, log: str, input: Mapping | None = None,
             params: Mapping | None = None, wildcards: Iterable[Mapping] = ({},), modules: Sequence[str] = (),
             code: bool = True) -> Step:
        """A step running ``script``; its inputs end with the package sources the script runs
        (``code``: every module it imports, transitively, and ``modules``, imported by a name
        computed at run time), so that editing a module reruns the jobs that run it."""
        inputs = dict(input or {})
        if code:
            inputs["code"] = self.code(script, *modules)
        return Step(script=script, output=output, log=log, input=inputs, params=params or {},
                    wildcards=tuple(wildcards))

    def code(self, script: str, *modules: str) -> tuple[str, ...]:
        """The package sources ``workflow/scripts/<script>`` runs, relative to the working directory."""
        files = script_dependencies(self.root / "workflow" / "scripts" / script, self.package_dir, modules)
        return tuple(os.path.relpath(path) for path in files)

    def result(self, path: str) -> str:
        """A path of the registry (relative to a results folder) in this configuration's folder."""
        return self.paths.result(path)

    def simulations(self, cases: Iterable[str]) -> list[str]:
        return [self.paths.simulation(case) for case in cases]

    def figure(self, name: str) -> dict[str, str]:
        """The outputs of a figure: its PDF and its PNG."""
        return {ext: self.paths.figure(name, ext) for ext in FIGURE_FORMATS}

    def case(self, wildcards) -> object:
        """The resolved case of a job's ``{case}`` (a ``Case``)."""
        return self.settings.case(wildcards.case)

    def numerics(self) -> dict:
        return {"n_modes": self.cfg["numerics"]["modes"], "n_quad": self.cfg["numerics"]["quadrature_points"]}

    # --- simulations (simulate.smk, matrices.smk) ------------------------------------------------

    def _matrices_configurations(self) -> dict[str, dict]:
        """``{name: {mass, position, inertia, offset, functions, modes}}`` of the tip masses (or bodies)
        and transverse functions of the cases, each with the most modes a case using it takes (the
        others read leading blocks: the functions of a count are the first of a larger count's)."""
        configurations = {}
        for case in self.settings.cases.values():
            tip = case.tip_mass
            if tip.mass == 0.0 and tip.is_point:
                tip = TipMass(mass=0.0, position=self.cfg["beam"]["length"])
            entry = configurations.setdefault(configuration_name(tip, case.transverse_functions), {
                "mass": tip.mass, "position": tip.position, "inertia": tip.inertia, "offset": tip.offset,
                "functions": case.transverse_functions, "modes": case.modes})
            entry["modes"] = max(entry["modes"], case.modes)
        return configurations

    def matrices_configuration(self, wildcards) -> dict:
        """The tip mass and mode count of a job's ``{config_name}``."""
        configurations = self.matrices_configurations
        if wildcards.config_name not in configurations:
            raise NotPlanned(f"{self.paths.matrices(wildcards.config_name)}: unknown configuration "
                             f"{wildcards.config_name!r}; allowed: {', '.join(sorted(configurations))}")
        return configurations[wildcards.config_name]

    def case_matrices(self, wildcards) -> str:
        """The matrices file of a job's case (:meth:`matrices_file`)."""
        return self.matrices_file(self.case(wildcards))

    def matrices_file(self, case) -> str:
        """The matrices file of ``case``: that of its tip-mass configuration and transverse functions."""
        return self.paths.matrices(configuration_name(case.tip_mass, case.transverse_functions))

    def case_kernel(self, wildcards) -> str:
        """The marker of the compiled kernel a job's case runs: its family's, or its sampled-controller
        kernel (:data:`KERNELS`)."""
        case = self.case(wildcards)
        return SHARED.kernel_marker(kernel_name(model(case.model).family, sampling_of(case) is not None))

    def simulation_steps(self) -> dict[str, Step]:
        paths, settings = self.paths, self.settings
        numerics = settings.numerics.simulation()
        check = settings.numerics.convergence_check
        return {
            "simulation_kernel": self.step(
                "compile_simulation_kernel.py", output={"done": SHARED.kernel_marker("{kernel}")},
                log=SHARED.log("simulations", "kernel_{kernel}.log"),
                params={"family": _kernel_family, "sampled": _kernel_sampled},
                wildcards=[{"kernel": name} for name in KERNELS]),
            "matrices": self.step(
                "assemble_matrices.py", output={"nc": paths.matrices("{config_name}")},
                log=paths.log("matrices", "{config_name}.log"),
                params={"beam": self.cfg["beam"], "configuration": self.matrices_configuration,
                        "n_quad": self.cfg["numerics"]["quadrature_points"]},
                wildcards=[{"config_name": name} for name in sorted(self.matrices_configurations)]),
            "simulate": self.step(
                "simulate_case.py", output={"nc": paths.simulation("{case}")},
                log=paths.log("simulations", "{case}.log"),
                input={"matrices": self.case_matrices, "kernel": self.case_kernel},
                params={"beam": settings.beam, "case": self.case, "numerics": numerics, "convergence_check": check,
                        "settings": fingerprint(settings.beam, self.case, numerics, check)},
                wildcards=[{"case": case} for case in self.cases]),
        }

    # --- the eigen-analysis (eigen.smk) -----------------------------------------------------------

    def eigen_steps(self) -> dict[str, Step]:
        eigen, beam = self.cfg["eigen"], self.cfg["beam"]
        search = {"search_max": eigen["critical_speed_search_max"]}
        return {
            "eigen_k22": self.step(
                "eigen_k22.py", output={"nc": self.result(K22_NC)}, log=self.paths.log("eigen", "k22.log"),
                params={"beam": beam, "tip_masses": eigen["tip_masses"], "positions": eigen["positions"],
                        "speeds": eigen["speeds"], **self.numerics()}),
            "eigen_critical_speeds": self.step(
                "eigen_critical_speeds.py", output={"nc": self.result(CRITICAL_SPEEDS_NC)},
                log=self.paths.log("eigen", "critical_speeds.log"),
                params={"beam": beam, "tip_masses": eigen["tip_masses"], "positions": eigen["positions"], **search,
                        **self.numerics()}),
            "eigen_critical_speed_table": self.step(
                "eigen_critical_speed_table.py", output={"csv": self.result(CRITICAL_SPEEDS_CSV)},
                log=self.paths.log("eigen", "critical_speed_table.log"),
                params={"beam": beam, "tip_masses": eigen["tip_masses"], **search, **self.numerics()}),
            "eigen_campbell": self.step(
                "eigen_campbell.py", output={"nc": self.result(CAMPBELL_NC)},
                log=self.paths.log("eigen", "campbell.log"),
                params={"beam": beam, "tip_masses": eigen["tip_masses"], "speeds": eigen["speeds"],
                        **self.numerics()}),
            "eigen_beam": self.step(
                "eigen_beam.py", output={"nc": self.result(BEAM_NC)}, log=self.paths.log("eigen", "beam.log"),
                params={"beam": beam, "tips": {name: case.tip_mass for name, case in self.settings.cases.items()},
                        "speeds": [0.0, eigen["speeds"]["stop"]], "tip_masses": eigen["tip_masses"],
                        "n_shapes": BEAM_MODE_SHAPES, **self.numerics()}),
            "eigen_table2": self.step(
                "eigen_table2.py", output={"csv": self.result(TABLE2_CSV)}, log=self.paths.log("eigen", "table2.log"),
                params={"beam": beam, "speed": self.settings.eigen.table2_speed, **self.numerics()}),
        }

    # --- figures (figures.smk, study.smk) ---------------------------------------------------------

    def figure_names(self, key: str, product: Product) -> list[tuple[str, str]]:
        """``(label, figure name)`` of every figure of ``product``: its key, or one ``<key>_<name>``
        per case or per comparison, labelled by the case or the comparison."""
        names = {CASE_FIGURE: self.cases, COMPARISON_FIGURE: sorted(self.comparisons)}.get(product.kind)
        return [(key, key)] if names is None else [(name, f"{key}_{name}") for name in names]

    def figure_files(self, ext: str) -> dict[str, str]:
        """``{figure name: path}`` of every figure of the configuration in the format ``ext``."""
        return {name: self.paths.figure(name, ext) for key, product in self.products.items() if product.is_figure
                for _, name in self.figure_names(key, product)}

    def report_figures(self) -> dict[str, dict[str, str]]:
        """The PNG of every figure by the section of the reports its product names, then by label."""
        sections: dict[str, dict[str, str]] = {}
        for key, product in self.products.items():
            if product.is_figure:
                for label, name in self.figure_names(key, product):
                    sections.setdefault(product.section, {})[label] = self.paths.figure(name, "png")
        return sections

    def comparison(self, wildcards) -> list[str]:
        """The cases of a job's ``{comparison}`` (``study.comparisons``)."""
        if wildcards.comparison not in self.comparisons:
            raise NotPlanned(f"unknown comparison {wildcards.comparison!r}; defined in study.comparisons: "
                             f"{', '.join(sorted(self.comparisons)) or 'none'}")
        return list(self.comparisons[wildcards.comparison])

    def comparison_simulations(self, wildcards) -> list[str]:
        return self.simulations(self.comparison(wildcards))

    def figure_step(self, key: str, product: Product) -> Step:
        """The step of the figure(s) of ``product``."""
        common = {"function": product.function, "caption": product.caption()}
        log = self.paths.log("figures", f"{key}.log")
        if product.kind == SIMULATION_FIGURE:
            return self.step("figure_simulation.py", output=self.figure(key), log=log, modules=(product.module,),
                             input={"datasets": self.simulations(product.cases), "style": self.style},
                             params={**common, "cases": list(product.cases)})
        if product.kind == FILES_FIGURE:
            files = {name: self.result(path) for name, path in product.files.items()}
            return self.step("figure_files.py", output=self.figure(key), log=log, modules=(product.module,),
                             input={**files, "style": self.style}, params={**common, "options": dict(product.options)})
        if product.kind == CASE_FIGURE:
            return self.step("study_figure.py", output=self.figure(f"{key}_{{case}}"), modules=(product.module,),
                             log=self.paths.log("figures", f"{key}_{{case}}.log"),
                             input={"simulations": [self.paths.simulation("{case}")]},
                             params={**common, "per_case": True, "cases": ["{case}"], "name": "{case}"},
                             wildcards=[{"case": case} for case in self.cases])
        if product.kind == COMPARISON_FIGURE:
            return self.step("study_figure.py", output=self.figure(f"{key}_{{comparison}}"),
                             modules=(product.module,), log=self.paths.log("figures", f"{key}_{{comparison}}.log"),
                             input={"simulations": self.comparison_simulations},
                             params={**common, "per_case": False, "cases": self.comparison, "name": "{comparison}"},
                             wildcards=[{"comparison": name} for name in sorted(self.comparisons)])
        name = self.settings.study.name if self.settings.study is not None else key
        if product.kind == SHAPING_FIGURE:
            return self.step("study_figure.py", output=self.figure(key), log=log, modules=(product.module,),
                             input={"simulations": self.simulations(self.cases)},
                             params={**common, "per_case": False, "cases": list(self.cases), "name": name})
        designed = designed_cases(self.cfg)
        return self.step("study_figure.py", output=self.figure(key), log=log, modules=(product.module,),
                         input={"simulations": self.simulations(designed)},
                         params={**common, "per_case": False, "cases": designed, "name": name})

    def figure_steps(self) -> dict[str, Step]:
        return {f"figure_{key}": self.figure_step(key, product) for key, product in self.products.items()
                if product.kind in (SIMULATION_FIGURE, FILES_FIGURE, CASE_FIGURE, COMPARISON_FIGURE, DESIGNS_FIGURE,
                                    SHAPING_FIGURE)}

    def figure_targets(self) -> list[str]:
        """The PDF and PNG of every figure of the configuration."""
        return sorted(path for ext in FIGURE_FORMATS for path in self.figure_files(ext).values())

    # --- tables (figures.smk) ---------------------------------------------------------------------

    def table_steps(self) -> dict[str, Step]:
        def log(key):
            return self.paths.log("tables", f"{key}.log")

        def outputs(key, formats=TABLE_FORMATS):
            return {ext: self.paths.table(key, ext) for ext in formats}

        table2, table3 = PAPER_PRODUCTS["table2"], PAPER_PRODUCTS["table3"]
        return {
            "table1": self.step("table_1.py", output=outputs("table1"), log=log("table1"),
                                params={"beam": self.cfg["beam"], "caption": PAPER_PRODUCTS["table1"].caption()}),
            "table2_render": self.step("table_2.py", output=outputs("table2", ("md", "tex")), log=log("table2"),
                                       input={name: self.result(path) for name, path in table2.files.items()},
                                       params={"speed": self.settings.eigen.table2_speed, "caption": table2.caption()}),
            "table3": self.step("table_3.py", output=outputs("table3"), log=log("table3"),
                                input={"datasets": self.simulations(table3.cases)},
                                params={"cases": list(table3.cases), "caption": table3.caption()}),
        }

    def table_targets(self) -> list[str]:
        """csv, Markdown and LaTeX of every table (table2.csv comes from the eigen-analysis)."""
        return [self.paths.table(key, ext) for key in self.table_keys() for ext in TABLE_FORMATS]

    def table_keys(self) -> list[str]:
        return sorted(key for key, product in self.products.items() if product.kind == TABLE)

    # --- linear models (linear.smk) ---------------------------------------------------------------

    def linear_exports(self) -> list[LinearExport]:
        """Every model and hub condition at every tip mass of ``linear.tip_masses``."""
        return [LinearExport(k, name, hub, *(self.paths.linear_model(name, hub, k, ext) for ext in ("nc", "mat")))
                for k in range(len(self.cfg["linear"]["tip_masses"])) for name in MODELS for hub in HUBS]

    def linear_steps(self) -> dict[str, Step]:
        linear, numerics = self.cfg["linear"], self.cfg["numerics"]
        common = {"beam": self.cfg["beam"], "tip_masses": linear["tip_masses"], "speeds": linear["speeds"],
                  "damping": linear.get("damping"), **self.numerics()}

        def dataset(product, **params):
            return self.step("linear_dataset.py", output={"nc": self.result(LINEAR_NC[product])},
                             log=self.paths.log("linear", f"{product}.log"),
                             params={**common, "product": product, **params})

        exports = self.linear_exports()
        return {
            "linear_models": self.step(
                "linear_models.py", output={"files": [path for export in exports
                                                      for path in (export.netcdf, export.matlab)]},
                log=self.paths.log("linear", "models.log"), params={**common, "exports": exports}),
            "linear_campbell": dataset("campbell"),
            "linear_poles_zeros": dataset("poles_zeros"),
            "linear_bode": dataset("bode", bode_speeds=linear["bode_speeds"], frequencies=linear["frequencies"]),
            "linear_mode_shapes": self.step(
                # no more than the vibration modes every model has (SFOAM: numerics.modes)
                "linear_mode_shapes.py", output={"nc": self.result(LINEAR_NC["mode_shapes"])},
                log=self.paths.log("linear", "mode_shapes.log"), input={"campbell": self.result(LINEAR_NC["campbell"])},
                params={"beam": self.cfg["beam"], "shapes": min(linear["shapes"], numerics["modes"])}),
        }

    # --- alternative readings (readings.smk) ------------------------------------------------------

    def reading(self, wildcards) -> ReadingRuns:
        """The runs of a job's ``{reading}``."""
        if wildcards.reading not in self.readings:
            raise NotPlanned(f"{self.paths.reading(wildcards.reading)}: unknown reading {wildcards.reading!r}; "
                             f"allowed: {', '.join(self.readings) or 'none configured'}")
        return self.readings[wildcards.reading]

    def reading_cases(self, wildcards) -> list[str]:
        """The default runs a job's reading reads (its claims' products), sorted."""
        return sorted(self.reading(wildcards).bases)

    def reading_simulations(self, wildcards) -> list[str]:
        return self.simulations(self.reading_cases(wildcards))

    def reading_matrix(self) -> list[str]:
        """The claims x readings matrix (none without readings)."""
        return [self.paths.readings("csv"), self.paths.readings("nc")] if self.readings else []

    def reading_steps(self) -> dict[str, Step]:
        return {
            "reading": self.step(
                "readings_reading.py", output={"csv": self.paths.reading("{reading}")},
                log=self.paths.log("readings", "{reading}.log"),
                input={"datasets": self.reading_simulations, **self.claim_tables(), "claims": self.paths.claims(),
                       "kernel": [SHARED.kernel_marker(family) for family in FAMILIES]},
                params={"cases": self.reading_cases, "runs": self.reading, "settings": fingerprint(self.reading)},
                wildcards=[{"reading": name} for name in self.readings]),
            "readings_matrix": self.step(
                "readings_matrix.py", output={"csv": self.paths.readings("csv"), "nc": self.paths.readings("nc")},
                log=self.paths.log("readings", "matrix.log"),
                input={"readings": [self.paths.reading(name) for name in self.readings]},
                params={"readings": self.cfg.get("readings", {})}),
        }

    # --- claims, reports and archive (report.smk, study.smk) --------------------------------------

    def claim_tables(self) -> dict[str, str]:
        """The tables of the eigen-analysis the claims read besides the runs, by input name."""
        return {"table2": self.result(TABLE2_CSV), "critical_speeds": self.result(CRITICAL_SPEEDS_CSV)}

    def published_validation(self) -> dict[str, str]:
        """The products of the published-table validation the reproduction report reads, by input
        name (none without the paper's products or without ``validation.published``)."""
        if not self.with_paper or "published" not in (self.validation or {}):
            return {}
        return {"published": self.paths.published_comparison(), "tip_mass": self.paths.tip_mass_comparison(),
                "curves": self.paths.rotating_eigen(), "published_figure": self.paths.rotating_frequencies("png")}

    def reports(self) -> list[str]:
        """The reports the configuration asks for: the claims and the reproduction report with the
        paper's products, the study report with a ``study`` section."""
        paper = [self.paths.claims(), self.paths.reproduction("md"), self.paths.reproduction("html")]
        study = [self.paths.study_report("md"), self.paths.study_report("html"), self.paths.summary(),
                 *self.shaping_data().values()]
        return (paper if self.with_paper else []) + (study if self.settings.study is not None else [])

    def shaping_data(self) -> dict[str, str]:
        """The numbers of a study that shapes commands (``hubbeam.study.shaping``), written with its
        report: ``{"shaping": report/shaping.nc}``, or nothing."""
        shaped = self.settings.study is not None and shaped_cases(self.cfg)
        return {"shaping": self.paths.shaping()} if shaped else {}

    def report_steps(self) -> dict[str, Step]:
        paths, cfg, settings = self.paths, self.cfg, self.settings
        claim_cases = product_cases(PAPER_PRODUCTS)
        return {
            "claims": self.step(
                "report_claims.py", output={"claims": paths.claims()}, log=paths.log("report", "claims.log"),
                input={"datasets": self.simulations(claim_cases), **self.claim_tables()},
                params={"cases": claim_cases}),
            "reproduction_report": self.step(
                "report_reproduction.py", output={"markdown": paths.reproduction("md"),
                                                  "html": paths.reproduction("html")},
                log=paths.log("report", "reproduction.log"),
                input={"claims": paths.claims(), "figures": list(self.figure_files("png").values()),
                       "tables": [paths.table(key, "md") for key in self.table_keys()],
                       "datasets": self.simulations(self.cases), **self.published_validation(),
                       **({"readings": paths.readings("csv")} if self.readings else {})},
                params={"cases": list(self.cases), "numerics": cfg["numerics"], "readings": cfg.get("readings", {})}),
            "study_report": self.step(
                "study_report.py", output={"markdown": paths.study_report("md"), "html": paths.study_report("html"),
                                           "summary": paths.summary(), **self.shaping_data()},
                log=paths.log("report", "report.log"),
                input={"simulations": self.simulations(self.cases), "figures": list(self.figure_files("png").values()),
                       "matrices": [self.matrices_file(settings.case(case)) for case in self.cases],
                       **self.control_report_inputs()},
                params={"study": cfg.get("study"), "beam": cfg["beam"], "cases": list(self.cases),
                        "case_settings": [settings.case(case) for case in self.cases],
                        "settings": fingerprint(*(settings.case(case) for case in self.cases)),
                        "figures": self.report_figures(), "control_cases": self.control_cases()}),
            "archive": self.step(
                "archive.py", output={"archive": paths.archive()}, log=paths.log("report", "archive.log"),
                input={"files": self.archived()},
                params={"config": cfg, "paths": paths, "workflow_root": str(self.root)}, code=False),
        }

    def archived(self) -> list[str]:
        """Everything the archive bundles (the targets of ``all`` but the archive): the netCDF
        results (simulations, matrices, eigen-analysis, sweeps, linear models), figures, tables,
        reports, the published-table validation and the readings (not the optional Exudyn
        validation)."""
        matrices = [self.paths.matrices(name) for name in sorted(self.matrices_configurations)]
        read = {self.result(path) for product in self.products.values() for path in product.files.values()}
        eigen = sorted(read | (set(self.claim_tables().values()) if self.with_paper else set()))
        models = [path for export in self.linear_exports() for path in (export.netcdf, export.matlab)]
        published = self.published_validation()
        validation = sorted(published.values()) + ([self.paths.rotating_frequencies("pdf")] if published else [])
        return sorted(set(self.simulations(self.cases) + matrices + eigen + self.sweep_files(in_all=True) + models
                          + self.figure_targets() + self.table_targets() + self.reports() + validation
                          + self.reading_matrix() + self.controller_files()))

    # --- parameter sweeps (sweeps.smk) ------------------------------------------------------------

    def sweep(self, wildcards):
        """The :class:`~hubbeam.configuration.settings.Sweep` of a job's ``{sweep}``."""
        if wildcards.sweep not in self.settings.sweeps:
            raise NotPlanned(f"unknown sweep {wildcards.sweep!r}; allowed: "
                             f"{', '.join(self.settings.sweeps) or 'none configured'}")
        return self.settings.sweeps[wildcards.sweep]

    def sweep_config(self, wildcards) -> dict:
        """The sweep of a job as its plain mapping, the param Snakemake compares for it."""
        return self.sweep(wildcards).to_dict()

    def sweep_chunks(self, wildcards) -> list[str]:
        """The chunk files of a job's sweep."""
        return [self.paths.sweep_chunk(wildcards.sweep, str(chunk)) for chunk in range(n_chunks(self.sweep(wildcards)))]

    def sweep_files(self, in_all: bool) -> list[str]:
        """The map and its figure (PDF and PNG) of every sweep whose ``in_all`` is ``in_all``."""
        names = [name for name, sweep in self.settings.sweeps.items() if sweep.in_all == in_all]
        return [self.paths.sweep(name) for name in names] + [
            self.paths.figure(f"sweep_{name}", ext) for name in names for ext in FIGURE_FORMATS]

    def sweep_steps(self) -> dict[str, Step]:
        paths, sweeps = self.paths, self.settings.sweeps
        beam = self.cfg["beam"]
        return {
            "sweep_kernel": self.step(
                "sweep_compile.py", output={"done": SHARED.sweep_kernel_marker()},
                log=SHARED.log("sweeps", "kernel.log"),
                input={"simulation_kernels": [SHARED.kernel_marker(family) for family in FAMILIES]}),
            "sweep_chunk": self.step(
                "sweep_chunk.py", output={"nc": paths.sweep_chunk("{sweep}", "{chunk}")},
                log=paths.log("sweeps", "chunks", "{sweep}", "{chunk}.log"),
                input={"kernel": SHARED.sweep_kernel_marker()},
                params={"beam": beam, "sweep": self.sweep, "sweep_config": self.sweep_config, "chunk": "{chunk}",
                        "threads": _threads},
                wildcards=[{"sweep": name, "chunk": str(chunk)} for name, sweep in sweeps.items()
                           for chunk in range(n_chunks(sweep))]),
            "sweep": self.step(
                "sweep_gather.py", output={"nc": paths.sweep("{sweep}")}, log=paths.log("sweeps", "{sweep}.log"),
                input={"chunks": self.sweep_chunks},
                params={"beam": beam, "sweep": self.sweep, "sweep_config": self.sweep_config},
                wildcards=[{"sweep": name} for name in sweeps]),
            "figure_sweep": self.step(
                "figure_sweep.py", output=self.figure("sweep_{sweep}"), log=paths.log("figures", "sweep_{sweep}.log"),
                input={"sweep": paths.sweep("{sweep}"), "style": self.style},
                wildcards=[{"sweep": name} for name in sweeps]),
        }

    # --- independent validation (validate.smk, docs/validation.md) --------------------------------

    def validation_part(self, key: str):
        """``validation.<key>``, or, without it, a params function saying the section is needed."""
        if key in (self.validation or {}):
            return self.validation[key]
        return _needs(f"validation.{key}")

    def validation_cases(self) -> list[str]:
        """The names of the validation cases, sorted (none without a ``validation`` section)."""
        return sorted((self.validation or {}).get("cases", {}))

    def validation_case(self, wildcards) -> Mapping:
        """The validation case of a job's ``{vcase}``."""
        return self._named_validation_case(wildcards.vcase, "validation.cases")

    def convergence_case(self, wildcards) -> Mapping:
        """The validation case the reference's convergence study runs (``validation.convergence.case``)."""
        if self.validation is None:
            _needs("validation.convergence")(wildcards)
        return self._named_validation_case(self.validation["convergence"]["case"], "validation.convergence.case")

    def _named_validation_case(self, name: str, key: str) -> Mapping:
        cases = (self.validation or {}).get("cases", {})
        if name not in cases:
            raise NotPlanned(f"{key}: validation case {name!r} is not defined; defined: "
                             f"{', '.join(sorted(cases)) or 'none (no validation section)'}")
        return cases[name]

    def nonuniform_checks(self) -> dict[str, str]:
        """The tables of the non-uniform checks by name: Ritz against our finite elements always,
        pyBModes for a beam off the hub axis (it needs rA > 0)."""
        checks = ("ritz_fe", "pybmodes") if self.cfg["beam"]["hub_radius"] > 0.0 else ("ritz_fe",)
        return {check: self.paths.nonuniform_check(check) for check in checks}

    def exudyn_report(self) -> dict[str, str]:
        """The Exudyn products the validation report reads, by input name (none without a
        ``validation`` section)."""
        if self.validation is None:
            return {}
        return {"comparison": self.paths.exudyn_comparison("csv"), "figure": self.paths.exudyn_comparison("png"),
                "mode_study": self.paths.exudyn_mode_study(), "convergence": self.paths.exudyn_convergence("csv")}

    def validation_files(self) -> list[str]:
        """What ``snakemake validate`` builds: the published-table validation (with the paper's
        products and ``validation.published``), the Exudyn comparison (with a ``validation``
        section), the non-uniform checks and the report of them all."""
        published = self.published_validation()
        files = sorted(published.values()) + ([self.paths.rotating_frequencies("pdf")] if published else [])
        if self.validation is not None:
            files += [self.paths.exudyn_comparison("pdf"), self.paths.exudyn_convergence("nc"),
                      *self.exudyn_report().values(),
                      *(self.paths.exudyn_case(name) for name in self.validation_cases())]
        return files + list(self.nonuniform_checks().values()) + [self.paths.validation_report("md"),
                                                                  self.paths.validation_report("html")]

    def validation_steps(self) -> dict[str, Step]:
        paths, cfg = self.paths, self.cfg
        beam, numerics = cfg["beam"], cfg["numerics"]
        names = self.validation_cases()
        per_case = [{"vcase": name} for name in names]
        return {
            "validate_published": self.step(
                "validate_published.py",
                output={"table": paths.published_comparison(), "tip_mass": paths.tip_mass_comparison(),
                        "curves": paths.rotating_eigen(), "pdf": paths.rotating_frequencies("pdf"),
                        "png": paths.rotating_frequencies("png")},
                log=paths.log("validation", "published.log"), input={"style": self.style},
                params={"published": self.validation_part("published"), "n_quad": numerics["quadrature_points"]}),
            "validate_exudyn": self.step(
                "validate_exudyn.py", output={"nc": paths.exudyn_run("{vcase}")},
                log=paths.log("validation", "exudyn_{vcase}.log"),
                params={"beam": beam, "case": self.validation_case, "exudyn": self.validation_part("exudyn"),
                        "output_step": numerics["output_step"], "name": "{vcase}"}, wildcards=per_case),
            "validate_models": self.step(
                "validate_models.py", output={"nc": paths.model_runs("{vcase}")},
                log=paths.log("validation", "models_{vcase}.log"),
                params={"beam": beam, "case": self.validation_case, "models": self.validation_part("models"),
                        "numerics": numerics, "name": "{vcase}"}, wildcards=per_case),
            "validate_case": self.step(
                "validate_case.py", output={"nc": paths.exudyn_case("{vcase}")},
                log=paths.log("validation", "case_{vcase}.log"),
                input={"reference": paths.exudyn_run("{vcase}"), "models": paths.model_runs("{vcase}")},
                params={"name": "{vcase}"}, wildcards=per_case),
            "validate_comparison": self.step(
                "validate_comparison.py",
                output={"table": paths.exudyn_comparison("csv"), "pdf": paths.exudyn_comparison("pdf"),
                        "png": paths.exudyn_comparison("png")},
                log=paths.log("validation", "comparison.log"),
                input={"cases": [paths.exudyn_case(name) for name in names] or _needs("validation.cases"),
                       "style": self.style},
                params={"cases": names or _needs("validation.cases")}),
            "validate_modes": self.step(
                "validate_modes.py", output={"csv": paths.exudyn_mode_study()},
                log=paths.log("validation", "modes.log"),
                input={"references": [paths.exudyn_run(name) for name in names] or _needs("validation.cases")},
                params={"beam": beam, "cases": {name: self.validation["cases"][name] for name in names}
                        or _needs("validation.cases"), "models": self.validation_part("models"),
                        "modes": self.validation_part("mode_study"), "numerics": numerics}),
            "validate_convergence": self.step(
                "validate_convergence.py",
                output={"table": paths.exudyn_convergence("csv"), "runs": paths.exudyn_convergence("nc")},
                log=paths.log("validation", "convergence.log"),
                params={"beam": beam, "case": self.convergence_case, "exudyn": self.validation_part("exudyn"),
                        "convergence": self.validation_part("convergence"), "output_step": numerics["output_step"]}),
            "validate_nonuniform": self.step(
                "validate_nonuniform.py", output=self.nonuniform_checks(),
                log=paths.log("validation", "nonuniform.log"),
                params={"beam": beam, "n_quad": numerics["quadrature_points"]}),
            "validation_report": self.step(
                "report_validation.py", output={"markdown": paths.validation_report("md"),
                                                "html": paths.validation_report("html")},
                log=paths.log("report", "validation_exudyn.log"),
                input={**self.exudyn_report(), **self.nonuniform_checks()}),
        }


    # --- analyses of the sampled controllers (control.smk, docs/quanser-study.md) -----------------

    def control_cases(self) -> list[str]:
        """The sampled cases whose controllers are exported: all of them, with a ``control`` section."""
        return sampled_cases(self.settings) if "control" in self.cfg else []

    def control_report_inputs(self) -> dict:
        """What the study report reads of the ``control`` section: its datasets and the exported controllers."""
        control = self.cfg.get("control", {})
        found = {part: self.result(CONTROL_NC[part]) for part in ("sample_time", "robustness") if part in control}
        return found | ({"controllers": self.controller_files()} if self.control_cases() else {})

    def controller_files(self) -> list[str]:
        """The implementation files (``.mat``, ``.json``) of every exported controller."""
        return [self.paths.result(CONTROL_FOLDER, f"{case}.{ext}") for case in self.control_cases()
                for ext in ("mat", "json")]

    def control_steps(self) -> dict[str, Step]:
        control, settings = self.cfg.get("control", {}), self.settings
        paths = self.paths

        def analysis(part: str, product: str, extra_input: Mapping | None = None) -> Step:
            spec = control.get(part)
            cases = [settings.cases[name] for name in (spec or {}).get("cases", ())]
            return self.step(
                f"control_{part}.py", output={"nc": self.result(CONTROL_NC[product])},
                log=paths.log("control", f"{part}.log"), input=extra_input,
                params={"settings": settings, "spec": spec,
                        "fingerprint": fingerprint(settings.beam, settings.numerics, *cases)},
                wildcards=[{}] if spec is not None else [])

        def kernels(part: str) -> dict:  # the sampled-loop kernels of the nonlinear confirmation runs
            names = control.get(part, {}).get("cases", ())
            families = sorted({model(settings.cases[name].model).family for name in names})
            markers = [SHARED.kernel_marker(kernel_name(family, True)) for family in families]
            return {"kernels": markers} if names else {}

        return {
            "control_sample_time": analysis("sample_time", "sample_time", kernels("sample_time")),
            "control_robustness": analysis("robustness", "robustness", kernels("robustness")),
            "control_export": self.step(
                "control_export.py", output={ext: paths.result(CONTROL_FOLDER, f"{{case}}.{ext}")
                                             for ext in ("mat", "json")},
                log=paths.log("control", "export_{case}.log"),
                params={"settings": settings, "case": "{case}",
                        "fingerprint": fingerprint(settings.beam, settings.numerics, self.case)},
                wildcards=[{"case": case} for case in self.control_cases()]),
        }


def _threads(wildcards, threads: int) -> int:
    """The threads Snakemake gives the job (a params function)."""
    return threads


def _needs(key: str):
    """A params or input function for a job that needs ``key`` of a section the configuration lacks:
    it raises :class:`NotPlanned` saying so."""
    def missing(wildcards):
        raise NotPlanned(f"{key}: missing from the configuration in use; allowed: a configuration with it "
                         "(the `validation` section, docs/validation.md)")

    return missing
