"""The fit (``hubbeam.identification.fit``) on synthetic rig data with known parameters.

* round trip: from the H1 estimates of a swept sine and from a voltage pulse read by the encoder and
  the strain gauge (noise, quantisation), each identifiable parameter comes back within 2 % of its
  true value; the fit on the frequency responses predicts the held-out pulse to its noise;
* coverage: over 50 noise seeds of a frequency response with the stated errors, the 95 % interval
  of each parameter holds its true value at least 45 times;
* what an experiment cannot see is reported, not failed: the clamp's damping from a tap test's
  frequencies, a tip body's rotary inertia from the first mode alone;
* the fit's dataset is CF and round-trips through netCDF, and every figure draws from it.
"""

from __future__ import annotations

import numpy as np
import pytest

from hubbeam.identification.dataset import fit_dataset
from hubbeam.identification.experiments import FrequencyResponse, ModalTest
from hubbeam.identification.fit import fit
from hubbeam.identification.parameters import apply, free_parameters
from hubbeam.identification.plant import CasePlant
from hubbeam.identification.synthetic import TRUTH, doublet, measured, modal_test, rig_case, sweep_responses
from hubbeam.plotting import draw
from hubbeam.plotting.identification import plot_modes, plot_parameters, plot_response, plot_time_series
from hubbeam.results.io import open_result, write_netcdf

BOUNDS = {"root_spring.stiffness": {"lower": 10.0, "upper": 60.0}, "beam.EI_factor": {"lower": 0.7, "upper": 1.3},
          "damping.transverse": {"lower": 0.001, "upper": 0.1},
          "drive.motor_constant_factor": {"lower": 0.7, "upper": 1.3},
          "drive.viscous_friction": {"lower": 0.0, "upper": 0.05}}


@pytest.fixture(scope="module")
def plant():
    return CasePlant(*rig_case())


def _knowing(plant: CasePlant, unknown) -> CasePlant:
    """``plant`` with every true value but those of ``unknown`` applied (the fit's other parameters known)."""
    case, beam = apply(plant.case, plant.beam, {key: value for key, value in TRUTH.items() if key not in unknown})
    return CasePlant(case, beam, plant.numerics)


@pytest.fixture(scope="module")
def responses(plant):
    return sweep_responses(plant, TRUTH, np.random.default_rng(5), segment=2048, periods=6, band=(1.0, 40.0))[1]


@pytest.fixture(scope="module")
def pulse(plant):
    t, command = doublet(3.0, 0.002, 1.5, 0.2)
    return measured(plant, TRUTH, "pulse", t, ["hub_angle", "deflection_angle"], np.random.default_rng(6),
                    command=command)


@pytest.fixture(scope="module")
def response_fit(plant, responses, pulse):
    parameters = free_parameters(BOUNDS, plant.case, plant.beam)
    return fit(plant, responses, parameters, starts=3, seed=2, validation=[pulse])


def _recovered(result, tolerance=0.02):
    for key, value, identifiable in zip(result.keys, result.value, result.identifiable):
        if identifiable:
            assert value == pytest.approx(TRUTH[key], rel=tolerance), (key, value, TRUTH[key])
    return [key for key, identifiable in zip(result.keys, result.identifiable) if identifiable]


def test_a_frequency_response_fit_recovers_the_rig_and_predicts_the_held_out_pulse(response_fit):
    identifiable = _recovered(response_fit)
    assert {"damping.transverse", "drive.motor_constant_factor", "drive.viscous_friction"} <= set(identifiable)
    # the clamp and EI lower the first mode together: told apart only by the second mode, correlated
    assert abs(response_fit.correlation[0, 1]) > 0.9
    held_out = response_fit.validations["pulse"]
    assert held_out.rms_weighted < 1.5 and held_out.error < 0.02
    assert np.all(response_fit.start_costs >= response_fit.cost - 1e-9)


def test_a_time_series_fit_with_quantised_sensors_recovers_the_rig(plant, pulse):
    keys = ("root_spring.stiffness", "damping.transverse", "drive.motor_constant_factor")
    plant = _knowing(plant, keys)
    parameters = free_parameters({key: BOUNDS[key] for key in keys}, plant.case, plant.beam)
    result = fit(plant, [pulse], parameters, starts=1)
    assert _recovered(result) == list(keys)
    assert 0.5 < result.s2 < 2.0  # the noise and the quantisation, as stated
    inside = (result.lower_95 <= [TRUTH[key] for key in keys]) & ([TRUTH[key] for key in keys] <= result.upper_95)
    assert inside.sum() >= 2


