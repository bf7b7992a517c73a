"""Figures: the registry's cases, every figure renders from contract datasets, reproducible bytes,
loud failures on missing data, divergence handling, labels with units."""

from __future__ import annotations

import hashlib
import json
import re

import matplotlib.text
import numpy as np
import pytest
from PIL import Image
from synthetic_results import paper_cases, run_script, simulation_dataset, write_eigen, write_simulations

from hubbeam.plotting import draw
from hubbeam.plotting.style import styled, units_tex
from hubbeam.reporting.products import (
    FILES_FIGURE,
    PAPER_PRODUCTS,
    SIMULATION_FIGURE,
    Product,
    ProductError,
    of_kind,
    product_case_problems,
)
from hubbeam.results.io import ResultFileError, open_result
from hubbeam.results.reader import DatasetError


@pytest.fixture(scope="module")
def sims(tmp_path_factory):
    return write_simulations(tmp_path_factory.mktemp("simulations"), dt=0.1)


@pytest.fixture(scope="module")
def datasets(sims):
    return {case: open_result(path) for case, path in sims.items()}


SIMULATION_FIGURES = sorted(of_kind(PAPER_PRODUCTS, SIMULATION_FIGURE))


def group(datasets, key):
    return {case: datasets[case] for case in PAPER_PRODUCTS[key].cases}


def plotter(key):
    return PAPER_PRODUCTS[key].resolve()


def render(key, runs, pdf_path):
    return draw(plotter(key), pdf_path, runs)


def sha(path):
    return hashlib.sha256(path.read_bytes()).hexdigest()


# --- which case goes where -----------------------------------------------------------------------

def test_every_case_a_product_names_is_configured():
    assert product_case_problems(PAPER_PRODUCTS, paper_cases()) == []
    assert PAPER_PRODUCTS["fig05"].cases == ("fig05_foam_wf2p8", "fig05_foam_wf3p5", "fig05_tlam_wf2p8",
                                             "fig05_tlam_wf3p5")
    # Fig. 8 compares with the FOAM torque runs of Table 3
    assert set(PAPER_PRODUCTS["table3"].cases) < set(PAPER_PRODUCTS["fig08"].cases)


def test_missing_cases_are_listed_one_product_each():
    names = [name for name in paper_cases() if name not in ("fig04_foam", "tab3_foam_tau50")]
    problems = product_case_problems(PAPER_PRODUCTS, names)
    assert "cases: product fig04 reads fig04_foam, which the config `cases` does not define" in problems
    assert [problem.split()[2] for problem in problems] == ["fig04", "fig07", "fig08", "table3"]
    assert all(problem.endswith("reads tab3_foam_tau50, which the config `cases` does not define")
               for problem in problems[1:])


def test_a_case_joins_a_figure_only_when_a_product_names_it():
    names = list(paper_cases()) + ["fig05_cfoam_wf2p8"]
    assert product_case_problems(PAPER_PRODUCTS, names) == []
    assert all("fig05_cfoam_wf2p8" not in p.cases for p in PAPER_PRODUCTS.values())


def test_the_paper_products_cover_its_figures_and_tables():
    paper = [key for key, p in PAPER_PRODUCTS.items() if p.in_paper]
    assert paper == [f"fig{i:02d}" for i in range(3, 11)] + ["table1", "table2", "table3"]
    assert set(of_kind(PAPER_PRODUCTS, FILES_FIGURE)) == {"fig09", "campbell", "critical_map"}
    for product in PAPER_PRODUCTS.values():
        assert callable(product.resolve()), product.key
        assert (product.paper and product.ours) or product.kind == "table", product.key


def test_a_product_declaration_is_checked():
    product = Product("spinups", "simulation figure", "hubbeam.plotting.fig05:plot", "Spin-ups", "Our runs.",
                      in_paper=False, cases=["a", "b"])
    assert product.cases == ("a", "b") and product.category == "Beyond the paper"
    with pytest.raises(ProductError, match="kind 'movie' is not allowed; allowed: simulation figure"):
        Product("x", "movie", "m:f", "X", "x")
    with pytest.raises(ProductError, match="x: section 'appendix' is not allowed; allowed: paper, beam"):
        Product("x", "simulation figure", "m:f", "X", "x", section="appendix")
    with pytest.raises(ProductError, match="function 'draw' is not allowed; allowed: an import path"):
        Product("x", "simulation figure", "draw", "X", "x")


