"""A rig nobody shipped: products that must be right on an arm the shipped studies never show.

The arm: a 0.6 m aluminium strip (25 mm x 3 mm, E 69 GPa, 2700 kg/m^3) on a light hub, an 80 g
payload body at its tip, a 30 N m/rad bracket at its root. Each test holds one thing a new user's
run of it got wrong: a run the step budget stopped called valid; the root's speed drawn as the
hub's; the collocated Bode phase of the undamped arm a turn away from where theory puts it;
rounding drawn as damping; the top mode of a few assumed functions listed like the converged
ones; a quantised ring-down of two modes taken for no oscillation; a sample-time
sweep without any design reported as a stability boundary.
"""

from __future__ import annotations

import math

import matplotlib
import numpy as np
import pytest
import yaml

from hubbeam.check import check_configuration
from hubbeam.configuration.load import ConfigError
from hubbeam.configuration.settings import tip_mass_to_dict
from hubbeam.control.sample_time import NO_DESIGN, sample_time_sweep, stability_boundary
from hubbeam.linear import datasets
from hubbeam.linear.axes import plant_axis
from hubbeam.linear.frequency import frequency_response
from hubbeam.linear.plant_dataset import CONVERGED, free_frequencies, plant_dataset
from hubbeam.linear.plant_models import plant_linear
from hubbeam.model.parameters import BeamProducts, TipMass
from hubbeam.model.plant import Plant
from hubbeam.model.root import RootSpring
from hubbeam.model.validity import STOPPED
from hubbeam.plotting import campbell_tracked, case_figure
from hubbeam.results.measures import fit_decaying_sinusoid
from hubbeam.simulation.simulate import simulate

matplotlib.use("Agg")

WIDTH, THICKNESS, E, RHO = 0.025, 0.003, 69e9, 2700.0
ARM = BeamProducts(L=0.6, rhoA=RHO * WIDTH * THICKNESS, EI=E * WIDTH * THICKNESS**3 / 12.0,
                   EA=E * WIDTH * THICKNESS, Jh=0.002, rA=0.0)
PAYLOAD = TipMass(mass=0.08, position=0.6, inertia=2e-5)
BRACKET = RootSpring(30.0)
NUMERICS = {"rtol": 1e-8, "atol": 1e-10, "output_step": 0.002, "max_steps": 200000, "step_warning": 100000,
            "divergence_limit": 1.0, "modes": 2, "quadrature_points": 32}
PULSE = {"model": "FOAM", "maneuver": {"kind": "torque", "tau_max": 0.05, "tf": 0.2}, "t_end": 1.0, "modes": 2,
         "tip_mass": tip_mass_to_dict(PAYLOAD)}


def test_a_run_the_step_budget_stopped_is_stopped_and_says_what_to_change():
    ds = simulate(PULSE, ARM, NUMERICS | {"max_steps": 40, "step_warning": 20})
    assert ds.attrs["integrator_status"] != "success"
    assert ds.attrs["validity"] == STOPPED
    assert "numerics.max_steps" in ds.attrs["warnings"]


def test_the_case_figure_names_the_hub_s_and_the_root_s_speeds_apart():
    ds = simulate(PULSE | {"root_spring": BRACKET.to_dict()}, ARM, NUMERICS)
    assert "hub_speed" in ds
    figure = case_figure.plot("bracket", ds)
    speed_axes = [ax for ax in figure.get_axes() if "speed" in ax.get_ylabel()]
    assert len(speed_axes) == 1
    labels = [text.get_text() for text in speed_axes[0].get_legend().get_texts()]
    assert any("hub" in label and "phi" in label for label in labels)
    assert any("root" in label and "theta" in label for label in labels)
    assert not speed_axes[0].get_ylabel().startswith("hub speed")


def undamped_plant(modes: int = 3) -> Plant:
    return Plant(ARM, modes, 64, PAYLOAD)


