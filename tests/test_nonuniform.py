"""Non-uniform beams: the section tables, the matrices built from them, and their validation by an
independent finite-element model (hubbeam.validation.fe_beam) and by analytic limits."""

import numpy as np
import pytest
import scipy.integrate
from test_matrices import assert_converged_in_quadrature_points

from hubbeam.model.beam import (
    BeamSections,
    beam_attributes,
    beam_from_attributes,
    beam_from_config,
    scaled_bending_stiffness,
)
from hubbeam.model.eigen import tip_mass_frequency_roots
from hubbeam.model.matrices import assemble
from hubbeam.model.modes import clamped_free_roots
from hubbeam.model.parameters import BeamParameters, BeamProducts, TipMass
from hubbeam.model.printed import TABLE1
from hubbeam.model.quadrature import beam_rule, segment_points
from hubbeam.validation import fe_beam
from hubbeam.validation.nonuniform import ritz_vs_fe, tapered_beam

PARAMS = BeamParameters(**TABLE1)
MATRIX_FIELDS = ("Jb", "K1", "K2", "M1", "M2", "V1", "V2", "D", "R", "SL")
#: a beam with a kink inside (three stations), stiffer and heavier at the root
KINKED = BeamSections(L=8.0, Jh=200.0, rA=0.5, x=(0.0, 3.0, 8.0), rhoA=(0.3, 0.2, 0.1),
                      EI=(800.0, 500.0, 300.0), EA=(7e6, 5e6, 3e6))
TAPERED = tapered_beam(PARAMS)
UNIFORM_CONFIG = {"length": 8.0, "density": 2766.7, "area": 7.2968e-5, "youngs_modulus": 6.8952e10,
                  "second_moment": 8.2189e-9, "hub_inertia": 200.0, "hub_radius": 0.5}
SECTIONS_CONFIG = {"length": 8.0, "hub_inertia": 200.0, "hub_radius": 0.5,
                   "sections": {"x": [0.0, 3.0, 8.0], "rhoA": [0.3, 0.2, 0.1],
                                "EI": [800.0, 500.0, 300.0], "EA": [7e6, 5e6, 3e6]}}


def relative_difference(a, b):
    return np.max(np.abs(np.asarray(a) - b)) / np.max(np.abs(b))


def constant_table(params, stations):
    """``params`` (uniform) as a section table with the given stations."""
    n = len(stations)
    return BeamSections(L=params.L, Jh=params.Jh, rA=params.rA, x=stations,
                        rhoA=[params.rhoA] * n, EI=[params.EI] * n, EA=[params.EA] * n)


# -- the tables --------------------------------------------------------------------------------

def test_config_builds_either_beam():
    assert beam_from_config(UNIFORM_CONFIG) == BeamParameters(**TABLE1)
    assert beam_from_config(SECTIONS_CONFIG) == KINKED
    for beam in (PARAMS, KINKED):
        assert beam_from_attributes(beam_attributes(beam)) == beam


def test_interpolation_is_piecewise_linear_and_integrals_exact():
    np.testing.assert_allclose(KINKED.rhoA_at([0.0, 1.5, 3.0, 5.5, 8.0]),
                               [0.3, 0.25, 0.2, 0.15, 0.1], rtol=1e-15)
    np.testing.assert_allclose(KINKED.EI_at(4.0), 460.0, rtol=1e-15)
    np.testing.assert_allclose(KINKED.EA_at(8.0), 3e6, rtol=1e-15)
    # trapezoids, by hand: 3 * 0.25 + 5 * 0.15
    assert KINKED.beam_mass == pytest.approx(1.5, rel=1e-15)
    assert KINKED.rhoA_ref == pytest.approx(1.5 / 8.0, rel=1e-15)
    for x in (0.0, 1.0, 3.0, 6.2, 8.0):
        reference, _ = scipy.integrate.quad(lambda s: KINKED.rhoA_at(s) * (KINKED.rA + s), x, 8.0,
                                            points=[3.0] if x < 3.0 else None, epsabs=0,
                                            epsrel=1e-13)
        assert KINKED.outboard_moment(x) == pytest.approx(reference, rel=1e-13, abs=1e-15)
    uniform = constant_table(PARAMS, [0.0, PARAMS.L])
    x = np.linspace(0, PARAMS.L, 7)
    np.testing.assert_allclose(uniform.outboard_moment(x), PARAMS.outboard_moment(x),
                               rtol=1e-14, atol=1e-15)


