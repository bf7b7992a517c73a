"""Damping of the elastic coordinates of a case: the damping matrices ``C1, C2``.

A case's optional ``damping`` mapping acts on the axial block ``q1`` (mass ``M1``, stiffness
``K1``, Eqs. 14, 16) and the transverse block ``q2`` (``M2``, ``K2``, Eqs. 15, 16) separately; the
damping forces ``-C1 q1'`` and ``-C2 q2'`` join the elastic rows of Eq. (24):

* ``{kind: modal, axial: zeta1, transverse: zeta2}``: the damping ratio of every mode of the block,
  ``0 <= zeta < 1``: ``C = M Phi diag(2 zeta omega_i) Phi^T M`` with the eigenpairs
  ``K phi_i = omega_i^2 M phi_i`` of the non-rotating block, ``Phi^T M Phi = I`` (so that
  ``Phi^T C Phi = diag(2 zeta omega_i)``, valid for a non-diagonal ``M`` with a tip mass too);
  optionally ``transverse_modes: [zeta2_1, zeta2_2, ...]``, the ratios of the first transverse
  modes in ascending order of frequency (a rig's measured ratios differ from mode to mode), the
  modes beyond the list keeping ``transverse`` and entries beyond the case's modes unused;
* ``{kind: rayleigh, mass_coefficient: alpha, stiffness_coefficient: beta}`` (s-1, s; >= 0):
  ``C = alpha M + beta K`` per block.

The transverse block's mass is ``M2`` with a tip body's rotary inertia (``transverse_mass``).

Each kind is one record (:class:`ModalDamping`, :class:`RayleighDamping`; :data:`DAMPINGS`),
built from the checked configuration (schema ``damping``). No damping (``None``) gives zero
matrices: the undamped equations, bit for bit.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import asdict, dataclass
from typing import ClassVar

import numpy as np
from scipy.linalg import eigh

from hubbeam.core.system_matrices import transverse_mass


def modal_damping(M: np.ndarray, K: np.ndarray, ratio) -> np.ndarray:
    """``M Phi diag(2 ratio omega_i) Phi^T M`` from the mass-normalised eigenpairs of ``(K, M)``
    (``ratio`` one number, or one per eigenpair in ascending order of ``omega_i``)."""
    omega2, phi = eigh(K, M)
    mphi = M @ phi
    return (mphi * (2.0 * ratio * np.sqrt(np.clip(omega2, 0.0, None)))) @ mphi.T


@dataclass(frozen=True)
class ModalDamping:
    """The damping ratio of every axial (``q1``) and every transverse (``q2``) mode; with
    ``transverse_modes``, the ratios of the first transverse modes by ascending frequency (module
    docstring)."""

    kind: ClassVar[str] = "modal"
    axial: float
    transverse: float
    transverse_modes: tuple[float, ...] | None = None

    def block(self, b: int, M: np.ndarray, K: np.ndarray) -> np.ndarray:
        if b == 0 or self.transverse_modes is None:
            return modal_damping(M, K, (self.axial, self.transverse)[b])
        return modal_damping(M, K, self.transverse_ratios(M.shape[0]))

    def transverse_ratios(self, n: int) -> np.ndarray:
        """The ratios of ``n`` transverse modes by ascending frequency."""
        given = np.asarray(self.transverse_modes or (), dtype=float)[:n]
        return np.concatenate([given, np.full(n - given.size, self.transverse)])


@dataclass(frozen=True)
class RayleighDamping:
    """``C = alpha M + beta K`` per block (``mass_coefficient`` s-1, ``stiffness_coefficient`` s)."""

    kind: ClassVar[str] = "rayleigh"
    mass_coefficient: float
    stiffness_coefficient: float

    def block(self, b: int, M: np.ndarray, K: np.ndarray) -> np.ndarray:
        return self.mass_coefficient * M + self.stiffness_coefficient * K


#: the damping kinds by name (schema ``damping``)
DAMPINGS = {record.kind: record for record in (ModalDamping, RayleighDamping)}


def damping_from_dict(entry: Mapping | ModalDamping | RayleighDamping | None):
    """The record of a checked ``damping`` mapping (None: undamped; a record as it is)."""
    if entry is None or isinstance(entry, ModalDamping | RayleighDamping):
        return entry
    record = DAMPINGS[entry["kind"]]
    return record(**{key: tuple(map(float, value)) if isinstance(value, list | tuple) else float(value)
                     for key, value in entry.items() if key != "kind"})


def damping_to_dict(damping: ModalDamping | RayleighDamping | None) -> dict:
    """``{"kind": ..., key: value}`` as written in a configuration (empty: undamped; keys not given
    left out, lists for tuples)."""
    if damping is None:
        return {}
    return {"kind": damping.kind} | {key: list(value) if isinstance(value, tuple) else value
                                     for key, value in asdict(damping).items() if value is not None}


def damping_matrices(damping: ModalDamping | RayleighDamping | Mapping | None, sm) -> np.ndarray:
    """``C = [C1, C2]`` (shape ``(2, n, n)``) of a damping (a record, or its checked mapping) for
    SystemMatrices ``sm``."""
    n = np.shape(sm.M1)[0]
    C = np.zeros((2, n, n))
    damping = damping_from_dict(damping)
    if damping is None:
        return C
    for b, (M, K) in enumerate(((sm.M1, sm.K1), (transverse_mass(sm), sm.K2))):
        C[b] = damping.block(b, np.asarray(M), np.asarray(K))
    return np.ascontiguousarray(C)
