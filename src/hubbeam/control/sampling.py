"""What the sampled designs share: sensors, weights, mode names and the checks on modes.

* a sensor (:class:`hubbeam.model.maneuvers.SensorSpec`) measures an output of the linear models
  (``statespace.OUTPUTS``) with its gain (sensor units per signal unit), noise and quantisation
  step; :func:`measurement_rows` gives its rows ``gain c`` on a model's states (outputs with a
  feedthrough are refused), :func:`sensor_unit` its unit.
* :func:`weight_matrix`: ``Q`` from weights on named states or outputs, as
  ``hubbeam.control.feedback`` builds it (``w`` on a state's diagonal, ``w c^T c`` for an output).
* :func:`describe_modes`: a name for each eigenvalue of a continuous model (the rigid-body mode,
  ``vibration mode k`` by frequency, a real mode) and its frequency, for the messages.
* The checks, each a ``ValueError`` naming the mode, its frequency (Hz) and the sample time:
  :func:`nyquist_check` (a design-model mode above half the sampling frequency),
  :func:`observability_check` (PBH on the discrete model: a mode the signals cannot see that is
  not asymptotically stable, or one that sampling made invisible although the continuous model
  shows it: two poles ``lambda_i != lambda_j`` with ``exp(lambda_i Ts) = exp(lambda_j Ts)``, a mode
  at exactly half the sampling frequency), :func:`reachability_check` (PBH on the left
  eigenvectors: a mode that is not asymptotically stable, or on the unit circle, that an input or
  a noise cannot move).

PBH on a discrete model ``(Ad, Cd)``: ``Ad`` has the plant's eigenvalues ``z = exp(lambda Ts)``
(their eigenvectors the continuous ones, zero on the delayed inputs) and 0 for the delayed inputs.
Eigenvalues closer than :data:`SAME_EIGENVALUE` form one cluster whose eigenspace is the span of
their eigenvectors (orthonormalised, directions below :data:`PARALLEL` of the largest dropped: a
defective pair, such as the free hub's rigid-body mode, has one); the cluster is observable when
``Cd`` is injective on it: the smallest singular value of ``Cd_hat V`` above :data:`INVISIBLE`,
``Cd_hat`` the rows scaled to unit length. A cluster of ``k`` eigenvectors and fewer than ``k``
signals is never observable: why a mode sampled at exactly half the sampling frequency (a double
real ``z``) is lost to one sensor. Reachability is the same test on the left eigenvectors with
the input or noise columns.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping

import numpy as np
import scipy.linalg

from hubbeam.linear.export import state_units
from hubbeam.linear.statespace import OUTPUTS
from hubbeam.linear.tracking import ZERO_TOLERANCE
from hubbeam.model.maneuvers import SensorSpec

#: eigenvalues of a discrete model closer than this form one cluster: well above the split of a
#: defective pair by rounding (about ``sqrt(eps) = 1.5e-8``), so that the rigid-body pair stays one
#: mode, and a mode within about ``5e-8`` rad of half the sampling frequency counts as sampled
#: there
SAME_EIGENVALUE = 1e-7
#: eigenvectors of one cluster whose singular values fall below this share of the largest are one
#: direction (a defective eigenvalue's nearly parallel computed eigenvectors)
PARALLEL = 1e-6
#: a cluster's smallest singular value of ``Cd_hat V`` (or ``V^H G_hat``) at or below this: invisible
#: (or unreachable), as ``hubbeam.control.feedback.UNCONTROLLABLE`` for the hub torque
INVISIBLE = 1e-9
#: a mode lies above half the sampling frequency when ``|Im lambda| Ts > pi (1 + NYQUIST_MARGIN)``;
#: a mode within this of it is sampled exactly there (the pathological case of the PBH test)
NYQUIST_MARGIN = 1e-9


def sensor_unit(sensor: SensorSpec) -> str:
    """A sensor's unit: its own, else its signal's (``statespace.OUTPUTS``, or
    ``hubbeam.linear.export.state_units`` for a state read exactly)."""
    if sensor.unit:
        return sensor.unit
    return OUTPUTS[sensor.signal][0] if sensor.signal in OUTPUTS else state_units(sensor.signal)


def measurement_rows(model, sensors) -> np.ndarray:
    """``gain_j c_j`` (p, states): the rows of the ``sensors``' signals
    (:class:`~hubbeam.model.maneuvers.SensorSpec`) on ``model``'s states (``model.C``,
    ``model.outputs``); ``ValueError`` for a sensor no loop may hold
    (:meth:`~hubbeam.model.maneuvers.SensorSpec.problem`), a signal the model lacks or one with a
    feedthrough from the input."""
    rows = []
    for j, sensor in enumerate(sensors):
        problem = sensor.problem()
        if problem is not None:
            key, value, allowed = problem
            raise ValueError(f"sensors[{j}].{key} = {value!r}; allowed: {allowed}")
        if sensor.signal not in model.outputs:
            raise ValueError(f"sensors[{j}].signal = {sensor.signal!r}: not an output of {model.name}; allowed: "
                             f"{', '.join(model.outputs)}")
        k = model.outputs.index(sensor.signal)
        if np.any(np.asarray(model.D)[k] != 0.0):
            raise ValueError(f"sensors[{j}].signal = {sensor.signal!r} has a feedthrough from the input in "
                             f"{model.name}; allowed: a signal without one")
        rows.append(sensor.gain * np.asarray(model.C)[k])
    return np.array(rows).reshape(len(rows), np.shape(model.C)[1])


def _real(value) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def weight_matrix(model, weights: Mapping[str, float], argument: str = "weights") -> np.ndarray:
    """``Q``: ``w`` on the diagonal of each named state of ``model`` and ``w c^T c`` for each named
    output (rows of ``model.C``, outputs without feedthrough); ``ValueError`` for an unknown name or a
    weight that is negative or not finite."""
    Q = np.zeros((len(model.states), len(model.states)))
    for key, value in weights.items():
        if not (_real(value) and math.isfinite(value) and value >= 0.0):
            raise ValueError(f"{argument}.{key} = {value!r}; allowed: weights >= 0 (Q positive semidefinite)")
        if key in model.states:
            i = model.states.index(key)
            Q[i, i] += value
        elif key in model.outputs and not np.any(np.asarray(model.D)[model.outputs.index(key)] != 0.0):
            row = np.asarray(model.C)[model.outputs.index(key)]
            Q += value * np.outer(row, row)
        else:
            signals = [name for k, name in enumerate(model.outputs) if not np.any(np.asarray(model.D)[k] != 0.0)]
            raise ValueError(f"{argument}.{key}: unknown name; allowed: the states {', '.join(model.states)} or "
                             f"the outputs {', '.join(signals)}")
    return Q


def positive_weight(value, argument: str) -> float:
    """``value`` as a float; ``ValueError`` unless finite and > 0."""
    if not (_real(value) and math.isfinite(value) and value > 0.0):
        raise ValueError(f"{argument} = {value!r}; allowed: a finite weight > 0")
    return float(value)


def zero_tolerance(A: np.ndarray) -> float:
    """``|lambda|`` and ``Re lambda`` (s-1) below this count as zero
    (``hubbeam.linear.tracking.ZERO_TOLERANCE``)."""
    return ZERO_TOLERANCE * math.sqrt(float(np.max(np.abs(A)))) if np.size(A) else 0.0


def describe_modes(A: np.ndarray, states) -> tuple[np.ndarray, list[str]]:
    """The eigenvalues (s-1) of the continuous ``A`` and a description of each: ``the rigid-body
    mode``, ``vibration mode k`` (k-th by damped frequency, both members of a pair), or ``the real
    mode at lambda = ...``, with its frequency in Hz and the state with the largest share of its
    eigenvector's position part (``states`` the names of ``A``'s states)."""
    values, vectors = np.linalg.eig(A)
    tol = zero_tolerance(A)
    positions = [k for k, name in enumerate(states) if not name.endswith("_dot")]
    vibration = sorted({round(abs(v.imag), 12) for v in values if abs(v) > tol and v.imag != 0.0})
    described = []
    for value, vector in zip(values, vectors.T):
        mostly = states[positions[int(np.argmax(np.abs(vector[positions])))]]
        hz = abs(value.imag) / (2.0 * math.pi)
        if abs(value) <= tol:
            text = f"the rigid-body mode (0 Hz, mostly {mostly})"
        elif value.imag != 0.0:
            rank = vibration.index(round(abs(value.imag), 12)) + 1
            text = f"vibration mode {rank} ({hz:.6g} Hz, mostly {mostly})"
        else:
            text = f"the real mode at lambda = {value.real:.6g} s-1 (0 Hz, mostly {mostly})"
        described.append(text)
    return values, described


def _plant_mode(dm, z: complex) -> str:
    """The description of the continuous mode of ``dm`` whose ``exp(lambda Ts)`` is nearest ``z``."""
    values, described = describe_modes(dm.continuous.A, dm.continuous.states)
    return described[int(np.argmin(np.abs(np.exp(values * dm.Ts) - z)))]


def nyquist_check(dm, what: str) -> None:
    """``ValueError`` naming the lowest mode of ``dm``'s continuous model whose damped frequency lies
    above half the sampling frequency (``|Im lambda| Ts > pi``, :data:`NYQUIST_MARGIN`)."""
    values, described = describe_modes(dm.continuous.A, dm.continuous.states)
    for k in np.argsort(np.abs(values.imag)):
        if abs(values[k].imag) * dm.Ts > math.pi * (1.0 + NYQUIST_MARGIN):
            raise ValueError(
                f"{what}: {described[k]} of {dm.continuous.name} lies above half the sampling frequency "
                f"{0.5 / dm.Ts:.6g} Hz (Ts = {dm.Ts:g} s); allowed: a design model whose modes lie below it "
                "(hubbeam.linear.reduction.reduce_for_sampling) or a shorter sample time")


def _clusters(values: np.ndarray) -> list[np.ndarray]:
    """Indices of the eigenvalues grouped into clusters closer than :data:`SAME_EIGENVALUE`."""
    left = list(range(values.size))
    groups = []
    while left:
        group = [left.pop(0)]
        grown = True
        while grown:
            near = [k for k in left if np.min(np.abs(values[group] - values[k])) <= SAME_EIGENVALUE]
            grown = bool(near)
            group += near
            left = [k for k in left if k not in near]
        groups.append(np.array(group))
    return groups


def _span(vectors: np.ndarray) -> np.ndarray:
    """An orthonormal basis of the span of the columns of ``vectors`` (:data:`PARALLEL`)."""
    U, s, _ = np.linalg.svd(vectors, full_matrices=False)
    return U[:, s > PARALLEL * s[0]]


def _least_singular(matrix: np.ndarray, columns: int) -> float:
    """The smallest of the ``columns`` singular values of ``matrix`` (0 where it has fewer rows)."""
    if matrix.shape[0] < columns or matrix.size == 0:
        return 0.0
    return float(np.linalg.svd(matrix, compute_uv=False)[-1])


def _unit_rows(rows: np.ndarray) -> np.ndarray:
    norms = np.linalg.norm(rows, axis=1, keepdims=True)
    return np.divide(rows, norms, out=np.zeros_like(rows, dtype=float), where=norms > 0.0)


def _not_asymptotically_stable(dm, z: complex) -> bool:
    return abs(z) >= math.exp(-zero_tolerance(dm.continuous.A) * dm.Ts)


def _on_unit_circle(dm, z: complex) -> bool:
    return abs(abs(z) - 1.0) <= 1.0 - math.exp(-zero_tolerance(dm.continuous.A) * dm.Ts)


def observability_check(dm, rows: np.ndarray, what: str) -> None:
    """``ValueError`` for the first cluster of eigenvalues of the discrete ``dm.A`` that the
    measurement ``rows`` (on ``dm``'s states) cannot see (module docstring): lost by pathological
    sampling when the continuous model shows each of its modes, else undetectable unless
    asymptotically stable."""
    values, vectors = scipy.linalg.eig(dm.A)
    C = _unit_rows(np.asarray(rows, dtype=float))
    for group in _clusters(values):
        z = values[group[0]]
        if abs(z) == 0.0:  # the delayed inputs (and nothing of the plant: exp never vanishes)
            continue
        basis = _span(vectors[:, group])
        if _least_singular(C @ basis, basis.shape[1]) > INVISIBLE:
            continue
        mode = _plant_mode(dm, z)
        seen_alone = all(np.linalg.norm(C @ vectors[:, k]) > INVISIBLE * np.linalg.norm(vectors[:, k])
                         for k in group)
        if seen_alone and len(group) > 1:
            raise ValueError(
                f"{what}: {mode} is lost by pathological sampling: the continuous model shows it, but two of "
                f"its poles sample to the same z = {z:.6g} at Ts = {dm.Ts:g} s (a mode at half the sampling "
                f"frequency {0.5 / dm.Ts:.6g} Hz), which the measured signals cannot tell apart (PBH test on "
                "the discrete model); allowed: another sample time or more signals")
        if _not_asymptotically_stable(dm, z):
            raise ValueError(
                f"{what}: {mode} (z = {z:.6g}, Ts = {dm.Ts:g} s) is undetectable from the measured signals "
                "(PBH: no measured signal sees it, and it does not decay); allowed: signals that see it, "
                "such as the hub angle for the rigid-body mode")


def reachability_check(dm, columns: np.ndarray, what: str, by: str, unit_circle_only: bool = False) -> None:
    """``ValueError`` for the first cluster of eigenvalues of ``dm.A`` that is not asymptotically
    stable (or, with ``unit_circle_only``, on the unit circle) and that ``columns`` (on ``dm``'s
    states: the input or the noise) cannot move: PBH on the left eigenvectors."""
    values, left = scipy.linalg.eig(dm.A, left=True, right=False)
    G = _unit_rows(np.asarray(columns, dtype=float).T).T
    for group in _clusters(values):
        z = values[group[0]]
        concerned = _on_unit_circle(dm, z) if unit_circle_only else _not_asymptotically_stable(dm, z)
        if not concerned:
            continue
        basis = _span(left[:, group])
        if _least_singular(basis.conj().T @ G, basis.shape[1]) > INVISIBLE:
            continue
        place = "on the unit circle" if unit_circle_only else "not asymptotically stable"
        raise ValueError(f"{what}: {_plant_mode(dm, z)} (z = {z:.6g}, {place}, Ts = {dm.Ts:g} s) is left "
                         f"undisturbed by {by} (PBH on its left eigenvectors); allowed: {by} that moves it")


def stability_check(dm, poles: np.ndarray, what: str) -> None:
    """``ValueError`` when a pole of the sampled loop of ``dm`` is not asymptotically stable (a
    Riccati solver may return a gain that leaves a mode the weights do not see where it was),
    naming the open-loop mode nearest to it."""
    for z in poles:
        if _not_asymptotically_stable(dm, z):
            raise ValueError(f"{what}: the loop leaves {_plant_mode(dm, z)} at z = {z:.6g} (Ts = {dm.Ts:g} s), not "
                             "asymptotically stable: the weights do not see it; allowed: weights on a state or output "
                             "that does (the hub angle for the rigid-body mode)")


__all__ = ["INVISIBLE", "NYQUIST_MARGIN", "PARALLEL", "SAME_EIGENVALUE", "describe_modes", "measurement_rows",
           "nyquist_check", "observability_check", "positive_weight", "reachability_check", "sensor_unit",
           "stability_check", "weight_matrix", "zero_tolerance"]