def test_the_undamped_collocated_phase_alternates_between_minus_180_and_0_degrees():
    """Hub torque to hub angle of the undamped arm: a double integrator (-180 deg) whose poles and
    zeros alternate on the imaginary axis, zero first (Martins et al.; Cannon and Schmitz), so the
    phase steps +180 at each zero and -180 at each pole and never leaves [-180, 0]."""
    lm = plant_linear(undamped_plant(), "FOAM", 0.0, "free", ("hub_angle",))
    poles = np.linalg.eigvals(lm.A)
    top = np.abs(poles.imag).max()
    omega = np.geomspace(0.5, 3.0 * top, 4000)
    _, phase = frequency_response(lm, ["hub_angle"], omega)
    phase = phase[0]
    near = np.minimum(np.abs(phase + 180.0), np.abs(phase))
    assert near.max() < 1.0, phase[np.argmax(near)]
    assert phase.min() > -181.0 and phase.max() < 1.0
    assert (np.abs(phase) < 1.0).any() and (np.abs(phase + 180.0) < 1.0).any()


def test_rounding_is_not_drawn_as_damping():
    """The undamped arm's damping ratios are rounding (|zeta| of 1e-14 or so); the damping panels
    draw them as 0."""
    campbell = datasets.campbell(plant_axis(undamped_plant(2)), [0.0, 5.0, 10.0])
    ratios = campbell["damping_ratio"].values
    assert np.nanmax(np.abs(ratios)) < 1e-9
    figure = campbell_tracked.plot(campbell)
    damping_axes = [ax for ax in figure.get_axes() if "damping" in ax.get_ylabel()]
    assert damping_axes
    drawn = [line.get_ydata() for ax in damping_axes for line in ax.get_lines()]
    assert drawn and all(np.all((np.asarray(y) == 0.0) | np.isnan(y)) for y in drawn)


def test_on_the_light_hub_the_free_hub_has_one_rigid_mode_and_every_other_mode_is_flexible():
    """The hub (0.002 kg m^2) is light against the link (0.015 kg m^2 about the axis), so the first
    flexible mode of the free hub moves the hub most; it is still a flexible mode, 'bending 1', at
    the first frequency of the undamped free arm, and the one rigid-body mode ('hub') is at 0 Hz."""
    plant = Plant(ARM, 3, 64, PAYLOAD, root_spring=BRACKET)
    assert ARM.Jh < ARM.rhoA * ARM.L**3 / 3.0
    free = datasets.campbell(plant_axis(plant), [0.0]).sel(hub="free").isel(plant=0, speed=0)
    first = free_frequencies(plant)[0]
    for model in free["model"].values:
        one = free.sel(model=model)
        labels = [str(label) for label in one["mode_label"].values]
        frequency = one["frequency"].values
        assert labels.count("hub") == 1 and frequency[labels.index("hub")] == 0.0, (model, labels)
        assert frequency[labels.index("bending 1")] == pytest.approx(first, rel=1e-9), (model, labels)


def test_the_top_mode_of_few_assumed_functions_is_marked_not_converged():
    """Assumed modes bound each frequency from above (Rayleigh-Ritz): with one function more the
    frequencies fall or stay, the lowest is converged and the highest of three is not."""
    found = plant_dataset(Plant(ARM, 3, 64, PAYLOAD, root_spring=BRACKET), ["bracket"], 500.0)
    held, more = found["held_frequency"].values, found["more_modes_frequency"].values
    assert np.all(more <= held * (1.0 + 1e-12))
    assert found["converged"].values[0] == 1 and found["relative_change"].values[0] < CONVERGED
    assert found["converged"].values[-1] == 0 and found["relative_change"].values[-1] > CONVERGED


def test_a_ring_down_of_two_modes_read_quantised_is_still_an_oscillation():
    """The held arm's ring-down as a quantised reading sees it: the first mode at 1.29 Hz with 2 %
    damping and a little of the second; the two-term linear prediction (Prony) finds only real poles
    there. The fit still finds the first mode's frequency and damping; a constant signal has no
    oscillation to find."""
    t = np.arange(0.0, 6.0, 0.002)
    f1, zeta = 1.29, 0.02
    sigma = zeta * 2 * math.pi * f1
    signal = 0.1 * np.exp(-sigma * t) * np.cos(2 * math.pi * f1 * t) + 0.004 * np.sin(2 * math.pi * 9.1 * t)
    quantum = 1e-3
    fit = fit_decaying_sinusoid(t, quantum * np.round(signal / quantum), 0.0)
    assert abs(fit.omega) / (2 * math.pi) == pytest.approx(f1, rel=0.01)
    assert fit.decay_rate == pytest.approx(sigma, rel=0.1)
    with pytest.raises(ValueError, match="oscillation"):
        fit_decaying_sinusoid(t, np.full_like(t, 0.4), 0.0)


