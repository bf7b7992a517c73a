"""Per-mode transverse damping ratios (``damping.transverse_modes``, ``hubbeam.model.damping``).

* each listed ratio is its mode's, by ascending frequency; the modes beyond the list keep
  ``transverse``, and a list longer than the modes is cut;
* a configuration without the list gives the same matrices, bit for bit, as before it existed
  (the single ratio through the same call), and the case records it as before;
* the list is checked with the configuration, and a case with it round-trips through its mapping.
"""

import numpy as np
import pytest
from scipy.linalg import eigh

from hubbeam.configuration.load import ConfigError
from hubbeam.configuration.settings import simulation_settings
from hubbeam.model.damping import ModalDamping, damping_from_dict, damping_matrices, damping_to_dict, modal_damping
from hubbeam.model.matrices import assemble
from hubbeam.model.parameters import BeamProducts, TipMass

LINK = BeamProducts(L=0.6, rhoA=0.135, EI=1.15, EA=3.45e6, Jh=0.0021, rA=0.0)


@pytest.fixture(scope="module")
def sm():
    return assemble(LINK, TipMass(0.015, 0.57, 5e-7), 4, 32)


def _modal_ratios(sm, C):
    M = sm.M2 + sm.Jt * np.outer(sm.dF2t, sm.dF2t)
    omega2, phi = eigh(sm.K2, M)
    return np.diag(phi.T @ C @ phi) / (2.0 * np.sqrt(omega2))


def test_each_listed_ratio_is_its_modes_and_the_rest_keep_the_common_one(sm):
    C = damping_matrices({"kind": "modal", "axial": 0.0, "transverse": 0.05, "transverse_modes": [0.01, 0.02]}, sm)
    np.testing.assert_allclose(_modal_ratios(sm, C[1]), [0.01, 0.02, 0.05, 0.05], rtol=1e-9)
    longer = damping_matrices({"kind": "modal", "axial": 0.0, "transverse": 0.05,
                               "transverse_modes": [0.01, 0.02, 0.03, 0.04, 0.09, 0.09]}, sm)
    np.testing.assert_allclose(_modal_ratios(sm, longer[1]), [0.01, 0.02, 0.03, 0.04], rtol=1e-9)


def test_without_the_list_the_matrices_are_those_of_the_single_ratio_bit_for_bit(sm):
    C = damping_matrices({"kind": "modal", "axial": 0.01, "transverse": 0.03}, sm)
    M = sm.M2 + sm.Jt * np.outer(sm.dF2t, sm.dF2t)
    np.testing.assert_array_equal(C[1], modal_damping(M, sm.K2, 0.03))
    np.testing.assert_array_equal(C[0], modal_damping(sm.M1, sm.K1, 0.01))
    assert damping_to_dict(damping_from_dict({"kind": "modal", "axial": 0.01, "transverse": 0.03})) == {
        "kind": "modal", "axial": 0.01, "transverse": 0.03}


def test_the_list_round_trips_through_a_cases_mapping():
    case = {"name": "c", "model": "FOAM", "modes": 3, "t_end": 1.0, "maneuver": {"kind": "torque", "tau_max": 0.1,
                                                                               "tf": 0.5},
            "damping": {"kind": "modal", "axial": 0.0, "transverse": 0.02, "transverse_modes": [0.01, 0.015]}}
    numerics = {"rtol": 1e-8, "atol": 1e-10, "output_step": 0.01, "max_steps": 10000, "step_warning": 10000,
                "divergence_limit": 1.0, "quadrature_points": 32}
    resolved, _ = simulation_settings(case, numerics, LINK.L)
    assert resolved.damping == ModalDamping(0.0, 0.02, (0.01, 0.015))
    assert resolved.to_dict()["damping"] == case["damping"]
    bad = dict(case, damping=dict(case["damping"], transverse_modes=[0.01, 1.0]))
    with pytest.raises(ConfigError) as error:
        simulation_settings(bad, numerics, LINK.L)
    (problem,) = error.value.problems
    assert problem.path == "cases.c.damping.transverse_modes[1]" and "< 1" in problem.text, problem
