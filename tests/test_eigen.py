"""Eigen-analysis: analytic frequencies, critical speeds, FOAM's missing critical speed, sweeps."""

import dataclasses

import numpy as np
import pytest

from hubbeam.model.eigen import (
    K22,
    campbell,
    critical_speed,
    critical_speed_by_root_search,
    critical_speed_sweep,
    gyroscopic_eigenvalues,
    gyroscopic_frequencies,
    k22_sweep,
    natural_frequencies,
    table2,
    tip_mass_frequency_roots,
    transverse_frequencies,
)
from hubbeam.model.matrices import assemble
from hubbeam.model.modes import clamped_free_roots
from hubbeam.model.parameters import BeamParameters, TipMass
from hubbeam.model.printed import TABLE1

PARAMS = BeamParameters(**TABLE1)
RHO_A = PARAMS.rhoA
#: omega = (beta L)^2 * SCALE for the Euler-Bernoulli cantilever
SCALE = np.sqrt(PARAMS.E * PARAMS.I / (RHO_A * PARAMS.L**4))


def test_natural_frequencies_are_the_analytic_cantilever_values():
    for n in (1, 5, 20):
        omega = natural_frequencies(assemble(PARAMS, None, n))
        np.testing.assert_allclose(omega, clamped_free_roots(n) ** 2 * SCALE, rtol=1e-12)
    assert 2.90 < natural_frequencies(assemble(PARAMS, None, 1))[0] < 2.92


def test_tlam_without_tip_mass_is_sqrt_omega2_minus_speed2():
    sm = assemble(PARAMS, None, 5)
    omega = clamped_free_roots(5) ** 2 * SCALE
    np.testing.assert_allclose(transverse_frequencies(sm, "TLAM", 1.0), np.sqrt(omega**2 - 1),
                               rtol=1e-12)
    # FOAM stiffens, TLAM softens (Table 2's ordering)
    assert np.all(transverse_frequencies(sm, "FOAM", 1.0) > omega)


@pytest.mark.parametrize(
    "mu, root",
    [(0.0, 1.87510), (0.1, 1.72274), (0.2, 1.61640), (0.5, 1.41996), (1.0, 1.24792),
     (2.0, 1.07620)],
)
def test_tip_mass_frequency_equation_solver_against_published_roots(mu, root):
    roots = tip_mass_frequency_roots(mu, 3)
    assert abs(roots[0] - root) <= 5.1e-6
    b = roots
    residual = 1 + np.cos(b) * np.cosh(b) + mu * b * (np.cos(b) * np.sinh(b) - np.sin(b) * np.cosh(b))
    assert np.all(np.abs(residual) < 1e-12 * np.cosh(b) * (1 + mu * b))
    assert np.all(np.diff(roots) > 0)


@pytest.mark.parametrize("mass", [0.1, 0.5, 2.0])
def test_tlam_critical_speed_with_tip_mass_converges_to_the_continuum(mass):
    """Omega_c(TLAM) is the first frequency of the cantilever with the tip mass; the assumed
    modes give a Rayleigh-Ritz upper bound that decreases with n."""
    mu = mass / (RHO_A * PARAMS.L)
    exact = tip_mass_frequency_roots(mu, 1)[0] ** 2 * SCALE
    tip = TipMass(mass, PARAMS.L)
    speeds = [critical_speed("TLAM", PARAMS, tip, n, 20.0) for n in (1, 2, 5, 10, 20)]
    assert np.all(np.diff(speeds) <= 1e-14 * exact)
    assert speeds[-1] >= exact * (1 - 1e-13)
    assert speeds[-1] / exact - 1 < 1e-4


def test_critical_speed_matches_brent_root_search():
    for tip in (None, TipMass(0.1, PARAMS.L), TipMass(0.5, PARAMS.L), TipMass(0.5, 3.3)):
        exact = critical_speed("TLAM", PARAMS, tip, 5, 20.0)
        searched = critical_speed_by_root_search("TLAM", PARAMS, tip, 5, 20.0)
        assert abs(exact - searched) < 1e-12 * exact
    # below the search range there is none
    assert np.isnan(critical_speed("TLAM", PARAMS, None, 5, 2.0))


