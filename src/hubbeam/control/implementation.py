"""A sampled controller as one discrete system for a rig's software, with its plant, in files.

The loop of :class:`hubbeam.control.sampled.SampledController` without the saturation is one
discrete linear system from the sensors' readings ``m`` (sensor units) and the reference ``rho =
(theta_r, theta_r', theta_r'')`` to the command ``u``:

    u_k      = Cc xc_k + Dm m_k + Dr rho_k,
    xc_{k+1} = Acl xc_k + Bm m_k + Br rho_k,

    Cc = -K E,     Dm = -K F,     Dr = U_r + K F R_m,
    Acl = Ac - Bu K E,     Bm = Bc - Bu K F,     Br = (Bu K F - Bc) R_m

(``u - U_r rho = -K (E xc + F (m - R_m rho))`` fed back into ``xc``). :func:`controller_system`
gives it as a python-control system with ``dt = Ts``, inputs the sensors' signals then
``reference_angle, reference_speed, reference_acceleration``, output the design model's input
(``voltage`` for a drive). :func:`plant_system` is the design's discrete plant from that input to
the sensors' readings (``gain c`` on its states), in the same units, so that the two close the
loop as on the rig. :func:`write_implementation` writes both as a MATLAB file
(``scipy.io.savemat``: ``Ac, Bc, Cc, Dc`` and ``Ap, Bp, Cp, Dp``, ``Ts``, the names as cell arrays,
the sensors' gains and units, ``u_max``) and as JSON (the same under ``controller`` and
``plant``); :func:`read_implementation` loads either back as python-control systems.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np

from hubbeam.control.sampled import REFERENCE
from hubbeam.control.sampling import measurement_rows, sensor_unit
from hubbeam.linear.export import cell
from hubbeam.linear.statespace import INPUT_UNITS
from hubbeam.results.io import staged, write_text

#: what the files say they hold
FORMAT = "hubbeam sampled controller and plant, discrete state space x[k+1] = A x[k] + B u[k], y[k] = C x[k] + D u[k]"


def controller_matrices(controller) -> tuple[np.ndarray, ...]:
    """``(Acl, B, Cc, D)`` of the controller as one system (module docstring); ``B = [Bm, Br]``,
    ``D = [Dm, Dr]`` (one row: the command)."""
    c = controller
    K = np.asarray(c.K)[None, :]
    Bu = np.asarray(c.Bu).reshape(-1, 1)
    KE, KF = K @ c.E, K @ c.F
    Acl = c.Ac - Bu @ KE
    B = np.hstack([c.Bc - Bu @ KF, (Bu @ KF - c.Bc) @ c.R_m])
    D = np.hstack([-KF, c.U_r[None, :] + KF @ c.R_m])
    return Acl, B, -KE, D


def _signal_names(controller) -> list[str]:
    return [sensor.signal for sensor in controller.sensors]


def controller_system(controller):
    """The controller of ``controller`` (a ``SampledController``) as a discrete python-control system."""
    import control as ct

    A, B, C, D = controller_matrices(controller)
    return ct.ss(A, B, C, D, dt=controller.Ts, states=list(controller.controller_states) or None,
                 inputs=_signal_names(controller) + list(REFERENCE), outputs=list(controller.design.inputs),
                 name="controller")


def plant_system(controller):
    """The design's discrete plant from its input to the sensors' readings (sensor units)."""
    import control as ct

    dm = controller.design
    rows = _reading_rows(controller)
    return ct.ss(dm.A, dm.B, rows, np.zeros((rows.shape[0], dm.B.shape[1])), dt=dm.Ts, states=list(dm.states),
                 inputs=list(dm.inputs), outputs=_signal_names(controller), name="plant")


def _reading_rows(controller) -> np.ndarray:
    """The sensors' readings on the design model's states: ``gain c`` of a signal
    (``hubbeam.control.sampling.measurement_rows``), or the state itself for an exact reading of a
    state (``hubbeam.control.sampled.state_controller``)."""
    dm = controller.design
    return np.array([np.eye(dm.A.shape[0])[dm.states.index(sensor.signal)] if sensor.signal in dm.states
                     else measurement_rows(dm, [sensor])[0] for sensor in controller.sensors])


def _record(system, units_in, units_out) -> dict:
    return {"A": np.asarray(system.A).tolist(), "B": np.asarray(system.B).tolist(), "C": np.asarray(system.C).tolist(),
            "D": np.asarray(system.D).tolist(), "states": list(system.state_labels),
            "inputs": list(system.input_labels), "outputs": list(system.output_labels), "input_units": units_in,
            "output_units": units_out, "n_states": int(system.nstates)}


def write_implementation(controller, path: os.PathLike | str) -> tuple[Path, Path]:
    """Write the controller and the plant (module docstring) to ``path`` with the suffixes ``.mat``
    and ``.json``; return both paths."""
    from scipy.io import savemat

    base = Path(path)
    mat, text = base.with_suffix(".mat"), base.with_suffix(".json")
    K, P = controller_system(controller), plant_system(controller)
    command_unit = INPUT_UNITS.get(controller.design.inputs[0], "")
    sensor_units = [sensor_unit(sensor) for sensor in controller.sensors]
    reference_units = ["rad", "rad s-1", "rad s-2"]
    document = {
        "format": FORMAT, "kind": controller.kind, "sample_time_s": controller.Ts,
        "input_delay_samples": controller.D, "u_max": controller.u_max if np.isfinite(controller.u_max) else None,
        "saturation": "ignored in these systems: clip the command to +-u_max on the rig",
        "sensors": [{"signal": sensor.signal, "gain": sensor.gain, "unit": sensor_unit(sensor), "sigma": sensor.noise,
                     "quantum": sensor.quantum} for sensor in controller.sensors],
        "controller": _record(K, sensor_units + reference_units, [command_unit]),
        "plant": _record(P, [command_unit], sensor_units),
    }
    contents = {"Ac": K.A, "Bc": K.B, "Cc": K.C, "Dc": K.D, "Ap": P.A, "Bp": P.B, "Cp": P.C, "Dp": P.D,
                "Ts": controller.Ts, "input_delay_samples": controller.D, "u_max": controller.u_max,
                "controller_states": cell(K.state_labels), "controller_inputs": cell(K.input_labels),
                "controller_outputs": cell(K.output_labels), "plant_states": cell(P.state_labels),
                "plant_inputs": cell(P.input_labels), "plant_outputs": cell(P.output_labels),
                "sensor_gains": np.array([sensor.gain for sensor in controller.sensors]),
                "sensor_units": cell(sensor_units), "command_unit": command_unit, "kind": controller.kind}
    with staged(mat) as (stand_in,):
        savemat(stand_in, contents, oned_as="column")
    write_text(text, json.dumps(document, indent=1))
    return mat, text


def read_implementation(path: os.PathLike | str):
    """``(controller, plant)`` python-control systems from a file of :func:`write_implementation`
    (``.json`` or ``.mat``)."""
    import control as ct

    path = Path(path)
    if path.suffix == ".json":
        document = json.loads(path.read_text(encoding="utf-8"))
        Ts = document["sample_time_s"]

        def system(record, name):
            n, m, p = record["n_states"], len(record["inputs"]), len(record["outputs"])
            A = np.array(record["A"], dtype=float).reshape(n, n)
            B = np.array(record["B"], dtype=float).reshape(n, m)
            C = np.array(record["C"], dtype=float).reshape(p, n)
            return ct.ss(A, B, C, np.array(record["D"], dtype=float).reshape(p, m), dt=Ts,
                         states=record["states"] or None, inputs=record["inputs"], outputs=record["outputs"], name=name)

        return system(document["controller"], "controller"), system(document["plant"], "plant")
    from scipy.io import loadmat

    data = loadmat(path)
    Ts = float(data["Ts"].squeeze())

    def names(key):
        return [str(item[0]) for item in data[key].ravel()]

    def system(prefix, who, name):
        A, B, C, D = (np.atleast_2d(data[f"{letter}{prefix}"]).astype(float) for letter in "ABCD")
        n = len(names(f"{who}_states"))
        m, p = len(names(f"{who}_inputs")), len(names(f"{who}_outputs"))
        return ct.ss(A.reshape(n, n), B.reshape(n, m), C.reshape(p, n), D.reshape(p, m), dt=Ts,
                     states=names(f"{who}_states") or None, inputs=names(f"{who}_inputs"),
                     outputs=names(f"{who}_outputs"), name=name)

    return system("c", "controller", "controller"), system("p", "plant", "plant")


__all__ = ["FORMAT", "controller_matrices", "controller_system", "plant_system", "read_implementation",
           "write_implementation"]
