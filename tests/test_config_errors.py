"""Inputs the one check of a configuration once let through or crashed on, refused by name before any job.

* a gain of ``output_feedback`` on a signal that is none (``tip_acceleration``): the schema's
  explainer crashed on the list of allowed names (``_pattern_words``);
* a sampled controller at ``sample_time: 1.0e-7`` for 50 s: 5e8 samples, whose arrays the check did
  not count, so the simulation job died of a MemoryError; now the memory budget counts them (and
  a shaper's impulses, and a table's rows) and the check refuses it at the key;
* a Kalman filter without process noise (``input_noise`` left at its default 0): refused, but at
  ``maneuver.sampling`` without naming the key to set.

Each through :func:`hubbeam.check.check_configuration` on a shipped study, and the first
two through ``snakemake -n``, which stops before any job.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml
from checking import checked_configuration

from hubbeam.configuration import checks
from hubbeam.configuration.load import read_config_file
from hubbeam.core.inputs import IDENTITY_SHAPER
from hubbeam.linear import lumped
from hubbeam.model.limits import MEMORY_BUDGET_MB
from hubbeam.model.maneuvers import SensorSpec
from hubbeam.results import variables
from hubbeam.simulation.sampled import SampledLoop, held_table, loop_arrays

REPO = Path(__file__).resolve().parents[1]
TRUST = REPO / "studies" / "controller_trust.yaml"
QUANSER = REPO / "studies" / "quanser_rotflex.yaml"
#: a state feedback on an output that is no measured signal, beside a valid one
OUTPUT_FEEDBACK = {"hub_angle": 10, "tip_acceleration": 1}
SIGNALS = "hub_angle, hub_speed, tip_deflection, tip_arc, root_moment, deflection_angle, deflection_rate"


def problems(cfg: dict, path: Path) -> list[str]:
    return [str(problem) for problem in checked_configuration(cfg, [path])[2]]


def with_output_feedback() -> dict:
    """studies/controller_trust.yaml with a case of gains on measured signals, one of them none."""
    cfg = read_config_file(TRUST)
    cfg["cases"] = {"output_gains": {
        "model": "FOAM", "t_end": 30.0,
        "maneuver": {"kind": "state_feedback", "reference": {"kind": "prescribed", "wf": 1.0, "tf": 15.0},
                     "output_feedback": OUTPUT_FEEDBACK}}}
    return cfg


def sampled_too_fast() -> dict:
    """studies/quanser_rotflex.yaml with its Kalman case sampled every 1e-7 s for 50 s."""
    cfg = read_config_file(QUANSER)
    case = cfg["cases"]["lumped_kalman"]
    case["t_end"] = 50.0
    case["maneuver"]["sampling"]["sample_time"] = 1.0e-7
    return cfg


def test_a_gain_on_a_signal_that_is_none_is_refused_by_name():
    [problem] = problems(with_output_feedback(), TRUST)
    assert problem == (f"cases.output_gains.maneuver.output_feedback.tip_acceleration: illegal name "
                       f"'tip_acceleration'; allowed: one of {SIGNALS}")


@pytest.mark.parametrize("names, where, allowed", [
    ({"output_feedback": {"tip_acceleration": 1}}, "output_feedback.tip_acceleration", f"one of {SIGNALS}"),
    ({"gains": {"theta": 1.0}, "design": {}}, "", "exactly one of the keys gains, output_feedback, design"),
    ({"output_feedback": {}}, "output_feedback", "at least one entry"),
])
def test_every_rule_on_the_names_and_keys_of_a_mapping_is_said_in_words(names, where, allowed):
    """A name of a list of names (propertyNames with an enum), exactly one of some keys (oneOf),
    an empty mapping of gains (minProperties): each in words, at its key."""
    cfg = with_output_feedback()
    maneuver = cfg["cases"]["output_gains"]["maneuver"]
    del maneuver["output_feedback"]
    maneuver.update(names)
    key = "cases.output_gains.maneuver" + (f".{where}" if where else "")
    found = [problem for problem in problems(cfg, TRUST) if problem.startswith(key + ": ")]
    assert found and allowed in found[0], problems(cfg, TRUST)
    assert not any('"enum"' in problem or "described in docs" in problem for problem in problems(cfg, TRUST))


def test_a_sampled_controller_too_fast_for_the_memory_budget_is_refused_at_its_sample_time():
    """5e8 samples of 23 values (2 sensors, 4 estimated states, 13 of the loop) x 8 bytes = 85.7 GiB,
    where the job used to die of a MemoryError at its first array (3.7 GiB)."""
    [problem] = problems(sampled_too_fast(), QUANSER)
    assert problem.startswith("cases.lumped_kalman.maneuver.sampling.sample_time: got 1e-07 s: the sampled "
                              "controller runs 500000001 samples up to t_end = 50 s, each holding 23 values")
    assert f"above the memory budget numerics.memory_budget_mb = {MEMORY_BUDGET_MB:g} MiB" in problem
    assert "allowed: sample_time >= 4.3e-06 s" in problem
    cfg = sampled_too_fast()
    cfg["cases"]["lumped_kalman"]["maneuver"]["sampling"]["sample_time"] = 4.3e-6  # the smallest allowed
    assert problems(cfg, QUANSER) == []


def test_the_sampled_loop_s_arrays_are_what_the_budget_counts():
    """The arrays :func:`hubbeam.simulation.sampled.loop_arrays` and ``held_table`` allocate per sample
    (records, noise, sample and switch times, stops, the held command's table) are
    ``variables.sampled_loop_bytes`` but for the working copies numpy's union of the stops makes."""
    N, t_end, Ts = 3, 1.0, 1.0e-3
    loop = SampledLoop([SensorSpec("hub_angle"), SensorSpec("hub_speed")], np.eye(2 * N)[[0, N]],
                       np.zeros((0, 0)), np.zeros((0, 2)), np.zeros(0), np.zeros((3, 0)), np.ones((3, 2)),
                       np.ones(3), np.zeros((2, 3)), np.zeros(3), np.zeros(0), Ts=Ts, D=0.5)
    arrays, stops, noise = loop_arrays(loop, np.arange(N), t_end, np.zeros(4), IDENTITY_SHAPER)
    count = arrays.timing.sample_times.size
    held = sum(np.asarray(array).nbytes for array in arrays.records) + arrays.timing.sample_times.nbytes \
        + arrays.timing.switch_times.nbytes + stops.nbytes + noise.nbytes + held_table(count, 0.0).nbytes
    estimate = variables.sampled_loop_bytes(t_end, Ts, sensors=2, estimated=3)
    assert count == variables.sample_count(t_end, Ts) == 1001
    assert held <= estimate <= held + 4 * variables.BYTES_PER_VALUE * count + 64


def test_a_shaper_of_too_many_impulses_is_refused_at_its_modes():
    """A ZVD shaper convolved over 20 frequencies has up to 3^20 impulses: 442 GiB."""
    cfg = read_config_file(REPO / "studies" / "first_study.yaml")
    [case] = cfg["cases"].values()
    case["shaper"] = {"kind": "ZVD", "frequencies": [1.0 + k for k in range(20)]}
    [problem] = problems(cfg, REPO / "studies" / "first_study.yaml")
    assert problem.startswith("cases.spinup.shaper.frequencies: got 20 frequencies: the ZVD shaper convolves one "
                              "per mode, up to 3^20 = 3486784401 impulses")
    assert "allowed: at most 15 frequencies for a ZVD shaper" in problem


def test_a_table_of_too_many_rows_is_refused_at_its_times():
    path = REPO / "studies" / "first_study.yaml"
    cfg = read_config_file(path)
    [case] = cfg["cases"].values()
    rows = 20_000
    case["maneuver"] = {"kind": "torque_table", "time": [0.001 * k for k in range(rows)], "torque": [0.0] * rows}
    cfg["numerics"] = {"memory_budget_mb": 1.0}
    [problem] = problems(cfg, path)
    assert problem.startswith(f"cases.spinup.maneuver.time: got {rows} rows: the kernel's table of them holds "
                              f"{variables.TABLE_VALUES} values per row")
    assert "above the memory budget numerics.memory_budget_mb = 1 MiB; allowed: at most" in problem


def test_a_kalman_filter_without_process_noise_is_refused_at_input_noise():
    cfg = read_config_file(QUANSER)
    del cfg["cases"]["lumped_kalman"]["maneuver"]["sampling"]["estimator"]["input_noise"]
    [problem] = problems(cfg, QUANSER)
    assert problem.startswith("cases.lumped_kalman.maneuver.sampling.estimator.input_noise: missing (default 0) with "
                              "no state_noise: the Kalman filter would have no process noise")
    assert "allowed: input_noise > 0" in problem
    cfg["cases"]["lumped_kalman"]["maneuver"]["sampling"]["estimator"]["input_noise"] = 0.0
    [problem] = problems(cfg, QUANSER)
    assert problem.startswith("cases.lumped_kalman.maneuver.sampling.estimator.input_noise: got 0.0 with no "
                              "state_noise")


def test_a_huge_number_is_refused_before_it_overflows_the_model():
    """1e300 m of beam overflowed the eigen defaults (``L**2``): refused at the key."""
    path = REPO / "studies" / "first_study.yaml"
    cfg = read_config_file(path)
    cfg["beam"]["length"] = 1e300
    assert problems(cfg, path) == [f"beam.length: got 1e+300; allowed: a number of magnitude at most "
                                   f"{checks.LARGEST_NUMBER:g} (SI units; beyond, the products of the model's "
                                   "quantities overflow double precision)"]


def test_the_checks_name_the_lumped_model_s_states_and_outputs_as_it_does():
    assert checks.LUMPED_STATES == lumped.LUMPED_STATES and checks.LUMPED_OUTPUTS == lumped.LUMPED_OUTPUTS


# ---------------------------------------------------------------------------------------------
# through Snakemake


def snakemake_dry_run(workdir: Path, config: Path) -> subprocess.CompletedProcess:
    command = [sys.executable, "-m", "snakemake", "--snakefile", str(REPO / "Snakefile"), "--directory", str(workdir),
               "--dry-run", "--configfile", str(config)]
    return subprocess.run(command, cwd=REPO, capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize("build, study, fragments", [
    (with_output_feedback, TRUST, ["cases.output_gains.maneuver.output_feedback.tip_acceleration: illegal name "
                                   f"'tip_acceleration'; allowed: one of {SIGNALS}"]),
    (sampled_too_fast, QUANSER, ["cases.lumped_kalman.maneuver.sampling.sample_time: got 1e-07 s",
                                 "allowed: sample_time >= 4.3e-06 s"]),
], ids=["output_feedback", "sample_time"])
def test_snakemake_refuses_them_before_any_job(tmp_path, build, study, fragments):
    config = tmp_path / study.name
    config.write_text(yaml.safe_dump(build(), sort_keys=False))
    workdir = tmp_path / "work"
    workdir.mkdir()
    run = snakemake_dry_run(workdir, config)
    output = run.stdout + run.stderr
    assert run.returncode != 0
    assert output.count("invalid hubbeam configuration") == 1 and "1 problem:" in output, output
    assert all(fragment in output for fragment in fragments), output
    assert "Traceback" not in output and 'File "' not in output
    assert "Building DAG" not in output and "Job stats" not in output
    assert sorted(p.name for p in workdir.iterdir()) in ([], [".snakemake"])
