"""Command shapers (hubbeam.model.shapers) on linear oscillators, where everything is known.

* Closed forms of the undamped curves (Singer & Seering 1990): ZV leaves ``|cos(pi r / 2)|`` of
  the vibration at the frequency ratio ``r``, 15.6 % at ``r = 0.9``; ZVD its square, 2.45 %; EI
  (Singhose et al. 1994) ``|(1 - V) / 2 + (1 + V) / 2 cos(pi r)|``, equal to ``V`` at ``r = 1``.
  Their bands ``V <= 5 %`` follow from these by hand: ZV ``r in 1 +- (1 - 2 acos(0.05) / pi)``,
  ZVD ``1 +- (1 - 2 acos(sqrt(0.05)) / pi)``, EI ``cos(pi r) <= (3 V - 1) / (1 + V)``.
* ZV and ZVD leave nothing at the design frequency, damped too; EI leaves exactly ``V_tol``,
  and no more anywhere in its band, damped too; its damped amplitudes are those of the published
  curve fits Klipper's input shaper uses, within their accuracy.
* The closed form ``V`` against a direct simulation (scipy) of the shaped step on the oscillator:
  the residual's amplitude, read from the state after the last impulse, relative to the unshaped
  step's.
* Two modes (a two-mass chain): the convolution of one ZV per mode leaves neither; one ZV for the
  first leaves the second its closed-form share.
* Rounding to a sample time: the simulated residual is the closed form at the rounded times, and
  it is at most ``omega Ts / 2`` (each impulse moved by at most half a sample).
"""

import math

import numpy as np
import pytest
import scipy.linalg
import scipy.optimize
from scipy.integrate import solve_ivp

from hubbeam.core.inputs import IDENTITY_SHAPER
from hubbeam.model.shapers import (
    EI_MAX_V_TOL,
    EI_MAX_ZETA,
    IDENTITY,
    Shaper,
    check_sampling,
    convolve,
    ei,
    insensitive_band,
    insensitivity,
    multi_mode,
    residual_vibration,
    rounded,
    shaped_stops,
    zv,
    zvd,
)

OMEGA = 2.9  # rad s-1, about the first bending mode of the paper's beam
#: the integration of the oscillators (rtol 1e-11) leaves errors far below this on amplitudes of 1
SIMULATED = 1e-8


def test_amplitudes_sum_to_one_and_times_start_at_zero():
    for shaper in (zv(OMEGA), zvd(OMEGA, 0.1), ei(OMEGA), ei(OMEGA, 0.2, 0.1),
                   multi_mode([(OMEGA, 0.01), (18.0, 0.02)], "ZVD")):
        assert shaper.times[0] == 0.0 and np.all(np.diff(shaper.times) > 0.0)
        assert math.fsum(shaper.amplitudes) == pytest.approx(1.0, abs=1e-14)
        assert np.all(shaper.amplitudes > 0.0)
        assert shaper.duration == shaper.times[-1]
        assert shaper.kernel_array().shape == (2, shaper.times.size)


def test_undamped_curves_are_the_closed_forms():
    ratios = np.linspace(0.3, 1.7, 141)
    v = 0.05
    cases = {zv(OMEGA): np.abs(np.cos(np.pi * ratios / 2)),
             zvd(OMEGA): np.cos(np.pi * ratios / 2) ** 2,
             ei(OMEGA, 0.0, v): np.abs((1 - v) / 2 + (1 + v) / 2 * np.cos(np.pi * ratios))}
    for shaper, expected in cases.items():
        np.testing.assert_allclose(insensitivity(shaper, OMEGA, 0.0, ratios)[1], expected,
                                   rtol=0, atol=1e-14)
    # at 90 % of the design frequency: cos(0.45 pi) = 0.1564 and its square
    assert residual_vibration(zv(OMEGA), 0.9 * OMEGA) == pytest.approx(0.156434, abs=1e-6)
    assert residual_vibration(zvd(OMEGA), 0.9 * OMEGA) == pytest.approx(0.024472, abs=1e-6)


def test_insensitive_bands_of_the_undamped_shapers():
    zv_half = 1 - 2 * math.acos(0.05) / math.pi
    zvd_half = 1 - 2 * math.acos(math.sqrt(0.05)) / math.pi
    ei_half = 1 - math.acos((3 * 0.05 - 1) / (1 + 0.05)) / math.pi
    for shaper, half in ((zv(OMEGA), zv_half), (zvd(OMEGA), zvd_half), (ei(OMEGA), ei_half)):
        low, high = insensitive_band(shaper, OMEGA, 0.0, 0.05)
        assert (low, high) == pytest.approx((1 - half, 1 + half), abs=1e-10)
    # widths 0.064, 0.287, 0.399: EI tolerates the widest error
    assert zv_half < zvd_half < ei_half


