"""Where every result and log of a configuration goes: the one place that names folders and files.

A configuration without a ``study`` section (the paper, Bai et al. 2009) writes directly under
``results/`` and ``logs/``; a study named ``<name>`` writes under ``results/<name>/`` and
``logs/<name>/`` and owns that folder (:func:`hubbeam.study.claim_folder`). The compiled
kernels are the same for every configuration, so their markers stay under ``logs/`` itself
(:data:`SHARED`).

:class:`StudyPaths` gives each kind of file its path: the rules, the scripts and the product
registry ask it instead of spelling ``results/...``; the registry states the files a product reads
relative to the results folder (:data:`IN_RESULTS`), which the rules place with
:meth:`StudyPaths.result`.
"""

from __future__ import annotations

from dataclasses import dataclass

#: the configuration of the paper, which a ``--configfile`` without a ``study`` section extends
DEFAULT_CONFIG_FILE = "config/config.yaml"
RESULTS_ROOT = "results"
LOGS_ROOT = "logs"
#: the formats every figure is written in
FIGURE_FORMATS = ("pdf", "png")
#: the formats every table is written in
TABLE_FORMATS = ("csv", "md", "tex")
#: the folder of each kind of file in a results folder: the one statement of their names
FOLDERS = {
    "simulation": "simulations",
    "matrices": "matrices",
    "eigen": "eigen",
    "linear": "linear",
    "figure": "figures",
    "table": "tables",
    "report": "report",
    "validation": "validation",
    "sweep": "sweeps",
    "reading": "readings",
    "benchmark": "benchmarks",
    "plant": "plants",
    "identification": "identification",
}


