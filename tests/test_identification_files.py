"""Experiment files and the identify section refuse bad input by name (``hubbeam.identification``).

* each kind of file is read back as it was written; a spreadsheet's CSV (byte-order mark, CRLF) too;
* a missing column, a unit not allowed, a column the experiment does not know, a header cell
  without a unit, a time or frequency column that does not increase, NaN or inf, too few rows, ``;``
  separators: each refused naming the file, the line, the column and what is allowed;
* a key that is not a parameter, inverted bounds, a start outside them, a parameter the case does not
  have, an experiment the case cannot predict (a voltage without a drive, a mode it does not have,
  a signal without a noise level): refused naming the key or the experiment and what is allowed;
* the planned ``identify`` section is checked with every problem under its ``identify.<...>`` key.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from hubbeam.identification.experiments import (
    FrequencyResponse,
    ModalTest,
    PdLoop,
    TimeSeries,
    read_frequency_response,
    read_modal_test,
    read_time_series,
    write_experiment,
)
from hubbeam.identification.files import ExperimentError
from hubbeam.identification.parameters import ParameterError, free_parameters
from hubbeam.identification.plant import CasePlant
from hubbeam.identification.predictions import ExperimentMismatch, check_experiment
from hubbeam.identification.section import identify_problems
from hubbeam.identification.synthetic import SENSORS, rig_case


@pytest.fixture(scope="module")
def rig():
    return rig_case()


def _write(path, text: str):
    path.write_text(text, encoding="utf-8")
    return path


def _refusal(read, path, *args, **options) -> str:
    with pytest.raises(ExperimentError) as caught:
        read(path, *args, **options)
    return str(caught.value)


def test_every_kind_is_read_back_as_written(tmp_path):
    t = np.arange(20) * 0.01
    series = TimeSeries(name="pulse", input="voltage", time=t, command=np.sin(t), signals={"hub_angle": t**2},
                        sensors={"hub_angle": SENSORS["hub_angle"]})
    modal = ModalTest(name="tap", hub="held", mode=np.array([1, 2]), frequency=np.array([3.1, 22.4]),
                      damping_ratio=np.array([0.01, 0.02]))
    response = FrequencyResponse(name="frf", input="voltage", output="deflection_angle",
                                 frequency=np.array([1.0, 2.0, 3.0]), response=np.array([1 + 1j, 2 - 1j, -0.5j]),
                                 coherence=np.array([0.9, 0.95, 0.5]), averages=4)
    back = read_time_series(write_experiment(series, tmp_path / "pulse.csv"), "voltage",
                            sensors={"hub_angle": SENSORS["hub_angle"]})
    np.testing.assert_allclose(back.signals["hub_angle"], series.signals["hub_angle"], rtol=1e-6, atol=1e-12)
    np.testing.assert_allclose(back.command, series.command, rtol=1e-6, atol=1e-12)
    assert back.name == "pulse" and back.sensors["hub_angle"] == SENSORS["hub_angle"]
    tap = read_modal_test(write_experiment(modal, tmp_path / "tap.csv"))
    np.testing.assert_allclose(tap.frequency, modal.frequency)
    np.testing.assert_allclose(tap.damping_ratio_std, modal.damping_ratio_std, rtol=1e-6)
    frf = read_frequency_response(write_experiment(response, tmp_path / "frf.csv"), "voltage", "deflection_angle",
                                  averages=4)
    np.testing.assert_allclose(frf.response, response.response, rtol=1e-6)
    assert frf.unit == "rad V-1"


def test_a_spreadsheets_csv_and_the_other_forms_of_a_response_are_read(tmp_path):
    text = "frequency [Hz],real [m s-2 N-1 m-1],imag [m s-2 N-1 m-1]\r\n1,1,0\r\n2,0,1\r\n3,-1,0\r\n"
    path = tmp_path / "acc.csv"
    path.write_bytes(b"\xef\xbb\xbf" + text.encode())
    frf = read_frequency_response(path, "hub_torque", "tip_acceleration")
    np.testing.assert_allclose(frf.response, [1, 1j, -1])
    decibels = _write(tmp_path / "db.csv", "frequency [Hz],magnitude [dB],phase [rad]\n1,20,0\n2,0,1\n3,-20,2\n")
    np.testing.assert_allclose(np.abs(read_frequency_response(decibels, "voltage", "hub_angle").response),
                               [10.0, 1.0, 0.1])
    decrement = _write(tmp_path / "decay.csv", "mode [1],frequency [Hz],log_decrement [1]\n1,3.0,0.2\n")
    zeta = read_modal_test(decrement).damping_ratio[0]
    assert zeta == pytest.approx(0.2 / math.sqrt(4 * math.pi**2 + 0.04))


@pytest.mark.parametrize("text, fragments", [
    ("time [s],hub_angle [rad]\n0,0\n", ["line 1", "no column voltage [V]", "allowed: a header with time [s], "
                                                                             "voltage [V]"]),
    ("time [ms],voltage [V],hub_angle [rad]\n", ["line 1, column time", "unit 'ms'", "allowed: 's'"]),
    ("time [s],voltage [V],hub_angle [deg]\n", ["line 1, column hub_angle", "unit 'deg'", "allowed: 'rad'"]),
    ("time,voltage [V],hub_angle [rad]\n", ["line 1, column 'time'", "no unit", "allowed: time [s]"]),
    ("time [s],voltage [V],root_moment [N m]\n", ["line 1, column 'root_moment [N m]'", "not a column",
                                                  "hub_angle [rad]"]),
    ("time [s],voltage [V],hub_angle [rad],hub_angle [rad]\n", ["column hub_angle: given twice"]),
    ("time [s],voltage [V]\n" + "".join(f"{k * 0.01},0\n" for k in range(12)), ["no measured signal",
                                                                                 "deflection_angle [rad]"]),
    ("time [s],voltage [V],hub_angle [rad]\n0,0,0\n0.01,0,0\n", ["2 rows of values", "at least 10"]),
    ("time [s],voltage [V],hub_angle [rad]\n" + "".join(f"{t},0,0\n" for t in [0, .01, .02, .02, .04, .05, .06,
                                                                                .07, .08, .09, .1]),
     ["line 5, column time", "0.02 after 0.02", "increasing strictly"]),
    ("time [s],voltage [V],hub_angle [rad]\n" + "".join(f"{t},0,0\n" for t in [0, .01, .02, .03, .05, .06, .07,
                                                                                .08, .09, .1, .11]),
     ["line 6, column time", "off the grid", "equally spaced"]),
    ("time [s],voltage [V],hub_angle [rad]\n0,0,nan\n" + "".join(f"{k * 0.01},0,0\n" for k in range(1, 12)),
     ["line 2, column hub_angle", "'nan'", "a finite number"]),
    ("time [s],voltage [V],hub_angle [rad]\n0,inf,0\n", ["line 2, column voltage", "'inf'", "a finite number"]),
    ("time [s];voltage [V];hub_angle [rad]\n", ["separated by ';'"]),
])
def test_a_bad_time_series_file_is_refused_with_file_line_and_column(tmp_path, text, fragments):
    path = _write(tmp_path / "series.csv", text)
    message = _refusal(read_time_series, path, "voltage")
    assert f"file {path}" in message and all(fragment in message for fragment in fragments), message


@pytest.mark.parametrize("text, fragments", [
    ("frequency [Hz],magnitude [rad V-1],phase [deg]\n1,1,0\n3,1,0\n2,1,0\n",
     ["line 4, column frequency", "2.0 after 3.0", "increasing strictly"]),
    ("frequency [Hz],magnitude [m V-1],phase [deg]\n", ["column magnitude", "unit 'm V-1'", "'rad V-1' or 'dB'"]),
    ("frequency [Hz],magnitude [rad V-1]\n1,1\n2,1\n3,1\n", ["columns magnitude of the response",
                                                           "magnitude [rad V-1] and phase [deg], or real"]),
    ("frequency [Hz],magnitude [rad V-1],phase [deg],coherence [1]\n1,1,0,1.2\n2,1,0,1\n3,1,0,1\n",
     ["line 2, column coherence", "a coherence in [0, 1]"]),
    ("frequency [Hz],magnitude [rad V-1],phase [deg]\n0,1,0\n1,1,0\n2,1,0\n", ["line 2, column frequency",
                                                                            "a frequency > 0 Hz"]),
])
def test_a_bad_frequency_response_file_is_refused(tmp_path, text, fragments):
    message = _refusal(read_frequency_response, _write(tmp_path / "frf.csv", text), "voltage", "deflection_angle")
    assert all(fragment in message for fragment in fragments), message


def test_a_coherence_needs_its_averages_and_a_modal_test_increasing_modes(tmp_path):
    path = _write(tmp_path / "frf.csv", "frequency [Hz],real [rad V-1],imag [rad V-1],coherence [1]\n"
                                        "1,1,0,0.9\n2,1,0,0.9\n3,1,0,0.9\n")
    with pytest.raises(ExperimentError, match=r"experiment frf.averages = None; allowed: the number of averages"):
        read_frequency_response(path, "voltage", "deflection_angle")
    modes = _write(tmp_path / "tap.csv", "mode [1],frequency [Hz]\n1,3\n1,20\n")
    assert "line 3, column mode" in _refusal(read_modal_test, modes)
    frequencies = _write(tmp_path / "tap2.csv", "mode [1],frequency [Hz]\n1,30\n2,20\n")
    assert "line 3, column frequency: 20.0 after 30.0" in _refusal(read_modal_test, frequencies)
    with pytest.raises(ExperimentError, match=r"experiment tap3.hub = 'pinned'; allowed: one of held, free"):
        read_modal_test(_write(tmp_path / "tap3.csv", "mode [1],frequency [Hz]\n1,3\n"), hub="pinned")


@pytest.mark.parametrize("entries, fragments", [
    ({"root_spring.stiffnes": {"lower": 1, "upper": 2}}, ["parameters.'root_spring.stiffnes': not a parameter",
                                                          "allowed: beam.EI_factor"]),
    ({"root_spring.stiffness": {"lower": 50, "upper": 10}}, ["parameters.root_spring.stiffness: lower = 50.0, "
                                                             "upper = 10.0; allowed: lower < upper"]),
    ({"beam.EI_factor": {"lower": 0.5, "upper": 1.5, "start": 2.0}},
     ["parameters.beam.EI_factor.start = 2.0; allowed: a start in [0.5, 1.5]"]),
    ({"damping.transverse": {"lower": 0.0, "upper": 1.0}},
     ["parameters.damping.transverse.upper = 1.0; allowed: a finite value >= 0 and < 1"]),
    ({"tip_mass.mass": {"lower": 0.0}}, ["parameters.tip_mass.mass = {'lower': 0.0}; allowed: {lower, upper}"]),
    ({"sensors.hub_angle.gain": {"lower": 0.9, "upper": 1.1}}, ["no experiment measures hub_angle"]),
])
def test_a_bad_parameter_is_refused_with_its_key_its_value_and_what_is_allowed(rig, entries, fragments):
    case, beam, _ = rig
    with pytest.raises(ParameterError) as caught:
        free_parameters(entries, case, beam)
    assert all(fragment in str(caught.value) for fragment in fragments), str(caught.value)


def test_a_parameter_of_a_part_the_case_does_not_have_is_refused(rig):
    case, beam, _ = rig
    bare = dataclasses.replace(case, root_spring=None, drive=None)
    with pytest.raises(ParameterError, match=r"'root_spring.stiffness': case 'rig' has no root_spring; allowed: a "
                                             "case with a root_spring section"):
        free_parameters({"root_spring.stiffness": {"lower": 1, "upper": 2}}, bare, beam)
    with pytest.raises(ParameterError, match=r"'drive.motor_constant_factor': case 'rig' has no drive"):
        free_parameters({"drive.motor_constant_factor": {"lower": 0.5, "upper": 2}}, bare, beam)


def test_an_experiment_the_case_cannot_predict_is_refused_naming_it(rig):
    case, beam, numerics = rig
    plant = CasePlant(dataclasses.replace(case, drive=None), beam, numerics)
    t = np.arange(20) * 0.01
    series = TimeSeries(name="pulse", input="voltage", time=t, command=t, signals={"hub_angle": t},
                        sensors={"hub_angle": SENSORS["hub_angle"]})
    with pytest.raises(ExperimentMismatch, match=r"experiment pulse: input voltage, but case 'rig' has no drive; "
                                                 "allowed: an experiment driven by hub_torque"):
        check_experiment(plant, series)
    tap = ModalTest(name="tap", hub="held", mode=np.array([1, 5]), frequency=np.array([3.0, 200.0]))
    with pytest.raises(ExperimentMismatch, match=r"experiment tap: mode 5, but case 'rig' has 4 bending modes with "
                                                 "the hub held; allowed: modes 1..4"):
        check_experiment(plant, tap)
    quiet = TimeSeries(name="quiet", input="hub_torque", time=t, command=t, signals={"tip_deflection": t})
    with pytest.raises(ExperimentMismatch, match=r"experiment quiet.sensors.tip_deflection: no noise level"):
        check_experiment(plant, quiet)
    with pytest.raises(ExperimentError, match=r"experiment loop.reference = None; allowed: the loop's hub-angle "
                                              "reference"):
        TimeSeries(name="loop", input="voltage", time=t, command=None, signals={"hub_angle": t}, loop=PdLoop(5.0))


def test_the_identify_section_is_checked_under_its_keys(tmp_path):
    _write(tmp_path / "tap.csv", "mode [1],frequency [Hz]\n1,3.1\n2,22\n")
    _write(tmp_path / "bad.csv", "mode [1],frequency [rad/s]\n1,19\n")
    section = {
        "case": "rig",
        "experiments": {"tap": {"kind": "modal", "file": "tap.csv"},
                        "bad": {"kind": "modal", "file": "bad.csv"},
                        "gone": {"kind": "modal", "file": "gone.csv"},
                        "odd": {"kind": "impulse", "file": "tap.csv"},
                        "frf": {"kind": "frequency_response", "file": "tap.csv", "input": "current"}},
        "parameters": {"root_spring.stiffness": {"lower": 60, "upper": 10}, "beam.EI": {"lower": 1, "upper": 2}},
        "fit": ["tap", "tapp"],
        "starts": 0,
        "extra": 1,
    }
    problems = identify_problems(section, ["rig", "other"], tmp_path)
    expected = [
        "identify.extra: not a key of the section",
        "identify.experiments.bad.file: file ",
        "column frequency: unit 'rad/s'; allowed: 'Hz'",
        "identify.experiments.gone.file: file ",
        "cannot be read",
        "identify.experiments.odd.kind = 'impulse'; allowed: one of modal, free_decay, frequency_response, time_series",
        "identify.experiments.frf.input = 'current'; allowed: one of voltage, hub_torque",
        "identify.parameters.root_spring.stiffness: lower = 60.0, upper = 10.0; allowed: lower < upper",
        "identify.parameters.'beam.EI': not a parameter",
        "identify.fit: 'tapp' is not an experiment",
        "identify.starts = 0; allowed: a whole number >= 1",
    ]
    text = "\n".join(problems)
    assert all(fragment in text for fragment in expected), text
    assert identify_problems({"case": "rig", "experiments": {"tap": {"kind": "modal", "file": "tap.csv"}},
                              "parameters": {"beam.EI_factor": {"lower": 0.5, "upper": 1.5}}}, ["rig"], tmp_path) == []
    assert identify_problems({"case": "gig", "experiments": {"tap": {"kind": "modal", "file": "tap.csv"}},
                              "parameters": {"beam.EI_factor": {"lower": 0.5, "upper": 1.5}}}, ["rig"], tmp_path) == [
        "identify.case = 'gig'; allowed: one of the cases rig"]


def test_the_shipped_rig_data_are_valid_small_and_say_they_are_synthetic(repo_root):
    """The shipped study identifies the nominal rig its data were made from (the beam, the numerics
    and every section of the case but the run itself), its section passes the check, and the data
    are small and say they are synthetic."""
    import json

    from hubbeam.api import load
    from hubbeam.identification.synthetic import RIG_BEAM, RIG_CASE, RIG_NUMERICS, TRUTH

    folder = repo_root / "studies" / "identification_rig"
    configuration = load(folder / "study.yaml", identified=False)
    assert identify_problems(configuration.config["identify"], configuration.case_names, folder) == []
    config = configuration.config
    assert {key: config["beam"][key] for key in RIG_BEAM} == RIG_BEAM
    assert {key: config["numerics"][key] for key in RIG_NUMERICS} == RIG_NUMERICS
    rig = config["cases"]["rig"]
    assert {key: rig[key] for key in RIG_CASE if key not in ("maneuver", "t_end")} == {
        key: value for key, value in RIG_CASE.items() if key not in ("maneuver", "t_end")}
    assert sum(path.stat().st_size for path in folder.iterdir()) < 300_000
    assert json.loads((folder / "synthetic.json").read_text())["truth"] == TRUTH
    readme = (folder / "README.md").read_text()
    assert "synthetic" in readme and "not measured" in readme
    assert all(f"{key}" in readme for key in TRUTH)
    assert all("synthetic" in path.read_text().splitlines()[0] for path in folder.glob("*.csv"))
