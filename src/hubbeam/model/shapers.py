"""Command shapers: impulse sequences that cancel the vibration a command excites in given modes.

A shaper is ``k`` impulses of amplitudes ``A_i`` (summing to 1) at times ``0 = t_0 < ... <
t_{k-1}``; the shaped command is the command convolved with it, ``r_s(t) = sum_i A_i r(t - t_i)``
(the kernels' side: ``hubbeam.core.shaping``). On a linear damped oscillator of natural
frequency ``omega`` and damping ratio ``zeta`` (``omega_d = omega sqrt(1 - zeta^2)``) the
vibration left after the last impulse, relative to that of a single unit impulse, is (Singer &
Seering 1990, Eq. 4)

    V(omega, zeta) = exp(-zeta omega t_n) sqrt(C^2 + S^2),
    C = sum_i A_i exp(zeta omega t_i) cos(omega_d t_i),   S = sum_i A_i exp(zeta omega t_i) sin(omega_d t_i),

with ``t_n`` the last impulse's time (:func:`residual_vibration`); the same ratio holds for the
residual vibration after any shaped command against the unshaped one, each measured from its own
end. Its curve over the frequency (:func:`insensitivity`) shows how much a shaper tolerates a
wrong frequency. The designs, ``K = exp(-zeta pi / sqrt(1 - zeta^2))`` and ``T_d = 2 pi / omega_d``:

* ZV (zero vibration; Singer & Seering 1990): ``A = (1, K) / (1 + K)`` at ``t = (0, T_d / 2)``:
  ``V = 0`` at the design frequency, ``V = |cos(pi omega / (2 omega_m))|`` around it (undamped);
* ZVD (zero vibration and derivative; Singer & Seering 1990): ``A = (1, 2 K, K^2) / (1 + K)^2`` at
  ``t = (0, T_d / 2, T_d)``, also ``dV/domega = 0``: the square of ZV's curve (undamped);
* EI (extra insensitive; Singhose, Seering & Singer 1994, "Residual vibration reduction using
  vector diagrams to generate shaping inputs"): three impulses with ``V = V_tol`` and
  ``dV/domega = 0`` at the design frequency and ``V = 0`` at one frequency below and one above
  it, so that ``V <= V_tol`` over a band wider than ZVD's. Undamped in closed form, ``A = ((1 +
  V_tol) / 4, (1 - V_tol) / 2, (1 + V_tol) / 4)`` at ``t = (0, T / 2, T)``; damped, the seven
  conditions (the amplitudes summing to 1, two on ``V`` at the design frequency, four for the two
  complex zeros) are solved for the amplitudes, the two times and the two zeros, by continuation
  in ``zeta`` from the closed form (:data:`EI_MAX_ZETA`, :data:`EI_MAX_V_TOL` bound the range where
  every step was checked to converge).

Several modes: the convolution of one shaper per mode (:func:`convolve`, :func:`multi_mode`)
cancels each, at the sum of their durations. A sampled controller changes its reference at
samples only: :func:`rounded` moves each impulse to the nearest sample, amplitudes unchanged
(impulses that land on one sample merge, their amplitudes added), so the sum stays 1 and the
residual is :func:`residual_vibration` at the rounded times; a mode whose half damped period
(ZV's impulse spacing) is shorter than a sample cannot be shaped at that rate
(:func:`check_sampling`).

For the kernel: :meth:`Shaper.kernel_array` (times in row 0, amplitudes in row 1; ``IDENTITY``
leaves a run unchanged) and :func:`shaped_stops`, the maneuver's non-smooth times shifted by
every impulse (the integrator must not step across any of them).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.optimize

#: largest damping ratio and tolerated residual of an EI shaper: over ``0 <= zeta <= 0.3`` and
#: ``0 < V_tol <= 0.2`` the continuation from the undamped closed form converges at every step
#: (checked on a grid: residuals of the conditions below 1e-15); beyond, its branch folds
EI_MAX_ZETA = 0.3
EI_MAX_V_TOL = 0.2
#: steps of the EI continuation in the damping ratio
EI_ZETA_STEP = 0.02
#: the EI conditions are met to this (absolute: they are residuals of order one)
EI_SOLVED = 1e-12
#: amplitudes of a shaper must sum to 1 within this
SUM_TOLERANCE = 1e-12


@dataclass(frozen=True, eq=False)
class Shaper:
    """Impulses of ``amplitudes`` at ``times`` (s; the first at 0, increasing), summing to 1.

    ``name`` says what it is (``ZV``, ``ZVD``, ``EI``, convolutions ``ZV*ZV``, ...); ``modes`` the
    ``(omega, zeta)`` it was designed for (rad s-1, 1), one per shaped mode (none for the
    identity)."""

    times: np.ndarray
    amplitudes: np.ndarray
    name: str = "shaper"
    modes: tuple = ()

    def __post_init__(self):
        times = np.array(self.times, dtype=float).ravel()
        amplitudes = np.array(self.amplitudes, dtype=float).ravel()
        if times.size == 0 or times.size != amplitudes.size:
            raise ValueError(f"shaper {self.name}: {times.size} times and {amplitudes.size} "
                             "amplitudes; allowed: as many of each, at least one")
        if not (np.all(np.isfinite(times)) and times[0] == 0.0 and np.all(np.diff(times) > 0.0)):
            raise ValueError(f"shaper {self.name}: times = {times.tolist()}; allowed: finite, the "
                             "first 0, strictly increasing")
        total = float(np.sum(amplitudes))
        if not (np.all(np.isfinite(amplitudes)) and abs(total - 1.0) <= SUM_TOLERANCE):
            raise ValueError(f"shaper {self.name}: amplitudes = {amplitudes.tolist()} (sum "
                             f"{total!r}); allowed: finite, summing to 1 (within {SUM_TOLERANCE:g})")
        times.flags.writeable = False
        amplitudes.flags.writeable = False
        object.__setattr__(self, "times", times)
        object.__setattr__(self, "amplitudes", amplitudes)
        object.__setattr__(self, "modes", tuple((float(w), float(z)) for w, z in self.modes))

    @property
    def duration(self) -> float:
        """The last impulse's time (s): how much later the shaped command ends."""
        return float(self.times[-1])

    def kernel_array(self) -> np.ndarray:
        """The kernel's ``shaper`` (``hubbeam.core.inputs.SimulationInputs``): shape ``(2, k)``,
        times in row 0 and amplitudes in row 1, C-contiguous float64, writable (a fresh copy)."""
        return np.ascontiguousarray(np.vstack([self.times, self.amplitudes]))

    def to_dict(self) -> dict:
        """The shaper as plain lists (a dataset attribute records it as JSON)."""
        return {"name": self.name, "times": self.times.tolist(),
                "amplitudes": self.amplitudes.tolist(), "modes": [list(m) for m in self.modes]}


