"""Frequency responses, poles and zeros of the linear models, computed with python-control.

The transfer functions run from a model's input (the hub torque of a free hub) to its named
outputs (:data:`hubbeam.linear.statespace.OUTPUTS`): to the hub angle (collocated: the sensor
measures where the actuator acts), to the tip deflection ``v(L)`` and to the tip's arc position
``(rA + L) theta + v(L)`` (non-collocated). Every number comes from python-control on the model's
:class:`control.StateSpace` (``LinearModel.to_control``): ``control.frequency_response``,
``control.poles``, ``control.zeros`` (transmission zeros; without slycot, the finite generalised
eigenvalues of the Rosenbrock pencil ``([A, B; C, D], [I, 0; 0, 0])`` by QZ).

What the zeros show:

* collocated: the zeros of hub torque to hub angle are the poles of the model with the hub held
  (prescribed), because holding the output at zero is what the zeros describe; for an undamped
  model poles and zeros then lie on the imaginary axis and alternate, starting with the free hub's
  rigid-body double pole at 0 (:func:`alternates`), which makes a collocated loop easy to close;
* non-collocated: the tip's arc position has zeros in the right half-plane (real pairs ``+-z`` and
  quartets ``+-a +- i b`` of an undamped model, mirrored because its transfer function depends on
  ``s^2`` only): the tip first moves against the torque. :func:`right_half_plane` picks them.

Phase: python-control's response angle, unwrapped along the frequency grid and shifted by a whole
turn so that the lowest frequency's phase lies in ``(-360, 0]`` degrees (the hub angle of a free
hub starts at -180 degrees, a double integrator).
"""

from __future__ import annotations

import numpy as np

from hubbeam.linear.statespace import LinearModel
from hubbeam.model.linearised import pair_frequencies

#: relative tolerance of the comparisons of pole and zero frequencies (alternation, right
#: half-plane): the QZ zeros of the unbalanced pencil, whose stiff axial rows make ``|A|`` 1e7
#: to 1e8 times the bending ones, carry relative errors up to about 1e-9 (``hubbeam.model.linearised``
#: measured 4e-10 to 1e-9 for the same pencil structure); 100 times that.
RELATIVE_TOLERANCE = 1e-7


def _checked_output(lm: LinearModel, output: str) -> str:
    if output not in lm.outputs:
        raise ValueError(f"output = {output!r}; allowed: one of {', '.join(lm.outputs)} (the "
                         f"outputs of this {lm.model} model)")
    return output


def transfer(lm: LinearModel, output: str):
    """The single-input single-output :class:`control.StateSpace` from the model's input to
    ``output``."""
    return lm.to_control()[_checked_output(lm, output), lm.inputs[0]]


def check_omega(omega) -> np.ndarray:
    """``omega`` as a float array; ``ValueError`` unless a non-empty 1-D grid of finite circular
    frequencies > 0 rad s-1."""
    values = np.asarray(omega, dtype=float)
    if values.ndim != 1 or values.size == 0 or not np.all(np.isfinite(values) & (values > 0.0)):
        raise ValueError(f"omega = {omega!r}; allowed: a non-empty 1-D array of finite "
                         "frequencies > 0 rad s-1")
    return values


def frequency_response(lm: LinearModel, outputs, omega):
    """Magnitude (output units per input unit) and phase (degree) from the input to each of
    ``outputs`` at the circular frequencies ``omega`` (rad s-1): arrays (outputs, frequencies)."""
    names = [_checked_output(lm, output) for output in outputs]
    omega = check_omega(omega)
    import control as ct

    response = ct.frequency_response(lm.to_control()[names, lm.inputs[0]], omega, squeeze=False)
    values = np.asarray(response.complex)[:, 0, :]
    phase = np.unwrap(np.angle(values), axis=-1)
    for row, output in enumerate(names):
        phase[row] = _half_turns(lm, output, omega, phase[row])
    phase -= 2.0 * np.pi * np.ceil(phase[:, :1] / (2.0 * np.pi))
    return np.abs(values), np.degrees(phase)


