"""Signal measures of a simulated response, on plain numpy arrays (one place for every product).

The claims of the reproduction report, Table 3, the Exudyn comparison and the figures use these
definitions; they are documented in the report:

- peak: ``max |x(t)|`` over the run, NaN samples (after a divergence) ignored;
- residual vibration: the response for ``t > t_f``, after the spin-up of Eq. 43 or the torque
  pulse of Eq. 44; its amplitude is ``max |x(t)|`` over ``t > t_f``; after a shaped command
  (``hubbeam.model.shapers``), which ends the shaper's duration later, over ``t > t_f + D``;
- fitted sinusoid: least-squares fit of ``c + A cos(omega (t - t_0) + phi)``; ``omega`` starts at
  the peak of the Hann-windowed, zero-padded spectrum and is refined by minimising the fit
  residual within one spectral bin; ``phi`` is the phase at ``t = t_0``;
- fitted decaying sinusoid: least-squares fit of ``A exp(-sigma (t - t_0)) cos(omega (t - t_0) + phi)``
  (a single mode decaying to zero); ``sigma`` and ``omega`` start at the root of the two-term
  linear prediction ``y_{k+2} = a_1 y_{k+1} + a_2 y_k`` (Prony's method, exact for one such mode)
  and are refined by minimising the residual with ``A`` and ``phi`` eliminated (variable
  projection);
- settling time: from ``t_0`` until ``|x|`` stays within a band (a fraction of its peak, or a
  given tolerance) to the end of the record; 0 when it already does at ``t_0``, NaN when it never
  does before the end;
- move-time penalty of a shaped command: the shaper's duration ``D`` (the command ends that much
  later) and the change of the settling time from the start of the move, both responses held to
  the same tolerance (a fraction of the unshaped response's peak);
- phase lead of ``a`` over ``b``: ``phi_a - phi_b`` wrapped to (-pi, pi] (positive: ``a`` leads);
- relative difference of two curves: ``max |x_a - x_b| / max |x_b|`` on a common time grid.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.optimize


def peak(values) -> float:
    """``max |x|`` ignoring NaN (samples after a divergence)."""
    return float(np.nanmax(np.abs(np.asarray(values, dtype=float))))


def peak_time(time, values) -> float:
    """The first time at which ``|x|`` reaches its peak (non-finite samples ignored)."""
    magnitude = np.abs(np.asarray(values, dtype=float))
    index = int(np.argmax(np.where(np.isfinite(magnitude), magnitude, -np.inf)))
    return float(np.asarray(time)[index])


def after(time, values, t0: float) -> tuple[np.ndarray, np.ndarray]:
    """Times and values for ``t > t0`` (the residual window), finite samples only."""
    time = np.asarray(time)
    values = np.asarray(values, dtype=float)
    keep = (time > t0) & np.isfinite(values)
    return time[keep], values[keep]


def residual_amplitude(time, values, t0: float) -> float:
    """Residual vibration amplitude ``max |x(t)|`` over ``t > t0``; NaN without a finite sample."""
    window = after(time, values, t0)[1]
    return peak(window) if window.size else math.nan


def shaped_residual_amplitude(time, values, command_end: float, shaper_duration: float) -> float:
    """Residual vibration amplitude after a shaped command: ``max |x(t)|`` over ``t > command_end
    + shaper_duration`` (the unshaped command's end delayed by the shaper's last impulse)."""
    return residual_amplitude(time, values, command_end + shaper_duration)


def settled_after(time, values, t0: float, tolerance: float) -> float:
    """Time after ``t0`` from which ``|x| <= tolerance`` to the end of the record: 0 when it is
    inside at ``t0`` already, NaN when its last sample is outside."""
    time = np.asarray(time)
    magnitude = np.abs(np.asarray(values, dtype=float))
    outside = np.flatnonzero(magnitude > tolerance)
    last = time[outside[-1]] if outside.size else t0
    return max(float(last) - t0, 0.0) if last < time[-1] else math.nan


def settling_time(time, values, t0: float, band: float) -> float:
    """Time after ``t0`` from which ``|x|`` stays within ``band`` times its peak to the end of the
    record (module docstring, :func:`settled_after`)."""
    return settled_after(time, values, t0, band * peak(values))


@dataclass(frozen=True)
class MoveTimePenalty:
    """What shaping a command costs in time: the shaper's duration (s) and the settling times
    (s, from the start of the move) of the shaped and the unshaped response."""

    shaper_duration: float
    settling_shaped: float
    settling_unshaped: float

    @property
    def settling_difference(self) -> float:
        """Settling time of the shaped response minus the unshaped one's (s; negative: the shaped
        move settles sooner despite its longer command)."""
        return self.settling_shaped - self.settling_unshaped


def move_time_penalty(time, shaped, unshaped, shaper_duration: float, band: float = 0.05) -> MoveTimePenalty:
    """The :class:`MoveTimePenalty` of a shaped response against the unshaped one (same time
    grid, the move starting at ``t = 0``): each settles once ``|x|`` stays within ``band`` times
    the unshaped response's peak."""
    tolerance = band * peak(unshaped)
    return MoveTimePenalty(float(shaper_duration), settled_after(time, shaped, 0.0, tolerance),
                           settled_after(time, unshaped, 0.0, tolerance))


