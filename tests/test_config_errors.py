"""Inputs the one check of a configuration once crashed on, refused by name before any job.

* a gain of ``output_feedback`` on a signal that is none (``tip_acceleration``): the schema's
  explainer crashed on the list of allowed names (``_pattern_words``); now every rule of the schema,
  on values or on the names and keys of a mapping, is said in words at its key;
* a huge number (``beam.length: 1e300``) overflowed the model while the check completed the
  configuration: numbers beyond ``checks.LARGEST_NUMBER`` are refused at their key.

Each through :func:`hubbeam.pipeline.plan.checked_configuration` on a shipped study.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from hubbeam.configuration import checks
from hubbeam.configuration.load import read_config_file
from hubbeam.linear import lumped
from hubbeam.pipeline.plan import checked_configuration

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
