"""Admissible functions that converge with a tip body: the modes of the uniform beam clamped at the
hub and loaded by the body at rest (``assemble(..., functions="tip_body")``, ``hubbeam.model.modes``).

* the roots against the closed form's (``hubbeam.validation.tip_body``, a 4x4 determinant solved
  apart), today's functions without a load;
* each function clamped at the root, meeting the body's end conditions and of unit modal mass of
  the bare beam, from its own derivatives and an independent quadrature;
* hubbeam's frequencies at rest, hub held, equal to the closed form for every number of modes up to
  ``MAX_MODES`` (the De Luca and Siciliano link, a body with an offset), the mass and stiffness
  matrices diagonal;
* at speed, FOAM's frequencies converging to the finite-element model with the body far faster
  than with the clamped-free functions;
* energy and angular momentum conserved with them; the matrices dataset records them; the linear
  models accept them; bad requests named.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from hubbeam.linear.statespace import linear_model
from hubbeam.model import eigen
from hubbeam.model.beam import BeamSections
from hubbeam.model.limits import MAX_MODES
from hubbeam.model.matrices import assemble, from_dataset, to_dataset
from hubbeam.model.modes import (
    _beam_coefficients,
    clamped_free_roots,
    loaded_coefficients,
    loaded_roots,
    transverse_modes,
)
from hubbeam.model.parameters import BeamParameters, BeamProducts, TipMass
from hubbeam.simulation.simulate import simulate
from hubbeam.validation import fe_beam
from hubbeam.validation.tip_body import DE_LUCA_SICILIANO, body_frequencies, body_frequency_roots

ROOT = Path(__file__).resolve().parents[1]

#: the De Luca and Siciliano link clamped at the hub, its payload, and the payload 3 cm beyond the tip
LINK = BeamProducts(L=DE_LUCA_SICILIANO["L"], rhoA=DE_LUCA_SICILIANO["rhoA"], EI=DE_LUCA_SICILIANO["EI"],
                    EA=1.0e4, Jh=0.1, rA=0.0)
PAYLOAD = TipMass(DE_LUCA_SICILIANO["mass"], LINK.L, DE_LUCA_SICILIANO["inertia"])
OFFSET_PAYLOAD = TipMass(PAYLOAD.mass, LINK.L, PAYLOAD.inertia, 0.03)
#: a body on the paper's beam (Table 1): half a kilogram, 2 kg m2, centre 0.3 m beyond the tip
BODY = TipMass(0.5, 8.0, 2.0, 0.3)


def _load(beam, tip):
    return (tip.mass / (beam.rhoA * beam.L), tip.inertia / (beam.rhoA * beam.L**3), tip.offset / beam.L)


# --- the functions ------------------------------------------------------------------------------


@pytest.mark.parametrize("load", [(0.2, 0.0, 0.0), (1.0, 0.02, 0.0), (1.0, 0.02, 0.06), (5.0, 0.5, 0.3)])
def test_the_loaded_roots_are_the_closed_form_s(load):
    """The 2x2 determinant of the loaded end (the clamped root eliminated) has the roots of the
    closed form's 4x4 determinant, solved independently, to 1e-13 (both refined to 1e-15)."""
    np.testing.assert_allclose(loaded_roots(MAX_MODES, load), body_frequency_roots(*load, MAX_MODES), rtol=1e-13)


def test_without_a_load_they_are_today_s_functions():
    """No body: the clamped-free roots and coefficients of ``1 + cos z cosh z = 0`` (to 5e-15), and
    a norm ``int_0^1 phi^2 dxi`` of 1 (the Gauss rule integrates it to rounding)."""
    Z, s, c_plus, c_minus, norm = loaded_coefficients(MAX_MODES, (0.0, 0.0, 0.0))
    np.testing.assert_allclose(Z, clamped_free_roots(MAX_MODES), rtol=4e-16)
    expected = _beam_coefficients(clamped_free_roots(MAX_MODES))
    for got, want in zip((s, c_plus, c_minus), expected):
        np.testing.assert_allclose(got, want, rtol=0, atol=5e-15)
    np.testing.assert_allclose(norm, 1.0, rtol=0, atol=5e-15)