BAD_TABLES = [
    ({"x": [0.0]}, r"beam.sections.x = \[0.0\]: expected at least 2 stations"),
    ({"rhoA": [0.3, 0.2]}, r"beam.sections.rhoA has 2 values: expected one per station, 3"),
    ({"x": [0.0, 5.0, 3.0, 8.0], "rhoA": [1, 1, 1, 1], "EI": [1, 1, 1, 1], "EA": [1, 1, 1, 1]},
     r"beam.sections.x\[2\] = 3.0: expected a finite station > x\[1\] = 5.0"),
    ({"x": [0.5, 3.0, 8.0]}, r"beam.sections.x\[0\] = 0.5: expected 0"),
    ({"x": [0.0, 3.0, 7.0]}, r"beam.sections.x\[2\] = 7.0: expected the beam length 8.0"),
    ({"EI": [800.0, 0.0, 300.0]}, r"beam.sections.EI\[1\] = 0.0: expected a finite value > 0 N m2"),
    ({"EA": [7e6, 5e6, -3e6]}, r"beam.sections.EA\[2\] = -3000000.0: expected a finite value > 0"),
    ({"rhoA": [0.3, float("nan"), 0.1]}, r"beam.sections.rhoA\[1\] = nan: expected a finite"),
    ({"x": [0.0, "a", 8.0]}, r"beam.sections.x = \[0.0, 'a', 8.0\]: expected a list of numbers"),
]


@pytest.mark.parametrize(("change", "message"), BAD_TABLES)
def test_bad_tables_name_field_index_and_value(change, message):
    beam = {**SECTIONS_CONFIG, "sections": {**SECTIONS_CONFIG["sections"], **change}}
    with pytest.raises(ValueError, match=message):
        beam_from_config(beam)


@pytest.mark.parametrize(("beam", "message"), [
    ({**SECTIONS_CONFIG, "density": 2766.7}, r"beam.density = 2766.7: not allowed with sections"),
    ({k: v for k, v in SECTIONS_CONFIG.items() if k != "hub_radius"},
     "beam is missing hub_radius"),
    ({**SECTIONS_CONFIG, "sections": {"file": "tapered.csv"}},
     r"beam.sections = \['file'\]: expected inline lists x, rhoA, EI, EA"),
    ({k: v for k, v in UNIFORM_CONFIG.items() if k != "area"}, "beam is missing area"),
    ({**SECTIONS_CONFIG, "length": -1.0}, r"beam.length = -1.0: expected a finite length > 0 m"),
])
def test_bad_beam_sections(beam, message):
    with pytest.raises(ValueError, match=message):
        beam_from_config(beam)


# -- matrices ----------------------------------------------------------------------------------

@pytest.mark.parametrize("tip", [None, TipMass(mass=0.5, position=5.3)])
@pytest.mark.parametrize("stations", [[0.0, 8.0], [0.0, 3.0, 8.0], [0.0, 0.01, 4.0, 8.0]])
def test_constant_table_gives_the_uniform_matrices(stations, tip):
    """A table of constant properties is the uniform beam: the same matrices, whatever stations
    break the quadrature (bitwise up to rounding for the single segment)."""
    uniform = assemble(PARAMS, tip, 10)
    table = assemble(constant_table(PARAMS, stations), tip, 10)
    tolerance = 1e-14 if len(stations) == 2 else 1e-12
    for name in MATRIX_FIELDS:
        assert relative_difference(getattr(table, name), getattr(uniform, name)) < tolerance, name


def test_composite_rule_counts_and_exactness():
    assert segment_points(64, [0.0, 8.0]) == [64]
    assert segment_points(64, [0.0, 3.0, 8.0]) == [24, 40]
    assert segment_points(64, [0.0, 0.01, 4.0, 8.0]) == [4, 32, 32]  # a short segment's minimum
    nodes, weights = beam_rule(KINKED, 64)
    assert nodes.size == 64 and weights.sum() == pytest.approx(8.0, rel=1e-15)
    # piecewise-linear rho A times a polynomial is integrated exactly across the kink at x = 3
    assert np.sum(weights * KINKED.rhoA_at(nodes)) == pytest.approx(KINKED.beam_mass, rel=1e-14)


@pytest.mark.parametrize("n_modes", [5, 20])
@pytest.mark.parametrize("tip", [None, TipMass(mass=0.5, position=5.3)])
def test_kinked_beam_matrices_converged_in_quadrature_points(n_modes, tip):
    assert_converged_in_quadrature_points(KINKED, tip, n_modes)


