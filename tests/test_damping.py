"""Damping of the elastic coordinates (``hubbeam.model.damping``).

* modal damping: after a short spin-up and stop the hub is held (zero speed) and the first
  bending mode of a beam with a tip mass (non-diagonal ``M2``) decays with the logarithmic
  decrement ``2 pi zeta / sqrt(1 - zeta^2)`` of its set ratio;
* ``energy(t) - energy(0) = work(t) - dissipated_energy(t)`` with modal and Rayleigh damping;
* the modal matrices give ``Phi^T C Phi = diag(2 zeta omega)`` (independent of the kernels);
* zero damping and no damping give bit-identical runs;
* each bad input names its key, its value and what is allowed.
"""

import math

import numpy as np
import pytest
from scipy.linalg import eigh

from hubbeam.configuration.load import ConfigError
from hubbeam.configuration.settings import simulation_settings
from hubbeam.model.damping import damping_matrices
from hubbeam.model.matrices import assemble
from hubbeam.model.parameters import BeamParameters, TipMass
from hubbeam.simulation.simulate import simulate


@pytest.fixture(scope="module")
def setup(_study_config):
    return BeamParameters.from_config(_study_config), _study_config["numerics"]


TIP = {"mass": 0.5, "position": 8.0}
STOP = {"kind": "speed_table", "time": [0.0, 0.5, 1.0], "speed": [0.0, 0.5, 0.0]}


def _case(maneuver, damping=None, model="FOAM", t_end=4.0, modes=3):
    case = {"name": "d", "model": model, "modes": modes, "t_end": t_end, "maneuver": maneuver,
            "tip_mass": TIP}
    return case | ({"damping": damping} if damping is not None else {})


def test_modal_matrices_are_diagonal_in_the_mass_normalised_modes(setup):
    params, numerics = setup
    sm = assemble(params, TipMass(**TIP), 4, numerics["quadrature_points"])
    C = damping_matrices({"kind": "modal", "axial": 0.01, "transverse": 0.03}, sm)
    for zeta, M, K, Cb in ((0.01, sm.M1, sm.K1, C[0]), (0.03, sm.M2, sm.K2, C[1])):
        assert np.abs(M - np.diag(np.diag(M))).max() > 0  # the tip mass couples the modes
        omega2, phi = eigh(K, M)
        np.testing.assert_allclose(phi.T @ Cb @ phi, np.diag(2 * zeta * np.sqrt(omega2)),
                                   atol=1e-10 * 2 * zeta * np.sqrt(omega2.max()))


@pytest.mark.parametrize("zeta", [0.02, 0.1])
def test_modal_damping_gives_the_logarithmic_decrement_of_the_ratio(setup, zeta):
    params, numerics = setup
    numerics = dict(numerics, output_step=0.001, rtol=1e-10, atol=1e-12)
    damping = {"kind": "modal", "axial": 0.0, "transverse": zeta}
    ds = simulate(_case(STOP, damping, t_end=12.0), params, numerics)
    sm = assemble(params, TipMass(**TIP), 3, numerics["quadrature_points"])
    phi = eigh(sm.K2, sm.M2)[1]
    eta = ds.q2.values @ (sm.M2 @ phi[:, 0])  # first bending mode's coordinate
    free = ds.time.values > STOP["time"][-1] + 0.05
    x = eta[free]
    peaks = []
    for k in np.flatnonzero((x[1:-1] > x[:-2]) & (x[1:-1] >= x[2:])) + 1:
        a, b, c = x[k - 1], x[k], x[k + 1]  # parabola through three samples
        peaks.append(b - (a - c) ** 2 / (8 * (a - 2 * b + c)))
    peaks = np.array(peaks)
    assert peaks.size >= 3
    decrement = np.log(peaks[:-1] / peaks[1:])
    expected = 2 * np.pi * zeta / np.sqrt(1 - zeta ** 2)
    np.testing.assert_allclose(decrement, expected, rtol=2e-3)
    assert ds.dissipated_energy.values[-1] > 0


