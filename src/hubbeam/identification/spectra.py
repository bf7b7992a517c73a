"""From a time series to the other two kinds: a frequency response (H1) and a free decay's mode.

**H1 estimate.** :func:`frequency_response_estimate` divides the averaged cross spectrum of the
input ``u`` and a measured output ``y`` by the input's auto spectrum, ``H1 = S_uy / S_uu``, and gives
the coherence ``gamma^2 = |S_uy|^2 / (S_uu S_yy)`` (Welch's segment averaging,
``scipy.signal.csd`` / ``welch``, a Hann window and half-overlapping segments by default; Bendat and
Piersol, *Random Data*, 2010, Sec. 9.2). H1 is unbiased by noise on the output, which the rig's
sensors add; noise on the input, or a loop that feeds the output's noise back into the input,
biases it, so an experiment taken inside a loop is refused (fit its time series instead). The
estimate is of the response from the input's samples, so it holds the input's hold (recorded in
the estimate, ``FrequencyResponse.hold``, and predicted with it). The
reading is turned back into the physical signal by the sensor's gain (the offset is removed with
each segment's mean). The number of averages the standard error needs
(``FrequencyResponse.standard_error``) is the equivalent number of independent segments: ``K``
segments overlapping with the window's correlation ``c_j`` at a shift of ``j`` segments count as
``K / (1 + 2 sum_j (1 - j/K) c_j^2)`` (Welch 1967, Eq. 10; 1.06 for a Hann window at half
overlap).

**Free decay.** :func:`free_decay` measures the frequency and damping of a free oscillation (the
courseware's test: the link deflected and released with the hub held) from its extrema: each
maximum and minimum refined by a parabola through its three samples, the half-periods averaged
into the damped frequency ``omega_d``, and the logarithm of the peak-to-peak amplitude between
successive extrema fitted by a straight line in time, whose slope is ``-sigma``. Then ``zeta =
sigma / sqrt(sigma^2 + omega_d^2)``, the natural frequency ``sqrt(sigma^2 + omega_d^2)`` and the
logarithmic decrement ``delta = 2 pi sigma / omega_d`` (Inman, *Engineering Vibration*, 4th ed.,
Sec. 1.8). Peak-to-peak amplitudes need no zero level (an offset cancels) and the fit uses every
half cycle above ``floor`` of the first amplitude (noise and quantisation dominate below).
:func:`decay_modal_test` makes the result a one-mode :class:`~hubbeam.identification.experiments.ModalTest`.
"""

from __future__ import annotations

import dataclasses
import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.signal

from hubbeam.identification.experiments import MIN_ROWS, SIGNALS, FrequencyResponse, ModalTest, TimeSeries
from hubbeam.identification.files import (
    ColumnSpec,
    ExperimentError,
    check_increasing,
    read_columns,
    uniform_step,
)
from hubbeam.linear.statespace import OUTPUTS


def equivalent_averages(window: np.ndarray, step: int, segments: int) -> float:
    """The equivalent number of independent averages of ``segments`` segments of ``window``
    starting every ``step`` samples (module docstring)."""
    energy = float(window @ window)
    total = 1.0
    for j in range(1, segments):
        shift = j * step
        if shift >= window.size:
            break
        c = float(window[shift:] @ window[:-shift]) / energy
        total += 2.0 * (1.0 - j / segments) * c * c
    return segments / total


