"""A seeded generator of small, physically sane study configurations (``generate_study(seed)``).

Each draw is one study: a beam (uniform by its products or by the paper's factors, or by sections),
a light or heavy hub, a short or long link, and one to three cases spread over the schema (every
maneuver kind, tip bodies at and inward of the tip, root springs, drives, damping, shapers, steady-spin
starts, state feedback with sampled loops, estimators and sensors), optionally a case grid, a
comparison and the ``control`` section. Sizes are chosen so that a study's whole workflow runs in
seconds: at most three modes, a few vibration periods of simulated time, coarse output steps and
grids of a few points.

The magnitudes follow the beam's own scales, so that every run stays in the small-deflection range
the models describe: the first clamped-free frequency sets the time scale, the rigid-body inertia
about the axis sets the torques and gains, and hub speeds stay well below the first frequency.
"""

from __future__ import annotations

import math

import numpy as np

#: (beta L)^2 of the first clamped-free bending mode of a uniform beam
BETA1_SQUARED = 1.875104068711961**2
#: the SRV02 servo as ``studies/quanser_rotflex.yaml`` writes it (``hubbeam.model.drive.QUANSER_SRV02``)
SRV02 = {"resistance": 2.6, "torque_constant": 7.68e-3, "back_emf_constant": 7.68e-3, "gear_ratio": 70.0,
         "motor_efficiency": 0.69, "gearbox_efficiency": 0.9, "viscous_friction": 0.015, "voltage_limit": 10.0}
MODELS = ("TLAM", "FOAM", "SFOAM", "CFOAM")
OPEN_LOOP = ("prescribed", "torque", "speed_table", "torque_table", "pd")


def _log_uniform(rng: np.random.Generator, low: float, high: float) -> float:
    return float(math.exp(rng.uniform(math.log(low), math.log(high))))


def _round(value: float, digits: int = 4) -> float:
    """``value`` to ``digits`` significant digits (readable configs, exact YAML round trips)."""
    return float(f"{value:.{digits - 1}e}")


class _Scales:
    """The beam's scales the draws are made against."""

    def __init__(self, length, rhoA, EI, hub_inertia):
        self.length = length
        self.omega1 = BETA1_SQUARED * math.sqrt(EI / (rhoA * length**4))  # rad s-1, clamped-free
        self.period = 2 * math.pi / self.omega1
        self.beam_inertia = rhoA * length**3 / 3.0
        self.inertia = hub_inertia + self.beam_inertia
        self.rhoA = rhoA
        self.EI = EI


def _beam(rng: np.random.Generator) -> tuple[dict, _Scales]:
    short = rng.random() < 0.5
    if short:  # a lab link: 0.3-1 m strip
        length = _round(rng.uniform(0.3, 1.0), 3)
        rhoA = _log_uniform(rng, 0.08, 0.6)
        EI = _log_uniform(rng, 0.3, 20.0)
        EA = EI * _log_uniform(rng, 1e5, 3e6)
    else:  # a long arm: 2-10 m
        length = _round(rng.uniform(2.0, 10.0), 3)
        rhoA = _log_uniform(rng, 0.3, 3.0)
        EI = _log_uniform(rng, 3e2, 3e4)
        EA = EI * _log_uniform(rng, 3e3, 1e5)
    beam_inertia = rhoA * length**3 / 3.0
    heavy = rng.random() < 0.5
    hub_inertia = _round(beam_inertia * (_log_uniform(rng, 5.0, 100.0) if heavy else _log_uniform(rng, 0.05, 1.0)))
    hub_radius = 0.0 if rng.random() < 0.5 else _round(rng.uniform(0.0, 0.15) * length, 3)
    rhoA, EI, EA = _round(rhoA), _round(EI), _round(EA)
    beam = {"length": length, "hub_inertia": hub_inertia, "hub_radius": hub_radius}
    form = rng.choice(["products", "factors", "sections"], p=[0.45, 0.25, 0.3])
    if form == "products":
        beam |= {"rhoA": rhoA, "EI": EI, "EA": EA}
    elif form == "factors":  # aluminium-like density and modulus, the section from the products
        density, modulus = 2.7e3, 7.0e10
        beam |= {"density": density, "area": _round(rhoA / density), "youngs_modulus": modulus,
                 "second_moment": _round(EI / modulus)}
        rhoA, EI = density * beam["area"], modulus * beam["second_moment"]
    else:  # tapered or stepped: 2-4 stations, properties within a factor 2 of the mean
        stations = int(rng.integers(2, 5))
        x = np.linspace(0.0, length, stations)
        taper = rng.uniform(0.5, 1.0, stations) if rng.random() < 0.5 else np.linspace(1.0, rng.uniform(0.5, 1.0),
                                                                                         stations)
        beam["sections"] = {"x": [_round(v, 6) for v in x],
                            "rhoA": [_round(rhoA * t) for t in taper],
                            "EI": [_round(EI * t**3) for t in taper],
                            "EA": [_round(EA * t) for t in taper]}
        rhoA, EI = float(np.mean(beam["sections"]["rhoA"])), float(np.mean(beam["sections"]["EI"]))
    return beam, _Scales(length, rhoA, EI, hub_inertia)