@pytest.mark.parametrize("tip", [PAYLOAD, OFFSET_PAYLOAD, TipMass(0.3, 0.5, 0.002, -0.1)],
                         ids=["payload", "offset_payload", "centre_inboard"])
def test_each_function_is_a_mode_of_the_loaded_beam(tip):
    """Every loaded function, from its own derivatives: ``f(0) = f'(0) = 0`` (clamped), the body's
    shear ``EI f''' + m omega^2 (f + e f') = 0`` and moment ``-EI f'' + omega^2 (m e (f + e f') + J
    f') = 0`` at the end with ``omega^2 = beta^4 EI / rho A`` (each to 1e-10 of its largest term,
    the roots' ``1e-15`` times ``beta^4`` and the terms' cancellation), and unit modal mass of the
    bare beam, ``int_0^L rho A f^2 dx = 1``, by a 400-point Gauss rule (to 1e-12)."""
    beam, n = LINK, MAX_MODES
    load = _load(beam, tip)
    f = [transverse_modes(np.array([0.0, beam.L]), n, beam, k, load) for k in range(4)]
    scale = [np.abs(f[k]).max(axis=0) for k in range(4)]
    assert np.all(np.abs(f[0][0]) <= 1e-12 * scale[0]) and np.all(np.abs(f[1][0]) <= 1e-12 * scale[1])
    beta = loaded_roots(n, load) / beam.L
    omega2 = beta**4 * beam.EI / beam.rhoA
    value, slope, curvature, shear = (f[k][1] for k in range(4))
    centre = value + tip.offset * slope
    terms = (beam.EI * shear, tip.mass * omega2 * centre)
    assert np.all(np.abs(sum(terms)) <= 1e-10 * np.max(np.abs(terms), axis=0))
    terms = (-beam.EI * curvature, omega2 * tip.mass * tip.offset * centre, omega2 * tip.inertia * slope)
    assert np.all(np.abs(sum(terms)) <= 1e-10 * np.max(np.abs(terms), axis=0))
    nodes, weights = np.polynomial.legendre.leggauss(400)
    x = 0.5 * beam.L * (nodes + 1.0)
    mass = 0.5 * beam.L * beam.rhoA * weights @ transverse_modes(x, n, beam, 0, load) ** 2
    np.testing.assert_allclose(mass, 1.0, rtol=0, atol=1e-12)


# --- hubbeam's frequencies ------------------------------------------------------------------------


@pytest.mark.parametrize("tip", [PAYLOAD, OFFSET_PAYLOAD], ids=["de_luca_siciliano", "offset_payload"])
def test_at_rest_the_frequencies_are_the_closed_form_for_any_number_of_modes(tip):
    """With the loaded functions hubbeam's frequencies at rest, hub held, are the closed form's for
    1 to 20 (``MAX_MODES``) modes: the functions are the loaded beam's modes, so ``K2`` and ``M2 + Jt
    g^T g`` are diagonal (to 1e-12 of their largest entry, the quadrature's rounding) and every
    frequency the closed form's to 1e-10 (measured 4e-12; the clamped-free functions give 1.5 % on
    the second with 20 modes, docs/tip-body.md). The De Luca and Siciliano link: 2.178334 and
    15.914513 Hz, published 2.18 and 15.91."""
    exact = body_frequencies(LINK, tip, MAX_MODES)
    for n in (1, 2, 5, 10, MAX_MODES):
        sm = assemble(LINK, tip, n, functions="tip_body")
        np.testing.assert_allclose(eigen.natural_frequencies(sm), exact[:n], rtol=1e-10)
    mass = sm.M2 + sm.Jt * np.outer(sm.dF2t, sm.dF2t)
    for matrix in (mass, sm.K2):
        off = matrix - np.diag(np.diag(matrix))
        assert np.abs(off).max() <= 1e-12 * np.abs(matrix).max()
    if tip is PAYLOAD:
        np.testing.assert_array_equal(np.round(exact[:2] / (2 * math.pi), 2), DE_LUCA_SICILIANO["frequencies_hz"])


