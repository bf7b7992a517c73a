"""The registry of products: every figure and table, what it reads, how it is drawn, what it says.

A :class:`Product` declares its key (``fig05``, ``campbell``, ``table3``), its kind (a figure drawn
from simulation runs, one figure per case or per comparison of a study, a figure drawn from the
result files of the eigen-analysis or the linear models, or a table), the function that draws it
(an import path ``"module:attribute"``, imported only when the product is drawn, so that importing
the registry stays cheap), the simulation cases it reads by their exact names (no name patterns),
or the result files it reads (relative to the results folder,
:data:`hubbeam.results.paths.IN_RESULTS`; each file named once here), the configuration keys it
needs, its caption, the claims of the paper it carries and the section of the reports it is shown in.

:data:`GENERAL_PRODUCTS` are those of every configuration whose keys they need are present (the
Campbell diagram always; the study report's figures with a ``study`` section);
:data:`PAPER_PRODUCTS` are the paper's own, built when the configuration asks for them
(``products: [paper]``, :data:`PRODUCT_SETS`). :func:`products_for` gives a configuration's
products, :func:`product_case_problems` the cases they read that a configuration lacks: the
workflow's plan (:mod:`hubbeam.pipeline.plan`: targets, rules' inputs,
``snakemake --report`` captions), the figure sections of the reproduction report (with their
captions) and of the study report (by the products' ``section``) are derived from it. A new
product of every study is one entry of :data:`GENERAL_PRODUCTS` (plus a rule when no rule of its
kind exists).
"""

from __future__ import annotations

import importlib
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

from hubbeam.results.paths import IN_RESULTS

#: kinds of product: a figure drawn from simulation runs (the cases it names)
SIMULATION_FIGURE = "simulation figure"
#: one figure per configured case (``<key>_<case>``), drawn from that case's run
CASE_FIGURE = "figure per case"
#: one figure per comparison of ``study.comparisons`` (``<key>_<comparison>``), its runs overlaid
COMPARISON_FIGURE = "figure per comparison"
#: a figure drawn from the result files it names (``files``): the eigen-analysis, the linear models'
#: Campbell diagram, mode shapes, poles and zeros and Bode diagrams, the beam's data
FILES_FIGURE = "figure of result files"
#: one figure (``<key>``) of every case whose state feedback was designed (``maneuver.design``)
DESIGNS_FIGURE = "figure of the feedback designs"
#: one figure (``<key>``) of every run of a study that shapes a case's command (``shaper``); its
#: ``options`` select the shapers it needs (:func:`shaped_cases`)
SHAPING_FIGURE = "figure of the shaped commands"
#: one figure per plant of a study (``<key>_<plant>``), drawn from that plant's result files (its
#: ``files`` hold the wildcard ``{plant}``)
PLANT_FIGURE = "figure per plant"
TABLE = "table"
KINDS = (SIMULATION_FIGURE, CASE_FIGURE, COMPARISON_FIGURE, FILES_FIGURE, DESIGNS_FIGURE, SHAPING_FIGURE,
         PLANT_FIGURE, TABLE)

#: the section of the reports a product is shown in: the paper's reproduction report, or a
#: section of the study report (the beam, the cases, the comparisons, the feedback designs, the
#: eigen-analysis, the linear models)
PAPER_SECTION = "paper"
BEAM_SECTION = "beam"
CASES_SECTION = "cases"
COMPARISONS_SECTION = "comparisons"
DESIGNS_SECTION = "designs"
EIGEN_SECTION = "eigen"
LINEAR_SECTION = "linear"
SHAPING_SECTION = "shaping"
#: the model the studies of command shapers and of controllers take for the truth, the most complete
#: of the four (``hubbeam.study.shaping``, ``hubbeam.study.trust``)
REFERENCE_MODEL = "CFOAM"
PLANTS_SECTION = "plants"
SECTIONS = (PAPER_SECTION, BEAM_SECTION, CASES_SECTION, COMPARISONS_SECTION, DESIGNS_SECTION, EIGEN_SECTION,
            LINEAR_SECTION, SHAPING_SECTION, PLANTS_SECTION)