def _reference(rng, s: _Scales, t_end: float) -> dict:
    """A reference motion for pd or state feedback ending well before ``t_end``."""
    tf = _round(rng.uniform(0.3, 0.5) * t_end, 3)
    if rng.random() < 0.5:
        return {"kind": "prescribed", "wf": _round(rng.uniform(0.05, 0.3) * s.omega1, 3), "tf": tf}
    angle = _round(rng.uniform(0.1, 0.6), 3)
    return {"kind": "angle_table", "time": [0.0, tf], "angle": [0.0, angle]}


def _maneuver(rng, kind: str, s: _Scales, t_end: float, drive: dict | None, bandwidth: float) -> dict:
    tf = _round(rng.uniform(0.3, 0.5) * t_end, 3)
    if kind == "prescribed":
        return {"kind": "prescribed", "wf": _round(rng.uniform(0.05, 0.35) * s.omega1, 3), "tf": tf}
    if kind == "torque":  # a pulse turning the rigid body by about 0.05-0.3 rad
        return {"kind": "torque", "tau_max": _round(s.inertia * rng.uniform(0.5, 3.0) / tf**2), "tf": tf}
    if kind == "speed_table":
        speed = _round(rng.uniform(0.05, 0.3) * s.omega1, 3)
        return {"kind": "speed_table", "time": [0.0, tf / 2, tf], "speed": [0.0, speed / 2, speed]}
    if kind == "torque_table":
        tau = _round(s.inertia * rng.uniform(0.5, 3.0) / tf**2)
        return {"kind": "torque_table", "time": [0.0, tf / 2, tf], "torque": [tau, -tau, 0.0]}
    if kind == "voltage_table":
        volts = _round(rng.uniform(0.5, 3.0), 3)
        return {"kind": "voltage_table", "time": [0.0, 0.001, tf, tf + 0.001], "voltage": [0.0, volts, volts, 0.0]}
    if kind == "pd":  # the rigid closed loop well below the first bending frequency
        zeta = rng.uniform(0.6, 1.0)
        return {"kind": "pd", "kp": _round(s.inertia * bandwidth**2), "kd": _round(2 * zeta * s.inertia * bandwidth),
                "reference": _reference(rng, s, t_end)}
    raise ValueError(kind)


