"""What every family of steps reads: the checked configuration, its folders, and the files that
one family writes and another reads.

A :class:`PlanContext` is made once per plan (:func:`hubbeam.pipeline.plan.build_plan`) and handed
to each family of :mod:`hubbeam.pipeline.families`. It builds a :class:`~hubbeam.pipeline.steps.Step`
(:meth:`PlanContext.step`: the job function, its files, its params with the fingerprint of the
records among them, its code inputs) and names the files shared between families: the runs and
their matrices, the figures and tables of the products, the tables the claims read, the exported
controllers, the published-table validation. Nothing here reads a mapping of the configuration:
the records of :class:`~hubbeam.configuration.settings.Settings` are the only source.
"""

from __future__ import annotations

import inspect
import os
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path

from hubbeam.check import CheckedConfiguration
from hubbeam.control.analyses import sampled_cases
from hubbeam.control.cases import sampling_of
from hubbeam.model.matrices import configuration_name
from hubbeam.model.models import FAMILIES, model
from hubbeam.pipeline.steps import Step, fingerprint
from hubbeam.reporting.products import (
    CASE_FIGURE,
    COMPARISON_FIGURE,
    CONTROL_FOLDER,
    CONTROL_NC,
    CRITICAL_SPEEDS_CSV,
    PLANT_FIGURE,
    TABLE,
    TABLE2_CSV,
    Product,
    shaped_cases,
)
from hubbeam.reporting.sourcedeps import script_dependencies
from hubbeam.results.paths import FIGURE_FORMATS, SHARED, StudyPaths

#: the one script every rule runs: it runs the job function its step names (``params.job``)
SCRIPT = "run_job.py"
#: the compiled simulation kernels a workflow prepares, by name (their marker's): (family, sampled)
KERNELS = {**{family: (family, False) for family in FAMILIES},
           **{f"{family}_sampled": (family, True) for family in FAMILIES}}
#: the values a params entry may hold that Snakemake compares itself in its rerun trigger
PLAIN = (str, int, float, bool, type(None))


def kernel_name(family: str, sampled: bool) -> str:
    """The name in :data:`KERNELS` of ``family``'s simulation kernel, or of its sampled-controller kernel."""
    return next(name for name, kernel in KERNELS.items() if kernel == (family, sampled))


class NotPlanned(ValueError):
    """A job asks for something the configuration does not define (the message names it and what
    is allowed)."""