# the result files the products and the claims read, relative to a results folder: each named once
K22_NC = IN_RESULTS.eigen("k22")
CAMPBELL_NC = IN_RESULTS.eigen("campbell")
CRITICAL_SPEEDS_NC = IN_RESULTS.eigen("critical_speeds")
#: the study's beam as data: its properties along the span and first mode shapes (hubbeam.model.shapes)
BEAM_NC = IN_RESULTS.eigen("beam")
#: the linear-model datasets the figures read (hubbeam.linear.datasets)
LINEAR_NC = {name: IN_RESULTS.linear(name) for name in ("campbell", "mode_shapes", "poles_zeros", "bode")}
#: Table 2 of the paper as computed (the eigen-analysis writes it, the table's renderings and the claims read it)
TABLE2_CSV = IN_RESULTS.table("table2", "csv")
#: the critical speed of each tip mass at the beam tip (the claims read it)
CRITICAL_SPEEDS_CSV = IN_RESULTS.table("critical_speeds", "csv")
#: the products of each plant of a study (hubbeam.linear.datasets on hubbeam.linear.axes.plant_axis; the
#: plant's natural frequencies, their convergence and its critical speeds: hubbeam.study.plants), by name
PLANT_NC = {name: IN_RESULTS.plant("{plant}", name) for name in ("plant", "campbell", "mode_shapes", "poles_zeros",
                                                                  "bode")}
#: the analyses of the sampled controllers (``control`` section, hubbeam.control.analyses) and their folder
CONTROL_FOLDER = "control"
CONTROL_NC = {name: IN_RESULTS.result(CONTROL_FOLDER, f"{name}.nc") for name in ("sample_time", "robustness")}


class ProductError(ValueError):
    """A product declaration or a case it names is invalid (names the key, value and what is allowed)."""


@dataclass(frozen=True)
class Product:
    """One figure or table.

    ``cases``: the simulation cases it reads (simulation figures, tables from runs); ``files``: the
    result files it reads relative to the results folder, by the keyword its function takes them
    under (figures of result files, tables from csv). ``needs``: the configuration keys (dotted, e.g.
    ``study.comparisons``; a number indexes a list) without which it is not built. ``options``: keyword arguments of the
    drawing function besides the files (e.g. which tip mass a linear-model figure shows).
    ``paper``: what the paper shows in it; ``ours``: what our product shows. ``section``: the
    section of the reports it is shown in (:data:`SECTIONS`). ``unless``: configuration keys whose
    presence means the product is not built (a study's plants replace the paper's grid of tip masses).
    """

    key: str
    kind: str
    function: str
    title: str
    ours: str
    paper: str = ""
    in_paper: bool = True
    cases: tuple[str, ...] = ()
    files: Mapping[str, str] = field(default_factory=dict)
    claims: tuple[str, ...] = ()
    needs: tuple[str, ...] = ()
    options: Mapping[str, object] = field(default_factory=dict)
    section: str = PAPER_SECTION
    unless: tuple[str, ...] = ()

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ProductError(f"product {self.key}: kind {self.kind!r} is not allowed; "
                               f"allowed: {', '.join(KINDS)}")
        if self.section not in SECTIONS:
            raise ProductError(f"product {self.key}: section {self.section!r} is not allowed; "
                               f"allowed: {', '.join(SECTIONS)}")
        module, _, attribute = self.function.partition(":")
        if not module or not attribute:
            raise ProductError(f"product {self.key}: function {self.function!r} is not allowed; "
                               "allowed: an import path 'package.module:function'")
        object.__setattr__(self, "cases", tuple(self.cases))
        object.__setattr__(self, "files", MappingProxyType(dict(self.files)))
        object.__setattr__(self, "claims", tuple(self.claims))
        object.__setattr__(self, "needs", tuple(self.needs))
        object.__setattr__(self, "unless", tuple(self.unless))
        object.__setattr__(self, "options", MappingProxyType(dict(self.options)))

    @property
    def is_figure(self) -> bool:
        return self.kind != TABLE

    @property
    def category(self) -> str:
        """Category of the product in ``snakemake --report``."""
        if self.kind == TABLE:
            return "Tables"
        return "Figures of the paper" if self.in_paper else "Beyond the paper"

    def is_built_for(self, cfg: Mapping) -> bool:
        """Whether the configuration ``cfg`` has every key the product needs (and, for a figure of
        the feedback designs, a designed case; for a figure of the shaped commands, a case with
        the shaper its ``options`` select)."""
        return (all(_has(cfg, key.split(".")) for key in self.needs)
                and not any(_has(cfg, key.split(".")) for key in self.unless)
                and (self.kind != DESIGNS_FIGURE or bool(designed_cases(cfg)))
                and (self.kind != SHAPING_FIGURE or bool(shaped_cases(cfg, **self.options))))

    @property
    def module(self) -> str:
        """The drawing function's module, e.g. ``hubbeam.plotting.fig05``."""
        return self.function.partition(":")[0]

    def resolve(self):
        """The function that draws the product (imported now)."""
        return resolve(self.function)

    def caption(self) -> str:
        """The caption of ``snakemake --report`` (reStructuredText): title, the paper's and our text."""
        parts = [f"**{_rst(self.title)}.**"]
        if self.paper:
            parts.append(f"*Paper:* {_rst(self.paper)}")
        parts.append(f"*This study:* {_rst(self.ours)}" if self.paper else _rst(self.ours))
        return " ".join(parts)


