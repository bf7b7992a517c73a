"""Frequency responses, poles and zeros of the linear models (hubbeam.linear.frequency) and their
datasets and figures (hubbeam.linear.datasets)."""

import numpy as np
import pytest

from hubbeam.linear import datasets, frequency, linear_model
from hubbeam.linear.axes import tip_mass_axis
from hubbeam.model import eigen
from hubbeam.model.damping import damping_matrices
from hubbeam.model.matrices import assemble
from hubbeam.model.parameters import BeamParameters, TipMass
from hubbeam.model.printed import TABLE1

PARAMS = BeamParameters(**TABLE1)
N_MODES = 4
MODELS = ("TLAM", "FOAM", "SFOAM", "CFOAM")
TIP = TipMass(mass=0.5, position=PARAMS.L)
MODAL = {"kind": "modal", "axial": 0.01, "transverse": 0.03}


@pytest.fixture(scope="module")
def systems():
    return {mass: assemble(PARAMS, tip, N_MODES) for mass, tip in ((0.0, None), (0.5, TIP))}


def assert_same_roots(actual, expected, atol):
    """The two sets of roots agree to ``atol`` under the best one-to-one matching."""
    from scipy.optimize import linear_sum_assignment

    assert len(actual) == len(expected)
    distance = np.abs(np.subtract.outer(np.asarray(actual), np.asarray(expected)))
    rows, columns = linear_sum_assignment(distance)
    assert distance[rows, columns].max() <= atol, distance[rows, columns].max()


def critical(mass):
    return eigen.critical_speed("TLAM", PARAMS, TIP if mass else None, N_MODES, 20.0)


@pytest.mark.parametrize("mass", [0.0, 0.5])
@pytest.mark.parametrize("damped", [False, True])
def test_collocated_poles_and_zeros_alternate_for_every_model(systems, mass, damped):
    """Hub torque to hub angle: poles and zeros alternate on the imaginary axis for every model at
    every speed below TLAM's critical speed (and for FOAM, SFOAM, CFOAM above it too); beyond it
    TLAM's divergent pair breaks the alternation."""
    sm = systems[mass]
    C = damping_matrices(MODAL, sm) if damped else None
    below = np.array([0.0, 0.5, 0.9]) * critical(mass)
    above = 1.2 * critical(mass)
    for model in MODELS:
        for speed in [*below, above]:
            lm = linear_model(PARAMS, sm, model, speed, "free", C)
            alternating = frequency.alternates(frequency.poles(lm), frequency.zeros(lm, "hub_angle"))
            assert alternating == (model != "TLAM" or speed < above), (model, speed)


@pytest.mark.parametrize("model", MODELS)
def test_collocated_zeros_are_the_poles_with_the_hub_held(systems, model):
    """The zeros of hub torque to hub angle equal the poles of the prescribed-hub model (its two
    rigid poles at 0, the hub angle and speed driven by the input, left out)."""
    sm = systems[0.5]
    for speed in (0.0, 1.5, 3.0):
        zeros = frequency.zeros(linear_model(PARAMS, sm, model, speed, "free"), "hub_angle")
        held = frequency.poles(linear_model(PARAMS, sm, model, speed, "prescribed"))
        held = held[np.abs(held) > 1e-9 * np.abs(held).max()]
        assert_same_roots(zeros, held, frequency.RELATIVE_TOLERANCE * np.abs(held).max())


@pytest.mark.parametrize("model", MODELS)
def test_tip_arc_of_a_free_hub_has_a_mirrored_non_minimum_phase_zero_pair(systems, model):
    """Hub torque to the tip's arc position, undamped, at rest and at 1.5 rad/s (below TLAM's
    critical speeds, 1.94 rad/s with the tip mass): a real zero pair +-z (z > 0, right and left
    half-plane), the tip first moving against the torque; none for the collocated hub angle."""
    for speed in (0.0, 1.5):
        for sm in systems.values():
            lm = linear_model(PARAMS, sm, model, speed, "free")
            zeros = frequency.zeros(lm, "tip_arc")
            rhp = frequency.right_half_plane(zeros)
            z = rhp[0]
            assert abs(z.imag) <= 1e-9 * abs(z), (model, speed, rhp)
            assert np.min(np.abs(zeros + z)) <= 1e-7 * abs(z)  # the mirror -z
            # the collocated output has none
            assert frequency.right_half_plane(frequency.zeros(lm, "hub_angle")).size == 0