def test_tlam_critical_speed_without_tip_mass_is_the_first_natural_frequency():
    for tip in (None, TipMass(0.5, 0.0)):  # a mass on the hub does nothing (f2(0) = 0)
        np.testing.assert_allclose(critical_speed("TLAM", PARAMS, tip, 5, 20.0),
                                   clamped_free_roots(1)[0] ** 2 * SCALE, rtol=1e-12)


def test_foam_has_no_critical_speed():
    """M2 - D is negative definite for the paper's data with any tip mass (Cauchy-Schwarz:
    (int_0^x w')^2 <= x int_0^x w'^2 < (rA + x) int_0^x w'^2), so K22(FOAM) >= K2 > 0."""
    for n in (5, 20):
        for tip in (None, TipMass(0.1, 8.0), TipMass(0.5, 8.0), TipMass(5.0, 4.0),
                    TipMass(50.0, 0.2)):
            sm = assemble(PARAMS, tip, n)
            assert np.linalg.eigvalsh(sm.M2 - sm.D).max() < 0.0
            assert np.isnan(critical_speed("FOAM", PARAMS, tip, n, 1e6))
    sm = assemble(PARAMS, TipMass(0.5, 8.0), 5)
    lowest = np.linalg.eigvalsh(K22(sm, "FOAM", np.linspace(0.0, 20.0, 201)))[:, 0]
    assert np.all(np.diff(lowest) > 0.0)  # stiffening: increases with speed
    ds = critical_speed_sweep(PARAMS, [0.1, 0.5, 5.0], np.linspace(0, 8, 9), 5, 20.0)
    assert ds["critical_speed"].sel(model="FOAM").isnull().all()
    assert (ds["mu_max"].sel(model="FOAM") < 0).all()


def test_first_frequency_converges_with_the_number_of_modes():
    tip = TipMass(0.5, 6.0)  # interior point: the clamped-free modes are not eigenmodes
    first = np.array([natural_frequencies(assemble(PARAMS, tip, n))[0] for n in range(1, 13)])
    assert np.all(np.diff(first) <= 1e-14 * first[0])  # Rayleigh-Ritz: monotone from above
    changes = np.abs(np.diff(first))
    assert changes[-1] < 1e-6 * first[-1] and changes[-1] < 0.01 * changes[0]


def test_foam_stiffening_against_rotating_cantilever_tables():
    """rA = 0: the transverse FOAM frequency obeys omega_c^2 = omega_f^2 - gamma^2 with the
    classic flapwise values (Wright et al. 1982), printed to 4 decimals."""
    params = dataclasses.replace(PARAMS, rA=0.0)
    gamma = np.arange(13.0)
    flapwise = np.array([3.5160, 3.6816, 4.1373, 4.7973, 5.5850, 6.4495, 7.3604, 8.2996, 9.2568,
                         10.2257, 11.2023, 12.1843, 13.1702])
    sm = assemble(params, None, 20)
    chordwise = transverse_frequencies(sm, "FOAM", gamma * SCALE)[:, 0] / SCALE
    assert np.max(np.abs(np.sqrt(chordwise**2 + gamma**2) - flapwise)) < 1e-4


def test_coupled_foam_against_hamza_cherif_chordwise_values():
    """Axial stretch and Coriolis coupling included: delta = 0, slenderness alpha = 70
    (Hamza-Cherif & Houmat 2004, Table 2, printed to 3-5 significant digits and truncated, see
    hubbeam.validation.published): the exact value lies in [printed, printed + unit), and our
    20-mode Rayleigh-Ritz value lies above the exact one."""
    params = dataclasses.replace(PARAMS, rA=0.0, I=PARAMS.A * PARAMS.L**2 / 70**2)
    scale = np.sqrt(params.E * params.I / (RHO_A * params.L**4))
    gamma = np.array([2.0, 4.0, 6.0, 8.0, 10.0])
    printed = np.array([3.6195, 3.888, 4.2393, 4.6105, 4.97])
    unit = np.array([1e-4, 1e-3, 1e-4, 1e-4, 1e-2])  # of the last printed digit
    sm = assemble(params, None, 20)
    coupled = gyroscopic_frequencies(sm, "FOAM", gamma * scale)[:, 0] / scale
    assert np.all((coupled - printed >= 0.0) & (coupled - printed < unit)), coupled - printed
    # the transverse subsystem alone misses the coupling by much more than that at gamma = 10
    uncoupled = transverse_frequencies(sm, "FOAM", gamma * scale)[:, 0] / scale
    assert uncoupled[-1] - printed[-1] > 0.05