def _cases(cfg: Mapping) -> dict:
    """The cases of ``cfg`` that are mappings (none where ``cases`` is not one: the check says so)."""
    cases = cfg.get("cases")
    if not isinstance(cases, Mapping):
        return {}
    return {name: case for name, case in cases.items() if isinstance(case, Mapping)}


def designed_cases(cfg: Mapping) -> list[str]:
    """The cases of ``cfg`` the figure of the designs measures (``hubbeam.study.trust``): a state
    feedback designed by LQR (``maneuver.design``) run on the reference model (CFOAM) or on its own
    design model; sorted. A study with none has no figure of its designs (a design run on a third
    model is neither the truth nor its prediction)."""
    def measured(case: Mapping) -> bool:
        design = case["maneuver"]["design"]
        return case.get("model") in (REFERENCE_MODEL, design.get("model") if isinstance(design, Mapping) else None)

    return sorted(name for name, case in _cases(cfg).items()
                  if isinstance(case.get("maneuver"), Mapping) and "design" in case["maneuver"] and measured(case))


def shaped_cases(cfg: Mapping, kind: str | None = None, ratios: bool = False) -> list[str]:
    """The cases of ``cfg`` the command-shaping study measures (``hubbeam.study.shaping``): run on its
    reference model (CFOAM) towards a final speed (a spin-up, or a controller's spin-up reference),
    their command shaped (``shaper``) by a shaper tuned on a model's linearisation (not on given
    frequencies); of the shaper ``kind`` if given; with ``ratios`` only those designed at a
    ``frequency_ratio``, without it only those designed at the tuned frequency itself; sorted. A
    study with none has no shaping figures (a shaper on another model still shapes its case)."""
    def spin_up(maneuver) -> bool:
        reference = maneuver.get("reference")
        return "wf" in maneuver or (isinstance(reference, Mapping) and "wf" in reference)

    return sorted(name for name, case in _cases(cfg).items()
                  if isinstance(case.get("shaper"), Mapping) and case.get("model") == REFERENCE_MODEL
                  and isinstance(case.get("maneuver"), Mapping) and spin_up(case["maneuver"])
                  and "frequencies" not in case["shaper"] and kind in (None, case["shaper"].get("kind"))
                  and ratios == ("frequency_ratio" in case["shaper"]))


def _has(cfg, keys: list[str]) -> bool:
    """Whether ``cfg`` has the dotted path ``keys``; a number is an index into a list
    (``linear.tip_masses.1``: a second tip mass)."""
    if not keys:
        return True
    if isinstance(cfg, list) and keys[0].isdigit():
        return int(keys[0]) < len(cfg) and _has(cfg[int(keys[0])], keys[1:])
    return isinstance(cfg, Mapping) and keys[0] in cfg and _has(cfg[keys[0]], keys[1:])


