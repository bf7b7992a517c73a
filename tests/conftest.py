"""Fixtures shared by the test suite."""

from __future__ import annotations

import copy
from pathlib import Path

import pytest

from hubbeam.config import load_config

REPO_ROOT = Path(__file__).resolve().parents[1]
CONFIG_FILE = REPO_ROOT / "config" / "config.yaml"


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