def test_sweeps_are_consistent_with_the_pointwise_functions():
    masses, positions, speeds = [0.0, 0.5], np.linspace(0.0, 8.0, 5), np.linspace(0.0, 4.0, 81)
    k22 = k22_sweep(PARAMS, masses, positions, speeds, 5)
    crit = critical_speed_sweep(PARAMS, masses, positions, 5, 20.0)
    tip = TipMass(0.5, 6.0)
    sm = assemble(PARAMS, tip, 5)
    np.testing.assert_allclose(
        k22["eigenvalue"].sel(model="FOAM", tip_mass=0.5, position=6.0).values,
        np.linalg.eigvalsh(K22(sm, "FOAM", speeds)), rtol=1e-12, atol=1e-12)
    assert crit["critical_speed"].sel(model="TLAM", tip_mass=0.5, position=6.0) == pytest.approx(
        critical_speed("TLAM", PARAMS, tip, 5, 20.0), rel=1e-12)
    # the dominant eigenvalue changes sign at the critical speed
    dominant = k22["dominant_eigenvalue"].sel(model="TLAM", tip_mass=0.5, position=6.0).values
    omega_c = float(crit["critical_speed"].sel(model="TLAM", tip_mass=0.5, position=6.0))
    assert np.all(dominant[speeds < omega_c] > 0) and np.all(dominant[speeds > omega_c] < 0)
    for name in list(k22.variables) + list(crit.variables):
        ds = k22 if name in k22.variables else crit
        assert "long_name" in ds[name].attrs, name


def test_campbell_and_table2():
    speeds = np.linspace(0.0, 4.0, 41)
    ds = campbell(PARAMS, [0.0, 0.5], speeds, 5)
    sm = assemble(PARAMS, None, 5)
    natural_hz = natural_frequencies(sm) / (2 * np.pi)
    for model in ("TLAM", "FOAM"):
        np.testing.assert_allclose(ds["frequency"].sel(model=model, tip_mass=0.0, speed=0.0),
                                   natural_hz, rtol=1e-12)
    tlam = ds["frequency"].sel(model="TLAM", tip_mass=0.5, mode=1).values
    omega_c = critical_speed("TLAM", PARAMS, TipMass(0.5, 8.0), 5, 20.0)
    np.testing.assert_array_equal(np.isnan(tlam), speeds > omega_c)
    assert (ds["growth_rate"].sel(model="FOAM") < 1e-9).all()
    assert (ds["growth_rate"].sel(model="TLAM", tip_mass=0.5).values[speeds > omega_c] > 1e-3).all()
    table = table2(PARAMS, 1.0, 5)
    assert list(table.columns) == ["mode", "natural", "TLAM", "FOAM", "paper_natural",
                                   "paper_TLAM", "paper_FOAM"]
    np.testing.assert_allclose(table["natural"], natural_hz, rtol=1e-14)
    assert np.all(table["TLAM"] < table["natural"]) and np.all(table["natural"] < table["FOAM"])


def test_bad_model_name_is_reported():
    with pytest.raises(ValueError, match="model = 'SFOAM'"):
        critical_speed("SFOAM", PARAMS, None, 5, 20.0)
    with pytest.raises(ValueError, match="critical_speed_search_max"):
        critical_speed("TLAM", PARAMS, None, 5, -1.0)


