"""Fixtures shared by the test suite, and its markers.

``workflow`` marks the tests that run Snakemake or interrupt and kill runs (minutes); ``slow`` the
tests of :data:`SLOW_MODULES` (integrations through the plain-Python reference, seconds each). The
fast loop ``make test-fast`` (``pytest -m "not workflow and not slow"``) leaves both out;
``make test`` runs everything. A test is marked here, not in its body: ``workflow`` from the names
its code uses (:func:`runs_the_workflow`): a name containing ``snakemake`` (the command, or a helper
that builds its command line) or one of :data:`KILL_NAMES`.
"""

from __future__ import annotations

import copy
import inspect
from pathlib import Path
from types import CodeType

import pytest

from hubbeam.configuration.load import load_config
from hubbeam.model.parameters import FLEXIBLE_LINK, BeamParameters

REPO_ROOT = Path(__file__).resolve().parents[1]
CONFIG_FILE = REPO_ROOT / "config" / "config.yaml"
#: names of the calls and signals with which tests interrupt and kill processes
KILL_NAMES = {"kill", "killpg", "SIGINT", "SIGTERM", "SIGKILL"}
#: test modules whose every test is slow (but runs no workflow)
SLOW_MODULES = {"test_reference", "test_config_install", "test_quanser_plan"}


def _names(code: CodeType) -> set[str]:
    """Global, attribute and local names used by ``code`` and the functions defined in it."""
    names = set(code.co_names) | set(code.co_varnames)
    for const in code.co_consts:
        if isinstance(const, CodeType):
            names |= _names(const)
    return names


def _runs_the_workflow(function) -> bool:
    names = _names(inspect.unwrap(function).__code__)
    return bool(names & KILL_NAMES) or any("snakemake" in name for name in names)


def runs_the_workflow(item: pytest.Item) -> bool:
    """Whether the test ``item``, or a fixture it uses, runs Snakemake or kills a process (see
    the module docstring)."""
    function = getattr(item, "function", None)
    if function is None:
        return False
    fixtures = getattr(item, "_fixtureinfo", None)
    definitions = fixtures.name2fixturedefs.values() if fixtures is not None else ()
    return _runs_the_workflow(function) or any(
        _runs_the_workflow(definition.func) for defs in definitions for definition in defs
        if definition.baseid.startswith("tests"))


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    for item in items:
        if runs_the_workflow(item):
            item.add_marker(pytest.mark.workflow)
        if item.module.__name__.rpartition(".")[2] in SLOW_MODULES:
            item.add_marker(pytest.mark.slow)


@pytest.fixture(scope="session")
def repo_root() -> Path:
    """The repository checkout (where the Snakefile and config/ live)."""
    return REPO_ROOT


@pytest.fixture(scope="session")
def _study_config() -> dict:
    return load_config(CONFIG_FILE)


@pytest.fixture
def study_config(_study_config) -> dict:
    """The validated config/config.yaml, as a private copy each test may modify."""
    return copy.deepcopy(_study_config)


@pytest.fixture(scope="session")
def flexible_link() -> BeamParameters:
    """The flexible link of a servo rig (``hubbeam.model.parameters.FLEXIBLE_LINK``), which the
    rig's tests turn with the SRV02's drive."""
    return FLEXIBLE_LINK