@pytest.mark.parametrize("zeta", [0.0, 0.02, 0.1, 0.3])
def test_zv_and_zvd_leave_nothing_at_the_design_frequency(zeta):
    for design in (zv, zvd):
        assert residual_vibration(design(OMEGA, zeta), OMEGA, zeta) < 1e-15
    # ZVD's curve is flat there: a 1 % frequency error leaves second-order residual
    assert residual_vibration(zvd(OMEGA, zeta), 1.01 * OMEGA, zeta) < 1e-3


@pytest.mark.parametrize("zeta", [0.0, 0.05, 0.2, EI_MAX_ZETA])
@pytest.mark.parametrize("v_tol", [0.02, 0.05, EI_MAX_V_TOL])
def test_ei_leaves_v_tol_at_the_design_frequency_and_no_more_over_its_band(zeta, v_tol):
    shaper = ei(OMEGA, zeta, v_tol)
    assert residual_vibration(shaper, OMEGA, zeta) == pytest.approx(v_tol, abs=1e-12)
    low, high = insensitive_band(shaper, OMEGA, zeta, v_tol)
    # wider than ZVD's band at the same tolerance
    zvd_low, zvd_high = insensitive_band(zvd(OMEGA, zeta), OMEGA, zeta, v_tol)
    assert low < zvd_low and high >= zvd_high
    if math.isinf(high):  # heavily damped: V tends to the last amplitude, below v_tol
        assert zeta == EI_MAX_ZETA and v_tol == EI_MAX_V_TOL
        high = 3.0
    inside = np.linspace(low, high, 4001)[1:-1]  # the edges are where V reaches v_tol
    assert np.max(insensitivity(shaper, OMEGA, zeta, inside)[1]) <= v_tol + 1e-12
    # a zero inside the band on each side of the design frequency
    for side in ((low, 1.0), (1.0, high)):
        least = scipy.optimize.minimize_scalar(lambda r: residual_vibration(shaper, r * OMEGA, zeta),
                                               bounds=side, method="bounded", options={"xatol": 1e-12})
        # bounded Brent finds the kink of |V| to about sqrt(eps) of the ratio; |dV/dr| < 2 pi
        assert least.fun < 1e-6


def _klipper_ei(zeta, v_tol=0.05):
    """The damped EI shaper of the polynomial curve fits in ``zeta`` that Klipper's input shaper
    uses (``klippy/extras/shaper_defs.py``, ``get_ei_shaper``; the last impulse held at ``T_d``),
    for a unit frequency: ``(amplitudes, times)``."""
    a1 = 0.24968 + 0.24961 * v_tol + (0.80008 + 1.23328 * v_tol + (0.49599 + 3.17316 * v_tol) * zeta) * zeta
    a3 = 0.25149 + 0.21474 * v_tol + (-0.83249 + 1.41498 * v_tol + (0.85181 - 4.90094 * v_tol) * zeta) * zeta
    t2 = 0.4999 + ((0.46159 + 8.57843 * v_tol) * v_tol + ((4.26169 - 108.644 * v_tol) * v_tol
                                                          + (1.75601 + 336.989 * v_tol) * v_tol * zeta) * zeta) * zeta
    period = 2 * math.pi / math.sqrt(1 - zeta**2)
    return np.array([a1, 1 - a1 - a3, a3]), np.array([0.0, t2 * period, period])


@pytest.mark.parametrize("zeta", [0.02, 0.05, 0.1, 0.2])
def test_damped_ei_amplitudes_agree_with_published_curve_fits(zeta):
    """Within the fits' accuracy: their own residual at the design frequency misses 5 % by up to
    1.2e-3 (measured over these damping ratios), so amplitudes within 1e-3."""
    amplitudes, times = _klipper_ei(zeta)
    fitted = Shaper(times, amplitudes / amplitudes.sum())
    assert abs(residual_vibration(fitted, 1.0, zeta) - 0.05) < 1.2e-3
    np.testing.assert_allclose(ei(1.0, zeta).amplitudes, amplitudes, atol=1e-3)