#: one impulse of amplitude 1 at t = 0: the unshaped command
IDENTITY = Shaper([0.0], [1.0], "identity")


def _number(value) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool)


def checked_zeta(zeta, where: str) -> float:
    """``zeta`` as a float; ``ValueError`` naming ``where`` unless ``0 <= zeta < 1``."""
    if not (_number(zeta) and 0.0 <= zeta < 1.0):
        raise ValueError(f"{where}: zeta = {zeta!r}; allowed: a damping ratio 0 <= zeta < 1 "
                         "(an underdamped mode)")
    return float(zeta)


def checked_mode(omega, zeta, where: str) -> tuple[float, float]:
    """``(omega, zeta)`` as floats; ``ValueError`` naming ``where`` and the value unless
    ``omega`` is finite and > 0 rad s-1 and ``0 <= zeta < 1``."""
    if not (_number(omega) and math.isfinite(omega) and omega > 0.0):
        raise ValueError(f"{where}: omega = {omega!r}; allowed: a finite natural frequency > 0 rad s-1")
    return float(omega), checked_zeta(zeta, where)


def _damped(omega: float, zeta: float) -> tuple[float, float]:
    """``(K, T_d)``: the decay over half a damped period and the damped period."""
    root = math.sqrt(1.0 - zeta * zeta)
    return math.exp(-zeta * math.pi / root), 2.0 * math.pi / (omega * root)


