"""``rig.csv``: a servo rig under a sampled LQG controller, in hubbeam's one compiled call and in
the Python loop a user would otherwise write.

    python -m benchmarks.rig [--output DIR] [--repeats 3]

The rig: the flexible link (``hubbeam.model.parameters.FLEXIBLE_LINK``) on CFOAM with
:data:`MODES` modes, turned by the SRV02 drive (``QUANSER_SRV02``: back-EMF, viscous friction,
10 V limit), for :data:`T_END` s at :data:`RATE` Hz with one sample of delay, tracking a
rest-to-rest hub angle table (:data:`REFERENCE`). Sensors: the SRV02's encoder (4096 counts per
turn, counting edges) and a strain gauge reading the link's deflection angle ``v(L) / L`` with
noise and a 12-bit converter. The controller: LQR and a predictor Kalman filter designed with
python-control (``ct.dlqr``, ``ct.dlqe``) on the ZOH model of SFOAM with :data:`DESIGN_MODES`
modes at rest (its input the voltage: the drive's torque gain and damping added).

Rows: ``hubbeam sampled loop`` (:func:`hubbeam.simulation.simulate.run`, the whole run and its
outputs), also on exact sensors; ``python loop`` (per sample, the same sensors and controller in numpy and
``scipy.integrate.solve_ivp`` (Radau) over the sample interval with hubbeam's jitted first-order
right-hand side and Jacobian, :mod:`hubbeam.core.first_order`, on the same plant); ``hubbeam
continuous`` (the same plant under continuous LQR state feedback, a ``state_feedback`` maneuver,
for the cost of sampling). Both sampled runs integrate the same equations; their agreement is
reported with every sensor on (a count of the encoder or of the converter flips where the two
integrations differ by rounding, and the loop carries it on) and with the quantisation off (the
noise kept), where only the integrators' errors part them.
"""

from __future__ import annotations

import argparse
import math
import time
from collections import deque
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path

import control as ct
import numpy as np
import pandas as pd
from scipy.integrate import solve_ivp

from benchmarks.timing import median_time
from hubbeam.configuration.settings import Case, Numerics, simulation_settings
from hubbeam.control.feedback import feedback_law
from hubbeam.core import maneuver as kernel_maneuvers
from hubbeam.core.eom import free_dofs
from hubbeam.core.first_order import first_order_jacobian, first_order_rhs
from hubbeam.core.inputs import SimulationInputs
from hubbeam.core.integrate import integration_problem, output_columns
from hubbeam.core.sampled import quantised
from hubbeam.linear.statespace import linear_model
from hubbeam.model.damping import damping_matrices
from hubbeam.model.drive import QUANSER_SRV02
from hubbeam.model.maneuvers import SensorSpec
from hubbeam.model.matrices import assemble
from hubbeam.model.models import model
from hubbeam.model.parameters import FLEXIBLE_LINK
from hubbeam.simulation.sampled import QUANTISATION_MODES, SampledLoop, reference_array
from hubbeam.simulation.simulate import Resolved, case_matrices, initial_state, run

MODEL, MODES = "CFOAM", 5
DESIGN_MODEL, DESIGN_MODES = "SFOAM", 2
T_END = 15.0
RATE = 500.0
DELAY = 1
RTOL, ATOL = 1e-6, 1e-8
QUADRATURE = 40
DAMPING = {"kind": "modal", "axial": 0.02, "transverse": 0.02}
#: rest-to-rest moves of the hub angle (rad): out, across, back
REFERENCE = {"kind": "angle_table", "time": [0.0, 1.0, 2.5, 6.0, 7.5, 11.0, 12.5, 15.0],
             "angle": [0.0, 0.0, 0.8, 0.8, -0.8, -0.8, 0.0, 0.0]}