class PlanContext:
    """The checked configuration as the families of steps read it (module docstring)."""

    def __init__(self, checked: CheckedConfiguration, paths: StudyPaths, root: Path):
        self.checked, self.settings, self.paths = checked, checked.settings, paths
        self.products: Mapping[str, Product] = checked.products
        self.root, self.package_dir = root, root / "src" / "hubbeam"
        self.with_paper = checked.with_paper
        self.cases = tuple(self.settings.cases)
        self.style = os.path.relpath(self.package_dir / "plotting" / "hubbeam.mplstyle")
        study = self.settings.study
        self.comparisons = dict(study.comparisons) if study is not None else {}
        #: every file of ``all`` but the archive (the plan sets it once every family has named its targets)
        self.archived: tuple[str, ...] = ()

    # --- steps ---------------------------------------------------------------------------------

    def step(self, job: str, output: Mapping, log: str, input: Mapping | None = None, params: Mapping | None = None,
             wildcards: Iterable[Mapping] = ({},), modules: Sequence[str] = (), code: bool = True,
             stands_for: Sequence | None = None, **snakemake: object) -> Step:
        """A step running the job function ``job`` (``"module:function"`` of
        :mod:`hubbeam.pipeline.jobs`) on its files and params. Its inputs end with the package
        sources the job runs (``code``: its module and every module it imports, transitively, and
        ``modules``, imported by a name computed at run time), so that editing a module reruns
        the jobs that run it; a params entry that is a record (or a function of the wildcards
        giving one) is stood for by the param ``fingerprint`` in Snakemake's rerun trigger
        (:func:`hubbeam.pipeline.steps.fingerprint`), or by ``stands_for`` when given (the parts of
        a larger record the job reads, so that editing another part reruns nothing).
        ``snakemake`` holds the step's flags (:class:`~hubbeam.pipeline.steps.Step`)."""
        inputs = dict(input or {})
        if code:
            inputs["code"] = self.code(job.partition(":")[0], *modules)
        params = {"job": job, **(params or {})}
        records = list(stands_for) if stands_for is not None else [value for value in params.values()
                                                                   if not _plain(value)]
        if records:
            params["fingerprint"] = fingerprint(*records)
        return Step(script=SCRIPT, output=output, log=log, input=inputs, params=params, wildcards=tuple(wildcards),
                    **snakemake)

    def code(self, *modules: str) -> tuple[str, ...]:
        """The package sources the generic script runs for ``modules``, relative to the working directory."""
        files = script_dependencies(self.root / "workflow" / "scripts" / SCRIPT, self.package_dir, modules)
        return tuple(os.path.relpath(path) for path in files)

    def result(self, path: str) -> str:
        """A path of the registry (relative to a results folder) in this configuration's folder."""
        return self.paths.result(path)

    def figure(self, name: str) -> dict[str, str]:
        """The outputs of a figure: its PDF and its PNG."""
        return {ext: self.paths.figure(name, ext) for ext in FIGURE_FORMATS}

    # --- the runs -------------------------------------------------------------------------------

    def simulations(self, cases: Iterable[str]) -> list[str]:
        return [self.paths.simulation(case) for case in cases]

    def case(self, wildcards):
        """The resolved case of a job's ``{case}`` (a ``Case``)."""
        return self.settings.case(wildcards.case)

    def matrices_file(self, case) -> str:
        """The matrices file of ``case``: that of its tip-mass configuration and transverse functions."""
        return self.paths.matrices(configuration_name(case.tip_mass, case.transverse_functions))

    def case_kernel(self, wildcards) -> str:
        """The marker of the compiled kernel a job's case runs: its family's, or its sampled-controller
        kernel (:data:`KERNELS`)."""
        case = self.case(wildcards)
        return SHARED.kernel_marker(kernel_name(model(case.model).family, sampling_of(case) is not None))

    # --- the products ---------------------------------------------------------------------------

    def figure_names(self, key: str, product: Product) -> list[tuple[str, str]]:
        """``(label, figure name)`` of every figure of ``product``: its key, or one ``<key>_<name>``
        per case or per comparison, labelled by the case or the comparison, or per plant, labelled
        ``<plant>/<key>``."""
        if product.kind == PLANT_FIGURE:
            return [(f"{plant}/{key}", f"{key}_{plant}") for plant in self.settings.plants]
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

    def table_keys(self) -> list[str]:
        return sorted(key for key, product in self.products.items() if product.kind == TABLE)

    def claim_tables(self) -> dict[str, str]:
        """The tables of the eigen-analysis the claims read besides the runs, by input name."""
        return {"table2": self.result(TABLE2_CSV), "critical_speeds": self.result(CRITICAL_SPEEDS_CSV)}

    def published_validation(self) -> dict[str, str]:
        """The products of the published-table validation the reproduction report reads, by input
        name (none without the paper's products or without ``validation.published``)."""
        validation = self.settings.validation
        if not self.with_paper or validation is None or validation.published is None:
            return {}
        return {"published": self.paths.published_comparison(), "tip_mass": self.paths.tip_mass_comparison(),
                "curves": self.paths.rotating_eigen(), "published_figure": self.paths.rotating_frequencies("png")}

    def reading_matrix(self) -> list[str]:
        """The claims x readings matrix (none without readings)."""
        return [self.paths.readings("csv"), self.paths.readings("nc")] if self.checked.readings else []

    def shaping_data(self) -> dict[str, str]:
        """The numbers of a study that shapes commands (``hubbeam.study.shaping``), written with its
        report: ``{"shaping": report/shaping.nc}``, or nothing."""
        config = self.checked.config
        shaped = self.settings.study is not None and bool(shaped_cases(config) or shaped_cases(config, ratios=True))
        return {"shaping": self.paths.shaping()} if shaped else {}

    # --- the identification ---------------------------------------------------------------------

    def identification_files(self) -> dict[str, str]:
        """The fit of the ``identify`` section and the fitted plant (``{"fit": ..., "fitted": ...}``,
        written when the plan is made, :mod:`hubbeam.calibration`); none without the section."""
        if self.settings.identify is None:
            return {}
        return {"fit": self.paths.identification_fit(), "fitted": self.paths.identified_plant()}

    def identification_figures(self) -> dict[str, str]:
        """The figures of the fit by name: one per experiment (its kind, which says how it is drawn)
        and ``parameters``; none without an ``identify`` section."""
        identify = self.settings.identify
        if identify is None:
            return {}
        return {**{name: identify.experiments[name] for name in (*identify.fitted, *identify.held_out)},
                "parameters": "parameters"}

    def identification_figure(self, name: str) -> list[str]:
        """The PDF and the PNG of the fit's figure ``name``."""
        return [self.paths.identification_figure(name, ext) for ext in FIGURE_FORMATS]

    # --- the sampled controllers ----------------------------------------------------------------

    def control_cases(self) -> list[str]:
        """The sampled cases whose controllers are exported: all of them, with a ``control`` section."""
        return sampled_cases(self.settings) if self.settings.control is not None else []

    def controller_files(self) -> list[str]:
        """The implementation files (``.mat``, ``.json``) of every exported controller."""
        return [self.paths.result(CONTROL_FOLDER, f"{case}.{ext}") for case in self.control_cases()
                for ext in ("mat", "json")]

    def control_report_inputs(self) -> dict:
        """What the study report reads of the ``control`` section: its datasets and the exported controllers."""
        control = self.settings.control
        found = {part: self.result(CONTROL_NC[part]) for part in (control.analyses if control else {})}
        return found | ({"controllers": self.controller_files()} if self.control_cases() else {})


def _plain(value) -> bool:
    """Whether Snakemake compares a params entry itself: built-in values, lists and dicts of them, a
    function of the job's threads (not of its settings)."""
    if callable(value):
        return "threads" in inspect.signature(value).parameters
    if isinstance(value, (list, tuple)):
        return all(_plain(item) for item in value)
    if isinstance(value, dict):
        return all(_plain(item) for item in value.values())
    return isinstance(value, PLAIN)


def threads(wildcards, threads: int) -> int:
    """The threads Snakemake gives the job (a params function)."""
    return threads


def needs(key: str):
    """A params or input function for a job that needs ``key`` of a section the configuration lacks:
    it raises :class:`NotPlanned` saying so."""
    def missing(wildcards):
        raise NotPlanned(f"{key}: missing from the configuration in use; allowed: a configuration with it "
                         "(the `validation` section, docs/validation.md)")

    return missing