def test_a_sweep_without_any_design_has_no_stability_boundary():
    """Where no sample time of the grid has a design (every radius NaN) the sweep reports no
    boundary, never the grid's first sample time."""
    boundary, mode = stability_boundary(None, None, None, None, [0.001, 0.002, 0.004], [math.nan] * 3, 0.0,
                                        "discrete", modes=object())
    assert math.isnan(boundary) and mode == NO_DESIGN


def test_a_held_run_without_an_oscillation_is_said_in_its_row_not_raised():
    """The held hub's ring-down of a run that never left rest: the table of held frequencies says
    there is no oscillation to fit, and the report is built."""
    import json

    import xarray as xr

    from hubbeam.study.controllers import held_frequency_rows

    t = np.arange(0.0, 3.0, 0.002)
    still = xr.Dataset({"tip_transverse": ("time", np.zeros(t.size))}, coords={"time": t},
                       attrs={"model": "CFOAM", "case_config": json.dumps(
                           {"maneuver": {"kind": "speed_table", "time": [0, 3], "speed": [0, 0]}})})
    (row,) = held_frequency_rows({"still": still})
    assert "no oscillation" in row["source"] and math.isnan(row["frequency_hz"])


SRV02 = {"resistance": 2.6, "torque_constant": 7.68e-3, "back_emf_constant": 7.68e-3, "gear_ratio": 70.0,
         "motor_efficiency": 0.69, "gearbox_efficiency": 0.9, "viscous_friction": 0.015, "voltage_limit": 10.0}


def lqg_study() -> dict:
    """The rig under an LQG at 1 ms through its drive, the design reduced to the modes it resolves."""
    sampling = {"sample_time": 0.001, "gain": "discrete", "reduce": True,
                "estimator": {"kind": "kalman", "input_noise": 0.1},
                "sensors": [{"signal": "hub_angle", "quantum": 2 * math.pi / 4096, "mode": "edges"},
                            {"signal": "tip_deflection", "noise": 1e-4}]}
    maneuver = {"kind": "state_feedback", "reference": {"kind": "angle_table", "time": [0.0, 0.5], "angle": [0.0, 0.5]},
                "design": {"model": "FOAM", "speed": 0.0, "voltage_weight": 1.0,
                           "weights": {"hub_angle": 100.0, "tip_deflection": 1000.0}},
                "sampling": sampling}
    return {"study": {"name": "rig"},
            "beam": {"length": ARM.L, "rhoA": ARM.rhoA, "EI": ARM.EI, "EA": ARM.EA, "hub_inertia": ARM.Jh,
                     "hub_radius": 0.0},
            "numerics": {"modes": 3, "quadrature_points": 32, "rtol": 1e-8, "atol": 1e-10, "output_step": 0.002,
                         "max_steps": 200000, "step_warning": 100000},
            "cases": {"lqg": {"model": "CFOAM", "drive": SRV02, "t_end": 2.0, "tip_mass": tip_mass_to_dict(PAYLOAD),
                              "root_spring": BRACKET.to_dict(),
                              "damping": {"kind": "modal", "axial": 0.0, "transverse": 0.01}, "maneuver": maneuver}},
            "control": {"sample_time": {"cases": ["lqg"], "sample_times": {"start": 0.001, "stop": 0.01, "num": 4}}}}


def test_a_sweep_of_a_reduced_design_is_refused_by_its_key_before_any_job(tmp_path):
    """The sample-time sweep reads a design's states exactly; a design reduced to the modes its
    sample time resolves has modal states the truth does not have. The one check refuses it at
    its key (it once passed, and the sweep's job came out all NaN)."""
    study = lqg_study()
    path = tmp_path / "rig.yaml"
    path.write_text(yaml.safe_dump(study))
    with pytest.raises(ConfigError, match=r"control\.sample_time\.cases\[0\].*reduce"):
        check_configuration(study, [path])
    del study["control"]
    checked = check_configuration(study, [path])  # the case itself runs: only the sweep cannot read it
    case = checked.settings.cases["lqg"]
    with pytest.raises(ValueError, match="sampling.reduce"):
        sample_time_sweep(case, checked.settings.beam, checked.settings.numerics, None, [0.001, 0.002])