SPEEDS = np.array([10.0, 25.0, 50.0])  # rad s-1; the link's first frequency is 13.7 rad s-1


def test_at_speed_they_converge_to_the_finite_elements():
    """FOAM's in-plane frequencies at 10, 25 and 50 rad/s on a 5 cm hub with the offset payload,
    against the finite-element model with the body (80 elements: 1e-8 from the closed form at rest,
    its best here, where more elements gain less than their rounding loses). At speed the loaded
    functions are no longer the modes (the centrifugal tension loads the tip too), yet the first
    three frequencies fall as ``N^-5`` (order from 10 to 20 modes at least 4 at 25 and 50 rad/s;
    measured 4.9 to 5.4) to 2.2e-6 at 50 rad/s and 2e-7 at 25 with 20 modes, where the clamped-free
    functions converge at order 2 at most (1.95 on the first frequency at 50 rad/s, about 1 on the
    others) and stay 1.4 % off the second frequency."""
    beam = BeamProducts(L=LINK.L, rhoA=LINK.rhoA, EI=LINK.EI, EA=LINK.EA, Jh=LINK.Jh, rA=0.05)
    fe = fe_beam.frequencies(beam, SPEEDS, "inplane", OFFSET_PAYLOAD, 80, 3)
    def error(n, functions):
        sm = assemble(beam, OFFSET_PAYLOAD, n, functions=functions)
        return eigen.transverse_frequencies(sm, "FOAM", SPEEDS)[:, :3] / fe - 1.0

    loaded, clamped = (np.array([error(n, functions) for n in (10, 20)]) for functions in ("tip_body", "clamped_free"))
    assert np.all(np.abs(loaded[1]) <= np.array([[1e-8], [2e-7], [2.2e-6]]))
    orders = np.log2(np.abs(loaded[0, 1:] / loaded[1, 1:]))
    assert np.all(orders >= 4.0)
    assert np.all(np.log2(clamped[0] / clamped[1]) <= 2.0) and np.all(clamped[1, :, 1] >= 1e-2)


@pytest.mark.parametrize("model", ["TLAM", "FOAM", "CFOAM"])
def test_energy_is_conserved_with_the_loaded_functions(_study_config, model):
    """The paper's beam with the body, its loaded functions: after a torque pulse the free,
    undamped hub-beam keeps its energy and angular momentum to the integrator's tolerance (as with
    the clamped-free functions, docs/tip-body.md), and the pulse leaves no net momentum."""
    beam = BeamParameters.from_config(_study_config)
    rtol = 1e-9
    numerics = dict(_study_config["numerics"], rtol=rtol, atol=1e-2 * rtol)
    sm = assemble(beam, BODY, 3, numerics["quadrature_points"], functions="tip_body")
    case = {"name": f"loaded_{model}", "model": model, "modes": 3, "t_end": 12.0,
            "maneuver": {"kind": "torque", "tau_max": 10.0, "tf": 5.0},
            "tip_mass": {"mass": BODY.mass, "position": BODY.position}}
    ds = simulate(case, beam, numerics, sm)
    assert ds.attrs["diverged"] == 0 and float(abs(ds.tip_transverse).max()) > 1e-3
    after = ds.time >= 5.0
    energy, momentum = ds.energy[after].values, ds.angular_momentum[after].values
    assert np.ptp(energy) <= rtol * np.max(abs(energy))
    assert np.ptp(momentum) <= rtol * float(abs(ds.angular_momentum).max())
    assert abs(momentum[0]) <= rtol * float(abs(ds.angular_momentum).max())