ENCODER = 2.0 * math.pi / 4096
#: strain gauge on the deflection angle v(L) / L: noise and a 12-bit converter over +-0.2 rad
GAUGE_NOISE, GAUGE_QUANTUM = 2e-4, 0.4 / 4096
#: the integrator's counters reported
STATS = ("n_steps", "n_rejected", "n_rhs", "n_jacobian", "n_lu")
NUMERICS = Numerics(rtol=RTOL, atol=ATOL, output_step=0.01, max_steps=10**7, step_warning=10**7,
                    divergence_limit=0.5, quadrature_points=QUADRATURE)


def rig_case(maneuver: dict | None = None) -> Case:
    """The benchmark's case (checked once, as the workflow hands it to a job): the tracking
    maneuver gives the reference (a sampled loop replaces its law; the continuous run uses its
    gains)."""
    case = {"name": "rig", "model": MODEL, "modes": MODES, "t_end": T_END, "damping": DAMPING,
            "drive": QUANSER_SRV02.to_dict(),
            "maneuver": maneuver or {"kind": "pd", "kp": 0.0, "kd": 0.0, "reference": REFERENCE}}
    return simulation_settings(case, NUMERICS, FLEXIBLE_LINK.L)[0]


def voltage_plant(sm, model_name: str):
    """The linear model at rest of ``model_name`` on ``sm`` with the voltage as input (the drive's
    ``tau = torque_gain V - hub_damping theta'``) and the sensors' outputs, the hub angle and the
    deflection angle ``v(L) / L``."""
    lin = linear_model(FLEXIBLE_LINK, sm, model_name, 0.0, "free", damping_matrices(DAMPING, sm),
                       outputs=["hub_angle", "tip_deflection"])
    A = lin.A.copy()
    A[:, lin.states.index("theta_dot")] -= QUANSER_SRV02.hub_damping * lin.B[:, 0]
    C = lin.C / np.array([[1.0], [FLEXIBLE_LINK.L]])  # the gauge reads the deflection angle
    return lin, ct.ss(A, QUANSER_SRV02.torque_gain * lin.B, C, 0)


def design(Ts: float):
    """The LQR gains and the predictor Kalman filter on the design model, and the continuous LQR
    gains by state name (the continuous run's)."""
    sm = assemble(FLEXIBLE_LINK, None, DESIGN_MODES, QUADRATURE)
    lin, plant = voltage_plant(sm, DESIGN_MODEL)
    weighed = np.sqrt([50.0, 1e4])[:, None] * plant.C
    Q = weighed.T @ weighed + 1e-4 * np.eye(plant.nstates)  # symmetric to the bit, as ct.dlqr asks
    R = np.eye(1)
    sysd = ct.sample_system(plant, Ts)
    K, _, _ = ct.dlqr(sysd.A, sysd.B, Q * Ts, R * Ts)
    # the input's uncertainty (0.5 V) and the sensors' noise and quantisation as the filter's
    L, _, _ = ct.dlqe(sysd.A, sysd.B, sysd.C, np.eye(1) * 0.5**2,
                      np.diag([ENCODER**2 / 12, GAUGE_NOISE**2 + GAUGE_QUANTUM**2 / 12]))
    K_cont, _, _ = ct.lqr(plant.A, plant.B, Q, R)
    return lin, sysd, K[0], L, dict(zip(lin.states, K_cont[0].tolist()))


def sampled_loop(Ts: float, quantised_sensors: bool = True, seed: int = 1) -> SampledLoop:
    """The benchmark's LQG loop (predictor form: ``E = I``, ``F = 0``, ``Ac = Ad - L Cd``, ``Bc =
    L``, ``Bu = Bd``) on the simulated model's state."""
    lin, sysd, K, L, _ = design(Ts)
    n = MODES
    N = 1 + 2 * n
    encoder = np.zeros(2 * N)
    encoder[0] = 1.0
    gauge = np.zeros(2 * N)
    gauge[1 + n:N] = assemble(FLEXIBLE_LINK, None, MODES, QUADRATURE).f2L / FLEXIBLE_LINK.L
    sensors = (SensorSpec("hub_angle", quantum=ENCODER if quantised_sensors else 0.0, mode="edges"),
               SensorSpec("deflection_angle", noise=GAUGE_NOISE, quantum=GAUGE_QUANTUM if quantised_sensors else 0.0))
    ns = sysd.A.shape[0]
    return SampledLoop(sensors, np.array([encoder, gauge]), sysd.A - L @ sysd.C, L, sysd.B[:, 0], np.eye(ns),
                       np.zeros((ns, 2)), K,
                       [[1.0, 0.0, 0.0], [0.0, 0.0, 0.0]], np.zeros(3), np.zeros(ns), Ts=Ts, D=DELAY,
                       u_max=QUANSER_SRV02.voltage_limit, seed=seed)


