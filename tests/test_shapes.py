"""The study's beam as data and as figures: properties along the span with the stations, the
cases' tip masses, and the first transverse mode shapes, checked against the continuum
cantilever, against the Campbell diagram's frequencies and for M2-orthogonality; the report's
beam table keeps to one row per property whatever the number of stations."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hubbeam.configuration.settings import Study
from hubbeam.model.beam import beam_from_config
from hubbeam.model.eigen import campbell
from hubbeam.model.matrices import assemble
from hubbeam.model.modes import transverse_modes
from hubbeam.model.parameters import TipMass
from hubbeam.model.shapes import SPAN_POINTS, beam_dataset, span
from hubbeam.plotting import beam_properties
from hubbeam.plotting.style import styled
from hubbeam.study.report import beam_summary, study_markdown

UNIFORM = {"length": 10.0, "density": 1.2e4, "area": 1.0e-4, "youngs_modulus": 2.8e11,
           "second_moment": 5.0e-8, "hub_inertia": 1.0, "hub_radius": 0.0}
#: 161 stations of a linear taper, as the beams that motivated a summary instead of the full table
X = np.linspace(0.0, 8.0, 161)
TAPERED = {"length": 8.0, "hub_inertia": 20.0, "hub_radius": 0.3,
           "sections": {"x": X.tolist(), "rhoA": (4.9 - 0.3 * X).tolist(), "EI": (9450.0 - 590.0 * X).tolist(),
                        "EA": (1.26e8 - 7.9e6 * X).tolist()}}
BETA1 = 1.8751040687119611  # cos(b) cosh(b) = -1
SPEEDS = [0.0, 6.0]


def dataset(beam=UNIFORM, tips=None, masses=(0.0, 0.5)):
    params = beam_from_config(beam)
    tips = tips if tips is not None else {"bare": TipMass(0.0, params.L), "loaded": TipMass(0.5, 6.0)}
    return params, beam_dataset(params, tips, SPEEDS, list(masses), 3, 5, 64)


def test_properties_and_stations_of_a_tabulated_beam():
    params, ds = dataset(TAPERED)
    assert ds.sizes["station"] == 161 and ds.sizes["x"] == len(np.union1d(np.linspace(0, 8, SPAN_POINTS), X))
    np.testing.assert_array_equal(ds["station_EI"].values, TAPERED["sections"]["EI"])
    np.testing.assert_allclose(ds["rhoA"].values, 4.9 - 0.3 * ds["x"].values, rtol=1e-14)


def test_the_cases_tip_masses_are_recorded():
    _, ds = dataset()
    assert ds["case"].values.tolist() == ["bare", "loaded"]
    assert ds["case_tip_mass"].values.tolist() == [0.0, 0.5] and ds["case_tip_position"].values.tolist() == [10.0, 6.0]
    assert beam_properties.tip_masses(ds) == [(0.5, 6.0)]


def test_the_first_shape_at_rest_is_the_continuum_cantilevers():
    """Uniform, no tip mass, at rest: the first mode of cos(b) cosh(b) = -1, written out here."""
    params, ds = dataset()
    x = ds["x"].values / params.L
    b = BETA1
    sigma = (math.cosh(b) + math.cos(b)) / (math.sinh(b) + math.sin(b))
    exact = np.cosh(b * x) - np.cos(b * x) - sigma * (np.sinh(b * x) - np.sin(b * x))
    exact /= np.max(np.abs(exact))
    for model in ("TLAM", "FOAM"):
        shape = ds["shape"].sel(model=model, tip_mass=0.0, speed=0.0, mode=1).values
        np.testing.assert_allclose(shape, exact, atol=1e-9)
        frequency = float(ds["frequency"].sel(model=model, tip_mass=0.0, speed=0.0, mode=1))
        expected = b**2 * math.sqrt(params.EI / (params.rhoA * params.L**4)) / (2 * math.pi)
        assert frequency == pytest.approx(expected, rel=1e-9)


def test_frequencies_agree_with_the_campbell_diagram():
    """The eigenvectors' solver (scipy's eigh) against hubbeam.model.eigen's frequencies of the same K22."""
    params, ds = dataset()
    reference = campbell(params, [0.0, 0.5], SPEEDS, 5)["frequency"].isel(mode=slice(0, 3))
    for model in ("TLAM", "FOAM"):
        ours = ds["frequency"].sel(model=model).transpose("tip_mass", "speed", "mode").values
        np.testing.assert_allclose(ours, reference.sel(model=model).values, rtol=1e-10, equal_nan=True)