def zv(omega: float, zeta: float = 0.0) -> Shaper:
    """The zero-vibration shaper of the mode ``(omega, zeta)`` (module docstring)."""
    omega, zeta = checked_mode(omega, zeta, "zv")
    K, T = _damped(omega, zeta)
    return Shaper([0.0, T / 2.0], np.array([1.0, K]) / (1.0 + K), "ZV", ((omega, zeta),))


def zvd(omega: float, zeta: float = 0.0) -> Shaper:
    """The zero-vibration-and-derivative shaper of the mode ``(omega, zeta)`` (module docstring)."""
    omega, zeta = checked_mode(omega, zeta, "zvd")
    K, T = _damped(omega, zeta)
    return Shaper([0.0, T / 2.0, T], np.array([1.0, 2.0 * K, K * K]) / (1.0 + K) ** 2, "ZVD",
                  ((omega, zeta),))


def _ei_conditions(x, zeta: float, v_tol: float) -> list[float]:
    """The EI conditions for a mode of unit frequency: ``x = (A_0, A_1, t_1, t_2, w_low,
    w_high)``, ``A_2 = 1 - A_0 - A_1``, ``t_0 = 0``. Powers of ``exp(s (t_i - t_2))``, ``s =
    zeta + i sqrt(1 - zeta^2)``, keep the numbers of order one."""
    a0, a1, t1, t2, low, high = x
    amplitudes = np.array([a0, a1, 1.0 - a0 - a1])
    lag = np.array([0.0, t1, t2]) - t2
    s = complex(zeta, math.sqrt(1.0 - zeta * zeta))

    def vector(w):
        return np.sum(amplitudes * np.exp(w * s * lag))

    r = vector(1.0)
    dr = np.sum(amplitudes * s * lag * np.exp(s * lag))
    r_low, r_high = vector(low), vector(high)
    return [abs(r) - v_tol, (np.conj(r) * dr).real, r_low.real, r_low.imag, r_high.real, r_high.imag]


def _ei_unit(zeta: float, v_tol: float) -> np.ndarray:
    """The EI solution ``x`` of :func:`_ei_conditions` for a unit frequency, by continuation in
    ``zeta`` from the undamped closed form."""
    spread = math.acos((1.0 - v_tol) / (1.0 + v_tol)) / math.pi
    x = np.array([(1.0 + v_tol) / 4.0, (1.0 - v_tol) / 2.0, math.pi, 2.0 * math.pi,
                  1.0 - spread, 1.0 + spread])
    steps = math.ceil(zeta / EI_ZETA_STEP)
    for z in np.linspace(0.0, zeta, steps + 1)[1:]:
        x = scipy.optimize.root(_ei_conditions, x, args=(z, v_tol), method="hybr", tol=1e-14).x
    worst = float(np.max(np.abs(_ei_conditions(x, zeta, v_tol))))
    amplitudes = (x[0], x[1], 1.0 - x[0] - x[1])
    if not (worst < EI_SOLVED and min(amplitudes) > 0.0 and 0.0 < x[2] < x[3] and x[4] < 1.0 < x[5]):
        raise RuntimeError(f"ei: no EI shaper found for zeta = {zeta!r}, V_tol = {v_tol!r} "
                           f"(conditions met to {worst:.3g})")
    return x