def _oscillator_step_response(shaper, omega, zeta, extra=0.0):
    """The state ``(x, x')`` of ``x'' + 2 zeta omega x' + omega^2 x = omega^2 u`` from rest under
    the shaped unit step ``u = sum_i A_i H(t - t_i)``, at the last impulse plus ``extra``."""
    def rhs(t, z, u):
        return [z[1], omega**2 * (u - z[0]) - 2 * zeta * omega * z[1]]

    edges = [*shaper.times, shaper.duration + extra]
    z, u = np.zeros(2), 0.0
    for k, amplitude in enumerate(shaper.amplitudes):
        u += amplitude
        if edges[k + 1] > edges[k]:
            z = solve_ivp(rhs, (edges[k], edges[k + 1]), z, args=(u,), method="DOP853",
                          rtol=1e-11, atol=1e-13).y[:, -1]
    return z


def simulated_residual(shaper, omega, zeta):
    """The residual after the shaped step relative to the unshaped one's, from the simulated
    state at the last impulse: the error ``e = x - 1`` is ``exp(-sigma s) (a cos(wd s) + b
    sin(wd s))`` after it, amplitude ``hypot(a, b)``; the unshaped step's is ``1 / sqrt(1 -
    zeta^2)`` (``a = -1``, ``b = -zeta / sqrt(1 - zeta^2)``)."""
    x, v = _oscillator_step_response(shaper, omega, zeta)
    wd = omega * math.sqrt(1 - zeta**2)
    a = x - 1.0
    b = (v + zeta * omega * a) / wd
    return math.hypot(a, b) * math.sqrt(1 - zeta**2)


@pytest.mark.parametrize("zeta", [0.0, 0.05, 0.2])
@pytest.mark.parametrize("ratio", [0.8, 0.9, 1.0, 1.15])
def test_closed_form_against_the_simulated_shaped_step(zeta, ratio):
    for shaper in (zv(OMEGA, zeta), zvd(OMEGA, zeta), ei(OMEGA, zeta)):
        omega = ratio * OMEGA
        assert simulated_residual(shaper, omega, zeta) == pytest.approx(
            residual_vibration(shaper, omega, zeta), abs=SIMULATED)


def _chain():
    """A two-mass chain on a moving base (masses 1 and 0.5 kg, springs 40 and 30 N/m): ``M x'' +
    K x = k1 e1 u``; its natural frequencies and mass-normalised modes."""
    M = np.diag([1.0, 0.5])
    K = np.array([[70.0, -30.0], [-30.0, 30.0]])
    squares, modes = scipy.linalg.eigh(K, M)
    return M, K, np.sqrt(squares), modes


def _chain_residuals(shaper):
    """The modal amplitudes ``hypot(eta_j, eta_j' / omega_j)`` of the two-mass chain after the
    shaped unit step of its base, about the static position ``x = (1, 1)``."""
    M, K, omegas, modes = _chain()
    force = np.array([40.0, 0.0])

    def rhs(t, z, u):
        return np.concatenate([z[2:], np.linalg.solve(M, force * u - K @ z[:2])])

    z, u = np.zeros(4), 0.0
    edges = [*shaper.times, shaper.duration]
    for k, amplitude in enumerate(shaper.amplitudes):
        u += amplitude
        if edges[k + 1] > edges[k]:
            z = solve_ivp(rhs, (edges[k], edges[k + 1]), z, args=(u,), method="DOP853",
                          rtol=1e-11, atol=1e-13).y[:, -1]
    eta = modes.T @ M @ (z[:2] - 1.0)
    rate = modes.T @ M @ z[2:]
    return np.hypot(eta, rate / omegas), omegas


def test_multi_mode_shaper_cancels_both_modes_of_a_two_mode_oscillator():
    unshaped, omegas = _chain_residuals(IDENTITY)
    both = multi_mode([(omegas[0], 0.0), (omegas[1], 0.0)], "ZV")
    assert both.name == "ZV*ZV" and both.times.size == 4
    np.testing.assert_allclose(_chain_residuals(both)[0], 0.0, atol=SIMULATED)
    # one ZV on the first mode leaves the second its closed-form share
    first = zv(omegas[0])
    left = _chain_residuals(first)[0]
    assert left[0] == pytest.approx(0.0, abs=SIMULATED)
    assert left[1] == pytest.approx(unshaped[1] * residual_vibration(first, omegas[1]),
                                    abs=SIMULATED)
    # the convolution's curve is the product of its factors' curves
    w = np.linspace(2.0, 15.0, 27)
    np.testing.assert_allclose(residual_vibration(both, w),
                               residual_vibration(zv(omegas[0]), w) * residual_vibration(zv(omegas[1]), w),
                               atol=1e-14)


