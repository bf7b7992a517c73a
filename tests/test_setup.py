"""The setup `make test` runs: it installs the `validation` extra, so that the independent
Exudyn and pyBModes checks run on every change; the extra's pins are those of the lock; the
setup reruns when the extras change; CI runs exactly `make test`."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
MAKEFILE = (REPO / "Makefile").read_text()


def make_variable(name: str) -> str:
    return re.search(rf"^{name} := (.*)$", MAKEFILE, re.M).group(1).strip()


def test_make_test_installs_the_validation_extra():
    extras = make_variable("EXTRAS").split(",")
    assert {"test", "validation"} <= set(extras)
    assert "$(EXTRAS)" in make_variable("STAMP")  # a change of the extras reruns the setup
    assert re.search(r'^\$\(STAMP\):.*\n\t.*--constraint requirements\.lock --editable "\.\[\$\(EXTRAS\)\]"',
                     MAKEFILE, re.M)
    assert re.search(r"^test: \$\(STAMP\)$", MAKEFILE, re.M)


def test_the_validation_extra_is_pinned_as_in_the_lock():
    extras = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]["optional-dependencies"]
    lock = {line.split("==")[0].lower(): line for line in (REPO / "requirements.lock").read_text().splitlines()
            if "==" in line and not line.startswith("#")}
    for requirement in extras["validation"]:
        assert lock[requirement.split("==")[0].lower()] == requirement


def test_ci_runs_exactly_make_test():
    commands = [line for line in (REPO / ".ci" / "run").read_text().splitlines()
                if line.strip() and not line.startswith("#") and not line.startswith(("set ", "cd "))]
    assert commands == ["make test"]
