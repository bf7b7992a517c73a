"""A smaller design model: modal truncation that keeps the rigid-body mode.

A controller sampled every ``Ts`` seconds cannot act on, nor an observer follow, the modes above half
the sampling frequency; a design model with many assumed modes carries them anyway (and a Kalman
filter refuses them, ``hubbeam.control.kalman``). Balanced truncation does not apply: the free
hub's rigid-body mode (a double pole at 0) has no finite Gramians. Modal truncation does: the
real Schur form of ``A``, reordered so that the kept eigenvalues (``|lambda|`` up to a cutoff, the
rigid-body pair at 0 among them) come first (``scipy.linalg.schur`` with ``sort``),

    Z^T A Z = [[S11, S12], [0, S22]],

is block-diagonalised by ``T = [[I, X], [0, I]]`` with the Sylvester equation ``S11 X - X S22 =
-S12`` (``scipy.linalg.solve_sylvester``; the two blocks share no eigenvalue), and the leading block
is kept:

    xi' = S11 xi + B_r u,   y = C_r xi + D u,   B_r = (Z^T B)_1 - X (Z^T B)_2,   C_r = (C Z)_1.

The reduced model's poles are exactly the kept poles of the full one; it keeps ``D`` (the dropped
modes' static contribution is lost, which the error below measures). Its states are modal
coordinates ``xi = W x`` (``W`` the first rows of ``T^-1 Z^T``; ``x ~ V xi``, ``V`` the first
columns of ``Z``), named ``mode_1 ..``; the outputs are the full model's.

:func:`response_error` measures the largest relative error ``|G_r(i w) - G(i w)| / |G(i w)|``
of each output's response to the input over a logarithmic grid of frequencies up to a limit
(half the sampling frequency for a sampled design), and where it is largest. The grid starts a
decade below the lowest kept vibration mode: further down, the dropped modes' static
contribution (which truncation loses) dominates the outputs whose response vanishes at rest, such
as the deflection of a hub held by a drive's damping, whose relative error then grows like
``1 / w`` although the absolute error stays that static residual.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg

from hubbeam.linear.statespace import LinearModel

#: the names of a truncated model's states: ``mode_1``, ``mode_2``, ...
MODAL_PREFIX = "mode_"


@dataclass(frozen=True, eq=False)
class ReducedModel(LinearModel):
    """A :class:`LinearModel` on modal coordinates ``xi = W x`` of the ``full`` model's states.

    ``projection`` ``W`` (r, n), ``expansion`` ``V`` (n, r) with ``W V = I``; ``cutoff`` the largest
    kept ``|lambda|`` (rad s-1); ``full_states`` the full model's state names.
    """

    projection: np.ndarray | None = None
    expansion: np.ndarray | None = None
    cutoff: float = math.inf
    full_states: tuple[str, ...] = ()

    @property
    def name(self) -> str:
        """The full model's name with the number of kept states."""
        return super().name + f"_modal{self.A.shape[0]}"


@dataclass(frozen=True)
class ResponseError:
    """The largest relative frequency-response error: ``value`` at ``frequency`` (Hz) on ``output``,
    over ``[lowest, limit]`` Hz; ``per_output`` the largest of each output."""

    value: float
    frequency: float
    output: str
    lowest: float
    limit: float
    per_output: dict


def modal_truncation(model: LinearModel, max_frequency: float) -> ReducedModel:
    """``model`` reduced to its modes with ``|lambda| <= 2 pi max_frequency`` (``max_frequency`` in
    Hz; the rigid-body mode always among them), by the module docstring's block diagonalisation."""
    if not (isinstance(max_frequency, (int, float)) and math.isfinite(max_frequency) and max_frequency > 0.0):
        raise ValueError(f"max_frequency = {max_frequency!r}; allowed: a finite frequency > 0 Hz")
    cutoff = 2.0 * math.pi * float(max_frequency)
    A = np.asarray(model.A, dtype=float)

    def kept(re, im):
        return np.hypot(re, im) <= cutoff

    S, Z, r = scipy.linalg.schur(A, output="real", sort=kept)
    if r == 0:
        raise ValueError(f"max_frequency = {max_frequency!r} Hz keeps no mode of {model.name}")
    n = A.shape[0]
    if r < n:
        X = scipy.linalg.solve_sylvester(S[:r, :r], -S[r:, r:], -S[:r, r:])
    else:
        X = np.zeros((r, 0))
    ZB = Z.T @ model.B
    W = Z[:, :r].T - X @ Z[:, r:].T
    return ReducedModel(model=model.model, hub=model.hub, speed=model.speed, A=S[:r, :r],
                        B=ZB[:r] - X @ ZB[r:], C=model.C @ Z[:, :r], D=np.array(model.D, dtype=float),
                        states=tuple(f"{MODAL_PREFIX}{k}" for k in range(1, r + 1)), inputs=tuple(model.inputs),
                        outputs=tuple(model.outputs), projection=W, expansion=Z[:, :r], cutoff=cutoff,
                        full_states=tuple(model.states))


