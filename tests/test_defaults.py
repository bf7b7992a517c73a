"""Defaults of a study: ``numerics`` and ``eigen`` may be left out, wholly or in part; the filled-in
values are those the schema documents, the eigen grids cover the study's speeds and critical
speeds, a value given is kept, and the paper's configuration (which spells everything out) is
not changed by the completion."""

from __future__ import annotations

import copy
import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from hubbeam.configuration import defaults
from hubbeam.configuration.load import ConfigError, check_schema, load_config, read_config_file
from hubbeam.configuration.schema import SCHEMA
from hubbeam.configuration.tabular import resolve_files
from hubbeam.model.beam import beam_from_config
from hubbeam.model.eigen import critical_speed
from hubbeam.model.maneuvers import maneuver_from_dict
from hubbeam.model.matrices import assemble
from hubbeam.model.parameters import TipMass

REPO = Path(__file__).resolve().parents[1]
FIRST_STUDY = REPO / "studies" / "first_study.yaml"
#: the classic benchmark beam of studies/spinup10m.yaml, by its four factors
BEAM = {"length": 10.0, "density": 1.2e4, "area": 1.0e-4, "youngs_modulus": 2.8e11,
        "second_moment": 5.0e-8, "hub_inertia": 1.0, "hub_radius": 0.0}
#: first root of the clamped-free frequency equation cos(b) cosh(b) = -1
BETA1 = 1.8751040687119611


def bare_study(**cases) -> dict:
    return {"study": {"name": "bare"}, "beam": dict(BEAM), "cases": cases}


def spin_up(wf: float, **extra) -> dict:
    return {"model": "FOAM", "maneuver": {"kind": "prescribed", "wf": wf, "tf": 15.0}, "t_end": 20.0, **extra}


def first_frequency(beam: dict) -> float:
    """The continuum cantilever's first bending frequency, rad s-1."""
    rhoA, EI = beam["density"] * beam["area"], beam["youngs_modulus"] * beam["second_moment"]
    return BETA1**2 * math.sqrt(EI / (rhoA * beam["length"] ** 4))


def test_the_first_study_is_ten_lines_and_gets_every_default():
    lines = [line for line in FIRST_STUDY.read_text().splitlines() if line.strip() and not line.startswith("#")]
    assert len(lines) <= 12
    cfg = load_config(FIRST_STUDY)
    assert cfg["numerics"] == defaults.numerics_defaults()
    assert set(cfg["eigen"]) == {"tip_masses", "positions", "speeds", "critical_speed_search_max"}


def test_docs_open_with_the_first_study_as_written():
    """docs/studies.md shows studies/first_study.yaml itself (what a newcomer copies runs)."""
    text = (REPO / "docs" / "studies.md").read_text()
    first_block = re.search(r"```yaml\n(.*?)```", text, re.S).group(1)
    assert first_block == FIRST_STUDY.read_text()


def test_numerics_defaults_are_the_schema_defaults_and_valid():
    properties = SCHEMA["properties"]["numerics"]["properties"]
    documented = {key: node["default"] for key, node in properties.items() if "default" in node}
    assert defaults.numerics_defaults() == documented
    # every key that was required before has a default; the optional ones keep theirs in the code
    assert set(documented) == {"modes", "quadrature_points", "rtol", "atol", "output_step", "max_steps",
                               "step_warning", "divergence_limit"}
    cfg = check_schema(bare_study(spin=spin_up(6.0)))
    assert cfg["numerics"] == documented


def test_a_numerics_value_given_is_kept_and_checked():
    cfg = bare_study(spin=spin_up(6.0))
    cfg["numerics"] = {"modes": 3}
    check_schema(cfg)
    assert cfg["numerics"]["modes"] == 3 and cfg["numerics"]["rtol"] == defaults.numerics_defaults()["rtol"]
    cfg = bare_study(spin=spin_up(6.0))
    cfg["numerics"] = {"rtol": 2.0}
    with pytest.raises(ValueError, match=r"numerics\.rtol: got 2\.0"):
        check_schema(cfg)


def test_a_case_shorter_than_the_default_output_step_is_reported():
    with pytest.raises(ValueError, match=r"t_end >= numerics\.output_step = 0\.01"):
        check_schema(bare_study(spin=spin_up(6.0) | {"t_end": 0.005}))