# --- records, consumers, bad requests ---------------------------------------------------------------


def test_the_matrices_dataset_records_the_functions():
    """The dataset of matrices assembled with the loaded functions names them
    (``transverse_functions``, and the normalisation text) and reads back bit for bit; the default's
    dataset has no such attribute (unchanged)."""
    sm = assemble(LINK, OFFSET_PAYLOAD, 4, functions="tip_body")
    ds = to_dataset(sm, LINK, OFFSET_PAYLOAD, functions="tip_body")
    assert ds.attrs["transverse_functions"] == "tip_body" and "loaded by the tip body" in ds.attrs["mode_normalisation"]
    for got, want in zip(from_dataset(ds), sm):
        assert np.asarray(got).tobytes() == np.asarray(want).tobytes()
    assert "transverse_functions" not in to_dataset(assemble(LINK, OFFSET_PAYLOAD, 4), LINK, OFFSET_PAYLOAD).attrs


def test_the_linear_models_take_the_loaded_functions():
    """``linear_model`` recognises matrices of the loaded functions (by ``f2(L)``) and reads the root
    moment with their curvature: its row is ``EI f''(0)`` of the loaded functions; its held hub's
    poles at rest are the closed form's frequencies."""
    sm = assemble(LINK, OFFSET_PAYLOAD, 4, functions="tip_body")
    lin = linear_model(LINK, sm, "FOAM", 0.0, "prescribed", outputs=["root_moment"])
    curvature = transverse_modes(0.0, 4, LINK, 2, _load(LINK, OFFSET_PAYLOAD))[0]
    q2 = [lin.states.index(f"q2_{i}") for i in range(1, 5)]
    np.testing.assert_allclose(lin.C[0, q2], LINK.EI * curvature, rtol=1e-15)
    poles = np.sort(np.abs(np.linalg.eigvals(lin.A).imag))
    bending = body_frequencies(LINK, OFFSET_PAYLOAD, 2)
    for frequency in bending:
        assert np.min(np.abs(poles / frequency - 1.0)) <= 1e-10


@pytest.mark.parametrize("request_, message", [
    (dict(functions="hermite"), "functions = 'hermite'; allowed: one of clamped_free, tip_body"),
    (dict(tip=TipMass(0.1, 0.4)), "tip_mass.position = 0.4; allowed: the beam's end L = 0.5 m"),
    (dict(beam=BeamSections(L=0.5, Jh=0.1, rA=0.0, x=np.array([0.0, 0.5]), rhoA=np.array([0.2, 0.1]),
                            EI=np.array([1.0, 1.0]), EA=np.array([1e4, 1e4]))),
     "with a beam of sections; allowed: a uniform beam"),
])
def test_a_request_the_functions_cannot_meet_is_named(request_, message):
    arguments = dict(dict(beam=LINK, tip=PAYLOAD, functions="tip_body"), **request_)
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        assemble(arguments["beam"], arguments["tip"], 3, functions=arguments["functions"])


# --- from a study's configuration ---------------------------------------------------------------


def test_the_shipped_link_study_gives_the_published_frequencies():
    """``studies/deluca_link.yaml`` read through the one check: its payload case (a body on the loaded
    beam's modes) has, hub held at rest, the closed form's frequencies to 1e-6 and the published 2.18
    and 15.91 Hz to their two decimals; the same body on the clamped-free functions misses the second
    by more than 5 %, and as a point mass the second lies above 22 Hz (the error the body removes).
    The study's beam and payload are compared with the published record, not read from it."""
    from hubbeam.api import load
    study = load(ROOT / "studies" / "deluca_link.yaml")
    beam, tip = study.beam, study.case("payload").tip_mass
    assert (beam.rhoA, beam.L, beam.EI, beam.rA) == (DE_LUCA_SICILIANO["rhoA"], DE_LUCA_SICILIANO["L"],
                                                      DE_LUCA_SICILIANO["EI"], 0.0)
    assert (tip.mass, tip.inertia, tip.position) == (DE_LUCA_SICILIANO["mass"], DE_LUCA_SICILIANO["inertia"], beam.L)
    exact = body_frequencies(beam, tip, 2) / (2 * math.pi)
    found = study.natural_frequencies("payload")[:2]
    np.testing.assert_allclose(found, exact, rtol=1e-6)
    assert tuple(round(float(f), 2) for f in found) == DE_LUCA_SICILIANO["frequencies_hz"]
    assert study.natural_frequencies("payload_clamped_free")[1] > 1.05 * exact[1]
    assert study.natural_frequencies("point_payload")[1] > 22.0