def test_normalisation_of_a_non_uniform_beam():
    """Unit modal mass of the uniform beam of equal mass: trace of M2 against int rhoA f2^2 done
    independently, and M1, M2 of a uniform-mass beam with varying stiffness are the identity."""
    stiff_taper = BeamSections(L=8.0, Jh=1.0, rA=0.5, x=(0.0, 8.0), rhoA=(0.2, 0.2),
                               EI=(800.0, 300.0), EA=(7e6, 3e6))
    sm = assemble(stiff_taper, None, 8)
    np.testing.assert_allclose(sm.M1, np.eye(8), atol=1e-13)
    np.testing.assert_allclose(sm.M2, np.eye(8), atol=1e-13)
    assert not np.allclose(sm.K2, np.diag(np.diag(sm.K2)), atol=1e-6 * sm.K2.max())
    sm = assemble(KINKED, None, 3)
    assert sm.w[:-1].sum() == pytest.approx(KINKED.beam_mass, rel=1e-14)
    assert np.trace(sm.M1) != pytest.approx(3.0, rel=1e-3)  # rhoA varies: not the identity


# -- finite elements: analytic limits ----------------------------------------------------------

def test_fe_cantilever_frequencies_at_rest():
    """(beta_i L)^2 sqrt(EI / (rho A L^4)), and the fourth-order convergence of cubic elements."""
    exact = clamped_free_roots(6) ** 2 * np.sqrt(PARAMS.EI / (PARAMS.rhoA * PARAMS.L**4))
    errors = [fe_beam.frequencies(PARAMS, [0.0], "flapwise", None, n, 6)[0] / exact - 1
              for n in (20, 40)]
    assert np.all(np.abs(errors[1]) < 3e-5)
    ratio = errors[0][1:] / errors[1][1:]  # mode 1 is already at rounding level
    assert np.all((ratio > 14) & (ratio < 17)), ratio
    fine = fe_beam.frequencies(PARAMS, [0.0], "inplane", None, 160, 6)[0]
    np.testing.assert_allclose(fine, exact, rtol=1e-7)


@pytest.mark.parametrize("mu", [0.1, 1.0])
def test_fe_tip_mass_frequency_equation_at_rest(mu):
    tip = TipMass(mass=mu * PARAMS.beam_mass, position=PARAMS.L)
    scale = np.sqrt(PARAMS.EI / (PARAMS.rhoA * PARAMS.L**4))
    exact = tip_mass_frequency_roots(mu, 4) ** 2 * scale
    np.testing.assert_allclose(fe_beam.frequencies(PARAMS, [0.0], "flapwise", tip, 160, 4)[0],
                               exact, rtol=1e-7)


def test_fe_inplane_is_flapwise_minus_speed_squared_for_uniform_beam():
    """omega_inplane^2 = omega_flap^2 - Omega^2 (the softening is -Omega^2 M exactly)."""
    speeds = np.array([0.0, 3.0, 10.0])
    flap = fe_beam.frequencies(TAPERED, speeds, "flapwise", None, 60, 4)
    inplane = fe_beam.frequencies(TAPERED, speeds, "inplane", None, 60, 4)
    np.testing.assert_allclose(inplane**2, flap**2 - speeds[:, None] ** 2, rtol=1e-9)


def test_fe_bad_direction():
    with pytest.raises(ValueError, match="direction = 'lag': expected one of flapwise, inplane"):
        fe_beam.frequencies(PARAMS, [0.0], "lag")


# -- Ritz against finite elements --------------------------------------------------------------

RITZ_CASES = {
    "uniform": (PARAMS, None),
    "uniform, tip mass": (PARAMS, TipMass(mass=0.5 * PARAMS.beam_mass, position=PARAMS.L)),
    "tapered": (TAPERED, None),
    "tapered, tip mass inside": (TAPERED, TipMass(mass=0.3 * TAPERED.beam_mass, position=5.6)),
    "kinked, tip mass": (KINKED, TipMass(mass=0.2, position=KINKED.L)),
}
#: largest |ritz / fe - 1| allowed with 20 modes over the first four modes at 0, 6 and 12 rad/s
#: (the first frequency is 2.9 rad/s at rest). Measured (the tables are printed with pytest -s):
#: 1.0e-5 for the bare beams, at 12 rad/s in the plane; 1.5e-4 with a tip mass, mode 4 at rest.
#: A tip mass makes the shear force jump at the mass, which the clamped-free basis (zero shear
#: at the free end) does not contain: the error falls as about n^-3 instead of n^-4.5.
RITZ_TOLERANCE = {"uniform": 2e-5, "uniform, tip mass": 3e-4, "tapered": 2e-5,
                  "tapered, tip mass inside": 3e-4, "kinked, tip mass": 3e-4}