def test_eigen_grids_cover_the_cases_and_the_critical_speed():
    cfg = check_schema(bare_study(slow=spin_up(2.0, tip_mass={"mass": 0.5, "position": 6.0}),
                                     fast=spin_up(9.0, tip_mass={"mass": 0.2})))
    eigen = cfg["eigen"]
    assert eigen["tip_masses"] == [0.0, 0.2, 0.5]
    assert eigen["positions"] == {"start": 0.0, "stop": BEAM["length"], "num": defaults.POSITION_POINTS}
    needed = defaults.SPEED_MARGIN * max(9.0, first_frequency(BEAM))
    top = eigen["speeds"]["stop"]
    # rounded up to two significant digits: at most one unit of the second digit above
    assert needed <= top < needed + 10.0 ** (math.floor(math.log10(needed)) - 1)
    assert eigen["speeds"] == {"start": 0.0, "stop": top, "num": defaults.SPEED_POINTS}
    assert eigen["critical_speed_search_max"] == top


def test_the_linear_section_follows_the_eigen_grid_and_the_largest_tip_mass():
    cfg = check_schema(bare_study(slow=spin_up(2.0, tip_mass={"mass": 0.5, "position": 6.0}),
                                     fast=spin_up(9.0, tip_mass={"mass": 0.2})))
    linear, top = cfg["linear"], cfg["eigen"]["speeds"]["stop"]
    assert linear["speeds"] == cfg["eigen"]["speeds"]
    assert linear["tip_masses"] == [0.0, 0.5]
    assert linear["bode_speeds"] == [0.0, 0.5 * top, 0.875 * top]
    assert linear["frequencies"] == defaults.LINEAR_FREQUENCIES
    assert linear["shapes"] == defaults.LINEAR_SHAPES
    assert "damping" not in linear
    assert check_schema(bare_study(one=spin_up(2.0)))["linear"]["tip_masses"] == [0.0]


@pytest.mark.parametrize("linear, key", [
    ({"bode_speeds": [1.0, 1.0]}, "linear.bode_speeds"),
    ({"speeds": {"start": 2.0, "stop": 1.0, "num": 3}}, "linear.speeds.stop"),
    ({"frequencies": {"start": 10.0, "stop": 1.0, "num": 3}}, "linear.frequencies.stop"),
])
def test_a_linear_grid_that_does_not_increase_is_reported(linear, key):
    with pytest.raises(ConfigError) as caught:
        check_schema(bare_study(one=spin_up(2.0)) | {"linear": linear})
    assert [str(problem) for problem in caught.value.problems if str(problem).startswith(f"{key}: got")]


def test_the_critical_speed_sets_the_grid_above_slow_cases():
    cfg = check_schema(bare_study(slow=spin_up(1.0)))
    assert cfg["eigen"]["speeds"]["stop"] >= defaults.SPEED_MARGIN * first_frequency(BEAM)


def test_the_highest_critical_speed_is_the_bare_beams_first_frequency():
    """The bare uniform beam's Ritz basis holds its exact first mode: the continuum value to the
    accuracy of the mode's root and the quadrature (1e-9 relative)."""
    sm = assemble(beam_from_config(BEAM), None, 5, 64)
    assert defaults.highest_critical_speed(sm.K2, sm.M2) == pytest.approx(first_frequency(BEAM), rel=1e-9)


@pytest.mark.parametrize("mass, position", [(0.1, 10.0), (1.0, 10.0), (1.0, 5.0), (5.0, 2.0)])
def test_no_tip_mass_raises_a_critical_speed_above_the_bound(mass, position):
    """The bound of the docstring against hubbeam.model.eigen's exact critical speeds: TLAM's fall with
    any tip mass anywhere, FOAM has none."""
    params = beam_from_config(BEAM)
    sm = assemble(params, None, 5, 64)
    bound = defaults.highest_critical_speed(sm.K2, sm.M2)
    tip = TipMass(mass=mass, position=position)
    assert critical_speed("TLAM", params, tip, 5, 10 * bound) < bound
    assert math.isnan(critical_speed("FOAM", params, tip, 5, 10 * bound))


def highest_speed(maneuver, t_end, inertia):
    """The highest hub speed the derived speed grid covers for ``maneuver`` (its record's, a free
    hub taken as rigid of ``inertia``)."""
    return maneuver_from_dict(maneuver).highest_speed(t_end, inertia)