def test_snakemake_captions_escape_restructuredtext_markup():
    caption = PAPER_PRODUCTS["fig03"].caption()
    assert caption.startswith("**Fig. 3: high-order terms of CFOAM.** *Paper:* The terms")
    assert "fig03\\_cfoam\\_n1" in caption and "M\\_thth" in caption
    assert "\\|Q\\_theta\\|" in PAPER_PRODUCTS["table3"].caption()


# --- rendering -----------------------------------------------------------------------------------

@pytest.mark.parametrize("key", sorted(SIMULATION_FIGURES))
def test_every_simulation_figure_renders_pdf_and_png(key, datasets, tmp_path):
    pdf, png = render(key, group(datasets, key), tmp_path / f"{key}.pdf")
    assert pdf.read_bytes().startswith(b"%PDF") and pdf.stat().st_size > 5000
    with Image.open(png) as image:
        assert image.format == "PNG" and min(image.size) > 300


def test_rerendering_gives_identical_files_without_volatile_metadata(datasets, tmp_path):
    first = render("fig05", group(datasets, "fig05"), tmp_path / "a" / "fig05.pdf")
    second = render("fig05", group(datasets, "fig05"), tmp_path / "b" / "fig05.pdf")
    assert [sha(p) for p in first] == [sha(p) for p in second]
    pdf = first[0].read_bytes()
    assert b"CreationDate" not in pdf and b"Producer" not in pdf
    with Image.open(first[1]) as image:
        assert "Software" not in image.info


@pytest.mark.parametrize("key", sorted(SIMULATION_FIGURES))
def test_every_axis_has_units_and_every_legend_names_model_and_modes(key, datasets):
    with styled():
        fig = plotter(key)(group(datasets, key))
    for ax in fig.axes:
        assert re.search(r"\(.+\)$", ax.get_ylabel()), (key, ax.get_ylabel())
        assert ax.get_xlabel() == "" or re.search(r"\(.+\)$|^Number of modes", ax.get_xlabel())
        if ax.get_legend() is not None:
            labels = [text.get_text() for text in ax.get_legend().get_texts()]
            assert all(re.search(r"(TLAM|FOAM|SFOAM|CFOAM), n = \d", label) or "max |q|" in label
                       or "residual" in label or "peak" in label for label in labels), labels


def test_fig10_legends_name_both_models(datasets):
    with styled():
        fig = plotter("fig10")(group(datasets, "fig10"))
    for ax in fig.axes:
        labels = {text.get_text().removesuffix(" (diverged)") for text in ax.get_legend().get_texts()}
        assert labels == {"TLAM, n = 5", "FOAM, n = 5"}
    assert fig.axes[-1].get_xlabel() == "Time $t$ (s)"


def test_diverged_run_is_drawn_up_to_divergence_and_marked(datasets):
    runs = group(datasets, "fig05")
    t_div = runs["fig05_tlam_wf3p5"].attrs["diverged_at_s"]
    with styled():
        fig = plotter("fig05")(runs)
    texts = [t.get_text() for t in fig.findobj(matplotlib.text.Text)]
    assert f"TLAM diverged at t = {t_div:.2f} s" in texts
    ax = fig.axes[1]  # transverse response at 3.5 rad/s
    line = next(l for l in ax.get_lines() if l.get_label() == "TLAM, n = 5 (diverged)")
    x, y = line.get_data()
    assert np.isfinite(y).any() and x[np.isfinite(y)].max() < t_div
    # the bounded FOAM run stays readable: the frame is set by it, not by the diverging TLAM run
    foam = runs["fig05_foam_wf3p5"]["tip_transverse"].values
    span = foam.max() - foam.min()
    assert ax.get_ylim() == pytest.approx((foam.min() - span, foam.max() + span))


def test_a_study_comparison_is_titled_by_its_name_and_labels_each_run(datasets):
    from hubbeam.plotting import comparison

    runs = {case: datasets[case] for case in ("fig05_tlam_wf3p5", "fig05_foam_wf3p5")}
    with styled():
        fig = comparison.plot("spin_models", runs)
    assert fig.axes[0].get_title(loc="left") == "(a) comparison spin_models"
    labels = [line.get_label() for line in fig.axes[0].get_lines()]
    assert labels[1] == "fig05_foam_wf3p5 (FOAM, n = 5)"
    assert labels[0].startswith("fig05_tlam_wf3p5 (TLAM, n = 5), diverged at ")


