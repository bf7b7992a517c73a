"""Hub maneuvers besides Eqs. (43)-(44): a prescribed speed table, a torque table, PD feedback.

* a speed table sampled from Eq. (43) reproduces the Eq. (43) run (FOAM, wf = 2 rad/s) to the
  clamped spline's error bound;
* the work of the hub torque equals the change of the mechanical energy for every maneuver kind
  under TLAM, FOAM and CFOAM (SFOAM deletes Q_theta, Eq. 40, and has no such balance);
* with a beam a million times stiffer, the PD-controlled hub follows the closed-form rigid-body
  loop ``J theta'' + kd theta' + kp theta = kp theta_r + kd theta_r'`` (scipy on the 1-DOF
  equation);
* each bad input names its key, its value and what is allowed.
"""

import dataclasses
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.interpolate import CubicSpline

from hubbeam.configuration.load import ConfigError
from hubbeam.configuration.settings import simulation_settings
from hubbeam.model.matrices import assemble
from hubbeam.model.parameters import BeamParameters
from hubbeam.results.reader import simulation_inputs
from hubbeam.simulation.simulate import simulate


@pytest.fixture(scope="module")
def setup(_study_config):
    return BeamParameters.from_config(_study_config), _study_config["numerics"]


def _case(maneuver, model="FOAM", t_end=6.0, modes=2, **extra):
    return {"name": "m", "model": model, "modes": modes, "t_end": t_end, "maneuver": maneuver,
            "tip_mass": {"mass": 0.0, "position": 8.0}, **extra}


#: one maneuver of every kind, rows on the 0.01 s output grid
KINDS = {
    "prescribed": {"kind": "prescribed", "wf": 1.0, "tf": 4.0},
    "torque": {"kind": "torque", "tau_max": 50.0, "tf": 3.0},
    "speed_table": {"kind": "speed_table", "time": [0.0, 1.0, 2.5, 4.0],
                    "speed": [0.0, 0.4, 1.2, 0.8]},
    "torque_table": {"kind": "torque_table", "time": [0.0, 1.0, 2.0, 3.5],
                     "torque": [0.0, 40.0, -20.0, 0.0]},
    "pd": {"kind": "pd", "kp": 400.0, "kd": 200.0,
           "reference": {"kind": "angle_table", "time": [0.0, 2.0, 4.0], "angle": [0.0, 0.5, 1.0]}},
    "pd_prescribed": {"kind": "pd", "kp": 400.0, "kd": 200.0,
                      "reference": {"kind": "prescribed", "wf": 1.0, "tf": 4.0}},
}


def test_speed_table_sampled_from_eq43_reproduces_the_eq43_run(setup):
    """Clamped spline of theta_dot with spacing h: |s' - w'| <= h^3 max|w''''| / 24 (Hall and
    Meyer 1976) for theta_ddot, whose maximum is 2 wf / tf; the beam responds linearly to
    theta_ddot at these deflections, so the tip deflections differ by at most about that
    relative error (1e-8 here) plus the integrator's (rtol 1e-9): bound 10x their sum."""
    params, numerics = setup
    wf, tf, h = 2.0, 10.0, 0.05
    numerics = dict(numerics, rtol=1e-9, atol=1e-11)
    time = np.arange(0.0, tf + h / 2, h)
    phase = 2 * np.pi * time / tf
    speed = wf / tf * time - wf / (2 * np.pi) * np.sin(phase)
    eq43 = simulate(_case({"kind": "prescribed", "wf": wf, "tf": tf}, t_end=14.0), params, numerics)
    table = simulate(_case({"kind": "speed_table", "time": time.tolist(), "speed": speed.tolist()},
                           t_end=14.0), params, numerics)
    w4 = wf * (2 * np.pi / tf) ** 3  # max |d^4 theta_dot / dt^4|
    spline_rel = h ** 3 * w4 / 24 / (2 * wf / tf)
    tip = eq43.tip_transverse.values
    bound = 10 * (spline_rel + numerics["rtol"]) * np.abs(tip).max()
    assert np.abs(table.tip_transverse.values - tip).max() <= bound
    assert np.abs(table.theta_ddot.values - eq43.theta_ddot.values).max() <= (
        10 * spline_rel * 2 * wf / tf)
    # after the table: the last speed held, theta_ddot zero
    after = table.time.values > tf
    np.testing.assert_allclose(table.theta_dot.values[after], speed[-1], rtol=1e-14)
    assert np.all(table.theta_ddot.values[after] == 0.0)