def _rst(text: str) -> str:
    """``text`` with the reStructuredText markup characters escaped."""
    for char in "\\*`|_":
        text = text.replace(char, "\\" + char)
    return text


def resolve(path: str):
    """The object named by an import path ``"package.module:attribute"``."""
    module, _, attribute = path.partition(":")
    return getattr(importlib.import_module(module), attribute)


def registry(*products: Product) -> Mapping[str, Product]:
    """``{key: product}`` in declaration order; a repeated key is an error."""
    out: dict[str, Product] = {}
    for product in products:
        if product.key in out:
            raise ProductError(f"product key {product.key!r} is declared twice")
        out[product.key] = product
    return MappingProxyType(out)


def merged(*registries: Mapping[str, Product]) -> Mapping[str, Product]:
    """One registry of the products of ``registries``; a product listed in several (the same
    declaration) counts once, two different products under one key are an error."""
    out: dict[str, Product] = {}
    for products in registries:
        for key, product in products.items():
            if out.setdefault(key, product) is not product:
                raise ProductError(f"product key {key!r} is declared twice")
    return MappingProxyType(out)


def of_kind(products: Mapping[str, Product], *kinds: str) -> dict[str, Product]:
    return {key: p for key, p in products.items() if p.kind in kinds}


def product_cases(products: Mapping[str, Product]) -> list[str]:
    """Every case some product reads, sorted."""
    return sorted({case for product in products.values() for case in product.cases})


def product_case_problems(products: Mapping[str, Product], case_names: Iterable[str]) -> list[str]:
    """One problem per product that reads cases the configuration does not define, naming them."""
    configured = set(case_names)
    return [f"cases: product {key} reads {', '.join(missing)}, which the config `cases` does not define"
            for key, product in products.items()
            if (missing := [case for case in product.cases if case not in configured])]


# --- the products of every configuration ------------------------------------------------------

#: the Campbell diagram: a general product that the paper's products include
CAMPBELL = Product(
    "campbell", FILES_FIGURE, "hubbeam.plotting.campbell:plot",
    "Beyond the paper: Campbell diagram", in_paper=False, section=EIGEN_SECTION,
    paper="Not in the paper; Table 2 is one vertical slice of it (1 rad/s).",
    ours="Frequencies of TLAM and FOAM against hub speed: TLAM's first frequency reaches zero at the "
         "critical speed, FOAM's rises with speed (dynamic stiffening).",
    files={"campbell": CAMPBELL_NC, "critical": CRITICAL_SPEEDS_NC},
    claims=("table2_tlam_softens_foam_stiffens",), unless=("study",))