def test_the_95_percent_intervals_cover_the_truth_over_50_seeds(plant):
    frequency = np.geomspace(1.0, 40.0, 80)
    keys = ("root_spring.stiffness", "damping.transverse", "drive.motor_constant_factor")
    plant = _knowing(plant, keys)
    parameters = free_parameters({key: BOUNDS[key] for key in keys}, plant.case, plant.beam)
    truth = plant.frequency_response({key: TRUTH[key] for key in keys}, "voltage", "deflection_angle", frequency)
    coherence = np.full(frequency.size, 0.95)
    error = FrequencyResponse("x", "voltage", "deflection_angle", frequency, truth, coherence, 8).standard_error()
    covered = np.zeros(len(keys), dtype=int)
    for seed in range(50):
        noise = np.random.default_rng(seed).standard_normal((2, frequency.size)) * error
        noisy = FrequencyResponse("frf", "voltage", "deflection_angle", frequency,
                                  truth * np.exp(noise[0] + 1j * noise[1]), coherence, 8)
        result = fit(plant, [noisy], parameters, starts=1)
        assert result.identifiable.all()
        covered += (result.lower_95 <= [TRUTH[k] for k in keys]) & ([TRUTH[k] for k in keys] <= result.upper_95)
    assert np.all(covered >= 45), dict(zip(keys, covered))


def test_what_an_experiment_cannot_see_is_reported_not_identifiable(plant):
    rng = np.random.default_rng(3)
    taps = [modal_test(plant, TRUTH, hub, modes, rng, f"tap_{hub}") for hub, modes in (("held", 3), ("free", 2))]
    frequencies_only = [ModalTest(name=tap.name, hub=tap.hub, mode=tap.mode, frequency=tap.frequency,
                                  frequency_std=tap.frequency_std) for tap in taps]
    tap = taps[0]
    plant = _knowing(plant, ["root_spring.stiffness"])
    clamp = free_parameters({"root_spring.stiffness": {"lower": 10.0, "upper": 60.0},
                             "root_spring.damping": {"lower": 0.0, "upper": 0.01}}, plant.case, plant.beam)
    result = fit(plant, frequencies_only, clamp, starts=2)
    assert result.identifiable.tolist() == [True, False], result.reason
    assert result.value[0] == pytest.approx(TRUTH["root_spring.stiffness"], rel=0.02)
    first = ModalTest(name="first", hub="held", mode=tap.mode[:1], frequency=tap.frequency[:1],
                      frequency_std=tap.frequency_std[:1])
    inertia = free_parameters({"root_spring.stiffness": {"lower": 10.0, "upper": 60.0},
                               "tip_mass.inertia": {"lower": 0.0, "upper": 1e-4, "start": 5e-5}},
                              plant.case, plant.beam)
    result = fit(plant, [first], inertia, starts=1)
    assert not result.identifiable[1] and "near-singular Jacobian" in result.reason[1], result.reason
    assert np.isnan(result.lower_95[1])


def test_the_fits_dataset_round_trips_and_every_figure_draws_from_it(response_fit, responses, pulse, plant,
                                                                     tmp_path):
    tap = modal_test(plant, TRUTH, "held", 3, np.random.default_rng(4), "tap")
    result = fit(plant, [tap], free_parameters({"root_spring.stiffness": BOUNDS["root_spring.stiffness"]},
                                               plant.case, plant.beam), starts=1)
    for found, experiments in ((response_fit, {**{r.name: r for r in responses}, "pulse": pulse}),
                               (result, {"tap": tap})):
        ds = open_result(write_netcdf(fit_dataset(found, experiments), tmp_path / "fit.nc"))
        assert ds.attrs["Conventions"].startswith("CF-") and ds["identifiable"].attrs["flag_meanings"]
        np.testing.assert_allclose(ds["value"].values, found.value)
        assert list(ds["parameter"].values) == list(found.keys)
    ds = open_result(write_netcdf(fit_dataset(response_fit, {**{r.name: r for r in responses}, "pulse": pulse}),
                                  tmp_path / "fit.nc"))
    drawn = [draw(plot_response, tmp_path / "frf.pdf", ds, "frf_deflection"),
             draw(plot_time_series, tmp_path / "pulse.pdf", ds, "pulse"),
             draw(plot_parameters, tmp_path / "parameters.pdf", ds),
             draw(plot_modes, tmp_path / "tap.pdf", fit_dataset(result, {"tap": tap}), "tap")]
    assert all(png.stat().st_size > 10_000 for _, png in drawn)
    with pytest.raises(ValueError, match=r"experiment = 'pulse'; allowed: a frequency_response experiment of the "
                                         "dataset: frf_acceleration, frf_deflection"):
        plot_response(ds, "pulse")