def frequency_responses(model, omega: np.ndarray) -> np.ndarray:
    """``C (i w I - A)^-1 B + D`` of the first input at the circular frequencies ``omega``:
    (outputs, frequencies), by one complex solve per frequency."""
    n = model.A.shape[0]
    out = np.empty((model.C.shape[0], omega.size), dtype=complex)
    for k, w in enumerate(omega):
        out[:, k] = model.C @ np.linalg.solve(1j * w * np.eye(n) - model.A, model.B[:, 0]) + model.D[:, 0]
    return out


def lowest_vibration(model: LinearModel) -> float:
    """The lowest damped frequency (Hz) of ``model``'s vibration modes (complex poles); NaN if none."""
    imag = np.abs(np.linalg.eigvals(model.A).imag)
    imag = imag[imag > 0.0]
    return float(imag.min() / (2.0 * math.pi)) if imag.size else math.nan


def response_error(full: LinearModel, reduced: LinearModel, limit: float, outputs=None, lowest: float | None = None,
                   points: int = 2000) -> ResponseError:
    """The largest relative error of ``reduced`` against ``full`` (module docstring) over ``points``
    frequencies spaced logarithmically from ``lowest`` (default: a tenth of ``reduced``'s lowest
    vibration frequency, or ``limit / 1e3`` without one) to ``limit`` (Hz), on ``outputs`` (names;
    all by default)."""
    names = tuple(full.outputs) if outputs is None else tuple(outputs)
    unknown = [name for name in names if name not in full.outputs or name not in reduced.outputs]
    if unknown:
        raise ValueError(f"outputs = {list(names)!r}: {unknown[0]!r} is not an output of both models")
    if lowest is None:
        first = lowest_vibration(reduced)
        lowest = 0.1 * first if math.isfinite(first) and first < limit else limit * 1e-3
    hz = np.geomspace(lowest, limit, points)
    omega = 2.0 * math.pi * hz
    rows_full = [full.outputs.index(name) for name in names]
    rows_reduced = [reduced.outputs.index(name) for name in names]
    G = frequency_responses(full, omega)[rows_full]
    Gr = frequency_responses(reduced, omega)[rows_reduced]
    with np.errstate(divide="ignore", invalid="ignore"):
        relative = np.abs(Gr - G) / np.abs(G)
    per_output = {name: float(np.nanmax(relative[k])) for k, name in enumerate(names)}
    o, k = np.unravel_index(np.nanargmax(relative), relative.shape)
    return ResponseError(value=float(relative[o, k]), frequency=float(hz[k]), output=names[o],
                         lowest=float(lowest), limit=float(limit), per_output=per_output)


def reduce_for_sampling(model: LinearModel, Ts: float, outputs=None) -> tuple[ReducedModel, ResponseError]:
    """``model`` truncated to its modes below half the sampling frequency ``1 / (2 Ts)`` and the
    largest relative frequency-response error up to that frequency (:func:`response_error`)."""
    nyquist = 0.5 / Ts
    reduced = modal_truncation(model, nyquist)
    return reduced, response_error(model, reduced, nyquist, outputs)


__all__ = ["MODAL_PREFIX", "ReducedModel", "ResponseError", "frequency_responses", "lowest_vibration",
           "modal_truncation", "reduce_for_sampling", "response_error"]