def test_tlam_beyond_its_critical_speed_has_no_first_shape():
    _, ds = dataset()  # 6 rad/s > 3.80 rad/s, TLAM's critical speed
    assert np.isnan(ds["shape"].sel(model="TLAM", speed=6.0, mode=1)).all()
    assert np.isfinite(ds["shape"].sel(model="FOAM", speed=6.0, mode=1)).all()


@pytest.mark.parametrize("speed", SPEEDS)
def test_shapes_are_mass_orthogonal_and_scaled(speed):
    """w_i = f2 v_i with v_i M2-orthogonal: the shapes' coefficients (least squares on the span)
    are M2-orthogonal; each is scaled to a largest deflection of +1 (the one normalisation, unit_peak)."""
    params, ds = dataset()
    x = span(params)
    sm = assemble(params, TipMass(0.5, params.L), 5, 64)
    basis = transverse_modes(x, 5, params)
    shapes = ds["shape"].sel(model="FOAM", tip_mass=0.5, speed=speed).values
    coefficients = np.linalg.lstsq(basis, shapes.T, rcond=None)[0]
    gram = coefficients.T @ sm.M2 @ coefficients
    off = gram - np.diag(np.diag(gram))
    assert np.max(np.abs(off)) < 1e-9 * np.max(np.diag(gram))
    peaks = shapes[np.arange(len(shapes)), np.argmax(np.abs(shapes), axis=1)]
    np.testing.assert_array_equal(peaks, 1.0)  # unit_peak: the largest deflection is +1


def test_the_beam_summary_has_a_row_per_property_whatever_the_stations():
    rows = beam_summary(beam_from_config(TAPERED))
    assert [row["name"] for row in rows] == ["rhoA", "EI", "EA"]
    assert rows[0]["root"] == pytest.approx(4.9) and rows[0]["tip"] == pytest.approx(4.9 - 2.4)
    assert rows[1]["min"] == pytest.approx(9450.0 - 590.0 * 8.0) and rows[2]["max"] == pytest.approx(1.26e8)
    uniform = beam_summary(beam_from_config(UNIFORM))
    assert [row["root"] for row in uniform] == pytest.approx([1.2, 1.4e4, 2.8e7])
    figures = {"beam": {"beam_properties": "../figures/beam_properties.png"},
               "eigen": {"mode_shapes": "../figures/mode_shapes.png"}}
    markdown = study_markdown(Study("s"), beam_from_config(TAPERED), [], figures)
    beam_section = markdown[markdown.index("## Beam"):markdown.index("## Cases")]
    assert beam_section.count("\n|") == 2 + 3  # header, rule and one row per property
    assert "161 stations" in beam_section and "](../figures/beam_properties.png)" in beam_section
    eigen_section = markdown[markdown.index("## Eigen-analysis"):]
    assert "](../figures/mode_shapes.png)" in eigen_section and "beam_properties" not in eigen_section


def test_the_beam_properties_figure_marks_stations_and_tip_masses():
    _, ds = dataset(TAPERED)
    with styled():
        axes = beam_properties.plot(ds).axes
    assert len(axes) == 3
    for ax, name in zip(axes, ("rhoA", "EI", "EA")):
        curve, stations, tip = ax.lines[:3]
        np.testing.assert_array_equal(stations.get_ydata(), ds[f"station_{name}"].values)
        assert list(tip.get_xdata()) == [6.0, 6.0]  # the loaded case's tip mass, at 6 m
