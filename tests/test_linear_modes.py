"""Modes of linear models and their tracking over speed (hubbeam.linear.tracking)."""

import numpy as np
import pytest

from hubbeam.linear import tracking


def first_order(M, C, K):
    """``A`` of ``M y'' + C y' + K y = 0`` with ``x = (y, y')``, for stacks of ``C`` and ``K``."""
    K, C = np.broadcast_arrays(K, C)
    n = M.shape[-1]
    A = np.zeros(K.shape[:-2] + (2 * n, 2 * n))
    Minv = np.linalg.inv(M)
    A[..., :n, n:] = np.eye(n)
    A[..., n:, :n] = -Minv @ K
    A[..., n:, n:] = -Minv @ C
    return A


def two_modes(parameter, coupling):
    """Two oscillators, stiffness ``parameter`` and 1, coupled by ``coupling``: their frequencies
    cross at ``parameter = 1`` (no coupling) or veer apart by about ``coupling`` there."""
    p = np.asarray(parameter, float)
    K = np.zeros(p.shape + (2, 2))
    K[..., 0, 0], K[..., 1, 1] = p, 1.0
    K[..., 0, 1] = K[..., 1, 0] = coupling
    return first_order(np.eye(2), np.zeros((2, 2)), K)


# a grid that steps over the crossing (parameter 1) without landing on it
GRID = np.linspace(0.52, 1.52, 11)


def dominant(modes):
    """Index of the coordinate with the largest share of each shape, (s, m)."""
    return np.argmax(np.abs(modes.shape), axis=-1)


@pytest.mark.parametrize("coupling", [0.0, 1e-4])
def test_tracking_keeps_shape_identity_where_sorting_swaps(coupling):
    """Crossing (no coupling) and veering narrower than the grid step: sorted by frequency, the
    lower mode is coordinate 0 before the crossing and coordinate 1 after; tracked, each mode keeps
    its coordinate and its frequency follows sqrt(k) of that coordinate through the crossing."""
    sorted_modes = tracking.state_modes(two_modes(GRID, coupling))
    below, above = GRID < 1.0, GRID > 1.0
    assert np.all(dominant(sorted_modes)[below, 0] == 0)
    assert np.all(dominant(sorted_modes)[above, 0] == 1)
    tracked = tracking.track(sorted_modes)
    assert np.all(dominant(tracked)[:, 0] == 0) and np.all(dominant(tracked)[:, 1] == 1)
    # the coupling shifts each frequency by at most coupling^2 / (|k0 - k1| * 2 omega) <= 1e-7
    np.testing.assert_allclose(tracked.frequency[:, 0], np.sqrt(GRID), rtol=0, atol=1e-6)
    np.testing.assert_allclose(tracked.frequency[:, 1], 1.0, rtol=0, atol=1e-6)


def test_a_resolved_veering_follows_the_continuous_branches():
    """Where the grid resolves the veering (coupling 0.05, grid step 0.002), the shapes rotate into
    each other continuously: tracking then follows the frequency branches, which never cross."""
    grid = np.linspace(0.8, 1.2, 201)
    modes = tracking.state_modes(two_modes(grid, 0.05))
    tracked = tracking.track(modes)
    np.testing.assert_array_equal(tracked.eigenvalue, modes.eigenvalue)
    neighbours = tracking.mac(tracked.shape[:-1], tracked.shape[1:]).diagonal(axis1=1, axis2=2)
    assert np.all(neighbours > 0.99)
    # across the whole range each branch turns from one coordinate to the other
    np.testing.assert_array_equal(dominant(tracked)[[0, -1], 0], [0, 1])


def test_modal_damping_ratio_and_frequency_are_recovered():
    """``C = M Phi diag(2 zeta omega) Phi^T M`` gives each mode the ratio zeta and the damped
    frequency omega sqrt(1 - zeta^2)."""
    rng = np.random.default_rng(1)
    X = rng.normal(size=(4, 4))
    M = X @ X.T + 4 * np.eye(4)
    omega = np.array([1.0, 3.0, 7.0, 20.0])
    zeta = np.array([0.01, 0.05, 0.2, 0.5])
    L = np.linalg.cholesky(M)
    Phi = np.linalg.inv(L.T) @ np.linalg.qr(rng.normal(size=(4, 4)))[0]  # Phi^T M Phi = I
    Minv_phi = M @ Phi
    K = Minv_phi @ np.diag(omega**2) @ Minv_phi.T
    C = Minv_phi @ np.diag(2 * zeta * omega) @ Minv_phi.T
    modes = tracking.state_modes(first_order(M, C, K)[None])
    np.testing.assert_allclose(modes.damping_ratio[0], zeta, rtol=1e-12)
    np.testing.assert_allclose(modes.frequency[0], omega * np.sqrt(1 - zeta**2), rtol=1e-12)
    assert modes.stable.all() and not modes.divergent.any() and not modes.rigid.any()