def _state_feedback(rng, case: dict, s: _Scales, t_end: float, drive: dict | None) -> dict:
    """State feedback: given gains, or an LQR design (continuous, or sampled with an estimator)."""
    reference = _reference(rng, s, t_end)
    maneuver = {"kind": "state_feedback", "reference": reference}
    if reference["kind"] == "prescribed" and rng.random() < 0.5:
        maneuver["feedforward"] = True
    bandwidth = rng.uniform(0.1, 0.3) * s.omega1
    if rng.random() < 0.2 and drive is None:  # given gains on the hub's states: a PD law
        maneuver["gains"] = {"theta": _round(s.inertia * bandwidth**2),
                             "theta_dot": _round(1.6 * s.inertia * bandwidth)}
        return maneuver
    # a design's states are the simulated model's (SFOAM has no axial coordinates)
    design_models = ["SFOAM"] if case["model"] == "SFOAM" else ["TLAM", "FOAM", "SFOAM"]
    design = {"model": str(rng.choice(design_models)), "speed": 0.0,
              "weights": {"hub_angle": _round(s.inertia * bandwidth**2), "hub_speed": _round(0.1 * s.inertia),
                          "tip_deflection": _round(s.inertia * bandwidth**2 / s.length**2)}}
    if reference["kind"] == "prescribed" and rng.random() < 0.5:
        design["speed"] = reference["wf"]
    if drive is not None:
        design["voltage_weight"] = 1.0
    else:
        design["torque_weight"] = 1.0
    maneuver["design"] = design
    if rng.random() < 0.7:
        # a sample time fast against the closed loop: 1/40 to 1/15 of the first bending period
        sample_time = _round(s.period * rng.uniform(1 / 40, 1 / 15), 3)
        sampling: dict = {"sample_time": sample_time, "gain": str(rng.choice(["discrete", "continuous"]))}
        if rng.random() < 0.3:
            sampling["delay"] = float(rng.choice([0.5, 1.0]))
        estimator = rng.choice(["exact", "kalman"], p=[0.5, 0.5])
        if estimator == "kalman":
            sensors = [{"signal": "hub_angle", "quantum": _round(2 * math.pi / 4096)},
                       {"signal": "tip_deflection", "noise": _round(1e-4 * s.length)}]
            sampling["estimator"] = {"kind": "kalman", "form": str(rng.choice(["current", "predictor"])),
                                     "input_noise": _round(0.05 if drive else 0.05 * s.inertia * bandwidth**2)}
            sampling["sensors"] = sensors
            if rng.random() < 0.5:
                sampling["seed"] = int(rng.integers(0, 100))
            # the filter's model keeps only the modes below half the sampling frequency
            sampling["reduce"] = True
        maneuver["sampling"] = sampling
    return maneuver


def _case(rng, s: _Scales, numerics: dict, *, kind: str | None = None) -> dict:
    models = list(MODELS)
    model = str(rng.choice(models))
    t_end = _round(rng.uniform(3.0, 6.0) * s.period, 3)
    # enough outputs for a fit of the residual vibration, few enough to stay small
    case: dict = {"model": model, "t_end": t_end}
    if rng.random() < 0.5:
        case["modes"] = int(rng.integers(1, 4))
    # the SRV02 servo turns lab links only (a long arm's inertia would barely move)
    lab = s.length <= 1.0
    kinds = list(OPEN_LOOP) + (["voltage_table"] if lab else []) + ["state_feedback"]
    kind = kind or str(rng.choice(kinds))
    drive = None
    if kind == "voltage_table" or (lab and kind in ("state_feedback", "prescribed", "pd") and rng.random() < 0.3):
        drive = dict(SRV02)
        case["drive"] = drive
    # the payload: none, at the tip, or inward of it; a point mass or a body
    if rng.random() < 0.5:
        mass = _round(s.rhoA * s.length * _log_uniform(rng, 0.1, 1.0))
        tip = {"mass": mass}
        if rng.random() < 0.5:
            tip["position"] = _round(s.length * rng.uniform(0.6, 0.95), 4)
        if rng.random() < 0.3:
            tip["inertia"] = _round(mass * (0.05 * s.length) ** 2)
        case["tip_mass"] = tip
    # a root spring under every maneuver: a bracket from soft (about the beam's first frequency) to stiff
    if rng.random() < 0.3:
        stiffness = s.inertia * s.omega1**2 * _log_uniform(rng, 1.0, 100.0)
        spring = {"stiffness": _round(stiffness)}
        if rng.random() < 0.5:
            spring["damping"] = _round(0.02 * stiffness / s.omega1)
        if rng.random() < 0.3:
            spring["clamp_inertia"] = _round(0.01 * s.beam_inertia)
        case["root_spring"] = spring
    # an LQR design needs every undamped mode moved by the torque: the axial modes at rest are not,
    # so a designed state feedback always has modal damping
    if kind == "state_feedback" or rng.random() < 0.5:
        if kind == "state_feedback" or rng.random() < 0.6:
            case["damping"] = {"kind": "modal", "axial": _round(rng.uniform(0.005, 0.05), 3),
                               "transverse": _round(rng.uniform(0.005, 0.05), 3)}
        else:
            case["damping"] = {"kind": "rayleigh", "mass_coefficient": 0.0,
                               "stiffness_coefficient": _round(0.02 / s.omega1)}
    if kind == "state_feedback":
        case["maneuver"] = _state_feedback(rng, case, s, t_end, drive)
    else:
        bandwidth = rng.uniform(0.1, 0.3) * s.omega1
        case["maneuver"] = _maneuver(rng, kind, s, t_end, drive, bandwidth)
    if kind == "speed_table" and rng.random() < 0.4:  # a steady-spin start at the table's first speed
        speed = case["maneuver"]["speed"]
        speed[0] = _round(speed[-1] * rng.uniform(0.2, 0.8), 3)
        case["initial"] = {"hub_speed": speed[0]}
    elif kind in ("torque", "torque_table") and rng.random() < 0.3:
        case["initial"] = {"hub_speed": _round(rng.uniform(0.02, 0.2) * s.omega1, 3)}
    if kind in ("prescribed", "torque") and rng.random() < 0.3:
        case["shaper"] = {"kind": str(rng.choice(["ZV", "ZVD", "EI"]))}
        if rng.random() < 0.5:
            case["shaper"]["frequencies"] = [_round(s.omega1 * rng.uniform(0.8, 1.2))]
    return case