GENERAL_PRODUCTS: Mapping[str, Product] = registry(
    Product(
        "case", CASE_FIGURE, "hubbeam.plotting.case_figure:plot", "The response of one case",
        ours="Tip deflection, hub angular velocity, hub torque and energy balance of one run of the "
             "study.", in_paper=False, needs=("study",), section=CASES_SECTION),
    Product(
        "compare", COMPARISON_FIGURE, "hubbeam.plotting.comparison:plot", "A comparison of cases",
        ours="Tip deflection, hub angular velocity and hub torque of the runs of one comparison of the "
             "study, overlaid.", in_paper=False,
        needs=("study.comparisons",), section=COMPARISONS_SECTION),
    CAMPBELL,
    Product(
        "beam_properties", FILES_FIGURE, "hubbeam.plotting.beam_properties:plot", "The beam",
        ours="rhoA, EI and EA along the span, the stations marked, and the tip mass of every case at "
             "its position.", in_paper=False,
        files={"beam": BEAM_NC}, needs=("study",), section=BEAM_SECTION),
    *(product for key, function, title, what, files in (
        ("linear_campbell", "campbell_tracked", "Tracked, damped Campbell diagram",
         "Frequency and damping ratio of every mode of every model against hub speed, with the hub "
         "held and free; each mode followed through crossings and veering by the similarity of its "
         "shape (MAC), labelled by its dominant content; the speeds where a model is unstable shaded.",
         {"campbell": LINEAR_NC["campbell"]}),
        ("linear_mode_shapes", "linear_mode_shapes", "Mode shapes of the linear models",
         "The first vibration mode shapes along the span at rest and at the highest speed, held and "
         "free hub, for every model.",
         {"shapes": LINEAR_NC["mode_shapes"]}),
        ("linear_poles_zeros", "pole_zero", "Poles and zeros over hub speed",
         "Poles and zeros from the hub torque against hub speed for "
         "every model: the collocated hub angle's zeros alternate with its poles; the tip's arc "
         "position has a mirrored pair of real zeros (non-minimum phase) that dynamic stiffening "
         "moves; TLAM's first pole reaches zero at its critical speed.",
         {"poles_zeros": LINEAR_NC["poles_zeros"]}),
        ("linear_bode", "bode", "Bode diagrams from the hub torque",
         "Bode diagrams (magnitude and phase) from the hub torque to the hub "
         "angle, the tip deflection v(L) and the tip's arc position, every model, at several hub "
         "speeds.", {"bode": LINEAR_NC["bode"]}),
    ) for product in (
        Product(key, FILES_FIGURE, f"hubbeam.plotting.{function}:plot",
                f"{title}, no tip mass",
                ours=what, in_paper=False, files=files, options={"tip_mass": 0.0}, section=LINEAR_SECTION,
                unless=("study",)),
        Product(f"{key}_tip", FILES_FIGURE, f"hubbeam.plotting.{function}:plot",
                f"{title}, the largest tip mass",
                ours=what, in_paper=False, files=files, options={"tip_mass": "largest"},
                needs=("linear.tip_masses.1",), section=LINEAR_SECTION, unless=("study",)),
    )),
    *(Product(f"plant_{name}", PLANT_FIGURE, f"hubbeam.plotting.{function}:plot", f"{title} of the plant",
              ours=what, in_paper=False, files={files: PLANT_NC[name]}, needs=("study",), section=PLANTS_SECTION)
      for name, function, files, title, what in (
        ("campbell", "campbell_tracked", "campbell", "Tracked, damped Campbell diagram",
         "Frequency and damping ratio of every mode of every model of the plant (the arm as its cases run it: "
         "its tip body, root spring, drive and damping) against hub speed, with the hub held, free and, with a "
         "drive, driven through it; each mode followed by the similarity of its shape (MAC); the speeds where a "
         "model is unstable shaded, its critical speed marked."),
        ("mode_shapes", "linear_mode_shapes", "shapes", "Mode shapes",
         "The first vibration mode shapes of the plant along the span at rest and at the highest speed, every "
         "hub condition and model, with the rotation of a tip body drawn at its position."),
        ("poles_zeros", "pole_zero", "poles_zeros", "Poles and zeros over hub speed",
         "Poles and zeros of the plant from the rig's input (the drive's voltage with a drive, else the hub "
         "torque) against hub speed for every model."),
        ("bode", "bode", "bode", "Bode diagrams",
         "Bode diagrams of the plant from the rig's input (the drive's voltage with a drive, else the hub "
         "torque) to the hub angle, the tip deflection and the tip's arc position, every model, at several "
         "hub speeds."),
    )),
    Product(
        "controller_trust", DESIGNS_FIGURE, "hubbeam.plotting.controller_trust:plot",
        "Controllers designed on one model, run on another", in_paper=False,
        ours="Peak and residual tip deflection, settling time of v(L) and peak torque of every LQR "
             "design of the study against its design speed, on CFOAM and on its own design model; "
             "the paper's conclusion (iii) that SFOAM can be used for controller design, tested.",
        needs=("study",), section=DESIGNS_SECTION),
    Product(
        "sample_time_sweep", FILES_FIGURE, "hubbeam.plotting.sample_time:plot",
        "How slowly each design may be sampled", in_paper=False,
        ours="Spectral radius of each design's sampled loop with the truth plant against the sample time: "
             "the continuous gain through the hold and a discrete LQR redesigned at each sample time, without "
             "and with one sample of delay; each plant mode's aliasing sample time 1/(2f) marked.",
        files={"sweep": CONTROL_NC["sample_time"]}, needs=("control.sample_time",), section=DESIGNS_SECTION),
    Product(
        "robustness", FILES_FIGURE, "hubbeam.plotting.robustness:plot",
        "Robustness of the sampled controllers to the plant's parameters", in_paper=False,
        ours="Spectral radius of each sampled controller's loop (built for the nominal plant) with the plant's "
             "linear model, one parameter moved over its range at a time (payload, EI, Beq, kt = km, Rm); "
             "the nominal value marked; above 1 the loop is unstable.",
        files={"robustness": CONTROL_NC["robustness"]}, needs=("control.robustness",), section=DESIGNS_SECTION),
    Product(
        "shaping_residuals", SHAPING_FIGURE, "hubbeam.plotting.shaping:residuals",
        "Residual vibration of shaped spin-ups against final speed", in_paper=False,
        ours="The tip's residual vibration on CFOAM after the shaped command ends, per shaper and the "
             "model it was tuned on (or at rest), against the final speed, with the unshaped runs and "
             "TLAM's critical speed marked.",
        needs=("study",), section=SHAPING_SECTION),
    *(Product(
        f"shaping_insensitivity_{kind.lower()}", SHAPING_FIGURE,
        f"hubbeam.plotting.shaping:insensitivity_{kind.lower()}",
        f"Insensitivity of the {kind} shaper on CFOAM", in_paper=False,
        ours=f"The residual vibration a {kind} shaper designed at a multiple of CFOAM's own mode leaves on "
             "CFOAM, relative to the unshaped run's, against that multiple (the frequency error), beside "
             "the closed form for the linear mode.",
        needs=("study",), options={"kind": kind, "ratios": True}, section=SHAPING_SECTION)
      for kind in ("ZV", "ZVD", "EI")),
)