@pytest.mark.parametrize("case", RITZ_CASES)
def test_ritz_converges_to_fe_in_modes(case):
    params, tip = RITZ_CASES[case]
    table = ritz_vs_fe(params, [0.0, 6.0, 12.0], tip, modes=(5, 10, 20))
    print(f"\n{case}\n", table.pivot_table(index=["direction", "speed_rad_s", "mode"],
                                           columns="n_modes", values="rel_diff")
          .to_string(float_format=lambda v: f"{v:.2e}"))
    worst = table.assign(error=table["rel_diff"].abs()).groupby("n_modes")["error"].max()
    assert worst[20] < RITZ_TOLERANCE[case]
    # algebraic convergence in the number of modes, at least n^-2.5 (measured n^-3 to n^-4.5)
    assert worst[5] / worst[10] > 2**2.5 and worst[10] / worst[20] > 2**2.5, worst.to_dict()
    assert (table["rel_diff"] > -1e-7).all()  # Ritz frequencies are upper bounds (up to FE error)


# -- the rest of the package with a non-uniform beam -------------------------------------------

def test_eigen_analysis_of_a_non_uniform_beam():
    from hubbeam.model.eigen import campbell, critical_speed_sweep

    sweep = critical_speed_sweep(KINKED, [0.0, 0.2], [KINKED.L], 5, search_max=50.0)
    assert np.isnan(sweep["continuum_tlam_critical_speed_at_tip"]).all()  # uniform beams only
    assert np.isfinite(sweep["critical_speed"].sel(model="TLAM")).all()
    assert np.isnan(sweep["critical_speed"].sel(model="FOAM")).all()
    diagram = campbell(KINKED, [0.0], [0.0, 6.0], 5)
    fe = fe_beam.frequencies(KINKED, [0.0, 6.0], "inplane", None, 80, 1)[:, 0]
    np.testing.assert_allclose(diagram["frequency"].sel(model="FOAM", mode=1)[0] * 2 * np.pi, fe,
                               rtol=1e-3)
    assert diagram.attrs["sections_EI"].tolist() == [800.0, 500.0, 300.0]


@pytest.mark.parametrize("model", ["TLAM", "FOAM", "SFOAM", "CFOAM"])
def test_every_model_simulates_a_non_uniform_beam_and_reruns_from_its_attributes(model):
    from hubbeam.results.reader import simulation_inputs
    from hubbeam.simulation.simulate import simulate

    numerics = {"rtol": 1e-7, "atol": 1e-9, "output_step": 0.1, "max_steps": 100_000,
                "step_warning": 100_000, "divergence_limit": 1.0, "quadrature_points": 64}
    case = {"name": "kinked", "model": model, "modes": 3, "t_end": 1.0,
            "maneuver": {"kind": "prescribed", "wf": 1.0, "tf": 1.0},
            "tip_mass": {"mass": 0.2, "position": KINKED.L}}
    ds = simulate(case, KINKED, numerics)
    assert ds.attrs["integrator_status"] == "success"
    assert ds.attrs["sections_x"].tolist() == [0.0, 3.0, 8.0]
    assert np.abs(ds["tip_transverse"]).max() > 0.0
    rerun = simulate(**simulation_inputs(ds.attrs))
    np.testing.assert_array_equal(rerun["tip_transverse"], ds["tip_transverse"])


@pytest.mark.parametrize("form", ["factors", "products", "sections"])
def test_a_factor_on_the_bending_stiffness_scales_K2_alone_for_every_form_of_beam(form):
    """K2 = int EI f2''^T f2'' dx (Eq. 17) is linear in EI; the mass and axial matrices do not hold
    it. The robustness maps and the identification move EI this way, the tabulated beam included."""
    base = BeamParameters(**TABLE1)
    beam = {"factors": base,
            "products": BeamProducts(L=base.L, rhoA=base.rho * base.A, EI=base.E * base.I, EA=base.E * base.A,
                                     Jh=base.Jh, rA=base.rA),
            "sections": tapered_beam(base)}[form]
    factor = 1.7
    nominal, scaled = (assemble(b, n_modes=3, n_quad=32) for b in (beam, scaled_bending_stiffness(beam, factor)))
    np.testing.assert_allclose(scaled.K2, factor * nominal.K2, rtol=1e-12, atol=1e-13 * np.abs(scaled.K2).max())
    for name in ("M1", "M2", "K1"):
        np.testing.assert_array_equal(getattr(scaled, name), getattr(nominal, name))