def test_dynamic_stiffening_raises_the_non_minimum_phase_zero_and_tlam_loses_it(systems):
    """The smallest right-half-plane zero of the tip arc rises with speed for FOAM, SFOAM and
    CFOAM (stiffening) and falls towards 0 for TLAM as its critical speed nears (softening)."""
    sm = systems[0.0]
    speeds = np.linspace(0.0, 0.97 * critical(0.0), 8)

    def lowest(model):
        return np.array([abs(frequency.right_half_plane(frequency.zeros(
            linear_model(PARAMS, sm, model, s, "free"), "tip_arc"))[0]) for s in speeds])

    for model in ("FOAM", "SFOAM", "CFOAM"):
        assert np.all(np.diff(lowest(model)) > 0), model
    tlam = lowest("TLAM")
    assert np.all(np.diff(tlam) < 0) and tlam[-1] < 0.3 * tlam[0]


@pytest.mark.parametrize("mass", [0.0, 0.5])
def test_tlam_pole_crosses_zero_at_the_critical_speed(systems, mass):
    """Hub held: just below TLAM's critical speed every pole is on the imaginary axis and the
    lowest elastic one is slow; just above, a positive real pole (divergence) appears."""
    sm, omega_c = systems[mass], critical(mass)
    below = frequency.poles(linear_model(PARAMS, sm, "TLAM", omega_c * (1 - 1e-4), "prescribed"))
    above = frequency.poles(linear_model(PARAMS, sm, "TLAM", omega_c * (1 + 1e-4), "prescribed"))
    scale = np.abs(below).max()
    assert np.all(np.abs(below.real) <= 1e-9 * scale)
    slowest = np.sort(np.abs(below.imag[np.abs(below) > 1e-9 * scale]))[0]
    assert slowest < 0.05 * omega_c
    growing = above[above.real > 1e-9 * scale]
    assert growing.size == 1 and abs(growing[0].imag) == 0.0


@pytest.mark.parametrize("model", MODELS)
def test_hub_angle_response_has_the_rigid_and_the_blocked_inertia(systems, model):
    """Hub torque to hub angle at rest: ``1 / (J omega^2)`` with the whole inertia ``Jh + Jb``
    far below the first mode and with the inertia that the beam's modes leave to the hub,
    ``Jh + Jb - V2 M2^-1 V2^T``, far above them; phase -180 degrees at both ends."""
    sm = systems[0.5]
    omega = np.array([1e-4, 1e6])
    magnitude, phase = frequency.frequency_response(linear_model(PARAMS, sm, model, 0.0, "free"),
                                                    ["hub_angle"], omega)
    total = sm.Jh + sm.Jb
    high = total - sm.V2 @ np.linalg.solve(sm.M2, sm.V2)
    # relative corrections of order (omega / omega_1)^2 < 1e-8 (omega_1 = 1.2 rad/s) and
    # (omega_n / omega)^2 < 1e-7 (omega_n < 200 rad/s; the axial modes are not coupled to the hub
    # at rest)
    np.testing.assert_allclose(magnitude[0, 0] * omega[0]**2, 1 / total, rtol=1e-7)
    np.testing.assert_allclose(magnitude[0, 1] * omega[1]**2, 1 / high, rtol=1e-6)
    np.testing.assert_allclose(phase[0], -180.0, atol=1e-6)


def test_frequency_response_against_the_resolvent(systems):
    """python-control's response equals ``C (i omega I - A)^-1 B + D`` solved directly."""
    lm = linear_model(PARAMS, systems[0.5], "CFOAM", 2.0, "free",
                      damping_matrices(MODAL, systems[0.5]))
    omega = np.logspace(-1, 3, 7)
    outputs = ["hub_angle", "tip_deflection", "tip_arc", "tip_acceleration"]
    magnitude, phase = frequency.frequency_response(lm, outputs, omega)
    rows = [lm.outputs.index(name) for name in outputs]
    direct = np.stack([lm.C[rows] @ np.linalg.solve(1j * w * np.eye(lm.A.shape[0]) - lm.A, lm.B)[:, 0]
                       + lm.D[rows, 0] for w in omega], axis=-1)
    np.testing.assert_allclose(magnitude, np.abs(direct), rtol=1e-9)
    np.testing.assert_allclose(np.exp(1j * np.radians(phase)), direct / np.abs(direct), atol=1e-9)