@pytest.mark.parametrize("model", ["TLAM", "FOAM", "CFOAM"])
@pytest.mark.parametrize("kind", list(KINDS))
def test_work_of_the_hub_torque_equals_the_energy_change(setup, model, kind):
    """Simpson's rule on the 0.005 s grid: error O(h^4) where the power is smooth (the table rows
    lie on the grid, so no interval straddles a kink); measured about 1e-9 of the largest work,
    bound 1e-7. SFOAM, without the balance, misses it by 4e-5 to 1e-3."""
    params, numerics = setup
    ds = simulate(_case(KINDS[kind], model), params, dict(numerics, output_step=0.005))
    change = ds.energy.values - ds.energy.values[0]
    work = ds.work.values
    assert np.abs(work).max() > 1.0
    np.testing.assert_allclose(change, work, rtol=0, atol=1e-7 * np.abs(work).max())
    assert np.all(ds.dissipated_energy.values == 0.0)
    assert ds.hub_torque.attrs["units"] == "N m" and ds.work.attrs["units"] == "J"


def test_pd_hub_with_a_stiff_beam_follows_the_rigid_closed_loop(setup):
    """E scaled by 1e6: the beam's frequencies rise 1000-fold and its elastic share of the hub
    response falls as (loop frequency / first bending frequency)^2 ~ 1e-6."""
    params, numerics = setup
    stiff = dataclasses.replace(params, E=params.E * 1e6)
    sm = assemble(stiff, None, 2, numerics["quadrature_points"])
    J = float(sm.Jh + sm.Jb)
    omega, zeta = 2.0, 0.6
    kp, kd = J * omega ** 2, 2 * zeta * omega * J
    time, angle = [0.0, 1.0, 3.0], [0.0, 0.2, 0.2]
    maneuver = {"kind": "pd", "kp": kp, "kd": kd,
                "reference": {"kind": "angle_table", "time": time, "angle": angle}}
    ds = simulate(_case(maneuver, "FOAM", t_end=8.0), stiff, dict(numerics, rtol=1e-10,
                                                                  atol=1e-12))
    ref = CubicSpline(time, angle, bc_type="clamped")

    def reference(t):
        return (ref(t), ref(t, 1)) if t <= time[-1] else (angle[-1], 0.0)

    def loop(t, z):
        r, rd = reference(t)
        return [z[1], (kp * (r - z[0]) + kd * (rd - z[1])) / J]

    rigid = solve_ivp(loop, (0, 8.0), [0.0, 0.0], t_eval=ds.time.values, rtol=1e-12, atol=1e-14,
                      method="DOP853", first_step=1e-3, max_step=0.01)
    scale = max(angle)
    np.testing.assert_allclose(ds.theta.values, rigid.y[0], rtol=0, atol=1e-5 * scale)
    torque = kp * (np.array([reference(t)[0] for t in ds.time.values]) - rigid.y[0]) + kd * (
        np.array([reference(t)[1] for t in ds.time.values]) - rigid.y[1])
    np.testing.assert_allclose(ds.hub_torque.values, torque, rtol=0,
                               atol=1e-4 * np.abs(torque).max())


def test_a_table_maneuver_reruns_from_the_dataset_attributes(setup):
    params, numerics = setup
    case = _case(KINDS["torque_table"], t_end=2.0, damping={"kind": "modal", "axial": 0.01,
                                                           "transverse": 0.05})
    ds = simulate(case, params, dict(numerics, quadrature_points=40))
    again = simulate(**simulation_inputs(ds.attrs))
    np.testing.assert_array_equal(again.tip_transverse.values, ds.tip_transverse.values)
    assert '"torque_table"' in ds.attrs["maneuver"] and '"modal"' in ds.attrs["damping"]


