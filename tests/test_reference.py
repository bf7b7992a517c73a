"""The fast path (Radau IIA kernel) against the slow scipy reference (``hubbeam.simulation.reference``).

* ``pure_python`` yields a right-hand side free of compiled code that agrees with the kernel;
* on FOAM, w_f = 2.8 rad/s, t_f = 30 s, 0-50 s (Fig. 5) the fast path at the configured
  tolerances agrees with scipy's Radau at rtol 1e-12 in tip deflection to ten times the
  configured rtol relative to the largest deflection (the rule of test_simulate's convergence
  test: the global error of either run is well below its rtol);
* so do CFOAM with a tip mass and the torque-driven FOAM and SFOAM (whose right-hand sides in the
  fast path are built differently from the reference's general mass-matrix solve);
* so do shaped commands (a torque, a hub motion, a controller's reference);
* so do runs on a compliant root (the hub angle appended, the spring between hub and root);
* both paths record the divergence of TLAM at w_f = 3.5 rad/s at the same time.

The 50 s reference uses the jitted accelerations (the pure-Python ones take ~50 s there); the
pure-Python evaluation is checked against them state by state instead.
"""

import numpy as np
import pytest
from numba.core.dispatcher import Dispatcher
from synthetic_results import case_of

from hubbeam.core import eom
from hubbeam.core.inputs import SimulationInputs
from hubbeam.model.maneuvers import maneuver_from_dict
from hubbeam.model.matrices import assemble
from hubbeam.model.models import MODELS
from hubbeam.model.parameters import BeamParameters
from hubbeam.model.root import RootSpring, joint_inputs
from hubbeam.model.shapers import Shaper
from hubbeam.simulation.reference import pure_python, reference_simulation
from hubbeam.simulation.simulate import Resolved, kernel_matrices, simulate


@pytest.fixture(scope="module")
def setup(_study_config):
    return BeamParameters.from_config(_study_config), _study_config["numerics"], _study_config


def _reachable_functions(func, seen=None):
    seen = set() if seen is None else seen
    if func in seen:
        return seen
    seen.add(func)
    for value in func.__globals__.values():
        if callable(value) and getattr(value, "__module__", "").startswith("hubbeam"):
            if isinstance(value, Dispatcher):
                seen.add(value)
            elif hasattr(value, "__globals__"):
                _reachable_functions(value, seen)
    return seen


def _assert_close_runs(fast, reference, rtol, variable, mask=slice(None)):
    """``variable`` of two runs agrees to ``10 rtol`` of its largest magnitude (``rtol`` the
    looser of the two runs' tolerances)."""
    ref = reference[variable][mask]
    scale = float(abs(ref).max())
    assert scale > 0.0
    assert float(abs(fast[variable][mask] - ref).max()) <= 10 * rtol * scale, variable


def test_pure_python_accelerations_call_no_compiled_code_and_agree(setup):
    params, _, _ = setup
    plain = pure_python(eom.accelerations)
    assert not any(isinstance(f, Dispatcher) for f in _reachable_functions(plain))
    sm = kernel_matrices(assemble(params, None, 2, 16))
    rng = np.random.default_rng(7)
    C = np.stack([0.3 * np.eye(2), np.array([[0.2, 0.05], [0.05, 0.4]])])
    maneuvers = [{"kind": "prescribed", "wf": 2.8, "tf": 30.0},
                 {"kind": "torque", "tau_max": 50.0, "tf": 30.0},
                 {"kind": "speed_table", "time": [0.0, 10.0, 30.0], "speed": [0.0, 2.0, 1.0]},
                 {"kind": "torque_table", "time": [0.0, 10.0, 30.0], "torque": [0.0, 5.0, 1.0]},
                 {"kind": "pd", "kp": 3.0, "kd": 1.0,
                  "reference": {"kind": "angle_table", "time": [0.0, 20.0], "angle": [0.0, 1.0]}}]
    for model in MODELS.values():
        for kind, mp in (maneuver_from_dict(m).kernel_parameters() for m in maneuvers):
            inputs = SimulationInputs(model.traits, kind, mp, C, sm)
            free = eom.free_dofs(model.traits, kind, 2)
            for _ in range(3):
                t = rng.uniform(0, 40)
                y, v = rng.normal(scale=0.1, size=(2, 5))
                a_fast, a_plain = np.zeros(5), np.zeros(5)
                out_fast = eom.accelerations(inputs, t, y.copy(), v.copy(), free, a_fast)
                out_plain = plain(inputs, t, y.copy(), v.copy(), free, a_plain)
                assert np.allclose(a_plain, a_fast, rtol=1e-12, atol=1e-12)
                assert np.allclose(out_plain, out_fast, rtol=1e-12, atol=1e-12)