def test_alternation_and_right_half_plane_on_constructed_roots():
    poles = np.array([0, 0, 2j, -2j, 5j, -5j])
    assert frequency.alternates(poles, [1j, -1j, 3j, -3j])
    assert not frequency.alternates(poles, [3j, -3j, 4j, -4j])  # two zeros between two poles
    assert not frequency.alternates(poles, [1j, -1j])  # a pole pair too many
    assert not frequency.alternates(poles, [1.0, -1.0, 3j, -3j])  # a real zero pair
    # a cancelled pair (pole = zero) still alternates
    assert frequency.alternates(poles, [2j, -2j, 3j, -3j])
    rhp = frequency.right_half_plane([-1.0, 2.0, 1e-14 + 3j, 1 + 1j, 1 - 1j])
    np.testing.assert_array_equal(rhp, [1 + 1j, 1 - 1j, 2.0])


def test_bad_outputs_and_frequencies_are_refused(systems):
    lm = linear_model(PARAMS, systems[0.0], "FOAM", 1.0, "free", outputs=["hub_angle"])
    with pytest.raises(ValueError, match="output = 'tip_arc'"):
        frequency.zeros(lm, "tip_arc")
    with pytest.raises(ValueError, match="omega"):
        frequency.frequency_response(lm, ["hub_angle"], [-1.0, 2.0])
    with pytest.raises(ValueError, match="outputs"):
        datasets.bode(tip_mass_axis(PARAMS, [0.0], 2), [0.0], [1.0], outputs=["tip_speed"])
    with pytest.raises(ValueError, match="omega"):
        datasets.bode(tip_mass_axis(PARAMS, [0.0], 2), [0.0], [])


def test_pole_zero_and_bode_datasets_write_and_draw(tmp_path):
    from matplotlib.figure import Figure

    from hubbeam.plotting import bode, pole_zero
    from hubbeam.plotting.style import styled
    from hubbeam.results.io import open_result, write_netcdf

    speeds = np.linspace(0.0, 4.0, 9)
    pz = open_result(write_netcdf(datasets.poles_zeros(tip_mass_axis(PARAMS, [0.0, 0.5], 3), speeds),
                                  tmp_path / "pz.nc"))
    # alternation up to TLAM's critical speed only, everywhere for the others; beyond it TLAM's
    # collocated zeros (the held hub's poles) have their divergent one in the right half-plane
    others = ["FOAM", "SFOAM", "CFOAM"]
    for mass in (0.0, 0.5):
        below = speeds < eigen.critical_speed("TLAM", PARAMS, TIP if mass else None, 3, 20.0)
        tlam = pz.sel(model="TLAM", tip_mass=mass)
        np.testing.assert_array_equal(tlam.alternates.values.astype(bool), below)
        np.testing.assert_array_equal(tlam.rhp_zero_count.sel(output="hub_angle"), ~below)
        assert pz.alternates.sel(model=others, tip_mass=mass).all()
    assert (pz.rhp_zero_count.sel(output="hub_angle", model=others) == 0).all()
    assert (pz.rhp_zero_count.sel(output="tip_arc", model="FOAM") >= 2).all()
    omega = np.logspace(-1, 3, 50)
    bd = open_result(write_netcdf(datasets.bode(tip_mass_axis(PARAMS, [0.0], 3, damping=MODAL), [0.0, 3.5], omega),
                                  tmp_path / "bode.nc"))
    assert bd.hub_angle_magnitude.attrs["units"] == "rad N-1 m-1"
    np.testing.assert_array_equal(bd.stable.sel(tip_mass=0.0, speed=3.5).values, [0, 1, 1, 1])
    with styled():
        assert isinstance(pole_zero.plot(pz, tip_mass=0.5), Figure)
        fig = bode.plot(bd)
        assert "TLAM unstable" in fig.axes[1].get_title(loc="left")
        assert len(fig.axes) == 6 * 2
