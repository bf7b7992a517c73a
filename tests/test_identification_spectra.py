"""From a time series to a mode and to a frequency response (``hubbeam.identification.spectra``).

* the logarithmic decrement of a free oscillation simulated by CFOAM (the hub held, a link whose
  first mode is at 3 Hz with a damping ratio of 0.034, read by a noisy, quantised strain gauge)
  gives the frequency within 1 % and the damping ratio within 10 %;
* the H1 estimate of a periodic swept sine on the synthetic rig (CFOAM with the drive and noisy,
  quantised sensors) matches the linear model's response within its coherence-based standard
  error: nine points in ten within three standard errors, in magnitude and in phase;
* an experiment taken in a loop is refused for H1; the equivalent averages of a Hann window at half
  overlap are Welch's.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.signal

from hubbeam.identification.experiments import PdLoop, TimeSeries
from hubbeam.identification.plant import CasePlant
from hubbeam.identification.predictions import predict
from hubbeam.identification.spectra import equivalent_averages, free_decay, frequency_response_estimate
from hubbeam.identification.synthetic import RIG_CASE, SENSORS, TRUTH, read_by, rig_case, sweep_responses


def test_the_log_decrement_of_a_simulated_free_oscillation_gives_its_mode():
    link = {key: value for key, value in RIG_CASE.items() if key not in ("root_spring", "drive", "tip_mass")}
    plant = CasePlant(*rig_case({**link, "maneuver": {"kind": "speed_table", "time": [0.0, 1.0], "speed": [0.0, 0.0]},
                                 "damping": {"kind": "modal", "axial": 0.01, "transverse": 0.034}}))
    first = plant.modes({}, "held")[0][0]
    values = {"beam.EI_factor": (3.0 / first) ** 2}  # the frequency goes as the square root of EI
    frequency, zeta = plant.modes(values, "held")
    assert frequency[0] == pytest.approx(3.0, rel=1e-9) and zeta[0] == pytest.approx(0.034, rel=1e-9)
    _, _, sm = plant.system(values)
    shape = np.linalg.solve(sm.K2, sm.f2L)  # a force at the tip, released
    run = plant.release(values, 0.02 * shape / (sm.f2L @ shape), 5.0, 0.002)
    reading = read_by(SENSORS["deflection_angle"], run["deflection_angle"], np.random.default_rng(7), 0.002)
    decay = free_decay(run["time"], reading)
    assert decay.frequency == pytest.approx(3.0, rel=0.01)
    assert decay.damping_ratio == pytest.approx(0.034, rel=0.1)
    assert decay.log_decrement == pytest.approx(2 * math.pi * 0.034 / math.sqrt(1 - 0.034**2), rel=0.1)


@pytest.fixture(scope="module")
def sweep():
    plant = CasePlant(*rig_case())
    series, responses = sweep_responses(plant, TRUTH, np.random.default_rng(11), segment=2048, periods=6,
                                        band=(1.0, 40.0))
    return plant, series, responses


def test_the_h1_estimate_of_a_swept_sine_is_the_linear_response_within_its_error(sweep):
    plant, _, responses = sweep
    for response in responses:
        model = predict(plant, response, TRUTH).values["response"]
        error = response.standard_error()
        ratio = model / response.response
        for part in (np.log(np.abs(ratio)), np.angle(ratio)):
            within = np.mean(np.abs(part) < 3.0 * error)
            assert within >= 0.9, (response.name, within)
        assert response.hold == "linear" and response.averages == 4.0


def test_h1_refuses_a_loop_and_welchs_averages_are_counted(sweep):
    _, series, _ = sweep
    looped = TimeSeries(name="loop", input="voltage", time=series.time, command=series.command,
                        signals=dict(series.signals), sensors=dict(series.sensors), loop=PdLoop(5.0, 0.1),
                        reference=np.zeros(series.time.size))
    with pytest.raises(ValueError, match=r"experiment loop: taken inside a loop; allowed: an open-loop experiment"):
        frequency_response_estimate(looped, "deflection_angle", 1024)
    hann = scipy.signal.get_window("hann", 1024)
    assert 100 / equivalent_averages(hann, 512, 100) == pytest.approx(1.0 + 2 * (1 - 1 / 100) * 0.1667**2, rel=2e-3)
    assert equivalent_averages(hann, 1024, 7) == 7.0