def test_negative_stiffness_is_one_divergent_unstable_mode():
    """Stiffness -4 and 9: one divergent mode (+-2, represented by +2, ratio -1) and a vibration
    mode at 3 rad/s; the divergent one is unstable."""
    K = np.diag([-4.0, 9.0])
    modes = tracking.state_modes(first_order(np.eye(2), np.zeros((2, 2)), K)[None])
    np.testing.assert_allclose(modes.eigenvalue[0], [2.0, 3.0j], atol=1e-12)
    np.testing.assert_array_equal(modes.divergent[0], [True, False])
    np.testing.assert_array_equal(modes.stable[0], [False, True])
    np.testing.assert_allclose(modes.damping_ratio[0], [-1.0, 0.0], atol=1e-12)


def test_a_free_rotation_is_a_rigid_mode():
    """A free coordinate (no stiffness; a defective double eigenvalue 0) coupled to an oscillator
    by its mass: one rigid mode (frequency 0, ratio NaN, stable) and one vibration mode, whose
    frequency sqrt(k / (m (1 - c^2 / (J m)))) is that of the oscillator with the free inertia."""
    J, m, c, k = 2.0, 1.0, 0.5, 3.0
    M = np.array([[J, c], [c, m]])
    A = first_order(M, np.zeros((2, 2)), np.diag([0.0, k]))[None]
    modes = tracking.state_modes(A)
    np.testing.assert_array_equal(modes.rigid[0], [True, False])
    assert modes.stable.all()
    assert np.isnan(modes.damping_ratio[0, 0]) and modes.frequency[0, 0] == 0.0
    np.testing.assert_allclose(modes.frequency[0, 1], np.sqrt(k / (m - c**2 / J)), rtol=1e-12)


def test_labels_from_the_dominant_coordinate_group():
    """A rigid mode is the hub's; every other mode is flexible, axial or bending by the larger share
    of its content, the hub's (and a root's) angle counted with the bending functions."""
    names = ("theta", "q1_1", "q1_2", "q2_1", "q2_2")
    shapes = np.array([[1.0, 0.1, 0, 0.2, 0], [0.1, 0, 0.2, 0.3, 1.0], [0.0, 0.9, 0.1, 0.5, 0.5],
                       [1.0, 0.6, 0, 0.2, 0]])
    rigid = np.array([True, False, False, False])
    labels, fractions = tracking.dominant_content(shapes, names, np.ones(5), rigid)
    assert list(labels) == ["hub", "bending 2", "axial 1", "bending 1"]  # the last: mostly the hub's angle
    np.testing.assert_allclose(sum(fractions.values()), 1.0)
    # weights decide between the groups: the axial coordinates weighted by 20 take the second shape
    weights = np.array([1.0, 20, 20, 1, 1])
    assert tracking.dominant_content(shapes, names, weights, rigid)[0][1] == "axial 2"
    spring = ("theta", "q2_1", "phi")  # a compliant root: the root's and the hub's angles
    assert list(tracking.dominant_content(np.array([[1.0, 0.1, 0.5]]), spring, np.ones(3), [False])[0]) == [
        "bending 1"]


def test_mac_is_one_for_a_complex_multiple_and_zero_for_orthogonal_shapes():
    u = np.array([[1.0 + 1j, 2.0, 0.0]])
    v = np.array([[(1.0 + 1j) * (0.3 - 2j), 2.0 * (0.3 - 2j), 0.0], [0.0, 0.0, 1j]])
    np.testing.assert_allclose(tracking.mac(u, v), [[1.0, 0.0]], atol=1e-15)


@pytest.mark.parametrize("names", [("theta", "q1"), ("q3_1",), ("theta_1",)])
def test_unknown_state_names_are_refused(names):
    with pytest.raises(ValueError, match="state name"):
        tracking.coordinate_groups(names)


def test_a_matrix_that_is_not_a_stack_of_mechanical_systems_is_refused():
    with pytest.raises(ValueError, match="expected a stack"):
        tracking.state_modes(np.eye(3)[None])


# ---------------------------------------------------------------------------------------------
# the paper's beam: tracked, damped Campbell diagrams and mode shapes