def test_fast_path_agrees_with_the_reference_on_fig5_foam(setup):
    params, numerics, config = setup
    case = case_of(config, "fig05_foam_wf2p8")
    reference = reference_simulation(case, params, numerics, rtol=1e-12, atol=1e-14,
                                     pure_python_rhs=False)
    fast = simulate(case, params, numerics)
    assert reference.attrs["integrator_status"] == fast.attrs["integrator_status"] == "success"
    np.testing.assert_array_equal(reference.time, fast.time)
    _assert_close_runs(fast, reference, numerics["rtol"], "tip_transverse")
    assert float(abs(reference.tip_transverse).max()) > 0.1  # a real deflection was compared


@pytest.mark.parametrize("name,changes", [
    # CFOAM (pre-contracted tensors) with a tip mass, a short spin-up
    ("fig04_cfoam", {"maneuver": {"kind": "prescribed", "wf": 3.0, "tf": 10.0}, "t_end": 15.0,
                     "tip_mass": {"mass": 0.5, "position": 8.0}}),
    # free hub: FOAM and SFOAM (Schur complement of the modal mass), SFOAM with a tip mass
    ("tab3_foam_tau200", {"t_end": 12.0}),
    ("fig08_sfoam_tau200", {"t_end": 12.0, "tip_mass": {"mass": 0.1, "position": 6.0}}),
    # PD feedback on an angle table, modal damping; CFOAM under a damped speed table
    ("tab3_foam_tau200", {"t_end": 8.0, "damping": {"kind": "modal", "axial": 0.02,
                                                    "transverse": 0.05},
                          "maneuver": {"kind": "pd", "kp": 2000.0, "kd": 800.0,
                                       "reference": {"kind": "angle_table", "time": [0.0, 4.0],
                                                     "angle": [0.0, 1.0]}}}),
    ("fig04_cfoam", {"t_end": 10.0, "tip_mass": {"mass": 0.5, "position": 8.0},
                     "damping": {"kind": "rayleigh", "mass_coefficient": 0.1,
                                 "stiffness_coefficient": 1e-3},
                     "maneuver": {"kind": "speed_table", "time": [0.0, 4.0, 8.0],
                                  "speed": [0.0, 1.0, 0.5]}}),
])
def test_fast_right_hand_sides_agree_with_the_reference(setup, name, changes):
    """The integrator's right-hand sides (core.foam_rhs, core.cfoam_rhs) against scipy on the
    general mass-matrix equations (CFOAM's point-cloud sum), over whole runs."""
    params, numerics, config = setup
    case = case_of(config, name).to_dict() | changes
    reference = reference_simulation(case, params, numerics, rtol=1e-10, atol=1e-12,
                                     pure_python_rhs=False)
    fast = simulate(case, params, numerics)
    assert reference.attrs["integrator_status"] == fast.attrs["integrator_status"] == "success"
    rtol = max(numerics["rtol"], 1e-10)
    _assert_close_runs(fast, reference, rtol, "tip_transverse")
    _assert_close_runs(fast, reference, rtol, "theta")
    assert float(abs(reference.tip_transverse).max()) > 0.01  # a real deflection was compared


#: a command shaper whose delayed copies overlap the commands (hubbeam.model.shapers)
SHAPER = Shaper([0.0, 0.7, 1.9], [0.3, 0.5, 0.2], "three impulses")


@pytest.mark.parametrize("name,changes", [
    ("tab3_foam_tau200", {"t_end": 12.0}),  # the shaped torque on a free hub
    ("fig04_cfoam", {"maneuver": {"kind": "prescribed", "wf": 3.0, "tf": 10.0}, "t_end": 15.0,
                     "tip_mass": {"mass": 0.5, "position": 8.0}}),  # the shaped hub motion
    ("tab3_foam_tau200", {"t_end": 8.0, "maneuver": {"kind": "pd", "kp": 2000.0, "kd": 800.0,
                                                     "reference": {"kind": "angle_table", "time": [0.0, 4.0],
                                                                   "angle": [0.0, 1.0]}}}),  # shaped reference
])
def test_shaped_runs_agree_with_the_reference(setup, name, changes):
    """A shaped command (hubbeam.core.shaping) in the integrator's right-hand sides and the stops
    against scipy on the general equations under the same shaper, over whole runs."""
    params, numerics, config = setup
    case = case_of(config, name).to_dict() | changes
    reference = reference_simulation(case, params, numerics, rtol=1e-10, atol=1e-12,
                                     pure_python_rhs=False, shaper=SHAPER)
    fast = simulate(case, params, numerics, resolve=lambda case, sm: Resolved(shaper=SHAPER))
    assert reference.attrs["integrator_status"] == fast.attrs["integrator_status"] == "success"
    rtol = max(numerics["rtol"], 1e-10)
    _assert_close_runs(fast, reference, rtol, "tip_transverse")
    _assert_close_runs(fast, reference, rtol, "theta")
    assert float(abs(reference.tip_transverse).max()) > 0.01  # a real deflection was compared