# --- the paper's products ------------------------------------------------------------------------

_TAB3 = ("tab3_foam_tau100", "tab3_foam_tau200", "tab3_foam_tau400", "tab3_foam_tau50")
_FIG06 = ("fig06_foam_n1", "fig06_foam_n3", "fig06_foam_n5")

PAPER_PRODUCTS: Mapping[str, Product] = registry(
    Product(
        "fig03", SIMULATION_FIGURE, "hubbeam.plotting.fig03:plot",
        "Fig. 3: high-order terms of CFOAM",
        paper="The terms that distinguish CFOAM from FOAM, evaluated for a one-mode model during the "
              "spin-up to 3 rad/s; the paper finds them small and fading after the 30 s maneuver.",
        ours="Each panel is one difference CFOAM minus FOAM evaluated along the CFOAM trajectory (case "
             "fig03_cfoam_n1, 1 mode): the rotary inertia M_thth, the generalised force of the "
             "hub equation, and the generalised forces of the axial (q1) and transverse (q2) equations "
             "(note 5; derivation in docs/cfoam.md).",
        cases=("fig03_cfoam_n1",), claims=("cfoam_terms_small_after_tf",)),
    Product(
        "fig04", SIMULATION_FIGURE, "hubbeam.plotting.fig04:plot",
        "Fig. 4: CFOAM against FOAM",
        paper="Tip deflection of CFOAM and FOAM for the spin-up to 3 rad/s; the paper calls them "
              "identical.",
        ours="Panel (a) overlays both 5-mode runs, panel (b) shows their difference, so that "
             "'identical' becomes a number (claim below).",
        cases=("fig04_cfoam", "fig04_foam"), claims=("cfoam_foam_coincide_wf3",)),
    Product(
        "fig05", SIMULATION_FIGURE, "hubbeam.plotting.fig05:plot",
        "Fig. 5: TLAM against FOAM",
        paper="Transverse and axial tip response of TLAM and FOAM at 2.8 and 3.5 rad/s: TLAM diverges "
              "above about 3 rad/s and overshoots FOAM strongly at 2.8 rad/s (0.49 m against 0.22 m, "
              "residual vibration about 100 times larger).",
        ours="Columns are the two final speeds: panels (a), (b) the transverse tip deflection, (c), (d) "
             "the pure axial deformation w1(L) (note 11). A diverged run is drawn until it stops and "
             "labelled with its divergence time.",
        cases=("fig05_foam_wf2p8", "fig05_foam_wf3p5", "fig05_tlam_wf2p8", "fig05_tlam_wf3p5"),
        claims=("tlam_diverges_wf3p5", "foam_bounded_wf3p5", "peak_tip_tlam_wf2p8",
                "peak_tip_foam_wf2p8", "residual_ratio_tlam_foam_wf2p8")),
    Product(
        "fig06", SIMULATION_FIGURE, "hubbeam.plotting.fig06:plot",
        "Fig. 6: modal responses and mode count (FOAM, 5 rad/s)",
        paper="The five transverse modal coordinates during the spin-up to 5 rad/s (the first two "
              "dominate) and the axial tip response for different numbers of modes (identical); the "
              "transverse peak is about 1500 times the axial one.",
        ours="Panel (a): q2_i of the 5-mode run, modes normalised to unit modal mass (note 7), so q2_i "
             "is in kg^1/2 m; panel (b): w1(L) for n = 1, 3, 5.",
        cases=_FIG06,
        claims=("transverse_axial_ratio_wf5", "first_two_modes_dominate_wf5", "axial_same_for_n1_n5")),
    Product(
        "fig07", SIMULATION_FIGURE, "hubbeam.plotting.fig07:plot",
        "Fig. 7: inertia torque Q_theta under the torque pulse",
        paper="Q_theta for a 400 N m torque pulse; its largest value, 2.62 N m, is called a small "
              "disturbance ('about 6.5 %' of the torque, note 9: the ratio is 0.65 %).",
        ours="Panel (a) is the paper's figure; panel (b) shows Q_theta relative to the torque amplitude "
             "for all four torque cases (the numbers behind Table 3).",
        cases=_TAB3, claims=("table3_tau400", "q_theta_percent_of_tau400")),
    Product(
        "fig08", SIMULATION_FIGURE, "hubbeam.plotting.fig08:plot",
        "Fig. 8: SFOAM against FOAM under the torque pulse",
        paper="Tip deflection of FOAM and SFOAM at 50 and 200 N m: nearly equal at 50 N m; at 200 N m "
              "the residual vibration of SFOAM leads FOAM's by 0.45 rad with a 24 % smaller amplitude, "
              "and SFOAM with one mode equals SFOAM with five.",
        ours="One panel per torque amplitude; FOAM solid, SFOAM dashed (5 modes) and dotted (1 mode). "
             "Residual vibration is the response after the pulse (t > t_f = 10 s).",
        cases=("fig08_sfoam_tau200", "fig08_sfoam_tau200_n1", "fig08_sfoam_tau50") + _TAB3,
        claims=("sfoam_foam_close_tau50", "sfoam_phase_lead_tau200", "sfoam_amplitude_reduction_tau200",
                "sfoam_n1_equals_n5_tau200")),
    Product(
        "fig09", FILES_FIGURE, "hubbeam.plotting.fig09:plot",
        "Fig. 9: dominant eigenvalue of K22",
        paper="The sign of the lowest eigenvalue of TLAM's stiffness K22 against the tip-mass position, "
              "for 0.1 and 0.5 kg; the critical speeds are 2.91 rad/s (mass on the hub), 2.60 and "
              "1.91 rad/s (mass at the tip).",
        ours="The hub speed of the printed curves is not stated (note 10): we show the dominant "
             "eigenvalue over position and speed and mark where it crosses zero; eigenvalues depend on "
             "the unit modal mass normalisation (note 7).",
        files={"k22": K22_NC, "critical": CRITICAL_SPEEDS_NC},
        claims=("critical_speed_tlam_mt0", "critical_speed_tlam_mt0p1", "critical_speed_tlam_mt0p5",
                "tip_mass_lowers_tlam_critical_speed", "foam_no_critical_speed")),
    Product(
        "fig10", SIMULATION_FIGURE, "hubbeam.plotting.fig10:plot",
        "Fig. 10: TLAM with a tip mass at 2 rad/s",
        paper="TLAM tip deflection with 0.1 and 0.5 kg at the beam tip for a spin-up to 2 rad/s: with "
              "0.5 kg (critical speed 1.91 rad/s) TLAM fails, while without tip mass TLAM and FOAM "
              "nearly agree.",
        ours="One panel per tip mass, each with TLAM and FOAM (note 12 for the settings).",
        cases=("fig10_foam_mt0", "fig10_foam_mt0p1", "fig10_foam_mt0p5", "fig10_tlam_mt0",
               "fig10_tlam_mt0p1", "fig10_tlam_mt0p5"),
        claims=("tlam_fails_mt0p5_wf2", "tlam_foam_close_mt0_wf2")),
    CAMPBELL,
    Product(
        "critical_map", FILES_FIGURE, "hubbeam.plotting.critical_map:plot",
        "Beyond the paper: critical speed over tip mass and position", in_paper=False,
        paper="Not in the paper, which quotes three points of it.",
        ours="TLAM's critical speed for every tip mass and position of the eigen grid (FOAM has none).",
        files={"critical": CRITICAL_SPEEDS_NC}, claims=("critical_speed_equals_omega1",)),
    Product(
        "convergence", SIMULATION_FIGURE, "hubbeam.plotting.convergence:plot",
        "Beyond the paper: convergence in the number of modes", in_paper=False,
        paper="The paper uses five modes throughout and shows, for the axial response only, that fewer "
              "give the same result.",
        ours="Tip deflection and the dominant residual frequency of the FOAM spin-up to 5 rad/s with 1, "
             "3 and 5 modes.",
        cases=_FIG06),
    Product(
        "table1", TABLE, "hubbeam.paper.tables:table1", "Table 1: physical parameters",
        ours="The physical parameters of the hub-beam beside the printed ones (csv; Markdown and LaTeX "
             "renderings beside it)."),
    Product(
        "table2", TABLE, "hubbeam.paper.tables:table2", "Table 2: vibration frequencies",
        ours="The first five vibration frequencies of the beam, natural and of TLAM and FOAM at the hub "
             "speed of the table, beside the printed ones; the journal prints this table under Table "
             "3's caption (note 3).",
        files={"csv": TABLE2_CSV}),
    Product(
        "table3", TABLE, "hubbeam.paper.tables:table3", "Table 3: largest inertia torque",
        ours="The largest inertia torque |Q_theta| of FOAM under the torque pulse for each torque "
             "amplitude beside the printed values; the journal prints this table under Table 2's "
             "caption (note 3).",
        cases=_TAB3),
)

#: the name of the paper's product set
PAPER = "paper"
#: the products a configuration may ask for beside the general ones (``products: [paper]``)
PRODUCT_SETS: Mapping[str, Mapping[str, Product]] = MappingProxyType({PAPER: PAPER_PRODUCTS})


def product_sets(cfg: Mapping) -> list[str]:
    """The product sets the configuration asks for (``products``), each checked to exist."""
    names = cfg.get("products", [])
    if not isinstance(names, list):
        raise ProductError(f"products: got {names!r}; allowed: a list of {', '.join(PRODUCT_SETS)}")
    unknown = [name for name in names if not isinstance(name, str) or name not in PRODUCT_SETS]
    if unknown:
        raise ProductError(f"products: got {', '.join(map(repr, unknown))}; allowed: "
                           f"{', '.join(PRODUCT_SETS)}")
    return names


def products_for(cfg: Mapping) -> Mapping[str, Product]:
    """Every product of the configuration ``cfg``: the general products it has the keys for and
    those of the product sets it asks for."""
    general = {key: p for key, p in GENERAL_PRODUCTS.items() if p.is_built_for(cfg)}
    return merged(general, *(PRODUCT_SETS[name] for name in product_sets(cfg)))