def ei(omega: float, zeta: float = 0.0, v_tol: float = 0.05) -> Shaper:
    """The extra-insensitive shaper of the mode ``(omega, zeta)`` with the tolerated residual
    ``v_tol`` at the design frequency (module docstring)."""
    omega, zeta = checked_mode(omega, zeta, "ei")
    if not zeta <= EI_MAX_ZETA:
        raise ValueError(f"ei: zeta = {zeta!r}; allowed: 0 <= zeta <= {EI_MAX_ZETA}")
    if not (_number(v_tol) and 0.0 < v_tol <= EI_MAX_V_TOL):
        raise ValueError(f"ei: v_tol = {v_tol!r}; allowed: a tolerated residual 0 < v_tol <= "
                         f"{EI_MAX_V_TOL} (0 is the ZVD shaper)")
    if zeta == 0.0:
        T = 2.0 * math.pi / omega
        return Shaper([0.0, T / 2.0, T], [(1.0 + v_tol) / 4.0, (1.0 - v_tol) / 2.0, (1.0 + v_tol) / 4.0],
                      "EI", ((omega, zeta),))
    a0, a1, t1, t2, _, _ = _ei_unit(zeta, float(v_tol))
    return Shaper([0.0, t1 / omega, t2 / omega], [a0, a1, 1.0 - a0 - a1], "EI", ((omega, zeta),))


def _merged(times: np.ndarray, amplitudes: np.ndarray, keys: np.ndarray):
    """Impulses with equal ``keys`` merged (amplitudes added), sorted by key: ``(times,
    amplitudes)`` with each merged impulse at the first of its times."""
    unique, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
    return times[first], np.bincount(inverse.ravel(), weights=amplitudes, minlength=unique.size)


def convolve(*shapers: Shaper) -> Shaper:
    """The convolution of ``shapers``: impulses at every sum of their times, of the products of
    their amplitudes (coinciding times merged); it cancels what each of them cancels."""
    if not shapers:
        raise ValueError("convolve: no shaper given; allowed: one or more Shaper")
    times, amplitudes = np.zeros(1), np.ones(1)
    for shaper in shapers:
        times = np.add.outer(times, shaper.times).ravel()
        amplitudes = np.multiply.outer(amplitudes, shaper.amplitudes).ravel()
    times, amplitudes = _merged(times, amplitudes, times)
    return Shaper(times, amplitudes, "*".join(s.name for s in shapers),
                  tuple(m for s in shapers for m in s.modes))


#: the designs by name
DESIGNS = {"ZV": zv, "ZVD": zvd, "EI": ei}


def multi_mode(modes, design: str = "ZV", **options) -> Shaper:
    """One ``design`` shaper (:data:`DESIGNS`; ``options`` such as ``v_tol`` for EI) per mode
    ``(omega, zeta)`` of ``modes``, convolved (:func:`convolve`)."""
    if design not in DESIGNS:
        raise ValueError(f"design = {design!r}; allowed: one of {', '.join(DESIGNS)}")
    modes = list(modes)
    if not modes:
        raise ValueError("modes = []; allowed: one or more (omega, zeta) pairs")
    return convolve(*(DESIGNS[design](*mode, **options) for mode in modes))