#: bad maneuvers, with the key of the one problem each is reported with and fragments of its message
#: (the value found and what is allowed)
BAD = [
    ({"kind": "speed_table", "time": [0.0, 2.0, 1.0], "speed": [0, 1, 2]},
     "maneuver.time", ["got [0.0, 2.0, 1.0]", "allowed: strictly increasing values (s)"]),
    ({"kind": "speed_table", "time": [0.0, 1.0, 2.0], "speed": [0, 1]},
     "maneuver.speed", ["got 2 values", "allowed: one per entry of cases.m.maneuver.time (3)"]),
    ({"kind": "torque_table", "time": [0.0, 1.0], "torque": [1.0]},
     "maneuver.torque", ["got [1.0]", "allowed: a list of at least 2 values"]),
    ({"kind": "torque_table", "time": [0.0, 1.0], "torque": [1.0, math.nan]},
     "maneuver.torque[1]", ["got nan", "allowed: a finite number"]),
    ({"kind": "pd", "kp": -1.0, "kd": 1.0, "reference": KINDS["prescribed"]},
     "maneuver.kp", ["got -1.0", "allowed: a number >= 0"]),
    ({"kind": "pd", "kp": 1.0, "kd": -2.0, "reference": KINDS["prescribed"]},
     "maneuver.kd", ["got -2.0", "allowed: a number >= 0"]),
    ({"kind": "pd", "kp": 1.0, "kd": 1.0, "reference": {"kind": "speed_table"}},
     "maneuver.reference.kind", ["got 'speed_table'", "allowed: one of prescribed, angle_table"]),
    ({"kind": "pd", "kp": 1.0, "kd": 1.0,
      "reference": {"kind": "angle_table", "time": [1.0, 1.0], "angle": [0.0, 1.0]}},
     "maneuver.reference.time", ["got [1.0, 1.0]", "allowed: strictly increasing values (s)"]),
    ({"kind": "prescribed", "wf": 2.0},
     "maneuver.tf", ["missing (required when kind is 'prescribed')", "allowed: a number > 0"]),
    ({"kind": "ramp"},
     "maneuver.kind", ["got 'ramp'",
                       "allowed: one of prescribed, torque, speed_table, torque_table, voltage_table, pd"]),
    ({"kind": "torque_table", "time": [0, 1], "torque": [0, 1], "speed": [0, 1]},
     "maneuver.speed", ["got [0, 1]", "not allowed when kind is 'torque_table' (allowed keys: kind, time, torque)"]),
]


@pytest.mark.parametrize("maneuver,key,fragments", BAD)
def test_a_bad_maneuver_gives_one_clear_error(setup, maneuver, key, fragments):
    """The API's bare case is checked by the configuration's one pass: one problem, at the key."""
    _, numerics = setup
    with pytest.raises(ConfigError) as error:
        simulation_settings(_case(maneuver), numerics, 8.0)
    (problem,) = error.value.problems
    assert problem.path == "cases.m." + key and all(fragment in problem.text for fragment in fragments), problem


def test_every_maneuver_kind_is_one_record_with_the_keys_the_schema_declares():
    """Each kind of the schema's maneuvers and references has one record in
    hubbeam.model.maneuvers, whose fields are exactly that kind's keys, and no record lacks a
    schema branch; the damping kinds likewise in hubbeam.model.damping."""
    import dataclasses

    from hubbeam.configuration.schema import kind_keys
    from hubbeam.model.damping import DAMPINGS
    from hubbeam.model.maneuvers import MANEUVERS, REFERENCES

    for definition, records in (("maneuver", MANEUVERS), ("reference", REFERENCES), ("damping", DAMPINGS)):
        declared = {kind: set(keys) for kind, keys in kind_keys(definition).items()}
        held = {kind: {item.name for item in dataclasses.fields(record)} for kind, record in records.items()}
        assert held == declared, definition
        assert all(record.kind == kind for kind, record in records.items())


@pytest.mark.parametrize("maneuver", list(KINDS.values()), ids=list(KINDS))
def test_a_record_writes_back_the_mapping_it_was_read_from(maneuver):
    from hubbeam.model.maneuvers import maneuver_from_dict

    record = maneuver_from_dict(maneuver)
    assert record.to_dict() == maneuver
    assert maneuver_from_dict(record.to_dict()) == record