@pytest.mark.parametrize("design", [zv, zvd])
@pytest.mark.parametrize("zeta", [0.0, 0.05])
def test_rounded_shaper_leaves_its_closed_form_at_the_rounded_times(design, zeta):
    shaper = design(OMEGA, zeta)
    for sample_time in (0.2, 0.1, 0.05, 0.013):
        sampled = rounded(shaper, sample_time)
        steps = sampled.times / sample_time
        np.testing.assert_allclose(steps, np.round(steps), atol=1e-9)
        assert np.all(np.abs(sampled.times - shaper.times) <= sample_time / 2 + 1e-12)
        np.testing.assert_array_equal(sampled.amplitudes, shaper.amplitudes)  # kept
        predicted = residual_vibration(sampled, OMEGA, zeta)
        assert simulated_residual(sampled, OMEGA, zeta) == pytest.approx(predicted, abs=SIMULATED)
        if zeta == 0.0:  # |sum A_i exp(i w t_i) (exp(i w d_i) - 1)| <= w max |d_i|
            assert predicted <= OMEGA * sample_time / 2


def test_rounding_merges_impulses_on_one_sample():
    shaper = zvd(OMEGA)
    merged = rounded(shaper, shaper.duration)  # the middle impulse rounds up onto the last one
    np.testing.assert_allclose(merged.times, [0.0, shaper.duration])
    np.testing.assert_allclose(merged.amplitudes, [0.25, 0.75])


def test_convolution_merges_coinciding_impulses():
    one = zv(OMEGA)
    twice = convolve(one, one)  # ZV * ZV is ZVD (undamped)
    np.testing.assert_allclose(twice.times, zvd(OMEGA).times, rtol=1e-15)
    np.testing.assert_allclose(twice.amplitudes, zvd(OMEGA).amplitudes, rtol=1e-15)


def test_sampling_above_half_the_sampling_frequency_is_refused():
    shaper = multi_mode([(OMEGA, 0.0), (30.0, 0.1)])
    limit = math.pi / (30.0 * math.sqrt(1 - 0.01))  # the second mode's half damped period
    check_sampling(shaper, 0.999 * limit)
    with pytest.raises(ValueError, match="mode 2"):
        check_sampling(shaper, 1.001 * limit)
    with pytest.raises(ValueError, match=r"mode 2 .* 29\.8496 rad s-1.* sample_time = 0\.11 s"):
        check_sampling(shaper, 0.11)
    with pytest.raises(ValueError, match="sample_time = 0"):
        check_sampling(shaper, 0)


def test_shaped_stops_shift_the_start_and_every_stop_by_every_impulse():
    shaper = Shaper([0.0, 1.0, 2.5], [0.25, 0.5, 0.25])
    np.testing.assert_array_equal(shaped_stops([1.5, 4.0], shaper),
                                  [0.0, 1.0, 1.5, 2.5, 4.0, 5.0, 6.5])
    np.testing.assert_array_equal(shaped_stops([1.5, 4.0], IDENTITY), [0.0, 1.5, 4.0])


@pytest.mark.parametrize("call, message", [
    (lambda: zv(-1.0), "zv: omega = -1.0"),
    (lambda: zvd(OMEGA, 1.0), "zvd: zeta = 1.0"),
    (lambda: ei(OMEGA, 0.5), f"ei: zeta = 0.5; allowed: 0 <= zeta <= {EI_MAX_ZETA}"),
    (lambda: ei(OMEGA, 0.0, 0.0), "ei: v_tol = 0.0"),
    (lambda: Shaper([0.0, 1.0], [0.5, 0.6]), "sum 1.1"),
    (lambda: Shaper([0.1, 1.0], [0.5, 0.5]), r"times = \[0.1, 1.0\]"),
    (lambda: multi_mode([(OMEGA, 0.0)], "ZVDD"), "design = 'ZVDD'"),
    (lambda: rounded(zv(OMEGA), -0.1), "sample_time = -0.1"),
    (lambda: residual_vibration(zv(OMEGA), [1.0, np.nan]), "omega = "),
    (lambda: insensitive_band(ei(OMEGA), OMEGA, 0.0, 0.01), "tolerance = 0.01"),
])
def test_bad_input_is_refused_naming_it(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_the_identity_is_one_unit_impulse_at_zero():
    assert IDENTITY.times.tolist() == [0.0] and IDENTITY.amplitudes.tolist() == [1.0]
    np.testing.assert_array_equal(IDENTITY.kernel_array(), IDENTITY_SHAPER)  # the kernels' default
    assert residual_vibration(IDENTITY, OMEGA, 0.1) == 1.0