def python_loop(loop: SampledLoop) -> dict:
    """The loop as a user writes it: per sample, sensors and controller in numpy, then
    ``solve_ivp`` (Radau, jitted right-hand side and Jacobian) over the sample interval with the
    held voltage; returns the records and the states at the samples."""
    case = rig_case()
    sm = case_matrices(case, FLEXIBLE_LINK, NUMERICS)
    traits = model(MODEL).traits
    free = free_dofs(traits, kernel_maneuvers.HELD, MODES)
    held = np.array([1.0, 0.0, loop.u_init])  # one switch: the value the right-hand side reads
    inputs = SimulationInputs(traits, kernel_maneuvers.HELD, held, damping_matrices(DAMPING, sm), sm,
                              QUANSER_SRV02.packed())
    problem = integration_problem(inputs)
    start = initial_state(case, sm)
    z = np.concatenate([start.y[free], start.v[free]])
    N = 1 + 2 * MODES
    rows = loop.rows[:, np.concatenate([free, N + free])]
    gains = np.array([sensor.gain for sensor in loop.sensors])
    offsets = np.array([sensor.offset for sensor in loop.sensors])
    sigma = np.array([sensor.noise for sensor in loop.sensors])
    quanta = [(sensor.quantum, QUANTISATION_MODES[sensor.mode]) for sensor in loop.sensors]
    reference = reference_array(case.maneuver)
    times = loop.sample_times(T_END)
    noise = loop.noise(times.size)
    xc = loop.xc0.copy()
    pending = deque([loop.u_init] * DELAY)
    applied, states = np.empty(times.size), np.empty((times.size, z.size))
    for k, t in enumerate(times):
        states[k] = z
        sensed = gains * (rows @ z) + offsets
        measured = np.array([quantised(s + w, q, mode) for s, w, (q, mode) in
                             zip(sensed, sigma * noise[k], quanta)])
        rho = np.array(kernel_maneuvers.reference_motion(t, reference, 1))
        e = measured - loop.R_m @ rho
        xhat = loop.E @ xc + loop.F @ e
        u = min(max(loop.U_r @ rho - loop.K @ xhat, -loop.u_max), loop.u_max)
        xc = loop.Ac @ xc + loop.Bc @ e + loop.Bu * (u - loop.U_r @ rho)
        applied[k] = u
        pending.append(u)
        held[2] = pending.popleft()
        if k + 1 < times.size:
            result = solve_ivp(first_order_rhs, (t, times[k + 1]), z, method="Radau", rtol=RTOL, atol=ATOL,
                               jac=first_order_jacobian, args=(problem,))
            z = result.y[:, -1]
    return {"applied": applied, "theta": states[:, 0]}