def test_fig09_and_campbell_figures_draw_from_the_datasets():
    from matplotlib.figure import Figure

    from hubbeam.plotting import campbell as campbell_figure
    from hubbeam.plotting import fig09
    from hubbeam.plotting.style import styled

    masses, positions, speeds = [0.0, 0.1, 0.5], np.linspace(0.0, 8.0, 9), np.linspace(0, 4, 21)
    k22 = k22_sweep(PARAMS, masses, positions, speeds, 3)
    crit = critical_speed_sweep(PARAMS, masses, positions, 3, 20.0)
    with styled():
        fig = fig09.plot(k22, crit, speed=2.0)
        assert isinstance(fig, Figure) and "2 rad/s" in fig.axes[2].get_title(loc="left")
        # the plotted data: maps, critical-speed curves and single curves of the datasets
        for ax, mass in zip(fig.axes[:2], (0.1, 0.5)):
            dominant = k22.dominant_eigenvalue.sel(model="TLAM", tip_mass=mass)
            drawn = np.asarray(ax.collections[0].get_array()).ravel()
            np.testing.assert_array_equal(drawn, dominant.transpose("speed", "position").values.ravel())
            line = next(l for l in ax.get_lines() if l.get_label().startswith("critical speed"))
            np.testing.assert_array_equal(line.get_ydata(),
                                          crit.critical_speed.sel(model="TLAM", tip_mass=mass).values)
        curves = [l for l in fig.axes[2].get_lines() if l.get_label().startswith("TLAM")]
        assert len(curves) == 2
        for line, mass in zip(curves, (0.1, 0.5)):
            assert f"$m_t$ = {mass:g} kg" in line.get_label()
            np.testing.assert_array_equal(line.get_ydata(), k22.dominant_eigenvalue.sel(
                model="TLAM", tip_mass=mass, speed=2.0).values)
        fig = campbell_figure.plot(campbell(PARAMS, masses, speeds, 3), crit)
        assert isinstance(fig, Figure) and len(fig.axes) == 3
        with pytest.raises(ValueError, match="speed = 2.5"):
            fig09.plot(k22, crit, speed=2.5)


def test_printed_table2_supports_the_transverse_subsystem_reading():
    """The paper's TLAM row is sqrt(omega^2 - Omega^2) of its natural row to every printed digit
    (our reading of Table 2: transverse subsystem, no Coriolis coupling)."""
    from hubbeam.model import printed as paper

    natural = 2 * np.pi * np.array(paper.TABLE2["natural"])
    tlam = np.sqrt(natural**2 - paper.TABLE2_SPEED**2) / (2 * np.pi)
    np.testing.assert_array_equal(np.round(tlam, 4), paper.TABLE2["TLAM"])


def test_table2_k22_maps_critical_speeds_and_validation_share_one_stiffness(monkeypatch):
    """Eq. (31) has one home (hubbeam.model.linearised.centrifugal_matrix): changing it there changes
    Table 2, the K22 map, the critical speed and the published-table validation alike."""
    from hubbeam.model import linearised
    from hubbeam.validation import rotating_eigen

    sm = assemble(PARAMS, None, 3)
    dimensionless = assemble(rotating_eigen.dimensionless_parameters(70.0, 0.0), None, 3)

    def results():
        return (table2(PARAMS, 1.0, 3)[["TLAM", "FOAM"]].to_numpy(),
                k22_sweep(PARAMS, [0.0, 0.1], [8.0], [1.0, 2.0], 3)["eigenvalue"].values,
                critical_speed("TLAM", PARAMS, None, 3, 20.0),
                rotating_eigen.frequencies(dimensionless, 2.0, "flapwise"),
                rotating_eigen.frequencies(dimensionless, 2.0, "chordwise"),
                transverse_frequencies(sm, "FOAM", 1.0))

    before = results()
    original = linearised.centrifugal_matrix
    monkeypatch.setattr(linearised, "centrifugal_matrix",
                        lambda M2, D, model: 1.01 * original(M2, D, model))
    after = results()
    for old, new in zip(before, after):
        assert not np.allclose(old, new, rtol=1e-6, atol=0.0, equal_nan=True)


def test_gyroscopic_eigenvalues_accurate_for_slow_modes_near_the_critical_speed():
    """Slow TLAM mode just below its critical speed, beside axial frequencies ~1e4 times larger:
    each eigenvalue satisfies det(lambda^2 M + lambda G + K) = 0 to Newton-refinement accuracy
    (the refinement uses the smallest singular triplet of the quadratic, not our solver)."""
    from hubbeam.model import linearised

    sm = assemble(PARAMS, TipMass(0.0, PARAMS.L), 5)
    speed = 0.97 * critical_speed("TLAM", PARAMS, None, 5, 20.0)
    M, G, K = linearised.constant_speed_matrices(sm, "TLAM", speed, axial=True)
    lam = gyroscopic_eigenvalues(sm, "TLAM", speed)
    slow = lam[np.argmin(np.where(lam.imag > 0.0, lam.imag, np.inf))]
    refined = slow
    for _ in range(4):
        Q = refined**2 * M + refined * G + K
        U, _, Vh = np.linalg.svd(Q)
        x, y = Vh[-1].conj(), U[:, -1]
        refined -= (y.conj() @ Q @ x) / (y.conj() @ (2.0 * refined * M + G) @ x)
    assert abs(slow - refined) <= 1e-11 * abs(refined)