def test_both_paths_record_the_divergence_of_tlam_at_the_same_time(setup):
    params, numerics, config = setup
    case = case_of(config, "fig05_tlam_wf3p5", modes=1)
    reference = reference_simulation(case, params, numerics, rtol=1e-10, atol=1e-12,
                                     pure_python_rhs=False)
    fast = simulate(case, params, numerics)
    assert reference.attrs["diverged"] == fast.attrs["diverged"] == 1
    # the reference locates the crossing of the limit; the fast path stops after the step
    # that crossed it
    lag = fast.attrs["diverged_at_s"] - reference.attrs["diverged_at_s"]
    assert 0.0 <= lag < 0.5
    valid = (fast.time < reference.attrs["diverged_at_s"] - 1.0).values
    _assert_close_runs(fast, reference, max(numerics["rtol"], 1e-10), "tip_transverse", valid)


@pytest.mark.parametrize("name,changes", [
    ("tab3_foam_tau200", {"t_end": 8.0}),  # free hub: the two hub rows of the modal mass
    ("fig04_cfoam", {"maneuver": {"kind": "prescribed", "wf": 3.0, "tf": 10.0}, "t_end": 12.0,
                     "tip_mass": {"mass": 0.5, "position": 8.0}}),  # the prescribed hub, the link on the spring
    ("fig08_sfoam_tau200", {"t_end": 8.0, "damping": {"kind": "modal", "axial": 0.02, "transverse": 0.05},
                            "maneuver": {"kind": "pd", "kp": 2000.0, "kd": 800.0,
                                         "reference": {"kind": "angle_table", "time": [0.0, 4.0],
                                                       "angle": [0.0, 1.0]}}}),  # PD on the hub's angle
])
def test_runs_on_a_root_spring_agree_with_the_reference(setup, name, changes):
    """A compliant root (``RootSpring``: the hub angle appended, the hinge's terms, spring and
    damper) in the integrator's right-hand sides against scipy on the general equations, over whole
    runs: the tip, the root's angle and the hub's, and the plain-Python accelerations with the joint
    against the jitted ones."""
    params, numerics, config = setup
    spring = RootSpring(5e3, 20.0, 100.0)
    case = case_of(config, name).to_dict() | changes | {"root_spring": spring.to_dict()}
    reference = reference_simulation(case, params, numerics, rtol=1e-10, atol=1e-12, pure_python_rhs=False)
    fast = simulate(case, params, numerics)
    assert reference.attrs["integrator_status"] == fast.attrs["integrator_status"] == "success"
    rtol = max(numerics["rtol"], 1e-10)
    for variable in ("tip_transverse", "theta", "hub_angle"):
        _assert_close_runs(fast, reference, rtol, variable)
    assert float(abs(fast.hub_angle - fast.theta).max()) > 1e-4  # the spring did twist
    sm = kernel_matrices(assemble(params, None, 2, 16))
    link, root = joint_inputs(sm, spring)
    kind, mp = maneuver_from_dict(case["maneuver"]).kernel_parameters()
    inputs = SimulationInputs(MODELS[case["model"]].traits, kind, mp, np.zeros((2, 2, 2)), link, root=root)
    free = eom.free_coordinates(inputs)
    y, v = np.random.default_rng(3).normal(scale=0.1, size=(2, 6))
    a_fast, a_plain = np.zeros(6), np.zeros(6)
    out_fast = eom.accelerations(inputs, 2.0, y.copy(), v.copy(), free, a_fast)
    out_plain = pure_python(eom.accelerations)(inputs, 2.0, y.copy(), v.copy(), free, a_plain)
    assert np.allclose(a_plain, a_fast, rtol=1e-12, atol=1e-12)
    assert np.allclose(out_plain, out_fast, rtol=1e-12, atol=1e-12)