def frequency_response_estimate(series: TimeSeries, output: str, segment: int, *, overlap: float = 0.5,
                                window: str = "hann", band: tuple[float, float] | None = None,
                                name: str | None = None, skip: int = 0) -> FrequencyResponse:
    """The H1 estimate of the response from ``series``'s input to ``output`` with its coherence,
    over segments of ``segment`` samples overlapping by ``overlap`` (module docstring), at the
    frequencies of ``band`` (Hz, default every one above 0 Hz), the first ``skip`` samples left out
    (a transient). A periodic input whose period is the segment (:func:`periodic_chirp`), measured
    after its transient with ``window="boxcar"`` and no overlap, has no leakage: every line of the
    estimate is a line the input excites."""
    if series.loop is not None:
        raise ValueError(f"experiment {series.name}: taken inside a loop; allowed: an open-loop experiment "
                         "(in a loop the measurement noise reaches the input and biases H1: fit the time series)")
    if output not in series.signals:
        raise ValueError(f"output = {output!r}; allowed: a signal of experiment {series.name}: "
                         f"{', '.join(series.signals)}")
    if not (isinstance(segment, int) and 8 <= segment <= series.time.size):
        raise ValueError(f"segment = {segment!r}; allowed: a whole number of samples in 8..{series.time.size}")
    if not 0.0 <= overlap < 1.0:
        raise ValueError(f"overlap = {overlap!r}; allowed: a fraction in [0, 1)")
    if not (isinstance(skip, int) and 0 <= skip <= series.time.size - segment):
        raise ValueError(f"skip = {skip!r}; allowed: a whole number of samples in 0..{series.time.size - segment}")
    fs = 1.0 / series.step
    u = series.command[skip:]
    y = series.signals[output][skip:] / series.sensors[output].gain
    overlapped = int(round(overlap * segment))
    options = {"fs": fs, "window": window, "nperseg": segment, "noverlap": overlapped, "detrend": "constant"}
    frequency, s_uy = scipy.signal.csd(u, y, **options)
    s_uu = scipy.signal.welch(u, **options)[1]
    s_yy = scipy.signal.welch(y, **options)[1]
    low, high = band if band is not None else (0.0, math.inf)
    keep = (frequency > 0.0) & (frequency >= low) & (frequency <= high) & (s_uu > 0.0)
    step = segment - overlapped
    segments = 1 + (u.size - segment) // step
    averages = equivalent_averages(scipy.signal.get_window(window, segment), step, segments)
    coherence = np.clip(np.abs(s_uy[keep]) ** 2 / (s_uu[keep] * s_yy[keep]), 0.0, 1.0)
    return FrequencyResponse(name=name or f"{series.name}_{output}", input=series.input, output=output,
                             frequency=frequency[keep], response=s_uy[keep] / s_uu[keep], coherence=coherence,
                             averages=averages, hold=series.hold, sample_time=series.step,
                             source=f"H1 of {series.name} ({series.source})")


def periodic_chirp(segment: int, periods: int, step: float, start: float, stop: float, amplitude: float):
    """``(time, command)``: ``periods`` repetitions of a linear sweep from ``start`` to ``stop`` Hz
    lasting ``segment`` samples of ``step`` s, periodic to the sample (both ends moved to lines
    ``k / T`` of the period ``T``, ``k`` apart by an even number, so that the phase returns to a whole
    turn): a swept sine whose every period excites the lines of one segment."""
    period = segment * step
    low, high = max(1, round(start * period)), round(stop * period)
    high += (high - low) % 2
    t = np.arange(segment * periods) * step
    local = t % period
    phase = 2.0 * math.pi * (low * local / period + (high - low) * local**2 / (2.0 * period**2))
    return t, amplitude * np.sin(phase)


@dataclass(frozen=True, eq=False)
class Decay:
    """A free decay (module docstring): ``frequency`` (natural, Hz), ``damped_frequency`` (Hz),
    ``damping_ratio``, ``log_decrement``, the extrema used (``times`` s, ``values``) and the
    standard errors of the damping ratio and frequency from the line fit and the half-periods."""

    frequency: float
    damped_frequency: float
    damping_ratio: float
    log_decrement: float
    damping_ratio_std: float
    frequency_std: float
    times: np.ndarray
    values: np.ndarray


def _extrema(t: np.ndarray, y: np.ndarray, prominence: float):
    """Every maximum and minimum of ``y`` by prominence, refined by a parabola through its samples."""
    found = []
    for sign in (1.0, -1.0):
        index = scipy.signal.find_peaks(sign * y, prominence=prominence)[0]
        index = index[(index > 0) & (index < y.size - 1)]
        left, mid, right = y[index - 1], y[index], y[index + 1]
        curvature = left - 2.0 * mid + right
        shift = np.where(curvature != 0.0, 0.5 * (left - right) / np.where(curvature != 0.0, curvature, 1.0), 0.0)
        h = t[1] - t[0]
        found += list(zip(t[index] + shift * h, mid - 0.25 * (left - right) * shift, [sign] * index.size))
    found.sort()
    times, values, signs = (np.array(column) for column in zip(*found)) if found else (np.empty(0),) * 3
    alternating = np.concatenate([[True], signs[1:] != signs[:-1]]) if signs.size else signs.astype(bool)
    return times[alternating], values[alternating]