def generate_study(seed: int) -> dict:
    """The study configuration of ``seed`` (module docstring): a plain mapping, as read from YAML."""
    rng = np.random.default_rng(seed)
    beam, s = _beam(rng)
    output_step = _round(s.period / rng.uniform(8.0, 16.0), 3)
    numerics = {"modes": int(rng.integers(1, 4)), "quadrature_points": 16, "rtol": 1.0e-6, "atol": 1.0e-9,
                "output_step": output_step, "max_steps": 200000, "step_warning": 100000}
    top = _round(0.5 * s.omega1, 3)
    config: dict = {
        "study": {"name": f"generated_{seed}", "title": f"Generated study {seed}"},
        "beam": beam,
        "numerics": numerics,
        "eigen": {"speeds": {"start": 0.0, "stop": top, "num": 3},
                  "positions": {"start": 0.0, "stop": beam["length"], "num": 3},
                  "critical_speed_search_max": _round(2.0 * s.omega1, 3)},
        "linear": {"speeds": {"start": 0.0, "stop": top, "num": 3}, "bode_speeds": [0.0],
                   "frequencies": {"start": _round(0.1 * s.omega1), "stop": _round(30 * s.omega1), "num": 40},
                   "shapes": 2},
    }
    cases = {}
    for index in range(int(rng.integers(1, 3))):
        cases[f"case{index + 1}"] = _case(rng, s, numerics)
    config["cases"] = cases
    if rng.random() < 0.3:  # a grid over a prescribed spin-up's final speed
        base = _case(rng, s, numerics, kind="prescribed")
        speeds = sorted({_round(rng.uniform(0.05, 0.3) * s.omega1, 2) for _ in range(2)})
        config["case_grids"] = {"spin": {"name": "spin_w{speed}", "case": base,
                                         "axes": [{"speed": {"keys": ["maneuver.wf"], "values": speeds}}]}}
    if len(cases) >= 2 and rng.random() < 0.7:
        config["study"]["comparisons"] = {"overlay": sorted(cases)[:2]}
    sampled = [name for name, case in cases.items()
               if "sampling" in case["maneuver"] and "design" in case["maneuver"]]
    if sampled and rng.random() < 0.6:
        control: dict = {}
        sample_time = cases[sampled[0]]["maneuver"]["sampling"]["sample_time"]
        # the sweep reads a design's states exactly: not those of a design reduced to what it resolves
        swept = [name for name in sampled if not cases[name]["maneuver"]["sampling"].get("reduce")]
        if swept and rng.random() < 0.7:
            control["sample_time"] = {"cases": swept, "sample_times": {
                "start": _round(sample_time / 2), "stop": _round(sample_time * 8), "num": 4}, "delays": [0, 1]}
        if not control or rng.random() < 0.5:
            ranges = {"tip_mass": [0.0, _round(0.3 * s.rhoA * s.length)], "EI_factor": [0.5, 2.0]}
            control["robustness"] = {"cases": sampled, "points": 3, "ranges": ranges}
        config["control"] = control
    return config
