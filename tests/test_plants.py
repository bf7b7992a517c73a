"""The plant of every case: the products of a study describe the arm its cases run.

* every shipped study: each case's plant product (its dataset's natural frequencies, its exported
  linear models) equals what ``hubbeam.api`` gives for the case, from the same functions;
* De Luca and Siciliano's link: the payload body and the point payload are two plants, side by
  side, with the published 2.18 / 15.91 Hz and the point mass's 2.217 / 23.15 Hz;
* a body inward of the tip and a root spring move the frequencies as an independent
  finite-element model says (``hubbeam.validation.fe_beam``), at rest and spinning, to the
  accuracy of 8 assumed modes (1e-4);
* the Quanser study's linear models take the voltage, and the free hub's rigid mode carries the
  drive's damping in closed form;
* an export writes the whole plant: a root spring's states and attributes, the drive's voltage;
* a study of 30 cases over 3 plants computes 3 sets of products.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from hubbeam.api import load
from hubbeam.linear import datasets
from hubbeam.linear.axes import plant_axis
from hubbeam.linear.export import to_dataset
from hubbeam.linear.plant_dataset import plant_dataset
from hubbeam.linear.plant_models import plant_linear
from hubbeam.model.parameters import BeamProducts, TipMass
from hubbeam.model.plant import Plant
from hubbeam.model.root import RootSpring
from hubbeam.pipeline.plan import build_plan
from hubbeam.validation import fe_beam

REPO = Path(__file__).resolve().parents[1]
STUDIES = sorted(path.name for path in (REPO / "studies").glob("*.yaml"))


@pytest.fixture(scope="module")
def deluca():
    return load(REPO / "studies" / "deluca_link.yaml")


@pytest.mark.parametrize("study", STUDIES)
def test_each_case_s_plant_products_are_the_api_s(study, monkeypatch):
    """For every case: the natural frequencies of its plant's dataset are the API's to 1e-9, and
    the linear models its plant exports are ``load(study).linear(case, speed)`` to 1e-12 at speeds
    of the study's grid (the first, the middle and the last)."""
    monkeypatch.chdir(REPO)
    config = load(f"studies/{study}")
    settings = config.settings
    grid = settings.linear.speeds.values
    speeds = grid[[0, grid.size // 2, -1]]
    for name, (plant, cases) in settings.plant_cases.items():
        product = plant_dataset(plant, cases, settings.eigen.critical_speed_search_max)
        for case in cases:
            np.testing.assert_allclose(product["held_frequency"].values, config.natural_frequencies(case),
                                       rtol=1e-9, atol=0.0)
        for model in sorted({settings.cases[case].model for case in cases}):
            case = next(case for case in cases if settings.cases[case].model == model)
            exported = to_dataset(plant, model, speeds, "free")
            for k, speed in enumerate(speeds):
                api = config.linear(case, float(speed))
                for matrix in "ABCD":
                    np.testing.assert_allclose(exported[matrix].values[k], getattr(api, matrix), rtol=1e-12,
                                               atol=1e-12 * np.abs(getattr(api, matrix)).max(), err_msg=name)
                assert list(exported.input.values) == list(api.inputs)


def test_the_payload_body_and_the_point_payload_are_two_plants_side_by_side(deluca):
    plants = deluca.settings.plants
    assert deluca.plant_of("payload").name == "payload" and deluca.plant_of("point_payload").name == "point_payload"
    published = {"payload": (2.1783, 15.9145), "point_payload": (2.2170, 23.150)}
    for name, (first, second) in published.items():
        ds = datasets.campbell(plant_axis(plants[name]), [0.0])
        held = ds["frequency"].sel(hub="held", model="CFOAM").isel(plant=0, speed=0).values
        bending = np.sort(held[held > 0])[:2]
        np.testing.assert_allclose(bending, (first, second), rtol=0, atol=1e-4 * second)


#: a 0.6 m aluminium strip with a small accelerometer 3 % inward of its tip
STRIP = BeamProducts(L=0.6, rhoA=0.27, EI=1.6, EA=1.3e6, Jh=0.002, rA=0.05)
SENSOR = TipMass(mass=0.08, position=0.582, inertia=2e-5)


@pytest.mark.parametrize("spring", [None, RootSpring(30.0)], ids=["clamped", "root spring"])
@pytest.mark.parametrize("speed", [0.0, 20.0])
def test_a_body_inward_of_the_tip_and_a_root_spring_move_the_frequencies_as_finite_elements_say(spring, speed):
    """Eight assumed modes give the first two in-plane frequencies of the finite-element model (320
    cubic elements) within 1e-4, hub held, at rest and at 20 rad/s (FOAM, which stiffens as the
    beam does); fewer modes do not: 4 modes miss the second by more than 1e-4."""
    fe = fe_beam.frequencies(STRIP, [speed], "inplane", SENSOR, 320, 3, spring)[0] / (2 * math.pi)

    def held(modes):
        A = plant_linear(Plant(STRIP, modes, 96, SENSOR, root_spring=spring), "FOAM", speed, "prescribed",
                         ("hub_angle",)).A
        poles = np.linalg.eigvals(A)
        return np.sort(np.abs(poles.imag[poles.imag > 1e-6]))[:2] / (2 * math.pi)

    assert np.all(np.abs(held(8) / fe[:2] - 1.0) < 1e-4)
    assert np.abs(held(4) / fe[:2] - 1.0).max() > 1e-4


def test_the_spring_s_and_the_body_s_shifts_are_the_finite_elements_shifts():
    """The root spring lowers the first frequency by the same ratio in both models, as a body moved
    inward raises it (to 1e-4 of the ratio)."""
    spring, inward = RootSpring(30.0), dataclasses.replace(SENSOR, position=0.54)
    fe = {key: fe_beam.frequencies(STRIP, [0.0], "inplane", tip, 320, 1, root)[0, 0]
          for key, (tip, root) in {"base": (SENSOR, None), "spring": (SENSOR, spring),
                                   "inward": (inward, None)}.items()}
    ritz = {key: datasets.campbell(plant_axis(Plant(STRIP, 8, 96, tip, root_spring=root, name=key)), [0.0])
            for key, (tip, root) in {"base": (SENSOR, None), "spring": (SENSOR, spring),
                                     "inward": (inward, None)}.items()}
    first = {key: float(ds["frequency"].sel(hub="held", model="FOAM").isel(plant=0, speed=0, mode=1))
             for key, ds in ritz.items()}
    assert fe["spring"] / fe["base"] < 0.9 and fe["inward"] / fe["base"] > 1.0
    for key in ("spring", "inward"):
        assert first[key] / first["base"] == pytest.approx(fe[key] / fe["base"], rel=1e-4)


def test_the_quanser_models_take_the_voltage_and_carry_the_drive_s_damping(monkeypatch):
    """The free hub's model of the Quanser study's drive plant has the voltage as its input; on a
    rigid link (EI x 1e6) its rigid mode decays at the rate of the drive's closed form, the back-EMF
    damping kt km Kg^2 eta_m eta_g / Rm plus Beq over the whole inertia Jh + Jb."""
    monkeypatch.chdir(REPO)
    settings = load("studies/quanser_rotflex.yaml").settings
    plant = next(plant for plant in settings.plants.values() if plant.drive is not None)
    ds = to_dataset(plant, "FOAM", [0.0], "free")
    assert list(ds.input.values) == ["voltage"] and ds.attrs["drive_resistance"] == plant.drive.resistance
    motor = plant.drive
    damping = (motor.torque_constant * motor.back_emf_constant * motor.gear_ratio**2 * motor.motor_efficiency
               * motor.gearbox_efficiency / motor.resistance + motor.viscous_friction)
    beam = plant.beam
    rigid = dataclasses.replace(plant, beam=BeamProducts(L=beam.L, rhoA=beam.rhoA, EI=beam.EI * 1e6, EA=beam.EA,
                                                         Jh=beam.Jh, rA=beam.rA), tip=TipMass(0.0, beam.L))
    inertia = beam.Jh + motor.reflected_inertia + beam.rhoA * ((beam.rA + beam.L) ** 3 - beam.rA**3) / 3.0
    poles = np.linalg.eigvals(plant_linear(rigid, "FOAM", 0.0, "free").A)
    real = poles[np.abs(poles.imag) < 1e-9]
    rigid_pole = real[np.argmin(np.abs(real + damping / inertia))]
    assert rigid_pole == pytest.approx(-damping / inertia, rel=1e-5)


def test_an_export_writes_the_root_spring_and_its_poles():
    plant = Plant(STRIP, 4, 96, SENSOR, root_spring=RootSpring(30.0, 0.01))
    ds = to_dataset(plant, "FOAM", [0.0, 5.0], "free")
    assert "phi" in ds.state.values and ds.attrs["root_spring_stiffness"] == 30.0
    assert ds.state_units.sel(state="phi") == "rad"
    rigid = dataclasses.replace(plant, root_spring=None)
    with_spring = np.sort_complex(np.linalg.eigvals(ds.A.values[1]))
    clamped = np.sort_complex(np.linalg.eigvals(to_dataset(rigid, "FOAM", [5.0], "free").A.values[0]))
    assert with_spring.size == clamped.size + 2
    np.testing.assert_allclose(with_spring, np.sort_complex(np.linalg.eigvals(plant_linear(plant, "FOAM", 5.0).A)),
                               rtol=1e-12)


def test_thirty_cases_over_three_plants_compute_three_sets_of_products(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    cases = {}
    for k in range(30):
        mass = (0.1, 0.2, 0.3)[k % 3]
        cases[f"spin_{k:02d}"] = {"model": "FOAM", "maneuver": {"kind": "prescribed", "wf": 1.0 + 0.05 * k,
                                                                "tf": 2.0}, "t_end": 3.0,
                                  "tip_mass": {"mass": mass, "position": 1.0}}
    config = {"study": {"name": "three_plants"},
              "beam": {"length": 1.0, "rhoA": 0.5, "EI": 20.0, "EA": 1.0e6, "hub_inertia": 0.1, "hub_radius": 0.0},
              "numerics": {"modes": 2}, "cases": cases}
    path = tmp_path / "study.yaml"
    path.write_text(yaml.safe_dump(config))
    plan = build_plan(yaml.safe_load(path.read_text()), [path], REPO)
    assert list(plan.settings.plants) == ["spin_00", "spin_01", "spin_02"]
    counts = {}
    for job in plan.jobs():
        counts[job.rule] = counts.get(job.rule, 0) + 1
    for rule in ("plant_summary", "plant_campbell", "plant_bode", "plant_poles_zeros", "plant_mode_shapes",
                 "plant_models", "figure_plant_campbell"):
        assert counts[rule] == 3, rule
    assert counts["simulate"] == 30