def test_the_loaded_functions_are_a_case_key_with_its_own_matrices(tmp_path):
    """``transverse_functions: tip_body`` reaches the case, its matrices (a configuration name of their
    own, so the workflow assembles them apart) and its dataset's record; a body away from the end or
    a beam of sections is refused by the key before anything runs."""
    import yaml

    from hubbeam.api import load
    from hubbeam.configuration.load import ConfigError
    from hubbeam.model.matrices import configuration_name

    cfg = yaml.safe_load((ROOT / "studies" / "deluca_link.yaml").read_text(encoding="utf-8"))
    case = cfg["cases"]["payload"]
    study = load(ROOT / "studies" / "deluca_link.yaml")
    loaded = study.case("payload")
    assert loaded.transverse_functions == "tip_body" and study.case("point_payload").transverse_functions == \
        "clamped_free"
    assert configuration_name(loaded.tip_mass, "tip_body").endswith("_tip_body")
    assert loaded.to_dict()["transverse_functions"] == "tip_body"
    assert "transverse_functions" not in study.case("point_payload").to_dict()
    cfg["cases"] = {"payload": case, "inside": dict(case, tip_mass={"mass": 0.1, "position": 0.4})}
    cfg["study"].pop("comparisons")
    path = tmp_path / "inside.yaml"
    path.write_text(yaml.safe_dump(cfg), encoding="utf-8")
    with pytest.raises(ConfigError) as error:
        load(path)
    assert [problem.path for problem in error.value.problems] == ["cases.inside.transverse_functions"]
    assert "allowed: 'clamped_free', or the tip mass at the beam's end" in str(error.value)


def test_the_study_report_lists_each_plant_s_own_frequencies():
    """The report's table of plants: the body on the loaded modes gives the closed form's
    frequencies, the point mass the point mass's, and the body on the clamped-free functions, whose
    second mode is too stiff with 6 of them, is marked not converged."""
    from hubbeam.api import load
    from hubbeam.linear.plant_dataset import plant_dataset
    from hubbeam.study.plants import plant_row, plants_markdown

    study = load(ROOT / "studies" / "deluca_link.yaml")
    plants = study.settings.plant_cases
    rows = [plant_row(plant_dataset(*plants[name], 40.0)) for name in ("payload", "point_payload",
                                                                      "payload_clamped_free")]
    exact = body_frequencies(study.beam, study.case("payload").tip_mass, 3) / (2 * math.pi)
    np.testing.assert_allclose(rows[0]["held_hz"], exact, rtol=1e-9)
    point = body_frequencies(study.beam, study.case("point_payload").tip_mass, 2) / (2 * math.pi)
    np.testing.assert_allclose(rows[1]["held_hz"][:2], point, rtol=1e-3)  # 6 clamped-free modes
    assert rows[0]["converged"] == [True] * 3 and rows[2]["converged"][:2] == [True, False]
    table = plants_markdown(rows)
    assert ("| payload | payload | 6 tip-body modes, 0.1 kg at 0.5 m (J 0.0005 kg m2, offset 0 m) | 2.17833 | "
            "15.9145 |") in table
    assert "16.7405 (not converged: 1.7 %)" in table