#: a phase step between two frequencies within this of a half turn (rad) is an undamped root's
HALF_TURN = 1e-3


def _half_turns(lm: LinearModel, output: str, omega, phase):
    """``phase`` (unwrapped, rad) with each step of a half turn between two frequencies of ``omega``
    given the sign of the roots on the imaginary axis between them: an undamped zero turns the phase
    by +pi, an undamped pole by -pi, which the unwrapping cannot tell apart from the wrap of -pi
    (the collocated response of an undamped arm would sit at -360 degrees instead of 0)."""
    steps = np.diff(phase)
    ambiguous = np.flatnonzero(np.abs(np.abs(steps) - np.pi) < HALF_TURN)
    if ambiguous.size == 0:
        return phase
    scale = float(np.abs(omega).max())
    on_axis = {sign: roots[(np.abs(roots.real) <= 1e-9 * scale) & (roots.imag > 0)].imag
               for sign, roots in ((1, zeros(lm, output)), (-1, poles(lm)))}
    for k in ambiguous:
        turns = sum(sign * int(np.sum((found > omega[k]) & (found < omega[k + 1]))) for sign, found in on_axis.items())
        if turns:
            steps[k] = turns * np.pi
    return np.concatenate([phase[:1], phase[0] + np.cumsum(steps)])


def poles(lm: LinearModel) -> np.ndarray:
    """The poles of the model (the eigenvalues of ``A``), sorted by :func:`sort_roots`."""
    import control as ct

    return sort_roots(ct.poles(lm.to_control()))


def zeros(lm: LinearModel, output: str) -> np.ndarray:
    """Transmission zeros from the model's input to ``output``, sorted like :func:`poles`."""
    import control as ct

    return sort_roots(ct.zeros(transfer(lm, output)))


def sort_roots(values) -> np.ndarray:
    """Complex roots sorted by ``|Im|``, then ``Im`` (conjugates side by side, the negative one
    first), then ``Re`` (real roots ascending)."""
    values = np.asarray(values, dtype=complex)
    return values[np.lexsort((values.real, values.imag, np.abs(values.imag)))]


def alternates(pole_values, zero_values, rtol: float = RELATIVE_TOLERANCE) -> bool:
    """Whether poles and zeros alternate along the imaginary axis, a pole first and last.

    One frequency per conjugate pair (``|Im|``; a real pair counts as frequency 0), sorted: with
    ``m + 1`` pole pairs and ``m`` zero pairs, ``p_0 <= z_0 <= p_1 <= ... <= z_{m-1} <= p_m``,
    equality allowed to ``rtol`` (a pole cancelled by a zero, such as an axial mode that the hub
    torque does not excite at rest). Any other count, or a root off the axis by more than its
    frequency (damping ratio above 1/sqrt 2, real roots other than at 0; to ``rtol`` times the
    largest root), breaks the alternation.
    """
    p = pair_frequencies(np.asarray(pole_values, dtype=complex))
    z = pair_frequencies(np.asarray(zero_values, dtype=complex))
    if p.size != z.size + 1:
        return False
    roots = np.concatenate([np.asarray(pole_values, complex), np.asarray(zero_values, complex)])
    floor = rtol * np.max(np.abs(roots))  # the rigid-body poles sit at 0 to rounding
    if np.any(np.abs(roots.real) > np.abs(roots.imag) + floor):
        return False
    slack = rtol * np.maximum(z, p[1:])
    return bool(np.all(p[:-1] <= z + slack) and np.all(z <= p[1:] + slack))


def right_half_plane(zero_values, rtol: float = RELATIVE_TOLERANCE) -> np.ndarray:
    """The zeros with ``Re z > rtol |z|`` (non-minimum phase), sorted by magnitude."""
    values = np.asarray(zero_values, dtype=complex)
    found = values[values.real > rtol * np.abs(values)]
    return found[np.argsort(np.abs(found), kind="stable")]
