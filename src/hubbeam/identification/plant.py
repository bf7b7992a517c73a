"""The one route from a case and parameter values to its matrices, linear responses and simulations.

:class:`CasePlant` holds a case as configured (its beam and numerics) and answers, for any values of
the free parameters (:mod:`hubbeam.identification.parameters`), what the fit predicts from:

* :meth:`~CasePlant.system`: the case and beam as the configuration would build them
  (:func:`~hubbeam.identification.parameters.apply`) and their system matrices, equal to
  ``hubbeam.simulation.simulate.case_matrices`` of them (a test checks it) without assembling
  them again where a parameter enters linearly: ``EI`` scales ``K2`` (Eq. 15) and nothing else
  the models read, the hub inertia is ``Jh`` (plus the drive rotor's reflected inertia), a tip
  body's rotary inertia is ``Jt``, and every matrix is affine in a point mass's value (the tip
  terms of Eqs. 13-19 are ``m_t`` times functions of its place), so the matrices of two masses
  assembled once per place give every mass; a root spring or damping ratio is not in the
  matrices at all. Only the tip's place, or a tip body whose own modes are the case's functions
  (``transverse_functions: tip_body``), assembles again, once per value (cached);
* :meth:`~CasePlant.equations`: ``M z'' + E z' + K z = b u`` about the steady spin
  (``hubbeam.linear.statespace.spin_equations``, the compliant root's joint included), ``E = G + C``
  with the drive's linearised damping on the hub row when the input is the voltage
  (``hubbeam.linear.voltage``: ``b = kV e_hub``, ``c = kV Kg km + B + Fc/eps sech^2``);
* :meth:`~CasePlant.modes`: frequency and damping ratio of the bending modes, the hub held (its
  row and column removed: ``Configuration.natural_frequencies`` with damping) or free (the drive's
  damping on the hub when the case has one), from the eigenvalues of the state matrix;
* :meth:`~CasePlant.frequency_response`: ``H(s) = (Cz + s Cv + s^2 Ca) (s^2 M + s E + K)^-1 b``
  by one batched solve over the frequencies (the rows ``Cz, Cv, Ca`` of
  ``hubbeam.linear.statespace.output_rows``), the same as the state-space model's ``C (sI - A)^-1
  B + D`` (a test checks it against python-control);
* :meth:`~CasePlant.simulate`: the case's nonlinear model (``hubbeam.simulation.simulate.run``)
  driven by a time series's input column (``voltage_table`` through the drive, or the net
  ``hub_torque`` on the hub with the drive's rotor inertia kept and its back-EMF and friction left
  in the measured torque; linear between the samples, or a staircase for a ``zero_order`` hold),
  or inside its PD loop on the hub angle (``pd`` maneuver tracking the
  ``reference`` column as an ``angle_table``), from rest, output at the samples; the signals
  ``hub_angle`` (the motor side with a compliant root), ``tip_deflection``, ``deflection_angle``
  (``v(L) / L``) and ``tip_acceleration`` (the second derivative of the tip's arc by a quintic
  spline through outputs :data:`ACCELERATION_OVERSAMPLING` times denser than the samples, plus
  ``-theta'^2 v + 2 theta' u'`` of ``hubbeam.linear.statespace``; its relative error is of order
  ``(omega h / 4)^4`` at a mode ``omega`` sampled every ``h``, 1e-5 at 25 Hz sampled at 500 Hz);
  :meth:`~CasePlant.release`: the hub held at rest, the link released from a deflection.

Everything the fit asks of the model goes through this module, so that the route can change (to a
shared plant object, say) without touching the fit.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import make_interp_spline

from hubbeam.configuration.settings import Case, InitialState, Numerics
from hubbeam.core.integrate import output_columns
from hubbeam.identification.experiments import TimeSeries
from hubbeam.identification.parameters import apply
from hubbeam.linear.statespace import output_rows, spin_equations
from hubbeam.linear.voltage import linearised_damping
from hubbeam.model.damping import damping_matrices
from hubbeam.model.maneuvers import AngleTable, PdControl, SpeedTable, TorqueTable, VoltageTable
from hubbeam.model.matrices import SystemMatrices, assemble
from hubbeam.model.models import model as model_traits
from hubbeam.model.modes import CLAMPED_FREE
from hubbeam.model.parameters import TipMass
from hubbeam.simulation.simulate import UNRESOLVED, kernel_matrices, output_times, run

#: a simulated accelerometer's signal is differentiated on a grid this many times finer than its samples
ACCELERATION_OVERSAMPLING = 4
#: a zero-order hold's step lasts this fraction of a sample less than the sample (the table's times
#: must increase)
HOLD_EDGE = 1e-6
#: an eigenvalue is a vibration when its imaginary part exceeds this fraction of the largest |lambda|
#: (the rigid-body pair of a free hub sits at the origin to about sqrt(eps) of it)
OSCILLATORY = 1e-6


@dataclass(frozen=True, eq=False)
class Equations:
    """``M z'' + E z' + K z = b u`` about the steady spin of ``case`` (on ``beam``, matrices ``sm``,
    axial stretch ``q1s``); the hub's angle is ``z[hub]``, ``b = gain e_hub``."""

    M: np.ndarray
    E: np.ndarray
    K: np.ndarray
    q1s: np.ndarray
    hub: int
    gain: float
    case: Case
    beam: object
    sm: SystemMatrices