def rig_rows(repeats: int, budget: float, log=print) -> list[dict]:
    """The rows of ``rig.csv`` (module docstring): the timings on the usual 0.01 s output grid,
    the agreement on an output per sample."""
    Ts = 1.0 / RATE
    loop = sampled_loop(Ts)
    case = rig_case()
    sm = case_matrices(case, FLEXIBLE_LINK, NUMERICS)
    runs = []

    def sampled_run(loop=loop, numerics=NUMERICS):
        runs.append(run(case, FLEXIBLE_LINK, numerics, sm, Resolved(loop=loop)))

    sampled_run()  # compilation, not timed
    wall, count = median_time(sampled_run, repeats, budget)
    sampled = runs[-1].integrator
    log(f"rig: hubbeam sampled loop {wall:.3f} s ({sampled['n_steps']} steps)")
    # the same loop on exact sensors: its commands step smoothly and excite no high modes
    exact = replace(loop, sensors=tuple(replace(sensor, quantum=0.0, noise=0.0) for sensor in loop.sensors))
    exact_wall, exact_count = median_time(lambda: sampled_run(exact), repeats, budget)
    exact_stats = runs[-1].integrator
    _, _, _, _, gains = design(Ts)
    continuous_case = rig_case({"kind": "state_feedback", "reference": REFERENCE, "gains": gains})
    law = feedback_law(continuous_case, sm, FLEXIBLE_LINK)[0]
    continuous = []

    def continuous_run():
        continuous.append(run(continuous_case, FLEXIBLE_LINK, NUMERICS, sm, Resolved(law=law)))

    continuous_run()
    continuous_wall, continuous_count = median_time(continuous_run, repeats, budget)
    log(f"rig: hubbeam continuous state feedback {continuous_wall:.3f} s")
    start = time.perf_counter()
    python = python_loop(loop)
    python_wall = time.perf_counter() - start
    log(f"rig: python loop {python_wall:.1f} s")
    # agreement, on an output per sample: with every sensor as above, and without quantisation,
    # where only the integrators' errors part the two loops
    per_sample = replace(NUMERICS, output_step=Ts)
    theta = output_columns(MODES)["theta"]
    agreement = {}
    smooth = replace(loop, sensors=tuple(replace(sensor, quantum=0.0) for sensor in loop.sensors))
    for label, checked, reference in (("", loop, python), (" unquantised", smooth, None)):
        sampled_run(checked, per_sample)
        reference = reference or python_loop(checked)
        agreement[f"max |theta - theta_python|{label}, rad"] = np.abs(runs[-1].out[:, theta] - reference["theta"]).max()
        agreement[f"max |u - u_python|{label}, V"] = np.abs(runs[-1].records.applied - reference["applied"]).max()
    common = {"model": MODEL, "modes": MODES, "t_end_s": T_END, "rate_hz": RATE, "delay_samples": DELAY,
              "rtol": RTOL, "atol": ATOL}
    rows = [
        {"measurement": "hubbeam sampled loop (simulate.run)", "wall_s": wall, "repeats": count,
         **{name: sampled[name] for name in STATS}, **common},
        {"measurement": "hubbeam sampled loop, exact sensors (no noise, no quantisation)", "wall_s": exact_wall,
         "repeats": exact_count, **{name: exact_stats[name] for name in STATS}, **common},
        {"measurement": "python loop (solve_ivp Radau per sample, jitted rhs and jacobian)",
         "wall_s": python_wall, "repeats": 1, **common},
        {"measurement": "hubbeam continuous state feedback (simulate.run)", "wall_s": continuous_wall,
         "repeats": continuous_count, **{name: continuous[-1].integrator[name] for name in STATS}, **common},
        {"measurement": "speed-up over the python loop", "value": python_wall / wall, **common},
        {"measurement": "cost of sampling (sampled / continuous)", "value": wall / continuous_wall, **common},
        *({"measurement": f"agreement: {name}", "value": float(value), **common} for name, value in agreement.items()),
    ]
    for row in rows[4:]:
        log(f"rig: {row['measurement']}: {row['value']:.4g}")
    return rows


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m benchmarks.rig", description=__doc__.split("\n\n")[0])
    parser.add_argument("--output", type=Path, default=Path("results/benchmarks"),
                        help="directory of rig.csv (default: %(default)s)")
    parser.add_argument("--repeats", type=int, default=3, help="warm runs per timing, median reported")
    parser.add_argument("--timing-budget", type=float, default=10.0, help="seconds of repeated runs per row")
    args = parser.parse_args(argv)
    args.output.mkdir(parents=True, exist_ok=True)
    path = args.output / "rig.csv"
    pd.DataFrame(rig_rows(args.repeats, args.timing_budget)).to_csv(path, index=False)
    print(f"rig: {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