def free_decay(time, signal, floor: float = 0.05, prominence: float | None = None,
               lowpass: float | None = None) -> Decay:
    """The :class:`Decay` of a free oscillation sampled at equally spaced ``time`` (module
    docstring): half cycles down to ``floor`` of the first peak-to-peak amplitude; extrema of at
    least ``prominence`` (default half of ``floor`` times the signal's range, above the noise of a
    sensor that resolves the oscillation). ``lowpass``
    (Hz): first remove the higher modes with a fourth-order Butterworth filter run forward and
    backward (no phase shift, and a constant gain at the mode's frequency, which leaves its decay
    rate as it was), its cut-off between the first mode and the second."""
    t = np.asarray(time, dtype=float)
    y = np.asarray(signal, dtype=float)
    if t.shape != y.shape or t.size < 8 or not np.all(np.isfinite(y)):
        raise ValueError("time, signal: finite samples of one length (at least 8); allowed: a free oscillation")
    if lowpass is not None:
        nyquist = 0.5 / (t[1] - t[0])
        if not 0.0 < lowpass < nyquist:
            raise ValueError(f"lowpass = {lowpass!r}; allowed: a cut-off in (0, {nyquist:g}) Hz")
        y = scipy.signal.sosfiltfilt(scipy.signal.butter(4, lowpass, fs=2.0 * nyquist, output="sos"), y - y.mean())
    prominence = 0.5 * floor * np.ptp(y) if prominence is None else prominence
    times, values = _extrema(t, y, prominence)
    amplitude = np.abs(np.diff(values))
    above = amplitude >= floor * amplitude[0] if amplitude.size else amplitude.astype(bool)
    count = int(np.argmin(above)) if not above.all() else amplitude.size
    if count < 4:
        raise ValueError(f"{count} half cycles above {floor:g} of the first; allowed: a free oscillation with at "
                         "least 4 (a longer record, a lower floor)")
    middle = 0.5 * (times[1:count + 1] + times[:count])
    fitted, covariance = np.polyfit(middle, np.log(amplitude[:count]), 1, cov=True)
    sigma = -fitted[0]
    halves = np.diff(times[:count + 1])
    omega_d = math.pi / halves.mean()
    omega_d_std = math.pi * halves.std(ddof=1) / math.sqrt(halves.size) / halves.mean() ** 2
    omega = math.hypot(sigma, omega_d)
    zeta = sigma / omega
    return Decay(frequency=omega / (2.0 * math.pi), damped_frequency=omega_d / (2.0 * math.pi), damping_ratio=zeta,
                 log_decrement=2.0 * math.pi * sigma / omega_d,
                 damping_ratio_std=math.sqrt(covariance[0, 0]) / omega,
                 frequency_std=max(omega_d_std, 1e-12) / (2.0 * math.pi),
                 times=times[:count + 1], values=values[:count + 1])


def read_free_decay(path: os.PathLike | str, name: str | None = None, hub: str = "held",
                    lowpass: float | None = None) -> ModalTest:
    """The one-mode :class:`ModalTest` of a free oscillation recorded in the file ``path`` (columns
    ``time [s]``, equally spaced, and one measured signal in its unit): its logarithmic decrement
    (:func:`free_decay`, ``lowpass`` its cut-off in Hz), the courseware's way to the link's first
    frequency and damping ratio with the hub ``held``."""
    columns = [ColumnSpec("time", ("s",)), *(ColumnSpec(signal, (OUTPUTS[signal][0],), False) for signal in SIGNALS)]
    table = read_columns(path, columns, MIN_ROWS["time_series"], "a free oscillation")
    check_increasing(table, "time")
    uniform_step(table, "time")
    found = [signal for signal in SIGNALS if signal in table.values]
    if len(found) != 1:
        raise ExperimentError(f"{table.where(None)}, line {table.header_line}: {len(found)} measured signals; "
                              f"allowed: exactly one of {', '.join(f'{s} [{OUTPUTS[s][0]}]' for s in SIGNALS)}")
    try:
        decay = free_decay(table.values["time"], table.values[found[0]], lowpass=lowpass)
    except ValueError as error:
        raise ExperimentError(f"{table.where(found[0])}: {error}") from None
    return dataclasses.replace(decay_modal_test(decay, name or Path(path).stem, hub), source=str(path))


def decay_modal_test(decay: Decay, name: str, hub: str = "held", mode: int = 1) -> ModalTest:
    """The one-mode :class:`ModalTest` of a :class:`Decay` (its frequency and damping ratio with
    their standard errors)."""
    return ModalTest(name=name, hub=hub, mode=np.array([mode]), frequency=np.array([decay.frequency]),
                     frequency_std=np.array([decay.frequency_std]), damping_ratio=np.array([decay.damping_ratio]),
                     damping_ratio_std=np.array([max(decay.damping_ratio_std, 1e-6)]),
                     source="free decay (logarithmic decrement)")


__all__ = ["Decay", "decay_modal_test", "equivalent_averages", "free_decay", "frequency_response_estimate",
           "periodic_chirp", "read_free_decay"]