class CasePlant:
    """A case (``case``, ``beam``, ``numerics`` as configured) as the fit sees it (module docstring)."""

    def __init__(self, case: Case, beam, numerics: Numerics) -> None:
        if numerics.quadrature_points is None:
            raise ValueError("numerics.quadrature_points: None; allowed: the configuration's numerics (the "
                             "matrices are assembled here)")
        self.case, self.beam, self.numerics = case, beam, numerics
        self.traits = model_traits(case.model)
        self._places: dict[tuple, tuple[SystemMatrices, SystemMatrices]] = {}
        self._maneuvers: dict[int, object] = {}

    @classmethod
    def from_configuration(cls, configuration, name: str) -> CasePlant:
        """The plant of case ``name`` of a ``hubbeam.api.Configuration`` (or anything with its
        ``settings``)."""
        settings = configuration.settings
        return cls(settings.case(name), settings.beam, settings.numerics)

    @property
    def joint(self) -> bool:
        """Whether the case has a compliant root."""
        return self.case.root_spring is not None

    def system(self, values: Mapping[str, float], drive: bool = True):
        """``(case, beam, sm)`` with ``values`` applied (module docstring); without its ``drive``
        (the net hub torque as input) when ``drive`` is false, the rotor's inertia kept in ``Jh``."""
        case, beam = apply(self.case, self.beam, values)
        tip = case.tip_mass
        if self.case.transverse_functions == CLAMPED_FREE:
            base, per_kg = self._place((tip.position, tip.inertia, tip.offset))
            sm = SystemMatrices(*(b + tip.mass * d if np.ndim(b) else float(b + tip.mass * d)
                                  for b, d in zip(base, per_kg)))
        else:
            key = (tip.mass, tip.position, tip.inertia, tip.offset)
            if key not in self._places:
                self._places[key] = (self._assemble(tip), None)
            sm = self._places[key][0]
        factor = float(values.get("beam.EI_factor", 1.0))
        reflected = 0.0 if case.drive is None else case.drive.reflected_inertia
        sm = sm._replace(K2=sm.K2 * factor if factor != 1.0 else sm.K2, Jh=float(beam.Jh) + reflected)
        if not drive:
            case = dataclasses.replace(case, drive=None)
        return case, beam, sm

    def _assemble(self, tip: TipMass) -> SystemMatrices:
        return kernel_matrices(assemble(self.beam, tip, self.case.modes, self.numerics.quadrature_points,
                                        self.case.transverse_functions))

    def _place(self, place: tuple) -> tuple[SystemMatrices, SystemMatrices]:
        """The matrices of a tip of no mass at ``place`` and their change per kg (two assemblies)."""
        if place not in self._places:
            one, two = (self._assemble(TipMass(mass, *place)) for mass in (1.0, 2.0))
            per_kg = SystemMatrices(*(b - a for a, b in zip(one, two)))
            self._places[place] = (SystemMatrices(*(a - d for a, d in zip(one, per_kg))), per_kg)
        return self._places[place]

    def equations(self, values: Mapping[str, float], speed: float = 0.0, input: str = "hub_torque") -> Equations:
        """The linear equations about the steady spin at ``speed`` with ``input`` (``voltage``:
        through the drive; ``hub_torque``: the net torque on the hub) (module docstring)."""
        voltage = input == "voltage"
        if voltage and self.case.drive is None:
            raise ValueError(f"input = 'voltage' for case {self.case.label!r} without a drive; allowed: "
                             "hub_torque, or a case with a drive")
        case, beam, sm = self.system(values, drive=voltage)
        damping = damping_matrices(case.damping, sm)
        M, G, C, K, q1s, hub = spin_equations(sm, self.traits, speed, damping, case.root_spring)
        E = G + C
        gain = 1.0
        if voltage:
            E[hub, hub] += linearised_damping(case.drive, speed)
            gain = case.drive.torque_gain
        return Equations(M, E, K, q1s, hub, gain, case, beam, sm)

    def modes(self, values: Mapping[str, float], hub: str, speed: float = 0.0):
        """``(frequency, damping_ratio)`` of the bending modes by ascending frequency: the natural
        frequency ``|lambda| / 2 pi`` (Hz) and ``-Re lambda / |lambda|`` of each vibration (module
        docstring), the hub ``held`` or ``free``."""
        eq = self.equations(values, speed, "voltage" if hub == "free" and self.case.drive is not None else "hub_torque")
        keep = np.delete(np.arange(eq.M.shape[0]), eq.hub) if hub == "held" else np.arange(eq.M.shape[0])
        M, E, K = (matrix[np.ix_(keep, keep)] for matrix in (eq.M, eq.E, eq.K))
        N = keep.size
        A = np.vstack([np.hstack([np.zeros((N, N)), np.eye(N)]), np.linalg.solve(M, np.hstack([-K, -E]))])
        lam, vectors = np.linalg.eig(A)
        upper = lam.imag > OSCILLATORY * np.abs(lam).max()
        lam, shapes = lam[upper], vectors[:N, upper]
        n = self.case.modes
        axial = np.isin(keep, np.arange(1, 1 + n)) if self.traits.keeps_axial else np.zeros(N, dtype=bool)
        weight = np.abs(shapes) ** 2 * np.diag(M)[:, None]
        bending = weight[axial].sum(axis=0) < 0.5 * weight.sum(axis=0)
        lam = lam[bending]
        lam = lam[np.argsort(np.abs(lam))]
        return np.abs(lam) / (2.0 * math.pi), -lam.real / np.abs(lam)

    def frequency_response(self, values: Mapping[str, float], input: str, output: str, frequency, speed: float = 0.0):
        """The complex response from ``input`` to ``output`` at ``frequency`` (Hz), in the output's
        unit per the input's (module docstring)."""
        eq = self.equations(values, speed, input)
        Cz, Cv, Ca = output_rows(eq.beam, eq.sm, self.traits, speed, eq.q1s, [output], eq.case.root_spring)
        s = 2j * math.pi * np.asarray(frequency, dtype=float)[:, None, None]
        b = np.zeros((eq.M.shape[0], 1))
        b[eq.hub, 0] = eq.gain
        z = np.linalg.solve(s * s * eq.M + s * eq.E + eq.K, np.broadcast_to(b, (s.shape[0],) + b.shape))
        rows = Cz[0] + s[:, :, 0] * Cv[0] + s[:, :, 0] ** 2 * Ca[0]
        return np.einsum("fn,fn->f", rows, z[:, :, 0])

    def _maneuver(self, series: TimeSeries):
        """The maneuver that replays ``series`` (its input table, or its loop with the reference), once per record."""
        key = id(series)
        if key not in self._maneuvers:
            t = series.time - series.time[0]
            if series.loop is not None:
                maneuver = PdControl(kp=series.loop.kp, kd=series.loop.kd,
                                     reference=AngleTable(time=tuple(t), angle=tuple(series.reference)))
            else:
                values = series.command
                if series.hold == "zero_order":  # each sample held up to just before the next
                    t = np.column_stack([t, t + (1.0 - HOLD_EDGE) * series.step]).ravel()
                    values = np.repeat(values, 2)
                table = VoltageTable if series.input == "voltage" else TorqueTable
                maneuver = table(time=tuple(t), **{table.column: tuple(values)})
            self._maneuvers[key] = (series, maneuver)  # the record kept alive with its id
        return self._maneuvers[key][1]

    def simulate(self, values: Mapping[str, float], series: TimeSeries, command: bool = False) -> dict[str, np.ndarray]:
        """The signals ``series`` measures, simulated at its samples (module docstring): physical
        values, before the sensors; NaN after a run that stopped early. With ``command``, also the
        input the hub received (``"command"``: the drive's voltage, or the hub torque), which a
        loop computes."""
        voltage = series.input == "voltage"
        if voltage and self.case.drive is None:
            raise ValueError(f"experiment {series.name}: input voltage for case {self.case.label!r} without a "
                             "drive; allowed: hub_torque, or a case with a drive")
        case, beam, sm = self.system(values, drive=voltage)
        case = dataclasses.replace(case, maneuver=self._maneuver(series), initial=None)
        names = list(series.signals) + (["command"] if command else [])
        return self._run(case, beam, sm, series.time - series.time[0], series.step, names)

    def release(self, values: Mapping[str, float], q2, t_end: float, step: float,
                signals=("deflection_angle",)) -> dict[str, np.ndarray]:
        """A free oscillation with the hub held at rest, released from the modal deflection ``q2``
        (one value per mode, kg1/2 m; the courseware's test), sampled every ``step`` up to ``t_end``
        (s): the ``signals`` and ``"time"``."""
        case, beam, sm = self.system(values, drive=False)
        case = dataclasses.replace(case, maneuver=SpeedTable(time=(0.0, float(t_end)), speed=(0.0, 0.0)),
                                   initial=InitialState(q2=tuple(map(float, q2))))
        t = output_times(t_end, step)
        return {"time": t} | self._run(case, beam, sm, t, step, list(signals))

    def _run(self, case: Case, beam, sm, t: np.ndarray, step: float, names) -> dict[str, np.ndarray]:
        """``case`` run on ``sm`` over the times ``t`` (from 0, every ``step``): the ``names``."""
        case = dataclasses.replace(case, t_end=float(t[-1]), shaper=None)
        finer = ACCELERATION_OVERSAMPLING if "tip_acceleration" in names else 1
        numerics = dataclasses.replace(self.numerics, output_step=step / finer)
        result = run(case, beam, numerics, sm, UNRESOLVED)
        columns = output_columns(case.modes, self.joint)
        grid = t[0] + np.arange((t.size - 1) * finer + 1) * (step / finer)

        def column(name):
            values = result.out[:, columns[name]]
            if values.size == grid.size and np.allclose(result.t, grid, rtol=0.0, atol=1e-6 * step):
                return values
            return np.interp(grid, result.t, values, right=np.nan)

        found = {}
        for name in names:
            if name == "command":
                found[name] = column("hub_voltage" if case.drive is not None else "hub_torque")[::finer]
            else:
                found[name] = self._signal(name, column, grid, beam, sm)[::finer]
        return found

    def _signal(self, signal: str, column, t, beam, sm) -> np.ndarray:
        tip = column("tip_transverse")
        if signal == "hub_angle":
            return column("hub_angle" if self.joint else "theta")
        if signal == "tip_deflection":
            return tip
        if signal == "deflection_angle":
            return tip / beam.L
        theta, rate = column("theta"), column("theta_dot")
        arc = beam.L * theta + tip + sm.rA * (column("hub_angle") if self.joint else theta)
        if not np.all(np.isfinite(arc)):
            return np.full(t.size, np.nan)
        axial_rate = make_interp_spline(t, column("tip_axial"), k=5)(t, 1)
        return make_interp_spline(t, arc, k=5)(t, 2) - rate**2 * tip + 2.0 * rate * axial_rate


__all__ = ["CasePlant", "Equations", "OSCILLATORY"]