def late_share(time, values, t0: float) -> float:
    """``max |x|`` over ``t > t0`` relative to ``max |x|`` over the whole run."""
    values = np.asarray(values, dtype=float)
    return peak(values[np.asarray(time) > t0]) / peak(values)


def relative_difference(a, b) -> float:
    """``max |a - b| / max |b|`` of two curves sampled on the same grid."""
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    return peak(a - b) / peak(b)


@dataclass(frozen=True)
class SinusoidFit:
    """``offset + amplitude * cos(omega * (t - t0) + phase)``."""

    amplitude: float
    omega: float
    phase: float
    offset: float
    t0: float


def _uniform(t, y, name: str):
    """``t`` and ``y`` as float arrays and the step of ``t``, which must be uniform."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    dt = np.diff(t)
    if len(t) < 8 or not np.allclose(dt, dt[0], rtol=1e-6, atol=0):
        raise ValueError(f"{name} needs at least 8 samples on a uniform time grid")
    return t, y, float(dt[0])


def _linear_fit(s, y, omega):
    basis = np.column_stack([np.ones_like(s), np.cos(omega * s), np.sin(omega * s)])
    coef, *_ = np.linalg.lstsq(basis, y, rcond=None)
    return coef, float(np.sum((basis @ coef - y) ** 2))


def fit_sinusoid(t, y, t0: float) -> SinusoidFit:
    """Least-squares sinusoid at the dominant frequency of ``y(t)`` (uniform ``t``), phase at ``t0``."""
    t, y, step = _uniform(t, y, "fit_sinusoid")
    s = t - t0
    pad = 8 * len(y)
    spectrum = np.abs(np.fft.rfft((y - y.mean()) * np.hanning(len(y)), pad))
    frequencies = np.fft.rfftfreq(pad, step)
    omega0 = 2 * np.pi * frequencies[1 + np.argmax(spectrum[1:])]
    half_width = 2 * np.pi / (len(y) * step)  # one bin of the unpadded spectrum
    best = scipy.optimize.minimize_scalar(
        lambda w: _linear_fit(s, y, w)[1], method="bounded",
        bounds=(max(omega0 - half_width, 1e-12), omega0 + half_width), options={"xatol": 1e-12})
    (c, a, b), _ = _linear_fit(s, y, best.x)
    # a cos + b sin = R cos(w s + phi) with R = hypot(a, b), phi = atan2(-b, a)
    return SinusoidFit(float(np.hypot(a, b)), float(best.x), float(np.arctan2(-b, a)), float(c), t0)


@dataclass(frozen=True)
class DecayingSinusoidFit:
    """``amplitude * exp(-decay_rate * (t - t0)) * cos(omega * (t - t0) + phase)``; the mode's
    pole is ``-decay_rate + 1j * omega``."""

    amplitude: float
    decay_rate: float
    omega: float
    phase: float
    t0: float


def _decaying_basis(s, sigma, omega):
    envelope = np.exp(-sigma * s)
    return np.column_stack([envelope * np.cos(omega * s), envelope * np.sin(omega * s)])


def _prony_pole(y, dt) -> complex:
    """The pole of the two-term linear prediction of ``y`` (upper half plane); ValueError where the
    prediction has no oscillating pole (real or zero roots)."""
    (a1, a2), *_ = np.linalg.lstsq(np.column_stack([y[1:-1], y[:-2]]), y[2:], rcond=None)
    z = np.roots([1.0, -a1, -a2]).astype(complex)
    with np.errstate(divide="ignore", invalid="ignore"):  # a zero root (a signal of zeros): no pole
        pole = np.log(z[np.argmax(z.imag)]) / dt
    if not (np.isfinite(pole) and pole.imag > 0.0):
        raise ValueError("fit_decaying_sinusoid found no oscillation in the signal (real poles)")
    return pole


def _dominant_omega(y, step) -> float:
    """The circular frequency of the highest peak of the spectrum of ``y`` (its mean removed, a
    Hann window, zero-padded eightfold); ValueError for a signal without one."""
    pad = 8 * len(y)
    spectrum = np.abs(np.fft.rfft((y - y.mean()) * np.hanning(len(y)), pad))
    omega = float(2 * np.pi * np.fft.rfftfreq(pad, step)[1 + np.argmax(spectrum[1:])])
    if not np.any(spectrum[1:] > 0.0) or omega < 2.0 * 2 * np.pi / (len(y) * step):
        raise ValueError("fit_decaying_sinusoid found no oscillation in the signal (no spectral peak of two "
                         "periods or more in the record)")
    return omega


def fit_decaying_sinusoid(t, y, t0: float) -> DecayingSinusoidFit:
    """Least-squares decaying sinusoid through ``y(t)`` (uniform ``t``), phase at ``t0``.

    Started from the two-term linear prediction's pole (Prony's method), or, where that finds no
    oscillation (a record of several modes, an offset, quantised readings), from the spectrum's
    highest peak with the decay of its envelope (:func:`envelope_growth_rate`); a ValueError when
    the signal is constant."""
    t, y, step = _uniform(t, y, "fit_decaying_sinusoid")
    s = t - t0
    try:
        pole = _prony_pole(y, step)
    except ValueError:
        rate = envelope_growth_rate(t, y - y.mean(), float(t[0]))
        pole = complex(rate if math.isfinite(rate) else 0.0, _dominant_omega(y, step))

    def residual(p):
        basis = _decaying_basis(s, *p)
        return basis @ np.linalg.lstsq(basis, y, rcond=None)[0] - y

    best = scipy.optimize.least_squares(residual, [-pole.real, pole.imag], x_scale=abs(pole),
                                        xtol=1e-14, ftol=1e-14, gtol=1e-14)
    sigma, omega = best.x
    (a, b), *_ = np.linalg.lstsq(_decaying_basis(s, sigma, omega), y, rcond=None)
    return DecayingSinusoidFit(float(np.hypot(a, b)), float(sigma), float(omega),
                               float(np.arctan2(-b, a)), t0)


def wrap_phase(angle: float) -> float:
    """Angle in (-pi, pi]."""
    wrapped = math.remainder(angle, 2 * math.pi)
    return math.pi if wrapped == -math.pi else wrapped


def phase_lead(a: SinusoidFit, b: SinusoidFit) -> float:
    """Phase of ``a`` minus phase of ``b``, wrapped to (-pi, pi]; positive when ``a`` leads."""
    return wrap_phase(a.phase - b.phase)


def envelope_growth_rate(time, values, t0: float, windows: int = 12, floor: float = 1e-6,
                         limit: float = math.inf) -> float:
    """The growth rate (s-1; negative: decay) of the envelope of ``x(t)`` after ``t0``: the
    least-squares slope of ``ln max |x|`` over ``windows`` equal windows of ``(t0, t_end]`` against
    the time of each window's maximum. Windows are left out from the first one whose maximum
    reaches ``limit`` (a saturated command) or falls below ``floor`` times the first window's
    (the rounding floor of a decayed signal); NaN with fewer than two windows left. For a loop
    whose least stable mode ``z`` dominates the record, the rate tends to ``ln |z| / Ts``."""
    time = np.asarray(time, dtype=float)
    magnitude = np.abs(np.asarray(values, dtype=float))
    keep = (time > t0) & np.isfinite(magnitude)
    time, magnitude = time[keep], magnitude[keep]
    if time.size < 2 * windows:
        return math.nan
    found_t, found_log = [], []
    for part_t, part in zip(np.array_split(time, windows), np.array_split(magnitude, windows)):
        top = float(part.max())
        if top >= limit or (found_log and top < floor * math.exp(found_log[0])) or top == 0.0:
            break
        found_t.append(float(part_t[int(np.argmax(part))]))
        found_log.append(math.log(top))
    if len(found_t) < 2:
        return math.nan
    return float(np.polyfit(found_t, found_log, 1)[0])