def test_fig03_fails_naming_a_missing_high_order_variable():
    spec = paper_cases()["fig03_cfoam_n1"]
    ds = simulation_dataset("fig03_cfoam_n1", spec, t_end=5.0, dt=0.5).drop_vars("dQ_q2")
    with styled(), pytest.raises(DatasetError, match="fig03_cfoam_n1.*'dQ_q2'"):
        plotter("fig03")({"fig03_cfoam_n1": ds})


def test_fig06_labels_the_mode_normalisation(datasets):
    with styled():
        fig = plotter("fig06")(group(datasets, "fig06"))
    assert "unit modal mass" in fig.axes[0].get_title(loc="left")
    assert fig.axes[0].get_ylabel() == "$q_{2,i}$ (kg$^{1/2}$ m)"


@pytest.mark.parametrize("units, tex", [("m", "m"), ("rad s-1", "rad s$^{-1}$"), ("kg m2", "kg m$^{2}$"),
                                        ("kg1/2 m", "kg$^{1/2}$ m"), ("N kg-1/2", "N kg$^{-1/2}$"),
                                        ("1", "-")])
def test_units_are_typeset(units, tex):
    assert units_tex(units) == tex


# --- the Snakemake scripts -----------------------------------------------------------------------

def test_figure_script_writes_pdf_and_png(sims, tmp_path):
    cases = list(PAPER_PRODUCTS["fig04"].cases)
    out = tmp_path / "fig04.pdf"
    run_script("hubbeam.pipeline.jobs.figures:simulation_figure", input={"datasets": [str(sims[c]) for c in cases]},
               output={"pdf": str(out), "png": str(out.with_suffix(".png"))},
               params={"function": PAPER_PRODUCTS["fig04"].function, "cases": cases})
    assert out.is_file() and out.with_suffix(".png").is_file()


@pytest.mark.parametrize("damage", ["missing", "corrupt", "truncated"])
def test_figure_script_fails_loudly_naming_a_bad_dataset(damage, sims, tmp_path):
    cases = list(PAPER_PRODUCTS["fig04"].cases)
    files = [str(sims[c]) for c in cases]
    bad = tmp_path / "fig04_foam.nc"
    if damage == "corrupt":
        bad.write_bytes(b"this is not a netCDF file" * 100)
    elif damage == "truncated":
        bad.write_bytes(sims["fig04_foam"].read_bytes()[:2000])
    files[cases.index("fig04_foam")] = str(bad)
    out = tmp_path / "fig04.pdf"
    with pytest.raises(ResultFileError, match=str(bad)):
        run_script("hubbeam.pipeline.jobs.figures:simulation_figure", input={"datasets": files},
                   output={"pdf": str(out)}, params={"function": PAPER_PRODUCTS["fig04"].function, "cases": cases})
    assert not out.exists()


@pytest.mark.parametrize("key, inputs", [
    ("fig09", {"k22": "k22", "critical": "critical_speeds"}),
    ("campbell", {"campbell": "campbell", "critical": "critical_speeds"}),
    ("critical_map", {"critical": "critical_speeds"}),
])
def test_eigen_figure_script_passes_named_inputs(key, inputs, tmp_path_factory, tmp_path):
    eigen = write_eigen(tmp_path_factory.mktemp("eigen"), n_modes=3, n_quad=16)
    out = tmp_path / f"{key}.pdf"
    run_script("hubbeam.pipeline.jobs.figures:files_figure",
               input={name: str(eigen[stem]) for name, stem in inputs.items()} | {"style": "x", "code": []},
               output={"pdf": str(out)}, params={"function": PAPER_PRODUCTS[key].function, "options": {}})
    assert out.is_file() and out.with_suffix(".png").is_file()


def test_fig05_panels_have_distinct_labels_row_by_row(datasets):
    with styled():
        fig = plotter("fig05")(group(datasets, "fig05"))
    titles = [ax.get_title(loc="left") for ax in fig.axes]
    assert [title[:3] for title in titles] == ["(a)", "(b)", "(c)", "(d)"]
    assert "Transverse" in titles[1] and "3.5 rad/s" in titles[1] and "Axial" in titles[2]


def test_campbell_legend_states_the_mode_count(tmp_path_factory):
    from hubbeam.plotting import campbell
    eigen = write_eigen(tmp_path_factory.mktemp("campbell"), n_modes=3, n_quad=16)
    with styled():
        fig = campbell.plot(open_result(eigen["campbell"]), open_result(eigen["critical_speeds"]))
    labels = [text.get_text() for legend in fig.legends for text in legend.get_texts()]
    assert labels == ["TLAM, n = 3 (modes 1-3)", "FOAM, n = 3 (modes 1-3)"]
    assert all(len(ax.get_lines()) >= 2 * 3 for ax in fig.axes)  # every mode of both models drawn