@pytest.mark.parametrize("model", ["FOAM", "CFOAM"])
@pytest.mark.parametrize("damping", [{"kind": "modal", "axial": 0.05, "transverse": 0.1},
                                     {"kind": "rayleigh", "mass_coefficient": 0.2,
                                      "stiffness_coefficient": 2e-3}])
@pytest.mark.parametrize("maneuver", [
    {"kind": "torque_table", "time": [0.0, 1.0, 2.0], "torque": [0.0, 60.0, 0.0]},
    {"kind": "pd", "kp": 400.0, "kd": 100.0,
     "reference": {"kind": "prescribed", "wf": 1.0, "tf": 2.0}},
    STOP,
])
def test_energy_change_is_work_less_dissipation(setup, model, damping, maneuver):
    """Simpson's rule on the 0.005 s grid, as in test_maneuvers; the dissipation rate also
    carries the fast axial and higher bending modes (measured up to 1e-7 of the largest work,
    bound 1e-6)."""
    params, numerics = setup
    ds = simulate(_case(maneuver, damping, model), params, dict(numerics, output_step=0.005))
    change = ds.energy.values - ds.energy.values[0]
    balance = ds.work.values - ds.dissipated_energy.values
    assert ds.dissipated_energy.values[-1] > 1e-3 * np.abs(ds.work.values).max()
    np.testing.assert_allclose(change, balance, rtol=0,
                               atol=1e-6 * np.abs(ds.work.values).max())


def test_zero_damping_is_no_damping(setup):
    params, numerics = setup
    maneuver = {"kind": "prescribed", "wf": 1.0, "tf": 2.0}
    plain = simulate(_case(maneuver, t_end=3.0), params, numerics)
    zero = simulate(_case(maneuver, {"kind": "rayleigh", "mass_coefficient": 0.0,
                                     "stiffness_coefficient": 0.0}, t_end=3.0), params, numerics)
    for name in ("tip_transverse", "hub_torque", "energy", "work"):
        np.testing.assert_array_equal(plain[name].values, zero[name].values)


@pytest.mark.parametrize("damping,key,fragments", [
    ({"kind": "modal", "axial": 1.0, "transverse": 0.1},
     "damping.axial", ["got 1.0", "allowed: a number >= 0 and < 1"]),
    ({"kind": "modal", "axial": 0.1, "transverse": -0.01},
     "damping.transverse", ["got -0.01", "allowed: a number >= 0 and < 1"]),
    ({"kind": "rayleigh", "mass_coefficient": -1.0, "stiffness_coefficient": 0.0},
     "damping.mass_coefficient", ["got -1.0", "allowed: a number >= 0"]),
    ({"kind": "rayleigh", "mass_coefficient": 0.0, "stiffness_coefficient": -1e-4},
     "damping.stiffness_coefficient", ["got -0.0001", "allowed: a number >= 0"]),
    ({"kind": "rayleigh", "mass_coefficient": 0.0, "stiffness_coefficient": math.inf},
     "damping.stiffness_coefficient", ["got inf", "allowed: a finite number"]),
    ({"kind": "viscous"}, "damping.kind", ["got 'viscous'", "allowed: one of modal, rayleigh"]),
    ({"kind": "modal", "axial": 0.1, "transverse": 0.1, "bending": 0.1},
     "damping.bending", ["got 0.1", "not allowed when kind is 'modal' (allowed keys: kind, axial, transverse, "
                                                           "transverse_modes)"]),
])
def test_a_bad_damping_gives_one_clear_error(setup, damping, key, fragments):
    """The API's bare case is checked by the configuration's one pass: one problem, at the key."""
    _, numerics = setup
    with pytest.raises(ConfigError) as error:
        simulation_settings(_case(STOP, damping), numerics, 8.0)
    (problem,) = error.value.problems
    assert problem.path == "cases.d." + key and all(fragment in problem.text for fragment in fragments), problem