from hubbeam.linear import datasets  # noqa: E402
from hubbeam.linear.axes import tip_mass_axis  # noqa: E402
from hubbeam.model import eigen  # noqa: E402
from hubbeam.model.matrices import assemble  # noqa: E402
from hubbeam.model.modes import transverse_modes  # noqa: E402
from hubbeam.model.parameters import BeamParameters, TipMass  # noqa: E402
from hubbeam.model.printed import TABLE1  # noqa: E402

PARAMS = BeamParameters(**TABLE1)
N_MODES = 4
MODAL = {"kind": "modal", "axial": 0.01, "transverse": 0.03}


@pytest.fixture(scope="module")
def campbell_ds():
    return datasets.campbell(tip_mass_axis(PARAMS, [0.0, 0.5], N_MODES, damping=MODAL), np.linspace(0.0, 4.0, 81))


@pytest.mark.parametrize("mass", [0.0, 0.5])
def test_tlam_becomes_unstable_at_its_critical_speed_to_the_grid_step(campbell_ds, mass):
    """The first growing mode of TLAM appears at the first grid speed above the exact critical
    speed of K22 (hubbeam.model.eigen), held and free hub; FOAM, SFOAM and CFOAM stay stable."""
    tip = TipMass(mass=mass, position=PARAMS.L) if mass else None
    critical = eigen.critical_speed("TLAM", PARAMS, tip, N_MODES, 20.0)
    speeds = campbell_ds.speed.values
    expected = speeds[speeds > critical][0]
    for hub in ("held", "free"):
        assert campbell_ds.unstable_from.sel(model="TLAM", tip_mass=mass, hub=hub) == expected
        tlam = campbell_ds.sel(model="TLAM", tip_mass=mass, hub=hub)
        growing = tlam.mode.values[(tlam.stable.sel(speed=expected) == 0).values]
        assert [str(tlam.mode_label.sel(mode=m).item()) for m in growing] == ["bending 1"]
        assert tlam.kind.sel(speed=expected, mode=growing[0]) == datasets.KINDS["divergent"]
    np.testing.assert_allclose(campbell_ds.critical_speed.sel(model="TLAM", tip_mass=mass), critical)
    assert np.isnan(campbell_ds.unstable_from.sel(model=["FOAM", "SFOAM", "CFOAM"])).all()


def test_modal_damping_ratio_is_recovered_with_the_hub_held_at_rest(campbell_ds):
    """Held hub at rest, modal damping: every bending mode has the transverse ratio and every
    axial mode the axial one (with and without the tip mass); the rigid hub mode has none."""
    at_rest = campbell_ds.sel(hub="held", speed=0.0)
    label = at_rest.mode_label.values
    ratio = at_rest.damping_ratio.values
    bending = np.char.startswith(label.astype(str), "bending")
    axial = np.char.startswith(label.astype(str), "axial")
    np.testing.assert_allclose(ratio[bending], MODAL["transverse"], rtol=1e-9)
    np.testing.assert_allclose(ratio[axial], MODAL["axial"], rtol=1e-9)
    assert np.isnan(ratio[label == "hub"]).all()
    assert (at_rest.kind.values[label == "hub"] == datasets.KINDS["rigid"]).all()
    # SFOAM keeps no axial modes: padded
    assert (at_rest.kind.sel(model="SFOAM").values == datasets.KINDS["none"]).sum() == 2 * N_MODES


def test_held_hub_modes_are_the_gyroscopic_eigenvalues_of_eqs_29_to_31():
    """Undamped, hub held, below TLAM's critical speed: the tracked frequencies of TLAM and FOAM
    are, as sets, those of hubbeam.model.eigen's gyroscopic eigenproblem (axial and bending)."""
    speeds = np.linspace(0.0, 2.8, 15)
    ds = datasets.campbell(tip_mass_axis(PARAMS, [0.0], N_MODES), speeds).sel(tip_mass=0.0, hub="held")
    sm = assemble(PARAMS, None, N_MODES)
    for model in ("TLAM", "FOAM"):
        tracked = ds.frequency.sel(model=model).where(ds.kind.sel(model=model) == 0).values
        tracked = np.sort(tracked, axis=-1)[:, :2 * N_MODES] * 2 * np.pi
        reference = eigen.gyroscopic_frequencies(sm, model, speeds)
        np.testing.assert_allclose(tracked, reference, rtol=1e-9)