#: the y-axis symbol of a response panel and the dataset variable it must show
PANEL_VARIABLES = {"$v(L)$": "tip_transverse", "$w_1(L)$": "tip_axial"}


def _model_curves(ax):
    """``(line, model, modes, label)`` of every curve of ``ax`` labelled like a legend entry."""
    for line in ax.get_lines():
        label = re.match(r"(TLAM|FOAM|SFOAM|CFOAM), n = (\d+)", line.get_label())
        if label is not None:
            yield line, label[1], int(label[2]), line.get_label()


def _is_series_of_a_run(line, runs, model, modes, series):
    """The curve is ``series(ds)`` against time for one of ``runs`` with that model and mode
    count (NaN where the run diverged)."""
    x, y = (np.asarray(a, dtype=float) for a in line.get_data())
    return any(np.array_equal(x, ds["time"].values)
               and np.array_equal(y, np.asarray(series(ds), dtype=float), equal_nan=True)
               for ds in runs.values()
               if ds.attrs["model"] == model and int(ds.attrs["n_modes"]) == modes
               and ds.sizes["time"] == x.size)


@pytest.mark.parametrize("key", ["fig04", "fig05", "fig06", "fig08", "fig10"])
def test_response_panels_draw_the_variable_their_axis_names(key, datasets):
    """Every model curve of a transverse or axial tip panel is exactly that variable of one of
    the figure's cases with the curve's model and mode count (not another variable, case or
    scaling); a diverged curve up to its divergence."""
    runs = group(datasets, key)
    with styled():
        fig = plotter(key)(runs)
    checked = 0
    for ax in fig.axes:
        name = next((v for symbol, v in PANEL_VARIABLES.items()
                     if ax.get_ylabel().startswith(symbol)), None)
        if name is None:
            continue
        for line, model, modes, label in _model_curves(ax):
            assert _is_series_of_a_run(line, runs, model, modes, lambda ds, name=name: ds[name].values), \
                (key, ax.get_ylabel(), label)
            checked += 1
    assert checked >= 2, key


def test_fig03_panels_draw_the_high_order_terms_they_name(datasets):
    from hubbeam.plotting.fig03 import PANELS

    runs = group(datasets, "fig03")
    with styled():
        fig = plotter("fig03")(runs)
    for ax, (name, _) in zip(fig.axes, PANELS):
        curves = list(_model_curves(ax))
        assert curves
        for line, model, modes, label in curves:
            mode = re.search(r", mode (\d+)", label)
            def series(ds, name=name, mode=mode):
                da = ds[name]
                return da.sel(mode=int(mode[1])).values if mode else da.values
            assert _is_series_of_a_run(line, runs, model, modes, series), (name, label)


def test_fig07_draws_q_theta_and_its_ratio_to_the_torque_amplitude(datasets):
    runs = group(datasets, "fig07")
    with styled():
        fig = plotter("fig07")(runs)
    absolute, relative = fig.axes[:2]
    for line, model, modes, label in _model_curves(absolute):
        assert _is_series_of_a_run(line, runs, model, modes, lambda ds: ds["Q_theta"].values), label
    curves = list(_model_curves(relative))
    assert curves
    for line, model, modes, label in curves:
        tau = float(re.search(r"= ([0-9.]+) N m", label)[1])
        same_tau = {c: d for c, d in runs.items()
                    if json.loads(d.attrs["maneuver"]).get("tau_max") == tau}
        assert _is_series_of_a_run(line, same_tau, model, modes,
                                   lambda ds, tau=tau: 100.0 / tau * ds["Q_theta"].values), label


# --- layering ------------------------------------------------------------------------------------

def test_plotting_and_the_registry_do_not_import_the_report_or_the_claims():
    import ast
    from pathlib import Path

    import hubbeam

    package = Path(hubbeam.__file__).parent
    forbidden = ("hubbeam.paper.report", "hubbeam.paper.claims", "hubbeam.reporting.document")
    for path in [*sorted((package / "plotting").glob("*.py")), package / "reporting" / "products.py",
                 package / "results" / "measures.py"]:
        for node in ast.walk(ast.parse(path.read_text())):
            names = ([alias.name for alias in node.names] if isinstance(node, ast.Import)
                     else [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
            assert not [n for n in names if n.startswith(forbidden)], (path.name, names)