@dataclass(frozen=True)
class ShaperSpec:
    """A case's shaper as configured (schema ``shaper``): the design ``kind`` (:data:`DESIGNS`),
    EI's ``v_tol``, and either given ``frequencies`` (rad s-1) and ``damping`` ratios, or the
    ``modes`` (numbers) of ``model``'s linearisation at ``speed`` to tune to (``hubbeam.control.shaping``;
    None: the case's model, the maneuver's final speed), each designed at ``frequency_ratio`` times
    its frequency (None: at the frequency itself; another ratio puts a known frequency error into
    the design, the horizontal axis of an insensitivity curve measured on a model).
    :meth:`given_modes` gives the modes of given frequencies; a tuned one needs the linear models."""

    kind: str
    v_tol: float | None = None
    modes: tuple[int, ...] = (1,)
    model: str | None = None
    speed: float | None = None
    frequencies: tuple[float, ...] | None = None
    damping: tuple[float, ...] | None = None
    frequency_ratio: float | None = None

    @classmethod
    def from_dict(cls, entry) -> ShaperSpec:
        values = {"kind": entry["kind"]}
        for key in ("v_tol", "speed", "frequency_ratio"):
            if key in entry:
                values[key] = float(entry[key])
        if "model" in entry:
            values["model"] = entry["model"]
        if "modes" in entry:
            values["modes"] = tuple(int(mode) for mode in entry["modes"])
        for key in ("frequencies", "damping"):
            if key in entry:
                values[key] = tuple(float(value) for value in entry[key])
        return cls(**values)

    def to_dict(self) -> dict:
        plain = {"kind": self.kind, "modes": list(self.modes)}
        for key in ("v_tol", "model", "speed", "frequencies", "damping", "frequency_ratio"):
            value = getattr(self, key)
            if value is not None:
                plain[key] = list(value) if isinstance(value, tuple) else value
        return plain

    @property
    def options(self) -> dict:
        """The design's keyword arguments (EI's ``v_tol``)."""
        return {} if self.v_tol is None else {"v_tol": self.v_tol}

    def shaper(self, modes) -> Shaper:
        """The shaper of this design for the ``(omega, zeta)`` pairs ``modes``."""
        return multi_mode(modes, self.kind, **self.options)

    def design_modes(self, modes) -> list[tuple[float, float]]:
        """The ``(omega, zeta)`` pairs the shaper is designed for, from the tuned ``modes``: each
        frequency times :attr:`frequency_ratio` (the pairs unchanged without one)."""
        if self.frequency_ratio is None:
            return list(modes)
        return [(self.frequency_ratio * omega, zeta) for omega, zeta in modes]

    def given_modes(self) -> list[tuple[float, float]] | None:
        """The ``(omega, zeta)`` pairs of given frequencies (None when tuned on a model)."""
        if self.frequencies is None:
            return None
        damping = self.damping or (0.0,) * len(self.frequencies)
        return list(zip(self.frequencies, damping))


def checked_sample_time(sample_time) -> float:
    """``sample_time`` as a float; ``ValueError`` unless finite and > 0 s."""
    if not (_number(sample_time) and math.isfinite(sample_time) and sample_time > 0.0):
        raise ValueError(f"sample_time = {sample_time!r}; allowed: a finite sample time > 0 s")
    return float(sample_time)


def rounded(shaper: Shaper, sample_time: float) -> Shaper:
    """``shaper`` with every impulse moved to the nearest multiple of ``sample_time`` (halves
    rounded up), amplitudes unchanged; impulses on one sample merge, their amplitudes added."""
    sample_time = checked_sample_time(sample_time)
    samples = np.floor(shaper.times / sample_time + 0.5).astype(np.int64)
    _, amplitudes = _merged(shaper.times, shaper.amplitudes, samples)
    return Shaper(np.unique(samples) * sample_time, amplitudes,
                  f"{shaper.name} on {sample_time:g} s samples", shaper.modes)


def check_sampling(shaper: Shaper, sample_time: float) -> None:
    """``ValueError`` if a mode the ``shaper`` was designed for oscillates faster than half the
    sampling frequency of a controller sampled every ``sample_time``: ``omega_d > pi /
    sample_time``, where half its damped period, the spacing of ZV's impulses, is shorter than
    one sample and rounding (:func:`rounded`) merges what should cancel."""
    sample_time = checked_sample_time(sample_time)
    limit = math.pi / sample_time
    for k, (omega, zeta) in enumerate(shaper.modes, start=1):
        damped = omega * math.sqrt(1.0 - zeta * zeta)
        if damped > limit:
            raise ValueError(
                f"shaper {shaper.name}: mode {k} oscillates at omega_d = {damped:.6g} rad s-1 "
                f"({damped / (2 * math.pi):.6g} Hz), above half the sampling frequency of "
                f"sample_time = {sample_time!r} s ({0.5 / sample_time:.6g} Hz); allowed: modes "
                f"with omega_d <= pi / sample_time = {limit:.6g} rad s-1 (a shorter sample time, or "
                "leave that mode unshaped)")