def test_torque_pulse_speed_against_its_table():
    """Eq. (44) on a rigid hub, in closed form, against the same pulse given as a torque table
    (linear between 401 samples: interpolation error (2 pi h / tf)^2 / 8 of the amplitude)."""
    tau_max, tf, inertia = 50.0, 10.0, 300.0
    closed = highest_speed({"kind": "torque", "tau_max": tau_max, "tf": tf}, 20.0, inertia)
    assert closed == pytest.approx(tau_max * tf / (math.pi * inertia), rel=1e-15)
    time = np.linspace(0.0, tf, 401)
    torque = tau_max * np.sin(2 * np.pi * time / tf)
    table = {"kind": "torque_table", "time": time.tolist(), "torque": torque.tolist()}
    h = time[1] - time[0]
    assert highest_speed(table, 20.0, inertia) == pytest.approx(closed, rel=(2 * np.pi * h / tf) ** 2)


def test_a_torque_table_holds_its_last_value_until_the_end():
    table = {"kind": "torque_table", "time": [0.0, 1.0], "torque": [0.0, 2.0]}
    # ramp to 2 N m over 1 s (1 N m s), then 2 N m held for 9 s: 19 N m s on 4 kg m2
    assert highest_speed(table, 10.0, 4.0) == pytest.approx(19.0 / 4.0, rel=1e-12)


@pytest.mark.parametrize("maneuver, expected", [
    ({"kind": "prescribed", "wf": 3.0, "tf": 2.0}, 3.0),
    ({"kind": "speed_table", "time": [0.0, 1.0, 2.0], "speed": [0.0, -4.0, 1.0]}, 4.0),
    ({"kind": "pd", "kp": 1.0, "kd": 1.0, "reference": {"kind": "prescribed", "wf": 2.5, "tf": 1.0}}, 2.5),
    ({"kind": "pd", "kp": 1.0, "kd": 1.0,
      "reference": {"kind": "angle_table", "time": [0.0, 2.0, 3.0], "angle": [0.0, 1.0, 1.5]}}, 0.5),
])
def test_highest_hub_speed_of_the_prescribed_and_reference_kinds(maneuver, expected):
    assert highest_speed(maneuver, 5.0, 1.0) == expected


def test_an_eigen_value_given_is_kept():
    cfg = bare_study(spin=spin_up(6.0))
    cfg["eigen"] = {"tip_masses": [0.0, 2.0], "speeds": {"start": 1.0, "stop": 3.0, "num": 3}}
    check_schema(cfg)
    assert cfg["eigen"]["tip_masses"] == [0.0, 2.0]
    assert cfg["eigen"]["speeds"] == {"start": 1.0, "stop": 3.0, "num": 3}
    assert cfg["eigen"]["critical_speed_search_max"] >= defaults.SPEED_MARGIN * first_frequency(BEAM)


@pytest.mark.parametrize("name", ["config/config.yaml", "studies/spinup10m.yaml", "studies/tapered_pd.yaml"])
def test_a_config_that_spells_everything_out_is_not_changed(name):
    path = REPO / name
    given = resolve_files(read_config_file(path), path.parent)
    assert check_schema(copy.deepcopy(given)) == given


def test_the_schema_describes_the_derived_grids():
    eigen = SCHEMA["properties"]["eigen"]["properties"]
    assert f"{defaults.SPEED_POINTS} speeds" in eigen["speeds"]["description"]
    assert f"{defaults.SPEED_MARGIN:g} times" in eigen["speeds"]["description"]
    assert f"{defaults.POSITION_POINTS} positions" in eigen["positions"]["description"]


@pytest.mark.parametrize("value, expected", [(12.46, 13.0), (12.5, 13.0), (7.5, 7.5), (0.0123, 0.013),
                                             (3.0, 3.0), (99.1, 100.0)])
def test_round_up_to_two_significant_digits(value, expected):
    assert defaults.round_up(value) == expected


def test_the_first_study_plans_every_product_as_written(tmp_path):
    """`snakemake -n --configfile studies/first_study.yaml` from an empty folder: the rules find
    every setting they read in the completed configuration."""
    snakemake_command = [sys.executable, "-m", "snakemake", "--snakefile", str(REPO / "Snakefile"), "--directory",
               str(tmp_path), "--dry-run", "--cores", "1", "--configfile", str(FIRST_STUDY)]
    run = subprocess.run(snakemake_command, cwd=tmp_path, capture_output=True, text=True, timeout=300, check=False)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    for rule in ("plant_campbell", "eigen_beam", "simulate", "study_report", "archive"):
        assert re.search(rf"^{rule}\s+1$", run.stdout, re.M), rule