@dataclass(frozen=True)
class StudyPaths:
    """The results and logs folders of one configuration and the paths of its files.

    Every method takes names (or Snakemake wildcards such as ``"{case}"``) and returns a path
    relative to the working directory, with ``/`` separators.
    """

    results: str = RESULTS_ROOT
    logs: str = LOGS_ROOT
    #: the top folder inside the archive, and the archive's name
    archive_top: str = "hubbeam-results"
    #: the folder the archive's members are named relative to
    archive_root: str = "."
    #: the results folder belongs to one configuration file (a study's; hubbeam.study records it)
    owned: bool = False

    def result(self, *parts: str) -> str:
        """A path under the results folder."""
        return "/".join(part for part in (self.results, *parts) if part)

    def log(self, *parts: str) -> str:
        """A path under the logs folder."""
        return "/".join(part for part in (self.logs, *parts) if part)

    def simulation(self, case: str) -> str:
        return self.result(FOLDERS["simulation"], f"{case}.nc")

    def matrices(self, configuration: str) -> str:
        return self.result(FOLDERS["matrices"], f"{configuration}.nc")

    def eigen(self, name: str) -> str:
        """An eigen-analysis dataset (``k22``, ``campbell``, ``critical_speeds``)."""
        return self.result(FOLDERS["eigen"], f"{name}.nc")

    def linear(self, name: str, ext: str = "nc") -> str:
        """A linear-model dataset (``campbell``, ``poles_zeros``, ``bode``, ``mode_shapes``)."""
        return self.result(FOLDERS["linear"], f"{name}.{ext}")

    def linear_model(self, model: str, hub: str, tip_mass: int, ext: str) -> str:
        """The exported linear models of ``model`` with the hub ``hub`` at the tip mass of index
        ``tip_mass`` of ``linear.tip_masses``, as ``nc`` or ``mat``."""
        return self.linear(f"models/{model}_{hub}_tip{tip_mass}", ext)

    def plant(self, plant: str, name: str, ext: str = "nc") -> str:
        """A product of the plant ``plant`` of a study (``plant``, ``campbell``, ``poles_zeros``,
        ``bode``, ``mode_shapes``)."""
        return self.result(FOLDERS["plant"], plant, f"{name}.{ext}")

    def plant_model(self, plant: str, model: str, hub: str, ext: str) -> str:
        """The exported linear models of ``model`` for the plant ``plant`` with the hub ``hub``, as
        ``nc`` or ``mat``."""
        return self.result(FOLDERS["plant"], plant, "models", f"{model}_{hub}.{ext}")

    def figure(self, key: str, ext: str) -> str:
        return self.result(FOLDERS["figure"], f"{key}.{ext}")

    def identification_fit(self) -> str:
        """The fit of the ``identify`` section (``hubbeam.identification.dataset``)."""
        return self.result(FOLDERS["identification"], "fit.nc")

    def identified_plant(self) -> str:
        """The fitted plant as a configuration fragment (``hubbeam.calibration``)."""
        return self.result(FOLDERS["identification"], "fitted.yaml")

    def identification_figure(self, name: str, ext: str) -> str:
        """A figure of the fit: an experiment's, or ``parameters``."""
        return self.result(FOLDERS["identification"], f"{name}.{ext}")

    def figures(self, key: str) -> list[str]:
        """The figure ``key`` in every format of :data:`FIGURE_FORMATS`."""
        return [self.figure(key, ext) for ext in FIGURE_FORMATS]

    def table(self, key: str, ext: str) -> str:
        return self.result(FOLDERS["table"], f"{key}.{ext}")

    def report(self, name: str) -> str:
        """A file of the reports folder (``claims.csv``, ``report.html``, ...)."""
        return self.result(FOLDERS["report"], name)

    def validation(self, name: str) -> str:
        """A file of the independent validation (each named by one of the methods below)."""
        return self.result(FOLDERS["validation"], name)

    def sweep(self, name: str) -> str:
        return self.result(FOLDERS["sweep"], f"{name}.nc")

    def sweep_chunk(self, name: str, chunk: str) -> str:
        return self.result(FOLDERS["sweep"], "chunks", name, f"{chunk}.nc")

    def reading(self, name: str) -> str:
        """The claims evaluated under the alternative reading ``name``."""
        return self.result(FOLDERS["reading"], "claims", f"{name}.csv")

    def readings(self, ext: str) -> str:
        """The claims x readings matrix (``csv`` or ``nc``)."""
        return self.result(FOLDERS["reading"], f"readings.{ext}")

    def benchmarks(self) -> str:
        """The folder of the benchmark's tables (``make benchmark``)."""
        return self.result(FOLDERS["benchmark"])

    def archive(self) -> str:
        return self.result(f"{self.archive_top}.tar.gz")

    # --- the reports (folder report/) -------------------------------------------------------

    def claims(self) -> str:
        """The paper's claims against our results (``hubbeam.paper.claims``)."""
        return self.report("claims.csv")

    def reproduction(self, ext: str) -> str:
        """The reproduction report of the paper (``md`` or ``html``)."""
        return self.report(f"reproduction.{ext}")

    def study_report(self, ext: str) -> str:
        """A study's report (``md`` or ``html``)."""
        return self.report(f"report.{ext}")

    def summary(self) -> str:
        """A study's summary, a row per case."""
        return self.report("summary.csv")

    def shaping(self) -> str:
        """The numbers of a study that shapes commands (``hubbeam.study.shaping``), beside its report."""
        return self.report("shaping.nc")

    def validation_report(self, ext: str) -> str:
        """The report of the independent validation (``md`` or ``html``; ``snakemake validate``)."""
        return self.report(f"validation_exudyn.{ext}")

    # --- the independent validation (folder validation/) ----------------------------------------

    def published_comparison(self) -> str:
        """Rotating-cantilever frequencies against the published tables."""
        return self.validation("published_comparison.csv")

    def tip_mass_comparison(self) -> str:
        """Frequencies of a cantilever with a tip mass against the published ones."""
        return self.validation("tip_mass_comparison.csv")

    def rotating_eigen(self) -> str:
        """The frequency curves of the rotating cantilever over the dimensionless speed."""
        return self.validation("rotating_eigen.nc")

    def rotating_frequencies(self, ext: str) -> str:
        """The figure of those curves with the published values."""
        return self.validation(f"rotating_frequencies.{ext}")

    def exudyn_run(self, case: str) -> str:
        """The Exudyn ANCF reference run of the validation case ``case``."""
        return self.validation(f"runs/exudyn_{case}.nc")

    def model_runs(self, case: str) -> str:
        """The runs of hubbeam's models of the validation case ``case``."""
        return self.validation(f"runs/models_{case}.nc")

    def exudyn_case(self, case: str) -> str:
        """The models' tip deflection against the reference's, validation case ``case``."""
        return self.validation(f"exudyn_{case}.nc")

    def exudyn_comparison(self, ext: str) -> str:
        """The comparison with the Exudyn reference: its table (``csv``) and figure (``pdf``, ``png``)."""
        return self.validation(f"exudyn_comparison.{ext}")

    def exudyn_mode_study(self) -> str:
        """The models' differences from the reference against the number of assumed modes."""
        return self.validation("exudyn_mode_study.csv")

    def exudyn_convergence(self, ext: str) -> str:
        """The convergence of the reference: its table (``csv``) and runs (``nc``)."""
        return self.validation(f"exudyn_convergence.{ext}")

    def nonuniform_check(self, check: str) -> str:
        """A table of the non-uniform beam's frequencies: ``ritz_fe`` (the Ritz model against our
        finite elements) or ``pybmodes`` (both against pyBModes)."""
        return self.validation(f"nonuniform_{check}.csv")

    # --- the compiled kernels' markers (of :data:`SHARED`: every configuration shares them) ----

    def kernel_marker(self, family: str) -> str:
        """The marker of the compiled simulation kernel of a family of models."""
        return self.log("simulations", f"kernel_{family}.done")

    def sweep_kernel_marker(self) -> str:
        """The marker of the compiled sweep kernel."""
        return self.log("sweeps", "kernel.done")


#: the default folders (the paper's), which also hold what every configuration shares
SHARED = StudyPaths()
#: paths relative to a results folder, for declarations that hold for every configuration
IN_RESULTS = StudyPaths(results="", logs="")
#: the names a study may not take: the folders of the paper's products directly under results/
PAPER_FOLDERS = tuple(sorted(FOLDERS.values()))


def study_paths(name: str | None) -> StudyPaths:
    """The folders of a configuration: those of its study ``name`` (``study.name``), or the
    default ones (``name`` None: the paper, or a file extending it)."""
    if name is None:
        return SHARED
    return StudyPaths(results=SHARED.result(name), logs=SHARED.log(name), archive_top=f"{name}-results",
                      archive_root=SHARED.result(name), owned=True)