def test_tracked_labels_at_rest_follow_the_coordinates_without_tip_mass(campbell_ds):
    """Without a tip mass and with the hub held at rest, the coordinates are the beam's own modes:
    by frequency the labels are hub, bending 1..n, axial 1..n; tracking keeps the bending labels
    over the whole speed range of FOAM (no crossing among its first modes)."""
    labels = campbell_ds.mode_label.sel(model="FOAM", tip_mass=0.0, hub="held").values.tolist()
    assert labels == (["hub"] + [f"bending {k}" for k in range(1, N_MODES + 1)]
                      + [f"axial {k}" for k in range(1, N_MODES + 1)])
    along = campbell_ds.label.sel(model="FOAM", tip_mass=0.0, hub="held").values
    assert (along == along[:1]).all()


def test_mode_shapes_at_rest_are_the_beam_functions(campbell_ds):
    """Held hub at rest, no tip mass: mode k's transverse shape is f2_k / max |f2_k|."""
    shapes = datasets.mode_shapes(campbell_ds, tip_mass_axis(PARAMS, [0.0], N_MODES), count=3, stations=41)
    x = shapes.x.values
    f2 = transverse_modes(x, N_MODES, PARAMS)[:, :3]
    expected = f2 / f2[np.argmax(np.abs(f2), axis=0), np.arange(3)]
    for model in shapes.model.values:
        got = shapes.shape.sel(model=model, tip_mass=0.0, hub="held", speed=0.0).values
        np.testing.assert_allclose(got, expected.T, atol=1e-9)
    assert shapes.mode_label.sel(model="TLAM", tip_mass=0.0, hub="free").values.tolist() == \
        ["bending 1", "bending 2", "bending 3"]
    assert np.all(np.abs(shapes.shape).max(dim="x") <= 1.0 + 1e-12)


def test_campbell_and_shapes_write_as_cf_files_and_draw(tmp_path, campbell_ds):
    from matplotlib.figure import Figure

    from hubbeam.plotting import campbell_tracked, linear_mode_shapes
    from hubbeam.plotting.style import styled
    from hubbeam.results.io import open_result, write_netcdf

    back = open_result(write_netcdf(campbell_ds, tmp_path / "campbell.nc"))
    np.testing.assert_array_equal(back.label.values, campbell_ds.label.values)
    np.testing.assert_array_equal(back.kind.values, campbell_ds.kind.values)
    shapes = datasets.mode_shapes(back, tip_mass_axis(PARAMS, [0.0], N_MODES))
    with pytest.raises(ValueError, match="count = 9"):
        datasets.mode_shapes(back, tip_mass_axis(PARAMS, [0.0], N_MODES), count=9)  # SFOAM has 4 bending modes only
    with styled():
        fig = campbell_tracked.plot(back, tip_mass=0.5)
        assert isinstance(fig, Figure) and len(fig.axes) == 4
        # every bending curve of every model on the frequency panels, FOAM's first one as stored
        for ax, hub in zip(fig.axes[:2], ("held", "free")):
            curves = [line for line in ax.get_lines() if len(line.get_xdata()) == back.speed.size]
            assert len(curves) == 4 * N_MODES  # beside them: TLAM's critical speed
            foam = back.frequency.sel(model="FOAM", tip_mass=0.5, hub=hub, mode=2).values
            assert any(np.array_equal(line.get_ydata(), foam) for line in curves)
        assert isinstance(linear_mode_shapes.plot(shapes), Figure)
        with pytest.raises(ValueError, match="tip_mass = 0.2"):
            campbell_tracked.plot(back, tip_mass=0.2)


@pytest.mark.parametrize("speeds, match", [([], "speeds"), ([0.0, -1.0], "speeds"),
                                           ([1.0, 1.0], "speeds"), ([0.0, np.inf], "speed")])
def test_bad_speed_grids_are_refused(speeds, match):
    with pytest.raises(ValueError, match=match):
        datasets.campbell(tip_mass_axis(PARAMS, [0.0], 2), speeds)


def test_bad_damping_and_tip_masses_are_refused():
    with pytest.raises(ValueError, match="damping.kind"):
        datasets.campbell(tip_mass_axis(PARAMS, [0.0], 2, damping={"kind": "viscous"}), [0.0])
    with pytest.raises(ValueError, match="tip_masses"):
        datasets.campbell(tip_mass_axis(PARAMS, [-1.0], 2), [0.0])


def test_labels_are_numbered_within_their_group_by_frequency():
    from hubbeam.linear.tracking import numbered_by_frequency

    labels = np.array([["hub", "bending 1", "bending 1", "axial 1", "bending 2"]])
    assert numbered_by_frequency(labels).tolist() == [["hub", "bending 1", "bending 2", "axial 1", "bending 3"]]