def residual_vibration(shaper: Shaper, omega, zeta: float = 0.0):
    """``V(omega, zeta)`` of the module docstring: the vibration a linear oscillator of natural
    frequency ``omega`` (rad s-1; a number or an array) and damping ratio ``zeta`` keeps after
    the shaped command, relative to the unshaped one."""
    w = np.asarray(omega, dtype=float)
    if not (np.all(np.isfinite(w)) and np.all(w > 0.0)):
        raise ValueError(f"omega = {omega!r}; allowed: finite natural frequencies > 0 rad s-1")
    zeta = checked_zeta(zeta, "residual_vibration")
    lag = shaper.times - shaper.duration  # exp(zeta w (t_i - t_n)): no overflow
    wd = w[..., None] * math.sqrt(1.0 - zeta * zeta)
    weights = shaper.amplitudes * np.exp(zeta * w[..., None] * lag)
    C = np.sum(weights * np.cos(wd * shaper.times), axis=-1)
    S = np.sum(weights * np.sin(wd * shaper.times), axis=-1)
    V = np.hypot(C, S)
    return float(V) if np.ndim(omega) == 0 else V


def insensitivity(shaper: Shaper, omega: float, zeta: float = 0.0, ratios=None) -> tuple[np.ndarray, np.ndarray]:
    """The insensitivity curve of ``shaper`` about the mode ``(omega, zeta)``: ``(ratios, V)``,
    the residual :func:`residual_vibration` at the frequencies ``ratios * omega`` (default 0.5 to
    1.5 in steps of 0.001), same damping ratio."""
    omega, zeta = checked_mode(omega, zeta, "insensitivity")
    ratios = np.linspace(0.5, 1.5, 1001) if ratios is None else np.asarray(ratios, dtype=float)
    return ratios, residual_vibration(shaper, ratios * omega, zeta)


def insensitive_band(shaper: Shaper, omega: float, zeta: float = 0.0, tolerance: float = 0.05,
                     step: float = 1e-3) -> tuple[float, float]:
    """The frequency ratios ``(low, high)`` around 1 between which the residual stays within
    ``tolerance``: walking out from the design frequency in ``step`` of the ratio to the first
    excess, then Brent's root of ``V - tolerance`` in that step. ``high`` is infinite when the
    residual can no longer exceed the tolerance: a damped mode's ``V`` at ratio ``r`` and above is
    at most ``sum_i A_i exp(zeta r omega (t_i - t_n))``. The residual at the design frequency
    must be within ``tolerance`` (an EI shaper's equals its ``V_tol`` up to :data:`EI_SOLVED`,
    which the comparison allows)."""
    omega, zeta = checked_mode(omega, zeta, "insensitive_band")

    def excess(ratio):
        return residual_vibration(shaper, ratio * omega, zeta) - tolerance - EI_SOLVED

    def bounded(ratio):
        return np.sum(shaper.amplitudes * np.exp(zeta * ratio * omega * (shaper.times - shaper.duration))) \
            <= tolerance

    if excess(1.0) > 0.0:
        raise ValueError(f"tolerance = {tolerance!r}: the residual at the design frequency is "
                         f"{residual_vibration(shaper, omega, zeta):.6g}; allowed: a tolerance "
                         "the shaper meets there")
    edges = []
    for direction in (-1.0, 1.0):
        k = 1
        while excess(1.0 + direction * k * step) <= 0.0:
            ratio = 1.0 + direction * k * step
            if direction > 0.0 and bounded(ratio):
                break
            if ratio <= step or ratio >= 1.0 / step:
                raise ValueError(f"tolerance = {tolerance!r}: the residual of {shaper.name} stays "
                                 f"within it from the design frequency to a ratio of {ratio:g}; "
                                 "allowed: a tolerance it exceeds on both sides")
            k += 1
        inner, outer = 1.0 + direction * (k - 1) * step, 1.0 + direction * k * step
        edges.append(scipy.optimize.brentq(excess, inner, outer, xtol=1e-14) if excess(outer) > 0.0
                     else math.inf)
    return edges[0], edges[1]


def shaped_stops(stops, shaper: Shaper) -> np.ndarray:
    """The sorted distinct times where a shaped command is not smooth: the maneuver's start
    (``t = 0``) and its ``stops`` (``hubbeam.model.maneuvers.Maneuver.stops``) shifted by every
    impulse time of ``shaper``."""
    times = np.concatenate([[0.0], np.asarray(stops, dtype=float)])
    return np.unique(np.add.outer(shaper.times, times))
