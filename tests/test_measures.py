"""Signal measures (hubbeam.results.measures) on signals whose measures are known in closed form."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hubbeam.results.measures import (
    after,
    fit_decaying_sinusoid,
    fit_sinusoid,
    late_share,
    move_time_penalty,
    peak,
    peak_time,
    phase_lead,
    relative_difference,
    residual_amplitude,
    settled_after,
    settling_time,
    shaped_residual_amplitude,
    wrap_phase,
)


def test_peak_and_its_time_ignore_samples_after_a_divergence():
    t = np.linspace(0.0, 2.0, 201)
    x = np.sin(np.pi * t) * np.exp(-t)  # |x| largest at tan(pi t) = pi
    x[150:] = np.nan
    t_star = math.atan(math.pi) / math.pi
    assert peak_time(t, x) == pytest.approx(t_star, abs=0.01)
    assert peak(x) == pytest.approx(math.sin(math.pi * t_star) * math.exp(-t_star), rel=1e-3)


def test_residual_window_and_amplitude_after_t0():
    t = np.arange(0.0, 10.0, 0.5)
    x = np.where(t > 4.0, 0.1, 3.0) * np.cos(np.pi * t)  # cos(pi t) = +-1 on this grid
    window_t, window_x = after(t, x, 4.0)
    assert window_t[0] == 4.5 and len(window_x) == 11
    assert residual_amplitude(t, x, 4.0) == pytest.approx(0.1)
    assert late_share(t, x, 4.0) == pytest.approx(0.1 / 3.0)
    assert math.isnan(residual_amplitude(t, x, 20.0))


def test_relative_difference_is_relative_to_the_second_curve():
    b = np.array([0.0, 2.0, -4.0, 1.0])
    assert relative_difference(b + np.array([0.0, 0.1, -0.2, 0.0]), b) == pytest.approx(0.05)
    assert relative_difference(b, b) == 0.0


def test_sinusoid_fit_recovers_amplitude_frequency_and_phase_off_the_spectral_grid():
    t = np.arange(10.0, 30.0, 0.01)
    y = 0.02 + 0.3 * np.cos(2.377 * (t - 10.0) - 2.9) + 0.01 * np.cos(17.0 * t)
    fit = fit_sinusoid(t, y, 10.0)
    assert fit.omega == pytest.approx(2.377, rel=1e-4)
    assert fit.amplitude == pytest.approx(0.3, rel=1e-3)
    assert wrap_phase(fit.phase + 2.9) == pytest.approx(0.0, abs=2e-3)


def test_phase_lead_of_two_fitted_sinusoids():
    t = np.arange(0.0, 20.0, 0.01)
    a = fit_sinusoid(t, np.cos(2.0 * t + 3.0), 0.0)
    b = fit_sinusoid(t, np.cos(2.0 * t - 3.0), 0.0)
    assert phase_lead(a, b) == pytest.approx(6.0 - 2 * math.pi, abs=1e-6)  # wrapped, so b leads


def test_decaying_sinusoid_fit_recovers_the_pole_amplitude_and_phase():
    """Exact for one mode (to rounding); a second, faster-decaying mode 1 % as large, at three times
    the frequency (nearly orthogonal to the fitted mode's derivatives), moves the fitted pole by
    less than a tenth of that share (measured relative shifts 1.6e-4 of the decay rate and 6e-5 of the frequency)."""
    t = np.arange(1.0, 9.0, 0.005)
    mode = 0.03 * np.exp(-0.41 * (t - 1.0)) * np.cos(7.3 * (t - 1.0) + 1.2)
    fit = fit_decaying_sinusoid(t, mode, 1.0)
    assert (fit.decay_rate, fit.omega) == (pytest.approx(0.41, rel=1e-9), pytest.approx(7.3, rel=1e-10))
    assert fit.amplitude == pytest.approx(0.03, rel=1e-9)
    assert wrap_phase(fit.phase - 1.2) == pytest.approx(0.0, abs=1e-9)
    other = 3e-4 * np.exp(-2.0 * (t - 1.0)) * np.cos(23.0 * t)
    fit = fit_decaying_sinusoid(t, mode + other, 1.0)
    assert (fit.decay_rate, fit.omega) == (pytest.approx(0.41, rel=1e-3), pytest.approx(7.3, rel=1e-3))


def test_decaying_sinusoid_fit_refuses_a_signal_without_oscillation():
    t = np.arange(0.0, 4.0, 0.01)
    with pytest.raises(ValueError, match="no oscillation"):
        fit_decaying_sinusoid(t, np.exp(-t) + np.exp(-3.0 * t), 0.0)


@pytest.mark.parametrize("fit", [fit_sinusoid, fit_decaying_sinusoid])
def test_sinusoid_fits_need_a_uniform_grid(fit):
    with pytest.raises(ValueError, match="uniform"):
        fit([0, 1, 3, 4, 5, 6, 7, 8, 9], np.zeros(9), 0.0)


@pytest.mark.parametrize("angle, wrapped", [(0.5, 0.5), (2 * math.pi + 0.5, 0.5), (-math.pi, math.pi),
                                            (3 * math.pi / 2, -math.pi / 2)])
def test_wrap_phase(angle, wrapped):
    assert wrap_phase(angle) == pytest.approx(wrapped)


def test_settling_time_is_the_last_exit_from_the_band_after_t0():
    t = np.linspace(0.0, 10.0, 10001)
    decay = np.exp(-t) * np.cos(20.0 * t)
    # |x| <= exp(-t) leaves the 5 % band of its peak (1, at t = 0) for good before ln 20
    settled = settling_time(t, decay, 1.0, 0.05)
    assert 0.0 < settled < math.log(20.0) - 1.0
    assert abs(decay[t > 1.0 + settled]).max() <= 0.05
    assert abs(decay[(t > 1.0) & (t <= 1.0 + settled)]).max() > 0.05
    assert settling_time(t, decay, 5.0, 0.05) == 0.0  # inside the band at t0 already
    assert math.isnan(settling_time(t, np.cos(t), 1.0, 0.05))  # never settles


def test_residual_after_a_shaped_command_starts_at_its_delayed_end():
    t = np.arange(0.0, 10.0, 0.5)
    x = np.where(t > 5.0, 0.1, 3.0) * np.cos(np.pi * t)  # cos(pi t) = +-1 on this grid
    assert shaped_residual_amplitude(t, x, 4.0, 1.0) == pytest.approx(0.1)
    assert shaped_residual_amplitude(t, x, 4.0, 0.0) == pytest.approx(3.0)


def test_move_time_penalty_of_two_decaying_responses():
    """Two envelopes ``a exp(-t)`` on a fast carrier: each settles into the tolerance ``band *
    peak(unshaped)`` about when its envelope reaches it, at ``ln(a / tolerance)``."""
    t = np.linspace(0.0, 10.0, 100001)
    carrier = np.cos(200.0 * t)
    unshaped = np.exp(-t) * carrier
    shaped = 0.1 * np.exp(-(t - 1.0)) * carrier * (t >= 1.0)  # ten times less, one second later
    penalty = move_time_penalty(t, shaped, unshaped, 1.0, band=0.05)
    assert penalty.shaper_duration == 1.0
    # the last exit lies within one carrier period (pi / 100 s) before the envelope's crossing
    assert penalty.settling_unshaped == pytest.approx(math.log(20.0), abs=math.pi / 100)
    assert penalty.settling_shaped == pytest.approx(1.0 + math.log(0.1 * 20.0), abs=math.pi / 100)
    assert penalty.settling_difference == pytest.approx(1.0 + math.log(0.1), abs=2 * math.pi / 100)
    assert penalty.settling_difference < 0.0  # the shaped move settles sooner despite its delay
    assert settled_after(t, unshaped, 0.0, 0.05) == settling_time(t, unshaped, 0.0, 0.05)
